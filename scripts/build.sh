#!/usr/bin/env bash
# Configure and build one precision: scripts/build.sh [float|double]  ->  build/ or build-double/
set -euo pipefail
cd "$(dirname "$0")/.."
precision=${1:-float}
case "$precision" in
  float)  dir=build;        flag=OFF ;;
  double) dir=build-double; flag=ON ;;
  *) echo "usage: scripts/build.sh [float|double]" >&2; exit 2 ;;
esac
cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=Release -DBULLET_BUOYANCY_DOUBLE_PRECISION=$flag >/dev/null
cmake --build "$dir" -j"${JOBS:-2}"
