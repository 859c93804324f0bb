// The review's words and moments: an item's attempts told from the episode's attempt log, when it failed
// (a drop: when the gripper found itself empty; never attempted: where the cell last left it), and the
// attempt log read back strictly.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "simcell/episode_metrics.h"
#include "app/sweep/sweep_record.h"
#include "app/sweep/sweep_review.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

simcell::AttemptLogEntry Dropped() {
  simcell::AttemptLogEntry a;
  a.time_s = 30.0;
  a.duration_s = 6.0;
  a.category = "cup";
  a.bin = "cup";
  a.confidence = 0.91;
  a.width_m = 0.071;
  a.result = "dropped";
  a.truth_object = "cup";
  a.phases = {{"reach", 31.0, "empty", 0.087},
              {"grasp", 31.5, "holding", 0.041},
              {"lift", 32.5, "holding", 0.041},
              {"carry", 34.2, "empty", 0.080}};
  return a;
}

simcell::AttemptLogEntry Skipped(double x, double y) {
  simcell::AttemptLogEntry a;
  a.time_s = 12.0;
  a.category = "others";
  a.bin = "others";
  a.xy = {x, y};
  a.result = "skipped: too_wide";
  return a;
}

simcell::ItemResult Item(const std::string& name, cell::ItemOutcome outcome, double x, double y) {
  simcell::ItemResult item;
  item.name = name;
  item.outcome = outcome;
  item.final_xyz = {x, y, 0};
  return item;
}

TEST(SweepReview, AttemptsAreToldInWords) {
  EXPECT_EQ(
      AttemptInWords(Dropped(), 2),
      "attempt 2 at 30.0-36.0 s: called cup (0.91) for bin cup; closed at 41 mm on a 71 mm wide view; dropped during "
      "carry at 34.2 s");
  EXPECT_EQ(AttemptInWords(Skipped(0.5, 0.1), 0), "at 12.0 s: seen, called others, not attempted: too wide");
  simcell::AttemptLogEntry released = Dropped();
  released.result = "released";
  released.squeezed_harder_in = "carry";
  EXPECT_NE(AttemptInWords(released, 1).find("released over bin cup; squeezed harder during carry"), std::string::npos);
}

TEST(SweepReview, EachFailedItemFailsWhenItsLogSays) {
  const std::vector<simcell::ItemResult> items = {
      Item("cup", cell::ItemOutcome::kDropped, 0.3, 0.2), Item("plate", cell::ItemOutcome::kUngraspable, 0.5, 0.1),
      Item("ball", cell::ItemOutcome::kSorted, 0.4, -0.2), Item("box", cell::ItemOutcome::kLeftOnTable, 0.6, -0.3)};
  const auto failures = FailuresOf(items, {Skipped(0.51, 0.11), Dropped()}, 80.0);
  ASSERT_EQ(failures.size(), 3u);  // The sorted ball is no failure.
  EXPECT_EQ(failures[0].item, "cup");
  EXPECT_DOUBLE_EQ(failures[0].at_s, 34.2);  // The end of the phase in which the gripper found itself empty.
  ASSERT_EQ(failures[0].log.size(), 1u);
  EXPECT_EQ(failures[1].item, "plate");
  EXPECT_DOUBLE_EQ(failures[1].at_s, 12.0);  // The skipped cluster where it lies.
  EXPECT_NE(failures[1].log[0].find("not attempted: too wide"), std::string::npos);
  EXPECT_DOUBLE_EQ(failures[2].at_s, 80.0);  // Never seen: the episode's end.
  EXPECT_EQ(failures[2].log[0], "never attempted; the episode ended at 80.0 s");
}

TEST(SweepReview, TheAttemptLogReadsBackAsWritten) {
  for (const simcell::AttemptLogEntry& a : {Dropped(), Skipped(0.2, 0.3)}) {
    const nlohmann::json j = a;
    EXPECT_EQ(nlohmann::json(j.get<simcell::AttemptLogEntry>()), j);
  }
  nlohmann::json bad = Dropped();
  bad["phases"][1].erase("hold");
  try {
    bad.get<simcell::AttemptLogEntry>();
    FAIL() << "read a phase without its hold";
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "phases[1].hold: missing");
  }
}

TEST(SweepReview, AnEpisodeThatCannotBeReplayedCostsOnlyItsOwnReview) {
  const sortcell_test::TempDir tmp;
  SweepRecord old;  // Written before records kept what a replay needs.
  old.episode = 4;
  old.items = {Item("cup", cell::ItemOutcome::kDropped, 0.3, 0.2)};
  old.summary = simcell::SummarizeEpisode(old.items, 1, 1, simcell::RunFigures{});
  SweepRecord fine = old;
  fine.episode = 5;
  fine.items[0].outcome = cell::ItemOutcome::kSorted;  // Nothing to review.
  {
    SweepResultsWriter writer(tmp.path() / "results.jsonl");
    writer.Append(old);
    writer.Append(fine);
    writer.Close();
  }
  const SweepReview review = ReviewSweep(tmp.path());
  EXPECT_EQ(review.episodes_replayed, 0);
  ASSERT_EQ(review.not_replayed.size(), 1u);
  EXPECT_EQ(review.not_replayed[0].find("episode 4: recorded before sweeps kept what a replay needs"), 0u)
      << review.not_replayed[0];
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "review.json"));
}

}  // namespace
}  // namespace sortcell::app
