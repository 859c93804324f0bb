#include "robot/joint_trajectory.h"

#include <gtest/gtest.h>

#include <random>

namespace sortcell::robot {
namespace {

constexpr double kSlack = 1e-9;

void ExpectWithinLimits(const JointTrajectory& t, double speed, double acceleration) {
  for (int k = 0; k < t.size(); ++k) {
    ASSERT_LE(t.qd[k].cwiseAbs().maxCoeff(), speed + kSlack) << "sample " << k;
    ASSERT_LE(t.qdd[k].cwiseAbs().maxCoeff(), acceleration + kSlack) << "sample " << k;
  }
}

// Velocity is continuous: between samples it changes by at most acceleration * dt, and the
// positions are consistent with it (no steps in q either).
void ExpectSmooth(const JointTrajectory& t, double acceleration) {
  for (int k = 1; k < t.size(); ++k) {
    ASSERT_LE((t.qd[k] - t.qd[k - 1]).cwiseAbs().maxCoeff(), acceleration * t.dt + 1e-9) << "sample " << k;
    const Joints mean_speed = (t.q[k] - t.q[k - 1]) / t.dt;
    ASSERT_LE((mean_speed - 0.5 * (t.qd[k] + t.qd[k - 1])).cwiseAbs().maxCoeff(), acceleration * t.dt) << k;
  }
  EXPECT_LT(t.qd.front().norm(), 1e-12);
  EXPECT_LT(t.qd.back().norm(), 1e-12);
}

TEST(SmoothProfile, ReachesTheDistanceWithTheRightDurationAndNoJumpInAcceleration) {
  const SmoothProfile cruise(2.0, 1.0, 2.0);  // 1 s ramps covering 0.5 m each, 1 s cruise
  EXPECT_NEAR(cruise.ramp_time(), 1.0, 1e-12);
  EXPECT_NEAR(cruise.duration(), 3.0, 1e-12);
  double s, sd, sdd;
  cruise.Evaluate(3.0, s, sd, sdd);
  EXPECT_NEAR(s, 2.0, 1e-12);
  cruise.Evaluate(1.5, s, sd, sdd);
  EXPECT_NEAR(s, 1.0, 1e-12);
  EXPECT_NEAR(sd, 1.0, 1e-12);
  cruise.Evaluate(0.5, s, sd, sdd);
  EXPECT_NEAR(sdd, 2.0, 1e-12);                  // the peak, mid-ramp
  for (const double t : {0.0, 1.0, 2.0, 3.0}) {  // where the phases meet, the acceleration is zero
    cruise.Evaluate(t, s, sd, sdd);
    EXPECT_NEAR(sdd, 0.0, 1e-9) << t;
  }
  const SmoothProfile short_move(0.1, 1.0, 2.0);  // never reaches 1 m/s: V = sqrt(A D / 2)
  const double v = std::sqrt(0.1);
  EXPECT_NEAR(short_move.duration(), 2 * v / 2.0 + 0.1 / v, 1e-12);
  short_move.Evaluate(short_move.duration() / 2, s, sd, sdd);
  EXPECT_NEAR(s, 0.05, 1e-12);
  EXPECT_NEAR(sd, v, 1e-12);
}

TEST(PlanJointMove, RespectsSpeedAndAccelerationAtEverySample) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int n = 0; n < 50; ++n) {
    Joints a, b;
    for (int i = 0; i < 6; ++i) a[i] = angle(rng), b[i] = angle(rng);
    for (const auto& [speed, acceleration] : {std::pair{kMovejSpeed, kMovejAcceleration}, std::pair{M_PI, 4.0}}) {
      const JointTrajectory t = PlanJointMove(a, b, speed, acceleration);
      ExpectWithinLimits(t, speed, acceleration);
      ExpectSmooth(t, acceleration);
      EXPECT_TRUE(t.q.front().isApprox(a));
      EXPECT_TRUE(t.q.back().isApprox(b));
      // The joint with the longest travel runs at the full speed when it has room to.
      const double distance = (b - a).cwiseAbs().maxCoeff();
      if (distance > 2 * speed * speed / acceleration + 0.01) {
        double peak = 0;
        for (const Joints& qd : t.qd) peak = std::max(peak, qd.cwiseAbs().maxCoeff());
        EXPECT_NEAR(peak, speed, 1e-9);
      }
    }
  }
}

TEST(PlanJointMove, ZeroLengthMoveIsOneSample) {
  const Joints q = Joints::Constant(0.3);
  const JointTrajectory t = PlanJointMove(q, q);
  EXPECT_EQ(t.size(), 1);
  EXPECT_DOUBLE_EQ(t.duration(), 0.0);
}

TEST(PlanJointMove, RejectsBadParameters) {
  const Joints q = Joints::Zero();
  EXPECT_THROW(PlanJointMove(q, q, 4.0), std::invalid_argument);  // above pi rad/s
  EXPECT_THROW(PlanJointMove(q, q, 0.0), std::invalid_argument);
  EXPECT_THROW(PlanJointMove(q, q, 1.0, -1.0), std::invalid_argument);
  Joints bad = q;
  bad[2] = std::nan("");
  EXPECT_THROW(PlanJointMove(q, bad), std::invalid_argument);
}

TEST(PlanCartesianLine, StraightLineAtTheRequestedSpeed) {
  const Joints q0 = (Joints() << 0.3, -1.3, 1.7, -1.97, -1.5708, 0.2).finished();
  Eigen::Isometry3d goal = TcpPose(q0);
  const Eigen::Vector3d start = goal.translation();
  goal.translation().z() -= 0.15;
  const CartesianPlan plan = PlanCartesianLine(q0, goal);
  ASSERT_EQ(plan.status, CartesianPlanStatus::kOk) << plan.detail;
  const JointTrajectory& t = plan.trajectory;
  EXPECT_NEAR(t.duration(), 0.15 / kMovelSpeed + 2 * kMovelSpeed / kMovelAcceleration, 0.005);
  for (int k = 0; k < t.size(); ++k) {
    const Eigen::Vector3d p = TcpPose(t.q[k]).translation();
    // On the line, with the orientation kept.
    ASSERT_LT(((p - start) - (p - start).dot(Eigen::Vector3d::UnitZ()) * Eigen::Vector3d::UnitZ()).norm(), 1e-9);
    ASSERT_LT(RotationError(TcpPose(t.q[k]), goal), 1e-9);
    ASSERT_LE(t.qd[k].cwiseAbs().maxCoeff(), kUr5MaxJointSpeed);
    if (k > 0) {
      const double tcp_speed = (p - TcpPose(t.q[k - 1]).translation()).norm() / t.dt;
      ASSERT_LE(tcp_speed, kMovelSpeed + 1e-6);
    }
  }
  EXPECT_LT(PositionError(TcpPose(t.q.back()), goal), 1e-9);
  EXPECT_LT(t.qd.back().norm(), 1e-12);
}

TEST(PlanCartesianLine, UnreachableGoalIsAStatus) {
  const Joints q0 = (Joints() << 0.3, -1.3, 1.7, -1.97, -1.5708, 0.2).finished();
  Eigen::Isometry3d goal = TcpPose(q0);
  goal.translation() << 1.5, 0.0, 0.2;  // beyond the arm's reach
  const CartesianPlan plan = PlanCartesianLine(q0, goal);
  // On the way out the elbow straightens: the joints speed up without bound (kTooFast) before the
  // line leaves the workspace (kUnreachable). Either way a status, never an exception.
  EXPECT_NE(plan.status, CartesianPlanStatus::kOk);
  EXPECT_FALSE(plan.detail.empty());
  // A goal the first step cannot reach at all.
  goal.translation() << 0.0, 0.02, 0.5;  // inside the shoulder column
  const CartesianPlan column = PlanCartesianLine(q0, goal);
  EXPECT_NE(column.status, CartesianPlanStatus::kOk);
}

TEST(JointTrajectory, AppendJoinsSegmentsWithoutRepeatingTheSeam) {
  const Joints a = Joints::Zero(), b = Joints::Constant(0.5), c = Joints::Constant(-0.2);
  JointTrajectory t = PlanJointMove(a, b);
  const int first = t.size();
  const JointTrajectory second = PlanJointMove(b, c);
  t.Append(second);
  EXPECT_EQ(t.size(), first + second.size() - 1);
  ExpectSmooth(t, kMovejAcceleration);
  EXPECT_THROW(t.Append(PlanJointMove(a, b)), std::invalid_argument);  // does not start where t ends
}

TEST(PlanJointMove, PerJointLimitsBoundEveryJoint) {
  const JointMotionLimits limits = Ur5FastLimits();
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  for (int n = 0; n < 30; ++n) {
    Joints a, b;
    for (int i = 0; i < 6; ++i) a[i] = angle(rng), b[i] = angle(rng);
    const JointTrajectory t = PlanJointMove(a, b, limits);
    double tightest = 0;  // How close the most limited joint comes to its limits.
    for (int k = 0; k < t.size(); ++k) {
      for (int j = 0; j < 6; ++j) {
        ASSERT_LE(std::abs(t.qd[k][j]), limits.speed[j] + kSlack);
        ASSERT_LE(std::abs(t.qdd[k][j]), limits.acceleration[j] + kSlack);
        tightest = std::max(
            {tightest, std::abs(t.qd[k][j]) / limits.speed[j], std::abs(t.qdd[k][j]) / limits.acceleration[j]});
      }
    }
    EXPECT_NEAR(tightest, 1.0, 1e-3);  // No slower than the limits make it.
    EXPECT_TRUE(t.q.back().isApprox(b));
    EXPECT_NEAR(t.accel_s, t.decel_s, 1e-12);
  }
}

TEST(BlendMoves, JoinsWithoutStoppingWithinTheLimitsAndEndsAtTheGoal) {
  const JointMotionLimits limits = Ur5FastLimits();
  const Joints a = Joints::Zero(), b = (Joints() << 1.0, -0.3, 0.4, 0.5, 0, 0).finished(),
               c = (Joints() << 1.6, -0.8, 0.9, 0.5, 0.2, 0).finished();
  const JointTrajectory first = PlanJointMove(a, b, limits), second = PlanJointMove(b, c, limits);
  int seam = -1;
  const JointTrajectory blended = BlendMoves(first, second, limits, &seam);
  // Shorter than stopping at b, by the overlap.
  const double overlap = 0.5 * std::min(first.decel_s, second.accel_s);
  EXPECT_NEAR(blended.duration(), first.duration() + second.duration() - overlap, 2 * first.dt);
  EXPECT_GT(seam, 0);
  EXPECT_LT(seam, blended.size());
  double slowest = 1e9;  // The arm never stops on the way between the two cruises.
  for (int k = 1; k + 1 < blended.size(); ++k) {
    if (k > first.size() / 2 && k < blended.size() - second.size() / 2)
      slowest = std::min(slowest, blended.qd[k].norm());
    for (int j = 0; j < 6; ++j) {
      ASSERT_LE(std::abs(blended.qd[k][j]), limits.speed[j] + kSlack);
      ASSERT_LE(std::abs(blended.qdd[k][j]), limits.acceleration[j] + kSlack);
    }
    const Joints mean_speed = (blended.q[k] - blended.q[k - 1]) / blended.dt;
    ASSERT_LE((mean_speed - 0.5 * (blended.qd[k] + blended.qd[k - 1])).cwiseAbs().maxCoeff(), 0.05) << k;
  }
  EXPECT_GT(slowest, 0.05);
  EXPECT_TRUE(blended.q.back().isApprox(c));
  EXPECT_LT(blended.qd.back().norm(), 1e-12);
  EXPECT_THROW(BlendMoves(first, first, limits), std::invalid_argument);  // does not join
}

TEST(BlendMoves, AReversalThatWouldBreakALimitOverlapsLessOrNotAtAll) {
  // Out and straight back on one joint: the two accelerations add up to twice the limit unless
  // the overlap shrinks.
  JointMotionLimits limits;
  limits.speed.setConstant(1.0);
  limits.acceleration.setConstant(2.0);
  const Joints a = Joints::Zero(), b = Joints::Unit(0);
  const JointTrajectory out = PlanJointMove(a, b, limits), back = PlanJointMove(b, a, limits);
  const JointTrajectory blended = BlendMoves(out, back, limits);
  for (int k = 0; k < blended.size(); ++k) ASSERT_LE(blended.qdd[k].cwiseAbs().maxCoeff(), 2.0 + kSlack);
  EXPECT_LT(blended.duration(), out.duration() + back.duration() + 1e-9);
  EXPECT_TRUE(blended.q.back().isApprox(a));
}

}  // namespace
}  // namespace sortcell::robot
