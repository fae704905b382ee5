#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Installs the Debian packages tricyl builds, tests and compares with.
# Idempotent: does nothing when they are all present. Needs root (or sudo).
# Usage: bash scripts/deps.sh [--cross]
#   --cross  also what CI's AArch64 stage needs (scripts/test.sh): the cross
#            compiler, qemu-user-static, and the arm64 multiarch -dev
#            packages of the kernel's and its tests' dependencies (GMP,
#            GoogleTest, tinyobjloader), which
#            install beside the amd64 ones (it adds the arm64 architecture
#            to dpkg). FCL is not needed there (libfcl-dev:arm64 conflicts
#            with the amd64 one).
set -euo pipefail
PKGS=(build-essential cmake libgmp-dev libfcl-dev libccd-dev libeigen3-dev
      libgtest-dev libbenchmark-dev libmpfr-dev libboost-dev libcli11-dev nlohmann-json3-dev gnuplot-nox
      clang-14 libclang-rt-14-dev libfuzzer-14-dev doxygen libtinyobjloader-dev
      # optional (examples/ompl_planner, its test, bench_planning): OMPL, and
      # the Boost libraries its CMake config links but does not pull in
      libompl-dev libboost-serialization-dev libboost-filesystem-dev
      libboost-system-dev)
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
if [ "${1:-}" = "--cross" ]; then
  PKGS+=(g++-aarch64-linux-gnu qemu-user-static libgmp-dev:arm64
         libgtest-dev:arm64 libtinyobjloader-dev:arm64)
  if ! dpkg --print-foreign-architectures | grep -qx arm64; then
    $SUDO dpkg --add-architecture arm64
    $SUDO apt-get update -qq
  fi
fi
missing=()
native=$(dpkg --print-architecture)
for p in "${PKGS[@]}"; do
  # A package installed for two architectures needs its architecture named.
  dpkg -s "$p" >/dev/null 2>&1 || dpkg -s "$p:$native" >/dev/null 2>&1 ||
    missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
echo "tricyl: installing ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
