#pragma once
/// @file
/// `sortcell sweep SPEC.yaml [-j N] [--resume] [--shard i/N] [--set KEY=VALUE]... --out DIR`.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

void AddSweepCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
