#include "perception/supervoxel_normals.h"

#include <pcl/features/normal_3d.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace sortcell::perception {
namespace {

// The corner of PCL's adjacency octree (OctreePointCloudAdjacency::addPointsFromInputCloud, then
// OctreePointCloud::defineBoundingBox and getKeyBitSize, PCL 1.13): the points' box, grown evenly on
// each side to the octree's cube of 2^depth voxels. In double, as PCL computes it.
Eigen::Vector3d OctreeCorner(const Cloud& points, double resolution) {
  Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max());
  Eigen::Vector3f high = -low;
  for (const PointT& p : points) low = low.cwiseMin(p.getVector3fMap()), high = high.cwiseMax(p.getVector3fMap());
  const double min_value = std::numeric_limits<float>::epsilon();
  const Eigen::Vector3d min = low.cast<double>(), max = high.cast<double>();
  std::uint32_t max_voxels = 2;
  for (int a = 0; a < 3; ++a) {
    max_voxels = std::max(max_voxels, static_cast<std::uint32_t>(std::ceil((max[a] - min[a] - min_value) / resolution)));
  }
  const auto depth = static_cast<std::uint32_t>(std::ceil(std::log2(max_voxels) - min_value));
  const double side = static_cast<double>(1u << depth) * resolution;
  Eigen::Vector3d corner = min;
  for (int a = 0; a < 3; ++a) {
    const double oversize = (side - (max[a] - min[a])) / 2.0;
    if (oversize > min_value) corner[a] -= oversize;
  }
  return corner;
}

constexpr int kKeyBits = 21;  // Per axis in a packed key: 2^21 voxels (15 km at 7.5 mm).

std::uint64_t Pack(std::uint64_t x, std::uint64_t y, std::uint64_t z) { return (x << (2 * kKeyBits)) | (y << kKeyBits) | z; }

// PCL's voxels: their keys (sorted), each point's voxel, and each voxel's centroid (the float mean of
// its points in input order, as the octree's leaf container sums them).
struct Voxels {
  std::vector<std::uint64_t> keys;
  std::vector<int> of_point;
  std::vector<Eigen::Vector3f> centroid;
  std::vector<Eigen::Vector3i> cell;
};

bool MakeVoxels(const Cloud& points, double resolution, Voxels& voxels) {
  const Eigen::Vector3d corner = OctreeCorner(points, resolution);
  std::vector<std::pair<std::uint64_t, int>> keyed;
  keyed.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    std::uint64_t k[3];
    for (int a = 0; a < 3; ++a) {
      k[a] = static_cast<std::uint32_t>((static_cast<double>(points[i].getVector3fMap()[a]) - corner[a]) / resolution);
      if (k[a] >= (1u << kKeyBits)) return false;
    }
    keyed.emplace_back(Pack(k[0], k[1], k[2]), static_cast<int>(i));
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
      const std::uint64_t mask = (1u << kKeyBits) - 1;
      voxels.cell.emplace_back(static_cast<int>(key >> (2 * kKeyBits)), static_cast<int>((key >> kKeyBits) & mask),
                               static_cast<int>(key & mask));
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
void Neighbours(const Voxels& voxels, std::vector<int>& offsets, std::vector<int>& indices) {
  offsets.assign(1, 0);
  for (const Eigen::Vector3i& c : voxels.cell) {
    for (int dx = -1; dx <= 1; ++dx) {
      for (int dy = -1; dy <= 1; ++dy) {
        if (c.x() + dx < 0 || c.y() + dy < 0) continue;
        const std::uint64_t column = Pack(c.x() + dx, c.y() + dy, 0);
        const std::uint64_t first = column + std::max(c.z() - 1, 0), last = column + c.z() + 1;
        for (auto k = std::lower_bound(voxels.keys.begin(), voxels.keys.end(), first);
             k != voxels.keys.end() && *k <= last; ++k) {
          indices.push_back(static_cast<int>(k - voxels.keys.begin()));
        }
      }
    }
    offsets.push_back(static_cast<int>(indices.size()));
  }
}

// The sums of 1, x, y, z, xx, xy, xz, yy, yz, zz over a multiset of centroids, in double about the
// voxels' first centroid.
using ListMoments = Eigen::Matrix<double, 10, 1>;

ListMoments ListMomentsOf(const Eigen::Vector3d& p) {
  ListMoments m;
  m << 1, p.x(), p.y(), p.z(), p.x() * p.x(), p.x() * p.y(), p.x() * p.z(), p.y() * p.y(), p.y() * p.z(), p.z() * p.z();
  return m;
}

// Each voxel's moments over the index list SupervoxelClustering::computeVoxelData fits a plane to:
// itself, then for each neighbour n (itself among them) n and each of n's neighbours. That is the voxel
// once, plus for each neighbour n its own moments and the sum over n's neighbourhood.
std::vector<ListMoments> IndexListMoments(const Voxels& voxels, const std::vector<int>& offsets, const std::vector<int>& indices) {
  const size_t n = voxels.centroid.size();
  std::vector<ListMoments> own(n), ring(n, ListMoments::Zero()), list(n);
  for (size_t v = 0; v < n; ++v) own[v] = ListMomentsOf((voxels.centroid[v] - voxels.centroid[0]).cast<double>());
  for (size_t v = 0; v < n; ++v) {
    for (int k = offsets[v]; k < offsets[v + 1]; ++k) ring[v] += own[indices[k]];
  }
  for (size_t v = 0; v < n; ++v) {
    list[v] = own[v] + ring[v];
    for (int k = offsets[v]; k < offsets[v + 1]; ++k) list[v] += ring[indices[k]];
  }
  return list;
}

// PCL's plane fit of the index list, flipped towards the camera at the origin. A voxel with no
// neighbour but itself fits one place three times: PCL's covariance, shifted by the first point, is
// exactly zero there, and so is the one given to the fit here.
pcl::Normal VoxelNormal(const ListMoments& m, bool alone, const Eigen::Vector3f& c) {
  Eigen::Matrix3f covariance = Eigen::Matrix3f::Zero();
  if (!alone) {
    const ListMoments e = m / m[0];
    const Eigen::Vector3d mean = e.segment<3>(1);
    Eigen::Matrix3d c2;
    c2 << e[4], e[5], e[6], e[5], e[7], e[8], e[6], e[8], e[9];
    covariance = (c2 - mean * mean.transpose()).cast<float>();
  }
  pcl::Normal normal;
  pcl::solvePlaneParameters(covariance, normal.normal_x, normal.normal_y, normal.normal_z, normal.curvature);
  pcl::flipNormalTowardsViewpoint(PointT(c.x(), c.y(), c.z()), 0.0f, 0.0f, 0.0f, normal.normal_x, normal.normal_y,
                                  normal.normal_z);
  normal.getNormalVector3fMap().normalize();
  return normal;
}

}  // namespace

pcl::PointCloud<pcl::Normal> SupervoxelVoxelNormals(const Cloud& points, float resolution_m) {
  pcl::PointCloud<pcl::Normal> normals;
  Voxels voxels;
  // PCL's resolution is the float it was given, widened to double.
  if (points.empty() || !MakeVoxels(points, static_cast<double>(resolution_m), voxels)) return normals;
  std::vector<int> offsets, indices;
  Neighbours(voxels, offsets, indices);
  const std::vector<ListMoments> moments = IndexListMoments(voxels, offsets, indices);
  std::vector<pcl::Normal> of_voxel;
  of_voxel.reserve(voxels.keys.size());
  for (size_t v = 0; v < voxels.keys.size(); ++v) {
    of_voxel.push_back(VoxelNormal(moments[v], offsets[v + 1] - offsets[v] == 1, voxels.centroid[v]));
  }
  normals.resize(points.size());
  for (size_t i = 0; i < points.size(); ++i) normals[i] = of_voxel[voxels.of_point[i]];
  return normals;
}

}  // namespace sortcell::perception
