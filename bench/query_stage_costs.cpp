// SPDX-License-Identifier: BSD-3-Clause
// tricyl-query-stage-costs: the sphere, segment and line queries family by
// family, as decideIntersect sees them: mean per query (whole passes, no
// clock inside the loop), median, p99 and max (queries timed one by one,
// the clock's own cost subtracted), and the share and cost of each stage.
// The sphere beside FCL 0.7's sphereCylinderIntersect (the test fcl::collide
// uses for that pair; tolerance-based) on the same cases in the same run.
// A report, not a test: it asserts nothing.
//
// Per family: 4096 cases of compare/query_scenes.h (seed 20261122, as
// bench_queries), visited in an order the branch predictor cannot learn
// (bench/walk.h).
// Usage: tricyl-query-stage-costs [passes] (default 20); markdown on stdout.
#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "query_cases.h"
#include "query_scenes.h"
#include "stage_report.h"
#include "tricyl/tricyl.h"
#include "walk.h"

#ifdef TRICYL_BENCH_WITH_FCL
#include "fcl_sphere_cases.h"
#endif

namespace {

using tricyl::bench::Clock;
using tricyl::bench::ns;
using tricyl::bench::quantile;
using tricyl::bench::Walk;
using tricyl::qscenes::Family;
using tricyl::qscenes::Query;
using tricyl::qscenes::QueryCase;

constexpr int kCases = tricyl::bench::kQueryCases;

std::vector<QueryCase> cases(Query q, Family f) {
  return tricyl::bench::queryCases(q, f);
}

tricyl::Decision decide(Query q, const QueryCase& c) {
  switch (q) {
    case Query::kSphere:
      return tricyl::decideIntersect(c.cyl, c.pose,
                                     tricyl::Sphere<double>{c.p, c.rho});
    case Query::kSegment:
      return tricyl::decideIntersect(c.cyl, c.pose,
                                     tricyl::Segment<double>{c.p, c.q});
    default:
      return tricyl::decideIntersect(c.cyl, c.pose,
                                     tricyl::Line<double>{c.p, c.q});
  }
}

#ifdef TRICYL_BENCH_WITH_FCL
/// FCL's sphereCylinderIntersect on the sphere cases: mean per query of
/// whole passes in the same visiting order.
double fclSphereMean(const std::vector<QueryCase>& cs, int passes) {
  const tricyl::bench::FclSphereCases fc(cs);
  Walk walk(cs.size());
  long hits = 0;
  const auto t0 = Clock::now();
  for (int p = 0; p < passes; ++p)
    for (std::size_t n = 0; n < cs.size(); ++n)
      hits += fc.intersect(walk.next());
  const double mean = ns(Clock::now() - t0) / double(passes * cs.size());
  if (hits == -1) std::printf("\n");
  return mean;
}
#endif

}  // namespace

int main(int argc, char** argv) {
  const int passes = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  const double clock_ns = tricyl::bench::clockOverheadNs();
  std::printf(
      "# tricyl-query-stage-costs\n\n%d cases per family, %d passes; "
      "clock overhead %.1f ns (subtracted from single-query times)\n\n",
      kCases, passes, clock_ns);
  std::printf(
      "| query | family | mean | median | p99 | max | FCL mean | "
      "FCL / tricyl |\n|---|---|---:|---:|---:|---:|---:|---:|\n");
  std::vector<std::string> stage_rows;
  const struct {
    Query q;
    const char* name;
  } queries[] = {{Query::kSphere, "sphere"},
                 {Query::kSegment, "segment"},
                 {Query::kLine, "line"}};
  for (const auto& qy : queries) {
    for (Family fam : tricyl::qscenes::kAllFamilies) {
      const std::vector<QueryCase> v = cases(qy.q, fam);
      const tricyl::bench::FamilyCosts fc = tricyl::bench::measureFamily(
          v, passes, clock_ns,
          [&](const QueryCase& c) { return decide(qy.q, c); });
      double fcl_mean = 0;
#ifdef TRICYL_BENCH_WITH_FCL
      if (qy.q == Query::kSphere) fcl_mean = fclSphereMean(v, passes);
#endif
      char fcl[64] = "-";
      char ratio[64] = "-";
      if (fcl_mean > 0) {
        std::snprintf(fcl, sizeof fcl, "%.1f ns", fcl_mean);
        std::snprintf(ratio, sizeof ratio, "%.2fx", fcl_mean / fc.mean);
      }
      const auto& all = fc.all;
      std::printf(
          "| %s | %s | %.1f ns | %.1f ns | %.0f ns | %.0f ns | %s | %s |\n",
          qy.name, tricyl::qscenes::familyName(fam), fc.mean,
          quantile(all, 0.5), quantile(all, 0.99),
          *std::max_element(all.begin(), all.end()), fcl, ratio);
      for (const auto& r : tricyl::bench::stageRows(
               std::string(qy.name) + " | " + tricyl::qscenes::familyName(fam),
               fc))
        stage_rows.push_back(r);
      if (fc.hits == -1) std::printf("\n");  // keep the answers alive
    }
  }
  std::printf(
      "\n## By stage (queries timed one by one)\n\n| query | family | stage | "
      "share | mean | p99 | max |\n|---|---|---|---:|---:|---:|---:|\n");
  for (const auto& r : stage_rows) std::printf("%s", r.c_str());
  return 0;
}
