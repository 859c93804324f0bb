#pragma once
/// @file
/// Joint-space trajectories sampled at the control period, and the planners that make them:
/// synchronised point-to-point moves (URScript movej-like: all joints start and stop together) and
/// straight-line Cartesian TCP moves through IK (movel-like), both time-scaled by a smooth profile
/// whose acceleration ramps up and down as a sine (continuous acceleration, bounded jerk: a held object
/// sees no jolt). Every segment starts and ends at rest; BlendMoves joins two of them without stopping
/// by starting the second while the first slows down.

#include <functional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "robot/ik_selection.h"
#include "robot/ur5_kinematics.h"
#include "robot/ur5_limits.h"

namespace sortcell::robot {

/// Uniform samples q(k dt), qd(k dt), qdd(k dt), k = 0 .. size-1.
struct JointTrajectory {
  double dt = 0.002;
  std::vector<Joints> q, qd, qdd;
  /// Time it spends speeding up from rest at its start and slowing down to rest at its end (s): the
  /// windows a blend may overlap with the segments before and after it.
  double accel_s = 0, decel_s = 0;

  int size() const { return static_cast<int>(q.size()); }
  double duration() const { return q.empty() ? 0.0 : dt * (size() - 1); }
  /// Appends `other` (same dt), dropping its first sample when it repeats this one's last.
  /// @throws std::invalid_argument if dt differs or the joints do not join (|dq| > 1e-6 rad).
  void Append(const JointTrajectory& other);
};

/// Smooth time scaling s(t) of a move of length `distance`: from rest to the peak speed `speed` with an
/// acceleration a(t) = A sin^2(pi t / T_ramp) that peaks at `acceleration` = A, cruise, and the mirror
/// image down to rest (when the distance is too short, the peak speed is lowered and there is no
/// cruise). Acceleration is continuous, so the controller's torques never step.
struct SmoothProfile {
  SmoothProfile(double distance, double speed, double acceleration);
  double duration() const { return duration_; }
  /// Time spent speeding up (= slowing down) (s).
  double ramp_time() const { return t_ramp_; }
  /// Position, velocity, acceleration along the path at time t (clamped to [0, duration]).
  void Evaluate(double t, double& s, double& sd, double& sdd) const;

 private:
  void Ramp(double t, double& s, double& sd, double& sdd) const;
  double distance_, speed_, t_ramp_, duration_;
};

/// Per-joint limits of a joint-space motion: speeds (rad/s) and accelerations (rad/s^2).
struct JointMotionLimits {
  Joints speed = Joints::Constant(kMovejSpeed);
  Joints acceleration = Joints::Constant(kMovejAcceleration);
};

/// The cell's fast joint moves: pi rad/s on every joint and the accelerations the torque limits allow
/// with the gripper and a payload (robot/ur5_limits.h).
inline JointMotionLimits Ur5FastLimits() { return {Joints::Constant(kUr5MaxJointSpeed), Ur5AccelerationLimits()}; }

/// A synchronised joint move from q_start to q_goal: the joint with the largest travel runs at
/// `speed` and `acceleration`, the others proportionally slower (a straight line in joint space).
/// @throws std::invalid_argument for speed outside (0, pi] rad/s, acceleration <= 0, dt <= 0, or
///         non-finite joints.
JointTrajectory PlanJointMove(const Joints& q_start, const Joints& q_goal, double speed = kMovejSpeed,
                              double acceleration = kMovejAcceleration, double dt = 0.002);
/// The same with per-joint limits: the move takes as long as its most limited joint needs.
/// @throws std::invalid_argument for a speed outside (0, pi], an acceleration <= 0, dt <= 0, or
///         non-finite joints.
JointTrajectory PlanJointMove(const Joints& q_start, const Joints& q_goal, const JointMotionLimits& limits,
                              double dt = 0.002);

/// Whether the arm can follow one sample (q, qd, qdd): e.g. TorqueBudget::Fits.
using SampleCheck = std::function<bool(const Joints& q, const Joints& qd, const Joints& qdd)>;

/// `first` then `second` without stopping in between: `second` starts while `first` is still slowing
/// down, for half the shorter of first.decel_s and second.accel_s, and the two motions add up over
/// that window (so the path cuts the corner at the seam by the little distance covered in it, about
/// 15 % of the ramps'). Where the sum
/// would break a limit (a joint faster or accelerating harder than both segments and `limits` allow),
/// the overlap is halved until it does not, down to a plain Append. `seam` (optional) receives the
/// sample index in the middle of the overlap, where a caller may split the result by phase. With
/// `fits` given, a blended sample's accelerations are judged by it (the torques they need) instead of
/// by limits.acceleration.
/// @throws std::invalid_argument if dt differs or the segments do not join.
JointTrajectory BlendMoves(const JointTrajectory& first, const JointTrajectory& second, const JointMotionLimits& limits,
                           int* seam = nullptr, const SampleCheck& fits = {});

enum class CartesianPlanStatus { kOk, kUnreachable, kTooFast, kOverTorqueBudget };

struct CartesianPlan {
  CartesianPlanStatus status = CartesianPlanStatus::kUnreachable;
  std::string detail;  ///< Why it failed, for reports.
  JointTrajectory trajectory;
};

/// A straight TCP line from FK(q_start) to X_BT_goal (orientation slerped), smoothly time-scaled in arc
/// length (m) with `speed` and `acceleration`, solved by IK at every sample, each solution the nearest
/// valid one to the previous sample. Fails (as a status) if some sample is unreachable or needs a
/// joint faster than pi rad/s (a singularity on the way).
/// @throws std::invalid_argument for speed <= 0 or acceleration <= 0.
CartesianPlan PlanCartesianLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed = kMovelSpeed,
                                double acceleration = kMovelAcceleration, double dt = 0.002,
                                const SelectionOptions& selection = {});

}  // namespace sortcell::robot
