#include "perception/normal_estimation.h"

#include <flann/flann.hpp>
#include <pcl/common/centroid.h>
#include <pcl/features/normal_3d.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <utility>

namespace sortcell::perception {

std::vector<std::vector<int>> RadiusNeighbours(const Cloud& points, double radius_m) {
  std::vector<std::vector<int>> neighbours;
  if (points.empty()) return neighbours;
  std::vector<float> xyz;
  xyz.reserve(3 * points.size());
  for (const PointT& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  const flann::Matrix<float> matrix(xyz.data(), points.size(), 3);
  flann::Index<flann::L2_Simple<float>> index(matrix, flann::KDTreeSingleIndexParams(15));  // PCL's leaf size.
  index.buildIndex();
  flann::SearchParams search(-1, 0, false);  // Unlimited checks, exact, unsorted (as the unsorted KdTree).
  search.max_neighbors = -1;
  std::vector<std::vector<float>> squared_distances;
  index.radiusSearch(matrix, neighbours, squared_distances, static_cast<float>(radius_m * radius_m), search);
  return neighbours;
}

std::vector<std::vector<int>> GridRadiusNeighbours(const Cloud& points, double radius_m) {
  std::vector<std::vector<int>> neighbours(points.size());
  if (points.empty()) return neighbours;
  Eigen::Vector3f lowest = points[0].getVector3fMap(), highest = lowest;
  for (const PointT& p : points) lowest = lowest.cwiseMin(p.getVector3fMap()), highest = highest.cwiseMax(p.getVector3fMap());
  // Cells a radius wide: a point's neighbours lie in the 3 x 3 x 3 cells around its own. 21 bits a
  // coordinate: cells up to 2^21 radii from the lowest corner (20 km at 1 cm).
  const float cell = static_cast<float>(radius_m);
  constexpr float kCellsPerAxis = 1 << 21;
  if (!(radius_m > 0) || !((highest - lowest).maxCoeff() / cell < kCellsPerAxis - 2)) return RadiusNeighbours(points, radius_m);
  const auto cell_of = [&](const Eigen::Vector3f& p) -> Eigen::Array3i {
    return ((p - lowest) / cell).array().floor().cast<int>();
  };
  const auto key = [](const Eigen::Array3i& c) {
    return (static_cast<std::uint64_t>(c.x()) << 42) | (static_cast<std::uint64_t>(c.y()) << 21) | static_cast<std::uint64_t>(c.z());
  };
  std::vector<std::pair<std::uint64_t, int>> keyed;
  keyed.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) keyed.emplace_back(key(cell_of(points[i].getVector3fMap())), static_cast<int>(i));
  std::sort(keyed.begin(), keyed.end());
  std::vector<std::uint64_t> keys;
  std::vector<Eigen::Vector3f> sorted;  // The points in key order: each column's candidates lie side by side.
  keys.reserve(points.size());
  sorted.reserve(points.size());
  for (const auto& [k, i] : keyed) keys.push_back(k), sorted.push_back(points[i].getVector3fMap());
  // Keys order cells by x, y, then z: the cells z-1, z, z+1 of one (x, y) column are one run of keys.
  // Visiting the cells in key order, each bound of each column ahead only moves forward: a cursor per
  // bound walks the keys once (a binary search per bound and cell cost more than the distances).
  const auto first_at_or_after = [&keys](size_t& cursor, std::uint64_t k) {
    while (cursor < keys.size() && keys[cursor] < k) ++cursor;
    return cursor;
  };
  size_t from_cursor[5] = {}, to_cursor[5] = {};
  const float radius2 = static_cast<float>(radius_m * radius_m);
  for (size_t i = 0; i < points.size(); ++i) neighbours[i].reserve(32), neighbours[i].push_back(static_cast<int>(i));
  // Each pair once: from a cell to the later cells of its own column (z+1) and to the four columns
  // ahead of it ((x, y+1), (x+1, y-1 ... y+1)); the columns behind reach it from theirs.
  constexpr int kAhead[5][2] = {{0, 0}, {0, 1}, {1, -1}, {1, 0}, {1, 1}};
  for (size_t first = 0, last = 0; first < keys.size(); first = last) {  // Each occupied cell.
    while (last < keys.size() && keys[last] == keys[first]) ++last;
    const Eigen::Array3i c = cell_of(sorted[first]);
    for (int o = 0; o < 5; ++o) {
      const auto [dx, dy] = kAhead[o];
      const Eigen::Array3i column(c.x() + dx, c.y() + dy, std::max(c.z() - 1, 0));
      if (column.y() < 0) continue;
      const bool own = dx == 0 && dy == 0;
      const size_t from = own ? first : first_at_or_after(from_cursor[o], key(column));
      const size_t to = first_at_or_after(to_cursor[o], key(column) + static_cast<std::uint64_t>(c.z() + 2 - column.z()));
      for (size_t q = first; q < last; ++q) {
        for (size_t k = own ? q + 1 : from; k < to; ++k) {
          if ((sorted[k] - sorted[q]).squaredNorm() > radius2) continue;
          neighbours[keyed[q].second].push_back(keyed[k].second);
          neighbours[keyed[k].second].push_back(keyed[q].second);
        }
      }
    }
  }
  return neighbours;
}

pcl::PointCloud<pcl::Normal> NormalsFromNeighbours(const Cloud& points, const std::vector<std::vector<int>>& neighbours) {
  pcl::PointCloud<pcl::Normal> normals;
  normals.resize(points.size());
  constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
  for (size_t i = 0; i < points.size(); ++i) {
    pcl::Normal& n = normals[i];
    Eigen::Matrix3f covariance;
    Eigen::Vector4f centroid;
    if (neighbours[i].size() < 3 ||
        pcl::computeMeanAndCovarianceMatrix(points, neighbours[i], covariance, centroid) == 0) {
      n.normal_x = n.normal_y = n.normal_z = n.curvature = kNaN;
      continue;
    }
    pcl::solvePlaneParameters(covariance, n.normal_x, n.normal_y, n.normal_z, n.curvature);
    pcl::flipNormalTowardsViewpoint(points[i], 0.0f, 0.0f, 0.0f, n.normal_x, n.normal_y, n.normal_z);
  }
  return normals;
}

pcl::PointCloud<pcl::Normal> EstimateNormals(const Cloud& points, double radius_m) {
  return NormalsFromNeighbours(points, GridRadiusNeighbours(points, radius_m));
}

}  // namespace sortcell::perception
