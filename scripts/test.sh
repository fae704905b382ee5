#!/usr/bin/env bash
# The whole test suite from scratch: packages, Release build, ctest.
# Usage: bash scripts/test.sh        (from the repository root)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
JOBS=$(nproc)
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DTRICYL_BUILD_BENCH=OFF
cmake --build build/release -j "$JOBS"
ctest --test-dir build/release --output-on-failure -j "$JOBS"
