// What the robot knows of its bins' contents (unit): seen in a capture, remembered from its own
// releases, and where the next object is let go because of it.
#include "cell/bin_fill.h"

#include <gtest/gtest.h>

#include <vector>

#include "error_of.h"

namespace sortcell::cell {
namespace {

const Eigen::Isometry3d kIdentity = Eigen::Isometry3d::Identity();

// The layout with one bin, 'others', floor at (0.45, -0.48, 0.008), 0.20 m square inside.
CellLayout OneBin() {
  CellLayout layout;
  layout.bins["others"] = Bin{Eigen::Vector3d(0.45, -0.48, 0.008), Eigen::Vector2d(0.10, 0.10)};
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
    const BinRelease r = bins.Upright("others", filled, 0.035, 0.03);
    EXPECT_TRUE(r.p_W_floor.isApprox(BinSlot(layout, "others", filled))) << filled;
    EXPECT_DOUBLE_EQ(r.clearance, 0.03);
    EXPECT_DOUBLE_EQ(r.yaw_step, layout.place_yaw_step);
  }
  const BinRelease lying = bins.Lying("others");
  EXPECT_TRUE(lying.p_W_floor.isApprox(layout.bins.at("others").p_W_floor));
  EXPECT_DOUBLE_EQ(lying.clearance, layout.bin_wall_height + 0.01);
  // Along either diagonal: the held object lies along the TCP's x, (-sin yaw, cos yaw).
  EXPECT_NEAR(std::abs(std::sin(lying.yaw_offset)), std::abs(std::cos(lying.yaw_offset)), 1e-9);
  EXPECT_DOUBLE_EQ(lying.yaw_step, M_PI / 2);
}

TEST(BinFill, OnlyASlotTheArmCanLetGoInIsChosenWhileThereIsOne) {
  const CellLayout layout = OneBin();
  const BinFill bins(layout);
  // The slot in the layout's order (slot 1) out of the arm's reach: the next in the order that is not.
  const Eigen::Vector3d out_of_reach = BinSlot(layout, "others", 1);
  const auto placeable = [&](const BinRelease& r) { return !r.p_W_floor.isApprox(out_of_reach); };
  EXPECT_TRUE(bins.Upright("others", 1, 0.035, 0.03, placeable).p_W_floor.isApprox(BinSlot(layout, "others", 2)));
  EXPECT_TRUE(bins.Upright("others", 0, 0.035, 0.03, placeable).p_W_floor.isApprox(BinSlot(layout, "others", 0)));
  // None is: the choice as if every slot were (the pick then puts the object back).
  const auto none = [](const BinRelease&) { return false; };
  EXPECT_TRUE(bins.Upright("others", 1, 0.035, 0.03, none).p_W_floor.isApprox(out_of_reach));
  EXPECT_DOUBLE_EQ(bins.Upright("others", 1, 0.035, 0.03, none).clearance, 0.03);
}

TEST(BinFill, ThePlaceabilityIsJudgedAtTheClearanceAboveWhatIsInTheSlot) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  perception::Cloud cloud;
  AddBlock(cloud, {0.36, -0.57, 0.05}, {0.40, -0.53, 0.078});  // 7 cm high in slot 0's corner.
  bins.See(cloud, kIdentity, {});
  // Only slot 0 is placeable: it is chosen, let go above the box, and judged at that clearance.
  std::vector<double> judged_at;
  const auto only_slot0 = [&](const BinRelease& r) {
    const bool slot0 = r.p_W_floor.isApprox(BinSlot(layout, "others", 0));
    if (slot0) judged_at.push_back(r.clearance);
    return slot0;
  };
  const BinRelease release = bins.Upright("others", 0, 0.035, 0.03, only_slot0);
  EXPECT_TRUE(release.p_W_floor.isApprox(BinSlot(layout, "others", 0)));
  EXPECT_GT(release.clearance, 0.06);
  ASSERT_EQ(judged_at.size(), 1u);
  EXPECT_DOUBLE_EQ(judged_at[0], release.clearance);
}

TEST(BinFill, AnObjectSeenInTheBinIsNotLetGoOnto) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  // A box 7 cm high in the (-x, -y) corner (slot 0), clear of the middle.
  perception::Cloud cloud;
  AddBlock(cloud, {0.36, -0.57, 0.05}, {0.40, -0.53, 0.078});
  bins.See(cloud, kIdentity, {});
  const BinRelease first = bins.Upright("others", 0, 0.035, 0.03);
  EXPECT_TRUE(first.p_W_floor.isApprox(BinSlot(layout, "others", 1)));  // The next slot, empty.
  EXPECT_DOUBLE_EQ(first.clearance, 0.03);
  // A lying object is let go above the walls, higher than the box.
  const BinRelease lying = bins.Lying("others");
  EXPECT_DOUBLE_EQ(lying.clearance, layout.bin_wall_height + 0.01);
  // Along the box's diagonal it would lie on the box.
  BinRelease on_box = lying;
  on_box.from = {-0.055, -0.055};
  on_box.to = {0.055, 0.055};
  EXPECT_NEAR(bins.HighestUnder("others", on_box), 0.075 - 0.008, 0.003);
}

TEST(BinFill, AFullBinIsLetGoIntoAboveWhatIsThere) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  perception::Cloud cloud;
  AddBlock(cloud, {0.37, -0.56, 0.10}, {0.53, -0.40, 0.128});  // 12 cm everywhere inside.
  bins.See(cloud, kIdentity, {});
  const BinRelease upright = bins.Upright("others", 2, 0.035, 0.03);
  EXPECT_TRUE(upright.p_W_floor.isApprox(BinSlot(layout, "others", 2)));  // All equal: the layout's order.
  EXPECT_NEAR(upright.clearance, 0.125 - 0.008 + 0.015, 1e-6);
  EXPECT_NEAR(bins.Lying("others").clearance, 0.125 - 0.008 + 0.015, 1e-6);
}

TEST(BinFill, StrayPointsTheWallsAndTheArmAreNotContents) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  perception::Cloud cloud;
  AddBlock(cloud, {0.40, -0.53, 0.10}, {0.40, -0.525, 0.10});   // 2 points: stray pixels.
  AddBlock(cloud, {0.545, -0.58, 0.05}, {0.555, -0.38, 0.10});  // the near wall
  AddBlock(cloud, {0.38, -0.55, 0.20}, {0.52, -0.41, 0.25});    // the gripper above the bin
  const CapsuleList arm{{{0.45, -0.48, 0.20}, {0.45, -0.48, 0.40}, 0.10}};
  bins.See(cloud, kIdentity, arm);
  EXPECT_DOUBLE_EQ(bins.Upright("others", 0, 0.035, 0.03).clearance, 0.03);
  BinRelease everywhere;
  everywhere.half_width = 1;
  EXPECT_DOUBLE_EQ(bins.HighestUnder("others", everywhere), 0.0);
}

TEST(BinFill, ReleasesAreRememberedUntilACaptureSeesThere) {
  const CellLayout layout = OneBin();
  BinFill bins(layout);
  const BinRelease first = bins.Upright("others", 0, 0.035, 0.03);
  bins.Released("others", first, 0.22);  // A bottle stood in slot 0.
  EXPECT_DOUBLE_EQ(bins.HighestUnder("others", first), 0.22);
  bins.See(perception::Cloud(), kIdentity, {});  // Hidden this time: still there.
  EXPECT_DOUBLE_EQ(bins.HighestUnder("others", first), 0.22);
  {
    BinFill seen = bins;  // Seen there: it fell over, the slot's floor shows.
    perception::Cloud floor;
    AddBlock(floor, {0.37, -0.56, 0.008}, {0.45, -0.48, 0.008});
    seen.See(floor, kIdentity, {});
    EXPECT_DOUBLE_EQ(seen.HighestUnder("others", first), 0.0);
  }
  EXPECT_TRUE(bins.Upright("others", 0, 0.035, 0.03).p_W_floor.isApprox(BinSlot(layout, "others", 1)));
  // A lying object goes along the other diagonal (the bottle stands on this one's end), let go just
  // above the walls, and may then lie anywhere in the bin.
  const BinRelease lying = bins.Lying("others");
  EXPECT_DOUBLE_EQ(lying.clearance, layout.bin_wall_height + 0.01);
  EXPECT_DOUBLE_EQ(lying.yaw_step, M_PI);
  const Eigen::Vector2d along(-std::sin(lying.yaw_offset), std::cos(lying.yaw_offset));
  EXPECT_NEAR(std::abs(along.x() + along.y()), 0, 1e-9) << "along the diagonal from (-x, +y) to (+x, -y)";
  bins.Released("others", lying, 0.07);
  EXPECT_DOUBLE_EQ(bins.Upright("others", 1, 0.035, 0.03).clearance, 0.22 + 0.07 + 0.015);
}

TEST(BinFill, MisuseIsNamed) {
  CellLayout layout = OneBin();
  const BinFill bins(layout);
  EXPECT_EQ(sortcell_test::ErrorOf([&] { bins.Upright("plate", 0, 0.035, 0.03); }), "cell layout: no bin 'plate'");
  EXPECT_EQ(sortcell_test::ErrorOf([&] { bins.Lying("plate"); }), "cell layout: no bin 'plate'");
  layout.bin_slots.clear();
  const BinFill no_slots(layout);
  EXPECT_EQ(sortcell_test::ErrorOf([&] { no_slots.Upright("others", 0, 0.035, 0.03); }), "cell layout: no bin slots");
}

}  // namespace
}  // namespace sortcell::cell
