#include "perception/pcl_adjacency_grid.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace sortcell::perception {
namespace {

// Each leaf's occupied neighbours and itself, as OctreePointCloudAdjacency::computeNeighbors lists them
// (dx, dy, dz ascending). Found in the keys sorted x, y, z, column by column: a column's cells z-1 .. z+1
// are one run, and as the columns ascend so does each of the nine around them, so nine cursors that only
// move forward find them all (PCL looks each of the 27 up in its octree). Keys under 2^(kPackedKeyBits -
// 1): a neighbour's coordinate never spills into the next field of a packed key.
NeighbourLists LeafNeighbours(const std::vector<VoxelKey>& keys) {
  constexpr int kMost = 27;
  std::vector<std::pair<std::uint64_t, int>> sorted;
  sorted.reserve(keys.size());
  for (size_t v = 0; v < keys.size(); ++v) sorted.emplace_back(PackKey(keys[v][0], keys[v][1], keys[v][2]), v);
  std::sort(sorted.begin(), sorted.end());
  const auto key_at = [&sorted](size_t at) { return at < sorted.size() ? sorted[at].first : ~std::uint64_t{0}; };
  std::vector<int> found(keys.size() * kMost), count(keys.size(), 0);
  size_t cursor[9] = {};
  for (size_t begin = 0, end = 0; begin < sorted.size(); begin = end) {
    const VoxelKey& k = keys[sorted[begin].second];
    while (end < sorted.size() && (sorted[end].first >> kPackedKeyBits) == (sorted[begin].first >> kPackedKeyBits)) {
      ++end;
    }
    for (int c = 0; c < 9; ++c) {  // Each neighbouring column's first cell.
      const std::int64_t x = std::int64_t{k[0]} + c / 3 - 1, y = std::int64_t{k[1]} + c % 3 - 1;
      if (x < 0 || y < 0) continue;
      while (key_at(cursor[c]) < PackKey(x, y, 0)) ++cursor[c];
    }
    for (size_t i = begin; i < end; ++i) {
      const int v = sorted[i].second;
      const std::uint32_t z = keys[v][2];
      for (int c = 0; c < 9; ++c) {
        const std::int64_t x = std::int64_t{k[0]} + c / 3 - 1, y = std::int64_t{k[1]} + c % 3 - 1;
        if (x < 0 || y < 0) continue;
        const std::uint64_t first = PackKey(x, y, z - (z > 0)), last = PackKey(x, y, z + 1);
        while (key_at(cursor[c]) < first) ++cursor[c];  // z ascends within the column.
        for (size_t at = cursor[c]; key_at(at) <= last; ++at) found[v * kMost + count[v]++] = sorted[at].second;
      }
    }
  }
  NeighbourLists lists;
  lists.indices.reserve(keys.size() * 12);
  for (size_t v = 0; v < keys.size(); ++v) {
    lists.indices.insert(lists.indices.end(), found.begin() + v * kMost, found.begin() + v * kMost + count[v]);
    lists.offsets.push_back(static_cast<int>(lists.indices.size()));
  }
  return lists;
}

}  // namespace

// OctreePointCloudAdjacency::addPointsFromInputCloud: the box fitted to the points' extent, each point
// added to its leaf in input order (OctreePointCloudAdjacencyContainer::addPoint, pcl_instantiations.cc),
// the sums made means (computeData), the leaves visited depth first.
bool MakePclAdjacencyGrid(const Cloud& points, double resolution, PclAdjacencyGrid& grid) {
  if (points.empty()) return false;
  Eigen::Vector3f low = Eigen::Vector3f::Constant(std::numeric_limits<float>::max()), high = -low;
  for (const PointT& p : points) {
    if (!p.getVector3fMap().allFinite()) return false;
    low = low.cwiseMin(p.getVector3fMap()), high = high.cwiseMax(p.getVector3fMap());
  }
  const OctreeBox box = PclOctreeBox(low.cast<double>(), high.cast<double>(), resolution);
  if (box.depth >= kPackedKeyBits) return false;
  std::vector<std::pair<std::uint64_t, int>> ordered;
  std::vector<VoxelKey> point_keys(points.size());
  ordered.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    if (!PclOctreeKey(points[i].getVector3fMap(), box, resolution, point_keys[i])) return false;
    ordered.emplace_back(PclLeafOrder(point_keys[i]), static_cast<int>(i));
  }
  std::sort(ordered.begin(), ordered.end());  // By leaf, then by input order within one.
  grid.of_point.assign(points.size(), -1);
  for (size_t n = 0; n < ordered.size(); ++n) {
    const int i = ordered[n].second;
    if (n == 0 || ordered[n].first != ordered[n - 1].first) {
      grid.keys.push_back(point_keys[i]);
      grid.xyz.push_back(Eigen::Vector3f::Zero());
      grid.rgb.push_back(Eigen::Vector3f::Zero());
      grid.count.push_back(0);
    }
    grid.xyz.back() += points[i].getVector3fMap();
    grid.rgb.back() += Eigen::Vector3f(points[i].r, points[i].g, points[i].b);
    ++grid.count.back();
    grid.of_point[i] = static_cast<int>(grid.keys.size()) - 1;
  }
  for (size_t v = 0; v < grid.keys.size(); ++v) {
    const auto n = static_cast<float>(grid.count[v]);
    for (int k = 0; k < 3; ++k) grid.rgb[v][k] /= n;
    for (int k = 0; k < 3; ++k) grid.xyz[v][k] /= n;
  }
  grid.neighbours = LeafNeighbours(grid.keys);
  const auto packed = [](const VoxelKey& k) { return PackKey(k[0], k[1], k[2]); };
  grid.first_in_key_order = static_cast<size_t>(
      std::min_element(grid.keys.begin(), grid.keys.end(),
                       [&packed](const VoxelKey& a, const VoxelKey& b) { return packed(a) < packed(b); }) -
      grid.keys.begin());
  return true;
}

}  // namespace sortcell::perception
