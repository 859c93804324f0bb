#pragma once
/// @file
/// `sortcell episode`: one perception-driven sorting episode with metrics and optional video.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace sortcell::app {

void AddEpisodeCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

}  // namespace sortcell::app
