#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The whole test suite from scratch: packages, then
#   1. a Release build with everything (FCL solver, harness, benchmarks) and
#      ctest (including a one-iteration smoke run of every benchmark, and
#      answers_digest: the answers of 52,500 fixed queries pinned to
#      tests/answers_digest.expected with the AVX2, SSE2 and portable
#      triangle prologues);
#   2. the core library and its tests again under AddressSanitizer +
#      UndefinedBehaviorSanitizer (-fno-sanitize-recover=all);
#   3. ThreadSanitizer (clang-14): tests/solver_threads_test.cpp, one shared
#      tricyl::Solver hammered from 4 threads (FCL itself is not
#      instrumented; tests/tsan.supp lists FCL-only suppressions, if any);
#   4. the same answers on every compiler and platform (issue 20; each
#      build's tricyl-answers-digest is compared with step 1's, answers bit
#      for bit, interval ends within the documented bound):
#      a. the test suite built with clang-14 (FP traps on, as everywhere);
#      b. the core tests with long double = double (-mlong-double-64; no
#         test may call libm's or libstdc++'s long double functions across
#         that ABI change: checked on the symbols);
#      c. the core tests cross-built for AArch64 (g++-aarch64-linux-gnu, the
#         arm64 multiarch GMP and GoogleTest) and run under qemu-user-static,
#         the oracle families (Families/*) with TRICYL_CASES_SCALE=
#         $TRICYL_EMULATED_SCALE (default 0.25); no threaded test there
#         (those need FCL, and run natively in steps 1 and 4a);
#   5. a short libFuzzer run (scripts/fuzz.sh, TRICYL_FUZZ_SECONDS per
#      target, default 20) on the checked-in seed corpus.
# Usage: bash scripts/test.sh        (from anywhere; as root or with sudo)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh --cross
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

# Every configuration below builds and runs tricyl-answers-digest and
# compares it with this dump of the Release build's.
REF_DUMP=$PWD/build/release/answers.txt
build/release/tests/tricyl-answers-digest --dump "$REF_DUMP" >/dev/null
CORE=(-DCMAKE_BUILD_TYPE=Release -DTRICYL_WITH_FCL=OFF -DTRICYL_BUILD_COMPARE=OFF
      -DTRICYL_BUILD_BENCH=OFF -DTRICYL_BUILD_EXAMPLES=OFF -DTRICYL_INSTALL=OFF)

echo "== clang-14: the test suite (FP traps on)"
cmake -S . -B build/clang -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_COMPILER=clang++-14 \
  -DTRICYL_BUILD_BENCH=OFF
cmake --build build/clang -j "$JOBS"
ctest --test-dir build/clang --output-on-failure -j "$JOBS"
build/clang/tests/tricyl-answers-digest --compare "$REF_DUMP"

echo "== long double = double (-mlong-double-64): the core tests"
cmake -S . -B build/ld64 "${CORE[@]}" -DCMAKE_CXX_FLAGS=-mlong-double-64
cmake --build build/ld64 -j "$JOBS"
# Nothing may call a long double function of libm (sqrtl, frexpl, ...) or
# libstdc++ (operator<< on long double, ...): those take the 80-bit format.
libm_l=$(nm -D --defined-only "$(gcc -print-file-name=libm.so.6)" | awk '{print $3}' |
         sed 's/@.*//' | sort -u)
bad=""
for exe in build/ld64/tests/*_test build/ld64/tests/tricyl-answers-digest; do
  while read -r sym; do
    sym=${sym%%@*}
    if [[ $sym == *l ]] && grep -qx "$sym" <<<"$libm_l" &&
       grep -qx "${sym%l}" <<<"$libm_l"; then
      bad+=" $(basename "$exe"):$sym"
    fi
  done < <(nm -u "$exe" | awk '{print $2}')
  demangled=$(nm -uC "$exe")
  if grep -q 'long double' <<<"$demangled"; then
    bad+=" $(basename "$exe"):$(grep -m1 'long double' <<<"$demangled" | xargs)"
  fi
done
if [ -n "$bad" ]; then
  echo "tricyl: long double functions called across -mlong-double-64:$bad" >&2
  exit 1
fi
ctest --test-dir build/ld64 --output-on-failure -j "$JOBS"
build/ld64/tests/tricyl-answers-digest --compare "$REF_DUMP"

echo "== AArch64 (cross-built, qemu-user-static): the core tests"
cmake -S . -B build/aarch64 "${CORE[@]}" \
  -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake
cmake --build build/aarch64 -j "$JOBS"
# The oracle families (triangle, segment, line, ...) take minutes each
# emulated (software quad long double, GMP; 54 of the 60 minutes of CPU of
# the full emulated run): a quarter of their cases, every family kept.
SLOW='^Families/'
ctest --test-dir build/aarch64 --output-on-failure -j "$JOBS" -E "$SLOW|^SolverThreads\."
TRICYL_CASES_SCALE=${TRICYL_EMULATED_SCALE:-0.25} \
  ctest --test-dir build/aarch64 --output-on-failure -j "$JOBS" -R "$SLOW"
qemu-aarch64-static -L /usr/aarch64-linux-gnu build/aarch64/tests/tricyl-answers-digest \
  --compare "$REF_DUMP"

echo "== libFuzzer (short run; the long local run is in the README)"
FUZZ_JOBS="$JOBS" bash scripts/fuzz.sh "${TRICYL_FUZZ_SECONDS:-20}"
