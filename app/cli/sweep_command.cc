#include "app/cli/sweep_command.h"

#include <csignal>

#include <cstdio>
#include <iostream>
#include <memory>
#include <string>

#include "app/sweep/sweep.h"
#include "app/sweep/sweep_html_report.h"
#include "app/sweep/sweep_review.h"

namespace sortcell::app {
namespace {

// "i/N" with 1 <= i <= N.
void ParseShard(const std::string& text, SweepOptions& o) {
  int used = 0;
  if (std::sscanf(text.c_str(), "%d/%d%n", &o.shard, &o.shards, &used) != 2 || used != static_cast<int>(text.size()) ||
      o.shards < 1 || o.shard < 1 || o.shard > o.shards) {
    throw std::invalid_argument("--shard: expected i/N with 1 <= i <= N, got '" + text + "'");
  }
}

// What the options ask beyond the sweep: failures reviewed, the report page.
struct SweepExtras {
  std::string shard = "1/1";
  bool review = false, report = false;
};

// Prints what the sweep did; returns the command's exit status.
int PrintSweep(const SweepOptions& o, const SweepRun& r) {
  const auto& s = r.summary;
  if (r.stopped_by != 0) {
    std::printf(
        "Sweep %s stopped by %s: %d episodes finished and recorded in this run, %d in flight ended and "
        "not recorded; `--resume` runs the rest. Summary of what is done: %s\n",
        o.spec.filename().string().c_str(), r.stopped_by == SIGINT ? "SIGINT" : "SIGTERM", r.ran, r.ended_in_flight,
        (o.out / "summary.md").string().c_str());
    return 128 + r.stopped_by;
  }
  std::printf(
      "Sweep %s: %d of %d episodes in this shard run now (%d were already done, %d failed to run) in %.0f s. "
      "All %d episodes in %s: %d items, correct-sort rate %.1f %% (95 %% CI %.1f-%.1f %%).\nSummary: %s\n",
      o.spec.filename().string().c_str(), r.ran, r.in_shard, r.already, r.crashed, r.wall_time_s,
      s["episodes"].get<int>(), (o.out / "results.jsonl").string().c_str(), s["items"].get<int>(),
      s["correct_sort_rate"].is_null() ? 0.0 : 100 * s["correct_sort_rate"].get<double>(),
      100 * s["correct_sort_rate_ci95"][0].get<double>(), 100 * s["correct_sort_rate_ci95"][1].get<double>(),
      (o.out / "summary.md").string().c_str());
  return 0;
}

void ReviewAndPrint(const std::filesystem::path& out) {
  const SweepReview v = ReviewSweep(out);
  std::string mismatches =
      v.mismatches.empty() ? "" : "; " + std::to_string(v.mismatches.size()) + " replays did NOT match their records";
  if (!v.not_replayed.empty())
    mismatches += "; " + std::to_string(v.not_replayed.size()) + " episodes could not be replayed";
  std::printf(
      "Review: %d episodes with a failed item replayed with video, %zu failed items each told in words with "
      "a clip (%s)%s.\n",
      v.episodes_replayed, v.failures.size(), (out / "review.json").string().c_str(), mismatches.c_str());
}

int RunSweepCommand(SweepOptions o, const SweepExtras& extras, const std::vector<std::string>& command_line) {
  ParseShard(extras.shard, o);
  const int status = PrintSweep(o, RunSweep(o, command_line));
  if (status != 0) return status;
  if (extras.review) ReviewAndPrint(o.out);
  if (extras.review || extras.report) std::printf("Report: %s\n", WriteHtmlReport(o.out).string().c_str());
  return 0;
}

}  // namespace

void AddSweepCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<SweepOptions>();
  auto extras = std::make_shared<SweepExtras>();
  CLI::App* cmd = app.add_subcommand(
      "sweep",
      "Many sorting episodes from a spec (scenes/sweeps/*.yaml), in worker processes. Appends each finished "
      "episode to results.jsonl; writes summary.json, summary.csv, summary.md and plot_<axis>.png.");
  cmd->add_option("spec", o->spec, "Sweep spec YAML, e.g. scenes/sweeps/paper_objects_100.yaml")->required();
  cmd->add_option("--out", o->out, "Output folder (created if missing)")->required();
  cmd->add_option("-j,--jobs", o->jobs, "Worker processes")->check(CLI::Range(1, 256))->capture_default_str();
  cmd->add_flag("--resume", o->resume, "Keep results.jsonl and run only the episodes missing from it");
  cmd->add_flag("--metrics-only", o->metrics_only,
                "For large sweeps: keep only results.jsonl and the summaries; an episode's folder is removed once its "
                "record is written, except when its worker crashed or timed out (its log.txt stays)");
  cmd->add_flag(
      "--review", extras->review,
      "After the sweep, replay every episode with a failed item with its review video (sortcell replay), find "
      "when each item failed, tell its attempts in words and cut a 6 s clip around it: DIR/review.json, "
      "DIR/replays/<episode>/");
  cmd->add_flag("--report", extras->report,
                "Also write the report page, DIR/report/index.html (sortcell report; --review writes it too)");
  cmd->add_option("--shard", extras->shard, "Run share i of N (episodes whose index is i-1 modulo N)")
      ->capture_default_str();
  cmd->add_option("--set", o->sets,
                  "Override a key of the spec (repeatable): scene, object_set, model, seed, episodes, seeds, mode, "
                  "episode_timeout_s, or axes.NAME (one value fixes the axis; a YAML list or {min: a, max: b} also "
                  "work), e.g. --set seed=7 --set axes.noise_scale=2. Files are relative to the working folder. "
                  "spec.yaml in the output folder lists the overrides; a --resume must repeat them")
      ->type_name("KEY=VALUE")
      ->allow_extra_args(false);
  cmd->callback([&run, o, extras, command_line] {
    run = [o, extras, command_line] { return RunSweepCommand(*o, *extras, command_line); };
  });
}

}  // namespace sortcell::app
