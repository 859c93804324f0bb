#pragma once
/// @file
/// `sortcell calibrate`: the hand-eye self-calibration of the Kinect's pose, alone, in the simulated
/// cell (simcell/calibration_run.h).

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

void AddCalibrateCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
