// SPDX-License-Identifier: BSD-3-Clause
// tricyl-stage-costs: what each stage of the triangle-cylinder Boolean
// costs, family by family, as decideIntersect sees it, beside FCL's MPR
// (GJKSolver_libccd, collision_tolerance 1e-6) on the same cases in the
// same run. A report, not a test: it asserts nothing.
//
// Per family: 4096 cases of compare/scenes.h (seed 7, as bench/), visited
// in an order the branch predictor cannot learn (bench/walk.h).
//   - mean per query of whole passes (no clock inside the loop) for tricyl
//     and for FCL, and their ratio: what a planner pays;
//   - per query, timed one by one (steady_clock, the clock's own cost
//     measured and subtracted), median and p99 over all queries, and by
//     the stage that decided it: share, mean, p99, max.
// Usage: tricyl-stage-costs [passes] (default 20); markdown on stdout.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "scenes.h"
#include "stage_report.h"
#include "tricyl/triangle_cylinder.h"
#include "walk.h"

#ifdef TRICYL_BENCH_WITH_FCL
#include "fcl_cases.h"
#endif

namespace {

using tricyl::Stage;
using tricyl::bench::Clock;
using tricyl::bench::ns;
using tricyl::bench::quantile;
using tricyl::bench::Walk;
using tricyl::scenes::Family;
using tricyl::scenes::TriCase;

constexpr int kCases = 4096;

}  // namespace

int main(int argc, char** argv) {
  const int passes = argc > 1 ? std::max(1, std::atoi(argv[1])) : 20;
  // The clock's own cost, subtracted from every single-query time.
  const double clock_ns = tricyl::bench::clockOverheadNs();
  std::printf(
      "# tricyl-stage-costs\n\n%d cases per family, %d passes; "
      "clock overhead %.1f ns (subtracted from single-query "
      "times)\n\n",
      kCases, passes, clock_ns);
  std::printf(
      "| family | tricyl mean | FCL MPR mean | ratio | tricyl median "
      "| tricyl p99 | tricyl max |\n|---|---:|---:|---:|---:|---:|---:|"
      "\n");
  std::vector<std::string> stage_rows;
  for (Family fam : tricyl::scenes::kAllFamilies) {
    std::vector<TriCase> v;
    for (int i = 0; i < kCases; ++i)
      v.push_back(tricyl::scenes::generate(fam, 7, std::uint64_t(i)));
    const tricyl::bench::FamilyCosts fc =
        tricyl::bench::measureFamily(v, passes, clock_ns, [](const TriCase& c) {
          return tricyl::decideIntersect(c.cyl, c.pose, c.tri);
        });
    long hits = fc.hits;
    double fcl_mean = 0;
#ifdef TRICYL_BENCH_WITH_FCL
    {
      const tricyl::bench::FclCases fcl_cases(v);
      fcl::detail::GJKSolver_libccd<double> solver;
      solver.collision_tolerance = 1e-6;
      Walk w(v.size());
      const int fcl_passes = std::max(1, passes / 4);
      const auto f0 = Clock::now();
      for (int p = 0; p < fcl_passes; ++p) hits += fcl_cases.pass(solver, w);
      fcl_mean = ns(Clock::now() - f0) / double(fcl_passes * kCases);
    }
#endif
    const auto& all = fc.all;
    std::printf(
        "| %s | %.1f ns | %.1f ns | %.1fx | %.1f ns | %.0f ns | %.0f ns |\n",
        tricyl::scenes::familyName(fam), fc.mean, fcl_mean,
        fcl_mean > 0 ? fcl_mean / fc.mean : 0.0, quantile(all, 0.5),
        quantile(all, 0.99), *std::max_element(all.begin(), all.end()));
    for (const auto& r :
         tricyl::bench::stageRows(tricyl::scenes::familyName(fam), fc))
      stage_rows.push_back(r);
    if (hits == -1) std::printf("\n");  // keep the answers alive
  }
  std::printf(
      "\n## By stage (queries timed one by one)\n\n| family | stage | "
      "share | mean | p99 | max |\n|---|---|---:|---:|---:|---:|\n");
  for (const auto& r : stage_rows) std::printf("%s", r.c_str());

  // What the stages after the filter cost: the queries the filter left
  // open, grouped by the stage that decided them, timed whole
  // (decideIntersect) and stopped after the filter (diagnostic::filterOnly)
  // in the same shuffled order, alternately, the least of the passes' means
  // each (a preemption of this shared machine is not the query's cost).
  std::printf(
      "\n## After the filter (the queries it left open, by deciding stage; "
      "least of %d alternated passes)\n\n| family | stage | queries | whole "
      "query | the filter's part | after the filter |\n"
      "|---|---|---:|---:|---:|---:|\n",
      passes);
  for (Family fam : tricyl::scenes::kAllFamilies) {
    std::vector<TriCase> by[8];
    for (int i = 0; i < kCases; ++i) {
      const TriCase c = tricyl::scenes::generate(fam, 7, std::uint64_t(i));
      by[int(tricyl::decideIntersect(c.cyl, c.pose, c.tri).stage)].push_back(c);
    }
    for (Stage s : {Stage::kRunning, Stage::kExtended, Stage::kExact}) {
      std::vector<TriCase>& v = by[int(s)];
      if (v.size() < 8) continue;
      std::mt19937 rng(11);
      std::shuffle(v.begin(), v.end(), rng);
      double whole = 1e300, filter = 1e300;
      long hits = 0;
      for (int p = 0; p < passes; ++p) {
        auto a = Clock::now();
        for (const TriCase& c : v)
          hits += tricyl::decideIntersect(c.cyl, c.pose, c.tri).answer ==
                  tricyl::Answer::kIntersect;
        whole = std::min(whole, ns(Clock::now() - a) / double(v.size()));
        a = Clock::now();
        for (const TriCase& c : v)
          hits += tricyl::diagnostic::filterOnly(c.cyl, c.pose, c.tri);
        filter = std::min(filter, ns(Clock::now() - a) / double(v.size()));
      }
      std::printf("| %s | %s | %zu | %.1f ns | %.1f ns | %.1f ns |\n",
                  tricyl::scenes::familyName(fam), tricyl::bench::stageName(s),
                  v.size(), whole, filter, whole - filter);
      if (hits == -1) std::printf("\n");  // keep the answers alive
    }
  }

  // Bounded time on hostile input: every coordinate, translation, radius,
  // length and rotation entry with a random exponent in 2^-1070 .. 2^1020
  // (seeded), so the range gate sends every query to GMP and the dyadic
  // integers span about 2,100 bits before the degree-8 products.
  {
    std::uint64_t x = 0x9e3779b97f4a7c15ULL;
    auto next = [&x]() {
      x ^= x << 13;
      x ^= x >> 7;
      x ^= x << 17;
      return x;
    };
    auto wild = [&next]() {
      const double f = 1.0 + double(next() >> 12) * 0x1p-52;
      const int e = -1070 + int(next() % 2091);
      return ((next() & 1) ? -1.0 : 1.0) * std::ldexp(f, e);
    };
    std::vector<double> t;
    long hits = 0;
    for (int i = 0; i < 20000; ++i) {
      tricyl::Cylinder<double> cyl{std::fabs(wild()), std::fabs(wild())};
      tricyl::Pose<double> pose;
      for (auto& row : pose.R)
        for (double& r : row) r = wild();
      pose.t = {wild(), wild(), wild()};
      tricyl::Triangle<double> tri{{wild(), wild(), wild()},
                                   {wild(), wild(), wild()},
                                   {wild(), wild(), wild()}};
      // The least of three timings: a preemption of this shared machine is
      // not the query's cost.
      double best = 1e300;
      for (int rep = 0; rep < 3; ++rep) {
        const auto a = Clock::now();
        hits +=
            tricyl::tryIntersect(cyl, pose, tri) == tricyl::Answer::kIntersect;
        best = std::min(best, ns(Clock::now() - a));
      }
      t.push_back(best);
    }
    std::printf(
        "\n## Random exponents (2^-1070 .. 2^1020, 20,000 queries)\n\n"
        "median %.1f us, p99 %.1f us, max %.1f us (least of 3 "
        "timings each; %ld hits)\n",
        quantile(t, 0.5) / 1e3, quantile(t, 0.99) / 1e3,
        *std::max_element(t.begin(), t.end()) / 1e3, hits);
  }
  return 0;
}
