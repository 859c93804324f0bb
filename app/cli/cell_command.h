#pragma once
/// @file
/// `sortcell cell check LAYOUT.yaml [--objects SET.yaml] [--out DIR]`: reads and checks a cell layout
/// (bins and rules, files/cell_file.h), says where each category goes and which bins cannot hold
/// what they receive, and writes the bins' MJCF fragment and a scene to open in mujoco-simulate.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

/// Registers the subcommand; `run` is set to the action to perform when it is chosen.
void AddCellCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
