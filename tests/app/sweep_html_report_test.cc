// The report page's data and file: what the page shows comes from the folder's records, summary and
// review; no value can close the page's script; a folder that is no finished sweep is refused; without
// Chart.js the page is still written.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "app/sweep/sweep_html_report.h"
#include "app/sweep/sweep_record.h"
#include "error_of.h"
#include "files/output_dir.h"
#include "temp_dir.h"

namespace sortcell::app {
namespace {

using sortcell_test::ErrorOf;
using sortcell_test::TempDir;

std::filesystem::path SweepFolder(const std::filesystem::path& dir) {
  std::filesystem::create_directories(dir);
  SweepResultsWriter writer(dir / "results.jsonl");
  for (int e : {1, 0}) {
    SweepRecord r;
    r.episode = e;
    r.seed = 40 + e;
    r.axes = {{"placement", "dense"}};
    simcell::ItemResult item;
    item.name = e ? "</script><b>cup" : "<!--<script>ball";
    item.outcome = e ? cell::ItemOutcome::kDropped : cell::ItemOutcome::kSorted;
    r.items = {item};
    r.summary = simcell::SummarizeEpisode(r.items, 1, 1, simcell::RunFigures{});
    writer.Append(r);
  }
  writer.Close();
  std::ofstream(dir / "summary.json") << R"({"episodes": 2, "items": 2})";
  return dir;
}

TEST(SweepHtmlReport, TheDataAreTheFoldersInEpisodeOrder) {
  const TempDir tmp;
  const auto dir = SweepFolder(tmp.path() / "sweep");
  nlohmann::json data = ReportData(dir);
  EXPECT_EQ(data["name"], "sweep");
  EXPECT_EQ(ReportData(dir / "")["name"], "sweep");
  EXPECT_EQ(ReportData(dir / ".")["name"], "sweep");
  EXPECT_EQ(data["summary"]["items"], 2);
  ASSERT_EQ(data["episodes"].size(), 2u);
  EXPECT_EQ(data["episodes"][0]["episode"], 0);
  EXPECT_EQ(data["episodes"][1]["items"][0], nlohmann::json({"</script><b>cup", "dropped"}));
  EXPECT_EQ(data["episodes"][0]["items"][0], nlohmann::json({"<!--<script>ball", "sorted"}));
  EXPECT_TRUE(data["review"].is_null());
  std::ofstream(dir / "review.json") << R"({"failures": []})";
  EXPECT_TRUE(ReportData(dir)["review"].is_object());
}

TEST(SweepHtmlReport, NoValueClosesThePagesScript) {
  const TempDir tmp;
  const std::string page = ReportPage(ReportData(SweepFolder(tmp.path() / "sweep")));
  EXPECT_EQ(page.find("</script><b>"), std::string::npos);
  EXPECT_EQ(page.find("<!--<script>"), std::string::npos);
  EXPECT_NE(page.find(R"(\u003c/script>\u003cb>cup)"), std::string::npos);
  EXPECT_NE(page.find(R"(\u003c!--\u003cscript>ball)"), std::string::npos);
  EXPECT_EQ(page.find("/*SORTCELL_DATA*/"), std::string::npos);
}

TEST(SweepHtmlReport, WhatIsNoFinishedSweepIsRefused) {
  const TempDir tmp;
  EXPECT_EQ(ErrorOf([&] { ReportData(tmp.path()); }),
            "'" + tmp.path().string() + "': not a finished sweep folder (no summary.json)");
  const auto dir = SweepFolder(tmp.path() / "sweep");
  std::ofstream(dir / "summary.json") << "{oops";
  EXPECT_NE(ErrorOf([&] { ReportData(dir); }).find("summary.json': not JSON"), std::string::npos);
}

TEST(SweepHtmlReport, WithoutChartJsThePageIsStillWritten) {
  const TempDir tmp;
  const auto dir = SweepFolder(tmp.path() / "sweep");
  ASSERT_EQ(setenv("SORTCELL_CHART_JS", (tmp.path() / "none.js").c_str(), 1), 0);
  const auto page = WriteHtmlReport(dir);
  unsetenv("SORTCELL_CHART_JS");
  EXPECT_TRUE(std::filesystem::exists(page));
  EXPECT_FALSE(std::filesystem::exists(dir / "report/chart.min.js"));
  EXPECT_NE(files::ReadTextFile(page).find("chart.min.js is missing beside this page"), std::string::npos);
}

}  // namespace
}  // namespace sortcell::app
