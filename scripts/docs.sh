#!/usr/bin/env bash
# Generates the API reference from the public headers' comments (Doxyfile)
# into <outdir>/html (default build/docs) and fails on any Doxygen warning
# (WARN_AS_ERROR, and the warning log must be empty).
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
{ cat Doxyfile; echo "OUTPUT_DIRECTORY = $out"; echo "WARN_LOGFILE = $log"; } |
  doxygen - >/dev/null
if [ -s "$log" ]; then
  echo "doxygen warnings:" >&2
  cat "$log" >&2
  exit 1
fi
echo "API reference: $out/html/index.html (doxygen $(doxygen --version), no warnings)"
