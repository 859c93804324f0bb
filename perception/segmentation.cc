#include "perception/segmentation.h"

#include <pcl/filters/voxel_grid.h>
#include <pcl/sample_consensus/ransac.h>
#include <pcl/sample_consensus/sac_model_perpendicular_plane.h>
#include <pcl/sample_consensus/sac_model_plane.h>
#include <pcl/search/kdtree.h>
#include <pcl/segmentation/extract_clusters.h>
#include <pcl/segmentation/extract_polygonal_prism_data.h>
#include <pcl/surface/convex_hull.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

#include "common/enum_names.h"
#include "common/wall_clock.h"

namespace sortcell::perception {
namespace {

using Clock = std::chrono::steady_clock;

bool Finite(const PointT& p) { return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z); }

// Kinect v1 axial noise at depth z (DESIGN.md section 5), for the background tolerance.
double AxialSigma(double z) { return 0.0012 + 0.0019 * (z - 0.4) * (z - 0.4); }

void CheckInput(const Cloud& cloud, const Cloud* background) {
  if (cloud.empty()) throw std::invalid_argument("segmentation: the cloud is empty");
  if (cloud.size() != static_cast<size_t>(cloud.width) * cloud.height) {
    throw std::invalid_argument("segmentation: the cloud holds " + std::to_string(cloud.size()) + " points, not its " +
                                std::to_string(cloud.width) + "x" + std::to_string(cloud.height));
  }
  if (background != nullptr && !cloud.isOrganized()) {
    throw std::invalid_argument(
        "segmentation: background subtraction needs an organized cloud (one point per "
        "pixel); this one is unorganized (height 1)");
  }
  if (background != nullptr && (background->width != cloud.width || background->height != cloud.height)) {
    throw std::invalid_argument("segmentation: the background cloud is " + std::to_string(background->width) + "x" +
                                std::to_string(background->height) + ", the cloud " + std::to_string(cloud.width) +
                                "x" + std::to_string(cloud.height));
  }
}

// Whether the valid point `p` lies in the region of interest: inside the world workspace box (with a pose).
bool InRegion(const PointT& p, const std::optional<Eigen::Isometry3d>& X_WC, const SegmentationParams& params) {
  if (!X_WC) return true;
  const Eigen::Vector3d p_W = *X_WC * Eigen::Vector3d(p.x, p.y, p.z);
  return !((p_W.array() < params.workspace_min_W.array()).any() ||
           (p_W.array() > params.workspace_max_W.array()).any());
}

// Whether the valid point `p` has the empty cell's depth `b` at its pixel (the paper's foreground/background
// subtraction).
bool IsBackground(const PointT& p, const PointT& b, double tolerance) {
  return Finite(b) && std::abs(p.z - b.z) < tolerance + 3.0 * AxialSigma(b.z);
}

// Why the region of interest is empty: no depth at all, or nothing inside the workspace box.
std::string NoValidPointDetail(const Cloud& cloud, const SegmentationParams& params) {
  if (std::none_of(cloud.begin(), cloud.end(), Finite)) return "segmentation: the cloud has no valid point (all NaN)";
  const Eigen::IOFormat row(4, Eigen::DontAlignCols, ", ", ", ", "", "", "(", ")");
  std::ostringstream detail;
  detail << "segmentation: no valid point inside the workspace box " << params.workspace_min_W.transpose().format(row)
         << " to " << params.workspace_max_W.transpose().format(row) << " m (world frame)";
  return detail.str();
}

// What the rest of the segmentation is taken from, both in pixel order: the region of interest's points the
// plane is fitted on, and the region's foreground pixels.
struct Crop {
  Cloud::Ptr plane_sample = std::make_shared<Cloud>();
  std::vector<int> candidates;
  bool any_in_region = false;
};

// One pass over the pixels. The plane's sample: organized, every plane_stride-th pixel of every plane_stride-th
// row (a grid); unorganized, every plane_stride^2-th point of the region, as many. A pixel the background
// subtraction drops and the grid leaves out is used by nothing, so its workspace test (a transform to the world)
// is skipped; the empty cell's depth is compared first. (A background needs an organized cloud, CheckInput: an
// unorganized cloud's sample counts every point of the region, so each is tested.)
Crop CropCloud(const Cloud& cloud, const Cloud* background, const std::optional<Eigen::Isometry3d>& X_WC,
               const SegmentationParams& params) {
  Crop crop;
  const bool organized = cloud.isOrganized();
  const int stride = std::max(1, params.plane_stride);
  const std::int64_t every = std::int64_t{stride} * stride;  // Unorganized: one sampled point in `every`.
  const int width = organized ? static_cast<int>(cloud.width) : static_cast<int>(cloud.size());
  const int height = organized ? static_cast<int>(cloud.height) : 1;
  crop.plane_sample->reserve(organized
                                 ? static_cast<size_t>((width + stride - 1) / stride) * ((height + stride - 1) / stride)
                                 : static_cast<size_t>(static_cast<std::int64_t>(cloud.size()) / every + 1));
  std::int64_t found_in_region = 0;  // Pixels found in the region so far (not counting those skipped).
  for (int row = 0; row < height; ++row) {
    const bool row_on_grid = organized && row % stride == 0;
    int phase = 0;  // col % stride, counted rather than divided.
    for (int col = 0; col < width; ++col, phase = phase + 1 == stride ? 0 : phase + 1) {
      const int i = row * width + col;
      const PointT& p = cloud[i];
      if (!Finite(p)) continue;
      const bool on_grid = row_on_grid && phase == 0;
      const bool foreground =
          background == nullptr || !IsBackground(p, (*background)[i], params.background_tolerance_m);
      if ((!foreground && !on_grid) || !InRegion(p, X_WC, params)) continue;
      if (organized ? on_grid : found_in_region % every == 0) crop.plane_sample->push_back(p);
      ++found_in_region;
      if (foreground) crop.candidates.push_back(i);
    }
  }
  // Every pixel in the region may have been background off the grid: then look again, testing each.
  crop.any_in_region = found_in_region > 0 || std::any_of(cloud.begin(), cloud.end(), [&](const PointT& p) {
                         return Finite(p) && InRegion(p, X_WC, params);
                       });
  return crop;
}

struct PlaneFit {
  Eigen::Vector4d plane_C;  // Oriented: the camera (origin) on the positive side.
  pcl::PointIndices::Ptr inliers;
  Cloud::Ptr sample;
};

// The plane as PCL's SACSegmentation finds it (RANSAC, then the coefficients refined on the inliers and
// the inliers selected again), from PCL's RANSAC and plane models themselves: SACSegmentation would
// compile every one of PCL's sample consensus models into this library (pcl_instantiations.cc). Not
// randomly seeded: the same cloud gives the same plane. Empty coefficients and no inliers: none found.
Eigen::VectorXf RansacPlane(const Cloud::Ptr& sample, const std::optional<Eigen::Isometry3d>& X_WC,
                            const SegmentationParams& params, pcl::Indices& inliers) {
  pcl::SampleConsensusModelPlane<PointT>::Ptr model;
  if (X_WC) {
    auto perpendicular = std::make_shared<pcl::SampleConsensusModelPerpendicularPlane<PointT>>(sample);
    perpendicular->setAxis((X_WC->rotation().transpose() * Eigen::Vector3d::UnitZ()).cast<float>());
    perpendicular->setEpsAngle(params.plane_max_tilt_rad);
    model = perpendicular;
  } else {
    model = std::make_shared<pcl::SampleConsensusModelPlane<PointT>>(sample);
  }
  pcl::RandomSampleConsensus<PointT> ransac(model, params.plane_distance_m);
  ransac.setMaxIterations(params.plane_iterations);
  inliers.clear();
  if (!ransac.computeModel()) return {};
  ransac.getInliers(inliers);
  Eigen::VectorXf coefficients, refined;
  ransac.getModelCoefficients(coefficients);
  model->optimizeModelCoefficients(inliers, coefficients, refined);
  model->selectWithinDistance(refined, params.plane_distance_m, inliers);
  return refined;
}

// RANSAC on the region of interest's sample (CropCloud). With a pose, the plane must be near horizontal in the
// world (the table), so a large object face can never be taken for it. No plane: nullopt, with the reason
// in `detail`.
std::optional<PlaneFit> FitSupportingPlane(const Cloud::Ptr& sample, const std::optional<Eigen::Isometry3d>& X_WC,
                                           const SegmentationParams& params, std::string& detail) {
  PlaneFit fit{Eigen::Vector4d::Zero(), std::make_shared<pcl::PointIndices>(), sample};
  Eigen::VectorXf coefficients;
  if (static_cast<int>(sample->size()) >= params.min_plane_points) {
    coefficients = RansacPlane(sample, X_WC, params, fit.inliers->indices);
  }
  if (static_cast<int>(fit.inliers->indices.size()) < params.min_plane_points || coefficients.size() != 4) {
    detail = "segmentation: no supporting plane found (" + std::to_string(fit.inliers->indices.size()) +
             " sampled inliers of " + std::to_string(sample->size()) + ", need " +
             std::to_string(params.min_plane_points) + "): expected objects standing on a table or floor";
    return std::nullopt;
  }
  Eigen::Vector4d plane = coefficients.cast<double>();
  plane /= plane.head<3>().norm();
  if (plane[3] < 0) plane = -plane;  // n.0 + d = d: positive on the camera's side.
  fit.plane_C = plane;
  return fit;
}

// Without a pose: keep what stands on the plane's inlier area (its convex hull), up to a height.
std::vector<int> OnPlaneArea(const Cloud& cloud, const std::vector<int>& pixels, const PlaneFit& fit,
                             const SegmentationParams& params) {
  // The inliers projected onto the plane, as PCL's ProjectInliers does it with the plane model.
  auto projected = std::make_shared<Cloud>();
  pcl::SampleConsensusModelPlane<PointT>(fit.sample)
      .projectPoints(fit.inliers->indices, fit.plane_C.cast<float>(), *projected, false);
  auto hull = std::make_shared<Cloud>();
  pcl::ConvexHull<PointT> convex;
  convex.setDimension(2);
  convex.setInputCloud(projected);
  convex.reconstruct(*hull);
  if (hull->size() < 3) return {};

  auto input = std::make_shared<Cloud>(cloud);
  auto candidates = std::make_shared<pcl::PointIndices>();
  candidates->indices = pixels;
  pcl::ExtractPolygonalPrismData<PointT> prism;
  prism.setInputCloud(input);
  prism.setIndices(candidates);
  prism.setInputPlanarHull(hull);
  prism.setHeightLimits(params.above_plane_m, params.max_object_height_m);
  pcl::PointIndices inside;
  prism.segment(inside);
  return inside.indices;
}

// With a pose: the candidates farther than `above_plane_m` above the plane, on the camera's side.
std::vector<int> AbovePlane(const Cloud& cloud, const std::vector<int>& candidates, const Eigen::Vector4d& plane_C,
                            const SegmentationParams& params) {
  std::vector<int> above;
  above.reserve(candidates.size());
  const Eigen::Vector3f n = plane_C.head<3>().cast<float>();
  const float d = static_cast<float>(plane_C[3]);
  for (int i : candidates) {
    if (n.dot(cloud[i].getVector3fMap()) + d > params.above_plane_m) above.push_back(i);
  }
  return above;
}

// The convex clustering's settings with the cluster size limits of the segmentation's.
ConvexClusteringParams ConvexParams(const SegmentationParams& params) {
  ConvexClusteringParams convex = params.convex;
  convex.min_cluster_voxels = params.min_cluster_voxels;
  convex.max_cluster_voxels = params.max_cluster_voxels;
  return convex;
}

// Euclidean clusters of `voxels`, largest first.
std::vector<pcl::PointIndices> EuclideanClusters(const Cloud::Ptr& voxels, const SegmentationParams& params) {
  auto tree = std::make_shared<pcl::search::KdTree<PointT>>();
  tree->setInputCloud(voxels);
  std::vector<pcl::PointIndices> clusters;
  pcl::EuclideanClusterExtraction<PointT> extract;
  extract.setClusterTolerance(params.cluster_tolerance_m);
  extract.setMinClusterSize(params.min_cluster_voxels);
  extract.setMaxClusterSize(params.max_cluster_voxels);
  extract.setSearchMethod(tree);
  extract.setInputCloud(voxels);
  extract.extract(clusters);
  std::sort(clusters.begin(), clusters.end(),
            [](const pcl::PointIndices& a, const pcl::PointIndices& b) { return a.indices.size() > b.indices.size(); });
  return clusters;
}

// Fills a segment whose pixels are set: its cloud, and centroid, box and principal axes of its voxels
// `cluster` in the output frame O.
void DescribeSegment(const Cloud& cloud, const Cloud& voxels, const pcl::PointIndices& cluster,
                     const Eigen::Isometry3d& X_OC, Segment& segment) {
  segment.voxels = static_cast<int>(cluster.indices.size());
  segment.cloud_C = std::make_shared<Cloud>();
  segment.cloud_C->reserve(segment.indices.size());
  for (int i : segment.indices) segment.cloud_C->push_back(cloud[i]);
  Eigen::Matrix3Xd p_O(3, segment.voxels);
  for (int k = 0; k < segment.voxels; ++k) {
    p_O.col(k) = X_OC * voxels[cluster.indices[k]].getVector3fMap().cast<double>();
  }
  segment.centroid = p_O.rowwise().mean();
  segment.bbox_min = p_O.rowwise().minCoeff();
  segment.bbox_max = p_O.rowwise().maxCoeff();
  const Eigen::Matrix3Xd centred = p_O.colwise() - segment.centroid;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca(centred * centred.transpose());
  segment.principal_axes = pca.eigenvectors().rowwise().reverse();  // Largest variance first.
}

// Voxelises the object pixels `above`, clusters the voxels and gives each cluster its pixels back
// (full resolution) as one segment of `result`.
void ClusterObjects(const Cloud& cloud, const std::vector<int>& above, const std::optional<Eigen::Isometry3d>& X_WC,
                    const SegmentationParams& params, SegmentationResult& result) {
  auto t = Clock::now();
  auto kept = std::make_shared<Cloud>();
  kept->reserve(above.size());
  for (int i : above) kept->push_back(cloud[i]);
  auto voxels = std::make_shared<Cloud>();
  pcl::VoxelGrid<PointT> grid;
  grid.setInputCloud(kept);
  const float leaf = static_cast<float>(params.voxel_leaf_m);
  grid.setLeafSize(leaf, leaf, leaf);
  grid.setSaveLeafLayout(true);
  grid.filter(*voxels);
  result.timings.voxel_s = SecondsSince(t);

  t = Clock::now();
  const std::vector<pcl::PointIndices> clusters = params.clustering == SegmentationParams::Clustering::kConvex
                                                      ? ConvexClusters(voxels, result.plane_C, ConvexParams(params))
                                                      : EuclideanClusters(voxels, params);
  std::vector<int> cluster_of_voxel(voxels->size(), -1);
  for (size_t c = 0; c < clusters.size(); ++c) {
    for (int v : clusters[c].indices) cluster_of_voxel[v] = static_cast<int>(c);
  }
  result.segments.resize(clusters.size());
  for (size_t k = 0; k < above.size(); ++k) {
    const int v = grid.getCentroidIndex((*kept)[k]);
    if (v < 0 || cluster_of_voxel[v] < 0) continue;
    result.segments[cluster_of_voxel[v]].indices.push_back(above[k]);
  }
  const Eigen::Isometry3d X_OC = X_WC.value_or(Eigen::Isometry3d::Identity());  // Output frame O.
  for (size_t c = 0; c < clusters.size(); ++c) DescribeSegment(cloud, *voxels, clusters[c], X_OC, result.segments[c]);
  result.timings.cluster_s = SecondsSince(t);
}

}  // namespace

constexpr EnumNames<SegmentationStatus, 3> kSegmentationStatusNames{
    {{SegmentationStatus::kOk, "ok"},
     {SegmentationStatus::kNoValidPoints, "no_valid_points"},
     {SegmentationStatus::kNoPlane, "no_plane"}}};

const char* ToString(SegmentationStatus status) { return NameOf(kSegmentationStatusNames, status); }

SegmentationResult SegmentObjects(const Cloud& cloud, const std::optional<Eigen::Isometry3d>& X_WC,
                                  const Cloud* background, const SegmentationParams& params) {
  CheckInput(cloud, background);
  SegmentationResult result;
  result.world_frame = X_WC.has_value();

  auto t = Clock::now();
  const Crop crop = CropCloud(cloud, background, X_WC, params);
  if (!crop.any_in_region) {
    result.status = SegmentationStatus::kNoValidPoints;
    result.detail = NoValidPointDetail(cloud, params);
    return result;
  }
  const std::vector<int>& candidates = crop.candidates;
  result.timings.crop_s = SecondsSince(t);

  t = Clock::now();
  const std::optional<PlaneFit> fit = FitSupportingPlane(crop.plane_sample, X_WC, params, result.detail);
  if (!fit) {
    result.status = SegmentationStatus::kNoPlane;
    return result;
  }
  result.plane_C = fit->plane_C;
  const std::vector<int> above =
      X_WC ? AbovePlane(cloud, candidates, fit->plane_C, params) : OnPlaneArea(cloud, candidates, *fit, params);
  result.timings.plane_s = SecondsSince(t);
  if (!above.empty()) ClusterObjects(cloud, above, X_WC, params, result);
  return result;
}

}  // namespace sortcell::perception
