#!/usr/bin/env bash
# Formats every C++ source in place with .clang-format (the check: scripts/check_format.sh): git's files and
# the new ones git does not ignore (a file not yet added is formatted too, so it is not caught only in CI).
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files -z --cached --others --exclude-standard '*.cc' '*.h' | xargs -0 clang-format -i
