#include "app/cli/replay_command.h"

#include <cstdio>
#include <memory>
#include <string>

#include "app/sweep/sweep_replay.h"

namespace sortcell::app {
namespace {

std::string ItemsText(const SweepRecord& r) {
  std::string text;
  for (const auto& item : r.items) text += (text.empty() ? "" : ", ") + item.name + " " + cell::ToString(item.outcome);
  return text;
}

}  // namespace

void AddReplayCommand(CLI::App& app, std::function<int()>& run) {
  auto o = std::make_shared<ReplayOptions>();
  CLI::App* cmd = app.add_subcommand(
      "replay",
      "Run one episode of a sweep again exactly (its recorded seed, axis values, scene, sets and model, in a fresh "
      "process) and check that its record matches the sweep's, wall-clock figures aside. Refused when this build or "
      "the model file differs from the sweep's. Exit code 0: the records match; 1: they differ (printed).");
  cmd->add_option("dir", o->sweep_dir, "Sweep folder (holding results.jsonl)")->required();
  cmd->add_option("--episode", o->episode, "Episode index, as in results.jsonl")
      ->required()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--video", o->video, "Also write the replay's review video (MP4)");
  cmd->add_option("--stills", o->stills, "Also write the Kinect still of every decision into this folder");
  cmd->add_option("--out", o->out,
                  "Folder for the replay's metrics.json, run.json and log.txt (default DIR/replays/<episode>)");
  cmd->callback([&run, o] {
    run = [o] {
      const ReplayResult r = ReplayEpisode(*o);
      const std::string axes = r.recorded.axes.empty() ? "" : ", " + AxesText(r.recorded.axes);
      std::printf("Episode %d (seed %llu%s) replayed into %s: ", o->episode,
                  static_cast<unsigned long long>(r.recorded.seed), axes.c_str(), r.out.string().c_str());
      if (r.matches) {
        std::printf("its record matches the sweep's (%s).\n", ItemsText(r.recorded).c_str());
        return 0;
      }
      std::printf("its record DIFFERS from the sweep's (%zu%s differences):\n", r.differences.size(),
                  r.differences.size() >= 20 ? " or more" : "");
      for (const auto& d : r.differences) std::printf("  %s\n", d.c_str());
      return 1;
    };
  });
}

}  // namespace sortcell::app
