// `sortcell sweep --review` and `sortcell replay` of a sweep's failed episode: replayed with a video and
// without, the record is the sweep's exactly; the failure is told in words with a clip around it; the
// report page works in a real browser.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "run_sortcell.h"
#include "sweep_test_support.h"
#include "temp_dir.h"

namespace sortcell_test {
namespace {

TEST(SweepReplay, AFailedEpisodeIsReviewedWithAClipAndReplayedExactly) {
  const TempDir tmp;
  // A plate (wider than the gripper's stroke every way: never graspable) beside a cup. Seed 0: of seeds 0-7, seed 3
  // alone has the plate, called a cup, found unreachable before too wide.
  const std::string models = std::string(SORTCELL_SOURCE_DIR) + "/models/objects/";
  std::ofstream(tmp.path() / "set.yaml") << "name: plate_and_cup\nobjects:\n"
                                         << "  - {name: plate1, category: others, instance: plate1, model: " << models
                                         << "plate1.inc.xml}\n"
                                         << "  - {name: cup, category: cup, instance: cup, model: " << models
                                         << "cup.inc.xml}\n";
  std::ofstream(tmp.path() / "spec.yaml")
      << "scene: " << kSweepScene << "\nobject_set: " << (tmp.path() / "set.yaml").string()
      << "\nmodel: " << SORTCELL_TEST_MODEL << "\nseed: 0\nepisodes: 1\naxes:\n  objects: [2]\n";
  const std::filesystem::path sweep = tmp.path() / "sweep";
  const auto s = RunSortcell("sweep " + (tmp.path() / "spec.yaml").string() + " --review --out " + sweep.string());
  ASSERT_EQ(s.exit_code, 0) << s.err;
  const std::string results = ReadFile((sweep / "results.jsonl").string());
  ASSERT_NE(results.find("\"outcome\":\"ungraspable\""), std::string::npos) << results;

  // The review replayed it with video (and found the same record), told the failure and cut its clip.
  const auto review = nlohmann::json::parse(ReadFile((sweep / "review.json").string()));
  EXPECT_EQ(review["episodes_replayed"], 1);
  EXPECT_TRUE(review["mismatches"].empty()) << review.dump();
  ASSERT_EQ(review["failures"].size(), 1u) << review.dump();
  const auto& f = review["failures"][0];
  EXPECT_EQ(f["item"], "plate1");
  EXPECT_EQ(f["outcome"], "ungraspable");
  EXPECT_NE(f["log"][0].get<std::string>().find("not attempted: too wide"), std::string::npos) << f.dump();
  EXPECT_EQ(f["clip"], "replays/000000/clip_plate1.mp4");
  EXPECT_GT(std::filesystem::file_size(sweep / "replays/000000/clip_plate1.mp4"), 10000u);
  EXPECT_GT(std::filesystem::file_size(sweep / "replays/000000/episode.mp4"), 10000u);
  EXPECT_EQ(f["decided_at_s"], f["at_s"]);  // Left alone when first seen: decided and failed at once.
  ASSERT_TRUE(f["still"].is_string());
  EXPECT_EQ(f["still"].get<std::string>().rfind("replays/000000/stills/still_", 0), 0u) << f.dump();
  EXPECT_TRUE(std::filesystem::exists(sweep / f["still"].get<std::string>()));

  // The report page, opened in headless Chromium: no console error, the table filters, the clip plays;
  // its screenshot is kept in the build folder (test_output/).
  ASSERT_TRUE(std::filesystem::exists(sweep / "report/index.html"));
  const std::filesystem::path shots =
      std::filesystem::path(SORTCELL_BINARY).parent_path().parent_path() / "test_output";
  std::filesystem::create_directories(shots);
  const std::string browser =
      std::string(SORTCELL_SOURCE_DIR) + "/scripts/report_in_browser.py " + (sweep / "report/index.html").string() +
      " --screenshot " + (shots / "report_in_browser.png").string() + " > " + (tmp.path() / "browser.json").string();
  EXPECT_EQ(std::system(browser.c_str()), 0) << ReadFile((tmp.path() / "browser.json").string());
  const auto seen = nlohmann::json::parse(ReadFile((tmp.path() / "browser.json").string()));
  EXPECT_EQ(seen["clips"].size(), 1u);
  EXPECT_TRUE(seen["errors"].empty());

  // And without video, into a folder of its own: the same record exactly.
  const auto r = RunSortcell("replay " + sweep.string() + " --episode 0 --out " + (tmp.path() / "again").string());
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("its record matches the sweep's (plate1 ungraspable, cup sorted)"), std::string::npos) << r.out;
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "again/metrics.json"));
}

}  // namespace
}  // namespace sortcell_test
