#include <gtest/gtest.h>

#include <fstream>

#include "app/sweep/sweep_report.h"
#include "app/sweep/sweep_spec.h"
#include "error_of.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

std::filesystem::path WriteSpec(const std::string& name, const std::string& body) {
  const std::filesystem::path file = std::filesystem::path(sortcell_test::TestTempDir()) / (name + ".yaml");
  std::ofstream(file) << "scene: " << SORTCELL_SOURCE_DIR << "/scenes/cell.xml\nobject_set: " << SORTCELL_SOURCE_DIR
                      << "/scenes/objects/paper.yaml\n"
                      << body;
  return file;
}

TEST(SweepSpec, ShippedSpecsLoad) {
  for (const char* name : {"paper_objects_100", "robustness_random", "calibration_grid"}) {
    const SweepSpec spec =
        LoadSweepSpec(std::filesystem::path(SORTCELL_SOURCE_DIR) / "scenes/sweeps" / (std::string(name) + ".yaml"));
    EXPECT_GT(spec.EpisodeCount(), 0) << name;
  }
  const SweepSpec paper =
      LoadSweepSpec(std::filesystem::path(SORTCELL_SOURCE_DIR) / "scenes/sweeps/paper_objects_100.yaml");
  EXPECT_EQ(paper.EpisodeCount(), 100);
  for (int i = 0; i < 100; ++i) {
    const int k = paper.Episode(i).second["objects"].get<int>();
    EXPECT_GE(k, 4);
    EXPECT_LE(k, 6);
  }
}

TEST(SweepSpec, RandomDrawsAreDeterministicAndInRange) {
  const SweepSpec spec = LoadSweepSpec(WriteSpec(
      "random", "seed: 5\nepisodes: 20\naxes:\n  light_intensity: {min: 0.5, max: 1.5}\n  objects: [2, 4]\n"));
  EXPECT_EQ(spec.EpisodeCount(), 20);
  std::set<double> distinct;
  for (int i = 0; i < 20; ++i) {
    const auto [seed, axes] = spec.Episode(i);
    EXPECT_EQ(seed, 5u + i);
    EXPECT_EQ(spec.Episode(i).second, axes);
    const double light = axes["light_intensity"].get<double>();
    EXPECT_GE(light, 0.5);
    EXPECT_LE(light, 1.5);
    distinct.insert(light);
    const int k = axes["objects"].get<int>();
    EXPECT_TRUE(k == 2 || k == 4);
  }
  EXPECT_EQ(distinct.size(), 20u);
}

TEST(SweepSpec, GridCoversEveryCellWithTheSameSeeds) {
  const SweepSpec spec = LoadSweepSpec(
      WriteSpec("grid", "mode: grid\nseeds: [7, 9]\naxes:\n  noise_scale: [1, 2]\n  objects: [2, 3, 4]\n"));
  ASSERT_EQ(spec.EpisodeCount(), 12);
  std::set<std::string> cells;
  for (int i = 0; i < 12; ++i) {
    const auto [seed, axes] = spec.Episode(i);
    EXPECT_EQ(seed, i % 2 == 0 ? 7u : 9u);
    cells.insert(axes.dump());
  }
  EXPECT_EQ(cells.size(), 6u);
}

TEST(SweepSpec, GridRangesAreDrawnPerRepeatAlikeInEveryCell) {
  const SweepSpec spec = LoadSweepSpec(WriteSpec("grid_range",
                                                 "mode: grid\nepisodes: 5\naxes:\n"
                                                 "  placement: [dense, clustered]\n"
                                                 "  objects: {min: 4, max: 6}\n"
                                                 "  lying_fraction: [0.3]\n"));
  ASSERT_EQ(spec.EpisodeCount(), 10);
  std::set<int> counts;
  for (int repeat = 0; repeat < 5; ++repeat) {
    const auto [seed_a, dense] = spec.Episode(repeat);
    const auto [seed_b, clustered] = spec.Episode(5 + repeat);
    EXPECT_EQ(seed_a, seed_b);
    EXPECT_EQ(dense["placement"], "dense");
    EXPECT_EQ(clustered["placement"], "clustered");
    EXPECT_EQ(dense["objects"], clustered["objects"]);
    EXPECT_EQ(dense["lying_fraction"], 0.3);
    counts.insert(dense["objects"].get<int>());
    EXPECT_GE(dense["objects"].get<int>(), 4);
    EXPECT_LE(dense["objects"].get<int>(), 6);
  }
  EXPECT_GT(counts.size(), 1u);  // Drawn, not fixed.
}

TEST(SweepSpec, SelfCalibrationIsAnAxisOfWords) {
  const SweepSpec spec = LoadSweepSpec(WriteSpec("calibrate",
                                                 "mode: grid\nepisodes: 1\naxes:\n"
                                                 "  self_calibrate: [on, off]\n"));
  ASSERT_EQ(spec.EpisodeCount(), 2);
  EXPECT_EQ(spec.Episode(0).second["self_calibrate"], "on");
  EXPECT_EQ(spec.Episode(1).second["self_calibrate"], "off");
}

TEST(SweepSpec, NoiseSeedsAreAnAxisOfWholeNumbers) {
  const SweepSpec spec =
      LoadSweepSpec(WriteSpec("noise_seed", "mode: grid\nepisodes: 1\naxes:\n  noise_seed: [0, 2]\n"));
  ASSERT_EQ(spec.EpisodeCount(), 2);
  EXPECT_EQ(spec.Episode(0).second["noise_seed"], 0);
  EXPECT_EQ(spec.Episode(1).second["noise_seed"], 2);
  EXPECT_EQ(spec.Episode(0).first, spec.Episode(1).first) << "the same scene seed under both draws of the noise";
}

TEST(SweepSpec, BadSpecsNameTheKey) {
  using sortcell_test::ErrorOf;
  const auto error = [](const std::string& name, const std::string& body) {
    return ErrorOf([&] { LoadSweepSpec(WriteSpec(name, body)); });
  };
  EXPECT_NE(error("unknown", "episodez: 3\n").find("unknown key 'episodez'"), std::string::npos);
  EXPECT_NE(error("axis", "axes:\n  lighting: [1]\n").find("unknown key 'lighting' in axes"), std::string::npos);
  EXPECT_NE(error("type", "episodes: many\n").find("key 'episodes': expected a non-negative integer, found 'many'"),
            std::string::npos);
  EXPECT_NE(error("number", "axes:\n  noise_scale: [1, loud]\n").find("key 'axes.noise_scale[1]': expected a number"),
            std::string::npos);
  EXPECT_NE(error("placement", "axes:\n  placement: [dense, heaped]\n")
                .find("key 'axes.placement[1]': expected sparse, dense or clustered, found 'heaped'"),
            std::string::npos);
  EXPECT_NE(error("placement_range", "axes:\n  placement: {min: 1, max: 2}\n").find("not a range"), std::string::npos);
  EXPECT_NE(error("calibrate", "axes:\n  self_calibrate: [on, sometimes]\n")
                .find("key 'axes.self_calibrate[1]': expected auto, on or off, found 'sometimes'"),
            std::string::npos);
  EXPECT_NE(
      error("lying", "axes:\n  lying_fraction: [1.5]\n").find("key 'axes.lying_fraction[0]': expected a fraction"),
      std::string::npos);
  EXPECT_NE(error("noise_seed", "axes:\n  noise_seed: [1, -2]\n")
                .find("key 'axes.noise_seed[1]': expected a non-negative integer"),
            std::string::npos);
  EXPECT_NE(error("noise_seed_half", "axes:\n  noise_seed: [1.5]\n").find("key 'axes.noise_seed[0]'"),
            std::string::npos);
  EXPECT_NE(error("mode", "mode: sometimes\n").find("key 'mode': expected random or grid"), std::string::npos);
  EXPECT_NE(error("model", "model: nowhere.json\n").find("key 'model': file"), std::string::npos);
  EXPECT_NE(error("negative", "axes:\n  mass_scale: [0]\n").find("expected a value > 0"), std::string::npos);
  EXPECT_NE(ErrorOf([] {
              LoadSweepSpec("/nonexistent/spec.yaml");
            }).find("sweep spec '/nonexistent/spec.yaml': file not found"),
            std::string::npos);
}

TEST(SweepReport, WilsonIntervalMatchesHandComputedValues) {
  // 95 of 100: [0.888, 0.978]; 10 of 10: [0.722, 1].
  const auto [lo, hi] = WilsonInterval(95, 100);
  EXPECT_NEAR(lo, 0.8883, 1e-3);
  EXPECT_NEAR(hi, 0.9785, 1e-3);
  const auto [lo2, hi2] = WilsonInterval(10, 10);
  EXPECT_NEAR(lo2, 0.7225, 1e-3);
  EXPECT_NEAR(hi2, 1.0, 1e-9);
  EXPECT_EQ(WilsonInterval(0, 0), std::make_pair(0.0, 1.0));
}

}  // namespace
}  // namespace sortcell::app
