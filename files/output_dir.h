#pragma once
/// @file
/// Output folders and the run.json every output folder gets.

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace sortcell::files {

/// Creates `dir` (and parents) and checks that a file can be written in it, before any work starts.
/// @throws std::invalid_argument "output folder '<dir>': <reason>" otherwise.
void PrepareOutputDir(const std::filesystem::path& dir);

/// ": <strerror(error)>", or "" when `error` is 0: the system's reason appended to a message.
std::string SystemReason(int error);

/// Writes `text` to `path` (replacing it) and checks the write after the file is closed, so a full
/// disk or a lost folder is an error, not a short file. Atomic: the text goes to a file beside `path`
/// that is renamed over it, so `path` is never seen half written, even if the process is killed (a
/// device, pipe or symbolic link, e.g. /dev/stdout, is written in place). Synced to disk before the
/// rename (and the folder after it), so it also survives a lost machine.
/// @throws std::runtime_error "cannot write '<path>'" (with the system's reason when it gives one).
void WriteTextFile(const std::filesystem::path& path, const std::string& text);

/// Removes the files "<name>.partial<pid>" in `dir` (not below it) whose writing process is gone: what
/// WriteTextFile leaves when its process is killed mid-write. A live process's file is kept. Only for a
/// folder that no other machine writes (a sweep's, under its lock): a writer elsewhere looks gone.
void RemoveStalePartialFiles(const std::filesystem::path& dir);

/// The whole of `path` as it is on disk (bytes, no conversions).
/// @throws std::runtime_error "cannot read '<path>'" (with the system's reason when it gives one).
std::string ReadTextFile(const std::filesystem::path& path);

/// Writes `json` (pretty-printed) to `path`. @throws std::runtime_error naming the file on failure.
void WriteJson(const std::filesystem::path& path, const nlohmann::json& json);

/// Closes `out`, which writes `path`, and checks that everything reached the file (for files too
/// large to build in memory first; set errno to 0 before opening `out` for a precise reason).
/// @throws std::runtime_error "cannot write '<path>'" otherwise (e.g. a full disk).
void CloseChecked(std::ofstream& out, const std::filesystem::path& path);

/// One CSV field (RFC 4180): `value` as it is, or, when it holds a comma, a double quote, CR or LF,
/// in double quotes with each of its double quotes doubled.
std::string CsvField(const std::string& value);

/// The run record: command line, seed, git revision, library versions, start time (UTC) and
/// `extra` fields. Wall-clock fields are "started_utc" and anything ending in "_wall_s".
nlohmann::json RunRecord(const std::vector<std::string>& command_line, uint64_t seed, const nlohmann::json& extra);

}  // namespace sortcell::files
