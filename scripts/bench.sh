#!/usr/bin/env bash
# Runs the benchmark harness (Release build in build/) and saves its JSON next to the console output.
#   scripts/bench.sh [--benchmark_filter=REGEX]
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build build -j"$(nproc)" --target wardmap_bench
mkdir -p build/bench-results
build/bench/wardmap_bench --benchmark_out=build/bench-results/bench.json --benchmark_out_format=json "$@"
