#!/usr/bin/env bash
# Builds wardmap and runs the whole test suite; ends with ctest's summary.
#   scripts/test.sh                 Release build in build/ (installs missing Debian packages first)
#   scripts/test.sh --sanitize      address + undefined sanitizers, in build-asan/
#   scripts/test.sh --tsan          thread sanitizer, in build-tsan/
# Tests that need ../shared (or $WARDMAP_DATA / $WARDMAP_MODELS) skip with a message when it is absent.
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=build
EXTRA=()
case "${1:-}" in
  --sanitize) BUILD=build-asan; EXTRA=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DWARDMAP_SANITIZE=address,undefined -DWARDMAP_BUILD_BENCH=OFF) ;;
  --tsan) BUILD=build-tsan; EXTRA=(-DCMAKE_BUILD_TYPE=RelWithDebInfo -DWARDMAP_SANITIZE=thread -DWARDMAP_BUILD_BENCH=OFF) ;;
  -h|--help) sed -n '2,7p' "$0"; exit 0 ;;
  "") EXTRA=(-DCMAKE_BUILD_TYPE=Release) ;;
  *) echo "test.sh: unknown option '$1' (see --help)" >&2; exit 2 ;;
esac

scripts/setup.sh --deps-only
JOBS=$(nproc 2>/dev/null || echo 2)
cmake -S . -B "$BUILD" "${EXTRA[@]}"
cmake --build "$BUILD" -j"$JOBS"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1}  # off only for the VTK render tests (tests/semantics/render)
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1}
# history_size=7: the longest access history, so that the other thread's stack of a report can be
# restored and matched against the suppressions (tests/sanitizers/tsan.supp).
export TSAN_OPTIONS=${TSAN_OPTIONS:-suppressions=$PWD/tests/sanitizers/tsan.supp second_deadlock_stack=1 history_size=7}
cd "$BUILD"
ctest --output-on-failure -j"$JOBS" --timeout 900
