#pragma once
/// @file
/// `sortcell dataset`, `sortcell train`, `sortcell eval`: the recognition building blocks for any
/// object set.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace sortcell::app {

void AddDatasetCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);
void AddTrainCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);
void AddEvalCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
