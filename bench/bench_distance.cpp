// SPDX-License-Identifier: BSD-3-Clause
// tricyl::distance vs FCL's libccd shapeTriangleDistance (issue 23) on the
// six triangle families, in the same run.
//
// BM_DistancePaired/<family>: one iteration runs every case of the family
// through tricyl::tryDistance, then through FCL's
// GJKSolver_libccd<double>::shapeTriangleDistance (default settings: its
// distance_tolerance default IS 1e-6, max_distance_iterations 1000), each
// block timed on its own, the cases visited in a shuffled order (walk.h),
// the same order for both. Counters: tricyl_ns and fcl_ns, the MEAN time
// per query over all iterations, and ratio = fcl_ns / tricyl_ns; then
// median and p99 per query of each (tricyl_med, tricyl_p99, fcl_med,
// fcl_p99), from one extra pass where every query is timed on its own (so
// they include the clock's overhead, some 20 ns, on both sides alike).
// tricyl_cpu_ns, fcl_cpu_ns and ratio_cpu: the same means from the
// thread's CPU-time clock (POSIX), which a preempted block does not charge
// for the time it waited: the figures to compare on a loaded machine.
// FCL gets proper rotations: the families' poses are rounded unit
// quaternions (det R = +1 to rounding) or exact signed permutations.
#include <benchmark/benchmark.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <vector>

#include "family_cases.h"
#include "fcl_cases.h"
#include "scenes.h"
#include "tricyl/tricyl.h"
#include "walk.h"

namespace {

using tricyl::bench::FclCases;
using tricyl::bench::Walk;
using tricyl::scenes::Family;
using tricyl::scenes::TriCase;
using Clock = std::chrono::steady_clock;

constexpr int kCases = tricyl::bench::kFamilyCases;

const std::vector<TriCase>& cases(Family f) {
  return tricyl::bench::familyCases(f);
}

// The calling thread's CPU time in ns (0 where there is no such clock).
double threadCpuNs() {
#if defined(CLOCK_THREAD_CPUTIME_ID)
  timespec ts{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
  return double(ts.tv_sec) * 1e9 + double(ts.tv_nsec);
#else
  return 0;
#endif
}

double tricylOne(const TriCase& c) {
  tricyl::DistanceResult<double> r;
  tricyl::tryDistance(c.cyl, c.pose, c.tri, &r);
  return r.distance;
}

double fclOne(const fcl::detail::GJKSolver_libccd<double>& solver,
              const FclCases& fc, std::size_t i) {
  double d = 0;
  fcl::Vector3d p1, p2;
  solver.shapeTriangleDistance(fc.cyl[i], fc.tf[i], fc.p[3 * i],
                               fc.p[3 * i + 1], fc.p[3 * i + 2], &d, &p1, &p2);
  return d;
}

double quantile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::size_t(q * double(v.size() - 1))];
}

void BM_DistancePaired(benchmark::State& state) {
  const Family fam = Family(state.range(0));
  const auto& k = cases(fam);
  const FclCases fc(k);
  const fcl::detail::GJKSolver_libccd<double> solver;  // tolerance 1e-6
  double t_tricyl = 0, t_fcl = 0, c_tricyl = 0, c_fcl = 0, sink = 0;
  Walk walk_tricyl(k.size()), walk_fcl(k.size());
  for (auto _ : state) {
    const double c0 = threadCpuNs();
    const auto t0 = Clock::now();
    for (std::size_t n = 0; n < k.size(); ++n)
      sink += tricylOne(k[walk_tricyl.next()]);
    const auto t1 = Clock::now();
    const double c1 = threadCpuNs();
    for (std::size_t n = 0; n < k.size(); ++n)
      sink += fclOne(solver, fc, walk_fcl.next());
    const auto t2 = Clock::now();
    const double c2 = threadCpuNs();
    t_tricyl += std::chrono::duration<double, std::nano>(t1 - t0).count();
    t_fcl += std::chrono::duration<double, std::nano>(t2 - t1).count();
    c_tricyl += c1 - c0;
    c_fcl += c2 - c1;
  }
  // One pass with every query timed on its own: median and p99.
  std::vector<double> qt, qf;
  Walk w(k.size());
  for (std::size_t n = 0; n < k.size(); ++n) {
    const std::size_t i = w.next();
    const auto a = Clock::now();
    sink += tricylOne(k[i]);
    const auto b = Clock::now();
    sink += fclOne(solver, fc, i);
    const auto c = Clock::now();
    qt.push_back(std::chrono::duration<double, std::nano>(b - a).count());
    qf.push_back(std::chrono::duration<double, std::nano>(c - b).count());
  }
  benchmark::DoNotOptimize(sink);
  const double n = double(state.iterations()) * double(k.size());
  state.counters["tricyl_ns"] = t_tricyl / n;
  state.counters["fcl_ns"] = t_fcl / n;
  state.counters["ratio"] = t_fcl / t_tricyl;
  if (c_tricyl > 0) {
    state.counters["tricyl_cpu_ns"] = c_tricyl / n;
    state.counters["fcl_cpu_ns"] = c_fcl / n;
    state.counters["ratio_cpu"] = c_fcl / c_tricyl;
  }
  state.counters["tricyl_med"] = quantile(qt, 0.5);
  state.counters["tricyl_p99"] = quantile(qt, 0.99);
  state.counters["fcl_med"] = quantile(qf, 0.5);
  state.counters["fcl_p99"] = quantile(qf, 0.99);
  state.SetLabel(tricyl::scenes::familyName(fam));
}
BENCHMARK(BM_DistancePaired)->DenseRange(0, 5)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
