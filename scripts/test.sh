#!/usr/bin/env bash
# README command 2: install what is missing, build both Bullet precisions, run every test not labelled `long`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
start=$SECONDS
for precision in float double; do
  echo "== build ($precision)"
  bash scripts/build.sh "$precision"
  dir=build; [ "$precision" = double ] && dir=build-double
  echo "== tests ($precision)"
  (cd "$dir" && ctest -LE long --output-on-failure -j"${JOBS:-2}" --timeout 900)
done
echo "tests done in $((SECONDS - start)) s"
