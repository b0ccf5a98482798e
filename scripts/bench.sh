#!/usr/bin/env bash
# Regenerate docs/benchmarks: build the `buoyancy` tool (Release, float Bullet), run
# `buoyancy bench` (speed against error, Fig. 9, scaling; several minutes), then draw the PNG plots.
# Usage: scripts/bench.sh [--quick] [--out DIR]      (default DIR: docs/benchmarks; BUILD_DIR default: build)
# Plots need matplotlib (Debian python3-matplotlib: scripts/install-deps.sh --bench); without it the CSVs and
# summary.md are still written.
set -euo pipefail
cd "$(dirname "$0")/.."
build=${BUILD_DIR:-build}
out=docs/benchmarks
args=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    *) args+=("$1"); shift ;;
  esac
done
bash scripts/install-deps.sh --bench || echo "warning: could not install the plotting packages; plots may be skipped" >&2
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j"${JOBS:-2}" --target buoyancy
mkdir -p "$out"
# The commit before machine.txt is rewritten (the redirection below truncates the tracked file first, which made
# every run report "with local changes").
commit="$(git rev-parse --short HEAD 2>/dev/null || echo unknown)$(git diff --quiet 2>/dev/null || echo ' (with local changes)')"
{
  echo "date: $(date -u +%Y-%m-%dT%H:%MZ)"
  echo "commit: $commit"
  echo "cpu: $(lscpu | sed -n 's/^Model name: *//p' | head -1)"
  echo "cores: $(nproc)"
  echo "load average before the run: $(cut -d' ' -f1-3 /proc/loadavg)"
  echo "compiler: $(c++ --version | head -1)"
  echo "bullet: $(pkg-config --modversion bullet 2>/dev/null || echo unknown) (float)"
} > "$out/machine.txt"
start=$(date +%s)
"$build/bin/buoyancy" bench --out "$out" "${args[@]}" 2> "$out/bench.log" >/dev/null
echo "run time: $(( $(date +%s) - start )) s" >> "$out/machine.txt"
echo "load average after the run: $(cut -d' ' -f1-3 /proc/loadavg)" >> "$out/machine.txt"
# Debian's matplotlib lives in the system interpreter (a pyenv python3 on PATH may not see it).
py=""
for cand in /usr/bin/python3 python3; do
  if command -v "$cand" >/dev/null && "$cand" -c "import matplotlib" 2>/dev/null; then py=$cand; break; fi
done
if [ -n "$py" ]; then
  "$py" scripts/bench_plots.py "$out"
else
  echo "warning: matplotlib not found: no PNG plots (scripts/install-deps.sh --bench)" >&2
fi
cat "$out/summary.md"
echo "wrote $out"
