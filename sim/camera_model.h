#pragma once
/// @file
/// Pinhole model of a MuJoCo fixed camera in the optical convention (x right, y down, z forward),
/// and the MuJoCo 2.2 depth-buffer conversion.

#include <Eigen/Geometry>
#include <opencv2/core/mat.hpp>

#include "sim/model.h"

namespace sortcell::sim {

/// Pinhole intrinsics in pixels, pixel centres at integer coordinates (OpenCV/PCL convention).
struct CameraIntrinsics {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  int width = 0, height = 0;
};

/// @throws std::invalid_argument naming the scene if `camera_id` is not a camera of the model.
void CheckCameraId(const Model& model, int camera_id);

/// Intrinsics of camera `camera_id` rendered at width x height: fy = (H/2)/tan(fovy/2), fx = fy
/// (MuJoCo pixels are square), principal point at the image centre (W/2 - 0.5, H/2 - 0.5).
CameraIntrinsics IntrinsicsOf(const Model& model, int camera_id, int width, int height);

/// Pose of the camera's optical frame C in the world, X_WC. MuJoCo cameras look along their -z with
/// +y up; the optical frame is that frame turned by pi about x. This is the one place it is converted.
Eigen::Isometry3d CameraPoseInWorld(const Model& model, const Data& data, int camera_id);

/// Clip planes of the model's depth buffer in metres: near = znear * extent, far = zfar * extent.
struct DepthRange {
  double near = 0, far = 0;
};
DepthRange DepthRangeOf(const Model& model);

/// Planar (optical-axis) depth in metres from MuJoCo 2.2's non-linear depth buffer d in [0, 1]:
/// z = near / (1 - d (1 - near/far)). Pixels where nothing was drawn (d = 1) become NaN.
cv::Mat LinearizeDepth(const cv::Mat& depth_buffer, const DepthRange& range);

}  // namespace sortcell::sim
