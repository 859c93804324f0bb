#pragma once
/// @file
/// PCL's supervoxels (Papon et al. 2013, pcl::SupervoxelClustering), computed in flat arrays: the same
/// supervoxels, labels and adjacency as PCL 1.13's, faster. PCL's own is kept as the reference.

#include <pcl/segmentation/supervoxel_clustering.h>

#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "perception/cloud.h"

namespace sortcell::perception {

/// pcl::SupervoxelClustering's settings (floats, as PCL keeps them).
struct SupervoxelSettings {
  float voxel_m = 0.0075f;
  float seed_m = 0.03f;
  float colour_importance = 0;
  float spatial_importance = 1;
  float normal_importance = 4;
};

/// What the convex clustering takes from PCL's supervoxels.
struct SupervoxelGraph {
  /// By label, as extract() gives them (centroid, colour, normal; their voxels_ and normals_ are left empty
  /// by Supervoxels: nothing here reads them).
  std::map<std::uint32_t, pcl::Supervoxel<PointT>::Ptr> supervoxels;
  std::multimap<std::uint32_t, std::uint32_t> adjacency;  ///< As getSupervoxelAdjacency() gives it.
  std::vector<std::uint32_t> label_of_point;              ///< As getLabeledCloud() labels the input (0: none).
};

/// pcl::SupervoxelClustering<PointXYZRGB> (no single-camera transform) given `normals` as its normal cloud,
/// reproduced step by step: the adjacency octree's voxels in its leaf order and their 26-neighbours, the
/// seeds (the voxels nearest the occupied cells of an octree of seed_m over the voxel centroids, grown as
/// PCL grows it), the flow of voxels to the nearest supervoxel centre in 1.8 seed_m / voxel_m - 1 rounds,
/// with each sum in PCL's order and each distance in PCL's float arithmetic, so that the result is PCL's
/// bit for bit (unit SupervoxelGraphs). Written here because PCL's keeps every voxel as an octree leaf
/// and each supervoxel's voxels in a std::set: about half of the convex clustering's time
/// (perception_benchmark, 2026-12-07). Empty (then use PclSupervoxels) where PCL's result would hang on
/// what is not reproduced: a point not finite or `normals` not one per point; points spread over 2^20
/// voxels or more along an axis, or reaching the far side of PCL's octree cube (PCL's keys would wrap);
/// a seed cell's two nearest voxels equally near its centre to within rounding, or (where seeds are
/// counted: seed_m over about 5 voxel_m) a seed's neighbour that near the counting radius (PCL's k-d tree
/// prunes on bounds that round too).
std::optional<SupervoxelGraph> ExtractSupervoxels(const Cloud& points, const pcl::PointCloud<pcl::Normal>& normals,
                                                  const SupervoxelSettings& settings);

/// The same given the normal cloud SupervoxelVoxelNormals(points, settings.voxel_m) would give, computed on
/// this grid in one pass (bit for bit that cloud's result: unit SupervoxelGraphs).
std::optional<SupervoxelGraph> ExtractSupervoxels(const Cloud& points, const SupervoxelSettings& settings);

/// The same from PCL's pcl::SupervoxelClustering itself (`normals` null: PCL computes the voxel normals).
SupervoxelGraph PclSupervoxels(const Cloud::Ptr& points, const pcl::PointCloud<pcl::Normal>::ConstPtr& normals,
                               const SupervoxelSettings& settings);

}  // namespace sortcell::perception
