// SPDX-License-Identifier: BSD-3-Clause
// tricyl-distance-counts: tricyl::tryDistance on the 4096 cases of one
// triangle family of bench_distance (seed 7, bench/family_cases.h), in
// bench_distance's visiting order (bench/walk.h), for a number of passes.
// Meant for callgrind and perf, whose instruction and branch counts are the
// A/B metric that a loaded machine does not blur (timings: bench_distance):
//
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null
//     --toggle-collect='*distanceAny*' ./build/rel/bench/tricyl-distance-counts
//     thin 1                                                 (one line)
//
// and divide the total by the queries printed. Arguments: uniform | near |
// far | thin | sliver | aligned, [passes] (default 3).
//
// tricyl-distance-paths is the same driver compiled with
// TRICYL_DIST_COUNT_PATHS: it includes src/triangle_cylinder_distance.cpp
// with TRICYL_DIST_PATH counting which step answered each query (the
// numbers of that file's TRICYL_DIST_PATH calls) and prints the counts;
// a third argument k then runs, in the measured passes (measuredQuery),
// only the cases that step k answered (classified in a first pass).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "family_cases.h"
#include "scenes.h"
#include "tricyl/tricyl.h"
#include "walk.h"

#ifdef TRICYL_DIST_COUNT_PATHS
static long g_path[24];
static int g_last = 0;  // the last step other than 10 (the Boolean's call)
#define TRICYL_DIST_PATH(k) (++g_path[k], g_last = (k) == 10 ? g_last : (k))
#include "../src/triangle_cylinder_distance.cpp"
#endif

// One query, out of line so that callgrind can collect it alone
// (--toggle-collect='*measuredQuery*').
__attribute__((noinline)) tricyl::Answer measuredQuery(
    const tricyl::scenes::TriCase& c, tricyl::DistanceResult<double>* r) {
  return tricyl::tryDistance(c.cyl, c.pose, c.tri, r);
}

int main(int argc, char** argv) {
  using tricyl::scenes::Family;
  if (argc < 2) {
    std::fprintf(stderr, "usage: %s family [passes]\n", argv[0]);
    return 2;
  }
  int fam = -1;
  for (int f = 0; f < 6; ++f)
    if (!std::strcmp(argv[1], tricyl::scenes::kFamilyNames[f])) fam = f;
  if (fam < 0) {
    std::fprintf(stderr, "unknown family %s\n", argv[1]);
    return 2;
  }
  const int passes = argc > 2 ? std::atoi(argv[2]) : 3;
  const auto& k = tricyl::bench::familyCases(Family(fam));
  std::vector<char> run(k.size(), 1);
#ifdef TRICYL_DIST_COUNT_PATHS
  if (argc > 3) {
    const int want = std::atoi(argv[3]);
    for (std::size_t n = 0; n < k.size(); ++n) {
      tricyl::DistanceResult<double> r;
      tricyl::tryDistance(k[n].cyl, k[n].pose, k[n].tri, &r);
      run[n] = g_last == want;
    }
    for (long& x : g_path) x = 0;
  }
#endif
  tricyl::bench::Walk walk(k.size());
  double sink = 0;
  long queries = 0, zero = 0;
  for (int p = 0; p < passes; ++p)
    for (std::size_t n = 0; n < k.size(); ++n) {
      const std::size_t i = walk.next();
      if (!run[i]) continue;
      const auto& c = k[i];
      tricyl::DistanceResult<double> r;
      if (measuredQuery(c, &r) == tricyl::Answer::kIntersect) ++zero;
      sink += r.distance;
      ++queries;
    }
  std::printf("%s: %ld queries (%ld intersecting), checksum %.17g\n", argv[1],
              queries, zero, sink);
#ifdef TRICYL_DIST_COUNT_PATHS
  for (int i = 0; i < 24; ++i)
    if (g_path[i]) std::printf("  path %d: %ld\n", i, g_path[i]);
#endif
  return 0;
}
