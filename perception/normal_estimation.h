#pragma once
/// @file
/// Surface normals of a voxelised cloud from each point's neighbours within a radius (perception's
/// descriptor and its convex clustering's crease test both need them), and the neighbours themselves.

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <vector>

#include "perception/cloud.h"

namespace sortcell::perception {

/// For each point of `points` (all finite), the indices of the points within `radius_m` of it, itself
/// included, in no particular order: one batched FLANN query (the same sets and order as
/// pcl::search::KdTree unsorted, which queries one point at a time, each query entering an OpenMP region
/// and allocating its result vectors).
std::vector<std::vector<int>> RadiusNeighbours(const Cloud& points, double radius_m);

/// Each point's neighbours in one flat array (one allocation, not one per point): those of point i are
/// indices[offsets[i]] up to indices[offsets[i + 1]], read as `for (int j : lists.Of(i))`.
struct NeighbourLists {
  std::vector<int> offsets{0};  ///< One more than the points; offsets[0] = 0.
  std::vector<int> indices;

  struct Range {
    const int* first;
    const int* last;
    const int* begin() const { return first; }
    const int* end() const { return last; }
    size_t size() const { return static_cast<size_t>(last - first); }
  };
  size_t size() const { return offsets.size() - 1; }
  bool empty() const { return size() == 0; }
  Range Of(size_t i) const { return {indices.data() + offsets[i], indices.data() + offsets[i + 1]}; }
};

/// Each point's neighbours within a radius (the same sets as RadiusNeighbours, in another order) and
/// the normal their plane fit gives (as NormalsFromNeighbours).
struct Neighbourhoods {
  NeighbourLists neighbours;
  pcl::PointCloud<pcl::Normal> normals;
};

/// The neighbourhoods within `radius_m`, found in a uniform grid of cells `radius_m` wide (a point's
/// neighbours lie in the 27 cells around its own), each pair once, the normals' moments summed as the
/// pairs are found; each point's list is itself, then the others in the order the grid found their
/// pairs. Written here because for a radius of a few voxels the grid takes half FLANN's time
/// (measured at 4385932, perception_benchmark: the descriptor's normals of a frame's six objects, 5 mm
/// voxels within 15 mm, 5.5-7 ms against 11.5), most of FLANN's going into its tree's descent. Memory
/// grows with the points, not their extent; points spread over more than 2^21 radii fall back to
/// RadiusNeighbours.
Neighbourhoods GridNeighbourhoods(const Cloud& points, double radius_m);

/// Normals of `points` from `neighbours` (RadiusNeighbours), facing the camera at the origin; NaN where
/// fewer than 3 neighbours. PCL's plane fit (solvePlaneParameters) of the neighbours' covariance, summed
/// in double about a common origin (so the order of the neighbours changes nothing but the last bits).
pcl::PointCloud<pcl::Normal> NormalsFromNeighbours(const Cloud& points,
                                                   const std::vector<std::vector<int>>& neighbours);

/// GridNeighbourhoods(points, radius_m).normals without keeping the neighbour lists: pcl::NormalEstimation's
/// normals up to rounding.
pcl::PointCloud<pcl::Normal> EstimateNormals(const Cloud& points, double radius_m);

}  // namespace sortcell::perception
