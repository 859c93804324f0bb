#include "robot/torque_limited_motion.h"

#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace sortcell::robot {
namespace {

// Stretching by the computed factor takes friction and damping as they were (they fall a little
// with the speed); a re-check of each re-plan finds the rare move that needs a few per cent more.
constexpr int kRechecks = 3;
constexpr double kRecheckMargin = 1.02;

// Plans with `plan_at(stretch)` until the torques fit the budget: stretched by the computed factor,
// each re-plan checked again. `plan_at` returns false where a re-plan fails for another reason.
template <typename PlanAt>
TorqueLimitedMove StretchUntilItFits(const TorqueBudget& budget, JointTrajectory first, const PlanAt& plan_at) {
  TorqueLimitedMove move{TorqueFit::kWithinBudget, 1, std::move(first)};
  for (int check = 0;; ++check) {
    const double k = TorqueTimeScale(move.trajectory, budget);
    if (k <= 1 + 1e-9) return move;
    if (!std::isfinite(k) || move.stretch >= kMaxStretch || check == kRechecks) {
      move.fit = TorqueFit::kOverBudget;
      return move;
    }
    move.stretch = std::fmin(kMaxStretch, move.stretch * k * (check == 0 ? 1 : kRecheckMargin));
    if (!plan_at(move.stretch, &move.trajectory)) return move;
  }
}

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

TorqueLimitedMove PlanTorqueLimitedJointMove(const Joints& q_start, const Joints& q_goal, const JointMotionLimits& caps,
                                             const TorqueBudget& budget, double dt) {
  return StretchUntilItFits(
      budget, PlanJointMove(q_start, q_goal, caps, dt), [&](double stretch, JointTrajectory* move) {
        *move = PlanJointMove(q_start, q_goal, {caps.speed / stretch, caps.acceleration / (stretch * stretch)}, dt);
        return true;
      });
}

CartesianPlan PlanTorqueLimitedLine(const Joints& q_start, const Eigen::Isometry3d& X_BT_goal, double speed,
                                    double acceleration, const TorqueBudget& budget, double dt) {
  CartesianPlan plan = PlanCartesianLine(q_start, X_BT_goal, speed, acceleration, dt);
  if (plan.status != CartesianPlanStatus::kOk) return plan;
  const TorqueLimitedMove move =
      StretchUntilItFits(budget, std::move(plan.trajectory), [&](double stretch, JointTrajectory* trajectory) {
        plan = PlanCartesianLine(q_start, X_BT_goal, speed / stretch, acceleration / (stretch * stretch), dt);
        *trajectory = std::move(plan.trajectory);
        return plan.status == CartesianPlanStatus::kOk;
      });
  plan.trajectory = move.trajectory;
  if (plan.status == CartesianPlanStatus::kOk && move.fit == TorqueFit::kOverBudget) {
    plan.status = CartesianPlanStatus::kOverTorqueBudget;
    plan.detail = "the line needs more than the torque budget even " + std::to_string(static_cast<int>(kMaxStretch)) +
                  " times slower";
  }
  return plan;
}

}  // namespace sortcell::robot
