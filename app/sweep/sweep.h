#pragma once
/// @file
/// `sortcell sweep`: many episodes of a spec (sweep_spec.h), each in its own worker process
/// (`sortcell episode`), `jobs` at a time. Each finished episode is appended to results.jsonl at once
/// and flushed, so an interrupted sweep loses only the episodes in flight; --resume runs what is
/// missing; --shard i/N runs the episodes whose index is i-1 modulo N, so shards can run on other
/// machines and their results.jsonl files be concatenated and summarised (--resume on the merged
/// folder runs nothing and writes the summary).

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sortcell::app {

struct SweepOptions {
  std::filesystem::path spec;
  std::filesystem::path out;
  int jobs = 1;
  bool resume = false;
  int shard = 1, shards = 1;  ///< This is shard `shard` (1-based) of `shards`.
  /// Keep only results.jsonl and the summaries: an episode's folder goes once its record is written,
  /// unless its worker crashed or timed out. Results do not depend on it.
  bool metrics_only = false;
  /// --set KEY=VALUE: overrides of the spec's keys (LoadSweepSpec). They are part of the sweep:
  /// spec.yaml in the output folder lists them, and a --resume must give the same ones.
  std::vector<std::string> sets;
};

struct SweepRun {
  int total = 0;     ///< Episodes of the spec.
  int in_shard = 0;  ///< Of them, this shard's.
  int already = 0;   ///< Found in results.jsonl.
  int ran = 0, crashed = 0;
  /// The signal (SIGINT, SIGTERM) that stopped the sweep early, 0 if it ran to the end; the episodes
  /// it ended in flight are not recorded (--resume runs them).
  int stopped_by = 0;
  int ended_in_flight = 0;
  double wall_time_s = 0;
  nlohmann::json summary;  ///< summary.json of everything in results.jsonl.
};

/// On --resume a damaged line of results.jsonl is reported ("<file> line <n>: <key>: <what>: dropped;
/// its episode runs again"), the file rewritten without it, and its episode run again; so is a
/// cut-short last line.
/// @throws std::invalid_argument for a bad spec (naming it) or --set, a bad shard or job count, an
///         output folder another sweep is running in (its sweep.lock held), one holding another spec's
///         results, or results without --resume.
/// @throws std::runtime_error "cannot write '<file>'" if a result or summary cannot be written (a
///         full disk): the results written before stay.
SweepRun RunSweep(const SweepOptions& options, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
