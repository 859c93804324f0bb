#include "app/cli/pick_command.h"

#include <iostream>
#include <memory>
#include <tuple>

#include "app/cli/cli_validators.h"
#include "simcell/scripted_pick.h"

namespace sortcell::app {

void AddPickCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto options = std::make_shared<simcell::PickOptions>();
  CLI::App* cmd = app.add_subcommand(
      "pick",
      "Scripted robot-layer check: pick one object whose pose is read from the scene definition (not "
      "perceived), with a top-down friction grasp, and place it in a bin. Writes result.json (in_bin, "
      "slip_mm, cycle_time_s, wall_time_s, phases, tracking error) and run.json.");
  cmd->add_option("--scene", options->scene, "MJCF scene file, e.g. scenes/cell.xml")->required();
  cmd->add_option("--cell", options->cell, "Cell layout: bins and rules (default: scenes/cells/default.yaml)");
  cmd->add_option("--object", options->object, "Object (free body) to pick, e.g. bottle1")->required();
  cmd->add_option("--bin", options->bin, "Bin of the cell layout to place it in, e.g. cup (or bin_<name>)")->required();
  cmd->add_option("--video", options->video, "Also write an H.264 MP4 from the review camera (30 fps)");
  auto video_size = std::make_shared<std::string>("1280x720");
  cmd->add_option("--video-size", *video_size, "The video's WIDTHxHEIGHT (at most 1280x960)")
      ->check(kVideoSize)
      ->capture_default_str();
  cmd->add_flag("--video-shadows", options->video_options.shadows,
                "Draw the video with shadows and the floor's reflection (about 2.5x the rendering time)");
  options->out = "out/pick";
  cmd->add_option("--out", options->out, "Output folder (created if missing)")->capture_default_str();
  cmd->callback([&run, options, video_size, command_line] {
    std::tie(options->video_options.width, options->video_options.height) = ParseVideoSize(*video_size);
    run = [options, command_line] {
      const simcell::PickResult r = simcell::RunPick(*options, command_line);
      std::cout << "Pick " << options->object << " -> " << options->bin << " (scripted pose): " << r.status
                << (r.in_bin ? ", in the bin" : ", NOT in the bin") << ", slip " << r.slip_mm << " mm, cycle "
                << r.cycle_time_s << " s simulated, " << r.wall_time_s << " s wall (real-time factor "
                << r.real_time_factor << ")"
                << (r.video_frames ? ", video " + std::to_string(r.video_frames) + " frames" : "")
                << ". Result: " << (options->out / "result.json").string() << "\n";
      return r.status == "sorted" ? 0 : 1;
    };
  });
}

}  // namespace sortcell::app
