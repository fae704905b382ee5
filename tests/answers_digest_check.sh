#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# The ctest answers_digest (issue 20): tricyl-answers-digest's digests equal
# the checked-in ones in tests/answers_digest.expected.
#   answers            every query's answer (52,500 queries, all kinds): one
#                      value for every compiler, platform and prologue;
#   intervals          the bits of the segment and line interval ends: also
#                      one value everywhere (every stage that computes an
#                      end is IEEE double arithmetic, with TwoProduct exact
#                      with or without FMA; no long double); every end is
#                      within 1.9e-15 max(1, |s*|) of the exact one, and
#                      scripts/test.sh also checks that across the builds
#                      (tricyl-answers-digest --compare).
# On x86-64 with AVX2 it also runs the SSE2 prologue (TRICYL_SCALAR_BASELINE)
# and, if given, the portable one (a second executable linked with
# tricyl_portable_prologue): all must print the same digests.
# Usage: answers_digest_check.sh EXPECTED DIGEST_EXE [PORTABLE_EXE]
# TRICYL_RUN: a prefix for running the executables (an emulator).
set -euo pipefail
expected=$1
exe=$2
portable=${3:-}
run=(${TRICYL_RUN:-})

digests() {  # the digest lines of one run
  grep -E '^(queries|answers|intervals) ' <<<"$1"
}
out=$("${run[@]}" "$exe")
echo "$out"
mine=$(digests "$out")
status=0
while read -r key value; do
  want=$(awk -v k="$key" '$1 == k { print $2 }' "$expected")
  if [ -z "$want" ]; then
    echo "FAIL: no '$key' in $expected (this build: $value)"
    status=1
  elif [ "$want" != "$value" ]; then
    echo "FAIL: $key $value, expected $want"
    status=1
  else
    echo "ok: $key $value"
  fi
done <<<"$mine"

same() {  # $1: label, $2: output of another run
  local theirs
  theirs=$(digests "$2")
  if [ "$theirs" != "$mine" ]; then
    echo "FAIL: the $1 prologue's digests differ:"
    echo "$theirs"
    status=1
  else
    echo "ok: the $1 prologue gives the same digests"
  fi
}
if grep -qw avx2 /proc/cpuinfo 2>/dev/null && [ ${#run[@]} -eq 0 ]; then
  same SSE2 "$(TRICYL_SCALAR_BASELINE=1 "$exe")"
fi
if [ -n "$portable" ]; then
  same portable "$("${run[@]}" "$portable")"
fi
exit $status
