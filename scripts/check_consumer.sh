#!/usr/bin/env bash
# Installs the build tree $1 to a temporary prefix, then, against it:
#   1. builds examples/consumer with find_package(tricyl CONFIG): the kernel
#      consumer always, the tricyl::fcl consumer when the package has it
#      (required when the build tree built tricyl_fcl); runs both and checks
#      their output;
#   2. compiles the kernel consumer with pkg-config (tricyl.pc) alone.
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
echo "consumer: built against the installed package (find_package), output as expected"

if [ -n "$(find "$tmp/prefix" -name tricylFclTargets.cmake)" ]; then
  test -x "$tmp/build/consumer_fcl" || { echo "tricyl::fcl installed but consumer_fcl not built" >&2; exit 1; }
  "$tmp/build/consumer_fcl" > "$tmp/out_fcl.txt"
  diff -u "$root/examples/consumer/expected_fcl.txt" "$tmp/out_fcl.txt"
  echo "consumer_fcl: tricyl::fcl from the installed package, output as expected"
elif [ -n "$(find "$build" -name 'libtricyl_fcl*' | head -1)" ]; then
  echo "the build tree has tricyl_fcl but the package does not export tricyl::fcl" >&2
  exit 1
fi

pc=$(dirname "$(find "$tmp/prefix" -name tricyl.pc | head -1)")
export PKG_CONFIG_PATH="$pc${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# shellcheck disable=SC2046
${CXX:-c++} -std=c++17 "$root/examples/consumer/main.cpp" -o "$tmp/consumer_pc" \
  $(pkg-config --cflags --libs tricyl)
"$tmp/consumer_pc" > "$tmp/out_pc.txt"
diff -u "$root/examples/consumer/expected.txt" "$tmp/out_pc.txt"
echo "consumer: built with pkg-config tricyl (version $(pkg-config --modversion tricyl)), output as expected"
