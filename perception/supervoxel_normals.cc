#include "perception/supervoxel_normals.h"

#include "perception/normal_estimation.h"
#include "perception/pcl_adjacency_grid.h"
#include "perception/plane_moments.h"

#include <vector>

namespace sortcell::perception {
namespace {

// Each voxel's moments over the index list SupervoxelClustering::computeVoxelData fits a plane to:
// itself, then for each neighbour n (itself among them) n and each of n's neighbours. That is the voxel
// once, plus for each neighbour n its own moments and the sum over n's neighbourhood. About the centroid
// of the voxel `origin`.
std::vector<Moments> IndexListMoments(const std::vector<Eigen::Vector3f>& centroids, const NeighbourLists& neighbours,
                                      size_t origin) {
  const size_t n = centroids.size();
  std::vector<Moments> own(n), ring(n), list(n);
  for (size_t v = 0; v < n; ++v) own[v] = Moments::Of((centroids[v] - centroids[origin]).cast<double>());
  for (size_t v = 0; v < n; ++v) {
    for (int u : neighbours.Of(v)) ring[v].Add(own[u]);
  }
  for (size_t v = 0; v < n; ++v) {
    list[v] = own[v];
    list[v].Add(ring[v]);
    for (int u : neighbours.Of(v)) list[v].Add(ring[u]);
  }
  return list;
}

// PCL's plane fit of a voxel's index list, flipped towards the camera at the origin and normalised as
// PCL's voxel data is. A voxel with no neighbour but itself fits one place three times: PCL's
// covariance, shifted by the first point, is exactly zero there, and so is the one of three points at
// the origin given to the fit here.
pcl::Normal VoxelNormal(const Moments& m, bool alone, const Eigen::Vector3f& c) {
  Moments one_place;
  for (int k = 0; k < 3; ++k) one_place.Add(Moments::Of(Eigen::Vector3d::Zero()));
  pcl::Normal normal = NormalOf(alone ? one_place : m, c);
  normal.getNormalVector3fMap().normalize();
  return normal;
}

}  // namespace

std::vector<pcl::Normal> PclVoxelNormals(const std::vector<Eigen::Vector3f>& centroids,
                                         const NeighbourLists& neighbours, size_t origin) {
  const std::vector<Moments> moments = IndexListMoments(centroids, neighbours, origin);
  std::vector<pcl::Normal> normals;
  normals.reserve(centroids.size());
  for (size_t v = 0; v < centroids.size(); ++v) {
    normals.push_back(VoxelNormal(moments[v], neighbours.Of(v).size() == 1, centroids[v]));
  }
  return normals;
}

pcl::PointCloud<pcl::Normal> SupervoxelVoxelNormals(const Cloud& points, float resolution_m) {
  pcl::PointCloud<pcl::Normal> normals;
  PclAdjacencyGrid grid;
  // PCL's resolution is the float it was given, widened to double.
  if (!MakePclAdjacencyGrid(points, static_cast<double>(resolution_m), grid)) return normals;
  const std::vector<pcl::Normal> of_voxel = PclVoxelNormals(grid.xyz, grid.neighbours, grid.first_in_key_order);
  normals.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) normals[i] = of_voxel[grid.of_point[i]];
  return normals;
}

}  // namespace sortcell::perception
