#pragma once
/// @file
/// PCL's adjacency octree over a cloud, flat: the voxels PCL's supervoxels start from, in PCL's order.

#include <Eigen/Core>

#include <vector>

#include "perception/cloud.h"
#include "perception/normal_estimation.h"
#include "perception/octree_box.h"

namespace sortcell::perception {

/// The leaves of pcl::octree::OctreePointCloudAdjacency (PCL 1.13, no transform) over a cloud, as
/// pcl::SupervoxelClustering<PointXYZRGB> fills them.
struct PclAdjacencyGrid {
  std::vector<VoxelKey> keys;        ///< Each leaf's key, in PCL's leaf order (its voxel data's idx_).
  std::vector<Eigen::Vector3f> xyz;  ///< Each leaf's centroid: its points' float sums in input order, made means.
  std::vector<Eigen::Vector3f> rgb;  ///< Each leaf's mean colour, the same way.
  std::vector<int> count;            ///< Each leaf's points.
  std::vector<int> of_point;         ///< Each point's leaf.
  NeighbourLists neighbours;         ///< Each leaf's occupied 26-neighbours and itself, in PCL's order.
  size_t first_in_key_order = 0;     ///< The leaf first in x, y, z order.
};

/// PCL's adjacency octree over `points` with voxels `resolution` wide. False where a point is not finite or
/// the points spread over 2^(kPackedKeyBits - 1) or more voxels along an axis (16 km at 7.5 mm): then the
/// grid is of no use (PCL's keys would be other than these).
bool MakePclAdjacencyGrid(const Cloud& points, double resolution, PclAdjacencyGrid& grid);

}  // namespace sortcell::perception
