#pragma once
/// @file
/// camera.json, as `sortcell capture` writes it: intrinsics and X_WC, the optical frame in the world.

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

#include "sim/kinect_camera.h"

namespace sortcell::files {

/// {"camera", "fx", "fy", "cx", "cy", "width", "height", "frame", "X_WC": 4x4 rows}.
nlohmann::json CameraJson(const std::string& camera, const sim::KinectFrame& frame, const Eigen::Isometry3d& X_WC);

/// X_WC from a camera.json.
/// @throws std::invalid_argument "camera file '<file>': <what>" for a missing or malformed file, a
///         missing "X_WC", or one that is not a 4x4 rigid transform.
Eigen::Isometry3d LoadCameraPose(const std::filesystem::path& file);

}  // namespace sortcell::files
