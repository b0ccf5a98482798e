#!/usr/bin/env bash
# Long soaks and property tests (CTest label `long`), both precisions. Not part of the default run or CI.
#   bash scripts/long-tests.sh            # float then double
#   PRECISIONS=double bash scripts/long-tests.sh
# What runs (tests tagged [long]): the 1,000-body × 10^5-substep soak in Gerstner waves with water graphs
# (tests/reliability/SoakTest.cpp), the 3000-case property test (tests/scenarios/HardCasesTest.cpp). Each
# prints its numbers (ctest --verbose); the last results are in docs/development.md.
# Then long fuzzing: scripts/fuzz-run.sh with FUZZ_SECONDS per target (default 900; FUZZ_SECONDS=0 skips it).
# (The fuzz build also has one CTest test per target labelled `long`: `ctest -L long` in build-fuzz.)
# On a shared machine run it with `nice -n 10`; it takes hours on 2 cores.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
for precision in ${PRECISIONS:-float double}; do
  start=$SECONDS
  bash scripts/build.sh "$precision"
  dir=build; [ "$precision" = double ] && dir=build-double
  (cd "$dir" && ctest -L long --verbose --output-on-failure --timeout 36000)
  echo "long tests ($precision): $((SECONDS - start)) s"
done
fuzz=${FUZZ_SECONDS:-900}
if [ "$fuzz" -gt 0 ]; then
  start=$SECONDS
  bash scripts/fuzz-run.sh "$fuzz"
  echo "long fuzzing ($fuzz s per target): $((SECONDS - start)) s"
fi
