#!/usr/bin/env bash
# The README's test command (and CI's, .ci/run): installs and builds (scripts/setup.sh), runs the sim and
# slow tests in the Release build, then the unit tests once, under AddressSanitizer + UndefinedBehavior-
# Sanitizer (scripts/sanitize.sh), rather than once plain and again under the sanitizers. The `bench`
# tests (benchmarks' refusals of bad input; the sanitizer build has no benchmarks) run in Release.
# Every test runs; after the whole build (./scripts/setup.sh) `ctest --test-dir build` runs them all in Release.
set -euo pipefail
cd "$(dirname "$0")/.."
# Release builds what it runs (target sortcell_release_tests: the app, the sim and slow tests, the
# benchmarks); the unit tests are built and run by sanitize.sh. CTest stands in a unit executable that
# was not built by a test "<name>_NOT_BUILT", which is left out with the unit tests.
SORTCELL_BUILD_TARGET=sortcell_release_tests ./scripts/setup.sh
# The sources in .clang-format's style (scripts/format.sh applies it), and clang-tidy's checks (.clang-tidy).
./scripts/check_format.sh
# clang-tidy over every compiled file: the libraries, the app, the tests, the benchmarks, the fuzz targets.
./scripts/tidy.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" -LE unit -E '_NOT_BUILT$'
ctest --test-dir build --output-on-failure -j "$(nproc)" -L bench
./scripts/sanitize.sh
