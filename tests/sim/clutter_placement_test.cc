// Objects' resting shapes come from their collision geoms, and clutter placement puts them touching
// (dense), in groups (clustered) or apart (sparse), some on their side, without overlap, inside the
// area; the physics then finds them at rest (sim: steps the cell).
#include "sim/clutter_placement.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "files/object_set.h"
#include "cell/cell_layout.h"
#include "error_of.h"
#include "sim/arm_io.h"
#include "sim/model.h"
#include "sim/object_placement.h"
#include "sim/scene_composer.h"
#include "source_tree.h"

namespace sortcell::sim {
namespace {

using sortcell_test::kRoot;

class PaperCell : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const files::ObjectSet set = files::LoadObjectSet(kRoot / "scenes/objects/paper.yaml");
    std::vector<std::filesystem::path> models;
    for (const auto& o : set.objects) {
      models.push_back(o.model);
      names_.push_back(o.name);
    }
    model_ = new Model(LoadComposedCell(kRoot / "models", models, "paper set"));
  }
  static void TearDownTestSuite() { delete model_; }
  static ObjectShape Shape(const std::string& name) { return ObjectShapeOf(*model_, model_->Id(mjOBJ_BODY, name)); }
  static std::vector<ObjectShape> Shapes() {
    std::vector<ObjectShape> shapes;
    for (const auto& n : names_) shapes.push_back(Shape(n));
    return shapes;
  }
  static Model* model_;
  static std::vector<std::string> names_;
};
Model* PaperCell::model_ = nullptr;
std::vector<std::string> PaperCell::names_;

std::vector<Eigen::Vector2d> Outline(const ObjectShape& shape, const TablePose& pose) {
  return PlacedOutline(shape.Resting(pose.lying).outline, {pose.x, pose.y}, pose.yaw);
}

TEST_F(PaperCell, ShapesRestUprightOrOnTheirLongSide) {
  const ObjectShape bottle = Shape("bottle1"), box = Shape("box"), ball = Shape("ball"), cup = Shape("cup");
  EXPECT_NEAR(bottle.upright.height, 0.224, 0.002);
  EXPECT_NEAR(bottle.disc_radius, 0.033, 1e-6);
  ASSERT_TRUE(bottle.lying.has_value());
  EXPECT_NEAR(bottle.lying->height, 0.066, 0.001);    // On its body's side.
  EXPECT_NEAR(bottle.lying->origin_z, 0.033, 0.001);  // The base centre is the axis's end.
  EXPECT_NEAR(bottle.lying->radius, 0.224, 0.005);    // The cap end is a bottle's length from the base.
  ASSERT_TRUE(box.lying.has_value());
  EXPECT_NEAR(box.lying->height, 0.06, 1e-6);  // On its largest face, 0.09 x 0.12.
  EXPECT_NEAR(box.disc_radius, std::hypot(0.03, 0.045), 1e-9);
  EXPECT_FALSE(ball.lying.has_value());
  EXPECT_FALSE(cup.lying.has_value());  // 0.0955 tall, 0.076 wide: it stands.
  EXPECT_NEAR(ball.upright.origin_z, 0.0, 1e-9);
}

// An imported object collides as mesh pieces: its disc is what its vertices reach across the table,
// not MuJoCo's bounding sphere (which counts the height and the corners of the mesh's box).
TEST(ObjectShape, AMeshDiscIsWhatItsVerticesReachAcross) {
  const Model model = Model::FromVirtualFiles(
      {{"plate.xml",
        R"(<mujoco><asset><mesh name="octagon" vertex="0.1 0 0  0.0707 0.0707 0  0 0.1 0  -0.0707 0.0707 0  -0.1 0 0
            -0.0707 -0.0707 0  0 -0.1 0  0.0707 -0.0707 0  0 0 0.016"/></asset>
            <worldbody><body name="plate"><freejoint/><geom type="mesh" mesh="octagon"/></body></worldbody></mujoco>)"}},
      "plate");
  EXPECT_NEAR(ObjectShapeOf(model, model.Id(mjOBJ_BODY, "plate")).disc_radius, 0.1, 1e-6);
}

TEST(Separation, IsTheGapAlongTheBestAxis) {
  const std::vector<Eigen::Vector2d> square{{0, 0}, {1, 0}, {1, 1}, {0, 1}};
  EXPECT_NEAR(Separation(square, PlacedOutline(square, {1.5, 0}, 0)), 0.5, 1e-12);
  EXPECT_NEAR(Separation(square, PlacedOutline(square, {0.75, 0.2}, 0)), -0.25, 1e-12);
}

TEST(ClusterSizes, GroupsOfTwoToFourLeaveNoOneAlone) {
  for (int count = 2; count <= 12; ++count) {
    std::mt19937_64 rng(count);
    int total = 0;
    for (const int size : ClusterSizes(count, rng)) {
      EXPECT_GE(size, 2);
      EXPECT_LE(size, 4);
      total += size;
    }
    EXPECT_EQ(total, count);
  }
}

// Each object's smallest separation from any other, and whether all keep out of each other and the area.
std::vector<double> Nearest(const std::vector<ObjectShape>& shapes, const std::vector<TablePose>& poses,
                            const PlacementArea& area) {
  std::vector<double> nearest(poses.size(), INFINITY);
  for (size_t i = 0; i < poses.size(); ++i) {
    for (const auto& v : Outline(shapes[i], poses[i])) {
      EXPECT_TRUE((v.array() >= area.min.array() - 1e-9).all() && (v.array() <= area.max.array() + 1e-9).all());
    }
    for (size_t j = 0; j < poses.size(); ++j) {
      if (j != i)
        nearest[i] = std::min(nearest[i], Separation(Outline(shapes[i], poses[i]), Outline(shapes[j], poses[j])));
    }
  }
  return nearest;
}

TEST_F(PaperCell, DenseScenesTouchWithoutOverlap) {
  const std::vector<ObjectShape> shapes = Shapes();
  const PlacementArea area;
  PlacementOptions options;
  options.mode = PlacementMode::kDense;
  options.lying_fraction = 0.5;
  int lying = 0;
  for (uint64_t seed = 0; seed < 20; ++seed) {
    std::mt19937_64 rng(seed);
    const auto poses = SampleClutter(shapes, {}, area, options, rng);
    ASSERT_TRUE(poses.has_value()) << "seed " << seed;
    for (const TablePose& p : *poses) lying += p.lying;
    for (const double d : Nearest(shapes, *poses, area)) {
      EXPECT_GE(d, options.contact_gap_m - 1e-9) << "seed " << seed;
      EXPECT_LE(d, options.contact_gap_m + 0.001) << "seed " << seed << ": every object touches another";
    }
  }
  // Three of the six can lie (the bottles and the box): about 0.5 x 3 x 20 = 30 of them.
  EXPECT_GT(lying, 15);
  EXPECT_LT(lying, 45);
}

TEST_F(PaperCell, ClusteredScenesFormGroupsApart) {
  const std::vector<ObjectShape> shapes = Shapes();
  const PlacementArea area;
  PlacementOptions options;
  options.mode = PlacementMode::kClustered;
  for (uint64_t seed = 0; seed < 20; ++seed) {
    std::mt19937_64 rng(seed);
    const auto poses = SampleClutter(shapes, {}, area, options, rng);
    ASSERT_TRUE(poses.has_value()) << "seed " << seed;
    // Groups: objects within touching distance, chained.
    std::vector<int> group(poses->size());
    for (size_t i = 0; i < group.size(); ++i) group[i] = static_cast<int>(i);
    const auto root = [&](int i) {
      while (group[i] != i) i = group[i];
      return i;
    };
    const auto separation = [&](size_t i, size_t j) {
      return Separation(Outline(shapes[i], (*poses)[i]), Outline(shapes[j], (*poses)[j]));
    };
    for (size_t i = 0; i < poses->size(); ++i) {
      for (size_t j = 0; j < i; ++j) {
        if (separation(i, j) < options.contact_gap_m + 0.001)
          group[root(static_cast<int>(i))] = root(static_cast<int>(j));
      }
    }
    for (size_t i = 0; i < poses->size(); ++i) {
      for (size_t j = 0; j < i; ++j) {
        if (root(static_cast<int>(i)) == root(static_cast<int>(j))) continue;
        EXPECT_GE(separation(i, j), area.gap_m - 1e-9) << "seed " << seed << ": groups closer than the gap";
      }
    }
    std::map<int, int> sizes;
    for (size_t i = 0; i < group.size(); ++i) ++sizes[root(static_cast<int>(i))];
    EXPECT_GE(sizes.size(), 2u) << "seed " << seed;
    for (const auto& [r, n] : sizes) EXPECT_GE(n, 2) << "seed " << seed << ": a group of one";
  }
}

TEST_F(PaperCell, FixedPosesStayAndTooManyObjectsAreReported) {
  const std::vector<ObjectShape> shapes = Shapes();
  PlacementOptions options;
  options.mode = PlacementMode::kDense;
  std::mt19937_64 rng(4);
  const TablePose fixed{0.5, 0.0, 0.4, true};
  const auto poses = SampleClutter(shapes, {fixed}, PlacementArea(), options, rng);
  ASSERT_TRUE(poses.has_value());
  EXPECT_EQ((*poses)[0].x, 0.5);
  EXPECT_TRUE((*poses)[0].lying);
  PlacementArea tiny;
  tiny.max = tiny.min + Eigen::Vector2d(0.1, 0.1);
  EXPECT_FALSE(SampleClutter(shapes, {}, tiny, options, rng, 20).has_value());
  options.lying_fraction = 2;
  EXPECT_NE(sortcell_test::ErrorOf([&] {
              SampleClutter(shapes, {}, PlacementArea(), options, rng);
            }).find("lying fraction must be in [0, 1]"),
            std::string::npos);
}

TEST_F(PaperCell, PlacedSceneStartsApartAndComesToRest) {
  const std::vector<ObjectShape> shapes = Shapes();
  PlacementOptions options;
  options.mode = PlacementMode::kDense;
  options.lying_fraction = 1;
  for (uint64_t seed = 0; seed < 3; ++seed) {
    std::mt19937_64 rng(seed);
    const auto poses = SampleClutter(shapes, {}, PlacementArea(), options, rng);
    ASSERT_TRUE(poses.has_value());
    Data data(*model_);
    const ArmIo arm(*model_);
    const auto q_observe = cell::CellLayout().q_observe;  // Out of the way, held there.
    arm.SetArmPosition(data, q_observe);
    std::vector<int> bodies;
    for (size_t i = 0; i < names_.size(); ++i) {
      bodies.push_back(model_->Id(mjOBJ_BODY, names_[i]));
      PlaceObject(*model_, data, bodies.back(), (*poses)[i], shapes[i]);
    }
    mj_forward(model_->get(), data.get());
    for (int c = 0; c < data->ncon; ++c) {
      EXPECT_GT(data->contact[c].dist, -0.001) << "seed " << seed << ": geoms " << data->contact[c].geom1 << ", "
                                               << data->contact[c].geom2 << " interpenetrate at the start";
    }
    std::vector<Eigen::Vector3d> start;
    for (const int b : bodies) start.emplace_back(data->xpos[3 * b], data->xpos[3 * b + 1], data->xpos[3 * b + 2]);
    const int steps = static_cast<int>(1.0 / (*model_)->opt.timestep);
    for (int k = 0; k < steps; ++k) {
      mj_step(model_->get(), data.get());
      arm.SetArmPosition(data, q_observe);
    }
    for (size_t i = 0; i < bodies.size(); ++i) {
      const int b = bodies[i];
      const Eigen::Vector3d p(data->xpos[3 * b], data->xpos[3 * b + 1], data->xpos[3 * b + 2]);
      EXPECT_LT((p - start[i]).norm(), 0.005) << "seed " << seed << ": " << names_[i] << " moved";
      const double* v = data->cvel + 6 * b;
      EXPECT_LT(Eigen::Vector3d(v[3], v[4], v[5]).norm(), 0.01)
          << "seed " << seed << ": " << names_[i] << " not at rest";
    }
  }
}

}  // namespace
}  // namespace sortcell::sim
