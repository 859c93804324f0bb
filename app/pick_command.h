#pragma once
/// @file
/// `sortcell pick`: a scripted, robot-layer check of a physical pick-and-place. The object's pose and
/// shape come from the scene definition (ground truth; this command only), then the robot layer plans
/// a top-down grasp, and the simulated arm and gripper execute it with a friction grasp: approach,
/// grasp, lift, carry to the bin at working speed, release, return home.

#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "robot/ur5_kinematics.h"

namespace sortcell::app {

struct PickOptions {
  std::filesystem::path scene;
  std::string object;
  std::string bin;  ///< "cup" or "bin_cup"
  std::filesystem::path video;  ///< Empty: no video.
  std::filesystem::path out;
};

struct PickResult {
  std::string status;  ///< "sorted", "missed_bin", "grasp_failed", "unreachable", "too_wide", "sim_diverged"
  bool in_bin = false;
  bool held = false;
  double slip_mm = 0;        ///< Object motion in the TCP frame during the carry (lifted -> above the bin).
  double slip_rotation_deg = 0;  ///< Rotation of the object in the TCP frame during the carry.
  double slip_total_mm = 0;  ///< The same from the grasp closing to the release (includes the lift).
  double cycle_time_s = 0;
  double wall_time_s = 0;
  double real_time_factor = 0;
  int video_frames = 0;
  double video_render_wall_s = 0;  ///< Wall time spent rendering and encoding the video.
};

/// The arm's home (= observe) pose: tool down, upper arm leaning back, TCP at (0.281, 0.109, 0.446),
/// behind and above the workspace (see pick_command.cc). scenes/cell.xml's "observe" keyframe holds it.
robot::Joints HomeJoints();

/// Runs the pick and writes result.json and run.json into options.out.
/// @throws std::invalid_argument for a bad scene, an unknown object or bin, or an unusable output.
PickResult RunPick(const PickOptions& options, const std::vector<std::string>& command_line);

void AddPickCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
