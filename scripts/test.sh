#!/usr/bin/env bash
# The whole test suite from scratch: packages, then
#   1. a Release build with everything (FCL solver, harness, benchmarks) and
#      ctest (including a one-iteration smoke run of every benchmark);
#   2. the core library and its tests again under AddressSanitizer +
#      UndefinedBehaviorSanitizer (-fno-sanitize-recover=all);
#   3. ThreadSanitizer (clang-14): tests/solver_threads_test.cpp, one shared
#      tricyl::Solver hammered from 4 threads (FCL itself is not
#      instrumented; tests/tsan.supp lists FCL-only suppressions, if any);
#   4. a short libFuzzer run (scripts/fuzz.sh, TRICYL_FUZZ_SECONDS per
#      target, default 20) on the checked-in seed corpus.
# Usage: bash scripts/test.sh        (from anywhere; as root or with sudo)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
JOBS=$(nproc)

echo "== Release build and tests"
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DTRICYL_BUILD_BENCH=ON
cmake --build build/release -j "$JOBS"
ctest --test-dir build/release --output-on-failure -j "$JOBS"

echo "== ASan + UBSan build and tests (core library)"
cmake -S . -B build/asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DTRICYL_SANITIZE=ON \
  -DTRICYL_WITH_FCL=OFF -DTRICYL_BUILD_COMPARE=OFF -DTRICYL_BUILD_BENCH=OFF
cmake --build build/asan -j "$JOBS"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build/asan --output-on-failure -j "$JOBS"

echo "== ThreadSanitizer: one shared tricyl::Solver from 4 threads"
cmake -S . -B build/tsan -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER=clang++-14 -DTRICYL_TSAN=ON -DTRICYL_BUILD_COMPARE=OFF \
  -DTRICYL_BUILD_BENCH=OFF -DTRICYL_BUILD_EXAMPLES=OFF -DTRICYL_INSTALL=OFF
cmake --build build/tsan -j "$JOBS" --target solver_threads_test
TSAN_OPTIONS="halt_on_error=1:second_deadlock_stack=1:suppressions=$PWD/tests/tsan.supp" \
  ctest --test-dir build/tsan -R '^SolverThreads\.' --output-on-failure

echo "== libFuzzer (short run; the long local run is in the README)"
FUZZ_JOBS="$JOBS" bash scripts/fuzz.sh "${TRICYL_FUZZ_SECONDS:-20}"
