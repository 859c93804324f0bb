#include "sim/camera_model.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace sortcell::sim {

void CheckCameraId(const Model& model, int camera_id) {
  if (camera_id < 0 || camera_id >= model->ncam) {
    throw std::invalid_argument("scene '" + model.source() + "': camera id " + std::to_string(camera_id) +
                                " does not exist");
  }
}

CameraIntrinsics IntrinsicsOf(const Model& model, int camera_id, int width, int height) {
  CheckCameraId(model, camera_id);
  const double fovy = model->cam_fovy[camera_id] * M_PI / 180.0;  // MJCF stores fovy in degrees.
  CameraIntrinsics k;
  k.width = width;
  k.height = height;
  k.fy = 0.5 * height / std::tan(0.5 * fovy);
  k.fx = k.fy;
  k.cx = 0.5 * width - 0.5;
  k.cy = 0.5 * height - 0.5;
  return k;
}

Eigen::Isometry3d CameraPoseInWorld(const Model& model, const Data& data, int camera_id) {
  CheckCameraId(model, camera_id);
  Eigen::Matrix3d R_WM;  // MuJoCo camera frame M in world; cam_xmat is row-major.
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) R_WM(r, c) = data->cam_xmat[9 * camera_id + 3 * r + c];
  }
  const Eigen::Matrix3d R_MC = Eigen::Vector3d(1, -1, -1).asDiagonal();
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() = R_WM * R_MC;
  X_WC.translation() = Eigen::Map<const Eigen::Vector3d>(data->cam_xpos + 3 * camera_id);
  return X_WC;
}

DepthRange DepthRangeOf(const Model& model) {
  return {model->vis.map.znear * model->stat.extent, model->vis.map.zfar * model->stat.extent};
}

cv::Mat LinearizeDepth(const cv::Mat& depth_buffer, const DepthRange& range) {
  if (depth_buffer.type() != CV_32FC1) throw std::invalid_argument("LinearizeDepth: expected a CV_32FC1 buffer");
  cv::Mat depth(depth_buffer.size(), CV_32FC1);
  const double ratio = 1.0 - range.near / range.far;
  for (int r = 0; r < depth.rows; ++r) {
    const float* d = depth_buffer.ptr<float>(r);
    float* z = depth.ptr<float>(r);
    for (int c = 0; c < depth.cols; ++c) {
      z[c] = d[c] >= 1.0f ? std::numeric_limits<float>::quiet_NaN()
                          : static_cast<float>(range.near / (1.0 - d[c] * ratio));
    }
  }
  return depth;
}

}  // namespace sortcell::sim
