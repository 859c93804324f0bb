#include "cell/motion_sequencer.h"

#include "robot/joint_trajectory.h"

namespace sortcell::cell {
namespace {

constexpr double kGripperTimeout = 1.5;  // s, for the fingers to stop
constexpr double kFingersGetGoing = 0.1;  // s, before judging that the fingers stopped
constexpr double kSqueezeTime = 0.2;      // s, for the squeeze to build up

}  // namespace

bool MotionSequencer::Phase(const std::string& name, const std::function<MotionResult()>& action) {
  const double start = io_.Now();
  const MotionResult result = action();
  phases_.push_back({name, start, io_.Now()});
  if (result.ok()) return true;
  failure_ = name + ": cell fault: " + result.detail;
  faulted_ = true;
  return false;
}

bool MotionSequencer::MoveJ(const std::string& name, const robot::Joints& q_goal) {
  const robot::JointTrajectory t = robot::PlanJointMove(io_.CommandedJoints(), q_goal);
  return Phase(name, [&] { return io_.Follow(name, t); });
}

bool MotionSequencer::MoveL(const std::string& name, const Eigen::Isometry3d& X_WT, double speed) {
  const robot::CartesianPlan plan =
      robot::PlanCartesianLine(io_.CommandedJoints(), X_WT, speed, robot::kMovelAcceleration);
  if (plan.status != robot::CartesianPlanStatus::kOk) {
    failure_ = name + ": " + plan.detail;
    return false;
  }
  return Phase(name, [&] { return io_.Follow(name, plan.trajectory); });
}

MotionResult MotionSequencer::MoveFingers(const std::string& name, double half_gap) {
  io_.CommandFingers(half_gap, half_gap);
  const double start = io_.Now();
  return io_.HoldUntil(name, kGripperTimeout, [&] {
    return io_.Now() - start >= kFingersGetGoing && Hold() != robot::HoldState::kMoving;
  });
}

bool MotionSequencer::Gripper(const std::string& name, double gap) {
  return Phase(name, [&] { return MoveFingers(name, robot::HalfGapTarget(gap)); });
}

MotionResult MotionSequencer::CloseAndSqueeze(const std::string& name) {
  MotionResult result = MoveFingers(name, 0.0);
  if (!result.ok() || Hold() != robot::HoldState::kHolding) return result;
  const robot::GripperSensors contact = io_.ReadGripper();
  io_.CommandFingers(robot::SqueezeTarget(contact.left_half_gap, robot::kDefaultGripForce),
                     robot::SqueezeTarget(contact.right_half_gap, robot::kDefaultGripForce));
  return io_.Wait(name, kSqueezeTime);
}

bool MotionSequencer::Grasp(const std::string& name) {
  return Phase(name, [&] { return CloseAndSqueeze(name); });
}

bool MotionSequencer::Wait(const std::string& name, double seconds) {
  return Phase(name, [&] { return io_.Wait(name, seconds); });
}

}  // namespace sortcell::cell
