// An episode's set-up refuses what it cannot do, naming the culprit: an object placed twice, objects
// that do not fit the table, a model that does not know a category of the set, a model class without
// a bin in the scene (unit: no rendering).
#include "simcell/episode_setup.h"

#include <gtest/gtest.h>

#include <random>

#include "files/output_dir.h"
#include "simcell/episode.h"
#include "simcell/sim_rig.h"
#include "common/seeding.h"
#include "error_of.h"
#include "perception/recognition_model.h"
#include "temp_dir.h"
#include "source_tree.h"

namespace sortcell::simcell {
namespace {

using sortcell_test::ErrorOf;

using sortcell_test::kSource;

files::ObjectSet ThreeObjects() {
  files::ObjectSet set;
  set.name = "three";
  set.source = "three.yaml";
  for (const char* name : {"a", "b", "c"}) set.objects.push_back({name, "cup", name, "", std::nullopt});
  return set;
}

TEST(EpisodeSetup, AnObjectPlacedTwiceIsRefused) {
  EpisodeOptions options;
  options.placements = {{"a", 0.4, 0.0, 0.0}, {"a", 0.5, 0.1, 0.0}};
  std::mt19937_64 rng(1);
  EXPECT_EQ(ErrorOf([&] { ChooseObjects(ThreeObjects(), options, rng); }), "--place: object 'a' placed twice");
}

TEST(EpisodeSetup, MorePlacementsThanObjectsOrAnUnknownObjectAreRefused) {
  std::mt19937_64 rng(1);
  EpisodeOptions options;
  options.objects = 1;
  options.placements = {{"a", 0.4, 0.0, 0.0}, {"b", 0.5, 0.1, 0.0}};
  EXPECT_EQ(ErrorOf([&] { ChooseObjects(ThreeObjects(), options, rng); }), "--place: 2 placements for 1 objects");
  options.objects = 0;
  options.placements = {{"z", 0.4, 0.0, 0.0}};
  EXPECT_NE(ErrorOf([&] { ChooseObjects(ThreeObjects(), options, rng); }).find("'z'"), std::string::npos);
  EXPECT_EQ(ObjectCount(ThreeObjects(), options), 3);
}

TEST(EpisodeSetup, PlacedObjectsComeFirstAndTheCountIsChecked) {
  EpisodeOptions options;
  options.objects = 2;
  options.placements = {{"c", 0.4, 0.0, 0.0}};
  std::mt19937_64 rng(1);
  const auto chosen = ChooseObjects(ThreeObjects(), options, rng);
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[0].name, "c");
  EXPECT_NE(chosen[1].name, "c");
  options.objects = 4;
  EXPECT_EQ(ErrorOf([&] { ChooseObjects(ThreeObjects(), options, rng); }),
            "--objects: expected 1..3 (the objects of set 'three.yaml'), got 4");
}

// Upright objects of footprint radius r (sparse placement keeps their discs apart).
std::vector<sim::ObjectShape> Discs(const std::vector<double>& radii) {
  std::vector<sim::ObjectShape> shapes;
  for (const double r : radii) {
    sim::ObjectShape shape;
    shape.disc_radius = r;
    shapes.push_back(shape);
  }
  return shapes;
}

TEST(EpisodeSetup, ObjectsThatDoNotFitTheTableAreRefused) {
  std::mt19937_64 rng(1);
  const sim::PlacementArea area;  // 0.36 x 0.44 m
  const sim::PlacementOptions sparse;
  EXPECT_EQ(ErrorOf([&] {
              DrawPoses({}, Discs({0.15, 0.15, 0.15}), area, sparse, rng);
            }),
            "--objects: 3 objects do not fit the table area (sparse placement) with the given placements");
  // One placed by hand in the middle leaves no room for a second large one.
  EXPECT_EQ(ErrorOf([&] {
              DrawPoses({{"a", 0.5, 0.0, 0.0}}, Discs({0.15, 0.1}), area, sparse, rng);
            }),
            "--objects: 2 objects do not fit the table area (sparse placement) with the given placements");
  EXPECT_EQ(ErrorOf([&] {
              DrawPoses({{"a", 0.5, 0.0, 0.0, true}}, Discs({0.03}), area, sparse, rng);
            }),
            "--place: object 'a' cannot lie on its side (not taller than it is narrow)");
  const auto poses = DrawPoses({{"a", 0.5, 0.0, 0.3}}, Discs({0.03, 0.03}), area, sparse, rng);
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_EQ(poses[0].x, 0.5);
  EXPECT_EQ(poses[0].yaw, 0.3);
  EXPECT_GE(std::hypot(poses[1].x - 0.5, poses[1].y), 0.03 + 0.03 + area.gap_m);
}

// A model file with the given classes (an SVM on separable blobs; only its classes matter here).
std::filesystem::path ModelWithClasses(const std::vector<std::string>& classes, const std::string& name) {
  const int n = static_cast<int>(classes.size());
  Eigen::MatrixXf x(6 * n, 500);
  std::vector<int> y, groups;
  std::mt19937_64 rng(3);
  std::normal_distribution<float> noise(0.0f, 0.1f);
  for (int r = 0; r < x.rows(); ++r) {
    for (int k = 0; k < x.cols(); ++k) x(r, k) = (k % n == r % n ? 1.0f : 0.0f) + noise(rng);
    y.push_back(r % n);
    groups.push_back(r / n);
  }
  perception::SvmGrid grid;
  grid.C = {4};
  grid.gamma = {1.0 / 32};
  perception::RecognitionModel model;
  model.classes = classes;
  model.classifier = perception::SvmClassifier::Train(x, y, groups, n, grid);
  const std::filesystem::path file = std::filesystem::path(sortcell_test::TestTempDir()) / (name + ".model.json");
  perception::SaveModel(file, model);
  return file;
}

EpisodeOptions PaperEpisode(const std::filesystem::path& model) {
  EpisodeOptions options;
  options.scene = kSource + "/scenes/cell.xml";
  options.object_set = kSource + "/scenes/objects/paper.yaml";
  options.model = model;
  options.out = std::filesystem::path(sortcell_test::TestTempDir()) / "episode";
  return options;
}

TEST(EpisodeSetup, AModelThatDoesNotKnowACategoryOfTheSetIsRefused) {
  const auto model = ModelWithClasses({"bottle", "cup", "ball"}, "three_classes");
  EXPECT_EQ(ErrorOf([&] { RunEpisode(PaperEpisode(model), {}); }),
            "model '" + model.string() + "': does not know category 'others' of object set '" + kSource +
                "/scenes/objects/paper.yaml'");
}

TEST(EpisodeSetup, AModelClassTheRulesSendNowhereIsRefused) {
  const auto model = ModelWithClasses({"bottle", "cup", "ball", "others", "plate"}, "five_classes");
  // The default bins with a rule per category of the set and no "*": a plate goes nowhere.
  std::string text = files::ReadTextFile(kSource + "/scenes/cells/default.yaml");
  const std::string wildcard = "\"*\": others";
  ASSERT_NE(text.find(wildcard), std::string::npos);
  text.replace(text.find(wildcard), wildcard.size(), "others: others");
  EpisodeOptions options = PaperEpisode(model);
  options.cell = std::filesystem::path(sortcell_test::TestTempDir()) / "no_wildcard.yaml";
  files::WriteTextFile(options.cell, text);
  EXPECT_EQ(ErrorOf([&] { RunEpisode(options, {}); }),
            "cell layout '" + options.cell.string() + "' with model '" + model.string() +
                "': rules: the model's class 'plate' goes to no bin (no rule for it and no \"*\")");
}

TEST(KinectNoiseRng, EachNoiseSeedIsAStreamOfItsOwnApartFromTheScenes) {
  const auto first = [](std::mt19937_64 rng) { return rng(); };
  EXPECT_EQ(first(KinectNoiseRng(3, 0)), first(KinectNoiseRng(3, 0)));
  EXPECT_NE(first(KinectNoiseRng(3, 0)), first(KinectNoiseRng(3, 1)));
  EXPECT_NE(first(KinectNoiseRng(3, 0)), first(KinectNoiseRng(4, 0)));
  EXPECT_NE(first(KinectNoiseRng(3, 0)), first(EpisodeRng(3, 0))) << "the scene's draws";
}

}  // namespace
}  // namespace sortcell::simcell
