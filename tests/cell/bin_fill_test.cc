// What the robot knows of its bins' contents (unit): seen in a capture, remembered from its own
// releases, and where the next object is let go because of it.
#include "cell/bin_fill.h"

#include <gtest/gtest.h>

#include "error_of.h"

namespace sortcell::cell {
namespace {

const Eigen::Isometry3d kIdentity = Eigen::Isometry3d::Identity();

// The layout with one bin, 'others', floor at (0.45, -0.48, 0.008).
CellLayout OneBin() {
  CellLayout layout;
  layout.p_W_bin = {{"others", Eigen::Vector3d(0.45, -0.48, 0.008)}};
  return layout;
}

// A block of points (world frame, here the camera frame too) filling [lo, hi] every 5 mm.
void AddBlock(perception::Cloud& cloud, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  for (double x = lo.x(); x <= hi.x() + 1e-9; x += 0.005) {
    for (double y = lo.y(); y <= hi.y() + 1e-9; y += 0.005) {
      for (double z = lo.z(); z <= hi.z() + 1e-9; z += 0.005) {
        perception::PointT p;
        p.x = static_cast<float>(x);
        p.y = static_cast<float>(y);
        p.z = static_cast<float>(z);
        cloud.push_back(p);
      }
    }
  }
}

TEST(BinFill, EmptyBinsTakeTheSlotsInOrderAndLyingObjectsAboveTheWalls) {
  const CellLayout layout = OneBin();
  const BinFill bins(layout);
  for (int filled = 0; filled < 7; ++filled) {
    const BinRelease r = bins.Upright("others", filled, 0.03);
    EXPECT_TRUE(r.p_W_floor.isApprox(BinSlot(layout, "others", filled))) << filled;
    EXPECT_DOUBLE_EQ(r.clearance, 0.03);
    EXPECT_DOUBLE_EQ(r.yaw_step, layout.place_yaw_step);
  }
  const BinRelease lying = bins.Lying("others");
  EXPECT_TRUE(lying.p_W_floor.isApprox(layout.p_W_bin.at("others")));
  EXPECT_DOUBLE_EQ(lying.clearance, layout.bin_wall_height + 0.01);
  // Along the rising diagonal (1, 1): the held object lies along the TCP's x, (-sin yaw, cos yaw).
  EXPECT_NEAR(-std::sin(lying.yaw_offset), std::cos(lying.yaw_offset), 1e-9);
  EXPECT_DOUBLE_EQ(lying.yaw_step, M_PI);
  EXPECT_EQ(lying.slots, (std::vector<int>{0, 1, 4}));
}

TEST(BinFill, AnObjectSeenInTheBinIsNotLetGoOnto) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  // A box 7 cm high in the (-x, -y) quadrant (slot 0) and the middle's corner of it.
  perception::Cloud cloud;
  AddBlock(cloud, {0.36, -0.57, 0.05}, {0.44, -0.49, 0.078});
  bins.See(cloud, kIdentity, {});
  EXPECT_NEAR(bins.Heights("others")[0], 0.07, 0.006);
  EXPECT_DOUBLE_EQ(bins.Heights("others")[1], 0.0);
  // The first slot is taken: the next one free (slot 1), at the usual height.
  const BinRelease upright = bins.Upright("others", 0, 0.03);
  EXPECT_EQ(upright.slots, std::vector<int>{1});
  EXPECT_DOUBLE_EQ(upright.clearance, 0.03);
  // A lying object goes along the other diagonal, which the box does not reach.
  const BinRelease lying = bins.Lying("others");
  EXPECT_EQ(lying.slots, (std::vector<int>{2, 3, 4}));
  EXPECT_NEAR(-std::sin(lying.yaw_offset), -std::cos(lying.yaw_offset), 1e-9);
}

TEST(BinFill, AFullBinIsLetGoIntoAboveWhatIsThere) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  perception::Cloud cloud;
  AddBlock(cloud, {0.37, -0.56, 0.10}, {0.53, -0.40, 0.128});  // 12 cm everywhere inside.
  bins.See(cloud, kIdentity, {});
  const BinRelease upright = bins.Upright("others", 2, 0.03);
  EXPECT_EQ(upright.slots, std::vector<int>{2});  // All equal: the layout's order.
  EXPECT_NEAR(upright.clearance, 0.12 + 0.015, 0.006);
  EXPECT_NEAR(bins.Lying("others").clearance, 0.12 + 0.015, 0.006);
}

TEST(BinFill, StrayPointsTheWallsAndTheArmAreNotContents) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  perception::Cloud cloud;
  AddBlock(cloud, {0.40, -0.53, 0.10}, {0.40, -0.525, 0.105});  // 4 points: a few stray pixels.
  AddBlock(cloud, {0.545, -0.58, 0.05}, {0.555, -0.38, 0.10});    // the near wall
  AddBlock(cloud, {0.38, -0.55, 0.20}, {0.52, -0.41, 0.25});      // the gripper above the bin
  const std::vector<Capsule> arm{{{0.45, -0.48, 0.20}, {0.45, -0.48, 0.40}, 0.10}};
  bins.See(cloud, kIdentity, arm);
  for (const double h : bins.Heights("others")) EXPECT_DOUBLE_EQ(h, 0.0);
}

TEST(BinFill, ReleasesAreRememberedAndACaptureNeverLowersASlot) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  const BinRelease first = bins.Upright("others", 0, 0.03);
  bins.Released("others", first, 0.22);  // A bottle stood in slot 0.
  EXPECT_DOUBLE_EQ(bins.Heights("others")[0], 0.25);
  bins.See(perception::Cloud(), kIdentity, {});  // Hidden this time: still there.
  EXPECT_DOUBLE_EQ(bins.Heights("others")[0], 0.25);
  EXPECT_EQ(bins.Upright("others", 0, 0.03).slots, std::vector<int>{1});
}

TEST(BinFill, MisuseIsNamed) {
  CellLayout layout = OneBin();
  const BinFill bins(layout);
  EXPECT_EQ(sortcell_test::ErrorOf([&] { bins.Upright("plate", 0, 0.03); }), "cell layout: no bin for category 'plate'");
  layout.bin_slots.clear();
  EXPECT_EQ(sortcell_test::ErrorOf([&] { BinFill{layout}; }), "BinFill: the cell layout has no bin slots");
}

}  // namespace
}  // namespace sortcell::cell
