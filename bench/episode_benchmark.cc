// Episode and sweep throughput, printed as figures (not a timed test):
//   real-time factor of a headless episode and of one with video (same seed, so the same motions);
//   episodes per hour of a sweep with 1 and with 2 worker processes; what starting a worker process costs.
// Usage: episode_benchmark [MODEL] [EPISODES]   (default: the cached default model, 6 episodes)
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "training/default_model.h"
#include "bench_args.h"
#include "bench_temp_dir.h"
#include "simcell/episode.h"
#include "files/object_set.h"
#include "sim/model.h"
#include "sim/object_placement.h"

namespace {

using namespace sortcell;

double SweepEpisodesPerHour(const std::string& model, int episodes, int jobs) {
  const std::filesystem::path dir = BenchTempDir("sortcell_bench_sweep_j" + std::to_string(jobs));
  const std::filesystem::path spec = dir / "spec.yaml";
  std::ofstream(spec) << "scene: " << SORTCELL_SOURCE_DIR << "/scenes/cell.xml\nobject_set: " << SORTCELL_SOURCE_DIR
                      << "/scenes/objects/paper.yaml\nmodel: " << model << "\nseed: 0\nepisodes: " << episodes
                      << "\naxes:\n  objects: {min: 4, max: 6}\n";
  const auto start = std::chrono::steady_clock::now();
  const std::string command = std::string(SORTCELL_BINARY) + " sweep " + spec.string() + " -j " + std::to_string(jobs) +
                              " --out " + (dir / "out").string() + " > /dev/null 2>&1";
  if (std::system(command.c_str()) != 0) {
    std::fprintf(stderr, "sweep failed: %s\n", command.c_str());
    return 0;
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return episodes * 3600.0 / wall;
}

// A sweep starts a `sortcell` process per episode: the wall time of starting one that exits at once
// (`sortcell --version`, output to /dev/null: loading the executable and its shared libraries), median of
// `runs`. Spawned from this small process; a sweep forks its larger one first (app::SpawnSelf), so a
// worker's start is this plus the fork.
double ProcessStartSeconds(int runs) {
  posix_spawn_file_actions_t quiet;
  if (posix_spawn_file_actions_init(&quiet) != 0) throw std::runtime_error("posix_spawn_file_actions_init failed");
  std::string binary = SORTCELL_BINARY, flag = "--version";
  char* argv[] = {binary.data(), flag.data(), nullptr};
  std::vector<double> walls;
  bool ok = posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0) == 0;
  for (int i = 0; ok && i < runs; ++i) {
    const auto start = std::chrono::steady_clock::now();
    pid_t pid = 0;
    int status = 0;
    ok = posix_spawn(&pid, binary.c_str(), &quiet, nullptr, argv, environ) == 0;
    while (ok && waitpid(pid, &status, 0) < 0) ok = errno == EINTR;
    ok = ok && WIFEXITED(status) && WEXITSTATUS(status) == 0;
    walls.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  posix_spawn_file_actions_destroy(&quiet);
  if (!ok) throw std::runtime_error("cannot run '" + binary + " --version'");
  std::nth_element(walls.begin(), walls.begin() + runs / 2, walls.end());
  return walls[runs / 2];
}

// The ceiling: MuJoCo stepping the episode's scene with its six objects standing in the workspace and
// nothing else (no planning, control, camera or perception; the arm held up by its own bias torques,
// which MuJoCo computes in every step anyway), the same number of steps as the episode took, with the
// scene's solver options. Returns simulated / wall seconds.
double RawSteppingRealTimeFactor(const std::string& scene, double steps) {
  const sim::Model model = sim::Model::FromFile(scene);
  sim::Data data(model);
  sim::ResetToObserve(model, data);
  const std::vector<std::string> objects = sim::FreeBodyNames(model);
  for (size_t i = 0; i < objects.size(); ++i) {
    sim::PlaceObject(model, data, model.Id(mjOBJ_BODY, objects[i]), 0.40 + 0.15 * (i % 3), -0.12 + 0.24 * (i / 3 % 2),
                     0.3 * i);
  }
  const mjModel* m = model.get();
  const auto start = std::chrono::steady_clock::now();
  for (long k = 0; k < static_cast<long>(steps); ++k) {
    for (int a = 0; a < m->nu; ++a) {
      if (m->actuator_trntype[a] == mjTRN_JOINT && m->actuator_gainprm[a * mjNGAIN] == 1 &&
          m->actuator_biastype[a] == mjBIAS_NONE) {
        data->ctrl[a] = data->qfrc_bias[m->jnt_dofadr[m->actuator_trnid[2 * a]]];  // A motor: hold its joint up.
      }
    }
    mj_step(m, data.get());
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return steps * m->opt.timestep / wall;
}

// The two episodes side by side: simulated and wall time, real-time factor, perception, video frames.
void PrintEpisodes(const nlohmann::json& headless, const nlohmann::json& video) {
  std::printf("episode (seed 3, 6 paper objects), one process:\n");
  std::printf("  %-9s %8s %8s %8s %14s %14s\n", "", "sim s", "wall s", "RTF", "perception ms", "video ms/frame");
  std::printf("  %-9s %8.1f %8.1f %8.1f %14.1f %14s\n", "headless", headless["sim_time_s"].get<double>(),
              headless["wall_time_s"].get<double>(), headless["real_time_factor"].get<double>(),
              headless["perception_ms_per_frame"].get<double>(), "-");
  std::printf("  %-9s %8.1f %8.1f %8.2f %14.1f %14.1f\n", "video", video["sim_time_s"].get<double>(),
              video["wall_time_s"].get<double>(), video["real_time_factor"].get<double>(),
              video["perception_ms_per_frame"].get<double>(),
              1000 * video["video_render_wall_s"].get<double>() / std::max(1, video["video_frames"].get<int>()));
  // Where the wall time goes, per stage (metrics.json "profile_wall_s"), headless and with video.
  std::printf("wall-time profile (s, %% of the episode):\n  %-14s %16s %16s\n", "stage", "headless", "video");
  for (const auto& [stage, seconds] : headless["profile_wall_s"].items()) {
    const double v = video["profile_wall_s"][stage].get<double>();
    std::printf("  %-14s %8.2f (%4.1f %%) %8.2f (%4.1f %%)\n", stage.c_str(), seconds.get<double>(),
                100 * seconds.get<double>() / headless["wall_time_s"].get<double>(), v,
                100 * v / video["wall_time_s"].get<double>());
  }
}

// Inside the physics steps (MuJoCo's stage timers) and the load they work on, then the ceiling: raw
// stepping of the same scene.
void PrintPhysics(const nlohmann::json& headless, const std::string& scene) {
  const auto& physics = headless["physics_profile"];
  const double step_s = physics["step_s"].get<double>();
  std::printf(
      "physics steps, headless: %.0f steps, %.1f us per step, %.1f contacts and %.1f constraint rows per step\n",
      physics["steps"].get<double>(), 1e6 * step_s / std::max(1.0, physics["steps"].get<double>()),
      physics["contacts_per_step"].get<double>(), physics["constraint_rows_per_step"].get<double>());
  for (const char* stage : {"collision_s", "constraint_s", "smooth_s"}) {
    const double s = physics[stage].get<double>();
    std::printf("  %-14s %8.2f s (%4.1f %% of the steps)\n", stage, s, 100 * s / std::max(1e-9, step_s));
  }
  const double ceiling = RawSteppingRealTimeFactor(scene, physics["steps"].get<double>());
  std::printf(
      "raw MuJoCo stepping of the same scene and objects, no controller (the ceiling): RTF %.1f; "
      "the headless episode runs at %.0f %% of it\n",
      ceiling, 100 * headless["real_time_factor"].get<double>() / ceiling);
}

// The pick cycle by phase, and the arm's least time over the same paths.
void PrintCycle(const nlohmann::json& headless) {
  std::printf("pick cycle: %.2f s per item; by phase, mean simulated s per attempt:",
              headless["mean_cycle_time_s"].get<double>());
  for (const auto& [phase, seconds] : headless["cycle_phases_s"].items())
    std::printf(" %s %.2f", phase.c_str(), seconds.get<double>());
  std::printf("; %.0f picks per hour\n", headless["picks_per_hour"].get<double>());
  if (!headless["cycle_to_bound"].is_number()) return;
  std::printf(
      "the arm's least time over the same paths (speeds and torque budget): %.2f s per item, the cycle %.2f "
      "times it; by phase:",
      headless["mean_cycle_bound_s"].get<double>(), headless["cycle_to_bound"].get<double>());
  for (const auto& [phase, seconds] : headless["cycle_phases_bound_s"].items()) {
    std::printf(" %s %.2f", phase.c_str(), seconds.get<double>());
  }
  std::printf("\n");
}

int Run(int argc, char** argv) {
  std::filesystem::path model_path;
  int episodes = 6;
  CLI::App cli("Times sorting episodes of the paper objects, one after another and as a sweep.", "episode_benchmark");
  cli.add_option("model", model_path, "a trained model (default: the cached default model, trained if missing)");
  cli.add_option("episodes", episodes, "episodes of the sweep")->check(WholeNumberAtLeast(1));
  if (const auto exit_code = ParseBenchmarkArgs(cli, argc, argv)) return *exit_code;
  const files::ObjectSet set = files::LoadObjectSet(std::string(SORTCELL_SOURCE_DIR) + "/scenes/objects/paper.yaml");
  const std::string model =
      std::filesystem::absolute(model_path.empty() ? training::EnsureDefaultModel(set) : model_path).string();
  const std::filesystem::path out = BenchTempDir("sortcell_bench_episode");

  simcell::EpisodeOptions options;
  options.scene = std::string(SORTCELL_SOURCE_DIR) + "/scenes/cell.xml";
  options.object_set = set.source;
  options.model = model;
  options.seed = 3;
  options.out = out / "headless";
  const auto headless = nlohmann::json(simcell::RunEpisode(options, {"episode_benchmark"}))["summary"];
  options.out = out / "video";
  options.video = out / "video" / "episode.mp4";
  const auto video = nlohmann::json(simcell::RunEpisode(options, {"episode_benchmark"}))["summary"];
  PrintEpisodes(headless, video);
  PrintPhysics(headless, options.scene.string());
  PrintCycle(headless);

  std::printf(
      "process start (`sortcell --version` spawned, as a sweep starts a worker after its fork): %.0f ms, median "
      "of 21\n",
      1000 * ProcessStartSeconds(21));
  std::printf("sweep of %d episodes (4-6 paper objects):\n", episodes);
  const double one = SweepEpisodesPerHour(model, episodes, 1);
  const double two = SweepEpisodesPerHour(model, episodes, 2);
  std::printf("  1 worker:  %6.0f episodes/hour\n  2 workers: %6.0f episodes/hour (x%.2f)\n", one, two,
              one > 0 ? two / one : 0.0);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  return RunBenchmark("episode_benchmark", [&] { return Run(argc, argv); });
}
