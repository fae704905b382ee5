# SPDX-License-Identifier: BSD-3-Clause
# bench_queries: the cylinder query family (issue 5) against the
# straightforward formulas of the sources in double. Included from
# bench/CMakeLists.txt.
find_package(benchmark REQUIRED)

add_executable(bench_queries ${CMAKE_CURRENT_LIST_DIR}/bench_queries.cpp)
target_link_libraries(bench_queries PRIVATE tricyl::tricyl benchmark::benchmark_main)
target_include_directories(bench_queries PRIVATE ${PROJECT_SOURCE_DIR}/compare)
tricyl_set_warnings(bench_queries)
tricyl_set_fp_flags(bench_queries)
if(TRICYL_HAVE_FCL)
  target_link_libraries(bench_queries PRIVATE fcl)
  target_compile_definitions(bench_queries PRIVATE TRICYL_BENCH_WITH_FCL=1)
endif()

# tricyl-query-counts: the sphere, segment and line queries of one family in
# bench_queries' order, for callgrind and perf (instruction counts).
add_executable(tricyl-query-counts ${CMAKE_CURRENT_LIST_DIR}/query_counts.cpp)
target_link_libraries(tricyl-query-counts PRIVATE tricyl::tricyl)
target_include_directories(tricyl-query-counts PRIVATE ${PROJECT_SOURCE_DIR}/compare)
tricyl_set_warnings(tricyl-query-counts)
tricyl_set_fp_flags(tricyl-query-counts)
if(TRICYL_BUILD_TESTS)  # a smoke run (it measures nothing): the tool cannot rot
  add_test(NAME tricyl_query_counts_smoke COMMAND tricyl-query-counts line near 1)
endif()
