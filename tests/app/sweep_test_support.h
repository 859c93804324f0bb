#pragma once
// What the sweep tests share: small specs on the default cell with the test model, results.jsonl read
// back, records without their wall-clock figures, and a sweep started in the background.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "app/sweep/sweep_record.h"

namespace sortcell_test {

inline const std::string kSweepScene = std::string(SORTCELL_SOURCE_DIR) + "/scenes/cell.xml";
inline const std::string kSweepSet = std::string(SORTCELL_SOURCE_DIR) + "/scenes/objects/paper.yaml";

/// A file's whole text ("" if it cannot be read).
inline std::string ReadFile(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// A sweep's summary.json without what depends on the wall clock or the machine.
inline nlohmann::json SummaryWithoutMachineFigures(nlohmann::json j) {
  if (j.is_object()) {
    for (const std::string& key : sortcell::files::FieldKeys<sortcell::simcell::RunFigures>(sortcell::files::kMachine))
      j.erase(key);
    j.erase("resources");
    for (auto& [key, value] : j.items()) value = SummaryWithoutMachineFigures(value);
  }
  return j;
}

/// Every non-empty line of a results.jsonl, parsed.
inline std::vector<nlohmann::json> Lines(const std::string& file) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(file);
  for (std::string line; std::getline(in, line);) {
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  }
  return lines;
}

/// Writes a sweep spec at `file`: `episodes` episodes of 1 or 2 objects sorted with the test model,
/// then `extra` (YAML lines) appended.
inline std::string SmallSweepSpec(const std::string& file, int seed, int episodes, const std::string& extra = "") {
  std::ofstream(file) << "scene: " << kSweepScene << "\nobject_set: " << kSweepSet << "\nmodel: " << SORTCELL_TEST_MODEL
                      << "\nseed: " << seed << "\nepisodes: " << episodes << "\naxes:\n  objects: [1, 2]\n"
                      << extra;
  return file;
}

/// metrics.json (or a record of results.jsonl) without its wall-clock figures (the library's rule,
/// the one `sortcell replay` checks by).
inline nlohmann::json WithoutWallClock(nlohmann::json m) { return sortcell::app::WithoutMachineFigures(std::move(m)); }

/// The records of a results.jsonl by episode, without wall-clock figures.
inline std::map<int, nlohmann::json> RecordsByEpisode(const std::string& results) {
  std::map<int, nlohmann::json> records;
  for (const auto& record : Lines(results)) records[record["episode"].get<int>()] = WithoutWallClock(record);
  return records;
}

/// Starts `sortcell <args>` as a child of this process, its stdout and stderr appended to `log`; returns
/// its pid. With `max_file_bytes`, no file it writes may grow past that (RLIMIT_FSIZE, SIGXFSZ ignored:
/// a write past it fails with EFBIG, as one on a full disk fails with ENOSPC).
inline pid_t StartSortcell(const std::vector<std::string>& args, const std::string& log,
                           std::optional<rlim_t> max_file_bytes = std::nullopt) {
  std::vector<std::string> argv_text{SORTCELL_BINARY};
  argv_text.insert(argv_text.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_text) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    if (max_file_bytes) {
      signal(SIGXFSZ, SIG_IGN);
      const rlimit limit{*max_file_bytes, *max_file_bytes};
      if (setrlimit(RLIMIT_FSIZE, &limit) != 0) _exit(125);
    }
    if (!freopen(log.c_str(), "a", stdout) || !freopen(log.c_str(), "a", stderr)) _exit(126);
    execv(SORTCELL_BINARY, argv.data());
    _exit(127);
  }
  return pid;
}

}  // namespace sortcell_test
