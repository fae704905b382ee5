#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Generates the API reference from the public headers' comments, with
# README.md as the main page and docs/ as related pages (Doxyfile), into
# <outdir>/html (default build/docs) and fails on any Doxygen warning
# (WARN_AS_ERROR, and the warning log must be empty). EXTRACT_ALL is off, so
# an undocumented public name is a warning.
# Exit 77 (ctest: skipped) when doxygen is not installed.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
out=$(realpath -m "${1:-$root/build/docs}")
if ! command -v doxygen >/dev/null; then
  echo "doxygen not installed: API reference skipped" >&2
  exit 77
fi
mkdir -p "$out"
log="$out/doxygen-warnings.log"
rm -f "$log"
cd "$root"
status=0
{ cat Doxyfile; echo "OUTPUT_DIRECTORY = $out"; echo "WARN_LOGFILE = $log"; } |
  doxygen - >/dev/null || status=$?
# WARN_AS_ERROR = FAIL_ON_WARNINGS makes doxygen exit non-zero on a warning;
# the log is checked as well, and printed either way.
if [ "$status" -ne 0 ] || [ -s "$log" ]; then
  echo "doxygen warnings:" >&2
  cat "$log" >&2
  exit 1
fi
echo "API reference: $out/html/index.html (doxygen $(doxygen --version), no warnings)"
