#!/usr/bin/env bash
# Long soaks and property tests (CTest label `long`), both precisions. Not part of the default run.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
for precision in float double; do
  bash scripts/build.sh "$precision"
  dir=build; [ "$precision" = double ] && dir=build-double
  (cd "$dir" && ctest -L long --output-on-failure --timeout 7200)
done
