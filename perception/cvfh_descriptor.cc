#include "perception/cvfh_descriptor.h"

#include <flann/flann.hpp>
#include <pcl/common/centroid.h>
#include <pcl/features/cvfh.h>
#include <pcl/features/normal_3d.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "perception/seconds_since.h"

namespace sortcell::perception {
namespace {

using Clock = std::chrono::steady_clock;

// `result` marked as an object that cannot be described (its histogram stays empty).
const CvfhResult& Unusable(CvfhResult& result, DescriptorStatus status, std::string detail) {
  result.status = status;
  result.detail = std::move(detail);
  return result;
}

// Normals of `points` (all finite) from their neighbours within `radius_m`, facing the camera at the
// origin; NaN where fewer than 3 neighbours. The same as pcl::NormalEstimation with an unsorted
// pcl::search::KdTree, bit for bit (the same FLANN tree and radius search, then PCL's covariance and
// plane fit), but the neighbours of all points are found in one batched FLANN query: PCL queries one
// point at a time, each query entering an OpenMP region and allocating its result vectors, which cost
// a quarter of the normals' time on a frame of six objects (perception_benchmark).
pcl::PointCloud<pcl::Normal> EstimateNormals(const Cloud& points, double radius_m) {
  std::vector<float> xyz;
  xyz.reserve(3 * points.size());
  for (const PointT& p : points) xyz.insert(xyz.end(), {p.x, p.y, p.z});
  const flann::Matrix<float> matrix(xyz.data(), points.size(), 3);
  flann::Index<flann::L2_Simple<float>> index(matrix, flann::KDTreeSingleIndexParams(15));  // PCL's leaf size.
  index.buildIndex();
  flann::SearchParams search(-1, 0, false);  // Unlimited checks, exact, unsorted (as the unsorted KdTree).
  search.max_neighbors = -1;
  std::vector<std::vector<int>> neighbours;
  std::vector<std::vector<float>> squared_distances;
  index.radiusSearch(matrix, neighbours, squared_distances, static_cast<float>(radius_m * radius_m), search);
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

}  // namespace

const char* ToString(DescriptorStatus status) {
  switch (status) {
    case DescriptorStatus::kOk: return "ok";
    case DescriptorStatus::kTooFewPoints: return "too_few_points";
    case DescriptorStatus::kNoHistogram: return "no_histogram";
  }
  return "unknown";
}

CvfhResult ComputeCvfh(const Cloud& object_C, const CvfhParams& params) {
  auto valid = std::make_shared<Cloud>();
  valid->reserve(object_C.size());
  for (const PointT& p : object_C) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) valid->push_back(p);
  }
  auto points = std::make_shared<Cloud>();
  if (!valid->empty()) {
    pcl::VoxelGrid<PointT> grid;
    const float leaf = static_cast<float>(params.voxel_leaf_m);
    grid.setLeafSize(leaf, leaf, leaf);
    grid.setInputCloud(valid);
    grid.filter(*points);
  }
  CvfhResult result;
  result.points = static_cast<int>(points->size());
  if (result.points < params.min_points) {
    return Unusable(result, DescriptorStatus::kTooFewPoints,
                    "CVFH: the object has " + std::to_string(result.points) + " valid points after " +
                        std::to_string(params.voxel_leaf_m * 1000) + " mm downsampling, need at least " +
                        std::to_string(params.min_points));
  }

  auto t = Clock::now();
  const pcl::PointCloud<pcl::Normal> normals = EstimateNormals(*points, params.normal_radius_m);
  // CVFH puts NaN normals into bin 0: drop points without a normal (too few neighbours).
  auto with_normal = std::make_shared<Cloud>();
  auto clean_normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
  for (size_t i = 0; i < points->size(); ++i) {
    const pcl::Normal& n = normals[i];
    if (std::isfinite(n.normal_x) && std::isfinite(n.normal_y) && std::isfinite(n.normal_z) &&
        std::isfinite(n.curvature)) {
      with_normal->push_back((*points)[i]);
      clean_normals->push_back(n);
    }
  }
  result.normals_s = SecondsSince(t);
  if (static_cast<int>(with_normal->size()) < params.min_points) {
    return Unusable(result, DescriptorStatus::kTooFewPoints,
                    "CVFH: only " + std::to_string(with_normal->size()) + " points have a normal, need " +
                        std::to_string(params.min_points));
  }

  t = Clock::now();
  pcl::CVFHEstimation<PointT, pcl::Normal, pcl::VFHSignature308> cvfh;  // Fresh per object.
  cvfh.setInputCloud(with_normal);
  cvfh.setInputNormals(clean_normals);
  cvfh.setSearchMethod(std::make_shared<pcl::search::KdTree<PointT>>());
  cvfh.setEPSAngleThreshold(static_cast<float>(params.eps_angle_rad));
  cvfh.setCurvatureThreshold(static_cast<float>(params.curvature_threshold));
  cvfh.setClusterTolerance(static_cast<float>(params.cluster_tolerance_m));
  cvfh.setMinPoints(params.min_region_points);
  cvfh.setNormalizeBins(false);  // Raw counts; normalisation is the descriptor's choice.
  pcl::PointCloud<pcl::VFHSignature308> regions;
  cvfh.compute(regions);
  result.cvfh_s = SecondsSince(t);
  result.regions = static_cast<int>(regions.size());
  if (regions.empty()) {
    return Unusable(result, DescriptorStatus::kNoHistogram,
                    "CVFH: PCL returned no histogram (" + std::to_string(with_normal->size()) +
                        " points with a normal, a smooth region needs " + std::to_string(params.min_region_points) +
                        ")");
  }

  result.histogram = Eigen::VectorXf::Zero(kCvfhBins);
  for (const auto& region : regions) {
    result.histogram += Eigen::Map<const Eigen::VectorXf>(region.histogram, kCvfhBins);
  }
  result.histogram /= static_cast<float>(regions.size());
  if (!result.histogram.allFinite()) throw std::runtime_error("CVFH: PCL returned a non-finite histogram");
  return result;
}

}  // namespace sortcell::perception
