#pragma once
/// @file
/// `sortcell experiment 1|2|3`: the options parsed, then training/experiment.h runs it.

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

#include "training/experiment.h"

namespace sortcell::app {

void AddExperimentCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
