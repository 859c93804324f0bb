#pragma once
/// @file
/// `sortcell experiment 1|2|3`: the options parsed, then app/recognition/experiment.h runs it.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "app/recognition/experiment.h"

namespace sortcell::app {

void AddExperimentCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
