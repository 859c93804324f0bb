#include "app/sweep/sweep_replay.h"

#include <sys/wait.h>

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <stdexcept>

#include "files/build_identity.h"
#include "files/output_dir.h"
#include "app/sweep/worker_process.h"

namespace sortcell::app {
namespace {

constexpr size_t kMostDifferences = 20;

SweepRecord RecordOf(const std::vector<SweepRecord>& records, const ReplayOptions& o,
                     const std::filesystem::path& file) {
  const auto it =
      std::find_if(records.begin(), records.end(), [&](const SweepRecord& r) { return r.episode == o.episode; });
  if (it != records.end()) return *it;
  int last = -1;
  for (const auto& r : records) last = std::max(last, r.episode);
  throw std::invalid_argument(fmt::format("episode {}: not in '{}' ({} records, episodes 0-{})", o.episode,
                                          file.string(), records.size(), last));
}

// The model file the record's arguments name.
std::filesystem::path ModelArgument(const SweepRecord& r) {
  const std::vector<std::string>& arguments = r.replay->arguments;
  const auto it = std::find(arguments.begin(), arguments.end(), "--model");
  if (it == arguments.end() || it + 1 == arguments.end()) {
    throw std::invalid_argument(fmt::format("episode {}: its recorded arguments name no --model", r.episode));
  }
  return *(it + 1);
}

// Refuses what would not replay the same episode.
void CheckReplayable(const SweepRecord& r, const std::filesystem::path& dir, const std::string& build) {
  if (!r.ok()) {
    throw std::invalid_argument(fmt::format("episode {} {} in the sweep: no record to compare with (its log: {})",
                                            r.episode, ToString(r.status),
                                            (dir / fmt::format("episodes/{:06d}/log.txt", r.episode)).string()));
  }
  if (!r.replay) {
    throw std::invalid_argument(fmt::format(
        "episode {}: recorded before sweeps kept what a replay needs (arguments, build, model): sweep again",
        r.episode));
  }
  if (r.replay->build != build) {
    throw std::invalid_argument(
        fmt::format("episode {} ran on another build (digest {}; this sortcell is {}): replay "
                    "it with the build that ran the sweep",
                    r.episode, r.replay->build, build));
  }
  const std::filesystem::path model = ModelArgument(r);
  std::string digest;
  try {
    digest = files::FileDigest(model);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(fmt::format("episode {}: its model is gone ({})", r.episode, e.what()));
  }
  if (digest != r.replay->model_digest) {
    throw std::invalid_argument(fmt::format("episode {}: model '{}' has changed since the sweep (digest {}, now {})",
                                            r.episode, model.string(), r.replay->model_digest, digest));
  }
}

std::string ValueText(const nlohmann::json& j, const std::string& pointer) {
  if (pointer.size() >= 2 && pointer.compare(pointer.size() - 2, 2, "/-") == 0) return "(none)";  // Appended.
  const nlohmann::json::json_pointer p(pointer);
  return j.contains(p) ? j.at(p).dump() : "(none)";
}

// One JSON patch operation of the sweep's record into the replay's, in words.
std::string DifferenceText(const nlohmann::json& sweep, const nlohmann::json& op) {
  const std::string path = op["path"].get<std::string>();
  const std::string replay = op.contains("value") ? op["value"].dump() : "(none)";
  return fmt::format("{}: sweep {}, replay {}", path, ValueText(sweep, path), replay);
}

}  // namespace

std::vector<std::string> ReplayArguments(const SweepRecord& record, const ReplayOptions& options,
                                         const std::filesystem::path& out) {
  std::vector<std::string> args{"sortcell"};
  if (record.replay) args.insert(args.end(), record.replay->arguments.begin(), record.replay->arguments.end());
  args.insert(args.end(), {"--out", out.string()});
  if (!options.video.empty()) args.insert(args.end(), {"--video", options.video.string()});
  if (!options.stills.empty()) args.insert(args.end(), {"--stills", options.stills.string()});
  return args;
}

std::vector<std::string> RecordDifferences(const nlohmann::json& sweep, const nlohmann::json& replay) {
  const nlohmann::json a = WithoutMachineFigures(sweep), b = WithoutMachineFigures(replay);
  std::vector<std::string> differences;
  for (const auto& op : nlohmann::json::diff(a, b)) {
    if (differences.size() == kMostDifferences) break;
    differences.push_back(DifferenceText(a, op));
  }
  return differences;
}

ReplayResult ReplayEpisode(const ReplayOptions& o) {
  return ReplayRecord(RecordOf(ReadSweepFolder(o.sweep_dir), o, o.sweep_dir / "results.jsonl"), o,
                      files::BuildDigest());
}

ReplayResult ReplayRecord(const SweepRecord& recorded, const ReplayOptions& o, const std::string& build) {
  ReplayResult result;
  result.recorded = recorded;
  std::error_code ec;
  CheckReplayable(result.recorded, o.sweep_dir, build);
  result.out = o.out.empty() ? o.sweep_dir / fmt::format("replays/{:06d}", recorded.episode) : o.out;
  files::PrepareOutputDir(result.out);
  std::filesystem::remove(result.out / "metrics.json", ec);
  const int status = WaitFor(SpawnSelf(ReplayArguments(result.recorded, o, result.out), result.out / "log.txt"));
  const std::filesystem::path metrics = result.out / "metrics.json";
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::exists(metrics, ec)) {
    throw std::runtime_error(fmt::format("replay of episode {} failed ({} {}); its log: {}", recorded.episode,
                                         WIFEXITED(status) ? "exit code" : "signal",
                                         WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status),
                                         (result.out / "log.txt").string()));
  }
  SweepRecord replayed = result.recorded;
  try {
    ReadSummaryAndItems(nlohmann::json::parse(files::ReadTextFile(metrics)), replayed.summary, replayed.items);
  } catch (const std::exception& e) {
    throw std::runtime_error("'" + metrics.string() + "': " + e.what());
  }
  result.differences = RecordDifferences(nlohmann::json(result.recorded), nlohmann::json(replayed));
  result.matches = result.differences.empty();
  return result;
}

}  // namespace sortcell::app
