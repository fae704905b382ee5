# SPDX-License-Identifier: BSD-3-Clause
# bench_fcl_collide: end-to-end collide, tricyl::Solver vs the stock
# GJKSolver_libccd (included from bench/CMakeLists.txt when FCL was found).
if(TRICYL_HAVE_FCL AND TARGET tricyl_fcl)
  add_executable(bench_fcl_collide ${CMAKE_CURRENT_LIST_DIR}/bench_fcl_collide.cpp)
  target_link_libraries(bench_fcl_collide PRIVATE tricyl::fcl benchmark::benchmark
                                                  tricyl_obj_mesh)
  target_compile_definitions(bench_fcl_collide PRIVATE
    TRICYL_MESH_DIR="${PROJECT_SOURCE_DIR}/../shared/data/meshes")
  tricyl_set_warnings(bench_fcl_collide)
  tricyl_set_fp_flags(bench_fcl_collide)
endif()

# bench_fcl_distance: mesh/cylinder distance (tricyl::distance, fcl::distance
# with tricyl::Solver, stock fcl::distance) and the margin collide, paired.
if(TRICYL_HAVE_FCL AND TARGET tricyl_fcl)
  add_executable(bench_fcl_distance ${CMAKE_CURRENT_LIST_DIR}/bench_fcl_distance.cpp)
  target_link_libraries(bench_fcl_distance PRIVATE tricyl::fcl benchmark::benchmark
                                                   tricyl_obj_mesh)
  target_compile_definitions(bench_fcl_distance PRIVATE
    TRICYL_MESH_DIR="${PROJECT_SOURCE_DIR}/../shared/data/meshes")
  tricyl_set_warnings(bench_fcl_distance)
  tricyl_set_fp_flags(bench_fcl_distance)
endif()

# fcl_walk_counts: one call per pose of the two benchmarks' mesh scenes, for
# callgrind's instruction counts (the A/B metric of the mesh walks).
if(TRICYL_HAVE_FCL AND TARGET tricyl_fcl)
  add_executable(fcl_walk_counts ${CMAKE_CURRENT_LIST_DIR}/fcl_walk_counts.cpp)
  target_link_libraries(fcl_walk_counts PRIVATE tricyl::fcl tricyl_obj_mesh)
  target_compile_definitions(fcl_walk_counts PRIVATE
    TRICYL_MESH_DIR="${PROJECT_SOURCE_DIR}/../shared/data/meshes")
  tricyl_set_warnings(fcl_walk_counts)
  tricyl_set_fp_flags(fcl_walk_counts)
  if(TRICYL_BUILD_TESTS)
    add_test(NAME fcl_walk_counts_smoke COMMAND fcl_walk_counts first rob tricyl)
    set_tests_properties(fcl_walk_counts_smoke PROPERTIES SKIP_RETURN_CODE 77)
  endif()
endif()
