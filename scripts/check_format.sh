#!/usr/bin/env bash
# Fails (exit 1, naming each file and line) where a C++ source in git differs from .clang-format's style;
# scripts/test.sh (CI) runs it first. scripts/format.sh applies the style.
set -euo pipefail
cd "$(dirname "$0")/.."
# New files git does not ignore count too (as scripts/format.sh formats them).
git ls-files -z --cached --others --exclude-standard '*.cc' '*.h' | xargs -0 clang-format --dry-run --Werror
