#!/usr/bin/env bash
# The comparison harness from scratch: packages, Release build with
# tricyl-compare, and a default run writing report/ (report.md, results.csv,
# results.json, stability.csv, hangs.txt, error_vs_time.png, stability_*.png).
# Usage: bash scripts/compare.sh [extra tricyl-compare options]
#        (from anywhere; the report lands in <repo>/report)
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
JOBS=$(nproc)
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DTRICYL_BUILD_COMPARE=ON
cmake --build build/release -j "$JOBS" --target tricyl-compare
./build/release/compare/tricyl-compare --out report "$@"
