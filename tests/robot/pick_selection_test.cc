#include <gtest/gtest.h>

#include "error_of.h"
#include "robot/pick_selection.h"

namespace sortcell::robot {
namespace {

ObjectFootprint At(double x, double y, double width = 0.06) {
  ObjectFootprint f;
  f.centre_xy = Eigen::Vector2d(x, y);
  f.width = width;
  f.top_z = 0.1;
  return f;
}

TEST(PickSelection, ChoosesTheObjectWithTheMostRoom) {
  // Two close together, one apart: the lone one first.
  const std::vector<ObjectFootprint> c{At(0.4, 0.0), At(0.48, 0.0), At(0.6, 0.2)};
  EXPECT_EQ(ChooseNextPick(c, PickMemory()), 2);
  EXPECT_EQ(ChooseNextPick({At(0.5, 0.1)}, PickMemory()), 0);
  EXPECT_EQ(ChooseNextPick({}, PickMemory()), -1);
}

TEST(PickSelection, SkippedPositionsAreNotChosenAgainEvenWhenNudged) {
  const std::vector<ObjectFootprint> c{At(0.4, 0.0), At(0.6, 0.2)};
  PickMemory memory;
  memory.Skip(Eigen::Vector2d(0.6, 0.2), SkipReason::kUnreachable);
  EXPECT_EQ(ChooseNextPick(c, memory), 0);
  EXPECT_EQ(memory.Skipped(Eigen::Vector2d(0.61, 0.21)), SkipReason::kUnreachable);
  memory.Skip(Eigen::Vector2d(0.405, 0.0), SkipReason::kUnreachable);
  EXPECT_EQ(ChooseNextPick(c, memory), -1);
}

TEST(PickSelection, GivesUpAPositionAfterMaxAttempts) {
  PickMemory memory(0.04, 3);
  const Eigen::Vector2d p(0.5, 0.0);
  EXPECT_EQ(memory.RecordAttempt(p), 1);
  EXPECT_EQ(memory.RecordAttempt(p + Eigen::Vector2d(0.01, 0)), 2);  // Nudged by the missed grasp.
  EXPECT_EQ(memory.Skipped(p), SkipReason::kNone);
  EXPECT_EQ(memory.RecordAttempt(p + Eigen::Vector2d(0.02, 0)), 3);
  EXPECT_EQ(memory.Skipped(p + Eigen::Vector2d(0.02, 0)), SkipReason::kGraspFailed);
  // Another object elsewhere is untouched.
  EXPECT_EQ(memory.Attempts(Eigen::Vector2d(0.3, 0.2)), 0);
}

// Two bottles side by side along x, 7 cm apart (touching gaps of 1 cm): closing along x puts a finger
// on the neighbour, closing along y keeps both fingers clear.
TEST(PickSelection, ARoundObjectIsPinchedFromTheSideItsNeighbourLeavesFree) {
  ObjectFootprint bottle = At(0.5, 0.0);
  bottle.width = 0.062;
  bottle.pinch_yaw = 0.0;
  Neighbours neighbours;
  const Eigen::Vector2d other(0.57, 0.0);
  neighbours.discs.emplace_back(other, 0.031);
  for (int k = 0; k < 36; ++k) {
    const double a = k * M_PI / 18;
    neighbours.p_xy.push_back(other + 0.031 * Eigen::Vector2d(std::cos(a), std::sin(a)));
  }
  const double open_gap = 0.062 + 2 * 0.008;
  EXPECT_LT(FingerClearance(bottle.centre_xy, 0.0, open_gap, neighbours), 0.0);
  const ClearGrasp grasp = ClearestGrasp(RoundWays(bottle), 0.008, neighbours);
  const double yaw = grasp.footprint.pinch_yaw;
  EXPECT_NEAR(std::abs(std::cos(yaw)), 0.0, 1e-9) << yaw;
  EXPECT_GT(FingerClearance(bottle.centre_xy, yaw, open_gap, neighbours), 0.0);
  EXPECT_DOUBLE_EQ(grasp.clearance, FingerClearance(bottle.centre_xy, yaw, open_gap, neighbours));
}

TEST(PickSelection, APinchThatIsClearAlreadyIsKept) {
  ObjectFootprint bottle = At(0.5, 0.0);
  bottle.width = 0.062;
  bottle.pinch_yaw = 0.3;
  EXPECT_DOUBLE_EQ(ClearestGrasp(RoundWays(bottle), 0.008, Neighbours{}).footprint.pinch_yaw, 0.3);
  Neighbours far;
  far.discs.emplace_back(Eigen::Vector2d(0.7, 0.0), 0.03);
  EXPECT_DOUBLE_EQ(ClearestGrasp(RoundWays(bottle), 0.008, far).footprint.pinch_yaw, 0.3);
  // The finger reaches 3 cm beyond its pad and 2 cm to either side.
  EXPECT_NEAR(FingerClearance(bottle.centre_xy, 0.0, 0.078, far), 0.2 - 0.03 - 0.039 - 0.03, 1e-9);
}

// A box between two neighbours along its pinch direction: its turned grasp (across its other sides)
// is the free one; with neighbours all round, the one that clears them most is returned.
TEST(PickSelection, ABlockedPrismIsPinchedTheOtherWay) {
  ObjectFootprint box = At(0.5, 0.0);
  box.width = 0.06;
  box.pinch_yaw = 0.0;
  ObjectFootprint turned = box;
  turned.width = 0.09;
  turned.pinch_yaw = M_PI / 2;
  Neighbours neighbours;
  for (const double x : {0.44, 0.56}) neighbours.p_xy.emplace_back(x, 0.0);
  const ClearGrasp grasp = ClearestGrasp({box, turned}, 0.008, neighbours);
  EXPECT_DOUBLE_EQ(grasp.footprint.pinch_yaw, M_PI / 2);
  EXPECT_GE(grasp.clearance, 0.015);
  for (const double y : {-0.06, 0.06}) neighbours.p_xy.emplace_back(0.5, y);
  EXPECT_LT(ClearestGrasp({box, turned}, 0.008, neighbours).clearance, 0.015);
  EXPECT_THROW(ClearestGrasp({}, 0.008, neighbours), std::invalid_argument);
  EXPECT_THROW(ClearestGrasp({box, turned}, std::vector<double>{0.008}, neighbours), std::invalid_argument);
}

TEST(PickSelection, RejectsBadMemoryParameters) {
  EXPECT_NE(sortcell_test::ErrorOf([] { PickMemory(0.0, 3); }).find("radius > 0"), std::string::npos);
  EXPECT_NE(sortcell_test::ErrorOf([] { PickMemory(0.04, 0); }).find("max_attempts >= 1"), std::string::npos);
}

}  // namespace
}  // namespace sortcell::robot
