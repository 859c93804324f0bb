#include "cell/carry_clearance.h"

#include <gtest/gtest.h>

#include <limits>
#include <stdexcept>

#include "cell/cell_layout.h"
#include "robot/ur5_kinematics.h"

namespace sortcell::cell {
namespace {

// One sample: the arm at its observe pose, the TCP at (0.281, 0.109, 0.446).
robot::JointTrajectory AtObservePose() {
  robot::JointTrajectory t;
  t.q = {CellLayout().q_observe};
  t.qd = t.qdd = {robot::Joints::Zero()};
  return t;
}

TEST(CarryClearance, TheBottomAboveTheHighestTopItComesOver) {
  const robot::JointTrajectory t = AtObservePose();
  const Eigen::Vector3d p_WT = robot::TcpPose(t.q[0]).translation();
  const HeldObject held{0.10, 0.04};  // Its bottom 0.10 below the TCP, 4 cm across from the axis.
  CarryObstacles over;
  // Under it (0.05 off, within its reach and the disc's radius), 0.20 high; 0.30 high but 0.20 away.
  over.discs.push_back({p_WT.head<2>() + Eigen::Vector2d(0.05, 0), 0.03, 0.20});
  over.discs.push_back({p_WT.head<2>() + Eigen::Vector2d(0, 0.20), 0.03, 0.30});
  EXPECT_NEAR(LeastClearanceOver(t, {held}, over, 0.02), p_WT.z() - 0.10 - 0.20, 1e-12);
  // A bin whose outline comes within 1.5 cm of the held object's reach, its top 0.25 high.
  over.boxes.push_back(
      {p_WT.head<2>() + Eigen::Vector2d(0.055, -0.1), p_WT.head<2>() + Eigen::Vector2d(0.3, 0.1), 0.25});
  EXPECT_NEAR(LeastClearanceOver(t, {held}, over, 0.02), p_WT.z() - 0.10 - 0.25, 1e-12);
  // Not within the reach widened by 1 cm: the disc alone counts.
  EXPECT_NEAR(LeastClearanceOver(t, {held}, over, 0.01), p_WT.z() - 0.10 - 0.20, 1e-12);
}

TEST(CarryClearance, EachPartByItsOwnLowestPointAndReach) {
  const robot::JointTrajectory t = AtObservePose();
  const Eigen::Vector3d p_WT = robot::TcpPose(t.q[0]).translation();
  CarryObstacles over;
  over.discs.push_back({p_WT.head<2>() + Eigen::Vector2d(0.09, 0), 0.01, 0.20});  // 9 cm out: 8 cm to its edge.
  // A held object reaching 4 cm from the axis does not come over it (4 + 2 < 8 cm); a palm reaching
  // 8.8 cm out, 8 cm above the TCP, does.
  const HeldObject held{0.10, 0.04}, palm{-0.08, 0.088};
  EXPECT_EQ(LeastClearanceOver(t, {held}, over, 0.02), std::numeric_limits<double>::infinity());
  EXPECT_NEAR(LeastClearanceOver(t, {held, palm}, over, 0.02), p_WT.z() + 0.08 - 0.20, 1e-12);
}

TEST(CarryClearance, OnAPlumbLineNothingIsPassedOver) {
  const robot::JointTrajectory t = AtObservePose();
  const Eigen::Vector2d p_xy = robot::TcpPose(t.q[0]).translation().head<2>();
  CarryObstacles over;
  over.discs.push_back({p_xy + Eigen::Vector2d(0.05, 0), 0.03, 0.40});  // Above the TCP: passed 'under'.
  const HeldObject held{0.10, 0.04};
  EXPECT_LT(LeastClearanceOver(t, {held}, over, 0.02), 0);
  // Straight above where it stood (within kOnPlumbLine): a neighbour is not passed over there.
  EXPECT_EQ(LeastClearanceOver(t, {held}, over, 0.02, {p_xy + Eigen::Vector2d(0.001, 0.001)}),
            std::numeric_limits<double>::infinity());
  EXPECT_LT(LeastClearanceOver(t, {held}, over, 0.02, {p_xy + Eigen::Vector2d(0.003, 0)}), 0);
}

TEST(CarryClearance, NothingUnderItOrNoSampleIsInfinite) {
  const robot::JointTrajectory t = AtObservePose();
  CarryObstacles over;
  over.discs.push_back({Eigen::Vector2d(-1, -1), 0.05, 0.5});
  EXPECT_EQ(LeastClearanceOver(t, {{0.1, 0.04}}, over, 0.02), std::numeric_limits<double>::infinity());
  EXPECT_EQ(LeastClearanceOver(robot::JointTrajectory{}, {{0.1, 0.04}}, over, 0.02),
            std::numeric_limits<double>::infinity());
}

}  // namespace
}  // namespace sortcell::cell
