#pragma once
/// @file
/// Output folders and the run.json every output folder gets.

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sortcell::app {

/// Creates `dir` (and parents) and checks that a file can be written in it, before any work starts.
/// @throws std::invalid_argument "output folder '<dir>': <reason>" otherwise.
void PrepareOutputDir(const std::filesystem::path& dir);

/// Writes `json` (pretty-printed) to `path`. @throws std::runtime_error naming the file on failure.
void WriteJson(const std::filesystem::path& path, const nlohmann::json& json);

/// The run record: command line, seed, git revision, library versions, start time (UTC) and
/// `extra` fields. Wall-clock fields are "started_utc" and anything ending in "_wall_s".
nlohmann::json RunRecord(const std::vector<std::string>& command_line, uint64_t seed, const nlohmann::json& extra);

}  // namespace sortcell::app
