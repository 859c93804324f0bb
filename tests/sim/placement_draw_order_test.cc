// Same seed, same scene under every compiler: the poses of a dense, a clustered and a sparse scene as the
// GCC Release build draws them. CI runs the unit tests under clang, which evaluates a call's arguments in
// another order than GCC does, so two draws passed as the arguments of one call (as the free spot's x and y
// once were) would move these poses there.
#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "sim/clutter_placement.h"
#include "sim/model.h"
#include "sim/object_placement.h"
#include "sim/object_shape.h"

namespace sortcell::sim {
namespace {

constexpr char kFourObjects[] = R"(<mujoco><worldbody>
  <body name="can"><freejoint/><geom type="cylinder" size="0.03 0.06"/></body>
  <body name="ball"><freejoint/><geom type="sphere" size="0.035"/></body>
  <body name="box"><freejoint/><geom type="box" size="0.02 0.04 0.07"/></body>
  <body name="cup"><freejoint/><geom type="cylinder" size="0.045 0.04"/></body>
</worldbody></mujoco>)";

std::vector<TablePose> Placed(PlacementMode mode, uint64_t seed) {
  const Model model = Model::FromVirtualFiles({{"objects.xml", kFourObjects}}, "four objects");
  std::vector<ObjectShape> shapes;
  for (const char* name : {"can", "ball", "box", "cup"})
    shapes.push_back(ObjectShapeOf(model, model.Id(mjOBJ_BODY, name)));
  PlacementOptions options;
  options.mode = mode;
  options.lying_fraction = 0.5;
  std::mt19937_64 rng(seed);
  const auto poses = SampleClutter(shapes, {}, PlacementArea{}, options, rng);
  EXPECT_TRUE(poses.has_value());
  return poses.value_or(std::vector<TablePose>{});
}

void ExpectPoses(const std::vector<TablePose>& poses, const std::vector<TablePose>& expected) {
  ASSERT_EQ(poses.size(), expected.size());
  for (size_t i = 0; i < poses.size(); ++i) {
    EXPECT_NEAR(poses[i].x, expected[i].x, 1e-12) << "object " << i;
    EXPECT_NEAR(poses[i].y, expected[i].y, 1e-12) << "object " << i;
    EXPECT_NEAR(poses[i].yaw, expected[i].yaw, 1e-12) << "object " << i;
    EXPECT_EQ(poses[i].lying, expected[i].lying) << "object " << i;
  }
}

TEST(PlacementDrawOrder, Dense) {
  ExpectPoses(Placed(PlacementMode::kDense, 7),
              {{0.61737104467762682, -0.14518449404989153, 5.9646353701029691, false},
               {0.56462227625942818, -0.10555132191546743, 4.7484860982529025, false},
               {0.55606323193881391, -0.028518686852349998, 6.2433042223454507, true},
               {0.44255680363448369, 0.021509000691185227, 1.7018106423784165, false}});
}

TEST(PlacementDrawOrder, Clustered) {
  ExpectPoses(Placed(PlacementMode::kClustered, 7),
              {{0.39256719629706921, 0.14872409881462484, 0.73773568544913903, false},
               {0.44664553228089748, 0.10980153755504184, 0.34616052403809106, false},
               {0.52918179241880881, 0.10650815573514288, 1.910120782427009, true},
               {0.46600770788558105, 0.028028607803423589, 2.0793119687756922, false}});
}

TEST(PlacementDrawOrder, Sparse) {
  ExpectPoses(Placed(PlacementMode::kSparse, 7),
              {{0.38522428431035544, 0.14892700715074103, 0.88763541024432568, false},
               {0.52789474642574563, -0.037945181866178457, 1.9385430991567183, false},
               {0.63356133985412066, 0.1284941459676707, 1.6814517866626322, false},
               {0.3740310398332129, -0.13171168731802674, 1.0601246449871091, false}});
}

}  // namespace
}  // namespace sortcell::sim
