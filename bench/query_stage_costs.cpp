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

#include "query_scenes.h"
#include "stage_report.h"
#include "tricyl/tricyl.h"
#include "walk.h"

#ifdef TRICYL_BENCH_WITH_FCL
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/sphere_cylinder.h>
#endif

namespace {

using tricyl::Stage;
using tricyl::bench::Clock;
using tricyl::bench::ns;
using tricyl::bench::quantile;
using tricyl::bench::Walk;
using tricyl::qscenes::Family;
using tricyl::qscenes::Query;
using tricyl::qscenes::QueryCase;

constexpr int kCases = 4096;

std::vector<QueryCase> cases(Query q, Family f) {
  std::vector<QueryCase> v;
  for (int i = 0; i < kCases; ++i)
    v.push_back(tricyl::qscenes::generate(q, f, 20261122u, std::uint64_t(i)));
  return v;
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
  std::vector<fcl::Sphered> sph;
  std::vector<fcl::Cylinderd> cyl;
  std::vector<fcl::Transform3d> X_FS, X_FC;
  for (const QueryCase& c : cs) {
    sph.emplace_back(c.rho);
    cyl.emplace_back(c.cyl.radius, c.cyl.lz);
    fcl::Transform3d s = fcl::Transform3d::Identity();
    s.translation() = fcl::Vector3d(c.p.x, c.p.y, c.p.z);
    X_FS.push_back(s);
    fcl::Transform3d t = fcl::Transform3d::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) t.linear()(i, j) = c.pose.R[i][j];
    t.translation() = fcl::Vector3d(c.pose.t.x, c.pose.t.y, c.pose.t.z);
    X_FC.push_back(t);
  }
  Walk walk(cs.size());
  long hits = 0;
  const auto t0 = Clock::now();
  for (int p = 0; p < passes; ++p)
    for (std::size_t n = 0; n < cs.size(); ++n) {
      const std::size_t i = walk.next();
      hits += fcl::detail::sphereCylinderIntersect<double>(
          sph[i], X_FS[i], cyl[i], X_FC[i], nullptr);
    }
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
      long hits = 0;
      Walk walk(v.size());
      const auto t0 = Clock::now();
      for (int p = 0; p < passes; ++p)
        for (std::size_t n = 0; n < v.size(); ++n)
          hits +=
              decide(qy.q, v[walk.next()]).answer == tricyl::Answer::kIntersect;
      const double mean = ns(Clock::now() - t0) / double(passes * kCases);
      double fcl_mean = 0;
#ifdef TRICYL_BENCH_WITH_FCL
      if (qy.q == Query::kSphere) fcl_mean = fclSphereMean(v, passes);
#endif
      std::vector<double> all;
      std::vector<double> by[8];
      Walk w1(v.size());
      for (int p = 0; p < passes; ++p)
        for (std::size_t n = 0; n < v.size(); ++n) {
          const QueryCase& c = v[w1.next()];
          const auto a = Clock::now();
          const tricyl::Decision d = decide(qy.q, c);
          const double t = std::max(0.0, ns(Clock::now() - a) - clock_ns);
          hits += d.answer == tricyl::Answer::kIntersect;
          all.push_back(t);
          by[int(d.stage)].push_back(t);
        }
      char fcl[64] = "-";
      char ratio[64] = "-";
      if (fcl_mean > 0) {
        std::snprintf(fcl, sizeof fcl, "%.1f ns", fcl_mean);
        std::snprintf(ratio, sizeof ratio, "%.2fx", fcl_mean / mean);
      }
      std::printf(
          "| %s | %s | %.1f ns | %.1f ns | %.0f ns | %.0f ns | %s | %s |\n",
          qy.name, tricyl::qscenes::familyName(fam), mean, quantile(all, 0.5),
          quantile(all, 0.99), *std::max_element(all.begin(), all.end()), fcl,
          ratio);
      for (Stage s : {Stage::kEarlyOut, Stage::kFastPath, Stage::kExtended,
                      Stage::kExact, Stage::kExactGmp}) {
        const auto& b = by[int(s)];
        if (b.empty()) continue;
        double sum = 0;
        for (double t : b) sum += t;
        char row[256];
        std::snprintf(row, sizeof row,
                      "| %s | %s | %s | %.3f %% | %.0f ns | %.0f ns | %.0f ns "
                      "|\n",
                      qy.name, tricyl::qscenes::familyName(fam),
                      tricyl::bench::stageName(s),
                      100.0 * double(b.size()) / double(all.size()),
                      sum / double(b.size()), quantile(b, 0.99),
                      *std::max_element(b.begin(), b.end()));
        stage_rows.push_back(row);
      }
      if (hits == -1) std::printf("\n");  // keep the answers alive
    }
  }
  std::printf(
      "\n## By stage (queries timed one by one)\n\n| query | family | stage | "
      "share | mean | p99 | max |\n|---|---|---|---:|---:|---:|---:|\n");
  for (const auto& r : stage_rows) std::printf("%s", r.c_str());
  return 0;
}
