#!/usr/bin/env bash
# Formats every C++ source in git in place with .clang-format (the check: scripts/check_format.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
git ls-files -z '*.cc' '*.h' | xargs -0 clang-format -i
