#pragma once
/// @file
/// `sortcell report DIR`: the sweep folder's report page, DIR/report/index.html (app/sweep/sweep_html_report.h).

#include <functional>

#include <CLI/CLI.hpp>

namespace sortcell::app {

/// Registers the subcommand; `run` is set to the action to perform when it is chosen.
void AddReportCommand(CLI::App& app, std::function<int()>& run);

}  // namespace sortcell::app
