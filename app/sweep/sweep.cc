#include "app/sweep/sweep.h"

#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <spdlog/fmt/fmt.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "files/build_identity.h"
#include "files/cell_file.h"
#include "files/data_dir.h"
#include "files/object_set.h"
#include "files/output_dir.h"
#include "files/progress.h"
#include "common/wall_clock.h"
#include "simcell/episode_setup.h"
#include "simcell/sim_layout.h"
#include "training/default_model.h"
#include "app/sweep/sweep_lock.h"
#include "app/sweep/sweep_record.h"
#include "app/sweep/sweep_report.h"
#include "app/sweep/sweep_spec.h"
#include "app/sweep/worker_process.h"
#include "perception/recognition_model.h"
#include "sim/model.h"

namespace sortcell::app {
namespace {

// ---- Checks before anything runs ----

void CheckOptions(const SweepOptions& options) {
  if (options.jobs < 1 || options.jobs > 256) throw std::invalid_argument("-j: expected 1..256 worker processes");
  if (options.shards < 1 || options.shard < 1 || options.shard > options.shards) {
    throw std::invalid_argument("--shard: expected i/N with 1 <= i <= N");
  }
}

// What spec.yaml in the output folder holds: the spec's text, and the --set overrides after it.
std::string SpecCopyText(const SweepOptions& options) {
  std::string text = files::ReadTextFile(options.spec);
  if (options.sets.empty()) return text;
  if (!text.empty() && text.back() != '\n') text += '\n';
  text += "# Overridden on the command line (sortcell sweep --set), applied over the keys above:\n";
  for (const auto& set : options.sets) text += "#   --set " + set + "\n";
  return text;
}

void CheckSameSpec(const std::filesystem::path& out, const std::filesystem::path& spec_copy,
                   const std::string& spec_text) {
  if (std::filesystem::exists(spec_copy) && files::ReadTextFile(spec_copy) != spec_text) {
    throw std::invalid_argument("output folder '" + out.string() + "' holds a sweep of another spec (" +
                                spec_copy.string() + "): use another --out");
  }
}

// The finished episodes of results.jsonl. Without --resume a folder with any is refused (before
// they are read, so the hint is not hidden behind a damaged line); with it they are read strictly.
SweepResults ReadFinishedResults(const std::filesystem::path& file, const SweepOptions& options) {
  if (options.resume) return ReadSweepResults(file);
  SweepResults results;
  if (!std::filesystem::exists(file)) return results;
  const std::string text = files::ReadTextFile(file);
  results.file_bytes = text.size();
  int lines = 0;
  for (size_t start = 0, end; (end = text.find('\n', start)) != std::string::npos; start = end + 1) {
    results.complete_bytes = end + 1;
    if (text.find_first_not_of(" \t\r", start) < end) ++lines;
  }
  if (lines > 0) {
    throw std::invalid_argument("output folder '" + options.out.string() + "' already holds " + std::to_string(lines) +
                                " results: add --resume to run what is missing");
  }
  return results;
}

// The model every episode sorts with (the spec's, or the set's default, trained if missing), after
// loading it and every model of a `model` axis once, so a bad one fails before any worker starts.
std::filesystem::path CheckModels(const SweepSpec& spec, const files::ObjectSet& set,
                                  const std::filesystem::path& spec_file) {
  std::filesystem::path model = spec.model;
  if (model.empty()) model = training::EnsureDefaultModel(set);
  std::vector<std::filesystem::path> models{model};
  for (const auto& axis : spec.axes) {
    if (axis.name == "model") {
      for (const auto& v : axis.values) models.push_back(v.get<std::string>());
    }
  }
  for (const auto& m : models) {
    try {
      perception::LoadModel(m);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument("sweep spec '" + spec_file.string() + "': " + e.what());
    }
  }
  return model;
}

// A last line cut short by an interruption is dropped; its episode runs again.
// Damaged lines are reported and the file rewritten without them (a new file moved over the old one,
// so a crash leaves one or the other whole); a cut-short last line is dropped. Their episodes run again.
void DropUnreadableRecords(const std::filesystem::path& file, const SweepResults& results) {
  if (!results.damaged.empty()) {
    for (const auto& line : results.damaged) spdlog::warn("{}: dropped; its episode runs again", line);
    files::WriteTextFile(file, results.good_text);  // Atomic: the old file stays until the new one is whole.
    return;
  }
  if (results.file_bytes <= results.complete_bytes) return;
  spdlog::warn("{}: dropping an incomplete last record ({} bytes); its episode runs again", file.string(),
               results.file_bytes - results.complete_bytes);
  std::filesystem::resize_file(file, results.complete_bytes);
}

// This shard's episodes not yet in `records`; counts them into `run`.
std::vector<int> EpisodesToRun(const SweepOptions& options, const std::vector<SweepRecord>& records, SweepRun& run) {
  std::set<int> done;
  for (const auto& r : records) done.insert(r.episode);
  std::vector<int> todo;
  for (int i = 0; i < run.total; ++i) {
    if (i % options.shards != options.shard - 1) continue;
    ++run.in_shard;
    if (done.count(i))
      ++run.already;
    else
      todo.push_back(i);
  }
  return todo;
}

// ---- Worker processes ----

struct Worker {
  pid_t pid = 0;
  int episode = 0;
  uint64_t seed = 0;
  nlohmann::json axes;
  std::filesystem::path dir;
  WallClock::time_point started;
  long peak_memory_kb = 0;             ///< The largest VmHWM seen while it ran.
  std::vector<std::string> arguments;  ///< Its `sortcell episode` command line.
  std::string model_digest;
};

// The worker's peak resident memory so far (VmHWM of /proc/<pid>/status), 0 once it is gone. Read
// while it runs rather than from its rusage: that would count the sweep's own pages, which the
// child shares until it runs `sortcell episode`.
long PeakMemoryKb(pid_t pid) {
  std::ifstream status("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmHWM:", 0) == 0) return std::atol(line.c_str() + 6);
  }
  return 0;
}

// waitpid for `pid`, again when a signal (the sweep's SIGINT/SIGTERM) interrupts it.
// A SIGINT or SIGTERM asks the sweep to stop: set by the handler, read by the runner's loop.
volatile std::sig_atomic_t g_stop_signal = 0;
extern "C" void RequestStop(int signal) { g_stop_signal = signal; }

// SIGINT and SIGTERM handled while the sweep runs; the previous handlers back after it.
class StopOnSignals {
 public:
  StopOnSignals() {
    g_stop_signal = 0;
    struct sigaction stop {};
    stop.sa_handler = RequestStop;
    sigemptyset(&stop.sa_mask);
    sigaction(SIGINT, &stop, &old_int_);
    sigaction(SIGTERM, &stop, &old_term_);
  }
  ~StopOnSignals() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  StopOnSignals(const StopOnSignals&) = delete;
  StopOnSignals& operator=(const StopOnSignals&) = delete;

 private:
  struct sigaction old_int_ {
  }, old_term_{};
};

// What every episode of the sweep shares.
struct SweepSetup {
  const SweepSpec& spec;
  const SweepOptions& options;
  std::filesystem::path model;
  std::string build;                                 ///< BuildDigest(), for replays.
  std::map<std::string, std::string> model_digests;  ///< By model file, for replays.
};

// The digest of every model a worker may sort with.
std::map<std::string, std::string> ModelDigests(const SweepSpec& spec, const std::filesystem::path& model) {
  std::map<std::string, std::string> digests{{model.string(), files::FileDigest(model)}};
  for (const auto& axis : spec.axes) {
    if (axis.name != "model") continue;
    for (const auto& v : axis.values) digests[v.get<std::string>()] = files::FileDigest(v.get<std::string>());
  }
  return digests;
}

std::string ModelOf(const SweepSetup& s, const Worker& w) {
  return w.axes.contains("model") ? w.axes["model"].get<std::string>() : s.model.string();
}

// The `sortcell episode` command line of worker `w`.
std::vector<std::string> EpisodeArguments(const SweepSetup& s, const Worker& w) {
  std::vector<std::string> args{"sortcell",     "episode",
                                "--scene",      s.spec.scene.string(),
                                "--object-set", s.spec.object_set.string(),
                                "--seed",       std::to_string(w.seed),
                                "--out",        w.dir.string(),
                                "--model",      ModelOf(s, w)};
  if (!s.spec.cell.empty()) args.insert(args.end(), {"--cell", s.spec.cell.string()});
  if (!s.spec.unknown_set.empty()) args.insert(args.end(), {"--unknown-set", s.spec.unknown_set.string()});
  static const std::map<std::string, std::string> kAxisOptions{
      {"light_intensity", "--light-intensity"}, {"noise_scale", "--noise-scale"},
      {"friction_scale", "--friction-scale"},   {"mass_scale", "--mass-scale"},
      {"camera_shift_m", "--camera-shift"},     {"camera_turn_rad", "--camera-turn"},
      {"reject_below", "--reject-below"},       {"lying_fraction", "--lying-fraction"},
      {"colour_jitter", "--colour-jitter"}};
  for (const auto& [axis, value] : w.axes.items()) {
    if (axis == "objects") args.insert(args.end(), {"--objects", std::to_string(value.get<int>())});
    if (axis == "unknown_objects") args.insert(args.end(), {"--unknown-objects", std::to_string(value.get<int>())});
    if (axis == "noise_seed") args.insert(args.end(), {"--noise-seed", std::to_string(value.get<int>())});
    if (axis == "placement") args.insert(args.end(), {"--placement", value.get<std::string>()});
    if (axis == "self_calibrate") args.insert(args.end(), {"--self-calibrate", value.get<std::string>()});
    const auto option = kAxisOptions.find(axis);
    if (option != kAxisOptions.end())
      args.insert(args.end(), {option->second, fmt::format("{:.17g}", value.get<double>())});
  }
  return args;
}

Worker StartEpisode(const SweepSetup& s, int episode) {
  Worker w;
  w.episode = episode;
  std::tie(w.seed, w.axes) = s.spec.Episode(episode);
  w.dir = s.options.out / fmt::format("episodes/{:06d}", episode);
  std::filesystem::create_directories(w.dir);
  files::RemoveStalePartialFiles(w.dir);  // A worker killed mid-write in an earlier, killed run.
  std::filesystem::remove(w.dir / "metrics.json");
  w.arguments = EpisodeArguments(s, w);
  w.model_digest = s.model_digests.at(ModelOf(s, w));
  w.started = WallClock::now();
  w.pid = SpawnSelf(w.arguments, w.dir / "log.txt");
  return w;
}

// The last line of a worker's log, or "" when it left none.
std::string LastLine(const std::filesystem::path& file) {
  std::string text;
  try {
    text = files::ReadTextFile(file);
  } catch (const std::runtime_error&) {
    return "";
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const size_t nl = text.rfind('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  const size_t cr = line.rfind('\r');  // Progress lines on a terminal.
  return cr == std::string::npos ? line : line.substr(cr + 1);
}

// The record of a worker that ended with wait status `status`: its metrics.json if it exited 0 and
// left a readable one, else what is known of the failure.
SweepRecord FinishedRecord(const Worker& w, const std::string& build, int status, bool timed_out) {
  SweepRecord record;
  record.episode = w.episode;
  record.seed = w.seed;
  record.axes = w.axes;
  record.wall_time_s = SecondsSince(w.started);
  if (w.peak_memory_kb > 0) record.peak_memory_mb = w.peak_memory_kb / 1024.0;
  ReplayRecipe replay;
  for (size_t i = 1; i < w.arguments.size(); ++i) {  // Without argv[0] and the worker's own --out.
    if (w.arguments[i] == "--out") {
      ++i;
    } else {
      replay.arguments.push_back(w.arguments[i]);
    }
  }
  replay.build = build;
  replay.model_digest = w.model_digest;
  record.replay = std::move(replay);
  const std::filesystem::path metrics_file = w.dir / "metrics.json";
  std::string problem;
  if (!timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0 && std::filesystem::exists(metrics_file)) {
    try {
      ReadSummaryAndItems(nlohmann::json::parse(files::ReadTextFile(metrics_file)), record.summary, record.items);
      record.status = RunStatus::kOk;
      return record;
    } catch (const nlohmann::json::exception& e) {
      problem = metrics_file.string() + ": not JSON: " + e.what();
    } catch (const std::invalid_argument& e) {
      problem = metrics_file.string() + ": " + e.what();
    } catch (const std::runtime_error& e) {
      problem = e.what();
    }
  }
  record.status = timed_out ? RunStatus::kTimeout : RunStatus::kCrashed;
  if (WIFEXITED(status)) record.exit_code = WEXITSTATUS(status);
  if (WIFSIGNALED(status)) record.signal = WTERMSIG(status);
  record.error = problem.empty() ? LastLine(w.dir / "log.txt") : problem;
  return record;
}

// Runs the episodes `todo`, `jobs` at a time; each finished one is appended to `writer` at once
// and to `records`. A worker past the spec's timeout is killed and recorded as such.
class EpisodeRunner {
 public:
  EpisodeRunner(const SweepSetup& setup, SweepResultsWriter& writer, std::vector<SweepRecord>& records, SweepRun& run)
      : setup_(setup), writer_(writer), records_(records), run_(run) {}

  void Run(const std::vector<int>& todo) {
    files::Progress progress("sweep " + setup_.spec.source.filename().string(), static_cast<int>(todo.size()));
    size_t next = 0;
    while ((next < todo.size() || !running_.empty()) && g_stop_signal == 0) {
      while (next < todo.size() && static_cast<int>(running_.size()) < setup_.options.jobs) {
        Worker w = StartEpisode(setup_, todo[next++]);
        running_[w.pid] = w;
      }
      for (auto& [pid, worker] : running_) worker.peak_memory_kb = std::max(worker.peak_memory_kb, PeakMemoryKb(pid));
      if (ReapOne(progress)) continue;
      KillOverdue(progress);
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
    if (g_stop_signal != 0) EndInFlight();
    progress.Finish();
  }

 private:
  // Asked to stop: the episodes still running are ended and not recorded (a --resume runs them).
  void EndInFlight() {
    for (const auto& [pid, worker] : running_) {
      kill(pid, SIGKILL);
      WaitFor(pid);
      ++run_.ended_in_flight;
    }
    running_.clear();
  }

  // Records a worker that has ended, if one has. Returns whether one had.
  bool ReapOne(files::Progress& progress) {
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    const auto it = running_.find(pid);
    if (pid <= 0 || it == running_.end()) return false;
    Finish(it->second, status, false, progress);
    running_.erase(it);
    return true;
  }

  void KillOverdue(files::Progress& progress) {
    for (auto it = running_.begin(); it != running_.end();) {
      if (SecondsSince(it->second.started) > setup_.spec.episode_timeout_s) {
        kill(it->first, SIGKILL);
        Finish(it->second, WaitFor(it->first), true, progress);
        it = running_.erase(it);
      } else {
        ++it;
      }
    }
  }

  void Finish(const Worker& w, int status, bool timed_out, files::Progress& progress) {
    SweepRecord record = FinishedRecord(w, setup_.build, status, timed_out);
    if (!record.ok()) {
      ++run_.crashed;
      spdlog::warn("episode {} {}: {}", record.episode, ToString(record.status), record.error.value_or(""));
    }
    writer_.Append(record);
    if (setup_.options.metrics_only && record.ok()) {
      std::error_code ec;
      std::filesystem::remove_all(w.dir, ec);  // Only space is at stake: the record is written.
      if (ec) spdlog::warn("--metrics-only: cannot remove {}: {}", w.dir.string(), ec.message());
    }
    records_.push_back(std::move(record));
    ++run_.ran;
    progress.Advance();
  }

  const SweepSetup& setup_;
  SweepResultsWriter& writer_;
  std::vector<SweepRecord>& records_;
  SweepRun& run_;
  std::map<pid_t, Worker> running_;
};

// The cell layout, the unknown set and the scene holding both sets, checked once rather than in every
// worker; a warning for each object a bin cannot hold.
// The largest value axis `name` takes (0 without it).
double AxisMax(const SweepSpec& spec, const std::string& name) {
  double most = 0;
  for (const auto& axis : spec.axes) {
    if (axis.name != name) continue;
    if (axis.is_range()) most = std::max(most, axis.max);
    for (const auto& v : axis.values) most = std::max(most, v.get<double>());
  }
  return most;
}

void CheckCell(const SweepSpec& spec, const files::ObjectSet& set) {
  const files::CellFile cell = files::ReadCellFileOrDefault(spec.cell);
  simcell::EpisodeOptions unknowns;
  unknowns.unknown_set = spec.unknown_set;
  unknowns.unknown_objects = spec.unknown_set.empty() ? 0 : 1;
  const files::ObjectSet unknown = simcell::LoadUnknownSet(unknowns, set);
  const std::string in_spec = "sweep spec '" + spec.source.string() + "': ";
  if (AxisMax(spec, "unknown_objects") > static_cast<double>(unknown.objects.size())) {
    throw std::invalid_argument(in_spec + "axis 'unknown_objects' reaches " +
                                fmt::format("{:g}", AxisMax(spec, "unknown_objects")) + ", but unknown set '" +
                                spec.unknown_set.string() + "' has " + std::to_string(unknown.objects.size()) +
                                " objects");
  }
  if (AxisMax(spec, "reject_below") > 0 && cell.rules.reject_bin.empty()) {
    throw std::invalid_argument(in_spec + "axis 'reject_below' needs a 'reject' bin in cell layout '" +
                                cell.source.string() + "'");
  }
  const sim::Model model = simcell::LoadEpisodeScene(spec.scene, simcell::WithUnknown(set, unknown), cell);
  const cell::CellLayout layout = simcell::ReadCellLayout(model, cell);
  const std::string where = "cell layout '" + cell.source.string() + "'";
  if (!unknown.objects.empty() && layout.rules.reject_bin.empty()) {
    throw std::invalid_argument(where + ": unknown objects (" + spec.unknown_set.string() + ") need a 'reject' bin");
  }
  std::vector<std::pair<std::string, std::string>> objects_and_bins;
  for (const auto& o : set.objects) {
    const auto bin = layout.rules.BinOf(o.category);
    if (!bin)
      throw std::invalid_argument(where + ": category '" + o.category +
                                  "' goes to no bin (no rule for it and no \"*\")");
    objects_and_bins.emplace_back(o.name, *bin);
  }
  for (const auto& o : unknown.objects) objects_and_bins.emplace_back(o.name, layout.rules.reject_bin);
  for (const auto& w : simcell::BinCapacityWarnings(model, layout, objects_and_bins)) spdlog::warn("{}: {}", where, w);
}

}  // namespace

SweepRun RunSweep(const SweepOptions& options, const std::vector<std::string>& command_line) {
  const auto wall_start = WallClock::now();
  // Cheap checks first: nothing in the output folder is touched until the spec, the set, the scene
  // and the folder's earlier results are known to be good.
  CheckOptions(options);
  const SweepSpec spec = LoadSweepSpec(options.spec, options.sets);
  const files::ObjectSet set = files::LoadObjectSet(spec.object_set);
  CheckCell(spec, set);  // Fails here, once, rather than in every worker.
  files::PrepareOutputDir(options.out);
  const SweepLock lock(options.out);            // Before anything in the folder is read or written.
  files::RemoveStalePartialFiles(options.out);  // What a killed sweep was writing.
  const std::filesystem::path results_file = options.out / "results.jsonl";
  const std::filesystem::path spec_copy = options.out / "spec.yaml";
  const std::string spec_text = SpecCopyText(options);
  CheckSameSpec(options.out, spec_copy, spec_text);
  SweepResults finished = ReadFinishedResults(results_file, options);
  const std::filesystem::path model = CheckModels(spec, set, options.spec);

  if (!std::filesystem::exists(spec_copy)) files::WriteTextFile(spec_copy, spec_text);
  DropUnreadableRecords(results_file, finished);
  SweepRun run;
  run.total = spec.EpisodeCount();
  const std::vector<int> todo = EpisodesToRun(options, finished.records, run);
  files::WriteJson(options.out / ("run_shard" + std::to_string(options.shard) + ".json"),
                   files::RunRecord(command_line, spec.seed,
                                    {{"command", "sweep"},
                                     {"spec", options.spec.string()},
                                     {"jobs", options.jobs},
                                     {"shard", std::to_string(options.shard) + "/" + std::to_string(options.shards)},
                                     {"episodes_to_run", todo.size()},
                                     {"set", options.sets}}));

  SweepResultsWriter writer(results_file);
  const SweepSetup setup{spec, options, model, files::BuildDigest(), ModelDigests(spec, model)};
  {
    const StopOnSignals stop;
    EpisodeRunner(setup, writer, finished.records, run).Run(todo);
    run.stopped_by = g_stop_signal;
  }
  writer.Close();
  run.wall_time_s = SecondsSince(wall_start);
  run.summary = WriteSweepReport(options.out, spec, finished.records);
  return run;
}

}  // namespace sortcell::app
