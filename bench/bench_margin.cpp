// SPDX-License-Identifier: BSD-3-Clause
// tricyl::withinDistance against tricyl::intersect on the same cases, in the
// same run: the six triangle families of compare/scenes.h (fixed seed, 4096
// cases each), each case with a margin drawn uniformly in [0, 10%] of the
// cylinder's size max(r, lz) (one in eight exactly 0). Cases are visited in
// the shuffled order of walk.h. The Google Benchmark rows give the MEAN time
// per query; `--percentiles` also prints, per family, the mean, median and
// p99 of single-query times (steady_clock around each query, the clock's own
// cost measured on an empty call and subtracted) and the ratio of the means.
//
//   ./bench_margin --benchmark_repetitions=5 --benchmark_report_aggregates_only
//   ./bench_margin --percentiles --benchmark_filter=none
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <vector>

#include "scenes.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_margin.h"
#include "walk.h"

namespace {

using tricyl::scenes::Family;
using tricyl::scenes::TriCase;

constexpr int kCases = 4096;

struct MarginCase {
  TriCase k;
  double m;
};

std::vector<MarginCase> cases(Family f) {
  std::vector<MarginCase> v;
  tricyl::scenes::Rng g(0x6d617267u ^ std::uint64_t(f));
  for (int i = 0; i < kCases; ++i) {
    MarginCase c;
    c.k = tricyl::scenes::generate(f, 20261122u, std::uint64_t(i));
    const double size = std::max(c.k.cyl.radius, c.k.cyl.lz);
    c.m = i % 8 == 0 ? 0.0 : 0.1 * size * g.uniform();
    v.push_back(c);
  }
  return v;
}

/// One row: withinDistance (margin) or intersect on the same cases.
void BM_Query(benchmark::State& state, Family f, bool margin) {
  const auto cs = cases(f);
  tricyl::bench::Walk walk(cs.size());
  long yes = 0;
  for (auto _ : state) {
    const MarginCase& c = cs[walk.next()];
    const auto a =
        margin ? tricyl::tryWithinDistance(c.k.cyl, c.k.pose, c.k.tri, c.m)
               : tricyl::tryIntersect(c.k.cyl, c.k.pose, c.k.tri);
    yes += a == tricyl::Answer::kIntersect;
    benchmark::DoNotOptimize(a);
  }
  state.counters[margin ? "within" : "hit"] =
      double(yes) / double(state.iterations());
}

void registerAll() {
  for (Family f : tricyl::scenes::kAllFamilies) {
    const std::string name = tricyl::scenes::familyName(f);
    benchmark::RegisterBenchmark(("margin/" + name + "/withinDistance").c_str(),
                                 BM_Query, f, true);
    benchmark::RegisterBenchmark(("margin/" + name + "/intersect").c_str(),
                                 BM_Query, f, false);
  }
}

double threadCpuNs() {
  timespec ts;
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e9 + double(ts.tv_nsec);
}

double pct(std::vector<double> v, double p) {
  std::sort(v.begin(), v.end());
  const size_t i = std::min(v.size() - 1, size_t(p / 100 * double(v.size())));
  return v[i];
}

// Per-query times: passes over the 4096 cases in the shuffled order of
// walk.h, alternating the two methods pass by pass (timing both on the same
// case back to back would hand the second one a warm cache and a trained
// predictor). The mean is from 8 passes per method without per-query clock
// reads: the thread's CPU time divided by the queries (on a shared machine a
// wall-clock mean is dominated by the few queries during which the thread
// was descheduled). Median and p99 are of the wall-clock time of each query
// of 8 other passes per method (32768 queries each), the clock's own cost
// subtracted.
void percentiles() {
  using Clock = std::chrono::steady_clock;
  std::printf(
      "| family | withinDistance mean ns | median | p99 | intersect mean ns "
      "| median | p99 | mean ratio "
      "|\n|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (Family f : tricyl::scenes::kAllFamilies) {
    const auto cs = cases(f);
    tricyl::bench::Walk walk(cs.size());
    std::vector<double> times[2];
    double empty = 1e300;
    for (int rep = 0; rep < 1000; ++rep) {  // the clock's own cost
      const auto t0 = Clock::now();
      const auto t1 = Clock::now();
      empty = std::min(
          empty, std::chrono::duration<double, std::nano>(t1 - t0).count());
    }
    long sink = 0;
    double cpu[2] = {0, 0};
    for (int pass = 0; pass < 32; ++pass) {
      const bool margin = pass % 2 == 0;
      if (pass % 4 >= 2) {  // a mean pass
        const double c0 = threadCpuNs();
        for (int i = 0; i < kCases; ++i) {
          const MarginCase& c = cs[walk.next()];
          sink +=
              int(margin ? tricyl::tryWithinDistance(c.k.cyl, c.k.pose, c.k.tri,
                                                     c.m)
                         : tricyl::tryIntersect(c.k.cyl, c.k.pose, c.k.tri));
        }
        cpu[margin ? 0 : 1] += threadCpuNs() - c0;
        continue;
      }
      for (int i = 0; i < kCases; ++i) {
        const MarginCase& c = cs[walk.next()];
        const auto t0 = Clock::now();
        sink += int(
            margin ? tricyl::tryWithinDistance(c.k.cyl, c.k.pose, c.k.tri, c.m)
                   : tricyl::tryIntersect(c.k.cyl, c.k.pose, c.k.tri));
        const auto t1 = Clock::now();
        times[margin ? 0 : 1].push_back(
            std::chrono::duration<double, std::nano>(t1 - t0).count() - empty);
      }
    }
    const double mw = cpu[0] / (8.0 * kCases), mi = cpu[1] / (8.0 * kCases);
    std::printf("| %s | %.1f | %.1f | %.1f | %.1f | %.1f | %.1f | %.2f |%s\n",
                tricyl::scenes::familyName(f), mw, pct(times[0], 50),
                pct(times[0], 99), mi, pct(times[1], 50), pct(times[1], 99),
                mw / mi, sink < 0 ? " " : "");
  }
}

}  // namespace

int main(int argc, char** argv) {
  bool pcts = false;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i) {
    if (std::strcmp(argv[i], "--percentiles") == 0)
      pcts = true;
    else
      args.push_back(argv[i]);
  }
  int n = int(args.size());
  registerAll();
  benchmark::Initialize(&n, args.data());
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  if (pcts) percentiles();
  return 0;
}
