#include "perception/supervoxel_normals.h"

#include "perception/normal_estimation.h"
#include "perception/octree_box.h"
#include "perception/plane_moments.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace sortcell::perception {
namespace {

// The corner of PCL's adjacency octree (OctreePointCloudAdjacency::addPointsFromInputCloud fits the box
// to the points' extent).
Eigen::Vector3d OctreeCorner(const Cloud& points, double resolution) {
  Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f high = -low;
  for (const PointT& p : points) low = low.cwiseMin(p.getVector3fMap()), high = high.cwiseMax(p.getVector3fMap());
  return PclOctreeBox(low.cast<double>(), high.cast<double>(), resolution).min;
}

// PCL's voxels: their keys (sorted), each point's voxel, and each voxel's centroid (the float mean of
// its points in input order, as the octree's leaf container sums them).
struct Voxels {
  std::vector<std::uint64_t> keys;
  std::vector<int> of_point;
  std::vector<Eigen::Vector3f> centroid;
};

bool MakeVoxels(const Cloud& points, double resolution, Voxels& voxels) {
  const Eigen::Vector3d corner = OctreeCorner(points, resolution);
  std::vector<std::pair<std::uint64_t, int>> keyed;
  keyed.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    std::uint64_t k[3];
    for (int a = 0; a < 3; ++a) {
      k[a] = static_cast<std::uint32_t>((static_cast<double>(points[i].getVector3fMap()[a]) - corner[a]) / resolution);
      if (k[a] >= (1u << kPackedKeyBits)) return false;
    }
    keyed.emplace_back(PackKey(k[0], k[1], k[2]), static_cast<int>(i));
  }
  std::sort(keyed.begin(), keyed.end());  // By voxel, then by input order within one.
  voxels.of_point.assign(points.size(), -1);
  std::vector<Eigen::Vector3f> sum;
  std::vector<int> count;
  for (const auto& [key, i] : keyed) {
    if (voxels.keys.empty() || voxels.keys.back() != key) {
      voxels.keys.push_back(key);
      sum.push_back(Eigen::Vector3f::Zero());
      count.push_back(0);
    }
    voxels.of_point[i] = static_cast<int>(voxels.keys.size()) - 1;
    sum.back() += points[i].getVector3fMap();
    ++count.back();
  }
  for (size_t v = 0; v < sum.size(); ++v) voxels.centroid.push_back(sum[v] / static_cast<float>(count[v]));
  return true;
}

// Each voxel's occupied 26-neighbours and itself (OctreePointCloudAdjacency::computeNeighbors), flat.
// Keys order voxels by x, y, then z: the cells z-1 .. z+1 of one (x, y) column are one run of keys, found
// with one search.
NeighbourLists Neighbours(const Voxels& voxels) {
  NeighbourLists lists;
  const std::uint64_t mask = (1u << kPackedKeyBits) - 1;
  for (const std::uint64_t key : voxels.keys) {
    const int x = static_cast<int>(key >> (2 * kPackedKeyBits)), y = static_cast<int>((key >> kPackedKeyBits) & mask);
    const int z = static_cast<int>(key & mask);
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        if (x + dx < 0 || y + dy < 0) continue;
        const std::uint64_t column = PackKey(x + dx, y + dy, 0);
        const std::uint64_t first = column + std::max(z - 1, 0), last = column + z + 1;
        for (auto k = std::lower_bound(voxels.keys.begin(), voxels.keys.end(), first);
             k != voxels.keys.end() && *k <= last; ++k) {
          lists.indices.push_back(static_cast<int>(k - voxels.keys.begin()));
        }
      }
    }
    lists.offsets.push_back(static_cast<int>(lists.indices.size()));
  }
  return lists;
}

// Each voxel's moments over the index list SupervoxelClustering::computeVoxelData fits a plane to:
// itself, then for each neighbour n (itself among them) n and each of n's neighbours. That is the voxel
// once, plus for each neighbour n its own moments and the sum over n's neighbourhood. About the first
// voxel's centroid.
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
  Voxels voxels;
  // PCL's resolution is the float it was given, widened to double.
  if (points.empty() || !MakeVoxels(points, static_cast<double>(resolution_m), voxels)) return normals;
  const std::vector<pcl::Normal> of_voxel = PclVoxelNormals(voxels.centroid, Neighbours(voxels), 0);
  normals.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) normals[i] = of_voxel[voxels.of_point[i]];
  return normals;
}

}  // namespace sortcell::perception
