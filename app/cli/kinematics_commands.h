#pragma once
/// @file
/// `sortcell ik` and `sortcell fk`: the robot layer's kinematics on the command line, as JSON on stdout.
/// Frames: poses are the flange's (D-H frame 6) in the Base frame (D-H frame 0 = the cell's world
/// frame), or the gripper TCP's with --tcp; R = Rz(yaw) Ry(pitch) Rx(roll); metres and radians.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "robot/ur5_kinematics.h"

namespace sortcell::app {

/// {"frame", "solutions": [{"q", "position_error", "rotation_error", "wrist_singular"}], "nearest",
///  "nearest_q", "status"}. `pose` = x y z roll pitch yaw.
/// @throws std::invalid_argument naming --pose or --q-near for a wrong count or non-finite values.
nlohmann::json IkJson(const std::vector<double>& pose, const std::vector<double>& q_near, bool tcp);

/// {"frame", "position", "rotation", "rpy"}.
/// @throws std::invalid_argument naming --q for a wrong count or non-finite values.
nlohmann::json FkJson(const std::vector<double>& values, bool tcp);

void AddKinematicsCommands(CLI::App& app, std::function<int()>& run);

}  // namespace sortcell::app
