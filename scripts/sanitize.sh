#!/usr/bin/env bash
# Builds what the unit tests need with AddressSanitizer + UndefinedBehaviorSanitizer into
# build-sanitize/ and runs them there (ctest -L unit; .ci/run runs this after the main suite). Needs the
# packages scripts/setup.sh installs.
#   scripts/sanitize.sh            build (clang, -O1 -g1) and run the unit tests
#   SORTCELL_SANITIZE_DIR=dir      build somewhere else
# clang (and lld), not the Release build's GCC: the same targets built in 642 CPU-seconds against GCC's 832,
# with half the memory, and the same runtimes (docs/reliability.md, Sanitizers). -O1 -g1: ASan's advice, and
# 2.5 times quicker to compile than -O2 -g. No benchmarks, no sim tests. Each test executable runs as a few
# processes, gtest's shards (SORTCELL_SHARDED_TESTS, tests/CMakeLists.txt), not one per test case: a process
# takes about 0.3 s to start under the sanitizers. The libraries are unity builds here too, as in every build
# (SORTCELL_UNITY_BUILD, CMakeLists.txt).
set -euo pipefail
cd "$(dirname "$0")/.."
build_dir=${SORTCELL_SANITIZE_DIR:-build-sanitize}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSORTCELL_SANITIZE=ON \
  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  "-DCMAKE_CXX_FLAGS_RELWITHDEBINFO=-O1 -g1" "-DCMAKE_C_FLAGS_RELWITHDEBINFO=-O1 -g1" \
  -DSORTCELL_BUILD_BENCHMARKS=OFF -DSORTCELL_SHARDED_TESTS=ON >/dev/null
cmake --build "$build_dir" --target sortcell_unit_tests -j "$(nproc)"
# Leaks count as findings; UBSan prints the stack of what it finds and stops the test. Every ASan check is on,
# alloc_dealloc_mismatch too: PCL's templates are compiled here (perception/pcl_instantiations.cc), so a
# supervoxel's shared state is allocated and released by code of this build (with Debian's prebuilt
# libpcl_segmentation it was allocated there with malloc and released here with operator delete).
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=0:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
# Leaks inside prebuilt libraries that are theirs (scripts/lsan_suppressions.txt says which and why).
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/scripts/lsan_suppressions.txt}
ctest --test-dir "$build_dir" -L unit --output-on-failure -j "$(nproc)"
