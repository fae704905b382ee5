#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the build tree $1 to a temporary prefix, then, against it:
#   1. a kernel-only consumer on a "machine without FCL": examples/consumer
#      configured with -DCMAKE_DISABLE_FIND_PACKAGE_fcl=ON, so that
#      find_package(fcl) finds nothing. find_package(tricyl REQUIRED) must
#      still succeed (the core needs GMP only), tricyl::fcl must be absent,
#      and the consumer (intersect and estimateContact) must build, link and
#      print what it should. Asking for COMPONENTS fcl there must fail.
#   2. with FCL: find_package(tricyl REQUIRED COMPONENTS fcl) (when the build
#      tree built tricyl_fcl), the double and the float FCL consumers (the
#      float one uses tricyl::collide and tricyl::Solver<float>); each run and
#      its output checked;
#   3. the kernel consumer compiled with pkg-config (tricyl.pc) alone.
set -euo pipefail
build=$1
root="$(cd "$(dirname "$0")/.." && pwd)"
src="$root/examples/consumer"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cmake --install "$build" --prefix "$tmp/prefix" >/dev/null

check() {  # check <expected file> <command...>
  local expected=$1
  shift
  "$@" >"$tmp/out.txt"
  diff -u "$expected" "$tmp/out.txt"
}

# 1. Kernel only, FCL unfindable.
cmake -S "$src" -B "$tmp/core" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_DISABLE_FIND_PACKAGE_fcl=ON >"$tmp/core.log"
grep -q "tricyl::fcl FALSE" "$tmp/core.log" || {
  echo "FCL disabled, yet the package defined tricyl::fcl" >&2
  cat "$tmp/core.log" >&2
  exit 1
}
cmake --build "$tmp/core" >/dev/null
if [ -e "$tmp/core/consumer_fcl" ]; then
  echo "consumer_fcl was built although FCL was disabled" >&2
  exit 1
fi
check "$src/expected.txt" "$tmp/core/consumer"
echo "consumer: the core alone (intersect, estimateContact) with FCL unfindable (-DCMAKE_DISABLE_FIND_PACKAGE_fcl=ON), output as expected"
if cmake -S "$src" -B "$tmp/core_req" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
  -DCMAKE_DISABLE_FIND_PACKAGE_fcl=ON -DCONSUMER_REQUIRE_FCL=ON \
  >"$tmp/core_req.log" 2>&1; then
  echo "find_package(tricyl COMPONENTS fcl) succeeded with FCL unfindable" >&2
  exit 1
fi
grep -q "component fcl (tricyl::fcl) unavailable" "$tmp/core_req.log" || {
  echo "COMPONENTS fcl failed without saying why:" >&2
  cat "$tmp/core_req.log" >&2
  exit 1
}
echo "find_package(tricyl REQUIRED COMPONENTS fcl) with FCL unfindable: fails, saying why"

# 2. With FCL: the fcl component, double and float.
if [ -n "$(find "$tmp/prefix" -name tricylFclTargets.cmake)" ]; then
  cmake -S "$src" -B "$tmp/fcl" -DCMAKE_PREFIX_PATH="$tmp/prefix" \
    -DCONSUMER_REQUIRE_FCL=ON >/dev/null
  cmake --build "$tmp/fcl" >/dev/null
  check "$src/expected.txt" "$tmp/fcl/consumer"
  check "$src/expected_fcl.txt" "$tmp/fcl/consumer_fcl"
  echo "consumer_fcl: find_package(tricyl REQUIRED COMPONENTS fcl), tricyl::collide, output as expected"
  check "$src/expected_float.txt" "$tmp/fcl/consumer_float"
  echo "consumer_float: tricyl::collide and tricyl::Solver<float> on float objects, output as expected"
elif [ -n "$(find "$build" -name 'libtricyl_fcl*' | head -1)" ]; then
  echo "the build tree has tricyl_fcl but the package does not export tricyl::fcl" >&2
  exit 1
fi

# 3. pkg-config.
pc=$(dirname "$(find "$tmp/prefix" -name tricyl.pc | head -1)")
export PKG_CONFIG_PATH="$pc${PKG_CONFIG_PATH:+:$PKG_CONFIG_PATH}"
# shellcheck disable=SC2046
${CXX:-c++} -std=c++17 "$src/main.cpp" -o "$tmp/consumer_pc" \
  $(pkg-config --cflags --libs tricyl)
check "$src/expected.txt" "$tmp/consumer_pc"
echo "consumer: built with pkg-config tricyl (version $(pkg-config --modversion tricyl)), output as expected"
