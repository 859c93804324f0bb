#pragma once
/// @file
/// `sortcell replay DIR --episode N [--video F.mp4] [--stills DIR3] [--out DIR2]`: one episode of a sweep run again
/// exactly, and its record checked against the sweep's (app/sweep/sweep_replay.h). Exit code 0 when they
/// match, 1 when they differ (each difference printed), 2 when it cannot be replayed (the reason named).

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

/// Registers the subcommand; `run` is set to the action to perform when it is chosen.
void AddReplayCommand(CLI::App& app, std::function<int()>& run);

}  // namespace sortcell::app
