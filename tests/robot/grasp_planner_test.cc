// The grasp planner's clearances (unit); its grasps and placements are tested through the pick
// selection (pick_selection_test.cc) and the sorting policy (tests/cell).
#include "robot/grasp_planner.h"

#include <gtest/gtest.h>

#include <vector>

namespace sortcell::robot {
namespace {

// The lift and the placement try their clearances from the highest down in 2 cm steps, none below the
// lowest allowed (which is tried where it lies on a step), and one only where the lowest is the highest.
TEST(GraspPlanner, LiftClearancesGoDownFromTheHighestInTwoCentimetreSteps) {
  GraspOptions options;
  options.lift_clearance = 0.30;
  options.min_lift_clearance = 0.15;
  const std::vector<double> clearances = LiftClearancesHighestFirst(options);
  ASSERT_EQ(clearances.size(), 8u);
  for (size_t k = 0; k < clearances.size(); ++k) EXPECT_NEAR(clearances[k], 0.30 - 0.02 * k, 1e-12);
  options.min_lift_clearance = 0.16;
  EXPECT_EQ(LiftClearancesHighestFirst(options).size(), 8u) << "0.16, on a step, is tried";
  options.lift_clearance = options.min_lift_clearance = 0.123;
  EXPECT_EQ(LiftClearancesHighestFirst(options), std::vector<double>{0.123});
  options.min_lift_clearance = 0.2;
  EXPECT_TRUE(LiftClearancesHighestFirst(options).empty());
}

}  // namespace
}  // namespace sortcell::robot
