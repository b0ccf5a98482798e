#!/usr/bin/env bash
# Bullet's ExampleBrowser with our scenes in a "Buoyancy" group (docs/example-browser.md):
#   bash scripts/example-browser.sh BULLET_SOURCE_DIR [BUILD_DIR]
# BULLET_SOURCE_DIR: a Bullet source tree with its examples/ folder (3.24 or newer: a git checkout or a release
# tarball). It is only read: our rows go into a copy of its ExampleEntries.cpp inside BUILD_DIR.
# BUILD_DIR (default: build-example-browser): one CMake build of that Bullet, BulletBuoyancy against it (one
# Bullet in the process) and the adapter (bullet_examples/example_browser). Builds App_ExampleBrowser only.
# PRECISION=double builds both in double precision (default float); JOBS=N parallel jobs (default 2).
# Downloads nothing.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)

usage() {
  cat >&2 <<'TXT'
usage: bash scripts/example-browser.sh BULLET_SOURCE_DIR [BUILD_DIR]
BULLET_SOURCE_DIR is a Bullet source tree with its examples/ folder (Bullet 3.24 or newer), for example
  git clone https://github.com/bulletphysics/bullet3
or a release tarball from https://github.com/bulletphysics/bullet3/releases (Debian's libbullet-dev has no examples).
This script downloads nothing.
TXT
  exit 2
}

[ $# -ge 1 ] && [ $# -le 2 ] || usage
src=$1
if [ ! -f "$src/examples/ExampleBrowser/ExampleEntries.cpp" ] || [ ! -f "$src/src/btBulletDynamicsCommon.h" ]; then
  echo "example-browser: $src is not a Bullet source tree with examples/ExampleBrowser" >&2
  usage
fi
src=$(cd "$src" && pwd)
build=${2:-$root/build-example-browser}
case "${PRECISION:-float}" in
  float) double=OFF ;;
  double) double=ON ;;
  *) echo "example-browser: PRECISION must be float or double" >&2; exit 2 ;;
esac

commit=""
if git -C "$src" rev-parse --verify -q HEAD >/dev/null 2>&1; then commit=$(git -C "$src" rev-parse --short HEAD); fi
version=$(cat "$src/VERSION" 2>/dev/null || echo "?")
echo "== Bullet $version${commit:+ (commit $commit)} from $src, ${PRECISION:-float} precision, build in $build"

cmake -S "$root/bullet_examples/example_browser" -B "$build" -DCMAKE_BUILD_TYPE=Release \
      -DBULLET_SOURCE_DIR="$src" -DBULLET_BUOYANCY_DOUBLE_PRECISION=$double -Wno-dev -Wno-deprecated >/dev/null
cmake --build "$build" --target App_ExampleBrowser -j"${JOBS:-2}"

exe=$(find "$build/bullet/examples/ExampleBrowser" -maxdepth 1 -type f -name 'App_ExampleBrowser*' -perm -u+x | head -n 1)
[ -n "$exe" ] || { echo "example-browser: App_ExampleBrowser was not built" >&2; exit 1; }
cat <<TXT

Built $exe
Start it (our scenes are the "Buoyancy" group at the end of the list):
  $exe --start_demo_name="Buoy in waves"
Without a display (Xvfb, software OpenGL):
  xvfb-run -a -s "-screen 0 1280x720x24" $exe --start_demo_name="Buoy in waves" --width=1280 --height=720
Unattended: BUOYANCY_EXAMPLE_FRAMES=N quits after N frames, BUOYANCY_EXAMPLE_PNG=FILE.png saves the last one.
TXT
