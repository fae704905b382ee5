# SPDX-License-Identifier: BSD-3-Clause
# tricyl::fcl: the FCL 0.7 narrow-phase solver (include/tricyl/fcl_solver.h).
# Included from src/CMakeLists.txt when FCL was found (TRICYL_HAVE_FCL).
# fcl_solver.cpp and fcl_solver_float.cpp hold FCL's collision/distance
# matrices for tricyl::Solver<double> and <float>, fcl_stock_float.cpp FCL's
# own float collide (each 30 to 60 s and 0.8 to 1.4 GB to compile, once).
add_library(tricyl_fcl
  ${CMAKE_CURRENT_LIST_DIR}/fcl_solver.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fcl_solver_float.cpp
  ${CMAKE_CURRENT_LIST_DIR}/fcl_stock_float.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_collide.cpp
  ${CMAKE_CURRENT_LIST_DIR}/mesh_distance.cpp
)
add_library(tricyl::fcl ALIAS tricyl_fcl)
target_compile_features(tricyl_fcl PUBLIC cxx_std_17)
target_link_libraries(tricyl_fcl PUBLIC tricyl fcl)
set_target_properties(tricyl_fcl PROPERTIES POSITION_INDEPENDENT_CODE ON)
tricyl_set_warnings(tricyl_fcl)
tricyl_set_fp_flags(tricyl_fcl)
set_target_properties(tricyl_fcl PROPERTIES EXPORT_NAME fcl)

# Installed as tricyl::fcl in its own export set, which tricylConfig.cmake
# loads (after find_dependency(fcl)) when it exists.
if(TRICYL_INSTALL)
  include(GNUInstallDirs)
  install(TARGETS tricyl_fcl EXPORT tricylFclTargets
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
    INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
  install(EXPORT tricylFclTargets NAMESPACE tricyl::
          DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/tricyl)
endif()
