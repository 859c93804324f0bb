#!/usr/bin/env bash
# The README's test command (and CI's, .ci/run): installs and builds (scripts/setup.sh), runs the sim and
# slow tests in the Release build, then the unit tests once, under AddressSanitizer + UndefinedBehavior-
# Sanitizer (scripts/sanitize.sh), rather than once plain and again under the sanitizers. The `bench`
# tests (benchmarks' refusals of bad input; the sanitizer build has no benchmarks) run in Release.
# Every test runs; `ctest --test-dir build` after a build still runs them all in Release.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/setup.sh
ctest --test-dir build --output-on-failure -j "$(nproc)" -LE unit
ctest --test-dir build --output-on-failure -j "$(nproc)" -L bench
./scripts/sanitize.sh
