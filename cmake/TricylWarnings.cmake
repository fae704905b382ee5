# SPDX-License-Identifier: BSD-3-Clause
# tricyl_set_warnings(<target>): the project's warning set, and the
# floating-point flags every exact predicate relies on.
function(tricyl_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  # clang's -Wpedantic flags GoogleTest's TYPED_TEST_SUITE(Suite, Types)
  # (a variadic macro given no variadic argument; valid C++20).
  if(CMAKE_CXX_COMPILER_ID MATCHES "Clang")
    target_compile_options(${target} PRIVATE
                           -Wno-gnu-zero-variadic-macro-arguments)
  endif()
endfunction()

# Flags that the error bounds of src/filter.h depend on: no contraction into
# FMA (keeps results identical across compilers and platforms, and with the
# documented operation count) and no fast-math. -fno-math-errno (nothing in
# tricyl reads errno; the results are unchanged): sqrt is the instruction,
# with no libm fallback call, which for long double would cross the ABI of
# -mlong-double-64 (issue 20; scripts/test.sh checks the symbols).
function(tricyl_set_fp_flags target)
  target_compile_options(${target} PRIVATE -ffp-contract=off -fno-fast-math
                                           -fno-math-errno)
endfunction()
