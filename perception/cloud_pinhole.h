#pragma once
/// @file
/// The pinhole an organized cloud was taken through, as its points show it: each valid point (x, y, z)
/// at pixel (u, v) satisfies u = fx x/z + cx, v = fy y/z + cy. Sub-pixel image measurements (a marker's
/// corners) become rays with it, without a separate intrinsics file.

#include <Eigen/Core>

#include "perception/cloud.h"

namespace sortcell::perception {

struct Pinhole {
  double fx = 0, fy = 0, cx = 0, cy = 0;
  /// The ray through pixel (u, v) in the camera frame, z = 1.
  Eigen::Vector3d Ray(const Eigen::Vector2d& uv) const { return {(uv.x() - cx) / fx, (uv.y() - cy) / fy, 1.0}; }
};

/// Least squares over the cloud's valid points (every `stride`-th pixel; lateral depth noise averages out).
/// @throws std::invalid_argument for an unorganized cloud or one with fewer than 100 valid points
///         spread over less than a tenth of its width or height.
Pinhole FitPinhole(const Cloud& cloud, int stride = 4);

}  // namespace sortcell::perception
