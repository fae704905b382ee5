#!/usr/bin/env bash
# Doxygen INPUT_FILTER: in `///` comment lines only, writes a template
# argument list such as `Solver<S>` as `Solver\<S\>`, so that Doxygen does not
# read `<S>` as the HTML strike-through tag. Code lines pass unchanged (same
# line count, so line numbers in warnings stay right).
exec sed -E '/^[[:space:]]*\/\/\//s/<([A-Za-z_][A-Za-z0-9_]*)>/\\<\1\\>/g' "$1"
