#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Runs an example and compares its standard output with the expected file.
# Usage: check_example.sh <expected.txt> <executable> [args...]
# Exit 77 (ctest: skipped) when the example itself exits 77 (a missing
# optional input file).
set -uo pipefail
expected=$1
shift
out=$(mktemp)
trap 'rm -f "$out"' EXIT
"$@" >"$out"
rc=$?
if [ $rc -eq 77 ]; then exit 77; fi
if [ $rc -ne 0 ]; then
  echo "example failed with exit code $rc: $*" >&2
  cat "$out"
  exit 1
fi
diff -u "$expected" "$out"
