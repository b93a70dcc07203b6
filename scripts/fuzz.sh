#!/usr/bin/env bash
# Fuzzes wardmap's input readers with libFuzzer under address + undefined sanitizers (tests/fuzz,
# docs/DEVELOPMENT.md#fuzzing). Installs what it needs (scripts/setup.sh --deps-only --with-clang: the
# project's packages, clang, libclang-rt-14-dev); builds in build-fuzz/.
#   scripts/fuzz.sh [SECONDS] [TARGET...]   each target (default: all) for SECONDS (default 60)
# Targets: trajectory settings sequences vocabulary onnx_rewrites annotations object_files model_description glb.
# Each starts from its committed corpus (tests/fuzz/corpus/<target>; onnx_rewrites from the models
# of $WARDMAP_MODELS or ../shared/models) and keeps what it finds in
# build-fuzz/corpus/<target>; a crash or an exception that is not an InputError is written to
# build-fuzz/findings/<target>/ and named at the end. A fixed finding's input goes into the committed
# corpus, where ctest replays it (fuzz_<target>_corpus).
set -euo pipefail
cd "$(dirname "$0")/.."
case "${1:-}" in -h|--help) sed -n '2,11p' "$0"; exit 0 ;; esac
SECONDS_EACH=60
if [[ "${1:-}" =~ ^[0-9]+$ ]]; then SECONDS_EACH=$1; shift; fi
TARGETS=("$@")
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(trajectory settings sequences vocabulary onnx_rewrites annotations object_files model_description glb)
scripts/setup.sh --deps-only --with-clang
CC=clang CXX=clang++ cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DWARDMAP_FUZZ=ON \
  -DWARDMAP_SANITIZE=address,undefined -DWARDMAP_BUILD_BENCH=OFF >/dev/null
cmake --build build-fuzz -j"$(nproc 2>/dev/null || echo 2)" --target "${TARGETS[@]/#/fuzz_}"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
failed=()
for t in "${TARGETS[@]}"; do
  corpus=build-fuzz/corpus/$t findings=build-fuzz/findings/$t
  mkdir -p "$corpus" "$findings"
  echo "== fuzz_$t: ${SECONDS_EACH} s (log build-fuzz/fuzz_$t.log)"
  seeds=()
  [ -d tests/fuzz/corpus/"$t" ] && seeds+=(tests/fuzz/corpus/"$t")
  if [ "$t" = onnx_rewrites ]; then  # the shared models, linked in (never committed)
    models=${WARDMAP_MODELS:-../shared/models}
    mkdir -p build-fuzz/seeds/onnx_rewrites
    for m in "$models"/*/*.onnx; do [ -f "$m" ] && ln -sf "$(realpath "$m")" build-fuzz/seeds/onnx_rewrites/; done
    seeds+=(build-fuzz/seeds/onnx_rewrites)
  fi
  if build-fuzz/tests/fuzz/fuzz_$t -max_total_time="$SECONDS_EACH" -timeout=10 -rss_limit_mb=4096 \
       -artifact_prefix="$findings/" "$corpus" "${seeds[@]}" >build-fuzz/fuzz_$t.log 2>&1; then
    grep -E "^Done [0-9]+ runs" build-fuzz/fuzz_$t.log | tail -1 || true
  else
    failed+=("$t"); grep -E "^fuzz: |ERROR: |SUMMARY: |Test unit written" build-fuzz/fuzz_$t.log | head -5
  fi
done
if [ ${#failed[@]} -gt 0 ]; then echo "findings in: ${failed[*]} (build-fuzz/findings/)"; exit 1; fi
echo "no findings in ${#TARGETS[@]} targets"
