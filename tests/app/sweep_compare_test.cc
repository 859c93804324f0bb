// `sortcell compare`: two sweeps of the same episodes, items paired by episode and name, the exact
// McNemar test on the discordant pairs; a sweep against itself differs in nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "app/sweep/sweep_compare.h"
#include "app/sweep/sweep_record.h"
#include "error_of.h"
#include "run_sortcell.h"
#include "sweep_test_support.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

using sortcell_test::ErrorOf;
using sortcell_test::TempDir;

simcell::ItemResult Item(const std::string& name, cell::ItemOutcome outcome) {
  simcell::ItemResult item;
  item.name = name;
  item.true_category = "cup";
  item.attempts = 1;
  item.outcome = outcome;
  return item;
}

// `episodes` episodes of four items each; in the first `dropped` episodes, cup2 was dropped.
std::vector<SweepRecord> Sweep(int episodes, int dropped) {
  std::vector<SweepRecord> records;
  for (int e = 0; e < episodes; ++e) {
    SweepRecord r;
    r.episode = e;
    r.seed = 1000 + e;
    r.axes = {{"objects", 4}, {"placement", e % 2 ? "dense" : "sparse"}};
    for (const char* name : {"cup1", "cup2", "cup3", "cup4"}) r.items.push_back(Item(name, cell::ItemOutcome::kSorted));
    if (e < dropped) r.items[1].outcome = cell::ItemOutcome::kDropped;
    r.summary = simcell::SummarizeEpisode(r.items, 4, 4 - (e < dropped), simcell::RunFigures{});
    records.push_back(r);
  }
  return records;
}

std::filesystem::path WriteSweep(const std::filesystem::path& dir, const std::vector<SweepRecord>& records) {
  std::filesystem::create_directories(dir);
  SweepResultsWriter writer(dir / "results.jsonl");
  for (const auto& r : records) writer.Append(r);
  writer.Close();
  return dir;
}

TEST(SweepCompare, ExactMcNemarMatchesTheBinomialTail) {
  EXPECT_DOUBLE_EQ(ExactMcNemarP(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(ExactMcNemarP(3, 3), 1.0);
  EXPECT_NEAR(ExactMcNemarP(0, 10), 2.0 / 1024, 1e-12);
  EXPECT_NEAR(ExactMcNemarP(5, 1), 2 * 7.0 / 64, 1e-12);  // (1 + 6) / 2^6, both tails.
  EXPECT_NEAR(ExactMcNemarP(1, 5), ExactMcNemarP(5, 1), 1e-15);
  const double large = ExactMcNemarP(1000, 1100);  // Terms far below a double's range on their own.
  EXPECT_GT(large, 0.01);
  EXPECT_LT(large, 0.05);
}

TEST(SweepCompare, ASweepAgainstItselfDiffersInNothing) {
  const auto records = Sweep(20, 6);
  const SweepComparison c = CompareSweepRecords(records, records);
  EXPECT_EQ(c.episodes_paired, 20);
  EXPECT_EQ(c.items_paired, 80);
  EXPECT_EQ(c.sorted_only_in_a + c.sorted_only_in_b, 0);
  EXPECT_TRUE(c.changed.empty());
  EXPECT_DOUBLE_EQ(c.p_value, 1.0);
  EXPECT_FALSE(c.significant);
  EXPECT_EQ(c.a.sorted, 74);
  EXPECT_NE(ComparisonText(c, "A", "A").find("no difference"), std::string::npos);
}

TEST(SweepCompare, AFixThatSavesTenItemsIsSignificantAndEachItemIsListed) {
  const SweepComparison c = CompareSweepRecords(Sweep(20, 10), Sweep(20, 0));
  EXPECT_EQ(c.a.sorted, 70);
  EXPECT_EQ(c.b.sorted, 80);
  EXPECT_EQ(c.sorted_only_in_a, 0);
  EXPECT_EQ(c.sorted_only_in_b, 10);
  EXPECT_NEAR(c.p_value, 2.0 / 1024, 1e-12);
  EXPECT_TRUE(c.significant);
  ASSERT_EQ(c.changed.size(), 10u);
  EXPECT_EQ(c.changed[3].episode, 3);
  EXPECT_EQ(c.changed[3].seed, 1003u);
  EXPECT_EQ(c.changed[3].item, "cup2");
  EXPECT_EQ(c.changed[3].before, cell::ItemOutcome::kDropped);
  EXPECT_EQ(c.changed[3].after, cell::ItemOutcome::kSorted);
  const std::string text = ComparisonText(c, "before", "after");
  EXPECT_NE(text.find("B sorts more, significant at 5 %"), std::string::npos) << text;
  EXPECT_NE(text.find("episode 3 (seed 1003, objects=4, placement=dense): cup2: dropped -> sorted"), std::string::npos)
      << text;
}

TEST(SweepCompare, ThreeItemsAreNotEnoughToBeSignificant) {
  const SweepComparison c = CompareSweepRecords(Sweep(20, 0), Sweep(20, 3));
  EXPECT_EQ(c.sorted_only_in_a, 3);
  EXPECT_NEAR(c.p_value, 0.25, 1e-12);
  EXPECT_FALSE(c.significant);
  EXPECT_NE(ComparisonText(c, "a", "b").find("A sorts more, not significant"), std::string::npos);
}

TEST(SweepCompare, CrashedAndMissingEpisodesPairNothing) {
  auto a = Sweep(6, 0), b = Sweep(5, 2);
  b[1].status = RunStatus::kCrashed;
  b[1].items.clear();
  const SweepComparison c = CompareSweepRecords(a, b);
  EXPECT_EQ(c.episodes_paired, 4);
  EXPECT_EQ(c.episodes_unpaired, (std::vector<int>{1, 5}));
  EXPECT_EQ(c.sorted_only_in_a, 1);  // Episode 0's cup2; episode 1 crashed in B.
  EXPECT_EQ(c.b.items, 16);
}

TEST(SweepCompare, OtherEpisodesUnderOneIndexAreRefused) {
  auto a = Sweep(3, 0), b = Sweep(3, 0);
  b[2].seed = 7;
  EXPECT_EQ(ErrorOf([&] { CompareSweepRecords(a, b); }), "episode 2: seed 1002 in A, 7 in B: not the same episodes");
  b = Sweep(3, 0);
  b[1].axes["objects"] = 5;
  EXPECT_NE(ErrorOf([&] { CompareSweepRecords(a, b); }).find("episode 1: axes"), std::string::npos);
}

TEST(SweepCompare, AnotherDrawOfTheNoiseIsTheSameEpisode) {
  auto a = Sweep(3, 0), b = Sweep(3, 0);
  for (auto& r : b) r.axes["noise_seed"] = 2;
  EXPECT_EQ(CompareSweepRecords(a, b).episodes_paired, 3);
}

TEST(SweepCompare, TheCommandPrintsWritesThePageAndRefusesWhatIsNoSweep) {
  const TempDir tmp;
  const auto a = WriteSweep(tmp.path() / "a", Sweep(8, 4));
  const auto b = WriteSweep(tmp.path() / "b", Sweep(8, 0));
  std::filesystem::create_directories(b / "episodes/000002");  // Kept by sweep B only.
  std::filesystem::create_directories(a / "report");
  std::ofstream(a / "report/index.html") << "<html></html>";  // A's report page.
  std::ofstream(a / "spec.yaml") << "episodes: 8\n";
  std::ofstream(b / "spec.yaml") << "episodes: 8\n# --set model=other.json\n";
  const auto r = sortcell_test::RunSortcell("compare " + a.string() + " " + b.string() + " --out " +
                                            (tmp.path() / "cmp").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("sorted in A only 0, in B only 4"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("spec.yaml differ"), std::string::npos) << r.out;
  const std::string html = sortcell_test::ReadFile((tmp.path() / "cmp/compare.html").string());
  EXPECT_NE(html.find("<a href=\"../b/episodes/000002/metrics.json\">sorted</a>"), std::string::npos) << html;
  EXPECT_NE(html.find("<a href=\"../a/report/index.html#failure-2-cup2\">dropped</a>"), std::string::npos) << html;
  EXPECT_NE(html.find("sorted (not kept)"), std::string::npos);  // B kept episode 2 only.
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "cmp/compare.json"));

  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell("compare " + a.string() + " " + tmp.path().string() +
                                                               " --out " + (tmp.path() / "cmp2").string()),
                                    "not a sweep folder (no results.jsonl)");
  std::ofstream(b / "results.jsonl", std::ios::app) << "{not json\n";
  sortcell_test::ExpectOneLineError(sortcell_test::RunSortcell("compare " + a.string() + " " + b.string() + " --out " +
                                                               (tmp.path() / "cmp3").string()),
                                    "sweep --resume");
}

}  // namespace
}  // namespace sortcell::app
