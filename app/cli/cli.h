#pragma once
/// @file
/// The `sortcell` command line: subcommands, help, and the error contract (one line on stderr,
/// exit code 2 for bad input).

namespace sortcell::app {

/// Parses and runs one subcommand. Returns the process exit code: 0 on success (and for --help),
/// 2 for bad arguments, unreadable or invalid input files, or unusable output folders.
int RunCli(int argc, char** argv);

}  // namespace sortcell::app
