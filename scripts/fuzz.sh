#!/usr/bin/env bash
# Fuzzes every reader of user files with libFuzzer under ASan + UBSan (fuzz/*_fuzz.cc), seeded from the
# kept corpora (fuzz/corpus/<reader>, which began as the shipped files). Needs clang (scripts/setup.sh
# installs it). Builds into build-fuzz/.
#   scripts/fuzz.sh                    every reader for 600 s each, two at a time
#   scripts/fuzz.sh 60 pcd camera      those readers, 60 s each
#   SORTCELL_FUZZ_JOBS=1               one reader at a time
#   SORTCELL_FUZZ_KEEP=1               merge what each run found into fuzz/corpus/<reader> (minimised)
# Findings (crash-*, timeout-*, oom-*, leak-* inputs) land in build-fuzz/findings/<reader>/; each run's
# log in build-fuzz/logs/<reader>.log; then every kept input is replayed under valgrind through the plain
# build's replays (build/fuzz/<reader>_fuzz), which sees writes inside the prebuilt libraries that ASan
# cannot; a table of executions and findings per reader is printed and written to
# build-fuzz/fuzz_report.md. Exit 1 if anything was found.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds=${1:-600}
shift || true
readers=("$@")
[ ${#readers[@]} -eq 0 ] && readers=(pcd object_set sweep_spec model dataset camera results scene mesh urdf cell image)
case "$seconds" in ''|*[!0-9]*) echo "fuzz.sh: seconds per reader must be a whole number, got '$seconds'" >&2; exit 2 ;; esac
for reader in "${readers[@]}"; do
  [ -f "fuzz/${reader}_fuzz.cc" ] || { echo "fuzz.sh: no reader '$reader' (fuzz/*_fuzz.cc)" >&2; exit 2; }
done
jobs=${SORTCELL_FUZZ_JOBS:-2}
build=build-fuzz
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -gline-tables-only" \
  -DSORTCELL_FUZZ=ON -DSORTCELL_BUILD_TESTS=OFF -DSORTCELL_BUILD_BENCHMARKS=OFF >/dev/null
cmake --build "$build" --target sortcell_fuzz_targets -j "$(nproc)"

# Leaks count, and every other check (scripts/sanitize.sh says why alloc_dealloc_mismatch is on again).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan_suppressions.txt}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

run_reader() {
  local reader=$1 seconds=$2 build=$3
  local work="$build/corpus/$reader" findings="$build/findings/$reader" log="$build/logs/$reader.log"
  rm -rf "$findings" && mkdir -p "$work" "$findings" "$(dirname "$log")"
  # -timeout: an input read for more than 10 s is a hang; -rss_limit_mb: more than 2 GiB is a blow-up.
  "$build/fuzz/${reader}_fuzz" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048 -print_final_stats=1 \
    -artifact_prefix="$findings/" "$work" "fuzz/corpus/$reader" >"$log" 2>&1 || true
  # A fuzzer that stopped without its final statistics and without leaving an input did not run.
  if ! grep -q "stat::number_of_executed_units" "$log" && [ -z "$(ls -A "$findings")" ]; then
    echo "fuzz.sh: $reader: the fuzzer did not run (see $log)" > "$findings/did-not-run"
  fi
  if [ "${SORTCELL_FUZZ_KEEP:-0}" = 1 ]; then
    local merged; merged=$(mktemp -d)
    if "$build/fuzz/${reader}_fuzz" -merge=1 "$merged" "fuzz/corpus/$reader" "$work" >>"$log" 2>&1 && [ -n "$(ls -A "$merged")" ]; then
      chmod 755 "$merged" && rm -rf "fuzz/corpus/$reader" && mv "$merged" "fuzz/corpus/$reader"
    else
      rm -rf "$merged"
    fi
  fi
}
export -f run_reader

printf '%s\n' "${readers[@]}" | xargs -P "$jobs" -I{} bash -c 'run_reader "$@"' _ {} "$seconds" "$build"

# ASan sees only the instrumented code: a write past a buffer inside the prebuilt PCL or MuJoCo shows
# at best as an ASan CHECK failure later. Replay every kept input through the plain replay build
# (build/, the unit tests' fuzz_replay_*) under valgrind, which watches those libraries too.
valgrind_found=0
if command -v valgrind >/dev/null && [ -x build/fuzz/pcd_fuzz ]; then
  cmake --build build --target sortcell_fuzz_targets -j "$(nproc)" >/dev/null  # The replays of this source.
  for reader in "${readers[@]}"; do
    rm -f "$build/logs/$reader.valgrind.result"
    inputs=("fuzz/corpus/$reader" "$build/corpus/$reader")
    [ -d "fuzz/regressions/$reader" ] && inputs+=("fuzz/regressions/$reader")
    if valgrind -q --error-exitcode=9 "build/fuzz/${reader}_fuzz" "${inputs[@]}" >"$build/logs/$reader.valgrind.log" 2>&1; then
      echo clean > "$build/logs/$reader.valgrind.result"
    else
      echo errors > "$build/logs/$reader.valgrind.result"
      echo "valgrind: errors replaying the $reader inputs: $build/logs/$reader.valgrind.log" >&2
      valgrind_found=$((valgrind_found + 1))
    fi
  done
else
  echo "fuzz.sh: no valgrind or no build/fuzz/*_fuzz (scripts/setup.sh builds them): the valgrind replay is skipped" >&2
fi

report="$build/fuzz_report.md"
found=$valgrind_found
for reader in "${readers[@]}"; do found=$((found + $(find "$build/findings/$reader" -type f | wc -l))); done
{
  echo "| reader | seconds | executions | corpus inputs | findings | valgrind replay |"
  echo "|---|---|---|---|---|---|"
  for reader in "${readers[@]}"; do
    log="$build/logs/$reader.log"
    runs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | tail -1 | grep -o '[0-9]*$' || echo "?")
    corpus=$(find "$build/corpus/$reader" "fuzz/corpus/$reader" -type f | wc -l)
    n=$(find "$build/findings/$reader" -type f | wc -l)
    vg=$(cat "$build/logs/$reader.valgrind.result" 2>/dev/null || echo "not run")
    echo "| $reader | $seconds | $runs | $corpus | $n | $vg |"
  done
} | tee "$report"
echo "report: $report; findings under $build/findings/"
[ "$found" -eq 0 ]
