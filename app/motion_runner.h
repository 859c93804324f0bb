#pragma once
/// @file
/// Named motion phases of the arm and gripper for pick-and-place: each phase runs on an ArmExecutor,
/// records its simulated time span, and reports a failure (a motion that cannot be planned, or a
/// diverged simulation) as a value with its reason.

#include <functional>
#include <string>

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include "app/arm_executor.h"
#include "robot/gripper_control.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::app {

class MotionRunner {
 public:
  MotionRunner(const sim::Model& model, sim::Data& data, sim::VideoRecorder* video) : exec_(model, data, video) {}

  ArmExecutor& exec() { return exec_; }
  /// Every phase run so far: [{"phase", "start_s", "end_s"}].
  const nlohmann::json& phases() const { return phases_; }
  /// Why the last step that returned false failed.
  const std::string& failure() const { return failure_; }
  bool diverged() const { return diverged_; }
  /// The status of a step that returned false: "sim_diverged" or "unreachable".
  std::string FailureStatus() const { return diverged_ ? "sim_diverged" : "unreachable"; }

  /// Runs `action` as phase `name`; false (and failure() says why) if the simulation diverged.
  bool Phase(const std::string& name, const std::function<sim::StepStatus()>& action);
  /// A joint-space move from where the controller holds the arm.
  bool MoveJ(const std::string& name, const robot::Joints& q_goal);
  /// A straight TCP line at `speed`; false with failure() set if it cannot be planned or run.
  bool MoveL(const std::string& name, const Eigen::Isometry3d& X_WT, double speed);
  /// Opens or closes the fingers to `gap`; the resulting hold state goes to `hold`.
  bool Gripper(const std::string& name, double gap, robot::HoldState& hold);
  /// Closes on an object and squeezes it with the default grip force.
  bool Grasp(const std::string& name, robot::HoldState& hold);
  /// Holds still for `seconds`.
  bool Wait(const std::string& name, double seconds);

 private:
  ArmExecutor exec_;
  nlohmann::json phases_ = nlohmann::json::array();
  std::string failure_;
  bool diverged_ = false;
};

}  // namespace sortcell::app
