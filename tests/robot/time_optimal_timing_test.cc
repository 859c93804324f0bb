// The fastest traversal of a joint path under speed and acceleration or torque limits
// (robot/time_optimal_timing.h).
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "robot/time_optimal_timing.h"
#include "robot/ur5_ik.h"
#include "tests/robot/random_poses.h"

namespace sortcell::robot {
namespace {

const Joints kStart = (Joints() << 0.3, -1.6, 1.4, -1.4, -1.57, 0.2).finished();

// The fastest rest-to-rest move over `distance` with speed v and acceleration a (the trapezoid, or
// the triangle when v is never reached).
double Trapezoid(double distance, double v, double a) {
  return distance >= v * v / a ? distance / v + v / a : 2 * std::sqrt(distance / a);
}

TEST(TimeOptimalTiming, OneJointMovesAsTheTrapezoidAllows) {
  JointMotionLimits limits;
  limits.speed = Joints::Constant(1.0);
  limits.acceleration = Joints::Constant(2.0);
  for (const double distance : {2.0, 0.5}) {
    Joints goal = kStart;
    goal[0] += distance;
    const JointTrajectory planned = PlanJointMove(kStart, goal, 0.5, 1.0);
    const PathTiming fastest = TimeOptimalTiming(planned, limits);
    ASSERT_TRUE(fastest.feasible);
    EXPECT_NEAR(fastest.duration(), Trapezoid(distance, 1.0, 2.0), 0.01 * Trapezoid(distance, 1.0, 2.0))
        << "distance " << distance;
    EXPECT_LT(fastest.duration(), planned.duration());
  }
}

TEST(TimeOptimalTiming, AStraightJointMoveIsAsSlowAsItsMostLimitedJoint) {
  JointMotionLimits limits;
  limits.speed << 3, 3, 1, 3, 3, 3;
  limits.acceleration << 20, 20, 20, 20, 20, 1.5;
  const Joints travel = (Joints() << 1.0, 0.4, 1.2, 0.0, 0.2, -0.9).finished();
  // Along the line the path's speed is held by v_j / |d_j| and its acceleration by a_j / |d_j|.
  const double v = (limits.speed.array() / travel.array().abs()).minCoeff();
  const double a = (limits.acceleration.array() / travel.array().abs()).minCoeff();
  const PathTiming fastest = TimeOptimalTiming(PlanJointMove(kStart, kStart + travel, 0.3, 0.5), limits);
  ASSERT_TRUE(fastest.feasible);
  EXPECT_NEAR(fastest.duration(), Trapezoid(1.0, v, a), 0.01 * Trapezoid(1.0, v, a));
}

TEST(TimeOptimalTiming, DependsOnThePathNotOnHowFastItWasPlanned) {
  const Joints goal = kStart + (Joints() << 1.2, 0.5, -0.7, 0.3, 0.4, -1.0).finished();
  const TorqueBudget budget;
  const Joints speed = Joints::Constant(kUr5MaxJointSpeed);
  const double slow = TimeOptimalTiming(PlanJointMove(kStart, goal, 0.2, 0.4), speed, budget).duration();
  const double fast = TimeOptimalTiming(PlanJointMove(kStart, goal, 2.0, 6.0), speed, budget).duration();
  EXPECT_NEAR(slow, fast, 0.01 * fast);
}

TEST(TimeOptimalTiming, IsALowerBoundOfEveryMoveThatKeepsTheBudget) {
  const TorqueBudget budget;
  const JointMotionLimits caps{Joints::Constant(kUr5MaxJointSpeed), Joints::Constant(60.0)};
  std::mt19937_64 rng(5);
  for (int n = 0; n < 20; ++n) {
    const Joints a = RandomPoseAboveTable(rng), b = RandomPoseAboveTable(rng);
    const TorqueLimitedMove move = PlanTorqueLimitedJointMove(a, b, caps, budget);
    ASSERT_EQ(move.fit, TorqueFit::kWithinBudget);
    const PathTiming fastest = TimeOptimalTiming(move.trajectory, caps.speed, budget, 5);
    ASSERT_TRUE(fastest.feasible) << "move " << n;
    // The planner's smooth profile and its one stretch for the worst sample leave time; never less.
    EXPECT_LE(fastest.duration(), move.trajectory.duration()) << "move " << n;
    EXPECT_GT(fastest.duration(), 0.3 * move.trajectory.duration()) << "move " << n;
  }
}

TEST(TimeOptimalTiming, BoundsAStraightToolLineToo) {
  const Eigen::Isometry3d X_BT = TcpPose(kStart);
  Eigen::Isometry3d X_BT_goal = X_BT;
  X_BT_goal.translation() += Eigen::Vector3d(0.1, -0.15, -0.2);
  const CartesianPlan line = PlanTorqueLimitedLine(kStart, X_BT_goal, 0.25, 1.2);
  ASSERT_EQ(line.status, CartesianPlanStatus::kOk);
  const PathTiming fastest = TimeOptimalTiming(line.trajectory, Joints::Constant(kUr5MaxJointSpeed), TorqueBudget{}, 5);
  ASSERT_TRUE(fastest.feasible);
  EXPECT_LT(fastest.duration(), line.trajectory.duration());
  EXPECT_GT(fastest.duration(), 0);
}

TEST(TimeOptimalTiming, ABudgetTheArmsWeightExceedsIsInfeasible) {
  Joints goal = kStart;
  goal[0] += 0.5;
  TorqueBudget weak;
  weak.limits = Joints::Constant(1.0);  // N m: the shoulder alone holds far more than this up.
  const PathTiming timing = TimeOptimalTiming(PlanJointMove(kStart, goal), Joints::Constant(1.0), weak);
  EXPECT_FALSE(timing.feasible);
  EXPECT_TRUE(timing.t.empty());
}

TEST(TimeOptimalTiming, InterpolatesBetweenItsSamples) {
  Joints goal = kStart;
  goal[1] += 0.8;
  const JointTrajectory planned = PlanJointMove(kStart, goal);
  const PathTiming every = TimeOptimalTiming(planned, Ur5FastLimits(), 1);
  const PathTiming fifth = TimeOptimalTiming(planned, Ur5FastLimits(), 5);
  ASSERT_TRUE(every.feasible && fifth.feasible);
  EXPECT_EQ(fifth.samples.back(), planned.size() - 1);
  EXPECT_DOUBLE_EQ(fifth.At(-3), 0.0);
  EXPECT_DOUBLE_EQ(fifth.At(planned.size() + 7), fifth.duration());
  EXPECT_NEAR(fifth.duration(), every.duration(), 0.01 * every.duration());
  const int middle = planned.size() / 2;
  EXPECT_NEAR(fifth.At(middle), every.At(middle), 0.01 * every.duration());
}

TEST(TimeOptimalTiming, RefusesBadArguments) {
  const JointTrajectory planned = PlanJointMove(kStart, kStart + Joints::Constant(0.1));
  EXPECT_THROW(TimeOptimalTiming(planned, Ur5FastLimits(), 0), std::invalid_argument);
  JointMotionLimits zero = Ur5FastLimits();
  zero.acceleration[2] = 0;
  EXPECT_THROW(TimeOptimalTiming(planned, zero), std::invalid_argument);
  EXPECT_THROW(TimeOptimalTiming(planned, Joints::Constant(-1.0), TorqueBudget{}), std::invalid_argument);
  EXPECT_FALSE(TimeOptimalTiming(JointTrajectory{}, Ur5FastLimits()).feasible);
}

}  // namespace
}  // namespace sortcell::robot
