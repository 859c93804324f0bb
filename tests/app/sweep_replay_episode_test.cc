// `sortcell replay` of a sweep's failed episode reproduces its record exactly, with a video or without.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "run_sortcell.h"
#include "sweep_test_support.h"
#include "temp_dir.h"

namespace sortcell_test {
namespace {

TEST(SweepReplay, AFailedEpisodeIsReplayedExactly) {
  const TempDir tmp;
  // A plate (wider than the gripper's stroke every way: never graspable) beside a cup.
  const std::string models = std::string(SORTCELL_SOURCE_DIR) + "/models/objects/";
  std::ofstream(tmp.path() / "set.yaml")
      << "name: plate_and_cup\nobjects:\n"
      << "  - {name: plate1, category: others, instance: plate1, model: " << models << "plate1.inc.xml}\n"
      << "  - {name: cup, category: cup, instance: cup, model: " << models << "cup.inc.xml}\n";
  std::ofstream(tmp.path() / "spec.yaml") << "scene: " << kSweepScene << "\nobject_set: " << (tmp.path() / "set.yaml").string()
                                          << "\nmodel: " << SORTCELL_TEST_MODEL << "\nseed: 3\nepisodes: 1\naxes:\n  objects: [2]\n";
  const std::filesystem::path sweep = tmp.path() / "sweep";
  const auto s = RunSortcell("sweep " + (tmp.path() / "spec.yaml").string() + " --out " + sweep.string());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string results = ReadFile((sweep / "results.jsonl").string());
  ASSERT_NE(results.find("\"outcome\":\"ungraspable\""), std::string::npos) << results;

  const auto r = RunSortcell("replay " + sweep.string() + " --episode 0 --video " + (tmp.path() / "replay.mp4").string());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("its record matches the sweep's (plate1 ungraspable, cup sorted)"), std::string::npos) << r.out;
  EXPECT_GT(std::filesystem::file_size(tmp.path() / "replay.mp4"), 10000u);
  EXPECT_TRUE(std::filesystem::exists(sweep / "replays/000000/metrics.json"));
}

}  // namespace
}  // namespace sortcell_test
