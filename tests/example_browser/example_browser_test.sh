#!/usr/bin/env bash
# CTest test "example-browser: our scene in Bullet's ExampleBrowser" (labels example-browser and long):
#   example_browser_test.sh REPO_ROOT BUILD_DIR [BULLET_SOURCE_DIR]
# Builds Bullet's ExampleBrowser with our scenes (scripts/example-browser.sh) from the Bullet tree given by CMake's
# BULLET_SOURCE_DIR or the environment's, then runs 240 frames of "Buoy in waves" under Xvfb and checks the frame
# loop's summary line. Without a Bullet tree it says so and exits 77 (CTest: skipped).
set -euo pipefail
root=$1
build=$2
src=${3:-${BULLET_SOURCE_DIR:-}}
if [ -z "$src" ]; then
  echo "skipped: set BULLET_SOURCE_DIR (environment or CMake) to a Bullet source tree with examples/ to run this test"
  exit 77
fi
xvfb=$(command -v xvfb-run || true)
if [ -z "$xvfb" ]; then
  echo "skipped: xvfb-run not found (Debian: xvfb)"
  exit 77
fi
bash "$root/scripts/example-browser.sh" "$src" "$build"
exe=$(find "$build/bullet/examples/ExampleBrowser" -maxdepth 1 -type f -name 'App_ExampleBrowser*' -perm -u+x | head -n 1)
log=$build/frame_loop.log
png=$build/frame_loop.png
rm -f "$log" "$png"
# A fixed step per frame (1/60 s) makes the 240 frames 4 s of simulated time whatever the machine's speed.
BUOYANCY_EXAMPLE_FRAMES=240 BUOYANCY_EXAMPLE_PNG="$png" timeout 600 \
  "$xvfb" -a -s "-screen 0 1024x768x24" "$exe" --start_demo_name="Buoy in waves" --width=1024 --height=768 \
  --fixed_timestep=0.016667 >"$log" 2>&1 || { cat "$log"; echo "App_ExampleBrowser failed"; exit 1; }
grep "Buoyancy example:" "$log"
grep -q "Buoyancy example: 240 frames, .* 1 bodies, .* all finite" "$log" || { echo "no good frame-loop summary"; exit 1; }
# 240 frames of 1/60 s: the scene's clock must have advanced 4 s (whole frames of its fixed step, within one frame).
t=$(sed -n 's/.*240 frames, \([0-9.]*\) s simulated.*/\1/p' "$log")
awk -v t="$t" 'BEGIN { exit !(t > 3.9 && t < 4.1) }' || { echo "simulated time $t s, expected 4 s"; exit 1; }
[ -s "$png" ] || { echo "no picture written to $png"; exit 1; }
echo "ok: $png"
