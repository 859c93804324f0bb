#pragma once
/// @file
/// One line of a sweep's results.jsonl as a struct, and the file read back into them (by --resume
/// and the report). Reading is strict: a line that is not JSON, or a missing or mistyped key, is an
/// error naming the file, the line and the key ("<file> line 17: summary.grasps: missing"), never a
/// silent zero.
///
/// A line, as written (keys as in every results.jsonl so far, so old result folders still read):
///   {"episode": 3, "seed": 3, "axes": {"objects": 5}, "wall_time_s": 6.6, "status": "ok",
///    "replay": {"arguments": [...], "build": "...", "model_digest": "..."},
///    "summary": {...metrics.json's summary...}, "items": [...metrics.json's items...]}
///   {"episode": 4, ..., "status": "crashed" | "timeout", "exit_code": 2, "signal": 9, "error": "..."}
/// (exit_code or signal as the worker ended; error: the last line of its log).

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "simcell/episode_metrics.h"
#include "common/enum_names.h"
#include "files/record_fields.h"

namespace sortcell::app {

/// How a sweep's worker process ended.
enum class RunStatus {
  kOk,       ///< Exited 0 and left a readable metrics.json.
  kCrashed,  ///< Anything else, before the timeout.
  kTimeout,  ///< Killed after the spec's episode_timeout_s.
};

/// The statuses' spellings in results.jsonl and summary.json.
inline constexpr EnumNames<RunStatus, 3> kRunStatusNames{
    {{RunStatus::kOk, "ok"}, {RunStatus::kCrashed, "crashed"}, {RunStatus::kTimeout, "timeout"}}};

/// "ok", "crashed", "timeout".
const char* ToString(RunStatus status);
/// The inverse of ToString.
/// @throws std::invalid_argument "unknown run status '<text>' (expected ok, crashed or timeout)".
RunStatus ParseRunStatus(std::string_view text);

/// What `sortcell replay` needs to run a sweep's episode again exactly: the worker's `sortcell episode`
/// arguments (without `--out`), and digests of the build and of the model file that ran it.
struct ReplayRecipe {
  std::vector<std::string> arguments;
  std::string build, model_digest;
};

/// One episode of a sweep: one line of results.jsonl.
struct SweepRecord {
  int episode = 0;  ///< Index in the spec.
  uint64_t seed = 0;
  nlohmann::json axes = nlohmann::json::object();  ///< The episode's axis values, as the spec gave them.
  double wall_time_s = 0;
  /// The worker process's peak resident memory (VmHWM, read while it ran), in MiB; absent in results
  /// written before it was recorded. A machine figure, like the wall time.
  std::optional<double> peak_memory_mb;
  RunStatus status = RunStatus::kOk;
  // kOk: the episode's metrics.
  simcell::EpisodeSummary summary;
  std::vector<simcell::ItemResult> items;
  /// Absent in results written before replays.
  std::optional<ReplayRecipe> replay;
  // kCrashed, kTimeout: what is known of the failure.
  std::optional<int> exit_code, signal;
  std::optional<std::string> error;

  bool ok() const { return status == RunStatus::kOk; }
};

/// The record's own keys (its episode's summary and items are metrics.json's), listed once.
struct SweepRecordFields {
  template <typename Self, typename F>
  static void Visit(Self& v, F&& field) {
    using namespace files;  // NOLINT(google-build-using-namespace): the flags' names, in this list only.
    field("episode", v.episode);
    field("seed", v.seed);
    field("axes", v.axes);
    field("wall_time_s", v.wall_time_s, kMachine);
    field("status", v.status);
    field("peak_memory_mb", v.peak_memory_mb, kIfSet | kMachine);
    field("replay", v.replay, kIfSet | kMachine);
  }
};
SweepRecordFields RecordFieldsOf(const SweepRecord*);

/// A record (or a metrics.json) without the figures of the machine that ran it: wall-clock times, the
/// real-time factor, memory, the video's frame count and render time, the physics profile's seconds
/// (its counts stay), and the replay block. Two runs of one episode agree on the rest exactly.
nlohmann::json WithoutMachineFigures(nlohmann::json record);

void to_json(nlohmann::json& j, const ReplayRecipe& v);
/// @throws std::invalid_argument "arguments: expected the episode's arguments, found none", or naming a key.
void from_json(const nlohmann::json& j, ReplayRecipe& v);
void to_json(nlohmann::json& j, const SweepRecord& v);
/// @throws std::invalid_argument "<key path>: <what>" for a missing or mistyped key, an unknown
///         status or outcome ("summary.grasps: missing", "items[2].outcome: unknown item outcome ...").
void from_json(const nlohmann::json& j, SweepRecord& v);

/// Reads `json["summary"]` and `json["items"]` (a metrics.json, or a record of status ok).
/// @throws std::invalid_argument naming the key, as from_json.
void ReadSummaryAndItems(const nlohmann::json& json, simcell::EpisodeSummary& summary,
                         std::vector<simcell::ItemResult>& items);

/// results.jsonl as read.
struct SweepResults {
  std::vector<SweepRecord> records;
  /// Complete lines that are not JSON or not a record: "<file> line <n>: <key>: <what>" each. Their
  /// episodes have no record, so a --resume runs them again.
  std::vector<std::string> damaged;
  /// The file's good lines (and blank ones) as they were, for rewriting it without the damaged ones.
  std::string good_text;
  /// Length of the file up to the end of its last complete line. A last line without its newline
  /// was cut short by an interruption: it is no record, and its episode runs again.
  size_t complete_bytes = 0;
  size_t file_bytes = 0;
};

/// Reads results.jsonl (none: no records). Blank lines are skipped; a damaged complete line (not JSON
/// or not a record) is listed in `damaged`, not read.
/// @throws std::runtime_error "cannot read '<file>'" if it exists but cannot be read.
SweepResults ReadSweepResults(const std::filesystem::path& file);

/// The records of sweep folder `dir`'s results.jsonl, for the commands that read a finished sweep
/// (report, replay, compare, review).
/// @throws std::invalid_argument "'<dir>': not a sweep folder (no results.jsonl)", or the first damaged
///         line's message with the advice to `sweep --resume` first.
std::vector<SweepRecord> ReadSweepFolder(const std::filesystem::path& dir);

/// An episode's axis values as text: "objects=5, placement=dense" ("" for none).
std::string AxesText(const nlohmann::json& axes);

/// Appends records to results.jsonl, one line each, flushed as written.
class SweepResultsWriter {
 public:
  /// @throws std::runtime_error "cannot append to '<file>'" if it cannot be opened.
  explicit SweepResultsWriter(std::filesystem::path file);
  /// Writes `record` as one line and flushes it.
  /// @throws std::runtime_error "cannot write '<file>'" (with the system's reason) if any of it did
  ///         not reach the file (a full disk, a lost folder).
  void Append(const SweepRecord& record);
  /// Closes the file, checked as Append. (The destructor closes it unchecked.)
  void Close();

 private:
  std::filesystem::path file_;
  std::ofstream out_;
};

}  // namespace sortcell::app

namespace nlohmann {
/// Run statuses travel as their spellings; an unknown spelling is an error naming the choices.
template <>
struct adl_serializer<sortcell::app::RunStatus> {
  static void to_json(json& j, sortcell::app::RunStatus v) { j = sortcell::app::ToString(v); }
  static void from_json(const json& j, sortcell::app::RunStatus& v) {
    v = sortcell::app::ParseRunStatus(j.get<std::string>());
  }
};
}  // namespace nlohmann
