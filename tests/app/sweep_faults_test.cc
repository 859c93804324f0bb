// A sweep under faults (label slow): killed with SIGKILL at random moments again and again, a disk that
// fills while it runs, an episode that hangs, a simulation that diverges. In each, finished results
// stay, every episode ends with an outcome, and --resume completes the sweep with the results an
// uninterrupted run gives. The model comes from the CTest fixture episode_model.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <thread>

#include <nlohmann/json.hpp>

#include "run_sortcell.h"
#include "sweep_test_support.h"
#include "temp_dir.h"

namespace {

using sortcell_test::Lines;
using sortcell_test::RecordsByEpisode;
using sortcell_test::RunSortcell;
using sortcell_test::SmallSweepSpec;
using sortcell_test::StartSortcell;
using sortcell_test::TempDir;

using sortcell_test::ReadFile;

// The complete lines of results.jsonl (a last line cut short by a kill is no record), each of which
// must be a whole JSON record.
std::vector<nlohmann::json> CompleteRecords(const std::filesystem::path& results) {
  std::string text = ReadFile(results);
  text.erase(text.rfind('\n') == std::string::npos ? 0 : text.rfind('\n') + 1);
  std::vector<nlohmann::json> records;
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty()) records.push_back(nlohmann::json::parse(line));  // Throws on a damaged line.
  }
  return records;
}

std::multiset<int> EpisodesOf(const std::vector<nlohmann::json>& records) {
  std::multiset<int> episodes;
  for (const auto& r : records) episodes.insert(r["episode"].get<int>());
  return episodes;
}

// SIGKILL (no clean-up at all) at 20 random moments of one sweep, each time resumed, then resumed to
// the end: every episode recorded exactly once, each record as an uninterrupted run's.
TEST(SweepFaults, KilledTwentyTimesAtRandomMomentsThenResumedGivesTheUninterruptedResults) {
  const TempDir dir("kill20");
  constexpr int kEpisodes = 10;
  const std::string spec = SmallSweepSpec(dir / "kill20.yaml", 40, kEpisodes);
  const std::string reference = dir / "reference", out = dir / "killed";
  ASSERT_EQ(RunSortcell("sweep " + spec + " -j 2 --out " + reference).exit_code, 0);

  std::mt19937 random(2026);  // The moments are random but the same in every run of the test.
  std::uniform_int_distribution<int> delay_ms(150, 2500);
  size_t recorded = 0;
  int kills = 0;
  for (int attempt = 0; attempt < 20; ++attempt) {
    const pid_t pid = StartSortcell({"sweep", spec, "-j", "2", "--resume", "--out", out}, dir / "killed.log");
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms(random)));
    ::kill(pid, SIGKILL);
    int status = 0;
    waitpid(pid, &status, 0);
    if (WIFEXITED(status)) {  // A fast machine: the sweep finished before this kill.
      EXPECT_EQ(WEXITSTATUS(status), 0);
      break;
    }
    ASSERT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL);
    ++kills;
    if (!std::filesystem::exists(out + "/results.jsonl")) continue;
    const auto records = CompleteRecords(out + "/results.jsonl");
    EXPECT_GE(records.size(), recorded) << "kill " << kills << ": finished results lost";
    recorded = records.size();
    for (int episode : EpisodesOf(records)) EXPECT_EQ(EpisodesOf(records).count(episode), 1u) << "kill " << kills;
  }
  EXPECT_GE(kills, 10) << "most of the 20 kills must land while the sweep runs";
  const auto r = RunSortcell("sweep " + spec + " -j 2 --resume --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::multiset<int> all;
  for (int e = 0; e < kEpisodes; ++e) all.insert(e);
  EXPECT_EQ(EpisodesOf(Lines(out + "/results.jsonl")), all);
  EXPECT_EQ(RecordsByEpisode(out + "/results.jsonl"), RecordsByEpisode(reference + "/results.jsonl"));
  const auto summary = nlohmann::json::parse(ReadFile(out + "/summary.json"));
  const auto unkilled = nlohmann::json::parse(ReadFile(reference + "/summary.json"));
  EXPECT_EQ(summary["episodes"], kEpisodes);
  EXPECT_EQ(summary["outcomes"], unkilled["outcomes"]);
  EXPECT_EQ(summary["correct_sort_rate"], unkilled["correct_sort_rate"]);
}

// The disk fills while the sweep runs (here: no file may grow past a few records' size, room for each
// episode's own files but not for every record in results.jsonl): the sweep stops with one line naming
// the file, exit 2; the records written before stay whole; --resume on a disk with room completes the
// sweep as an uninterrupted run.
TEST(SweepFaults, AFullDiskStopsTheSweepNamingTheFileAndKeepsWhatFinished) {
  const TempDir dir("full_disk");
  constexpr size_t kEpisodes = 10;
  const std::string spec = SmallSweepSpec(dir / "disk.yaml", 41, kEpisodes);
  const std::string reference = dir / "reference", out = dir / "full";
  // The reference runs on two workers: a sweep's records do not depend on its plan.
  ASSERT_EQ(RunSortcell("sweep " + spec + " -j 2 --out " + reference).exit_code, 0);
  std::vector<size_t> line_bytes;
  for (const auto& record : Lines(reference + "/results.jsonl")) line_bytes.push_back(record.dump().size() + 1);
  ASSERT_EQ(line_bytes.size(), kEpisodes);
  uintmax_t largest_episode_file = 0;
  for (const auto& f : std::filesystem::recursive_directory_iterator(reference + "/episodes")) {
    if (f.is_regular_file()) largest_episode_file = std::max(largest_episode_file, f.file_size());
  }
  const rlim_t limit = std::max<rlim_t>(largest_episode_file + 4096, line_bytes[0] + line_bytes[1] + line_bytes[2] / 2);
  ASSERT_LT(limit, std::accumulate(line_bytes.begin(), line_bytes.end(), size_t{0}) * 3 / 4)
      << "the limit leaves room for nearly every record: nothing to test";

  int status = 0;
  waitpid(StartSortcell({"sweep", spec, "-j", "1", "--out", out}, dir / "full.err", limit), &status, 0);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 2);
  const std::string err = ReadFile(dir / "full.err");
  const std::string expected = "sortcell sweep: error: cannot write '" + out + "/results.jsonl': File too large\n";
  EXPECT_TRUE(err.size() >= expected.size() &&
              err.compare(err.size() - expected.size(), expected.size(), expected) == 0)
      << "the last line names the file: " << err;
  // The records that fitted (their number depends on this run's wall-clock digits) are kept whole,
  // each as the uninterrupted run's.
  const auto kept = CompleteRecords(out + "/results.jsonl");
  EXPECT_GE(kept.size(), 1u);
  EXPECT_LT(kept.size(), kEpisodes);
  const auto unlimited = RecordsByEpisode(reference + "/results.jsonl");
  for (const auto& record : kept) {
    EXPECT_EQ(sortcell_test::WithoutWallClock(record), unlimited.at(record["episode"].get<int>()));
  }

  const auto r = RunSortcell("sweep " + spec + " -j 2 --resume --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(RecordsByEpisode(out + "/results.jsonl"), unlimited);
}

// An episode that hangs (here: every episode runs past a 0.5 s timeout; starting one and loading its
// scene and model take longer) is ended and recorded with its outcome, and the sweep goes on to the
// next; the summary counts them.
TEST(SweepFaults, AHungEpisodeIsRecordedAsATimeoutAndTheSweepGoesOn) {
  const TempDir dir("hang");
  const std::string spec = SmallSweepSpec(dir / "hang.yaml", 42, 3, "episode_timeout_s: 0.5\n");
  const std::string out = dir / "out";
  const auto r = RunSortcell("sweep " + spec + " -j 2 --metrics-only --out " + out);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  const auto records = Lines(out + "/results.jsonl");
  ASSERT_EQ(EpisodesOf(records), (std::multiset<int>{0, 1, 2}));
  EXPECT_TRUE(std::filesystem::exists(out + "/episodes/000001/log.txt")) << "--metrics-only keeps a failed run's log";
  for (const auto& record : records) {
    EXPECT_EQ(record["status"], "timeout") << record.dump();
    EXPECT_GE(record["wall_time_s"].get<double>(), 0.5);
  }
  const auto summary = nlohmann::json::parse(ReadFile(out + "/summary.json"));
  EXPECT_EQ(summary["episodes"], 3);
  EXPECT_EQ(summary["runs"]["timeout"], 3) << summary.dump();
}

// A scene whose simulation diverges (gravity of 1e11 m/s^2: MuJoCo resets the state at every step):
// each episode ends at once with status sim_diverged and no object in a bin, recorded as such; the sweep
// goes on. (Before MuJoCo's second reset was detected, this episode hung.) Whether the first look finds
// something to try first depends on the noise's draw: an item tried counts as a failed grasp.
TEST(SweepFaults, ADivergingSimulationIsRecordedWithItsOutcomeAndTheSweepGoesOn) {
  const TempDir dir("diverge");
  // The cell scene with its relative includes intact: beside a link to the models.
  std::filesystem::create_directories(dir / "scenes");
  std::filesystem::create_symlink(std::string(SORTCELL_SOURCE_DIR) + "/models", dir / "models");
  std::filesystem::create_symlink(std::string(SORTCELL_SOURCE_DIR) + "/scenes/flange_tool.inc.xml",
                                  dir / "scenes/flange_tool.inc.xml");
  std::string scene = ReadFile(sortcell_test::kSweepScene);
  const std::string cell = "<include file=\"../models/cell/cell.inc.xml\"/>";
  ASSERT_NE(scene.find(cell), std::string::npos);
  scene.replace(scene.find(cell), cell.size(), cell + "\n  <option gravity=\"0 0 -1e11\"/>");
  std::ofstream(dir / "scenes/diverging.xml") << scene;
  std::string spec_text = ReadFile(SmallSweepSpec(dir / "diverge.yaml", 44, 2, "episode_timeout_s: 120\n"));
  spec_text.replace(0, spec_text.find('\n'), "scene: " + (dir / "scenes/diverging.xml").string());
  std::ofstream(dir / "diverge.yaml") << spec_text;

  const auto r =
      RunSortcell("sweep " + (dir / "diverge.yaml").string() + " -j 2 --metrics-only --out " + (dir / "out").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "episodes" / "000000")) << "--metrics-only: only the record stays";
  const auto records = Lines(dir / "out" / "results.jsonl");
  ASSERT_EQ(EpisodesOf(records), (std::multiset<int>{0, 1}));
  for (const auto& record : records) {
    EXPECT_EQ(record["status"], "ok") << "the worker ended normally: " << record.dump();
    EXPECT_EQ(record["summary"]["status"], "sim_diverged") << record.dump();
    EXPECT_LT(record["wall_time_s"].get<double>(), 60.0);
    for (const auto& item : record["items"]) {
      EXPECT_TRUE(item["outcome"] == "left_on_table" || item["outcome"] == "grasp_failed") << item.dump();
      EXPECT_EQ(item["bin"], "") << item.dump();
    }
  }
}

}  // namespace
