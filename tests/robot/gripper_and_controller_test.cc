#include <gtest/gtest.h>

#include "robot/gripper_control.h"
#include "robot/joint_controller.h"

namespace sortcell::robot {
namespace {

TEST(JointController, PdPlusBiasWithinTheTorqueLimits) {
  JointController controller;
  const Joints q = Joints::Zero(), qd = Joints::Zero();
  const Joints bias = (Joints() << 0, 40, 10, 1, 0, 0).finished();
  // On target: the bias alone.
  EXPECT_TRUE(controller.Torque(q, qd, q, qd, bias).isApprox(bias));
  // A small error: proportional action.
  const Joints q_ref = Joints::Constant(0.001);
  const Joints tau = controller.Torque(q, qd, q_ref, qd, Joints::Zero());
  EXPECT_NEAR(tau[0], DefaultUr5Gains().kp[0] * 0.001, 1e-12);
  // A large error saturates at 150 / 28 N m.
  const Joints big = controller.Torque(q, qd, Joints::Constant(1.0), qd, bias);
  EXPECT_TRUE(big.isApprox(Ur5TorqueLimits()));
  const Joints negative = controller.Torque(q, qd, Joints::Constant(-1.0), qd, bias);
  EXPECT_TRUE(negative.isApprox(-Ur5TorqueLimits()));
  EXPECT_EQ(controller.stats().samples, 4);
  EXPECT_EQ(controller.stats().saturated_samples, 2);
  EXPECT_DOUBLE_EQ(controller.stats().max_error, 1.0);
}

TEST(JointController, RejectsBadGains) {
  PdGains gains = DefaultUr5Gains();
  gains.kd[3] = -1;
  EXPECT_THROW(JointController{gains}, std::invalid_argument);
  EXPECT_THROW(JointController(DefaultUr5Gains(), Joints::Zero()), std::invalid_argument);
}

TEST(GripperControl, HoldDetectionFromOpeningAndContacts) {
  GripperSensors s;
  s.left_half_gap = s.right_half_gap = 0.033;
  s.left_pad_force = s.right_pad_force = 60;
  EXPECT_EQ(DetectHold(s), HoldState::kHolding);
  s.left_speed = 0.05;
  EXPECT_EQ(DetectHold(s), HoldState::kMoving);
  s.left_speed = 0;
  s.right_pad_force = 0;  // one finger touches nothing
  EXPECT_EQ(DetectHold(s), HoldState::kEmpty);
  s.right_pad_force = 60;
  s.left_half_gap = s.right_half_gap = 0.0005;  // closed to the stop
  EXPECT_EQ(DetectHold(s), HoldState::kEmpty);
  EXPECT_STREQ(ToString(HoldState::kHolding), "holding");
}

TEST(GripperControl, TargetsStayInTheStroke) {
  EXPECT_DOUBLE_EQ(HalfGapTarget(0.05), 0.025);
  EXPECT_DOUBLE_EQ(HalfGapTarget(0.2), kMaxGap / 2);
  EXPECT_DOUBLE_EQ(HalfGapTarget(-1), 0.0);
}

TEST(GripperControl, CaughtAfterOpeningWhenShortOfTheGapOrPressed) {
  GripperSensors s;
  s.left_half_gap = s.right_half_gap = 0.04;  // opened to 0.08
  EXPECT_FALSE(CaughtAfterOpening(s, 0.08));
  EXPECT_TRUE(CaughtAfterOpening(s, 0.085));  // stopped 5 mm short: something in the way
  s.right_pad_force = 3;
  EXPECT_TRUE(CaughtAfterOpening(s, 0.08));  // something presses a pad
  s.right_pad_force = 0;
  s.left_half_gap = s.right_half_gap = kMaxGap / 2;
  EXPECT_FALSE(CaughtAfterOpening(s, 0.2));  // beyond the stroke: open as far as it goes
}

TEST(GripperControl, FrictionUseFromThePadsForces) {
  GripperSensors s;
  EXPECT_DOUBLE_EQ(FrictionUse(s), 0.0) << "no contact";
  s.left_pad_force = s.right_pad_force = 30;
  EXPECT_DOUBLE_EQ(FrictionUse(s), 0.0) << "squeezed, nothing pulling";
  s.left_pad_shear = 0.5 * kPadFriction * 30;  // Half the sliding friction used on the left.
  EXPECT_NEAR(FrictionUse(s), 0.5, 1e-12);
  s.right_pad_twist = 0.8 * kPadTwistFriction * 30;  // The right pads turning: the larger side counts.
  EXPECT_NEAR(FrictionUse(s), 0.8, 1e-12);
  s.right_pad_shear = 0.6 * kPadFriction * 30;  // Both at once add up on the friction ellipse.
  EXPECT_NEAR(FrictionUse(s), 1.0, 1e-12);
  const auto [left, right] = SqueezeTargets({0.03, 0.02}, 40);
  EXPECT_DOUBLE_EQ(left, 0.03 - 40 / kFingerServoKp);
  EXPECT_DOUBLE_EQ(right, 0.02 - 40 / kFingerServoKp);
  EXPECT_LT(kFirmGripForce, kFingerForceLimit) << "the servos stay springs";
}

}  // namespace
}  // namespace sortcell::robot
