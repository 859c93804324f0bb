#pragma once
/// @file
/// Motions as fast as the joint torque limits allow in the poses they pass through: a move is planned
/// at its nominal speed and acceleration, the arm's dynamics model (robot/ur5_dynamics.h) gives the
/// torque at every sample, and where some joint would need more than its budget the whole move is
/// stretched in time (speeds / k, accelerations / k^2) until none does. So a move near the body, or
/// one that swings the pan alone, runs much faster than the worst pose in the workspace would allow.

#include "robot/joint_trajectory.h"
#include "robot/ur5_dynamics.h"

namespace sortcell::robot {

/// How much of each joint's torque limit a planned motion may ask; the rest is left to the joint
/// controller's feedback.
struct TorqueBudget {
  const Ur5Dynamics* dynamics = &CellArmDynamics();
  double fraction = 0.8;
  Joints limits = Ur5TorqueLimits();

  /// Whether the torques at this sample are within the budget.
  bool Fits(const Joints& q, const Joints& qd, const Joints& qdd) const;
};

/// The factor k >= 1 by which `trajectory` must be slowed down in time for its torques to stay in
/// `budget` (1 where they already do; infinity where the arm's weight alone exceeds it somewhere).
double TorqueTimeScale(const JointTrajectory& trajectory, const TorqueBudget& budget);

/// Whether a planned move keeps within the torque budget.
enum class TorqueFit {
  kWithinBudget,
  kOverBudget,  ///< Even stretched kMaxStretch times (or the arm's weight alone exceeds it somewhere).
};

struct TorqueLimitedMove {
  TorqueFit fit = TorqueFit::kWithinBudget;
  double stretch = 1;  ///< How much slower than the caps it runs.
  JointTrajectory trajectory;
};

/// PlanJointMove with per-joint speed and acceleration caps, then slowed down as far as the torques
/// need (at most kMaxStretch times; beyond that kOverBudget, with the most stretched plan).
/// @throws std::invalid_argument as PlanJointMove.
TorqueLimitedMove PlanTorqueLimitedJointMove(const Joints& q_start, const Joints& q_goal, const JointMotionLimits& caps,
                                             const TorqueBudget& budget = {}, double dt = 0.002);

/// PlanCartesianLine at `speed` and `acceleration` at most, slowed down as far as the torques need;
/// CartesianPlanStatus::kOverTorqueBudget where kMaxStretch is not enough.
/// @throws std::invalid_argument as PlanCartesianLine.
CartesianPlan PlanTorqueLimitedLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed,
                                    double acceleration, const TorqueBudget& budget = {}, double dt = 0.002);

/// A move is stretched at most this much: beyond it the arm's weight alone nearly exhausts a joint,
/// which the UR5 with its planned payload never meets in reach.
inline constexpr double kMaxStretch = 4.0;

}  // namespace sortcell::robot
