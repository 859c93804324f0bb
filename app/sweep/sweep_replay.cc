#include "app/sweep/sweep_replay.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <spdlog/fmt/fmt.h>

#include <algorithm>
#include <cerrno>
#include <stdexcept>

#include "app/common/build_identity.h"
#include "app/common/output_dir.h"

extern char** environ;

namespace sortcell::app {
namespace {

constexpr size_t kMostDifferences = 20;

const SweepRecord& RecordOf(const SweepResults& results, const ReplayOptions& o, const std::filesystem::path& file) {
  const auto it = std::find_if(results.records.begin(), results.records.end(),
                               [&](const SweepRecord& r) { return r.episode == o.episode; });
  if (it != results.records.end()) return *it;
  int last = -1;
  for (const auto& r : results.records) last = std::max(last, r.episode);
  throw std::invalid_argument(fmt::format("episode {}: not in '{}' ({} records, episodes 0-{})", o.episode,
                                          file.string(), results.records.size(), last));
}

// The model file the record's arguments name.
std::filesystem::path ModelArgument(const SweepRecord& r) {
  const auto it = std::find(r.worker_arguments.begin(), r.worker_arguments.end(), "--model");
  if (it == r.worker_arguments.end() || it + 1 == r.worker_arguments.end()) {
    throw std::invalid_argument(fmt::format("episode {}: its recorded arguments name no --model", r.episode));
  }
  return *(it + 1);
}

// Refuses what would not replay the same episode.
void CheckReplayable(const SweepRecord& r, const std::filesystem::path& dir) {
  if (!r.ok()) {
    throw std::invalid_argument(fmt::format("episode {} {} in the sweep: no record to compare with (its log: {})",
                                            r.episode, ToString(r.status),
                                            (dir / fmt::format("episodes/{:06d}/log.txt", r.episode)).string()));
  }
  if (r.worker_arguments.empty()) {
    throw std::invalid_argument(fmt::format(
        "episode {}: recorded before sweeps kept what a replay needs (arguments, build, model): sweep again", r.episode));
  }
  const std::string build = BuildDigest();
  if (r.build != build) {
    throw std::invalid_argument(fmt::format("episode {} ran on another build (digest {}; this sortcell is {}): replay "
                                            "it with the build that ran the sweep",
                                            r.episode, r.build, build));
  }
  const std::filesystem::path model = ModelArgument(r);
  std::string digest;
  try {
    digest = FileDigest(model);
  } catch (const std::runtime_error& e) {
    throw std::invalid_argument(fmt::format("episode {}: its model is gone ({})", r.episode, e.what()));
  }
  if (digest != r.model_digest) {
    throw std::invalid_argument(fmt::format("episode {}: model '{}' has changed since the sweep (digest {}, now {})",
                                            r.episode, model.string(), r.model_digest, digest));
  }
}

// Runs this executable with `args` (argv[0] included), its output into `log`; returns the wait status.
int RunSelf(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, 1, 2);
  pid_t pid = 0;
  const int error = posix_spawn(&pid, "/proc/self/exe", &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("replay: cannot start the episode (posix_spawn: error " + std::to_string(error) + ")");
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("replay: lost the episode's process (waitpid failed)");
  }
  return status;
}

std::string ValueText(const nlohmann::json& j, const std::string& pointer) {
  const nlohmann::json::json_pointer p(pointer);
  return j.contains(p) ? j.at(p).dump() : "(none)";
}

}  // namespace

std::vector<std::string> ReplayArguments(const SweepRecord& record, const ReplayOptions& options,
                                         const std::filesystem::path& out) {
  std::vector<std::string> args{"sortcell"};
  args.insert(args.end(), record.worker_arguments.begin(), record.worker_arguments.end());
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
    const std::string path = op["path"].get<std::string>();
    differences.push_back(fmt::format("{}: sweep {}, replay {}", path, ValueText(a, path), ValueText(b, path)));
  }
  return differences;
}

ReplayResult ReplayEpisode(const ReplayOptions& o) {
  const std::filesystem::path file = o.sweep_dir / "results.jsonl";
  std::error_code ec;
  if (!std::filesystem::is_regular_file(file, ec)) {
    throw std::invalid_argument("'" + o.sweep_dir.string() + "': not a sweep folder (no results.jsonl)");
  }
  ReplayResult result;
  result.recorded = RecordOf(ReadSweepResults(file), o, file);
  CheckReplayable(result.recorded, o.sweep_dir);
  result.out = o.out.empty() ? o.sweep_dir / fmt::format("replays/{:06d}", o.episode) : o.out;
  PrepareOutputDir(result.out);
  std::filesystem::remove(result.out / "metrics.json", ec);
  const int status = RunSelf(ReplayArguments(result.recorded, o, result.out), result.out / "log.txt");
  const std::filesystem::path metrics = result.out / "metrics.json";
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || !std::filesystem::exists(metrics, ec)) {
    throw std::runtime_error(fmt::format("replay of episode {} failed ({} {}); its log: {}", o.episode,
                                         WIFEXITED(status) ? "exit code" : "signal",
                                         WIFEXITED(status) ? WEXITSTATUS(status) : WTERMSIG(status),
                                         (result.out / "log.txt").string()));
  }
  SweepRecord replayed = result.recorded;
  ReadSummaryAndItems(nlohmann::json::parse(ReadTextFile(metrics)), replayed.summary, replayed.items);
  result.differences = RecordDifferences(nlohmann::json(result.recorded), nlohmann::json(replayed));
  result.matches = result.differences.empty();
  return result;
}

}  // namespace sortcell::app
