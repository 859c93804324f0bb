#!/usr/bin/env bash
# The honesty rule, checked in the sources: robot/, perception/ and cell/ decide from sensors only, so
# none of them, nor common/ (on their include root), may include MuJoCo or the simulator (sim/) or
# the folders above it (files/, simcell/, training/, app/). Prints every offending line and exits 1 if there is one. (The build also refuses them: see
# cmake/sensor_side.cmake.)
#   scripts/check_sensor_side.sh [SOURCE_DIR]
set -euo pipefail
root=${1:-$(dirname "$0")/..}
pattern='^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]([^">]*/)?(mujoco/|mujoco\.h|sim/|simcell/|training/|files/|app/|GL/osmesa)'
found=0
for dir in robot perception cell common; do
  [ -d "$root/$dir" ] || { echo "check_sensor_side: no folder $root/$dir" >&2; exit 2; }
  if grep -rnE "$pattern" "$root/$dir" --include='*.h' --include='*.cc' --include='*.hpp' --include='*.cpp'; then
    found=1
  fi
done
if [ "$found" -ne 0 ]; then
  echo "check_sensor_side: robot/, perception/ and cell/ must not include MuJoCo, sim/, files/, simcell/, training/ or app/ (lines above)" >&2
  exit 1
fi
echo "check_sensor_side: robot/, perception/ and cell/ include neither MuJoCo nor sim/ nor the folders above it"
