#!/usr/bin/env bash
# Installs the Debian packages tricyl builds, tests and compares with.
# Idempotent: does nothing when they are all present. Needs root (or sudo).
set -euo pipefail
PKGS=(build-essential cmake libgmp-dev libfcl-dev libccd-dev libeigen3-dev
      libgtest-dev libbenchmark-dev libcli11-dev nlohmann-json3-dev gnuplot-nox
      clang-14 libclang-rt-14-dev libfuzzer-14-dev doxygen libtinyobjloader-dev)
missing=()
for p in "${PKGS[@]}"; do
  dpkg -s "$p" >/dev/null 2>&1 || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then exit 0; fi
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
echo "tricyl: installing ${missing[*]}" >&2
$SUDO apt-get update -qq
DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}"
