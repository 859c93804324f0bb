#pragma once
/// @file
/// The camera's pose from points seen by both the camera and the arm's encoders: the rigid X_WC that
/// best maps the camera-frame sightings p_C onto the forward-kinematics positions p_W (Umeyama 1991,
/// Eigen::umeyama without scale), refitted without the sightings that disagree with the rest (a
/// marker partly hidden or caught mid-swing).

#include <optional>
#include <vector>

#include <Eigen/Geometry>

namespace sortcell::cell {

struct HandEyeFitParams {
  /// A sighting is an outlier beyond this many robust sigmas (1.4826 x the median residual) of the
  /// fit, or beyond min_outlier_m, whichever is larger.
  double outlier_sigmas = 3.0;
  double min_outlier_m = 0.002;
  int min_inliers = 6;
  /// The inliers must spread over at least this much in two directions (m, RMS about their mean):
  /// points near a line leave the rotation about it free.
  double min_spread_m = 0.03;
};

struct HandEyeFit {
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  std::vector<bool> inlier;        ///< Per sighting.
  std::vector<double> residual_m;  ///< |X_WC p_C - p_W| per sighting (m), outliers included.
  int inliers = 0;
  double rms_m = 0, max_m = 0;  ///< Over the inliers (m).
};

/// The fit, or nullopt when fewer than min_inliers sightings agree or they do not spread out.
/// @throws std::invalid_argument when p_W and p_C differ in size.
std::optional<HandEyeFit> FitCameraPose(const std::vector<Eigen::Vector3d>& p_W,
                                        const std::vector<Eigen::Vector3d>& p_C, const HandEyeFitParams& params = {});

}  // namespace sortcell::cell
