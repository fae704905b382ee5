#!/usr/bin/env bash
# The whole test suite from scratch: packages, then
#   1. a Release build with everything (FCL solver, harness) and ctest;
#   2. the core library and its tests again under AddressSanitizer +
#      UndefinedBehaviorSanitizer (-fno-sanitize-recover=all).
# Usage: bash scripts/test.sh        (from anywhere; as root or with sudo)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
JOBS=$(nproc)

echo "== Release build and tests"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DTRICYL_BUILD_BENCH=OFF
cmake --build build/release -j "$JOBS"
ctest --test-dir build/release --output-on-failure -j "$JOBS"

echo "== ASan + UBSan build and tests (core library)"
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRICYL_SANITIZE=ON \
  -DTRICYL_WITH_FCL=OFF -DTRICYL_BUILD_COMPARE=OFF -DTRICYL_BUILD_BENCH=OFF
cmake --build build/asan -j "$JOBS"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build/asan --output-on-failure -j "$JOBS"
