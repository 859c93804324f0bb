#pragma once
/// @file
/// Joint-space trajectories sampled at the control period, and the planners that make them:
/// synchronised point-to-point moves (URScript movej-like: trapezoidal velocity, all joints start and
/// stop together) and straight-line Cartesian TCP moves through IK (movel-like). Every segment starts
/// and ends at rest, so velocity is continuous everywhere.

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

  int size() const { return static_cast<int>(q.size()); }
  double duration() const { return q.empty() ? 0.0 : dt * (size() - 1); }
  /// Appends `other` (same dt), dropping its first sample when it repeats this one's last.
  /// @throws std::invalid_argument if dt differs or the joints do not join (|dq| > 1e-6 rad).
  void Append(const JointTrajectory& other);
};

/// Trapezoidal time scaling s(t) of a move of length `distance` with peak speed `speed` and
/// acceleration `acceleration` (a triangle when the distance is too short to reach the speed).
struct TrapezoidProfile {
  TrapezoidProfile(double distance, double speed, double acceleration);
  double duration() const { return duration_; }
  /// Position, velocity, acceleration along the path at time t (clamped to [0, duration]).
  void Evaluate(double t, double& s, double& sd, double& sdd) const;

 private:
  double distance_, speed_, acceleration_, t_ramp_, duration_;
};

/// A synchronised joint move from q_start to q_goal: the joint with the largest travel runs at
/// `speed` and `acceleration`, the others proportionally slower (a straight line in joint space).
/// @throws std::invalid_argument for speed outside (0, pi] rad/s, acceleration <= 0, dt <= 0, or
///         non-finite joints.
JointTrajectory PlanJointMove(const Joints& q_start, const Joints& q_goal, double speed = kMovejSpeed,
                              double acceleration = kMovejAcceleration, double dt = 0.002);

enum class CartesianPlanStatus { kOk, kUnreachable, kTooFast };

struct CartesianPlan {
  CartesianPlanStatus status = CartesianPlanStatus::kUnreachable;
  std::string detail;  ///< Why it failed, for reports.
  JointTrajectory trajectory;
};

/// A straight TCP line from FK(q_start) to X_BT_goal (orientation slerped), trapezoidal in arc
/// length (m) with `speed` and `acceleration`, solved by IK at every sample, each solution the nearest
/// valid one to the previous sample. Fails (as a status) if some sample is unreachable or needs a
/// joint faster than pi rad/s (a singularity on the way).
/// @throws std::invalid_argument for speed <= 0 or acceleration <= 0.
CartesianPlan PlanCartesianLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed = kMovelSpeed,
                                double acceleration = kMovelAcceleration, double dt = 0.002,
                                const SelectionOptions& selection = {});

}  // namespace sortcell::robot
