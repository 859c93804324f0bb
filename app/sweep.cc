#include "app/sweep.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "app/default_model.h"
#include "app/object_set.h"
#include "app/output_dir.h"
#include "app/progress.h"
#include "app/sweep_report.h"
#include "app/sweep_spec.h"
#include "app/wall_clock.h"
#include "perception/recognition_model.h"
#include "sim/model.h"

namespace sortcell::app {
namespace {

std::string ReadText(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The finished episodes in results.jsonl, and the length of the file up to the last complete
// record (a last line cut short by an interruption is not one: its episode runs again).
std::vector<nlohmann::json> ReadResults(const std::filesystem::path& file, size_t& complete_bytes) {
  std::vector<nlohmann::json> records;
  complete_bytes = 0;
  if (!std::filesystem::exists(file)) return records;
  const std::string text = ReadText(file);
  size_t start = 0, good_end = 0;
  while (start < text.size()) {
    const size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // No newline: cut short.
    try {
      records.push_back(nlohmann::json::parse(text.substr(start, end - start)));
    } catch (const nlohmann::json::exception&) {
      break;
    }
    good_end = end + 1;
    start = end + 1;
  }
  complete_bytes = good_end;
  return records;
}

struct Worker {
  int episode = 0;
  uint64_t seed = 0;
  nlohmann::json axes;
  std::filesystem::path dir;
  WallClock::time_point started;
};

// Starts `sortcell episode` for one episode; its output goes to dir/log.txt.
pid_t Spawn(const std::vector<std::string>& args, const std::filesystem::path& log) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  const std::string log_path = log.string();
  const pid_t pid = fork();
  if (pid < 0) throw std::runtime_error("sweep: cannot start a worker process (fork failed)");
  if (pid == 0) {
    // A worker dies with the sweep (no orphans writing into a folder that a --resume reuses).
    prctl(PR_SET_PDEATHSIG, SIGKILL);
    const int fd = open(log_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    execv("/proc/self/exe", argv.data());
    _exit(127);
  }
  return pid;
}

std::string LastLine(const std::filesystem::path& file) {
  std::string text = ReadText(file);
  while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
  const size_t nl = text.rfind('\n');
  std::string line = nl == std::string::npos ? text : text.substr(nl + 1);
  const size_t cr = line.rfind('\r');  // Progress lines on a terminal.
  return cr == std::string::npos ? line : line.substr(cr + 1);
}

}  // namespace

SweepRun RunSweep(const SweepOptions& options, const std::vector<std::string>& command_line) {
  const auto wall_start = WallClock::now();
  if (options.jobs < 1 || options.jobs > 256) throw std::invalid_argument("-j: expected 1..256 worker processes");
  if (options.shards < 1 || options.shard < 1 || options.shard > options.shards) {
    throw std::invalid_argument("--shard: expected i/N with 1 <= i <= N");
  }
  const SweepSpec spec = LoadSweepSpec(options.spec);
  const ObjectSet set = LoadObjectSet(spec.object_set);
  sim::Model::FromFile(spec.scene.string());  // Fails here, once, rather than in every worker.
  PrepareOutputDir(options.out);
  const std::filesystem::path results_file = options.out / "results.jsonl";
  const std::filesystem::path spec_copy = options.out / "spec.yaml";
  const std::string spec_text = ReadText(options.spec);
  if (std::filesystem::exists(spec_copy) && ReadText(spec_copy) != spec_text) {
    throw std::invalid_argument("output folder '" + options.out.string() + "' holds a sweep of another spec (" +
                                spec_copy.string() + "): use another --out");
  }
  size_t complete_bytes = 0;
  std::vector<nlohmann::json> records = ReadResults(results_file, complete_bytes);
  if (!records.empty() && !options.resume) {
    throw std::invalid_argument("output folder '" + options.out.string() + "' already holds " +
                                std::to_string(records.size()) + " results: add --resume to run what is missing");
  }
  std::filesystem::path model = spec.model;
  if (model.empty()) model = EnsureDefaultModel(set);
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
      throw std::invalid_argument("sweep spec '" + options.spec.string() + "': " + e.what());
    }
  }

  if (!std::filesystem::exists(spec_copy)) std::ofstream(spec_copy, std::ios::binary) << spec_text;
  if (std::filesystem::exists(results_file) && std::filesystem::file_size(results_file) > complete_bytes) {
    spdlog::warn("{}: dropping an incomplete last record ({} bytes); its episode runs again", results_file.string(),
                 std::filesystem::file_size(results_file) - complete_bytes);
    std::filesystem::resize_file(results_file, complete_bytes);
  }

  SweepRun run;
  run.total = spec.EpisodeCount();
  std::set<int> done;
  for (const auto& r : records) done.insert(r.value("episode", -1));
  std::vector<int> todo;
  for (int i = 0; i < run.total; ++i) {
    if (i % options.shards != options.shard - 1) continue;
    ++run.in_shard;
    if (done.count(i)) ++run.already;
    else todo.push_back(i);
  }
  WriteJson(options.out / ("run_shard" + std::to_string(options.shard) + ".json"),
            RunRecord(command_line, spec.seed,
                      {{"command", "sweep"}, {"spec", options.spec.string()}, {"jobs", options.jobs},
                       {"shard", std::to_string(options.shard) + "/" + std::to_string(options.shards)},
                       {"episodes_to_run", todo.size()}}));

  std::ofstream results(results_file, std::ios::app);
  if (!results) throw std::runtime_error("sweep: cannot append to '" + results_file.string() + "'");
  Progress progress("sweep " + spec.source.filename().string(), static_cast<int>(todo.size()));
  std::map<pid_t, Worker> running;
  size_t next = 0;
  const auto finish = [&](const Worker& w, int status, bool timed_out) {
    nlohmann::json record = {{"episode", w.episode}, {"seed", w.seed}, {"axes", w.axes},
                             {"wall_time_s", SecondsSince(w.started)}};
    const std::filesystem::path metrics_file = w.dir / "metrics.json";
    const bool ok = !timed_out && WIFEXITED(status) && WEXITSTATUS(status) == 0 && std::filesystem::exists(metrics_file);
    nlohmann::json metrics;
    if (ok) {
      try {
        metrics = nlohmann::json::parse(ReadText(metrics_file));
      } catch (const nlohmann::json::exception&) {
      }
    }
    if (metrics.is_object() && metrics.contains("summary")) {
      record["status"] = "ok";
      record["summary"] = metrics["summary"];
      record["items"] = metrics["items"];
    } else {
      ++run.crashed;
      record["status"] = timed_out ? "timeout" : "crashed";
      if (WIFEXITED(status)) record["exit_code"] = WEXITSTATUS(status);
      if (WIFSIGNALED(status)) record["signal"] = WTERMSIG(status);
      record["error"] = LastLine(w.dir / "log.txt");
      spdlog::warn("episode {} {}: {}", w.episode, record["status"].get<std::string>(), record["error"].get<std::string>());
    }
    results << record.dump() << '\n';
    results.flush();
    records.push_back(std::move(record));
    ++run.ran;
    progress.Advance();
  };

  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && static_cast<int>(running.size()) < options.jobs) {
      Worker w;
      w.episode = todo[next++];
      std::tie(w.seed, w.axes) = spec.Episode(w.episode);
      char name[32];
      std::snprintf(name, sizeof name, "episodes/%06d", w.episode);
      w.dir = options.out / name;
      std::filesystem::create_directories(w.dir);
      std::filesystem::remove(w.dir / "metrics.json");
      std::vector<std::string> args{"sortcell", "episode", "--scene", spec.scene.string(), "--object-set",
                                    spec.object_set.string(), "--seed", std::to_string(w.seed), "--out", w.dir.string(),
                                    "--model", w.axes.contains("model") ? w.axes["model"].get<std::string>() : model.string()};
      for (const auto& [axis, value] : w.axes.items()) {
        if (axis == "objects") args.insert(args.end(), {"--objects", std::to_string(value.get<int>())});
        if (axis == "light_intensity") args.insert(args.end(), {"--light-intensity", Number(value)});
        if (axis == "noise_scale") args.insert(args.end(), {"--noise-scale", Number(value)});
        if (axis == "friction_scale") args.insert(args.end(), {"--friction-scale", Number(value)});
        if (axis == "mass_scale") args.insert(args.end(), {"--mass-scale", Number(value)});
        if (axis == "camera_shift_m") args.insert(args.end(), {"--camera-shift", Number(value)});
        if (axis == "camera_turn_rad") args.insert(args.end(), {"--camera-turn", Number(value)});
      }
      w.started = WallClock::now();
      running[Spawn(args, w.dir / "log.txt")] = w;
    }
    int status = 0;
    const pid_t pid = waitpid(-1, &status, WNOHANG);
    if (pid > 0 && running.count(pid)) {
      finish(running[pid], status, false);
      running.erase(pid);
      continue;
    }
    for (auto it = running.begin(); it != running.end();) {
      if (SecondsSince(it->second.started) > spec.episode_timeout_s) {
        kill(it->first, SIGKILL);
        waitpid(it->first, &status, 0);
        finish(it->second, status, true);
        it = running.erase(it);
      } else {
        ++it;
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  results.close();
  progress.Finish();
  run.wall_time_s = SecondsSince(wall_start);
  run.summary = WriteSweepReport(options.out, spec, records);
  return run;
}

}  // namespace sortcell::app
