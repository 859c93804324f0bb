#pragma once
/// @file
/// Named motion phases of the arm and gripper over a CellIo: joint moves and straight TCP lines
/// planned by the robot layer from where the controller holds the arm, chains of them run without
/// stopping in between, gripper opening, closing and squeezing, waiting. Each phase records its time
/// span on the cell's clock; a motion that cannot be planned or a cell that stops under one is
/// reported as `false` with the reason in failure().

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "cell/cell_io.h"
#include "robot/gripper_control.h"
#include "robot/joint_trajectory.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {

/// One phase as it ran, on the cell's clock, and what the gripper's sensors said at its end: a drop
/// shows as the first phase after which nothing is held.
struct PhaseSpan {
  std::string phase;
  double start_s = 0, end_s = 0;
  robot::HoldState hold = robot::HoldState::kMoving;
  double gap_m = 0;  ///< Between the pads.
  /// The least time the arm could take over this phase's path, as fast as its joint speeds and torque
  /// budget allow (robot::TimeOptimalTiming); a phase with the arm standing (the fingers, a wait)
  /// counts as long as it took.
  double bound_s = 0;
};

/// Motions run as one, each next one starting while the one before slows down (robot::BlendMoves):
/// joint moves within `joint_limits` and straight TCP lines, every motion and blend also slowed where
/// the arm's torques need it (robot/torque_limited_motion.h). Each keeps its phase name; the phases
/// meet in the middle of each blend.
class MotionChain {
 public:
  /// What the gripper carries along the chain: it decides how hard blends may accelerate.
  enum class Load {
    kEmptyHanded,  ///< Blends as hard as the torque budget allows.
    kHolding,      ///< Blends within joint_limits' accelerations too: what is held sees no harder jolt.
  };

  MotionChain(const robot::Joints& q_start, Load load,
              const robot::JointMotionLimits& joint_limits = robot::Ur5FastLimits())
      : q_end_(q_start), load_(load), joint_limits_(joint_limits) {}

  /// False (failure() set, the chain unchanged) if the move needs more than the torque budget.
  bool JointMove(const std::string& phase, const robot::Joints& q_goal);
  /// A straight TCP line to X_WT; false (failure() set, the chain unchanged) if it cannot be planned.
  bool Line(const std::string& phase, const Eigen::Isometry3d& X_WT, double speed, double acceleration);

  /// Where the chain leaves the arm.
  const robot::Joints& end() const { return q_end_; }
  const robot::JointTrajectory& trajectory() const { return trajectory_; }
  /// Each phase and its last sample in trajectory(), in order.
  const std::vector<std::pair<std::string, int>>& phase_ends() const { return phase_ends_; }
  const std::string& failure() const { return failure_; }

 private:
  void Add(const std::string& phase, const robot::JointTrajectory& segment);

  robot::Joints q_end_;
  Load load_;
  robot::JointMotionLimits joint_limits_;
  robot::JointTrajectory trajectory_;
  std::vector<std::pair<std::string, int>> phase_ends_;
  std::string failure_;
};

/// What a caller watches while a chain runs.
struct ChainHooks {
  /// After each phase of the chain; false stops the arm there (the rest is not run).
  std::function<bool(const std::string& phase)> after_phase;
  /// Called once, at the first sample (of any phase) where `when(q_commanded)` holds: e.g. the arm is
  /// out of the camera's view and a capture can be taken while it moves on.
  std::function<bool(const robot::Joints& q)> when;
  std::function<void()> then;
  /// Called every 20 ms of motion with the phase running (the arm moves on meanwhile): e.g. the grip
  /// watched for slipping.
  std::function<void(const std::string& phase)> watch;
};

class MotionSequencer {
 public:
  explicit MotionSequencer(CellIo& io) : io_(io) {}

  /// A joint-space move from where the controller holds the arm, at the UR5's fast limits.
  bool MoveJ(const std::string& name, const robot::Joints& q_goal);
  /// A straight TCP line at `speed` and `acceleration`; false with failure() set if it cannot be
  /// planned or run.
  bool MoveL(const std::string& name, const Eigen::Isometry3d& X_WT, double speed, double acceleration);
  /// A chain planned from where the controller holds the arm now; false with failure() set if the
  /// chain could not be planned, a hook stopped it (then stopped() is true) or the cell faulted.
  bool Run(const MotionChain& chain, const ChainHooks& hooks = {});
  /// Sets the fingers moving to `gap` without waiting for them (they open while the arm moves).
  void StartFingers(double gap);
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
  /// Whether the last Run was stopped by one of its hooks.
  bool stopped() const { return stopped_; }

 private:
  /// Runs `action` as phase `name`; `bound_s`: the arm's least time for it (none: the arm stands).
  bool Phase(const std::string& name, const std::function<MotionResult()>& action,
             std::optional<double> bound_s = std::nullopt);
  MotionResult CloseAndSqueeze(const std::string& name);
  MotionResult MoveFingers(const std::string& name, double half_gap);

  CellIo& io_;
  std::vector<PhaseSpan> phases_;
  std::string failure_;
  bool faulted_ = false;
  bool stopped_ = false;
};

}  // namespace sortcell::cell
