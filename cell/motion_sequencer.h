#pragma once
/// @file
/// Named motion phases of the arm and gripper over a CellIo: joint moves and straight TCP lines
/// planned by the robot layer from where the controller holds the arm, gripper opening, closing and
/// squeezing, waiting. Each phase records its time span on the cell's clock; a motion that cannot be
/// planned or a cell that stops under one is reported as `false` with the reason in failure().

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cell/cell_io.h"
#include "robot/gripper_control.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

/// One phase as it ran, on the cell's clock.
struct PhaseSpan {
  std::string phase;
  double start_s = 0, end_s = 0;
};

class MotionSequencer {
 public:
  explicit MotionSequencer(CellIo& io) : io_(io) {}

  /// A joint-space move from where the controller holds the arm.
  bool MoveJ(const std::string& name, const robot::Joints& q_goal);
  /// A straight TCP line at `speed`; false with failure() set if it cannot be planned or run.
  bool MoveL(const std::string& name, const Eigen::Isometry3d& X_WT, double speed);
  /// Opens or closes both fingers to `gap` and waits until they stop (at most 1.5 s).
  bool Gripper(const std::string& name, double gap);
  /// Closes on an object and, if something is held, squeezes it with robot::kDefaultGripForce per
  /// finger, unsaturated (robot::SqueezeTarget).
  bool Grasp(const std::string& name);
  /// Holds still for `seconds`.
  bool Wait(const std::string& name, double seconds);

  /// What the gripper's sensors say now.
  robot::HoldState Hold() const { return robot::DetectHold(io_.ReadGripper()); }
  CellIo& io() { return io_; }
  /// Every phase run so far.
  const std::vector<PhaseSpan>& phases() const { return phases_; }
  /// Why the last step that returned false failed.
  const std::string& failure() const { return failure_; }
  /// Whether the cell stopped under a motion.
  bool faulted() const { return faulted_; }

 private:
  bool Phase(const std::string& name, const std::function<MotionResult()>& action);
  MotionResult CloseAndSqueeze(const std::string& name);
  MotionResult MoveFingers(const std::string& name, double half_gap);

  CellIo& io_;
  std::vector<PhaseSpan> phases_;
  std::string failure_;
  bool faulted_ = false;
};

}  // namespace sortcell::cell
