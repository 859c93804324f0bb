#include "robot/ur5_ik.h"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>

#include "robot/ik_selection.h"

namespace sortcell::robot {
namespace {

constexpr double kTight = 1e-9;

Joints RandomJoints(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI);
  Joints q;
  for (int i = 0; i < 6; ++i) q[i] = angle(rng);
  return q;
}

bool Contains(const IkResult& ik, const Joints& q, double tolerance) {
  for (int k = 0; k < ik.count; ++k) {
    bool same = true;
    for (int i = 0; i < 6; ++i)
      same = same && std::abs(std::remainder(ik.solutions[k].q[i] - q[i], 2 * M_PI)) < tolerance;
    if (same) return true;
  }
  return false;
}

void ExpectAllReproduce(const IkResult& ik, const Eigen::Isometry3d& X, double tolerance) {
  for (int k = 0; k < ik.count; ++k) {
    const IkSolution& s = ik.solutions[k];
    ASSERT_TRUE(s.q.allFinite());
    const Eigen::Isometry3d fk = FlangePose(s.q);
    ASSERT_LE(PositionError(fk, X), tolerance) << "solution " << k;
    ASSERT_LE(RotationError(fk, X), tolerance) << "solution " << k;
    ASSERT_NEAR(s.position_error, PositionError(fk, X), 1e-15);
  }
}

// 100,000 random configurations (fixed seed): every solution reproduces the pose to 1e-9 and the
// configuration the pose came from is among the solutions, away from the singularities.
TEST(Ur5Ik, RoundTripOnRandomReachablePoses) {
  std::mt19937_64 rng(20261122);
  int checked = 0, total_solutions = 0;
  for (int n = 0; n < 100000; ++n) {
    const Joints q = RandomJoints(rng);
    const Eigen::Isometry3d X = FlangePose(q);
    const IkResult ik = SolveIk(X, q[5]);
    ASSERT_EQ(ik.status, IkStatus::kOk) << "n = " << n;
    total_solutions += ik.count;
    const bool near_singular = std::abs(std::sin(q[4])) < 1e-3 || std::abs(std::sin(q[2])) < 1e-3;
    if (near_singular) continue;
    ExpectAllReproduce(ik, X, kTight);
    ASSERT_TRUE(Contains(ik, q, 1e-7)) << "n = " << n;
    ++checked;
  }
  EXPECT_GT(checked, 99000);
  EXPECT_GT(total_solutions, 7 * 100000);  // nearly all random poses have all 8
}

TEST(Ur5Ik, NoDuplicatesModulo2Pi) {
  std::mt19937_64 rng(3);
  for (int n = 0; n < 2000; ++n) {
    const IkResult ik = SolveIk(FlangePose(RandomJoints(rng)));
    for (int a = 0; a < ik.count; ++a) {
      for (int b = a + 1; b < ik.count; ++b) {
        double diff = 0;
        for (int i = 0; i < 6; ++i)
          diff = std::fmax(diff, std::abs(std::remainder(ik.solutions[a].q[i] - ik.solutions[b].q[i], 2 * M_PI)));
        ASSERT_GT(diff, 1e-7);
      }
    }
  }
}

TEST(Ur5Ik, WristSingularPinsQ6) {
  for (const double q5 : {0.0, M_PI, -M_PI}) {
    const Joints q = (Joints() << 0.4, -1.2, 1.1, -0.8, q5, 0.7).finished();
    const Eigen::Isometry3d X = FlangePose(q);
    const double q6_current = -0.3;
    const IkResult ik = SolveIk(X, q6_current);
    ASSERT_EQ(ik.status, IkStatus::kOk);
    // The singularity belongs to the original shoulder branch; the other branch is regular.
    int singular = 0;
    for (int k = 0; k < ik.count; ++k) {
      const IkSolution& s = ik.solutions[k];
      EXPECT_EQ(s.wrist_singular, std::abs(std::sin(s.q[4])) < 1e-6);
      if (!s.wrist_singular) continue;
      ++singular;
      EXPECT_NEAR(s.q[5], q6_current, 1e-12);
      // Only q4 + q6 is defined: the original's sum is kept.
      if (std::abs(std::remainder(s.q[0] - q[0], 2 * M_PI)) < 1e-9 &&
          std::abs(std::remainder(s.q[2] - q[2], 2 * M_PI)) < 1e-9) {
        EXPECT_NEAR(std::remainder(s.q[3] + s.q[5] - q[3] - q[5], 2 * M_PI), 0.0, 1e-9);
      }
    }
    EXPECT_EQ(singular, 2);             // elbow up and down; the two wrist branches coincide
    ExpectAllReproduce(ik, X, kTight);  // exactly singular: pinning loses nothing
  }
}

// Near the singularity, outside the band, solutions are exact; inside it, errors stay small and
// bounded (measured here, documented in IkOptions).
TEST(Ur5Ik, WristNearSingularStaysAccurate) {
  for (const double s5 : {1e-3, 1e-4, 1e-5}) {
    const Joints q = (Joints() << 0.4, -1.2, 1.1, -0.8, std::asin(s5), 0.7).finished();
    const Eigen::Isometry3d X = FlangePose(q);
    const IkResult ik = SolveIk(X, 0.0);
    ASSERT_EQ(ik.status, IkStatus::kOk) << s5;
    ExpectAllReproduce(ik, X, 1e-9);
    EXPECT_TRUE(Contains(ik, q, 1e-6)) << s5;
  }
  for (const double s5 : {1e-7, 1e-8, 1e-10}) {
    const Joints q = (Joints() << 0.4, -1.2, 1.1, -0.8, std::asin(s5), 0.7).finished();
    const Eigen::Isometry3d X = FlangePose(q);
    const IkResult ik = SolveIk(X, 2.0);
    ASSERT_EQ(ik.status, IkStatus::kOk) << s5;
    ExpectAllReproduce(ik, X, 1e-6);
  }
}

TEST(Ur5Ik, ElbowStraight) {
  const Joints q = (Joints() << 0.3, -0.5, 0.0, -1.0, 1.2, 0.4).finished();
  const Eigen::Isometry3d X = FlangePose(q);
  const IkResult ik = SolveIk(X, q[5]);
  ASSERT_EQ(ik.status, IkStatus::kOk);
  ExpectAllReproduce(ik, X, 1e-7);
  EXPECT_TRUE(Contains(ik, q, 1e-6));
  EXPECT_LE(ik.count, 4);  // the elbow branches coincide
}

TEST(Ur5Ik, ShoulderColumnIsUnreachable) {
  // Wrist centre on the base axis: q1 is undefined.
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = RotationFromRpy(M_PI, 0, 0);  // tool down
  X.translation() << 0.0, 0.05, 0.4 - 0.0823;
  const IkResult ik = SolveIk(X);
  EXPECT_EQ(ik.status, IkStatus::kUnreachable);
  EXPECT_EQ(ik.count, 0);
}

TEST(Ur5Ik, OutOfReachIsUnreachable) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << 1.2, 0.3, 0.2;
  EXPECT_EQ(SolveIk(X).status, IkStatus::kUnreachable);
  X.translation() << 0, 0, 1.5;
  EXPECT_EQ(SolveIk(X).status, IkStatus::kUnreachable);
}

TEST(Ur5Ik, NonFiniteInputIsUnreachableNotNaN) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() << std::nan(""), 0.2, 0.3;
  EXPECT_EQ(SolveIk(X).status, IkStatus::kUnreachable);
  X.translation() << 0.4, 0.2, 0.3;
  X.linear()(0, 0) = std::numeric_limits<double>::infinity();
  EXPECT_EQ(SolveIk(X).status, IkStatus::kUnreachable);
}

TEST(Ur5Ik, TcpIkReachesTheTcpPose) {
  const Joints q = (Joints() << 0.2, -1.4, 1.6, -1.8, -1.57, 0.3).finished();
  const IkResult ik = SolveTcpIk(TcpPose(q), q[5]);
  ASSERT_EQ(ik.status, IkStatus::kOk);
  EXPECT_TRUE(Contains(ik, q, 1e-7));
}

TEST(IkSelection, NearestCopyIs2PiAwareAndInsideLimits) {
  const Joints q_current = (Joints() << 6.0, -1.0, 1.0, -1.5, -1.5, -6.0).finished();
  const Joints q = (Joints() << -0.2, -1.1, 1.1, -1.4, -1.6, 0.2).finished();
  Joints out;
  ASSERT_TRUE(NearestCopyWithinLimits(q, q_current, Ur5JointLimits(), out));
  EXPECT_NEAR(out[0], -0.2 + 2 * M_PI, 1e-12);
  EXPECT_NEAR(out[5], 0.2 - 2 * M_PI, 1e-12);
  EXPECT_NEAR(out[1], -1.1, 1e-12);
  // The elbow is limited to +-pi: a copy beyond it is not taken.
  const Joints elbow_far = (Joints() << 0, 0, 3.0, 0, 0, 0).finished();
  const Joints current_far = (Joints() << 0, 0, 3.1, 0, 0, 0).finished();
  ASSERT_TRUE(NearestCopyWithinLimits(elbow_far, current_far, Ur5JointLimits(), out));
  EXPECT_NEAR(out[2], 3.0, 1e-12);
}

TEST(IkSelection, PicksTheSolutionNearestToTheCurrentJoints) {
  std::mt19937_64 rng(11);
  int selected = 0;
  for (int n = 0; n < 500; ++n) {
    const Joints q = RandomJoints(rng);
    if (!LinksAboveTable(q, 0.06)) continue;
    const IkResult ik = SolveIk(FlangePose(q), q[5]);
    Joints near = q;
    near[0] += 0.01;
    const auto chosen = SelectNearest(ik, near);
    ASSERT_TRUE(chosen.has_value());
    EXPECT_LT((chosen->q - q).norm(), 1e-7);
    ++selected;
  }
  EXPECT_GT(selected, 50);
}

// The selection checks the links nearest solution first; it picks what a scan of every solution for the
// strictly nearest one whose links clear the table picks (the lower index among equally near ones).
TEST(IkSelection, ChoosesAsAScanOfEverySolutionWould) {
  std::mt19937_64 rng(12);
  int compared = 0, below = 0;
  for (int n = 0; n < 2000; ++n) {
    const Joints target = RandomJoints(rng), current = RandomJoints(rng);
    const IkResult ik = SolveIk(FlangePose(target), target[5]);
    std::optional<SelectedSolution> scan;
    double scan_distance = 0;
    for (int k = 0; k < ik.count; ++k) {
      Joints q;
      if (!NearestCopyWithinLimits(ik.solutions[k].q, current, Ur5JointLimits(), q)) continue;
      if (!LinksAboveTable(q, 0.06)) {
        ++below;
        continue;
      }
      if (!scan || (q - current).norm() < scan_distance) {
        scan = SelectedSolution{k, q};
        scan_distance = (q - current).norm();
      }
    }
    const auto chosen = SelectNearest(ik, current);
    ASSERT_EQ(chosen.has_value(), scan.has_value()) << n;
    if (!chosen) continue;
    EXPECT_EQ(chosen->index, scan->index) << n;
    EXPECT_EQ(chosen->q, scan->q) << n;
    ++compared;
  }
  EXPECT_GT(compared, 1000);
  EXPECT_GT(below, 500) << "solutions through the table were met and passed over";
  // Equally near: the lower index, as the scan's strict comparison keeps the first.
  const Joints q = (Joints() << 0.3, -1.2, 1.1, -1.4, -1.5, 0.2).finished();
  ASSERT_TRUE(LinksAboveTable(q, 0.06));
  IkResult twins;
  twins.count = 3;
  twins.solutions[0].q = q + Joints::Constant(0.2);  // Farther.
  twins.solutions[1].q = q;
  twins.solutions[2].q = q;
  const auto chosen = SelectNearest(twins, q);
  ASSERT_TRUE(chosen.has_value());
  EXPECT_EQ(chosen->index, 1);
}

TEST(IkSelection, RejectsLinksBelowTheTable) {
  // The elbow folded down through the table.
  const Joints q = (Joints() << 0, 0.6, -1.2, 0, 1.0, 0).finished();
  ASSERT_FALSE(LinksAboveTable(q, 0.06));
  const IkResult ik = SolveIk(FlangePose(q), q[5]);
  const auto chosen = SelectNearest(ik, q);
  if (chosen) {
    EXPECT_TRUE(LinksAboveTable(chosen->q, 0.06));
  }
  EXPECT_FALSE(chosen && (chosen->q - q).norm() < 1e-6);
}

}  // namespace
}  // namespace sortcell::robot
