#pragma once
/// @file
/// `sortcell replay DIR --episode N`: one episode of a sweep run again, exactly as the sweep's worker ran
/// it (its recorded `sortcell episode` arguments: seed, axis values, scene, sets and model), in a
/// process of its own, and its record checked against the sweep's, machine figures aside
/// (WithoutMachineFigures). Refused, with the reason, when this build or the model file is not the one
/// that ran the sweep: the episode would not be the same.

#include <filesystem>
#include <string>
#include <vector>

#include "app/sweep/sweep_record.h"

namespace sortcell::app {

struct ReplayOptions {
  std::filesystem::path sweep_dir;
  int episode = -1;
  /// Where the replay writes metrics.json, run.json and log.txt; empty: DIR/replays/<episode, 6 digits>.
  std::filesystem::path out;
  /// A review video of the replay (`sortcell episode --video`); empty: none.
  std::filesystem::path video;
  /// The Kinect still of every decision (`sortcell episode --stills`); empty: none.
  std::filesystem::path stills;
};

struct ReplayResult {
  SweepRecord recorded;       ///< The sweep's record of the episode.
  std::filesystem::path out;  ///< The replay's folder.
  bool matches = false;
  /// Where the two records differ, at most 20: "<JSON path>: sweep <value>, replay <value>".
  std::vector<std::string> differences;
};

/// The worker arguments of a record with `--out` (and `--video`, `--stills` when given) added: what the
/// replay runs.
std::vector<std::string> ReplayArguments(const SweepRecord& record, const ReplayOptions& options,
                                         const std::filesystem::path& out);

/// Where two records (as JSON) differ once the machine figures are set aside; empty when they agree.
std::vector<std::string> RecordDifferences(const nlohmann::json& sweep, const nlohmann::json& replay);

/// Runs the replay and compares.
/// @throws std::invalid_argument for a folder without results.jsonl, an episode it has no record of,
///         one that crashed or timed out (nothing to compare with), a record from before replays were
///         possible, another build, or a changed or missing model file (each named).
/// @throws std::runtime_error when the replayed episode itself fails (its exit status and log named).
ReplayResult ReplayEpisode(const ReplayOptions& options);

/// As ReplayEpisode, for a record already read (options.episode is not looked up) and this executable's
/// BuildDigest() already taken: a review replays many episodes of one folder.
ReplayResult ReplayRecord(const SweepRecord& recorded, const ReplayOptions& options, const std::string& build);

}  // namespace sortcell::app
