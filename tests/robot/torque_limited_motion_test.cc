// Motions slowed down only as far as the arm's torques need (robot/torque_limited_motion.h).
#include <gtest/gtest.h>

#include <random>

#include "robot/torque_limited_motion.h"
#include "tests/robot/random_poses.h"

namespace sortcell::robot {
namespace {

const JointMotionLimits kHighCaps{Joints::Constant(kUr5MaxJointSpeed), Joints::Constant(60.0)};

bool EverySampleFits(const JointTrajectory& t, const TorqueBudget& budget) {
  for (int k = 0; k < t.size(); ++k) {
    if (!budget.Fits(t.q[k], t.qd[k], t.qdd[k])) return false;
  }
  return true;
}

TEST(TorqueLimitedMotion, EveryJointMoveStaysWithinTheBudget) {
  const TorqueBudget budget;
  std::mt19937_64 rng(3);
  int stretched = 0;
  for (int n = 0; n < 40; ++n) {
    const Joints a = RandomPoseAboveTable(rng), b = RandomPoseAboveTable(rng);
    if (TorqueTimeScale(PlanJointMove(a, b, kHighCaps), budget) > 1) ++stretched;
    const TorqueLimitedMove move = PlanTorqueLimitedJointMove(a, b, kHighCaps, budget);
    EXPECT_EQ(move.fit, TorqueFit::kWithinBudget) << "move " << n;
    EXPECT_TRUE(EverySampleFits(move.trajectory, budget)) << "move " << n;
    EXPECT_LT((move.trajectory.q.back() - b).norm(), 1e-9);
  }
  // The caps alone would break the budget in many of them (the others are long enough to be limited
  // by the speed): the check does something.
  std::printf("%d of 40 moves slowed down for their torques\n", stretched);
  EXPECT_GE(stretched, 8);
}

TEST(TorqueLimitedMotion, AMoveThatFitsIsLeftAlone) {
  const Joints a = (Joints() << M_PI, -1.9, 1.3, -1.0, -M_PI_2, 0).finished();
  Joints b = a;
  b[5] += 0.3;  // The last wrist joint carries almost nothing.
  const JointMotionLimits gentle{Joints::Constant(1.0), Joints::Constant(1.0)};
  const JointTrajectory plain = PlanJointMove(a, b, gentle);
  EXPECT_DOUBLE_EQ(TorqueTimeScale(plain, TorqueBudget()), 1.0);
  const TorqueLimitedMove move = PlanTorqueLimitedJointMove(a, b, gentle);
  EXPECT_EQ(move.trajectory.size(), plain.size());
  EXPECT_EQ(move.stretch, 1.0);
}

TEST(TorqueLimitedMotion, ThePanTurnsFasterNearTheBodyThanTheWorstPoseAllows) {
  // Arm folded: the pan's inertia is small, so it may accelerate well beyond the 12 rad/s^2 that is
  // safe with the arm stretched out.
  const Joints folded = (Joints() << M_PI, -1.9, 2.4, -2.0, -M_PI_2, 0).finished();
  Joints turned = folded;
  turned[0] -= 1.5;
  const JointTrajectory fast = PlanTorqueLimitedJointMove(folded, turned, kHighCaps).trajectory;
  const JointTrajectory safe = PlanJointMove(folded, turned, Ur5FastLimits());
  std::printf("pan 1.5 rad: %.3f s torque-limited, %.3f s at the everywhere-safe limits\n", fast.duration(),
              safe.duration());
  EXPECT_LT(fast.duration(), 0.85 * safe.duration());
}

TEST(TorqueLimitedMotion, AnOverAmbitiousLineIsSlowedUntilItFits) {
  const Joints q = (Joints() << M_PI, -1.9, 1.3, -M_PI_2 + 0.6, -M_PI_2, 0).finished();  // The cell's home.
  Eigen::Isometry3d X_BT = TcpPose(q);
  X_BT.translation() += Eigen::Vector3d(0.15, 0, -0.2);
  const TorqueBudget budget;
  const CartesianPlan greedy = PlanCartesianLine(q, X_BT, 0.8, 40.0);
  ASSERT_EQ(greedy.status, CartesianPlanStatus::kOk);
  EXPECT_GT(TorqueTimeScale(greedy.trajectory, budget), 1.0);
  const CartesianPlan line = PlanTorqueLimitedLine(q, X_BT, 0.8, 40.0, budget);
  ASSERT_EQ(line.status, CartesianPlanStatus::kOk);
  EXPECT_TRUE(EverySampleFits(line.trajectory, budget));
  EXPECT_GT(line.trajectory.duration(), greedy.trajectory.duration());
}

TEST(TorqueLimitedMotion, BlendsAreJudgedByTheirTorques) {
  const TorqueBudget budget;
  const Joints a = (Joints() << M_PI, -1.9, 1.3, -1.0, -M_PI_2, 0).finished();
  const Joints b = (Joints() << 2.2, -1.4, 1.6, -1.5, -M_PI_2, 0).finished();
  const Joints c = (Joints() << 1.6, -1.0, 1.2, -1.7, -M_PI_2, 0.5).finished();
  const JointTrajectory first = PlanTorqueLimitedJointMove(a, b, kHighCaps, budget).trajectory;
  const JointTrajectory second = PlanTorqueLimitedJointMove(b, c, kHighCaps, budget).trajectory;
  const SampleCheck fits = [&budget](const Joints& q, const Joints& qd, const Joints& qdd) {
    return budget.Fits(q, qd, qdd);
  };
  const JointTrajectory blended = BlendMoves(first, second, kHighCaps, nullptr, fits);
  EXPECT_TRUE(EverySampleFits(blended, budget));
  EXPECT_LT(blended.size(), first.size() + second.size() - 1);
}

TEST(TorqueLimitedMotion, AMoveBeyondTheBudgetSaysSo) {
  // A budget of a tenth of the limits: the arm's weight alone needs more at the shoulder.
  TorqueBudget weak;
  weak.fraction = 0.1;
  const Joints a = (Joints() << M_PI, -1.9, 1.3, -M_PI_2 + 0.6, -M_PI_2, 0).finished();  // The cell's home.
  Joints b = a;
  b[0] -= 1.0;
  const TorqueLimitedMove move = PlanTorqueLimitedJointMove(a, b, kHighCaps, weak);
  EXPECT_EQ(move.fit, TorqueFit::kOverBudget);
  Eigen::Isometry3d X_BT = TcpPose(a);
  X_BT.translation().z() -= 0.05;
  const CartesianPlan line = PlanTorqueLimitedLine(a, X_BT, 0.5, 5.0, weak);
  EXPECT_EQ(line.status, CartesianPlanStatus::kOverTorqueBudget);
  EXPECT_NE(line.detail.find("torque budget"), std::string::npos) << line.detail;
}

TEST(TorqueLimitedMotion, AMoveStretchedToItsLimitIsCheckedAgain) {
  // A budget the weight leaves little room in: only a large stretch fits, and what is returned as
  // within the budget is checked to be so at every sample.
  TorqueBudget tight;
  tight.fraction = 0.35;
  std::mt19937_64 rng(5);
  int over = 0, stretched_to_fit = 0;
  for (int n = 0; n < 40; ++n) {
    const Joints a = RandomPoseAboveTable(rng), b = RandomPoseAboveTable(rng);
    const TorqueLimitedMove move = PlanTorqueLimitedJointMove(a, b, kHighCaps, tight);
    EXPECT_LE(move.stretch, kMaxStretch);
    if (move.fit == TorqueFit::kOverBudget) {
      ++over;
      continue;
    }
    if (move.stretch > 1.5) ++stretched_to_fit;
    EXPECT_TRUE(EverySampleFits(move.trajectory, tight)) << "move " << n;
  }
  std::printf("%d of 40 moves over a 35 %% budget, %d fit stretched more than 1.5 times\n", over, stretched_to_fit);
  EXPECT_GE(stretched_to_fit, 3);
}

TEST(TorqueLimitedMotion, ABadToolIsRefused) {
  MassProperties tool;
  tool.mass = -1;
  EXPECT_THROW(Ur5Dynamics{tool}, std::invalid_argument);
  tool.mass = 1;
  tool.p_com.x() = std::nan("");
  EXPECT_THROW(Ur5Dynamics{tool}, std::invalid_argument);
}

}  // namespace
}  // namespace sortcell::robot
