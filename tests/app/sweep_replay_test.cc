// `sortcell replay`: what cannot be replayed the same is refused with the reason, without running
// anything; what differs between two records is named by its JSON path, machine figures aside. (The
// replay of a real sweep's failed episode: SweepReplay.AFailedEpisodeIsReviewedWithAClipAndReplayedExactly, sim.)
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "files/build_identity.h"
#include "app/sweep/sweep_record.h"
#include "app/sweep/sweep_replay.h"
#include "run_sortcell.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

using sortcell_test::TempDir;

SweepRecord Recorded(const std::filesystem::path& model) {
  SweepRecord r;
  r.episode = 2;
  r.seed = 9;
  r.axes = {{"objects", 2}};
  simcell::ItemResult cup;
  cup.name = "cup";
  cup.true_category = "cup";
  cup.outcome = cell::ItemOutcome::kDropped;
  r.items = {cup};
  r.summary = simcell::SummarizeEpisode(r.items, 1, 1, simcell::RunFigures{});
  r.replay = ReplayRecipe{{"episode", "--seed", "9", "--model", model.string()},
                          files::FileDigest(SORTCELL_BINARY),
                          files::FileDigest(model)};
  return r;
}

std::filesystem::path Folder(const std::filesystem::path& dir, const std::vector<SweepRecord>& records) {
  std::filesystem::create_directories(dir);
  SweepResultsWriter writer(dir / "results.jsonl");
  for (const auto& r : records) writer.Append(r);
  writer.Close();
  return dir;
}

sortcell_test::Result Replay(const std::filesystem::path& dir, int episode) {
  return sortcell_test::RunSortcell("replay " + dir.string() + " --episode " + std::to_string(episode));
}

TEST(SweepReplay, TheReplayBlockRoundTrips) {
  const TempDir tmp;
  const std::filesystem::path model = tmp.path() / "m.json";
  std::ofstream(model) << "{}";
  const SweepRecord r = Recorded(model);
  const SweepRecord back = nlohmann::json(r).get<SweepRecord>();
  ASSERT_TRUE(back.replay);
  EXPECT_EQ(back.replay->arguments, r.replay->arguments);
  EXPECT_EQ(back.replay->build, r.replay->build);
  EXPECT_EQ(back.replay->model_digest, r.replay->model_digest);
  nlohmann::json j = r;
  j["replay"].erase("build");
  EXPECT_THROW(j.get<SweepRecord>(), std::invalid_argument);
  j.erase("replay");
  EXPECT_FALSE(j.get<SweepRecord>().replay);  // Results from before replays still read.
}

TEST(SweepReplay, DifferencesAreNamedByPathAndMachineFiguresAreNone) {
  const TempDir tmp;
  const std::filesystem::path model = tmp.path() / "m.json";
  std::ofstream(model) << "{}";
  const SweepRecord r = Recorded(model);
  nlohmann::json a = r, b = r;
  b["wall_time_s"] = 99.0;
  b["summary"]["real_time_factor"] = 3.0;
  b["summary"]["video_frames"] = 300;
  b["summary"]["physics_profile"]["step_s"] = 1.5;
  EXPECT_TRUE(RecordDifferences(a, b).empty());
  b["items"][0]["outcome"] = "sorted";
  const auto d = RecordDifferences(a, b);
  ASSERT_EQ(d.size(), 1u);
  EXPECT_EQ(d[0], "/items/0/outcome: sweep \"dropped\", replay \"sorted\"");
}

TEST(SweepReplay, WhatWouldNotBeTheSameEpisodeIsRefusedWithTheReason) {
  const TempDir tmp;
  const std::filesystem::path model = tmp.path() / "m.json";
  std::ofstream(model) << "{}";
  const SweepRecord good = Recorded(model);

  sortcell_test::ExpectOneLineError(Replay(tmp.path(), 0), "not a sweep folder (no results.jsonl)");
  sortcell_test::ExpectOneLineError(Replay(Folder(tmp.path() / "a", {good}), 5), "episode 5: not in");

  SweepRecord crashed = good;
  crashed.status = RunStatus::kCrashed;
  sortcell_test::ExpectOneLineError(Replay(Folder(tmp.path() / "b", {crashed}), 2),
                                    "episode 2 crashed in the sweep: no record to compare with");
  SweepRecord old = good;
  old.replay.reset();
  sortcell_test::ExpectOneLineError(Replay(Folder(tmp.path() / "c", {old}), 2),
                                    "recorded before sweeps kept what a replay needs");
  SweepRecord other_build = good;
  other_build.replay->build = "0123456789abcdef";
  sortcell_test::ExpectOneLineError(Replay(Folder(tmp.path() / "d", {other_build}), 2),
                                    "episode 2 ran on another build (digest 0123456789abcdef");
  const auto dir = Folder(tmp.path() / "e", {good});
  std::ofstream(model) << "{\"retrained\": true}";
  sortcell_test::ExpectOneLineError(Replay(dir, 2), "has changed since the sweep");
  std::filesystem::remove(model);
  sortcell_test::ExpectOneLineError(Replay(dir, 2), "its model is gone");
  EXPECT_FALSE(std::filesystem::exists(dir / "replays"));  // Nothing ran.
}

}  // namespace
}  // namespace sortcell::app
