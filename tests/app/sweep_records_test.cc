// The sweep's typed records (results.jsonl): round trip, strict reading with errors that name the
// file, line and key; the report's checked, quoted CSV; and --set on `episode` and `sweep`.
#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "app/cli/episode_command.h"
#include "app/sweep/sweep_lock.h"
#include "app/sweep/sweep_record.h"
#include "app/sweep/sweep_report.h"
#include "app/sweep/sweep_spec.h"
#include "error_of.h"
#include "files/output_dir.h"
#include "run_sortcell.h"
#include "temp_dir.h"
#include "source_tree.h"

namespace sortcell::app {
namespace {

using sortcell_test::ErrorOf;
using sortcell_test::TempDir;

using sortcell_test::kCell;
using sortcell_test::kSource;
const std::string kSet = kSource + "/scenes/objects/paper.yaml";

// The first line of a results.jsonl written before the records were typed (two of its items kept).
const std::string kOldLine =
    R"({"axes":{"objects":6},"episode":0,"items":[{"attempts":1,"confidence":0.9867939749764291,"cycle_time_s":13.052000000015951,)"
    R"("final_xyz":[0.3859753375632356,-0.4243846303689717,0.008688501691959859],"name":"bottle3","outcome":"sorted",)"
    R"("predicted_category":"others","true_category":"others"},{"attempts":1,"confidence":0.9894401504002078,)"
    R"("cycle_time_s":11.543999999997176,"final_xyz":[0.394846591054806,0.40904708809087653,0.00027294697641732816],)"
    R"("name":"cup","outcome":"sorted","predicted_category":"cup","true_category":"cup"}],"seed":0,"status":"ok",)"
    R"("summary":{"correct_sort_rate":1.0,"frames":7,"grasp_attempts":6,"grasp_success_rate":1.0,"grasps":6,"items":6,)"
    R"("items_classified":6,"mean_cycle_time_s":12.23866666666799,"mujoco_warnings":0,"outcomes":{"dropped":0,)"
    R"("grasp_failed":0,"left_on_table":0,"not_detected":0,"sorted":6,"unreachable":0,"wrong_bin":0},)"
    R"("perception_ms_per_frame":24.124468999999994,"real_time_factor":12.025111796484216,"recognition_accuracy":1.0,)"
    R"("render_ms_per_frame":117.4162777142857,"sim_time_s":75.4320000000056,"status":"completed","video_frames":0,)"
    R"("video_render_wall_s":0.0,"wall_time_s":6.272873074},"wall_time_s":6.599238022})";

// An episode that ran: one item sorted, one never grasped.
SweepRecord OkRecord(int episode, const nlohmann::json& axes) {
  SweepRecord r;
  r.episode = episode;
  r.seed = 100 + episode;
  r.axes = axes.is_null() ? nlohmann::json::object() : axes;  // {} is null.
  r.wall_time_s = 6.5;
  r.status = RunStatus::kOk;
  simcell::ItemResult cup;
  cup.name = "cup";
  cup.true_category = "cup";
  cup.predicted_category = "cup";
  cup.confidence = 0.9;
  cup.attempts = 1;
  cup.outcome = cell::ItemOutcome::kSorted;
  cup.cycle_time_s = 12.5;
  cup.final_xyz = {0.4, 0.4, 0.01};
  simcell::ItemResult ball;
  ball.name = "ball";
  ball.true_category = "ball";
  ball.attempts = 2;
  ball.outcome = cell::ItemOutcome::kGraspFailed;
  simcell::RunFigures run;
  run.sim_time_s = 40;
  run.wall_time_s = 4;
  run.real_time_factor = 10;
  run.frames = 3;
  r.items = {cup, ball};
  r.summary = simcell::SummarizeEpisode(r.items, 3, 1, run);
  return r;
}

std::string Dump(const SweepRecord& r) { return nlohmann::json(r).dump(); }

std::filesystem::path WriteFile(const std::filesystem::path& file, const std::string& text) {
  std::ofstream(file, std::ios::binary) << text;
  return file;
}

// ---- Records ----

TEST(SweepRecord, RoundTripKeepsEveryField) {
  const SweepRecord r = OkRecord(3, {{"objects", 2}, {"noise_scale", 1.25}});
  const nlohmann::json j = r;
  const SweepRecord back = j.get<SweepRecord>();
  EXPECT_EQ(nlohmann::json(back), j);
  EXPECT_EQ(back.episode, 3);
  EXPECT_EQ(back.seed, 103u);
  EXPECT_EQ(back.axes["noise_scale"], 1.25);
  EXPECT_EQ(back.status, RunStatus::kOk);
  ASSERT_EQ(back.items.size(), 2u);
  EXPECT_EQ(back.items[1].outcome, cell::ItemOutcome::kGraspFailed);
  EXPECT_FALSE(back.items[1].predicted_category.has_value());
  EXPECT_EQ(back.summary.grasps, 1);
  EXPECT_EQ(back.summary.outcomes.at(cell::ItemOutcome::kSorted), 1);
  EXPECT_DOUBLE_EQ(back.summary.run.sim_time_s, 40);

  SweepRecord failed;
  failed.episode = 4;
  failed.status = RunStatus::kTimeout;
  failed.signal = 9;
  failed.error = "killed after 900 s";
  failed.peak_memory_mb = 312.5;
  const nlohmann::json f = failed;
  EXPECT_EQ(f["status"], "timeout");
  EXPECT_EQ(f["peak_memory_mb"], 312.5);
  EXPECT_FALSE(j.contains("peak_memory_mb")) << "absent when not measured";
  EXPECT_FALSE(f.contains("summary"));
  EXPECT_FALSE(f.contains("exit_code"));
  const SweepRecord failed_back = f.get<SweepRecord>();
  EXPECT_EQ(nlohmann::json(failed_back), f);
  EXPECT_EQ(failed_back.signal, 9);
  EXPECT_EQ(failed_back.peak_memory_mb, 312.5);
  EXPECT_FALSE(failed_back.exit_code.has_value());
}

TEST(SweepReport, WorkerRunsAndTheirMemoryAreSummarised) {
  const TempDir dir("report_runs");
  SweepRecord ok = OkRecord(0, {});
  ok.peak_memory_mb = 300;
  SweepRecord slow;
  slow.episode = 1;
  slow.status = RunStatus::kTimeout;
  slow.error = "killed after 1 s";
  slow.peak_memory_mb = 500;
  const nlohmann::json summary = WriteSweepReport(dir.path(), SweepSpec(), {slow, ok});
  EXPECT_EQ(summary["runs"]["ok"], 1);
  EXPECT_EQ(summary["runs"]["timeout"], 1);
  EXPECT_EQ(summary["runs"]["crashed"], 0);
  ASSERT_EQ(summary["runs"]["not_ok"].size(), 1u);
  EXPECT_EQ(summary["runs"]["not_ok"][0]["episode"], 1);
  EXPECT_EQ(summary["resources"]["worker_peak_memory_mb"]["max"], 500.0);
  EXPECT_EQ(summary["resources"]["worker_peak_memory_mb"]["median"], 500.0) << "the upper median of two";
  EXPECT_NE(files::ReadTextFile(dir / "summary.md")
                .find("Worker runs: ok 1, crashed 0, timeout 1; episode 1 timeout (killed after 1 s). "
                      "Peak memory per worker: median 500 MiB, largest 500 MiB."),
            std::string::npos)
      << files::ReadTextFile(dir / "summary.md");
}

TEST(SweepRecord, StatusSpellings) {
  for (const RunStatus s : {RunStatus::kOk, RunStatus::kCrashed, RunStatus::kTimeout}) {
    EXPECT_EQ(ParseRunStatus(ToString(s)), s);
  }
  EXPECT_EQ(ErrorOf([] { ParseRunStatus("exploded"); }),
            "unknown run status 'exploded' (expected ok, crashed or timeout)");
}

TEST(SweepResults, OldResultsReadAndWriteBackTheSameKeys) {
  const TempDir dir("records_old");
  const auto file = WriteFile(dir / "results.jsonl", kOldLine + "\n");
  const SweepResults results = ReadSweepResults(file);
  ASSERT_EQ(results.records.size(), 1u);
  const SweepRecord& r = results.records[0];
  EXPECT_EQ(r.axes, nlohmann::json({{"objects", 6}}));
  EXPECT_EQ(r.summary.grasp_attempts, 6);
  EXPECT_EQ(r.items[1].name, "cup");
  // Written back: the same keys and values, plus the summary figures added since.
  nlohmann::json back = r;
  for (const char* key :
       {"picks_per_hour", "cycle_phases_s", "tracking_max_error_rad", "torque_saturated_samples", "profile_wall_s",
        "physics_profile", "carry_slip_max_mm", "carry_slip_mean_mm", "carries", "carry_turn_max_deg", "calibration",
        "mean_cycle_bound_s", "cycle_to_bound", "cycle_phases_bound_s"}) {
    ASSERT_TRUE(back["summary"].contains(key)) << key;
    back["summary"].erase(key);
  }
  for (auto& item : back["items"]) {  // The cycle's bound, added since: null (not known) in an old record.
    ASSERT_TRUE(item.contains("cycle_bound_s"));
    EXPECT_TRUE(item["cycle_bound_s"].is_null());
    item.erase("cycle_bound_s");
  }
  ASSERT_EQ(back["summary"]["outcomes"]["ungraspable"], 0);  // an outcome added since
  back["summary"]["outcomes"].erase("ungraspable");
  EXPECT_EQ(back, nlohmann::json::parse(kOldLine));
  EXPECT_EQ(results.complete_bytes, results.file_bytes);
}

TEST(SweepResults, WrittenRecordsReadBack) {
  const TempDir dir("records_write");
  const auto file = dir / "results.jsonl";
  {
    SweepResultsWriter writer(file);
    writer.Append(OkRecord(0, {{"objects", 2}}));
    writer.Append(OkRecord(1, {{"objects", 3}}));
    writer.Close();
  }
  const SweepResults results = ReadSweepResults(file);
  ASSERT_EQ(results.records.size(), 2u);
  EXPECT_EQ(results.records[1].episode, 1);
  EXPECT_EQ(files::ReadTextFile(file),
            Dump(OkRecord(0, {{"objects", 2}})) + "\n" + Dump(OkRecord(1, {{"objects", 3}})) + "\n");
}

TEST(SweepResults, ACalibratedEpisodesFiguresReadBack) {
  SweepRecord r = OkRecord(0, {{"camera_shift_m", 0.04}});
  simcell::CalibrationFigures c;
  c.status = "ok";
  c.sightings = 18, c.inliers = 17;
  c.rms_residual_m = 0.0002, c.duration_s = 17.6, c.error_m = 0.0004, c.error_rad = 0.0005;
  c.prior_error_m = 0.04, c.prior_error_rad = 0.03;
  r.summary.calibration = c;
  const SweepRecord back = nlohmann::json(r).get<SweepRecord>();
  ASSERT_TRUE(back.summary.calibration.has_value());
  EXPECT_EQ(nlohmann::json(*back.summary.calibration), nlohmann::json(c));
  nlohmann::json damaged = r;
  damaged["summary"]["calibration"].erase("error_m");
  try {
    (void)damaged.get<SweepRecord>();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("error_m: missing"), std::string::npos) << e.what();
  }
}

TEST(SweepLock, OneSweepAtATimeInAFolder) {
  const TempDir dir("lock");
  {
    const SweepLock first(dir.path());
    try {
      const SweepLock second(dir.path());
      FAIL() << "a second lock was taken";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("another sweep is running in it (it holds " + (dir / "sweep.lock").string()),
                std::string::npos)
          << e.what();
    }
  }
  EXPECT_NO_THROW(SweepLock again(dir.path())) << "released when the first ended";
  EXPECT_THROW(SweepLock nowhere(dir / "missing" / "folder"), std::invalid_argument);
}

TEST(SweepResults, AFullDiskIsAnErrorNamingTheFile) {
  if (!std::filesystem::exists("/dev/full")) GTEST_SKIP() << "no /dev/full";
  SweepResultsWriter writer("/dev/full");
  try {
    writer.Append(OkRecord(0, {}));
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '/dev/full'"), std::string::npos) << e.what();
  }
}

// results.jsonl with `middle` as line 2 between two good records: what reading it says of line 2
// (the two good records read, and kept for the rewrite).
std::string ErrorWithLine2(const std::string& name, const std::string& middle) {
  const TempDir dir("results_of_" + name);  // A folder name no key contains.
  const std::string good = Dump(OkRecord(0, {})) + "\n", other = Dump(OkRecord(2, {})) + "\n";
  const auto file = WriteFile(dir / "results.jsonl", good + middle + "\n" + other);
  const SweepResults results = ReadSweepResults(file);
  EXPECT_EQ(results.records.size(), 2u);
  EXPECT_EQ(results.good_text, good + other);
  return results.damaged.size() == 1 ? results.damaged[0] : "";
}

// A good record with one change.
std::string Changed(const std::function<void(nlohmann::json&)>& change) {
  nlohmann::json j = OkRecord(1, {});
  change(j);
  return j.dump();
}

TEST(SweepResults, BadLinesNameTheFileTheLineAndTheKey) {
  const auto expect = [](const std::string& error, const std::string& name, const std::string& where) {
    EXPECT_NE(error.find("results_of_" + name + "_"), std::string::npos) << error;  // The file.
    EXPECT_NE(error.find("/results.jsonl line 2: " + where), std::string::npos) << error;
  };
  expect(ErrorWithLine2("missing", Changed([](nlohmann::json& j) { j["summary"].erase("grasps"); })), "missing",
         "summary.grasps: missing");
  expect(ErrorWithLine2("mistyped", Changed([](nlohmann::json& j) { j["summary"]["grasps"] = "six"; })), "mistyped",
         "summary.grasps: expected a number, found string");
  expect(ErrorWithLine2("status", Changed([](nlohmann::json& j) { j["status"] = "exploded"; })), "status",
         "status: unknown run status 'exploded'");
  expect(ErrorWithLine2("outcome", Changed([](nlohmann::json& j) { j["items"][1]["outcome"] = "vanished"; })),
         "outcome", "items[1].outcome: unknown item outcome 'vanished'");
  expect(ErrorWithLine2("episode", Changed([](nlohmann::json& j) { j.erase("episode"); })), "episode",
         "episode: missing");
  expect(ErrorWithLine2("axes", Changed([](nlohmann::json& j) { j["axes"] = 3; })), "axes", "axes: expected an object");
  // A line cut short in the middle of the file (e.g. shards concatenated after an interruption).
  expect(ErrorWithLine2("damaged", R"({"episode":1,"sta)"), "damaged", "not a JSON record");
}

TEST(SweepResults, ACutShortLastLineIsNoRecord) {
  const TempDir dir("records_cut");
  const std::string good = Dump(OkRecord(0, {})) + "\n";
  const auto file = WriteFile(dir / "results.jsonl", good + R"({"episode":1,"sta)");
  const SweepResults results = ReadSweepResults(file);
  EXPECT_EQ(results.records.size(), 1u);
  EXPECT_EQ(results.complete_bytes, good.size());
  EXPECT_GT(results.file_bytes, results.complete_bytes);
  EXPECT_TRUE(ReadSweepResults(dir / "none.jsonl").records.empty());
}

// ---- The report ----

// A one-episode grid over one axis of text values.
SweepSpec TextAxisSpec(const std::string& name, const std::vector<std::string>& values) {
  SweepSpec spec;
  spec.source = "/specs/" + name + ".yaml";
  spec.grid = true;
  spec.episodes = 1;
  SweepAxis axis;
  axis.name = name;
  for (const auto& v : values) axis.values.push_back(v);
  spec.axes.push_back(axis);
  return spec;
}

// A CSV line's cells (quoted cells may hold commas and doubled quotes).
std::vector<std::string> CsvCells(const std::string& line) {
  std::vector<std::string> cells(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char c = line[i];
    if (c == '"' && quoted && i + 1 < line.size() && line[i + 1] == '"') {
      cells.back() += '"', ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (c == ',' && !quoted) {
      cells.emplace_back();
    } else {
      cells.back() += c;
    }
  }
  return cells;
}

// summary.csv's cell in `column` of the row of (axis, value); "<none>" if there is no such row or column.
std::string CsvCell(const std::string& csv, const std::string& axis, const std::string& value,
                    const std::string& column) {
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = CsvCells(line);
  const auto at = std::find(header.begin(), header.end(), column);
  while (std::getline(in, line)) {
    const std::vector<std::string> cells = CsvCells(line);
    if (cells.size() == header.size() && cells[0] == axis && cells[1] == value && at != header.end())
      return cells[at - header.begin()];
  }
  return "<none>";
}

TEST(SweepReport, CsvQuotesAValueWithAComma) {
  const TempDir dir("report_csv");
  const std::vector<std::string> models{"/models/a,b.model.json", "/models/plain.model.json",
                                        "/models/say \"hi\".model.json"};
  const SweepSpec spec = TextAxisSpec("model", models);
  std::vector<SweepRecord> records;
  for (int i = 0; i < 3; ++i) records.push_back(OkRecord(i, {{"model", models[i]}}));
  const nlohmann::json summary = WriteSweepReport(dir.path(), spec, records);
  const std::string csv = files::ReadTextFile(dir / "summary.csv");
  EXPECT_NE(csv.find("\nmodel,\"a,b.model.json\","), std::string::npos) << csv;
  EXPECT_NE(csv.find("\nmodel,\"say \"\"hi\"\".model.json\","), std::string::npos) << csv;
  for (const char* model : {"a,b.model.json", "plain.model.json", "say \"hi\".model.json"}) {
    EXPECT_EQ(CsvCell(csv, "model", model, "episodes"), "1") << csv;
    EXPECT_EQ(CsvCell(csv, "model", model, "items"), "2") << csv;
    EXPECT_EQ(CsvCell(csv, "model", model, "outcomes.sorted"), "1") << csv;
    EXPECT_EQ(CsvCell(csv, "model", model, "correct_sort_rate"), "0.5") << csv;
  }
  EXPECT_EQ(CsvCell(csv, "all", "all", "items"), "6") << csv;
  EXPECT_EQ(CsvCell(csv, "all", "all", "outcomes.sorted"), "3") << csv;
  EXPECT_EQ(summary["items"], 6);
  EXPECT_EQ(summary["grasp_attempts"], 9);
  EXPECT_EQ(summary["by_axis"]["model"]["a,b.model.json"]["outcomes"]["grasp_failed"], 1);
  EXPECT_NE(files::ReadTextFile(dir / "summary.md").find("| a,b.model.json | 1 | 2 | 50.0 % |"), std::string::npos);
}

// The CSV's columns follow from the records' field lists: every figure of a group in summary.json is a
// column, and the pooled run figures are there.
TEST(SweepReport, CsvColumnsAreTheGroupsFigures) {
  const TempDir dir("report_columns");
  std::vector<SweepRecord> records{OkRecord(0, {}), OkRecord(1, {})};
  records[0].summary.run.carry_turn_max_deg = 2.5;
  records[1].summary.run.carry_turn_max_deg = 4.0;
  const nlohmann::json summary = WriteSweepReport(dir.path(), SweepSpec(), records);
  const std::string csv = files::ReadTextFile(dir / "summary.csv");
  EXPECT_DOUBLE_EQ(summary["carry_turn_max_deg"].get<double>(), 4.0);
  EXPECT_EQ(CsvCell(csv, "all", "all", "carry_turn_max_deg"), "4.0") << csv;
  EXPECT_EQ(CsvCell(csv, "all", "all", "sim_time_s"), summary["sim_time_s"].dump()) << csv;
  EXPECT_EQ(CsvCell(csv, "all", "all", "correct_sort_rate_ci95.1"), summary["correct_sort_rate_ci95"][1].dump());
  EXPECT_EQ(CsvCell(csv, "all", "all", "rejection.known_objects"), summary["rejection"]["known_objects"].dump());
  // Figures that do not pool are not a group's (calibrations are summed up apart, at the top).
  for (const char* not_pooled : {"status", "perception_ms_per_frame", "physics_profile", "calibration"}) {
    EXPECT_FALSE(summary["by_object"]["ball"].contains(not_pooled)) << not_pooled;
    if (std::string(not_pooled) != "calibration") {
      EXPECT_FALSE(summary.contains(not_pooled)) << not_pooled;
    }
  }
}

TEST(SweepReport, APlacementAxisIsGroupedByMode) {
  const TempDir dir("report_placement");
  const SweepSpec spec = TextAxisSpec("placement", {"dense", "clustered"});
  const std::vector<SweepRecord> records{OkRecord(0, {{"placement", "dense"}}),
                                         OkRecord(1, {{"placement", "clustered"}})};
  const nlohmann::json summary = WriteSweepReport(dir.path(), spec, records);
  EXPECT_EQ(summary["by_axis"]["placement"]["dense"]["items"], 2);
  EXPECT_NE(files::ReadTextFile(dir / "summary.md").find("| clustered | 1 | 2 | 50.0 % |"), std::string::npos)
      << files::ReadTextFile(dir / "summary.md");
  EXPECT_THROW(WriteSweepReport(dir.path(), spec, {OkRecord(0, {{"placement", 3}})}), std::invalid_argument);
}

TEST(SweepReport, PicksPerHourAndTheCycleByPhasePooledOverEpisodes) {
  const TempDir dir("report_phases");
  std::vector<SweepRecord> records{OkRecord(0, {}), OkRecord(1, {})};
  // Episode 0: 3 attempts, 2 s approach each; episode 1: 3 attempts, 4 s approach each.
  records[0].summary.run.cycle_phases_s = {{"approach", 2.0}, {"carry", 1.0}};
  records[1].summary.run.cycle_phases_s = {{"approach", 4.0}};
  records[1].summary.run.torque_saturated_samples = 5;
  records[1].summary.run.tracking_max_error_rad = 0.02;
  const nlohmann::json summary = WriteSweepReport(dir.path(), SweepSpec(), records);
  EXPECT_DOUBLE_EQ(summary["picks_per_hour"].get<double>(), 3600.0 * 2 / 80);  // 2 sorted in 2 x 40 s
  EXPECT_DOUBLE_EQ(summary["cycle_phases_s"]["approach"].get<double>(), 3.0);
  EXPECT_DOUBLE_EQ(summary["cycle_phases_s"]["carry"].get<double>(), 0.5);
  EXPECT_EQ(summary["torque_saturated_samples"], 5);
  EXPECT_DOUBLE_EQ(summary["tracking_max_error_rad"].get<double>(), 0.02);
  EXPECT_NE(
      files::ReadTextFile(dir / "summary.md").find("mean simulated seconds per attempt: approach 3.00, carry 0.50."),
      std::string::npos)
      << files::ReadTextFile(dir / "summary.md");
}

TEST(SweepReport, FailuresByObjectAndTheCalibrations) {
  const TempDir dir("report_objects");
  std::vector<SweepRecord> records{OkRecord(0, {}), OkRecord(1, {})};
  records[1].items[1].outcome = cell::ItemOutcome::kSorted;  // The ball, sorted once of twice.
  simcell::CalibrationFigures c;
  c.status = "ok";
  c.error_m = 0.0004, c.error_rad = 0.0003, c.prior_error_m = 0.05, c.prior_error_rad = 0.05, c.duration_s = 17.5;
  records[0].summary.calibration = c;
  c.error_m = 0.0008;
  records[1].summary.calibration = c;
  const nlohmann::json summary = WriteSweepReport(dir.path(), SweepSpec(), records);
  EXPECT_EQ(summary["by_object"]["ball"]["items"], 2);
  EXPECT_EQ(summary["by_object"]["ball"]["outcomes"]["grasp_failed"], 1);
  EXPECT_EQ(summary["by_object"]["cup"]["episodes"], 2);
  const std::string md = files::ReadTextFile(dir / "summary.md");
  EXPECT_NE(md.find("| ball | 2 | 2 | 50.0 % |"), std::string::npos) << md;
  const std::string csv = files::ReadTextFile(dir / "summary.csv");
  EXPECT_EQ(CsvCell(csv, "object", "ball", "items"), "2") << csv;
  EXPECT_EQ(CsvCell(csv, "object", "ball", "correct_sort_rate"), "0.5") << csv;
  EXPECT_EQ(summary["calibration"]["episodes"], 2);
  EXPECT_DOUBLE_EQ(summary["calibration"]["max_error_m"].get<double>(), 0.0008);
  EXPECT_NE(md.find("Self-calibration in 2 episodes (2 ok): camera error median 0.80 mm"), std::string::npos) << md;
  EXPECT_TRUE(WriteSweepReport(dir.path(), SweepSpec(), {OkRecord(0, {})})["calibration"].is_null());
}

TEST(SweepReport, AFailedWriteIsAnErrorNamingTheFile) {
  const TempDir dir("report_fail");
  SweepSpec spec;
  spec.source = "/specs/x.yaml";
  try {
    WriteSweepReport(dir / "not_there", spec, {OkRecord(0, {})});
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("cannot write '" + (dir / "not_there").string() + "/summary."),
              std::string::npos)
        << e.what();
  }
}

// ---- --set on episode ----

// A `sortcell` command line parsed as RunCli does: --set expanded, then CLI11.
struct ParsedEpisode {
  CLI::App app;
  std::function<int()> run;
  CLI::App* episode = nullptr;

  explicit ParsedEpisode(std::vector<std::string> args) {
    AddEpisodeCommand(app, run, {});
    episode = app.get_subcommand("episode");
    args = ExpandEpisodeSets(*episode, args);
    std::vector<char*> argv;
    for (auto& a : args) argv.push_back(a.data());
    app.parse(static_cast<int>(argv.size()), argv.data());
  }
};

TEST(EpisodeSet, RewritesToTheOptionAfterTheOthers) {
  CLI::App app;
  std::function<int()> run;
  AddEpisodeCommand(app, run, {});
  const CLI::App& episode = *app.get_subcommand("episode");
  EXPECT_EQ(ExpandEpisodeSets(episode, {"sortcell", "episode", "--set", "seed=3", "--scene", "s.xml",
                                        "--set=noise-scale=1.5", "--out", "o"}),
            (std::vector<std::string>{"sortcell", "episode", "--scene", "s.xml", "--out", "o", "--seed=3",
                                      "--noise-scale=1.5"}));
}

TEST(EpisodeSet, AKnownKeyTakesEffectAndOverridesTheOption) {
  const ParsedEpisode p({"sortcell", "episode", "--scene", "s.xml", "--noise-scale", "2", "--set", "noise-scale=1.5",
                         "--set", "seed=3", "--set", "time-limit=100", "--out", "o"});
  EXPECT_DOUBLE_EQ(p.episode->get_option("--noise-scale")->as<double>(), 1.5);
  EXPECT_EQ(p.episode->get_option("--seed")->as<uint64_t>(), 3u);
  EXPECT_DOUBLE_EQ(p.episode->get_option("--time-limit")->as<double>(), 100);
  EXPECT_TRUE(static_cast<bool>(p.run));
}

TEST(EpisodeSet, TheOptionsOwnChecksApply) {
  EXPECT_THROW(ParsedEpisode({"sortcell", "episode", "--scene", "s.xml", "--out", "o", "--set", "objects=500"}),
               CLI::ValidationError);
  EXPECT_THROW(ParsedEpisode({"sortcell", "episode", "--scene", "s.xml", "--out", "o", "--set", "seed=-1"}),
               CLI::ValidationError);
}

TEST(EpisodeSet, AnUnknownKeyIsRejectedWithTheValidOnes) {
  CLI::App app;
  std::function<int()> run;
  AddEpisodeCommand(app, run, {});
  const CLI::App& episode = *app.get_subcommand("episode");
  const std::string error = ErrorOf([&] {
    ExpandEpisodeSets(episode, {"sortcell", "episode", "--set", "nois-scale=1"});
  });
  EXPECT_NE(error.find("--set: unknown key 'nois-scale' (valid keys: "), std::string::npos) << error;
  for (const char* key : {"noise-scale", "seed", "time-limit", "objects"})
    EXPECT_NE(error.find(key), std::string::npos) << key;
  EXPECT_EQ(error.find("help"), std::string::npos) << error;
  EXPECT_NE(ErrorOf([&] {
              ExpandEpisodeSets(episode, {"sortcell", "episode", "--set", "seed"});
            }).find("--set: expected KEY=VALUE, found 'seed'"),
            std::string::npos);
}

TEST(EpisodeSet, TheCommandLineRejectsAnUnknownKey) {
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("episode --scene " + kCell + " --out " + (TempDir("set_cli") / "out").string() +
                                 " --set colour=red"),
      "--set: unknown key 'colour'");
}

// ---- --set on sweep ----

std::filesystem::path WriteSweepSpec(const TempDir& dir, const std::string& body) {
  return WriteFile(dir / "spec.yaml", "scene: " + kCell + "\nobject_set: " + kSet + "\n" + body);
}

TEST(SweepSet, OverridesKeysOfTheSpec) {
  const TempDir dir("sweep_set");
  const auto file =
      WriteSweepSpec(dir, "seed: 1\nseeds: [3, 7]\naxes:\n  objects: [2, 4]\n  noise_scale: {min: 1, max: 2}\n");
  const SweepSpec spec = LoadSweepSpec(
      file, {"seed=9", "episodes=5", "axes.objects=3", "axes.light_intensity=[0.5, 1.5]", "episode_timeout_s=60"});
  EXPECT_EQ(spec.seed, 9u);
  EXPECT_TRUE(spec.seeds.empty());  // episodes replaces seeds.
  EXPECT_EQ(spec.EpisodeCount(), 5);
  EXPECT_DOUBLE_EQ(spec.episode_timeout_s, 60);
  ASSERT_EQ(spec.axes.size(), 3u);
  EXPECT_EQ(spec.axes[0].name, "objects");
  EXPECT_EQ(spec.axes[0].values, std::vector<nlohmann::json>{3});
  EXPECT_TRUE(spec.axes[1].is_range());
  EXPECT_EQ(spec.axes[2].name, "light_intensity");
  EXPECT_EQ(spec.axes[2].values.size(), 2u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(spec.Episode(i).second["objects"], 3);
  // Without overrides the file reads as written.
  EXPECT_EQ(LoadSweepSpec(file).seeds, (std::vector<uint64_t>{3, 7}));
}

TEST(SweepSet, UnknownOrBadOverridesAreRejected) {
  const TempDir dir("sweep_set_bad");
  const auto file = WriteSweepSpec(dir, "episodes: 2\n");
  const auto error = [&](const std::string& set) { return ErrorOf([&] { LoadSweepSpec(file, {set}); }); };
  EXPECT_NE(error("episodez=3").find("--set: unknown sweep spec key 'episodez' (expected "), std::string::npos);
  EXPECT_NE(error("axes.lighting=1").find("--set: unknown sweep spec key 'axes.lighting'"), std::string::npos);
  EXPECT_NE(error("seed").find("--set: expected KEY=VALUE, found 'seed'"), std::string::npos);
  EXPECT_NE(error("episodes=many").find("key 'episodes': expected a non-negative integer, found 'many'"),
            std::string::npos);
  EXPECT_NE(error("axes.objects=0").find("key 'axes.objects[0]': expected at least 1 object"), std::string::npos);
}

// ---- The sweep command ----

TEST(SweepCli, UnknownSetKeyIsAOneLineError) {
  const TempDir dir("sweep_cli_set");
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("sweep " + WriteSweepSpec(dir, "episodes: 2\n").string() + " --set episodez=3 --out " +
                                 (dir / "out").string()),
      "--set: unknown sweep spec key 'episodez'");
}

// A --resume re-runs a damaged middle line's episode (tests/app/episode_scenarios_test.cc); one that is
// refused (here: its model is missing) leaves the damaged file as it was.
TEST(SweepCli, ARefusedResumeLeavesADamagedFileAsItWas) {
  const TempDir dir("sweep_cli_damaged");
  const auto spec = WriteSweepSpec(dir, "episodes: 3\nmodel: /nonexistent/m.model.json\n");
  const auto out = dir / "out";
  std::filesystem::create_directories(out);
  std::filesystem::copy_file(spec, out / "spec.yaml");
  const std::string results =
      Dump(OkRecord(0, {})) + "\n" + R"({"episode":1,"sta)" + "\n" + Dump(OkRecord(2, {})) + "\n";
  WriteFile(out / "results.jsonl", results);
  sortcell_test::ExpectOneLineError(
      sortcell_test::RunSortcell("sweep " + spec.string() + " --resume --out " + out.string()),
      "/nonexistent/m.model.json");
  EXPECT_EQ(files::ReadTextFile(out / "results.jsonl"), results);
}

}  // namespace
}  // namespace sortcell::app
