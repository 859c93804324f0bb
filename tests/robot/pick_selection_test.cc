#include <gtest/gtest.h>

#include "error_of.h"
#include "robot/gripper_geometry.h"
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
  PickMemory memory({0.04, 3});
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
  EXPECT_NE(sortcell_test::ErrorOf([] { PickMemory({0.0, 3}); }).find("same_object_radius > 0"), std::string::npos);
  EXPECT_NE(sortcell_test::ErrorOf([] {
              PickMemory({0.04, 0});
            }).find("max_attempts_per_position >= 1"),
            std::string::npos);
}

// A tall box (0.21 m, 6 x 16 cm, its top seen) beside a can (0.10 m): 9 cm away, under the palm
// when the fingers close towards it, not when they close across; touching the can, under the housing
// whichever way they close, higher than the can's grasp may rise (the pick is not blocked by it: the
// fingers decide); beside a bottle (0.19 m), the grasp rises until the palm clears it.
TEST(PickSelection, TheGrippersBodyKeepsClearOfATallerNeighbour) {
  ObjectFootprint can = At(0.5, 0.0, 0.066);
  can.pinch_yaw = 0.0;
  const auto box_at = [](double x) {  // Its top's points, every centimetre.
    Neighbours n;
    for (int i = -3; i <= 3; ++i) {
      for (int j = -8; j <= 8; ++j) {
        n.p_xy.emplace_back(x + 0.01 * i, 0.01 * j);
        n.p_z.push_back(0.21);
      }
    }
    return n;
  };
  const double clearance = GraspOptions().palm_clearance;
  const Neighbours apart = box_at(0.62);  // Its near side 9 cm from the can's axis.
  EXPECT_NEAR(LowestTcpAboveNeighbours(can.centre_xy, 0.0, apart, 0.01, clearance), 0.21 + clearance - kPalmBeforeTcp,
              1e-12);
  EXPECT_EQ(LowestTcpAboveNeighbours(can.centre_xy, M_PI / 2, apart, 0.01, clearance), -INFINITY);
  Neighbours unknown_height = apart;
  unknown_height.p_z.clear();
  EXPECT_EQ(LowestTcpAboveNeighbours(can.centre_xy, 0.0, unknown_height, 0.01, clearance), -INFINITY);

  // The fingers clear the box (1.9 cm) the way preferred: kept, with the palm's height.
  const ClearGrasp towards = ClearestGrasp(RoundWays(can), 0.008, apart);
  EXPECT_DOUBLE_EQ(towards.footprint.pinch_yaw, 0.0);
  EXPECT_NEAR(towards.clearance, 0.09 - (0.033 + 0.008) - kFingerDepth, 1e-9);
  EXPECT_NEAR(towards.min_tcp_z, 0.21 + clearance - kPalmBeforeTcp, 1e-12);

  // Touching: the housing needs the TCP at 0.21 + 0.015 - 0.113 = 0.112 m, the pads allow 0.08 m, as
  // high as the can's grasp goes.
  const ClearGrasp touching = ClearestGrasp(RoundWays(can), 0.008, box_at(0.57));
  EXPECT_NEAR(touching.min_tcp_z, 0.21 + clearance - kHousingBeforeTcp, 1e-12);
  GraspOptions options;
  options.min_tcp_z = touching.min_tcp_z;
  EXPECT_NEAR(GraspHeight(touching.footprint, options), 0.10 - options.min_pad_overlap, 1e-12);

  ObjectFootprint bottle = can;
  bottle.top_z = 0.19;
  const ClearGrasp raised = ClearestGrasp({bottle}, 0.008, apart);
  EXPECT_GT(raised.clearance, 0.0);
  EXPECT_NEAR(raised.min_tcp_z, 0.21 + clearance - kPalmBeforeTcp, 1e-12);
}

// A can (0.10 m) against the face of a tall box (0.21 m): the box's grasp is high enough for its
// fingers to pass above the can, which does not block it; a can as tall as the finger tips does.
TEST(PickSelection, FingersPassAboveAShorterNeighbour) {
  ObjectFootprint box = At(0.5, 0.0, 0.06);
  box.top_z = 0.21;
  box.pinch_yaw = 0.0;
  const auto can_of = [](double top) {
    Neighbours n;
    n.discs.emplace_back(Eigen::Vector2d(0.565, 0.0), 0.033);
    n.disc_top_z.push_back(top);
    for (int k = 0; k < 12; ++k) {
      n.p_xy.push_back(Eigen::Vector2d(0.565, 0.0) +
                       0.033 * Eigen::Vector2d(std::cos(k * M_PI / 6), std::sin(k * M_PI / 6)));
      n.p_z.push_back(top);
    }
    return n;
  };
  const double tips_z = GraspHeight(box, GraspOptions()) - kFingerTipBeyondTcp;  // 0.125 m.
  EXPECT_LT(FingerClearance(box.centre_xy, 0.0, 0.076, can_of(0.10)), 0.0);
  EXPECT_EQ(FingerClearance(box.centre_xy, 0.0, 0.076, can_of(0.10), tips_z), INFINITY);
  EXPECT_GE(ClearestGrasp({box}, 0.008, can_of(0.10)).clearance, 0.015);
  EXPECT_LT(ClearestGrasp({box}, 0.008, can_of(tips_z)).clearance, 0.0);
}

// The planner raises the grasp to the lowest TCP height the neighbours leave, as far as the pads allow.
TEST(PickSelection, TheGraspRisesAboveATallerNeighbour) {
  ObjectFootprint bottle = At(0.5, 0.0, 0.06);
  bottle.top_z = 0.19;
  const Joints q_observe = (Joints() << 0, -1.9, 1.9, -1.57, -1.57, 0).finished();
  GraspOptions options;
  const GraspPlan free = PlanTopDownGrasp(bottle, q_observe, options);
  ASSERT_EQ(free.status, GraspStatus::kOk);
  EXPECT_NEAR(free.grasp_height, 0.19 - kPalmBeforeTcp + options.palm_clearance, 1e-12);
  options.min_tcp_z = 0.143;
  const GraspPlan raised = PlanTopDownGrasp(bottle, q_observe, options);
  ASSERT_EQ(raised.status, GraspStatus::kOk);
  EXPECT_NEAR(raised.grasp_height, 0.143, 1e-12);
  EXPECT_NEAR(raised.X_WT_grasp.translation().z(), 0.143, 1e-9);
  options.min_tcp_z = 0.40;  // Out of the pads' reach: as high as they allow.
  EXPECT_NEAR(GraspHeight(bottle, options), 0.19 - options.min_pad_overlap, 1e-12);
  EXPECT_NEAR(PlanTopDownGrasp(bottle, q_observe, options).grasp_height, 0.19 - options.min_pad_overlap, 1e-12);
  bottle.full_width_top_z = 0.15;  // Its shoulder: no higher.
  EXPECT_NEAR(GraspHeight(bottle, options), 0.15, 1e-12);
  bottle.full_width_top_z = 0.10;  // Below the grasp without neighbours: that one.
  EXPECT_NEAR(GraspHeight(bottle, options), free.grasp_height, 1e-12);
}

}  // namespace
}  // namespace sortcell::robot
