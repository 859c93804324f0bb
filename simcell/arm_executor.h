#pragma once
/// @file
/// Runs the simulated arm and gripper under the robot layer's control: trajectories tracked by the
/// joint controller at a fixed control rate, finger servo targets, holding still. It reads only
/// the controller's sensors (sim::ArmIo); simulated time and an optional review video advance with
/// every physics step.

#include <functional>
#include <string>

#include "robot/gripper_control.h"
#include "robot/joint_controller.h"
#include "robot/joint_trajectory.h"
#include "robot/ur5_dynamics.h"
#include "sim/arm_io.h"
#include "sim/model.h"
#include "sim/video_recorder.h"

namespace sortcell::simcell {

class ArmExecutor {
 public:
  /// The control period must be a whole number of physics timesteps.
  /// @throws std::invalid_argument otherwise, or if the model lacks the arm or gripper.
  ArmExecutor(const sim::Model& model, sim::Data& data, sim::VideoRecorder* video, double control_period);

  /// Puts the arm at q and the fingers at `half_gap`, at rest, and holds them there from now on.
  void Reset(const robot::Joints& q, double half_gap);

  /// Tracks the trajectory from its first sample (which should be where the arm is). Returns kOk, or
  /// the simulator's divergence/warning status (then it stops early).
  sim::StepStatus Follow(const robot::JointTrajectory& trajectory);
  /// Holds the last reference for `seconds`.
  sim::StepStatus Wait(double seconds);
  /// Holds the last reference for up to `max_seconds`, ending early once `done()` is true (checked
  /// after every control period).
  sim::StepStatus HoldUntil(double max_seconds, const std::function<bool()>& done);
  /// Sets the finger servos' position targets (half gaps, m).
  void SetFingerTargets(double left_half_gap, double right_half_gap);

  /// The encoders.
  robot::Joints JointPositions() const;
  /// Where the controller currently holds the arm (the last reference): motions are planned from
  /// here, so the reference never jumps.
  const robot::Joints& ReferenceJoints() const { return q_hold_; }
  robot::GripperSensors Gripper() const;
  const robot::TrackingStats& tracking() const { return controller_.stats(); }
  double time() const { return data_->time; }
  /// Wall time spent in physics steps so far (s), for profiles.
  double step_wall_s() const { return step_wall_s_; }
  /// Mean contacts and constraint rows per physics step so far (what the collision and constraint
  /// stages of a step work on), for profiles.
  double mean_contacts() const { return steps_ > 0 ? static_cast<double>(contacts_sum_) / steps_ : 0.0; }
  double mean_constraint_rows() const { return steps_ > 0 ? static_cast<double>(constraint_rows_sum_) / steps_ : 0.0; }
  /// Caption for the video (the current phase).
  void SetPhase(const std::string& phase);

 private:
  sim::StepStatus ControlStep(const robot::Joints& q_ref, const robot::Joints& qd_ref, const robot::Joints& qdd_ref);

  const sim::Model& model_;
  sim::Data& data_;
  sim::VideoRecorder* video_;
  sim::ArmIo io_;
  robot::JointController controller_;
  /// The controller's model of the arm and its gripper (not of what the gripper holds: the feedback
  /// takes that), for the feed-forward.
  robot::Ur5Dynamics arm_model_{robot::GripperMassProperties()};
  int substeps_;
  robot::Joints q_hold_ = robot::Joints::Zero();
  double step_wall_s_ = 0;
  long steps_ = 0, contacts_sum_ = 0, constraint_rows_sum_ = 0;
};

}  // namespace sortcell::simcell
