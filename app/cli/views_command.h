#pragma once
/// @file
/// `sortcell views`: a sheet of object views from datasets, row by row (e.g. the real views of an apple
/// beside the simulated apples a model was trained on), to see what the sensor gives each side.

#include <CLI/CLI.hpp>

#include <functional>

namespace sortcell::app {

void AddViewsCommand(CLI::App& app, std::function<int()>& run);

}  // namespace sortcell::app
