#!/usr/bin/env bash
# Short (CI) or long libFuzzer run of every target in fuzz/.
#   scripts/fuzz-run.sh [SECONDS_PER_TARGET]     default 45
# Exit status: 0 nothing found, 1 a finding in our code (or the CLI broke its contract on an assimp input),
# 3 the clang build failed.
# Builds build-fuzz/ with clang (ASan + UBSan + libFuzzer). Each target starts from its seed corpus
# fuzz/corpus/<name>/ (read-only) plus a working corpus in build-fuzz/corpus/<name>/ (grows across runs).
# A crash, leak, timeout, out-of-memory or contract violation in our code fails the run; the input is left in
# build-fuzz/artifacts/ — turn it into a regression test in tests/reliability/.
# fuzz_assimp_import imports in-process. When a crash, timeout or out-of-memory happens inside assimp (the
# first frame of the stack that belongs to assimp or to us is assimp's), the run checks that the `buoyancy`
# CLI (child-process import with --import-timeout) turns the same file into a clear error (exit 2, "importer
# crashed" / "import timed out"), records it in build-fuzz/assimp-known.txt and goes on fuzzing. Kinds
# listed in third_party_notes/assimp.md (table "Known problems", columns kind and format) are "known";
# others are reported as new (to be listed) without failing: the CLI contract held. If the CLI does not
# turn the file into exit 2 with a message, the run fails.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:-45}
dir=${FUZZ_BUILD_DIR:-build-fuzz}
# -O1 -g1 (line tables only), as OSS-Fuzz builds: about half the compile time of -O2 -g, reports keep file:line.
CC=clang CXX=clang++ cmake -S . -B "$dir" -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1 -DNDEBUG" \
  -DBULLET_BUOYANCY_FUZZ=ON -DBULLET_BUOYANCY_SANITIZE=ON -DBULLET_BUOYANCY_BUILD_TESTS=OFF >/dev/null
targets=(mesh_prepare atlas_bake scene_json water_graph_json permeability_image assimp_import)
# A build that fails is not a fuzz finding (the library no longer compiles with clang): exit 3, which CI gates on.
if ! cmake --build "$dir" -j"${JOBS:-2}" --target "${targets[@]/#/fuzz_}"; then
  echo "fuzz-run: the clang build of the fuzz targets failed" >&2
  exit 3
fi
# The CLI that checks assimp crash inputs: the normal build when present (scripts/test.sh made it).
cli=${BUOYANCY_CLI:-build/bin/buoyancy}
[ -x "$cli" ] || { cmake --build "$dir" -j"${JOBS:-2}" --target buoyancy; cli=$dir/bin/buoyancy; }
mkdir -p "$dir/artifacts"
exts=(.obj .ply .stl .gltf .glb .dae .fbx .3ds)   # supportedMeshExtensions() order: first byte picks one
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:allocator_may_return_null=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}
export LSAN_OPTIONS=${LSAN_OPTIONS:-suppressions=$PWD/fuzz/lsan.supp}   # leaks inside assimp only

# First frame of the crash stack that is not the sanitizer, libFuzzer, libc or libstdc++.
first_frame() {
  grep -E '^ +#[0-9]+ ' "$1" | grep -vE 'libclang_rt|compiler-rt|/libc\.so|libstdc\+\+|__sanitizer|__asan|__ubsan|__interceptor|fuzzer::|LLVMFuzzerTestOneInput|raise|abort| in operator new| in operator delete| in (malloc|calloc|realloc|free) ' | head -1 || true
}
# Whose code the failure is in: "assimp" when the first stack frame that belongs to assimp or to us is
# assimp's (frames of zlib, libm, ... in between are skipped), else "ours".
owner() {
  local who
  who=$(grep -E '^ +#[0-9]+ ' "$1" | grep -oE 'libassimp|Assimp::|buoyancy::|LLVMFuzzerTestOneInput' | head -1 || true)
  case "$who" in libassimp|Assimp::) echo assimp ;; *) echo ours ;; esac
}
# What went wrong, from libFuzzer's report.
failure_kind() {
  if grep -q 'ERROR: libFuzzer: timeout' "$1"; then echo timeout
  elif grep -qE 'ERROR: libFuzzer: out-of-memory|allocation-size-too-big|out of memory' "$1"; then echo out-of-memory
  else echo crash; fi
}
known_notes=third_party_notes/assimp.md

failed=0
for t in "${targets[@]}"; do
  exe=$dir/bin/fuzz_$t
  work=$dir/corpus/$t
  mkdir -p "$work"
  start=$SECONDS
  while :; do
    left=$((secs - (SECONDS - start)))
    [ "$left" -ge 3 ] || break
    log=$dir/fuzz_$t.log
    if "$exe" "$work" "fuzz/corpus/$t" -max_total_time="$left" -timeout=20 -rss_limit_mb=2560 -max_len=65536 \
         -print_final_stats=1 -artifact_prefix="$dir/artifacts/${t}-" >"$log" 2>&1; then
      echo "fuzz_$t: $(grep -E 'stat::number_of_executed_units' "$log" | awk '{print $2}') runs in $((SECONDS - start)) s, no crash"
      break
    fi
    artifact=$(grep -oE "Test unit written to [^ ]+" "$log" | tail -1 | awk '{print $5}')
    frame=$(first_frame "$log")
    kind=$(failure_kind "$log")
    if [ "$t" = assimp_import ] && [ -n "$artifact" ] && [ "$(owner "$log")" = assimp ]; then
      ext=${exts[$(( $(od -An -tu1 -N1 "$artifact" | tr -d ' ') % 8 ))]}
      file=$dir/artifacts/$(basename "$artifact")$ext
      tail -c +2 "$artifact" >"$file"
      set +e
      msg=$("$cli" hydrostatics "$file" --import-timeout 10 2>&1 >/dev/null); rc=$?
      set -e
      if [ "$rc" -eq 2 ] && [ -n "$msg" ]; then
        status="new: list it in $known_notes"
        grep -qiE "^\| *$kind *\| *\\$ext *\|" "$known_notes" && status=known
        echo "fuzz_assimp_import: $kind inside assimp on a $ext input ($status; $frame); CLI says: $msg" |
          tee -a "$dir/assimp-known.txt"
        continue
      fi
      echo "fuzz_assimp_import: $kind inside assimp and the CLI did not turn it into a clear error (exit $rc): $msg"
    fi
    echo "fuzz_$t: FAILED: $kind in our code (input: ${artifact:-none}); log $log:"
    grep -E 'ERROR|runtime error|contract violated|SUMMARY|ALARM|out-of-memory' "$log" | head -5
    echo "  first frame: $frame"
    failed=1
    break
  done
done
exit $failed
