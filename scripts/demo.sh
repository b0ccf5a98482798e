#!/usr/bin/env bash
# README command 1: install what is missing, build, run the main job (hydrostatics of the bundled boat hull).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
bash scripts/build.sh float
model=bullet_examples/models/boat_hull.obj
echo
echo "== buoyancy hydrostatics $model --rotate 0 0 1 10 --translate 0 0.1 0"
build/bin/buoyancy hydrostatics "$model" --rotate 0 0 1 10 --translate 0 0.1 0
echo
echo "== the same, as JSON"
build/bin/buoyancy hydrostatics "$model" --rotate 0 0 1 10 --translate 0 0.1 0 --json
