#pragma once
/// @file
/// `sortcell pick`: the CLI of the scripted pick-and-place check (simcell/scripted_pick.h).

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

void AddPickCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
