#!/usr/bin/env bash
# Make docs/pictures/*.png: a strip of three frames per example scene, rendered offscreen by
# `buoyancy run SCENE --png DIR` (Mesa EGL, no display needed), and a screenshot of the scene browser under
# Xvfb. Usage: bash scripts/pictures.sh [BUILD_DIR]   (default build/, made by scripts/build.sh float)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
if [ ! -x "$build/bin/buoyancy" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
fi
cmake --build "$build" -j"${JOBS:-2}" --target buoyancy
out=docs/pictures
work=$build/pictures
mkdir -p "$out" "$work"

# scene file, duration (s), the three output-frame numbers of its strip (frame k is t = k x output_interval)
scenes=(
  "buoy_waves          6   10 30 50"
  "boat_holed_bow      12  4 12 20"
  "boat_holed_stern    20  0 20 40"
  "ball_stability      2   0 10 20"
  "variable_density_ball 20 0 100 200"
  "plush_toy           60  0 60 120"
  "balloon_air         3   0 12 24"
  "fft_fleet           6   0 30 60"
  "beach_boat          12  0 50 120"
  "crate_splash        2   10 20 40"
  "demo_boat_gerstner  10  10 50 100"
)
for row in "${scenes[@]}"; do
  read -r name duration a b c <<<"$row"
  scene=bullet_examples/scenes/$name.json
  [ -f "$scene" ] || { echo "skip $name (no $scene)"; continue; }
  rm -rf "$work/$name"
  echo "== $name"
  "$build/bin/buoyancy" run "$scene" --out "$work/$name" --duration "$duration" --png "$work/$name/png" \
    --size 480 270 2>/dev/null
  frames=()
  for k in $a $b $c; do frames+=("$(printf '%s/%s/png/frame_%05d.png' "$work" "$name" "$k")"); done
  python3 scripts/png_strip.py "$out/$name.png" "${frames[@]}"
done

# The browser (needs GLFW/ImGui at configure time and xvfb-run).
if cmake --build "$build" -j"${JOBS:-2}" --target buoyancy_browser >/dev/null 2>&1 && command -v xvfb-run >/dev/null; then
  echo "== browser"
  xvfb-run -a -s "-screen 0 1280x720x24" "$build/bin/buoyancy_browser" --scene "Boat holed at the bow" \
    --frames 300 --screenshot "$out/browser.png"
else
  echo "skip the browser screenshot (no buoyancy_browser target or no xvfb-run)"
fi
ls -l "$out"
