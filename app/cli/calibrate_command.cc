#include "app/cli/calibrate_command.h"

#include <spdlog/fmt/fmt.h>

#include <iostream>
#include <memory>
#include <tuple>

#include "app/cli/cli_validators.h"
#include "app/cli/episode_command.h"
#include "simcell/calibration_run.h"

namespace sortcell::app {
namespace {

struct CalibrateCli {
  simcell::EpisodeOptions options;
  std::string video_size = "1280x720";
  std::vector<std::string> sets;  ///< Empty: ExpandEpisodeSets turned them into options before parsing.
};

std::string Summary(const simcell::CalibrationFigures& f, const std::filesystem::path& out) {
  return fmt::format(
      "Calibration {}: {} of {} sightings agree, residual {:.2f} mm RMS, {:.1f} s simulated. Camera error {:.2f} mm / "
      "{:.4f} rad (the nominal pose's: {:.2f} mm / {:.4f} rad).\nResult: {}",
      f.status, f.inliers, f.sightings, 1000 * f.rms_residual_m, f.duration_s, 1000 * f.error_m, f.error_rad,
      1000 * f.prior_error_m, f.prior_error_rad, (out / "calibration.json").string());
}

}  // namespace

void AddCalibrateCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line) {
  auto cli = std::make_shared<CalibrateCli>();
  simcell::EpisodeOptions& o = cli->options;
  CLI::App* cmd = app.add_subcommand(
      "calibrate",
      "Hand-eye self-calibration of the Kinect: the arm shows the marker on its gripper at 18 places in the "
      "workspace; the camera's pose is fitted to where the encoders put the marker and where the Kinect sees it. "
      "The simulator's true camera pose only scores the result. Writes calibration.json and run.json.");
  cmd->add_option("--scene", o.scene, "MJCF cell, e.g. scenes/cell.xml")->required();
  cmd->add_option("--cell", o.cell, "Cell layout: bins and rules (default: scenes/cells/default.yaml)");
  cmd->add_option("--seed", o.seed, "Seed (uint64): the camera's displacement, noise")
      ->check(kUnsignedInteger)
      ->capture_default_str();
  cmd->add_option("--video", o.video, "Also write an H.264 MP4 from the review camera");
  cmd->add_option("--video-size", cli->video_size, "The video's WIDTHxHEIGHT (at most 1280x960)")
      ->check(kVideoSize)
      ->capture_default_str();
  cmd->add_option("--out", o.out, "Output folder (created if missing)")->required();
  AddSensorVariationOptions(*cmd, o);
  AddSetOption(*cmd, cli->sets);
  cmd->callback([&run, cli, command_line] {
    run = [cli, command_line] {
      if (!cli->sets.empty())
        throw std::logic_error("calibrate: --set reached the parser (ExpandEpisodeSets not applied)");
      simcell::EpisodeOptions options = cli->options;
      std::tie(options.video_options.width, options.video_options.height) = ParseVideoSize(cli->video_size);
      const simcell::CalibrationFigures figures = simcell::RunCalibration(options, command_line);
      std::cout << Summary(figures, options.out) << "\n";
      return figures.status == "ok" ? 0 : 1;
    };
  });
}

}  // namespace sortcell::app
