// The pick choice (cell/pick_choice.h) on hand-made detections: the object with the most room first, a
// partly hidden one and an undescribed one waiting or never picked, one out of reach given up and said.
#include "cell/pick_choice.h"

#include <gtest/gtest.h>

#include "cell/cell_layout.h"

namespace sortcell::cell {
namespace {

// A described 6 cm upright object standing on the table (z 0) at (x, y), its outline seen as its centre.
Detection Standing(double x, double y) {
  Detection d;
  d.footprint.centre_xy = Eigen::Vector2d(x, y);
  d.footprint.top_z = 0.1;
  d.footprint.width = 0.06;
  d.p_W_xy = {d.footprint.centre_xy};
  d.p_W_z = {0.1};
  d.category = "cup";
  return d;
}

const robot::Joints kObserve = CellLayout().q_observe;

TEST(PickChoice, TheObjectWithTheMostRoomFirstWithAPlan) {
  robot::PickMemory memory;
  const PickChoice choice =
      ChoosePick({Standing(0.45, 0.0), Standing(0.55, 0.0), Standing(0.6, 0.25)}, memory, FixedObstacles{}, kObserve);
  EXPECT_EQ(choice.detection, 2);
  EXPECT_EQ(choice.plan.status, robot::GraspStatus::kOk);
  EXPECT_TRUE(choice.unplannable.empty());
}

TEST(PickChoice, AHiddenObjectWaitsAndAnUndescribedOneIsNeverPicked) {
  std::vector<Detection> seen{Standing(0.45, -0.2), Standing(0.6, 0.2)};
  seen[0].occluded = true;
  seen[1].category.reset();
  robot::PickMemory memory;
  EXPECT_EQ(ChoosePick(seen, memory, FixedObstacles{}, kObserve).detection, 0) << "the hidden one, as nothing else is";
  seen[0].category.reset();
  EXPECT_EQ(ChoosePick(seen, memory, FixedObstacles{}, kObserve).detection, -1);
  seen[0].occluded = false;
  seen.push_back(Standing(0.4, 0.0));
  seen.back().occluded = true;
  seen.push_back(Standing(0.7, -0.1));
  EXPECT_EQ(ChoosePick(seen, memory, FixedObstacles{}, kObserve).detection, 3) << "the unhidden one first";
}

TEST(PickChoice, AnObjectOutOfReachIsGivenUpAndSaid) {
  robot::PickMemory memory;
  const PickChoice choice = ChoosePick({Standing(2.0, 0.0), Standing(0.5, 0.1)}, memory, FixedObstacles{}, kObserve);
  EXPECT_EQ(choice.detection, 1);
  ASSERT_EQ(choice.unplannable.size(), 1u);
  EXPECT_EQ(choice.unplannable[0].first, 0);
  EXPECT_EQ(choice.unplannable[0].second, robot::GraspStatus::kUnreachable);
  EXPECT_EQ(memory.Skipped(Eigen::Vector2d(2.0, 0.0)), robot::SkipReason::kUnreachable);
}

TEST(PickChoice, FingersThatWouldLandOnABinWallWaitForAFreeObject) {
  // A bin wall where a finger of the first would come down (it closes along x); the second stands free.
  FixedObstacles walls{{Eigen::Vector2d(0.49, 0.0)}, 0.1};
  robot::PickMemory memory;
  const std::vector<Detection> seen{Standing(0.45, 0.0), Standing(0.6, 0.2)};
  EXPECT_EQ(ChoosePick(seen, memory, FixedObstacles{}, kObserve).detection, 0) << "as much room: the first";
  EXPECT_EQ(ChoosePick(seen, memory, walls, kObserve).detection, 1);
}

}  // namespace
}  // namespace sortcell::cell
