#pragma once
/// @file
/// The voxel normals PCL's supervoxels compute for themselves, computed faster, to be handed to
/// pcl::SupervoxelClustering as its normal cloud.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "perception/cloud.h"
#include "perception/normal_estimation.h"

namespace sortcell::perception {

/// For each point of `points` (all finite), the normal of the voxel it falls in as
/// pcl::SupervoxelClustering<PointT> (PCL 1.13, no single-camera transform, voxels `resolution_m` wide)
/// computes it when given no normal cloud: the plane fit of the voxel centroids of the voxel, each of its
/// 26-neighbours and theirs, each counted as often as PCL's index list repeats it, facing the camera at the
/// origin. PCL's voxel grid (its adjacency octree's keys), centroids and repetitions are reproduced
/// exactly; the fit's sums run in double, so the normals equal PCL's up to rounding. Written here
/// because PCL gathers each voxel's two rings through its octree one index at a time: about a fifth of
/// the convex clustering's time (measured at 7360cf6, perception_benchmark under perf). Every point of a
/// voxel gets the voxel's normal, so that PCL's average over a voxel's points is that normal. Empty
/// where `points` is, holds a point not finite or spreads over 2^20 voxels or more along an axis (then let
/// PCL compute them).
pcl::PointCloud<pcl::Normal> SupervoxelVoxelNormals(const Cloud& points, float resolution_m);

/// The same normal for each voxel, given PCL's voxel centroids, their neighbour lists (each voxel's occupied
/// 26-neighbours and itself, in PCL's order) and `origin`, the voxel first in x, y, z order: the fit's sums
/// are taken about its centroid (PclAdjacencyGrid gives all three; SupervoxelVoxelNormals uses them).
std::vector<pcl::Normal> PclVoxelNormals(const std::vector<Eigen::Vector3f>& centroids,
                                         const NeighbourLists& neighbours, size_t origin);

}  // namespace sortcell::perception
