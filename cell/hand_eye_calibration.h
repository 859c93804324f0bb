#pragma once
/// @file
/// Hand-eye self-calibration of the cell's camera from its own sensors: the arm shows the marker on
/// its gripper (robot/gripper_geometry.h, kMarker*) to the camera at a grid of places in the
/// workspace; the encoders' forward kinematics say where the marker is in the world, the camera
/// where it is in its own frame (perception::FindMarker); X_WC is fitted to the pairs
/// (cell::FitCameraPose). Only the prior pose is needed to aim the marker at the camera.

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cell/cell_io.h"
#include "cell/cell_layout.h"
#include "cell/hand_eye_fit.h"
#include "perception/marker_sighting.h"

namespace sortcell::cell {

struct HandEyeCalibrationParams {
  /// The marker's centre is shown at every (x, y, z) of these (world, m): inside the Kinect's view of
  /// the table, its plate turned to face the camera, high enough that the finger tips clear the table.
  std::vector<double> xs{0.42, 0.54, 0.66}, ys{-0.20, 0.0, 0.20}, zs{0.17, 0.29};
  /// Held still this long at each place before the capture (s): the arm's vibration dies out.
  double settle_s = 0.02;
  HandEyeFitParams fit;
};

enum class HandEyeStatus {
  kOk,
  kTooFewSightings,  ///< Fewer sightings agreed than the fit needs: the prior pose is kept.
  kFault,            ///< The cell stopped under a motion.
};
const char* ToString(HandEyeStatus status);

/// One place the marker was shown at.
struct MarkerShowing {
  robot::Joints q = robot::Joints::Zero();               ///< The encoders at the capture.
  Eigen::Vector3d p_W_marker = Eigen::Vector3d::Zero();  ///< Where forward kinematics puts the marker.
  std::optional<perception::MarkerSighting> seen;        ///< Empty: not found (or the place unreachable).
  bool reachable = true;
  bool inlier = false;
  double residual_m = -1;  ///< |X_WC p_C - p_W| of the fit (m); -1 where not seen.
};

struct HandEyeCalibration {
  HandEyeStatus status = HandEyeStatus::kOk;
  Eigen::Isometry3d X_WC_prior = Eigen::Isometry3d::Identity();
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();  ///< The fit; the prior unless kOk.
  std::vector<MarkerShowing> showings;
  int sightings = 0, inliers = 0;
  double rms_residual_m = 0, max_residual_m = 0;
  double start_s = 0, end_s = 0;  ///< On the cell's clock.
  std::string detail;             ///< Why it is not kOk.
};

/// The flange poses that show the marker at each of params' places to a camera at X_WC_prior, and the
/// joints that reach each from the one before (the first from q_start); nullopt where none does.
std::vector<std::optional<robot::Joints>> MarkerShowingJoints(const Eigen::Isometry3d& X_WC_prior,
                                                              const robot::Joints& q_start,
                                                              const HandEyeCalibrationParams& params);

/// Runs the calibration on the cell: from where the arm is, through every place, back to the layout's
/// observe pose. Nothing may stand in the workspace (the arm sweeps it).
HandEyeCalibration CalibrateHandEye(CellIo& io, const CellLayout& layout, const Eigen::Isometry3d& X_WC_prior,
                                    const HandEyeCalibrationParams& params = {});

}  // namespace sortcell::cell
