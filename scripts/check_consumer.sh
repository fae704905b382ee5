#!/usr/bin/env bash
# Installs the build tree $1 to a temporary prefix, builds examples/consumer
# against it with find_package(tricyl CONFIG), runs it and checks its output.
set -euo pipefail
build=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null
cmake -S "$root/examples/consumer" -B "$tmp/build" -DCMAKE_PREFIX_PATH="$tmp/prefix" >/dev/null
cmake --build "$tmp/build" >/dev/null
"$tmp/build/consumer" > "$tmp/out.txt"
diff -u "$root/examples/consumer/expected.txt" "$tmp/out.txt"
echo "consumer: built against the installed package, output as expected"
