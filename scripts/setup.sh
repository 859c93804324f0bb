#!/usr/bin/env bash
# Installs SortCell's Debian packages (skipping those already present), then configures and builds.
# Idempotent: a second run installs nothing and rebuilds only what changed.
#   scripts/setup.sh            install + configure + build (Release) into build/
#   SORTCELL_BUILD_DIR=dir      build somewhere else
#   SORTCELL_BUILD_TARGET=t     build target t only (scripts/test.sh: sortcell_release_tests)
set -euo pipefail
cd "$(dirname "$0")/.."

packages=(
  build-essential cmake ninja-build pkg-config git
  libmujoco-dev libmujoco-samples libosmesa6-dev
  libpcl-dev libopencv-dev libeigen3-dev liburdfdom-dev
  nlohmann-json3-dev libcli11-dev libyaml-cpp-dev libspdlog-dev libsvm-dev
  libassimp-dev libqhull-dev liblodepng-dev libturbojpeg0-dev
  libgtest-dev libgmock-dev libbenchmark-dev
  ffmpeg gnuplot-nox python3-yaml
  libjs-chart.js chromium python3-websocket
  parallel slurm-wlm munge
  clang lld clang-format clang-tidy valgrind
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${#missing[@]} Debian packages: ${missing[*]}" >&2
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -qq
  "${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build_dir=${SORTCELL_BUILD_DIR:-build}
cmake -S . -B "$build_dir" -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
# Two parallel jobs: PCL translation units take ~1 GiB each; 2 cores is the machine.
cmake --build "$build_dir" -j "$(nproc)" --target "${SORTCELL_BUILD_TARGET:-all}"
