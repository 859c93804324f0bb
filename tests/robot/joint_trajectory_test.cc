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

TEST(TrapezoidProfile, ReachesTheDistanceWithTheRightDuration) {
  const TrapezoidProfile trapezoid(2.0, 1.0, 2.0);  // 0.5 s ramps, 1.5 s cruise
  EXPECT_NEAR(trapezoid.duration(), 2.5, 1e-12);
  double s, sd, sdd;
  trapezoid.Evaluate(2.5, s, sd, sdd);
  EXPECT_NEAR(s, 2.0, 1e-12);
  trapezoid.Evaluate(1.0, s, sd, sdd);
  EXPECT_NEAR(sd, 1.0, 1e-12);
  const TrapezoidProfile triangle(0.1, 1.0, 2.0);  // never reaches 1 m/s
  EXPECT_NEAR(triangle.duration(), 2 * std::sqrt(0.05), 1e-12);
  triangle.Evaluate(triangle.duration() / 2, s, sd, sdd);
  EXPECT_NEAR(s, 0.05, 1e-12);
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
      if (distance > speed * speed / acceleration + 0.01) {
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
  EXPECT_NEAR(t.duration(), 0.15 / kMovelSpeed + kMovelSpeed / kMovelAcceleration, 0.005);
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

}  // namespace
}  // namespace sortcell::robot
