#include "app/motion_runner.h"

#include "robot/joint_trajectory.h"

namespace sortcell::app {
namespace {

constexpr double kGripperTimeout = 1.5;  // s

}  // namespace

bool MotionRunner::Phase(const std::string& name, const std::function<sim::StepStatus()>& action) {
  exec_.SetPhase(name);
  const double start = exec_.time();
  const sim::StepStatus status = action();
  phases_.push_back({{"phase", name}, {"start_s", start}, {"end_s", exec_.time()}});
  if (status.code == sim::StepStatus::kOk) return true;
  failure_ = name + ": simulation " + status.detail;
  diverged_ = true;
  return false;
}

bool MotionRunner::MoveJ(const std::string& name, const robot::Joints& q_goal) {
  const robot::JointTrajectory t = robot::PlanJointMove(exec_.ReferenceJoints(), q_goal);
  return Phase(name, [&] { return exec_.Follow(t); });
}

bool MotionRunner::MoveL(const std::string& name, const Eigen::Isometry3d& X_WT, double speed) {
  const robot::CartesianPlan plan =
      robot::PlanCartesianLine(exec_.ReferenceJoints(), X_WT, speed, robot::kMovelAcceleration);
  if (plan.status != robot::CartesianPlanStatus::kOk) {
    failure_ = name + ": " + plan.detail;
    return false;
  }
  return Phase(name, [&] { return exec_.Follow(plan.trajectory); });
}

bool MotionRunner::Gripper(const std::string& name, double gap, robot::HoldState& hold) {
  return Phase(name, [&] { return exec_.MoveGripper(robot::HalfGapTarget(gap), kGripperTimeout, hold); });
}

bool MotionRunner::Grasp(const std::string& name, robot::HoldState& hold) {
  return Phase(name, [&] { return exec_.Grasp(robot::kDefaultGripForce, kGripperTimeout, hold); });
}

bool MotionRunner::Wait(const std::string& name, double seconds) {
  return Phase(name, [&] { return exec_.Wait(seconds); });
}

}  // namespace sortcell::app
