# SPDX-License-Identifier: BSD-3-Clause
# Cross-compiling tricyl's core (kernel and tests, no FCL) for AArch64 Linux
# with Debian's g++-aarch64-linux-gnu and the arm64 multiarch -dev packages
# (libgmp-dev:arm64, libgtest-dev:arm64; scripts/deps.sh --arm64), run under
# qemu-user-static (issue 20; scripts/test.sh). Usage:
#   cmake -S . -B build/aarch64 \
#     -DCMAKE_TOOLCHAIN_FILE=cmake/aarch64-linux-gnu.cmake -DTRICYL_WITH_FCL=OFF
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(CMAKE_C_COMPILER aarch64-linux-gnu-gcc)
set(CMAKE_CXX_COMPILER aarch64-linux-gnu-g++)
# Multiarch: libraries in /usr/lib/aarch64-linux-gnu, arch-specific headers
# (gmp.h) in /usr/include/aarch64-linux-gnu; never the amd64 ones.
set(CMAKE_LIBRARY_ARCHITECTURE aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH /usr/aarch64-linux-gnu)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
# ctest and gtest_discover_tests run the test executables through qemu; the
# loader and libc come from the cross toolchain's sysroot, the multiarch
# libraries (libgmp, libgtest) from /usr/lib/aarch64-linux-gnu.
find_program(TRICYL_QEMU_AARCH64 qemu-aarch64-static REQUIRED)
set(CMAKE_CROSSCOMPILING_EMULATOR ${TRICYL_QEMU_AARCH64} -L /usr/aarch64-linux-gnu)
