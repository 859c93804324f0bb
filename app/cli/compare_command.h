#pragma once
/// @file
/// `sortcell compare A B --out DIR`: two sweep folders of the same episodes (a change's before and
/// after) compared item by item (app/sweep/sweep_compare.h): on the terminal, and as DIR/compare.html
/// and DIR/compare.json.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

/// Registers the subcommand; `run` is set to the action to perform when it is chosen.
void AddCompareCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
