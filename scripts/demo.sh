#!/usr/bin/env bash
# README command 1: install what is missing, build, run the main job (a model floating in Gerstner waves).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh float buoyancy   # the demo needs the command-line tool only (the tests: scripts/test.sh)
scene=bullet_examples/scenes/demo_boat_gerstner.json
out=build/demo_boat_gerstner
echo
echo "== buoyancy run $scene --out $out   (the boat hull, a buoy, a crate and a log in Gerstner waves)"
build/bin/buoyancy run "$scene" --out "$out"   # progress on stderr, the summary table at the end
