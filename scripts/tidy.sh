#!/usr/bin/env bash
# clang-tidy with .clang-tidy's checks over every file the build compiles (its compile_commands.json:
# the libraries' and tests' unity files, so each batch's headers are parsed once, the benchmarks, the fuzz
# targets), reporting what it finds in the project's own sources and headers. Exit 1 on any finding.
# scripts/test.sh (CI) runs it after the Release build.
#   scripts/tidy.sh [BUILD_DIR]      default build/ (configured by scripts/setup.sh)
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${1:-build}
root=$PWD
if [[ ! -f $build_dir/compile_commands.json ]]; then
  echo "tidy.sh: $build_dir/compile_commands.json not found (configure the build first: scripts/setup.sh)" >&2
  exit 2
fi
# The compiled files, each once (fuzz/replay_main.cc is in every fuzz replay).
files=$(/usr/bin/python3 -c 'import json, sys
print("\n".join(sorted({e["file"] for e in json.load(open(sys.argv[1]))})))' "$build_dir/compile_commands.json")
# The project's files, also as the sensor side's include root shows them (cmake/sensor_side.cmake).
filter="^($root|$(realpath "$build_dir")/sensor_side_include)/(app|assets|bench|cell|common|fuzz|models|perception|robot|sim|tests)/"
# Every finding is an error (.clang-tidy's WarningsAsErrors): xargs exits non-zero, and so does the pipe.
# The count of the libraries' own warnings that clang-tidy leaves out is not printed.
printf '%s\n' "$files" | xargs -P "$(nproc)" -n 1 clang-tidy -p "$build_dir" --quiet --header-filter="$filter" 2>&1 |
  { grep -v '^[0-9]* warnings\? generated\.$' || true; }
