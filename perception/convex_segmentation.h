#pragma once
/// @file
/// Clusters that stop at concave creases: supervoxels (PCL's SupervoxelClustering) joined across convex
/// or flat connections and cut across concave ones (PCL's LCCP, Stein et al. 2014). Two objects that
/// touch meet in a concave crease (box on box, can beside box) and come apart; one object's own faces
/// meet convexly and stay together, whatever is printed on them (colour plays no part). The inside of
/// a hollow object (a bowl, a mug, a pot) is concave, so LCCP cuts it into pieces: a piece that lies
/// mostly inside another cluster's volume (within its footprint on the supporting plane and below its
/// top) joins that cluster; an object stacked on another is above the lower one's top and stays apart.

#include <Eigen/Core>
#include <pcl/PointIndices.h>

#include <vector>

#include "perception/cloud.h"

namespace sortcell::perception {

struct ConvexClusteringParams {
  double voxel_m = 0.0075;       ///< Supervoxel voxel resolution.
  double seed_m = 0.03;          ///< Supervoxel seed resolution.
  double concavity_deg = 15;     ///< Connections more concave than this are cut.
  /// Smaller and larger segments are dropped; SegmentObjects sets both from SegmentationParams.
  int min_cluster_voxels = 25, max_cluster_voxels = 20000;
  double inside_fraction = 0.8;  ///< A piece with this share of its voxels inside another cluster's volume joins it.
  double top_tolerance_m = 0.01; ///< "Below the top": at most this much above the other cluster's highest voxel.
};

/// Clusters of `voxels` (camera frame) standing on the plane `plane_C` (n.p + d = 0, camera frame, n
/// towards the camera), as indices into `voxels`, largest first.
std::vector<pcl::PointIndices> ConvexClusters(const Cloud::Ptr& voxels, const Eigen::Vector4d& plane_C,
                                              const ConvexClusteringParams& params);

}  // namespace sortcell::perception
