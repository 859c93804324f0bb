#pragma once
/// @file
/// `sortcell capture`: one synthetic Kinect frame of a scene, written as images, cloud and metadata.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

struct CaptureOptions {
  std::filesystem::path scene;
  std::filesystem::path cell;  ///< Bins for the scene's bins.inc.xml; empty: the scene as written.
  uint64_t seed = 0;
  bool no_noise = false;
  std::filesystem::path out;
  std::string camera = "kinect";
};

/// What a capture produced, for the summary and the tests.
struct CaptureSummary {
  int width = 0, height = 0;
  double valid_depth_fraction = 0;
  std::vector<std::pair<std::string, int>> visible_objects;  ///< Name and pixel count, if > 0.
  double render_wall_s = 0;                                  ///< Colour + depth + labels render.
  double capture_wall_s = 0;                                 ///< Load to files written.
};

/// Loads the scene at its "observe" keyframe (or its default state), captures and writes rgb.png,
/// depth.png (16-bit mm, 0 = invalid), cloud.pcd (organized, camera frame, binary_compressed),
/// labels.png (16-bit object ids), labels.json, camera.json and run.json into options.out.
/// @throws std::invalid_argument for a missing or invalid scene or an unusable output folder.
CaptureSummary RunCapture(const CaptureOptions& options, const std::vector<std::string>& command_line);

/// Registers the subcommand; `run` is set to the action to perform when it is chosen.
void AddCaptureCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
