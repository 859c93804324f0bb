#pragma once
/// @file
/// Object segmentation of one organized Kinect cloud (paper section 2.1): invalid points out, region
/// of interest (world workspace box and/or background subtraction), RANSAC removal of the supporting
/// plane and of everything below it, voxel downsampling, Euclidean clustering.

#include <Eigen/Geometry>

#include <optional>
#include <string>
#include <vector>

#include "common/enum_names.h"
#include "perception/cloud.h"
#include "perception/convex_segmentation.h"

namespace sortcell::perception {

/// Parameters of the segmentation. Defaults suit a Kinect v1 0.8-1.5 m from a table.
struct SegmentationParams {
  /// Workspace box in the world frame, used when the camera pose is known.
  Eigen::Vector3d workspace_min_W{0.28, -0.30, -0.05};
  Eigen::Vector3d workspace_max_W{0.72, 0.30, 0.40};
  /// Background subtraction: a pixel is background when its depth is within this of the empty
  /// cell's depth at the same pixel (plus 3 sigma of the Kinect's axial noise at that depth).
  double background_tolerance_m = 0.010;
  /// RANSAC plane: inlier distance, iterations, points sampled (every `plane_stride`-th pixel in both
  /// directions), and, with a camera pose, the largest tilt of the plane from horizontal.
  double plane_distance_m = 0.008;
  int plane_iterations = 200;
  int plane_stride = 3;
  double plane_max_tilt_rad = 0.26;
  int min_plane_points = 200;  ///< Fewer sampled inliers: no supporting plane (SegmentationStatus::kNoPlane).
  /// Points closer to the plane than this (or below it) belong to it.
  double above_plane_m = 0.010;
  /// Without a camera pose: objects are what stands on the plane's inlier area up to this height.
  double max_object_height_m = 0.5;
  double voxel_leaf_m = 0.005;  ///< Voxel grid leaf for clustering.
  /// How the voxels are clustered: by Euclidean distance (touching objects merge), or into convex
  /// clusters (perception/convex_segmentation.h: touching objects come apart at concave creases).
  enum class Clustering { kEuclidean, kConvex } clustering = Clustering::kEuclidean;
  /// Their spellings ("euclidean", "convex": `sortcell segment --clustering`).
  static constexpr EnumNames<Clustering, 2> kClusteringNames{
      {{Clustering::kEuclidean, "euclidean"}, {Clustering::kConvex, "convex"}}};
  ConvexClusteringParams convex;
  double cluster_tolerance_m = 0.015;  ///< Euclidean clustering distance (3 voxels).
  int min_cluster_voxels = 25;
  int max_cluster_voxels = 20000;
};

/// One segmented object.
struct Segment {
  std::vector<int>
      indices;         ///< Pixels (row * width + col) of an organized input cloud; point indices of an unorganized one.
  Cloud::Ptr cloud_C;  ///< Those points, full resolution, camera optical frame.
  /// Centroid, bounding box and principal axes (columns, largest variance first) in the output frame:
  /// the world with a camera pose, else the camera frame.
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_min = Eigen::Vector3d::Zero();
  Eigen::Vector3d bbox_max = Eigen::Vector3d::Zero();
  Eigen::Matrix3d principal_axes = Eigen::Matrix3d::Identity();
  int voxels = 0;  ///< Size of the cluster after voxel downsampling.
};

/// Wall time of each stage in seconds.
struct SegmentationTimings {
  double crop_s = 0, plane_s = 0, voxel_s = 0, cluster_s = 0;
};

/// Expected ways a capture cannot be segmented (a status, not an error: e.g. the camera sees no table).
enum class SegmentationStatus {
  kOk,
  kNoValidPoints,  ///< No point with depth inside the region of interest (all NaN, or all outside the box).
  kNoPlane,        ///< No supporting plane (table or floor) found.
};

/// "ok", "no_valid_points", "no_plane".
const char* ToString(SegmentationStatus status);

struct SegmentationResult {
  SegmentationStatus status = SegmentationStatus::kOk;
  std::string detail;        ///< Why, for a person, when not ok (numbers included); empty when ok.
  bool world_frame = false;  ///< Whether centroids and boxes are in the world (camera pose given).
  Eigen::Vector4d plane_C =
      Eigen::Vector4d::Zero();    ///< Supporting plane n.p + d = 0, camera frame, n towards the camera.
  std::vector<Segment> segments;  ///< Largest first; empty when not ok.
  SegmentationTimings timings;
};

/// Segments `cloud` (camera optical frame, NaN where no depth; organized as a depth camera gives it, or
/// unorganized: then only background subtraction, which compares pixels, is not available, and the
/// plane is fitted on every plane_stride^2-th point instead of a pixel grid). A capture without a valid
/// point in the region of interest or without a supporting plane is an expected outcome: the result's
/// status says which (kNoValidPoints, kNoPlane), `detail` says why, and `segments` is empty.
/// @param X_WC      Camera pose in the world: enables the workspace box and world-frame outputs.
/// @param background The empty cell seen from the same camera (organized, same size), or null.
/// @throws std::invalid_argument naming the problem for misuse: an empty cloud, a cloud whose size is not
///         its width x height, a background with an unorganized cloud or of another size.
SegmentationResult SegmentObjects(const Cloud& cloud, const std::optional<Eigen::Isometry3d>& X_WC,
                                  const Cloud* background, const SegmentationParams& params = {});

}  // namespace sortcell::perception
