#include "robot/torque_limited_motion.h"

#include <cmath>
#include <limits>

namespace sortcell::robot {
namespace {

// Stretching by the computed factor takes friction and damping as they were (they fall a little
// with the speed); a re-check finds the rare move that needs a few per cent more.
constexpr int kRechecks = 3;
constexpr double kRecheckStep = 1.05;

}  // namespace

bool TorqueBudget::Fits(const Joints& q, const Joints& qd, const Joints& qdd) const {
  const Joints tau = dynamics->Torque(q, qd, qdd);
  return (tau.cwiseAbs().array() <= fraction * limits.array() * (1 + 1e-9)).all();
}

double TorqueTimeScale(const JointTrajectory& trajectory, const TorqueBudget& budget) {
  // At k times the duration: tau = gravity + friction + inertial / k^2, for each joint within +-B.
  double k2 = 1;
  for (int s = 0; s < trajectory.size(); ++s) {
    const Joints& q = trajectory.q[s];
    const Joints steady = budget.dynamics->Gravity(q) + Ur5Dynamics::Friction(trajectory.qd[s], trajectory.qdd[s]);
    const Joints inertial = budget.dynamics->Inertial(q, trajectory.qd[s], trajectory.qdd[s]);
    for (int j = 0; j < 6; ++j) {
      const double limit = budget.fraction * budget.limits[j];
      if (std::abs(steady[j]) >= limit) return std::numeric_limits<double>::infinity();
      const double room = inertial[j] > 0 ? limit - steady[j] : limit + steady[j];
      k2 = std::fmax(k2, std::abs(inertial[j]) / room);
    }
  }
  return std::sqrt(k2);
}

JointTrajectory PlanTorqueLimitedJointMove(const Joints& q_start, const Joints& q_goal, const JointMotionLimits& caps,
                                           const TorqueBudget& budget, double dt) {
  JointTrajectory move = PlanJointMove(q_start, q_goal, caps, dt);
  double stretch = 1;
  for (int check = 0; check <= kRechecks; ++check) {
    const double k = TorqueTimeScale(move, budget);
    if (k <= 1 + 1e-9 || stretch >= kMaxStretch) break;
    stretch = std::fmin(kMaxStretch, stretch * (check == 0 ? k : kRecheckStep));
    move = PlanJointMove(q_start, q_goal, {caps.speed / stretch, caps.acceleration / (stretch * stretch)}, dt);
  }
  return move;
}

CartesianPlan PlanTorqueLimitedLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed,
                                    double acceleration, const TorqueBudget& budget, double dt) {
  CartesianPlan plan = PlanCartesianLine(q_start, X_BT_goal, speed, acceleration, dt);
  double stretch = 1;
  for (int check = 0; check <= kRechecks && plan.status == CartesianPlanStatus::kOk; ++check) {
    const double k = TorqueTimeScale(plan.trajectory, budget);
    if (k <= 1 + 1e-9 || stretch >= kMaxStretch) break;
    stretch = std::fmin(kMaxStretch, stretch * (check == 0 ? k : kRecheckStep));
    plan = PlanCartesianLine(q_start, X_BT_goal, speed / stretch, acceleration / (stretch * stretch), dt);
  }
  return plan;
}

}  // namespace sortcell::robot
