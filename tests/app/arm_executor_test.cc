// The simulated arm under the robot layer's control: tracking within torque limits, and the gripper's
// hold detection closing on nothing (on an object: pick_command_test) (sim).
#include "app/arm_executor.h"

#include <gtest/gtest.h>

#include "app/pick_command.h"
#include "robot/joint_trajectory.h"
#include "sim/arm_io.h"

namespace sortcell::app {
namespace {

const std::string kCell = std::string(SORTCELL_SOURCE_DIR) + "/scenes/cell.xml";

TEST(ArmExecutor, TracksAJointMoveWithinTheTorqueLimits) {
  const sim::Model model = sim::Model::FromFile(kCell);
  sim::Data data(model);
  mj_resetDataKeyframe(model.get(), data.get(), 0);
  ArmExecutor exec(model, data);
  exec.Reset(HomeJoints(), 0.055);
  robot::Joints goal = HomeJoints();
  goal[0] -= 1.0;  // swing towards the bins, above everything
  goal[1] += 0.3;
  ASSERT_EQ(exec.Follow(robot::PlanJointMove(HomeJoints(), goal)).code, sim::StepStatus::kOk);
  ASSERT_EQ(exec.Wait(0.5).code, sim::StepStatus::kOk);
  EXPECT_LT((exec.JointPositions() - goal).cwiseAbs().maxCoeff(), 2e-3);
  EXPECT_LT(exec.tracking().max_error, 0.01);
  EXPECT_EQ(exec.tracking().saturated_samples, 0);
  // The motors never exceed 150 / 28 N m.
  for (int i = 0; i < 6; ++i) EXPECT_LE(std::abs(data->ctrl[i]), robot::Ur5TorqueLimits()[i] + 1e-9);
}

TEST(ArmExecutor, ClosingOnNothingIsEmpty) {
  const sim::Model model = sim::Model::FromFile(kCell);
  sim::Data data(model);
  mj_resetDataKeyframe(model.get(), data.get(), 0);
  ArmExecutor exec(model, data);
  exec.Reset(HomeJoints(), 0.055);
  robot::HoldState hold = robot::HoldState::kMoving;
  ASSERT_EQ(exec.Grasp(robot::kDefaultGripForce, 1.5, hold).code, sim::StepStatus::kOk);
  EXPECT_EQ(hold, robot::HoldState::kEmpty);
  EXPECT_LT(exec.Gripper().gap(), 0.004);
  EXPECT_EQ(exec.Gripper().left_pad_force, 0.0);
}

TEST(ArmExecutor, ControlPeriodMustBeWholeTimesteps) {
  const sim::Model model = sim::Model::FromFile(kCell);
  sim::Data data(model);
  EXPECT_THROW(ArmExecutor(model, data, nullptr, 0.003), std::invalid_argument);
  EXPECT_NO_THROW(ArmExecutor(model, data, nullptr, 0.004));
}

}  // namespace
}  // namespace sortcell::app
