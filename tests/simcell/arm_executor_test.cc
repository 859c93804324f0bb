// The simulated arm under the robot layer's control: tracking within torque limits, and the gripper's
// hold detection closing on nothing (on an object: pick_command_test) (sim).
#include "simcell/arm_executor.h"

#include <gtest/gtest.h>

#include "simcell/sim_cell.h"
#include "cell/cell_layout.h"
#include "cell/motion_sequencer.h"
#include "robot/joint_trajectory.h"
#include "sim/arm_io.h"
#include "source_tree.h"

namespace sortcell::simcell {
namespace {

using sortcell_test::kCell;

class ArmExecutorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(sim::ResetToObserve(model_, data_));
    exec_.Reset(cell::CellLayout().q_observe, 0.055);
  }
  const sim::Model model_ = sim::Model::FromFile(kCell);
  sim::Data data_{model_};
  ArmExecutor exec_{model_, data_, nullptr, cell::CellLayout().control_period};
};

TEST_F(ArmExecutorTest, ObserveKeyframeIsTheHomePose) {
  ASSERT_TRUE(sim::ResetToObserve(model_, data_));
  mj_forward(model_.get(), data_.get());
  EXPECT_LT((exec_.JointPositions() - cell::CellLayout().q_observe).cwiseAbs().maxCoeff(), 1e-6);
  EXPECT_NEAR(exec_.Gripper().gap(), robot::kMaxGap, 1e-9);  // open
}

TEST_F(ArmExecutorTest, TracksAJointMoveWithinTheTorqueLimits) {
  robot::Joints goal = cell::CellLayout().q_observe;
  goal[0] -= 1.0;  // swing towards the bins, above everything
  goal[1] += 0.3;
  ASSERT_EQ(exec_.Follow(robot::PlanJointMove(cell::CellLayout().q_observe, goal)).code, sim::StepStatus::kOk);
  ASSERT_EQ(exec_.Wait(0.5).code, sim::StepStatus::kOk);
  EXPECT_LT((exec_.JointPositions() - goal).cwiseAbs().maxCoeff(), 2e-3);
  EXPECT_LT(exec_.tracking().max_error, 0.01);
  EXPECT_EQ(exec_.tracking().saturated_samples, 0);
  // The motors never exceed 150 / 28 N m.
  for (int i = 0; i < 6; ++i) EXPECT_LE(std::abs(data_->ctrl[i]), robot::Ur5TorqueLimits()[i] + 1e-9);
}

TEST(SimCell, ClosingOnNothingIsEmpty) {
  const sim::Model model = sim::Model::FromFile(kCell);
  sim::Data data(model);
  ASSERT_TRUE(sim::ResetToObserve(model, data));
  SimCell cell(model, data, nullptr, nullptr, nullptr, nullptr, cell::CellLayout().control_period);
  cell.Reset(cell::CellLayout().q_observe, 0.055);
  cell::MotionSequencer motions(cell);
  ASSERT_TRUE(motions.Grasp("grasp")) << motions.failure();
  EXPECT_EQ(motions.Hold(), robot::HoldState::kEmpty);
  EXPECT_LT(cell.ReadGripper().gap(), 0.004);
  EXPECT_EQ(cell.ReadGripper().left_pad_force, 0.0);
  ASSERT_EQ(motions.phases().size(), 1u);
  EXPECT_EQ(motions.phases()[0].phase, "grasp");
  EXPECT_GT(motions.phases()[0].end_s, motions.phases()[0].start_s);
}

TEST(ArmExecutor, ControlPeriodMustBeWholeTimesteps) {
  const sim::Model model = sim::Model::FromFile(kCell);
  sim::Data data(model);
  EXPECT_THROW(ArmExecutor(model, data, nullptr, 0.003), std::invalid_argument);
  EXPECT_NO_THROW(ArmExecutor(model, data, nullptr, 0.004));
}

}  // namespace
}  // namespace sortcell::simcell
