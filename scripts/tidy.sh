#!/usr/bin/env bash
# clang-tidy with .clang-tidy's checks over the files the build compiles (its compile_commands.json: the
# unity files, so each batch's headers are parsed once), reporting what it finds in the project's own
# sources and headers. Exit 1 on any finding.
#   scripts/tidy.sh [--libraries] [BUILD_DIR]   default build/ (configured by scripts/setup.sh)
#     (all)        every compiled file: the libraries, the app, the tests, the benchmarks, the fuzz targets
#                  (2 min 2 s on 2 cores at 08177e6, 39 files: one unity file per target, the benchmarks' and
#                  fuzz targets' sources, and perception/pcl_instantiations.cc with PCL's implementation
#                  headers; 2 min 18 s with batches of 16, 44 files): what CI runs
#     --libraries  the libraries and the app only (about 240 CPU-seconds), for a quicker check while working
set -euo pipefail
cd "$(dirname "$0")/.."
only_libraries=0
if [[ ${1:-} == --libraries ]]; then
  only_libraries=1
  shift
fi
build_dir=${1:-build}
root=$PWD
if [[ ! -f $build_dir/compile_commands.json ]]; then
  echo "tidy.sh: $build_dir/compile_commands.json not found (configure the build first: scripts/setup.sh)" >&2
  exit 2
fi
# The compiled files, each once; with --libraries, those of
# the sortcell_* libraries and the sortcell executable.
files=$(/usr/bin/python3 -c 'import json, re, sys
files = sorted({e["file"] for e in json.load(open(sys.argv[1]))})
if sys.argv[2] == "1":
    files = [f for f in files if re.search(r"/CMakeFiles/sortcell(_[a-z]+)?\.dir/", f)]
print("\n".join(files))' "$build_dir/compile_commands.json" "$only_libraries")
# The project's files, also as the sensor side's include root shows them (cmake/sensor_side.cmake).
filter="^($root|$(realpath "$build_dir")/sensor_side_include)/(app|assets|bench|cell|common|files|fuzz|models|perception|robot|sim|simcell|tests|training)/"
# Every finding is an error (.clang-tidy's WarningsAsErrors): xargs exits non-zero, and so does the pipe.
# The count of the libraries' own warnings that clang-tidy leaves out is not printed.
# --config-file: clang-tidy looks for .clang-tidy beside each file, and the unity files are in the build
# folder: one outside the tree would run clang-tidy's default checks instead of the project's.
printf '%s\n' "$files" | xargs -P "$(nproc)" -n 1 clang-tidy -p "$build_dir" --config-file="$root/.clang-tidy" --quiet \
  --header-filter="$filter" 2>&1 |
  { grep -v '^[0-9]* warnings\? generated\.$' || true; }
