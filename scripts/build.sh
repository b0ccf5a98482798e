#!/usr/bin/env bash
# Configure and build one precision: scripts/build.sh [float|double] [TARGET ...]  ->  build/ or build-double/
# With targets, only those (and what they need) are built, e.g. `scripts/build.sh float buoyancy`.
set -euo pipefail
cd "$(dirname "$0")/.."
precision=${1:-float}
shift || true
case "$precision" in
  float)  dir=build;        flag=OFF ;;
  double) dir=build-double; flag=ON ;;
  *) echo "usage: scripts/build.sh [float|double] [TARGET ...]" >&2; exit 2 ;;
esac
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DBULLET_BUOYANCY_DOUBLE_PRECISION=$flag >/dev/null
if [ $# -gt 0 ]; then
  cmake --build "$dir" -j"${JOBS:-2}" --target "$@"
else
  cmake --build "$dir" -j"${JOBS:-2}"
fi
