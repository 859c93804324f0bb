#pragma once
/// @file
/// `sortcell objects check SET.yaml --out DIR`: imports every object of a set and drops each on the
/// cell's table (app/objects/object_check.h).

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

/// Registers the subcommand; `run` is set to the action to perform when it is chosen.
void AddObjectsCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
