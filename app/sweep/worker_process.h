#pragma once
/// @file
/// `sortcell episode` run in a child process of this executable: a sweep's workers and a replay.

#include <sys/types.h>

#include <filesystem>
#include <string>
#include <vector>

namespace sortcell::app {

/// Starts this executable (/proc/self/exe) with `args` (argv[0] included), stdout and stderr into `log`.
/// The child dies with its parent (no orphan writing into a folder that is reused) and runs in a process
/// group of its own (a terminal's Ctrl-C reaches the parent, which ends it).
/// @throws std::runtime_error if no process can be started.
pid_t SpawnSelf(const std::vector<std::string>& args, const std::filesystem::path& log);

/// Waits for child `pid` to end (through interruptions); its wait status.
int WaitFor(pid_t pid);

}  // namespace sortcell::app
