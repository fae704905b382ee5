#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The comparison harness from scratch: packages, Release build with
# tricyl-compare, and a default run writing report/ (report.md, results.csv,
# results.json, stability.csv, hangs.txt, worst_cases.txt, error_vs_time*.png,
# stability_*.png; compare/README.md explains every column).
# Usage: bash scripts/compare.sh [extra tricyl-compare options]
#        (from anywhere; the report lands in <repo>/report)
# The mesh families use the built-in meshes, plus env.obj, bunny.obj and
# rob.obj from ../shared/data/meshes when that folder is there.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
JOBS=$(nproc)
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DTRICYL_BUILD_COMPARE=ON
cmake --build build/release -j "$JOBS" --target tricyl-compare
MESH_DIR=../shared/data/meshes
MESHES=()
if [ -f "$MESH_DIR/env.obj" ] && [ -f "$MESH_DIR/bunny.obj" ] && [ -f "$MESH_DIR/rob.obj" ]; then
  MESHES=(--mesh builtin --mesh "$MESH_DIR/env.obj" --mesh "$MESH_DIR/bunny.obj"
          --mesh "$MESH_DIR/rob.obj")
fi
./build/release/compare/tricyl-compare --out report "${MESHES[@]}" "$@"
