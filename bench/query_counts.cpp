// SPDX-License-Identifier: BSD-3-Clause
// tricyl-query-counts: the public intersect of the sphere, segment or line
// query on the 4096 cases of one family of bench_queries (compare/
// query_scenes.h, seed 20261122), in bench_queries' visiting order
// (bench/walk.h), for a number of passes. Meant for callgrind and perf,
// whose instruction and branch counts are the A/B metric that a loaded
// machine does not blur (timings: bench_queries):
//
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null
//     --toggle-collect='tricyl::intersect*' ./build/bench/tricyl-query-counts
//     segment near 3                                         (one line)
//
// and divide the total by the queries printed. Arguments: sphere | segment
// | line, uniform | near | far | degenerate, [passes] (default 3).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "query_cases.h"
#include "query_scenes.h"
#include "tricyl/line_cylinder.h"
#include "tricyl/tricyl.h"
#include "walk.h"

int main(int argc, char** argv) {
  using tricyl::qscenes::Family;
  using tricyl::qscenes::Query;
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: %s sphere|segment|line uniform|near|far|degenerate "
                 "[passes]\n",
                 argv[0]);
    return 2;
  }
  const char* qn = argv[1];
  const Query q = !std::strcmp(qn, "sphere")    ? Query::kSphere
                  : !std::strcmp(qn, "segment") ? Query::kSegment
                  : !std::strcmp(qn, "line")    ? Query::kLine
                                                : Query::kPointCylinder;
  if (q == Query::kPointCylinder) {
    std::fprintf(stderr, "unknown query %s\n", qn);
    return 2;
  }
  int fam = -1;
  for (Family f : tricyl::qscenes::kAllFamilies)
    if (!std::strcmp(argv[2], tricyl::qscenes::familyName(f))) fam = int(f);
  if (fam < 0) {
    std::fprintf(stderr, "unknown family %s\n", argv[2]);
    return 2;
  }
  const int passes = argc > 3 ? std::max(1, std::atoi(argv[3])) : 3;
  const std::vector<tricyl::qscenes::QueryCase> cs =
      tricyl::bench::queryCases(q, Family(fam));
  tricyl::bench::Walk walk(cs.size());
  long hits = 0, n = 0;
  for (int pass = 0; pass < passes; ++pass)
    for (std::size_t k = 0; k < cs.size(); ++k, ++n) {
      const auto& c = cs[walk.next()];
      switch (q) {
        case Query::kSphere:
          hits += tricyl::intersect(c.cyl, c.pose,
                                    tricyl::Sphere<double>{c.p, c.rho});
          break;
        case Query::kSegment:
          hits += tricyl::intersect(c.cyl, c.pose,
                                    tricyl::Segment<double>{c.p, c.q});
          break;
        default:
          hits +=
              tricyl::intersect(c.cyl, c.pose, tricyl::Line<double>{c.p, c.q});
      }
    }
  std::printf("%s %s: %ld queries, %ld hits\n", qn, argv[2], n, hits);
  return 0;
}
