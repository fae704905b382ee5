#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Builds the libFuzzer targets with clang-14 (ASan + UBSan + coverage) in
# $FUZZ_BUILD_DIR (default build/fuzz) and runs each for the given time on
# its seed corpus.
# Usage: bash scripts/fuzz.sh [seconds per target, default 30]
#   FUZZ_BUILD_DIR  build directory (default build/fuzz)
#   FUZZ_JOBS       build parallelism (default 2)
#   FUZZ_ARGS       extra libFuzzer flags, e.g. "-runs=10000000"
#   FUZZ_TARGETS    space-separated subset of targets (default: every
#                   fuzz/fuzz_*.cpp), e.g. "fuzz_point_cone"
# New inputs go to $FUZZ_BUILD_DIR/corpus/<query>/ (the checked-in seeds in
# fuzz/corpus/ are read, never written); a crash or property violation
# leaves crash-* / leak-* files in $FUZZ_BUILD_DIR/artifacts/ and fails the
# script.
set -euo pipefail
cd "$(dirname "$0")/.."
SECONDS_PER_TARGET=${1:-30}
B=${FUZZ_BUILD_DIR:-build/fuzz}
JOBS=${FUZZ_JOBS:-2}
CXX_BIN=$(command -v clang++-14 || command -v clang++ || true)
if [ -z "$CXX_BIN" ]; then
  echo "fuzz.sh: clang++-14 not found (Debian: clang-14 libfuzzer-14-dev libclang-rt-14-dev)" >&2
  exit 1
fi
cmake -S . -B "$B" -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_COMPILER="$CXX_BIN" -DTRICYL_BUILD_FUZZ=ON \
  -DTRICYL_BUILD_TESTS=OFF -DTRICYL_BUILD_BENCH=OFF -DTRICYL_BUILD_COMPARE=OFF \
  -DTRICYL_WITH_FCL=OFF -DTRICYL_INSTALL=OFF -DTRICYL_BUILD_EXAMPLES=OFF >/dev/null
cmake --build "$B" -j "$JOBS"
mkdir -p "$B/artifacts"
status=0
targets=${FUZZ_TARGETS:-$(for src in fuzz/fuzz_*.cpp; do basename "$src" .cpp; done)}
for target in $targets; do
  query=${target#fuzz_}
  mkdir -p "$B/corpus/$query"
  echo "== $target: ${SECONDS_PER_TARGET} s"
  # shellcheck disable=SC2086
  if ! ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
       UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
       "$B/fuzz/$target" -max_total_time="$SECONDS_PER_TARGET" \
       -max_len=512 -timeout=10 -print_final_stats=1 \
       -artifact_prefix="$B/artifacts/${target}-" ${FUZZ_ARGS:-} \
       "$B/corpus/$query" "fuzz/corpus/$query" 2>&1 |
       tee "$B/$target.log" | grep -E '^(#[0-9]+ +(INITED|DONE)|stat::number_of_executed_units|tricyl fuzz|==[0-9]+==ERROR|SUMMARY|.*runtime error)'; then
    :
  fi
  if ! grep -q 'Done [0-9]* runs' "$B/$target.log" ||
     grep -qE 'PROPERTY VIOLATED|ERROR: (AddressSanitizer|libFuzzer|UndefinedBehavior)|runtime error' "$B/$target.log"; then
    echo "fuzz.sh: $target FAILED (log: $B/$target.log)" >&2
    status=1
  fi
done
exit $status
