# SPDX-License-Identifier: BSD-3-Clause
# FindMPFR: the MPFR library (Debian: libmpfr-dev), for the distance oracle
# (support/distance_oracle.*, tests and tricyl-compare only; the library
# tricyl::tricyl does not need it). Defines MPFR::mpfr and MPFR_FOUND.
find_path(MPFR_INCLUDE_DIR NAMES mpfr.h)
find_library(MPFR_LIBRARY NAMES mpfr)
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MPFR REQUIRED_VARS MPFR_INCLUDE_DIR MPFR_LIBRARY)
if(MPFR_FOUND AND NOT TARGET MPFR::mpfr)
  add_library(MPFR::mpfr UNKNOWN IMPORTED)
  set_target_properties(MPFR::mpfr PROPERTIES IMPORTED_LOCATION "${MPFR_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${MPFR_INCLUDE_DIR}"
    INTERFACE_LINK_LIBRARIES GMP::gmp)
endif()
mark_as_advanced(MPFR_INCLUDE_DIR MPFR_LIBRARY)
