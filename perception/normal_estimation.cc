#include "perception/normal_estimation.h"

#include "perception/octree_box.h"
#include "perception/plane_moments.h"

// FLANN's one index type we use, not flann.hpp: that instantiates every index type FLANN has (about
// 40 % of this file's compile, measured).
#include <flann/algorithms/dist.h>
#include <flann/algorithms/kdtree_single_index.h>
#include <pcl/features/normal_3d.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace sortcell::perception {
namespace {

// The points sorted into cells `radius_m` wide, keyed by their cell: a point's neighbours lie in the 27
// cells around its own. 21 bits a coordinate: cells up to 2^21 radii from the lowest corner (20 km at 1 cm).
class Grid {
 public:
  Grid(const Cloud& points, double radius_m) : cell_(static_cast<float>(radius_m)) {
    lowest_ = points[0].getVector3fMap();
    Eigen::Vector3f highest = lowest_;
    for (const PointT& p : points)
      lowest_ = lowest_.cwiseMin(p.getVector3fMap()), highest = highest.cwiseMax(p.getVector3fMap());
    constexpr float kCellsPerAxis = 1 << 21;
    usable_ = radius_m > 0 && (highest - lowest_).maxCoeff() / cell_ < kCellsPerAxis - 2;
    if (!usable_) return;
    std::vector<std::pair<std::uint64_t, int>> keyed;
    keyed.reserve(points.size());
    for (size_t i = 0; i < points.size(); ++i)
      keyed.emplace_back(Key(CellOf(points[i].getVector3fMap())), static_cast<int>(i));
    std::sort(keyed.begin(), keyed.end());
    keys_.reserve(points.size());
    original_.reserve(points.size());
    sorted_.reserve(points.size());
    for (const auto& [k, i] : keyed)
      keys_.push_back(k), original_.push_back(i), sorted_.push_back(points[i].getVector3fMap());
  }

  bool usable() const { return usable_; }  // False: spread over too many cells.
  int size() const { return static_cast<int>(sorted_.size()); }
  int original(int k) const { return original_[k]; }  // The input index of sorted point k.
  const Eigen::Vector3f& point(int k) const { return sorted_[k]; }
  Eigen::Vector3d FromLowest(int k) const { return (sorted_[k] - lowest_).cast<double>(); }

  // Calls visit(a, b) once for each pair of sorted points a < b within the radius. Keys order cells by
  // x, y, then z: the cells z-1, z, z+1 of one (x, y) column are one run of keys. From each cell the
  // pairs go to the later cells of its own column (z+1) and to the four columns ahead of it ((x, y+1),
  // (x+1, y-1 ... y+1)); the columns behind reach it from theirs. Visiting the cells in key order, each
  // bound of each column ahead only moves forward: a cursor per bound walks the keys once (a binary
  // search per bound and cell cost more than the distances).
  template <class Visit>
  void ForEachPair(Visit visit) const {
    constexpr int kAhead[5][2] = {{0, 0}, {0, 1}, {1, -1}, {1, 0}, {1, 1}};
    size_t from_cursor[5] = {}, to_cursor[5] = {};
    const auto first_at_or_after = [this](size_t& cursor, std::uint64_t k) {
      while (cursor < keys_.size() && keys_[cursor] < k) ++cursor;
      return cursor;
    };
    const float radius2 = cell_ * cell_;
    for (size_t first = 0, last = 0; first < keys_.size(); first = last) {  // Each occupied cell.
      while (last < keys_.size() && keys_[last] == keys_[first]) ++last;
      const Eigen::Array3i c = CellOf(sorted_[first]);
      for (int o = 0; o < 5; ++o) {
        const auto [dx, dy] = kAhead[o];
        const Eigen::Array3i column(c.x() + dx, c.y() + dy, std::max(c.z() - 1, 0));
        if (column.y() < 0) continue;
        const bool own = dx == 0 && dy == 0;
        const size_t from = own ? first : first_at_or_after(from_cursor[o], Key(column));
        const size_t to =
            first_at_or_after(to_cursor[o], Key(column) + static_cast<std::uint64_t>(c.z() + 2 - column.z()));
        for (size_t a = first; a < last; ++a) {
          for (size_t b = own ? a + 1 : from; b < to; ++b) {
            if ((sorted_[b] - sorted_[a]).squaredNorm() <= radius2) visit(static_cast<int>(a), static_cast<int>(b));
          }
        }
      }
    }
  }

 private:
  Eigen::Array3i CellOf(const Eigen::Vector3f& p) const { return ((p - lowest_) / cell_).array().floor().cast<int>(); }
  static std::uint64_t Key(const Eigen::Array3i& c) { return PackKey(c.x(), c.y(), c.z()); }

  float cell_;
  Eigen::Vector3f lowest_;
  bool usable_ = false;
  std::vector<std::uint64_t> keys_;
  std::vector<int> original_;
  std::vector<Eigen::Vector3f> sorted_;  // The points in key order: each column's candidates lie side by side.
};

// The moments of each sorted point's neighbourhood (itself included), from the grid's pairs; `also`
// is called with each pair too.
template <class AlsoVisit>
std::vector<Moments> NeighbourhoodMoments(const Grid& grid, AlsoVisit also) {
  std::vector<Moments> own(grid.size());
  for (int k = 0; k < grid.size(); ++k) own[k] = Moments::Of(grid.FromLowest(k));
  std::vector<Moments> moments = own;
  grid.ForEachPair([&](int a, int b) {
    moments[a].Add(own[b]);
    moments[b].Add(own[a]);
    also(a, b);
  });
  return moments;
}

pcl::PointCloud<pcl::Normal> NormalsInInputOrder(const Grid& grid, const std::vector<Moments>& moments) {
  pcl::PointCloud<pcl::Normal> normals;
  normals.resize(moments.size());
  for (int k = 0; k < grid.size(); ++k) normals[grid.original(k)] = NormalOf(moments[k], grid.point(k));
  return normals;
}

// Lists of the points 0 .. n-1: each point itself, then the partners of its `pairs` in their order.
NeighbourLists ListsFromPairs(size_t n, const std::vector<std::pair<int, int>>& pairs) {
  NeighbourLists lists;
  lists.offsets.assign(n + 1, 0);
  for (size_t i = 0; i < n; ++i) lists.offsets[i + 1] = 1;
  for (const auto& [a, b] : pairs) ++lists.offsets[a + 1], ++lists.offsets[b + 1];
  for (size_t i = 0; i < n; ++i) lists.offsets[i + 1] += lists.offsets[i];
  lists.indices.resize(lists.offsets[n]);
  std::vector<int> next(lists.offsets.begin(), lists.offsets.end() - 1);
  for (size_t i = 0; i < n; ++i) lists.indices[next[i]++] = static_cast<int>(i);
  for (const auto& [a, b] : pairs) lists.indices[next[a]++] = b, lists.indices[next[b]++] = a;
  return lists;
}

NeighbourLists Flattened(const std::vector<std::vector<int>>& per_point) {
  NeighbourLists lists;
  for (const auto& list : per_point) {
    lists.indices.insert(lists.indices.end(), list.begin(), list.end());
    lists.offsets.push_back(static_cast<int>(lists.indices.size()));
  }
  return lists;
}

}  // namespace

std::vector<std::vector<int>> RadiusNeighbours(const Cloud& points, double radius_m) {
  std::vector<std::vector<int>> neighbours;
  if (points.empty()) return neighbours;
  std::vector<float> xyz;
  xyz.reserve(3 * points.size());
  for (const PointT& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  const flann::Matrix<float> matrix(xyz.data(), points.size(), 3);
  flann::KDTreeSingleIndex<flann::L2_Simple<float>> index(matrix,
                                                          flann::KDTreeSingleIndexParams(15));  // PCL's leaf size.
  index.buildIndex();
  flann::SearchParams search(-1, 0, false);  // Unlimited checks, exact, unsorted (as the unsorted KdTree).
  search.max_neighbors = -1;
  std::vector<std::vector<float>> squared_distances;
  index.radiusSearch(matrix, neighbours, squared_distances, static_cast<float>(radius_m * radius_m), search);
  return neighbours;
}

Neighbourhoods GridNeighbourhoods(const Cloud& points, double radius_m) {
  Neighbourhoods out;
  if (points.empty()) return out;
  const Grid grid(points, radius_m);
  if (!grid.usable()) {
    const std::vector<std::vector<int>> per_point = RadiusNeighbours(points, radius_m);
    out.neighbours = Flattened(per_point);
    out.normals = NormalsFromNeighbours(points, per_point);
    return out;
  }
  std::vector<std::pair<int, int>> pairs;  // In input indices, in the order the grid finds them.
  pairs.reserve(16 * points.size());
  const std::vector<Moments> moments =
      NeighbourhoodMoments(grid, [&](int a, int b) { pairs.emplace_back(grid.original(a), grid.original(b)); });
  out.neighbours = ListsFromPairs(points.size(), pairs);
  out.normals = NormalsInInputOrder(grid, moments);
  return out;
}

pcl::PointCloud<pcl::Normal> NormalsFromNeighbours(const Cloud& points,
                                                   const std::vector<std::vector<int>>& neighbours) {
  pcl::PointCloud<pcl::Normal> normals;
  normals.resize(points.size());
  if (points.empty()) return normals;
  const Eigen::Vector3f origin = points[0].getVector3fMap();
  for (size_t i = 0; i < points.size(); ++i) {
    Moments m;
    for (int j : neighbours[i]) m.Add(Moments::Of((points[j].getVector3fMap() - origin).cast<double>()));
    normals[i] = NormalOf(m, points[i].getVector3fMap());
  }
  return normals;
}

pcl::PointCloud<pcl::Normal> EstimateNormals(const Cloud& points, double radius_m) {
  if (points.empty()) return {};
  const Grid grid(points, radius_m);
  if (!grid.usable()) return NormalsFromNeighbours(points, RadiusNeighbours(points, radius_m));
  return NormalsInInputOrder(grid, NeighbourhoodMoments(grid, [](int, int) {}));
}

}  // namespace sortcell::perception
