#include "cell/hand_eye_calibration.h"

#include <algorithm>
#include <stdexcept>

#include "cell/motion_sequencer.h"
#include "common/enum_names.h"
#include "perception/cloud_pinhole.h"
#include "robot/gripper_geometry.h"
#include "robot/ik_selection.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {
namespace {

const Eigen::Vector3d kMarkerInFlange(robot::kMarkerFaceX, 0, robot::kMarkerCentreZ);

// The flange pose that puts the marker's centre at p_W_marker facing the camera at p_W_camera: the
// plate's normal (x_F) at the camera, the tool (z_F) as near straight down as that allows.
Eigen::Isometry3d FlangeShowing(const Eigen::Vector3d& p_W_marker, const Eigen::Vector3d& p_W_camera) {
  const Eigen::Vector3d x = (p_W_camera - p_W_marker).normalized();
  const Eigen::Vector3d down(0, 0, -1);
  Eigen::Vector3d z = down - down.dot(x) * x;
  // A camera straight above the marker leaves "down" along x: any tool direction across it will do.
  z = z.norm() > 1e-6 ? z.normalized() : Eigen::Vector3d(x.unitOrthogonal());
  Eigen::Matrix3d R_WF;
  R_WF << x, z.cross(x), z;
  Eigen::Isometry3d X_WF = Eigen::Isometry3d::Identity();
  X_WF.linear() = R_WF;
  X_WF.translation() = p_W_marker - R_WF * kMarkerInFlange;
  return X_WF;
}

// One capture with the marker held still: where the encoders put it and where the camera sees it
// (not seen: the marker not found, or a capture too empty to read the camera's pinhole from).
MarkerShowing Show(CellIo& io, std::optional<perception::Pinhole>& pinhole) {
  MarkerShowing showing;
  const perception::Cloud::Ptr cloud = io.Capture();
  showing.q = io.ReadJoints();
  showing.p_W_marker = robot::FlangePose(showing.q) * kMarkerInFlange;
  if (!pinhole) {
    try {
      pinhole = perception::FitPinhole(*cloud);
    } catch (const std::invalid_argument&) {
      return showing;  // Try the next capture.
    }
  }
  showing.seen = perception::FindMarker(*cloud, *pinhole, robot::kMarkerId);
  return showing;
}

}  // namespace

constexpr EnumNames<HandEyeStatus, 3> kHandEyeStatusNames{{{HandEyeStatus::kOk, "ok"},
                                                           {HandEyeStatus::kTooFewSightings, "too_few_sightings"},
                                                           {HandEyeStatus::kFault, "fault"}}};

const char* ToString(HandEyeStatus status) { return NameOf(kHandEyeStatusNames, status); }

std::vector<std::optional<robot::Joints>> MarkerShowingJoints(const Eigen::Isometry3d& X_WC_prior,
                                                              const robot::Joints& q_start,
                                                              const HandEyeCalibrationParams& params) {
  std::vector<std::optional<robot::Joints>> joints;
  robot::Joints q = q_start;  // NOLINT(performance-unnecessary-copy-initialization): follows the arm (below)
  // Row by row, each row the other way: short moves between neighbouring places.
  int row = 0;
  for (double z : params.zs) {
    for (double x : params.xs) {
      std::vector<double> ys = params.ys;
      if (row++ % 2) std::reverse(ys.begin(), ys.end());
      for (double y : ys) {
        const Eigen::Isometry3d X_WF = FlangeShowing({x, y, z}, X_WC_prior.translation());
        const auto pick = robot::SelectNearest(robot::SolveIk(X_WF, q(5)), q);
        joints.push_back(pick ? std::optional<robot::Joints>(pick->q) : std::nullopt);
        if (pick) q = pick->q;
      }
    }
  }
  return joints;
}

HandEyeCalibration CalibrateHandEye(CellIo& io, const CellLayout& layout, const Eigen::Isometry3d& X_WC_prior,
                                    const HandEyeCalibrationParams& params) {
  HandEyeCalibration result;
  result.X_WC_prior = result.X_WC = X_WC_prior;
  result.start_s = io.Now();
  MotionSequencer motions(io);
  std::optional<perception::Pinhole> pinhole;
  std::vector<Eigen::Vector3d> p_W, p_C;
  std::vector<size_t> seen_at;  // Showing index of each pair.
  for (const auto& q_goal : MarkerShowingJoints(X_WC_prior, io.CommandedJoints(), params)) {
    MarkerShowing showing;
    MotionChain move(io.CommandedJoints(), MotionChain::Load::kEmptyHanded);
    // A place the arm cannot reach, or reach within its torques from the last one, is left out.
    showing.reachable = q_goal.has_value() && move.JointMove("calibrate", *q_goal);
    if (showing.reachable) {
      if (!motions.Run(move) || !motions.Wait("calibrate", params.settle_s)) {
        result.status = HandEyeStatus::kFault;  // The cell stopped under the motion: nothing more to do.
        result.detail = motions.failure();
        result.end_s = io.Now();
        return result;
      }
      showing = Show(io, pinhole);
      if (showing.seen) {
        p_W.push_back(showing.p_W_marker);
        p_C.push_back(showing.seen->p_C_centre);
        seen_at.push_back(result.showings.size());
      }
    }
    result.showings.push_back(showing);
  }
  if (!motions.MoveJ("calibrate", layout.q_observe)) {
    result.status = HandEyeStatus::kFault;
    result.detail = motions.failure();
  }
  result.end_s = io.Now();
  result.sightings = static_cast<int>(p_W.size());
  const auto fit = FitCameraPose(p_W, p_C, params.fit);
  if (!fit) {
    if (result.status == HandEyeStatus::kOk) {
      result.status = HandEyeStatus::kTooFewSightings;
      result.detail =
          std::to_string(result.sightings) + " sightings of the marker, too few agree or they do not spread out";
    }
    return result;
  }
  for (size_t k = 0; k < seen_at.size(); ++k) {
    result.showings[seen_at[k]].inlier = fit->inlier[k];
    result.showings[seen_at[k]].residual_m = fit->residual_m[k];
  }
  result.inliers = fit->inliers;
  result.rms_residual_m = fit->rms_m;
  result.max_residual_m = fit->max_m;
  if (result.status == HandEyeStatus::kOk) result.X_WC = fit->X_WC;
  return result;
}

}  // namespace sortcell::cell
