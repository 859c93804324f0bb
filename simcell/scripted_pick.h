#pragma once
/// @file
/// `sortcell pick`: a scripted, robot-layer check of a physical pick-and-place. The object's pose and
/// shape come from the scene definition (ground truth; this command only) as a grasp footprint; the
/// cell then runs the same pick-and-place sequence as the sorting episode (cell/pick_and_place.h)
/// with a friction grasp, and the simulator measures how the object moved in the hand.

#include <filesystem>
#include <string>
#include <vector>

#include "sim/video_recorder.h"

namespace sortcell::simcell {

struct PickOptions {
  std::filesystem::path scene;
  std::filesystem::path cell;  ///< Bins and rules; empty: the default cell.
  std::string object;
  std::string bin;              ///< "cup" or "bin_cup"
  std::filesystem::path video;  ///< Empty: no video.
  sim::VideoOptions video_options;
  std::filesystem::path out;
};

struct PickResult {
  /// "sorted", "missed_bin", "grasp_failed", "dropped", "unreachable", "too_wide", "too_low", "sim_diverged"
  std::string status;
  bool in_bin = false;
  bool held = false;             ///< Still held when lowered into the bin.
  double slip_mm = 0;            ///< Object motion in the TCP frame during the carry (lifted -> above the bin).
  double slip_rotation_deg = 0;  ///< Rotation of the object in the TCP frame during the carry.
  double slip_total_mm = 0;      ///< The same from the grasp closing to the release (includes the lift).
  double cycle_time_s = 0;
  double wall_time_s = 0;
  double real_time_factor = 0;
  int video_frames = 0;
  double video_render_wall_s = 0;  ///< Wall time spent rendering and encoding the video.
};

/// Runs the pick and writes result.json and run.json into options.out.
/// @throws std::invalid_argument for a bad scene, an unknown object or bin, or an unusable output.
PickResult RunPick(const PickOptions& options, const std::vector<std::string>& command_line);

}  // namespace sortcell::simcell
