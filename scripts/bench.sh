#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs every Google Benchmark suite of tricyl in one Release build and writes
# bench/results/<machine>.json: one object per suite, each the suite's own
# --benchmark_format=json output (context + benchmarks). See
# bench/results/README.md for how to read it.
# Usage: bash scripts/bench.sh [machine-name] [min-time-seconds]
#   machine-name  default: <cpu model>-<cores>core, lower case, dashes
#   min-time      per benchmark, default 0.2
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/deps.sh
cpu=$(grep -m1 'model name' /proc/cpuinfo | cut -d: -f2 | xargs | tr 'A-Z ' 'a-z-' | tr -cd 'a-z0-9-')
MACHINE=${1:-${cpu}-$(nproc)core}
MIN_TIME=${2:-0.2}
cmake -S . -B build/release -DCMAKE_BUILD_TYPE=Release -DTRICYL_BUILD_BENCH=ON >/dev/null
cmake --build build/release -j "$(nproc)"
mkdir -p bench/results build/bench-json
suites=()
for b in bench_triangle_cylinder bench_queries bench_mesh_cylinder bench_fcl_collide bench_margin; do
  exe=build/release/bench/$b
  [ -x "$exe" ] || continue
  echo "== $b" >&2
  extra=()
  # The scalar suite compares ~20 ns against ~300 ns on a VM whose speed
  # drifts by tens of percent within a minute: its rows run as 9
  # repetitions in random interleaving, and the ratio is read from the
  # medians (bench/results/README.md).
  if [ "$b" = bench_triangle_cylinder ] || [ "$b" = bench_margin ]; then
    extra=(--benchmark_repetitions=9 --benchmark_enable_random_interleaving=true)
  fi
  "$exe" --benchmark_min_time="$MIN_TIME" --benchmark_out="build/bench-json/$b.json" \
    --benchmark_out_format=json "${extra[@]}" >&2
  suites+=("$b")
done
python3 - "bench/results/$MACHINE.json" "${suites[@]}" <<'PY'
import json, sys
out, names = sys.argv[1], sys.argv[2:]
merged = {n: json.load(open(f"build/bench-json/{n}.json")) for n in names}
json.dump(merged, open(out, "w"), indent=1)
print(out)
PY
