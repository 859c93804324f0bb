#include "perception/cvfh_descriptor.h"

#include <pcl/features/cvfh.h>
#include <pcl/filters/voxel_grid.h>
#include <pcl/search/kdtree.h>

#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "perception/normal_estimation.h"
#include "common/wall_clock.h"

namespace sortcell::perception {
namespace {

using Clock = std::chrono::steady_clock;

// `result` marked as an object that cannot be described (its histogram stays empty).
const CvfhResult& Unusable(CvfhResult& result, DescriptorStatus status, std::string detail) {
  result.status = status;
  result.detail = std::move(detail);
  return result;
}

// The object's finite points on a voxel grid of `leaf` (m).
Cloud::Ptr DownsampledFinite(const Cloud& object_C, double leaf_m) {
  auto valid = std::make_shared<Cloud>();
  valid->reserve(object_C.size());
  for (const PointT& p : object_C) {
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) valid->push_back(p);
  }
  auto points = std::make_shared<Cloud>();
  if (!valid->empty()) {
    pcl::VoxelGrid<PointT> grid;
    const float leaf = static_cast<float>(leaf_m);
    grid.setLeafSize(leaf, leaf, leaf);
    grid.setInputCloud(valid);
    grid.filter(*points);
  }
  return points;
}

// The points that have a normal, with their normals: CVFH puts NaN normals into bin 0, so points
// without one (too few neighbours) are dropped.
void KeepPointsWithNormals(const Cloud& points, const pcl::PointCloud<pcl::Normal>& normals, Cloud& with_normal,
                           pcl::PointCloud<pcl::Normal>& clean_normals) {
  for (size_t i = 0; i < points.size(); ++i) {
    const pcl::Normal& n = normals[i];
    if (std::isfinite(n.normal_x) && std::isfinite(n.normal_y) && std::isfinite(n.normal_z) &&
        std::isfinite(n.curvature)) {
      with_normal.push_back(points[i]);
      clean_normals.push_back(n);
    }
  }
}

// PCL's CVFH of the points with their normals: one 308-bin histogram per smooth region, raw counts.
pcl::PointCloud<pcl::VFHSignature308> CvfhRegions(const Cloud::Ptr& points,
                                                  const pcl::PointCloud<pcl::Normal>::Ptr& normals,
                                                  const CvfhParams& params) {
  pcl::CVFHEstimation<PointT, pcl::Normal, pcl::VFHSignature308> cvfh;  // Fresh per object.
  cvfh.setInputCloud(points);
  cvfh.setInputNormals(normals);
  cvfh.setSearchMethod(std::make_shared<pcl::search::KdTree<PointT>>());
  cvfh.setEPSAngleThreshold(static_cast<float>(params.eps_angle_rad));
  cvfh.setCurvatureThreshold(static_cast<float>(params.curvature_threshold));
  cvfh.setClusterTolerance(static_cast<float>(params.cluster_tolerance_m));
  cvfh.setMinPoints(params.min_region_points);
  cvfh.setNormalizeBins(false);  // Raw counts; normalisation is the descriptor's choice.
  pcl::PointCloud<pcl::VFHSignature308> regions;
  cvfh.compute(regions);
  return regions;
}

}  // namespace

constexpr EnumNames<DescriptorStatus, 3> kDescriptorStatusNames{{{DescriptorStatus::kOk, "ok"},
                                                                 {DescriptorStatus::kTooFewPoints, "too_few_points"},
                                                                 {DescriptorStatus::kNoHistogram, "no_histogram"}}};

const char* ToString(DescriptorStatus status) { return NameOf(kDescriptorStatusNames, status); }

CvfhResult ComputeCvfh(const Cloud& object_C, const CvfhParams& params) {
  const Cloud::Ptr points = DownsampledFinite(object_C, params.voxel_leaf_m);
  CvfhResult result;
  result.points = static_cast<int>(points->size());
  if (result.points < params.min_points) {
    return Unusable(result, DescriptorStatus::kTooFewPoints,
                    "CVFH: the object has " + std::to_string(result.points) + " valid points after " +
                        std::to_string(params.voxel_leaf_m * 1000) + " mm downsampling, need at least " +
                        std::to_string(params.min_points));
  }

  auto t = Clock::now();
  auto with_normal = std::make_shared<Cloud>();
  auto clean_normals = std::make_shared<pcl::PointCloud<pcl::Normal>>();
  KeepPointsWithNormals(*points, EstimateNormals(*points, params.normal_radius_m), *with_normal, *clean_normals);
  result.normals_s = SecondsSince(t);
  if (static_cast<int>(with_normal->size()) < params.min_points) {
    return Unusable(result, DescriptorStatus::kTooFewPoints,
                    "CVFH: only " + std::to_string(with_normal->size()) + " points have a normal, need " +
                        std::to_string(params.min_points));
  }

  t = Clock::now();
  const pcl::PointCloud<pcl::VFHSignature308> regions = CvfhRegions(with_normal, clean_normals, params);
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
