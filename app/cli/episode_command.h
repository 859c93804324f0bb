#pragma once
/// @file
/// `sortcell episode`: one perception-driven sorting episode with metrics and optional video.

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "simcell/episode.h"

namespace sortcell::app {

void AddEpisodeCommand(CLI::App& app, std::function<int()>& run, const std::vector<std::string>& command_line);

/// --light-intensity, --noise-scale, --camera-shift and --camera-turn into `options` (episode, calibrate).
void AddSensorVariationOptions(CLI::App& cmd, simcell::EpisodeOptions& options);
/// --set KEY=VALUE (see ExpandEpisodeSets), after every other option of `cmd`: each of those takes the
/// last value given.
void AddSetOption(CLI::App& cmd, std::vector<std::string>& sets);

/// `--set KEY=VALUE` on `sortcell episode` and `sortcell calibrate` (DESIGN §3), repeatable: KEY is any of the
/// command's options by its long name without dashes (noise-scale, seed, time-limit, ...). Returns `args` (a whole
/// command line, "sortcell episode ...") with every `--set KEY=VALUE` (or `--set=KEY=VALUE`) taken out and
/// `--KEY=VALUE` appended after the other arguments, so that CLI11 parses it as that option (with its checks) and it
/// overrides the option given directly (the last value wins). Arguments after "--" are left alone.
/// @param episode the subcommand, as AddEpisodeCommand (or AddCalibrateCommand) made it.
/// @throws std::invalid_argument "--set: unknown key '<key>' (valid keys: ...)" or
///         "--set: expected KEY=VALUE, found '<text>'".
std::vector<std::string> ExpandEpisodeSets(const CLI::App& episode, const std::vector<std::string>& args);

}  // namespace sortcell::app
