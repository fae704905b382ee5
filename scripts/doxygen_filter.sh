#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Doxygen INPUT_FILTER for the public headers. Keeps the line count, so line
# numbers in warnings stay right.
# - In `///` comment lines, writes a template argument list such as
#   `Solver<S>` as `Solver\<S\>`, so that Doxygen does not read `<S>` as the
#   HTML strike-through tag. Left as written: @code ... @endcode blocks and
#   `backtick` code spans (Doxygen prints those verbatim, so an escape there
#   would show).
# - Blanks explicit instantiation declarations (`extern template ...;`, up to
#   the `;`): they repeat a documented template for float and double, and
#   would otherwise be listed, undocumented, beside it.
# Other files (README.md) pass unchanged.
case "$1" in
  *.h) ;;
  *) exec cat "$1" ;;
esac
exec perl -ne '
  if ($ext) { $ext = 0 if /;/; print "\n"; next }
  if (/^\s*extern\s+template\b/) { $ext = 1 unless /;/; print "\n"; next }
  if (m{^\s*///}) {
    if ($code) { $code = 0 if m{[@\\]endcode}; print; next }
    if (m{[@\\]code}) { $code = 1 unless m{[@\\]endcode}; print; next }
    my @parts = split /(`[^`]*`)/, $_, -1;
    for (@parts) { s/<([A-Za-z_][A-Za-z0-9_]*)>/\\<$1\\>/g unless /^`/ }
    print join("", @parts);
  } else { print }
' "$1"
