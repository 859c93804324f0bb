#pragma once
/// @file
/// The sorting cell as its brain sees it: a camera that gives organized clouds, the arm's encoders and
/// controller, the gripper's sensors and finger servos, and a clock. Nothing else: no object poses, no
/// identities, no labels. The simulated cell (simcell/sim_cell.h) implements it over MuJoCo; the
/// policy's unit tests implement it with scripted clouds and sensor readings.

#include <functional>
#include <string>
#include <string_view>

#include "perception/cloud.h"
#include "robot/gripper_control.h"
#include "robot/joint_trajectory.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

/// How a motion of the cell ended: kFault when the cell stopped under it (the simulation diverged;
/// on a real cell a protective stop). A fault ends the episode.
enum class MotionStatus { kOk, kFault };

struct MotionResult {
  MotionStatus status = MotionStatus::kOk;
  std::string detail;  ///< Why it faulted; empty when ok.
  bool ok() const { return status == MotionStatus::kOk; }
};

class CellIo {
 public:
  virtual ~CellIo() = default;

  /// One capture of the cell's depth camera: an organized cloud in its optical frame, NaN where it
  /// gives no depth.
  virtual perception::Cloud::Ptr Capture() = 0;
  /// The joint encoders.
  virtual robot::Joints ReadJoints() const = 0;
  /// Where the arm's controller holds it now (its last reference): motions are planned from here,
  /// so the reference never jumps.
  virtual robot::Joints CommandedJoints() const = 0;
  /// The gripper's finger encoders and pad force sensors.
  virtual robot::GripperSensors ReadGripper() const = 0;

  /// Tracks a joint trajectory (a joint move, or a Cartesian line solved to joints) from its first
  /// sample, which should be CommandedJoints(); afterwards the controller holds its last sample.
  /// `phase` names the motion in logs and the review video.
  virtual MotionResult Follow(std::string_view phase, const robot::JointTrajectory& trajectory) = 0;
  /// Sets the finger servos' position targets (half gaps, m). The fingers move while the cell runs.
  virtual void CommandFingers(double left_half_gap, double right_half_gap) = 0;
  /// Holds the arm where it is for up to `max_seconds`, ending early once `done()` is true (checked
  /// after every control period).
  virtual MotionResult HoldUntil(std::string_view phase, double max_seconds, const std::function<bool()>& done) = 0;
  /// Holds the arm where it is for `seconds` (a whole number of control periods).
  virtual MotionResult Wait(std::string_view phase, double seconds) = 0;
  /// The cell's clock (s).
  virtual double Now() const = 0;
};

}  // namespace sortcell::cell
