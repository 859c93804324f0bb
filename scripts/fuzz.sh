#!/usr/bin/env bash
# Fuzzes every reader of user files with libFuzzer under ASan + UBSan (fuzz/*_fuzz.cc), seeded from the
# kept corpora (fuzz/corpus/<reader>, which began as the shipped files). Needs clang (scripts/setup.sh
# installs it). Builds into build-fuzz/.
#   scripts/fuzz.sh                    every reader for 600 s each, two at a time
#   scripts/fuzz.sh 60 pcd camera      those readers, 60 s each
#   SORTCELL_FUZZ_JOBS=1               one reader at a time
#   SORTCELL_FUZZ_KEEP=1               merge what each run found into fuzz/corpus/<reader> (minimised)
# Findings (crash-*, timeout-*, oom-*, leak-* inputs) land in build-fuzz/findings/<reader>/; each run's
# log in build-fuzz/logs/<reader>.log; a table of executions and findings per reader is printed and
# written to build-fuzz/fuzz_report.md. Exit 1 if anything was found.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
readers=("$@")
[ ${#readers[@]} -eq 0 ] && readers=(pcd object_set sweep_spec model dataset camera results scene)
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: seconds per reader must be a whole number, got '$seconds'" >&2; exit 2 ;; esac
jobs=${SORTCELL_FUZZ_JOBS:-2}
build=build-fuzz
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" \
  -DSORTCELL_FUZZ=ON -DSORTCELL_BUILD_TESTS=OFF -DSORTCELL_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --target sortcell_fuzz_targets -j "$(nproc)"

# Leaks count; see scripts/sanitize.sh for alloc_dealloc_mismatch=0 (Debian PCL's allocator pairing).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:alloc_dealloc_mismatch=0}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

run_reader() {
  local reader=$1 seconds=$2 build=$3
  local work="$build/corpus/$reader" findings="$build/findings/$reader" log="$build/logs/$reader.log"
  rm -rf "$findings" && mkdir -p "$work" "$findings" "$(dirname "$log")"
  # -timeout: an input read for more than 10 s is a hang; -rss_limit_mb: more than 2 GiB is a blow-up.
  "$build/fuzz/${reader}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$work" "fuzz/corpus/$reader" >"$log" 2>&1 || true
  if [ "${SORTCELL_FUZZ_KEEP:-0}" = 1 ]; then
    local merged; merged=$(mktemp -d)
    "$build/fuzz/${reader}_fuzz" -merge=1 "$merged" "fuzz/corpus/$reader" "$work" >>"$log" 2>&1 || true
    rm -rf "fuzz/corpus/$reader" && mv "$merged" "fuzz/corpus/$reader"
  fi
}
export -f run_reader

printf '%s\n' "${readers[@]}" | xargs -P "$jobs" -I{} bash -c 'run_reader "$@"' _ {} "$seconds" "$build"

report="$build/fuzz_report.md"
found=0
{
  echo "| reader | seconds | executions | corpus inputs | findings |"
  echo "|---|---|---|---|---|"
  for reader in "${readers[@]}"; do
    log="$build/logs/$reader.log"
    runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo "?")
    corpus=$(find "$build/corpus/$reader" "fuzz/corpus/$reader" -type f | wc -l)
    n=$(find "$build/findings/$reader" -type f | wc -l)
    found=$((found + n))
    echo "| $reader | $seconds | $runs | $corpus | $n |"
  done
} | tee "$report"
echo "report: $report; findings under $build/findings/"
[ "$found" -eq 0 ]
