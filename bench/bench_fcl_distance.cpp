// SPDX-License-Identifier: BSD-3-Clause
// Mesh/cylinder distance and the margin collide through FCL (fcl_solver.h,
// DISTANCE and MARGIN COLLIDE), on env.obj, bunny.obj and rob.obj
// (BVHModel<OBBRSS>, the BV type stock fcl::distance supports best), in the
// same binary and the same iterations:
// - paired_distance/<mesh>: each iteration takes the next cylinder pose
//   (shuffled, bench/walk.h) and runs it through
//     tricyl  = tricyl::distance (tricyl's own traversal, certified bounds),
//     solver  = fcl::distance with tricyl::Solver (FCL's traversal,
//               tricyl::distance at the leaves),
//     stock   = fcl::distance with a default DistanceRequest (FCL's
//               traversal, GJKSolver_libccd, distance_tolerance 1e-6),
//   in a rotating order, each call timed on its own: counters <m>_mean_us,
//   <m>_median_us, <m>_p99_us per call, and x_stock_<m> = stock mean / <m>
//   mean (above 1: faster than stock fcl::distance).
// - paired_margin/<mesh>: tricyl::collide with CollideOptions{margin} (1 %
//   of the mesh diagonal) against plain tricyl::collide, first hit and
//   exhaustive: margin_* / plain_* as above, x_plain = plain / margin.
//
// Poses: a random triangle's centroid pushed out along its normal by
// 10^-6 .. 10^-1 of the diagonal (log-uniform), random orientation, sizes
// 0.3 .. 2.3 % (radius) and 1 .. 6 % (length) of the diagonal: most poses
// are near but clear of the surface (planner clearance queries), some touch.
//
//   cmake --build build --target bench_fcl_distance
//   ./build/bench/bench_fcl_distance --benchmark_min_time=2
#include <benchmark/benchmark.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "fcl_mesh_scenes.h"
#include "tricyl/fcl_solver.h"
#include "walk.h"

namespace {

using V3 = fcl::Vector3d;
using Tf = fcl::Transform3d;

constexpr int kPoses = 256;  // a power of two (bench/walk.h)
static_assert(tricyl::bench::Walk::valid(kPoses));

struct Scene {
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model;
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> cyls;
  double diag = 0;
  bool ok = false;
};

Scene load(const std::string& file, std::uint64_t seed) {
  Scene d;
  tricyl::bench::FclObjModel fm;
  if (!tricyl::bench::loadFclObj(file, &fm)) return d;
  d.model = fm.model;
  d.diag = fm.diag;
  const tricyl::bench::CylinderPoses p =
      tricyl::bench::clearancePoses(fm, seed, kPoses);
  for (std::size_t i = 0; i < p.poses.size(); ++i)
    d.cyls.push_back(
        std::make_unique<fcl::CollisionObjectd>(p.cyls[i], p.poses[i]));
  d.ok = true;
  return d;
}

const Scene& scene(const std::string& file) {
  static Scene env = load("env.obj", 52);
  static Scene bunny = load("bunny.obj", 53);
  static Scene rob = load("rob.obj", 54);
  return file == "env.obj" ? env : (file == "bunny.obj" ? bunny : rob);
}

using Clock = std::chrono::steady_clock;

/// Per-call times of one method: mean, median and p99 as counters.
struct Times {
  std::vector<double> us;
  double mean() const {
    double s = 0;
    for (double x : us) s += x;
    return us.empty() ? 0 : s / double(us.size());
  }
  double quantile(double q) {
    if (us.empty()) return 0;
    std::vector<double> c = us;
    const std::size_t k =
        std::min(c.size() - 1, std::size_t(q * double(c.size())));
    std::nth_element(c.begin(), c.begin() + std::ptrdiff_t(k), c.end());
    return c[k];
  }
  void report(benchmark::State& state, const std::string& name) {
    state.counters[name + "_mean_us"] = mean();
    state.counters[name + "_median_us"] = quantile(0.5);
    state.counters[name + "_p99_us"] = quantile(0.99);
  }
};

template <class F>
double timed(F&& f) {
  const auto t0 = Clock::now();
  f();
  const auto t1 = Clock::now();
  return std::chrono::duration<double, std::micro>(t1 - t0).count();
}

void BM_PairedDistance(benchmark::State& state, std::string file) {
  const Scene& d = scene(file);
  if (!d.ok) {
    state.SkipWithError("mesh not found (../shared/data/meshes)");
    return;
  }
  const fcl::CollisionObjectd o_mesh(d.model, Tf::Identity());
  const tricyl::Solver<double> solver;
  const fcl::DistanceRequestd req;  // FCL's defaults: libccd, tol 1e-6
  tricyl::bench::Walk walk(kPoses);
  Times t[3];  // tricyl, solver, stock
  double disagree = 0, colliding = 0;
  int first = 0;
  for (auto _ : state) {
    const fcl::CollisionObjectd* o_cyl = d.cyls[walk.next()].get();
    double value[3];
    for (int j = 0; j < 3; ++j) {
      const int m = (first + j) % 3;
      fcl::DistanceResultd res;
      t[m].us.push_back(timed([&] {
        if (m == 0)
          tricyl::distance(&o_mesh, o_cyl, req, res);
        else if (m == 1)
          fcl::distance(&o_mesh, o_cyl, &solver, req, res);
        else
          fcl::distance(&o_mesh, o_cyl, req, res);
      }));
      benchmark::DoNotOptimize(res);
      value[m] = res.min_distance;
    }
    first = (first + 1) % 3;
    if (value[0] <= 0) colliding += 1;
    // The two tricyl paths answer the same (up to FCL's traversal's
    // rounded BV distances): count the iterations where they do not.
    if (value[0] > 0 &&
        std::abs(value[1] - value[0]) > 1e-9 * value[0] + 1e-12 * d.diag)
      disagree += 1;
  }
  const char* names[3] = {"tricyl", "solver", "stock"};
  for (int m = 0; m < 3; ++m) t[m].report(state, names[m]);
  state.counters["x_stock_tricyl"] = t[2].mean() / t[0].mean();
  state.counters["x_stock_solver"] = t[2].mean() / t[1].mean();
  state.counters["colliding"] =
      benchmark::Counter(colliding, benchmark::Counter::kAvgIterations);
  state.counters["solver_ne_tricyl"] = disagree;
}

// tricyl's traversal alone, with its statistics per call: bounds computed
// (nodes), nodes and triangles pruned (pruned), triangles measured by
// tricyl::distance (leaves).
void BM_TricylDistance(benchmark::State& state, std::string file) {
  const Scene& d = scene(file);
  if (!d.ok) {
    state.SkipWithError("mesh not found (../shared/data/meshes)");
    return;
  }
  const fcl::DistanceRequestd req;
  tricyl::bench::Walk walk(kPoses);
  tricyl::TraversalStats stats;
  for (auto _ : state) {
    const fcl::CollisionObjectd* o_cyl = d.cyls[walk.next()].get();
    fcl::DistanceResultd res;
    tricyl::distanceMeshCylinder(d.model.get(), Tf::Identity(),
                                 o_cyl->collisionGeometry().get(),
                                 o_cyl->getTransform(), req, res, &stats);
    benchmark::DoNotOptimize(res);
  }
  using C = benchmark::Counter;
  state.counters["nodes"] = C(double(stats.nodes_tested), C::kAvgIterations);
  state.counters["pruned"] = C(double(stats.nodes_skipped), C::kAvgIterations);
  state.counters["leaves"] = C(double(stats.leaves), C::kAvgIterations);
}

void BM_PairedMargin(benchmark::State& state, std::string file,
                     bool exhaustive) {
  const Scene& d = scene(file);
  if (!d.ok) {
    state.SkipWithError("mesh not found (../shared/data/meshes)");
    return;
  }
  const fcl::CollisionObjectd o_mesh(d.model, Tf::Identity());
  const fcl::CollisionRequestd req(exhaustive ? 100000 : 1, false);
  const tricyl::CollideOptions<double> options{0.01 * d.diag};
  tricyl::bench::Walk walk(kPoses);
  Times t[2];  // margin, plain
  double hits_margin = 0, hits_plain = 0;
  bool margin_first = true;
  for (auto _ : state) {
    const fcl::CollisionObjectd* o_cyl = d.cyls[walk.next()].get();
    for (int k = 0; k < 2; ++k) {
      const bool margin = (k == 0) == margin_first;
      fcl::CollisionResultd res;
      t[margin ? 0 : 1].us.push_back(timed([&] {
        if (margin)
          tricyl::collide(&o_mesh, o_cyl, req, res, options);
        else
          tricyl::collide(&o_mesh, o_cyl, req, res);
      }));
      benchmark::DoNotOptimize(res);
      (margin ? hits_margin : hits_plain) += double(res.numContacts());
    }
    margin_first = !margin_first;
  }
  t[0].report(state, "margin");
  t[1].report(state, "plain");
  state.counters["x_plain"] = t[1].mean() / t[0].mean();
  state.counters["hits_margin"] =
      benchmark::Counter(hits_margin, benchmark::Counter::kAvgIterations);
  state.counters["hits_plain"] =
      benchmark::Counter(hits_plain, benchmark::Counter::kAvgIterations);
}

void registerAll() {
  for (const char* file : {"env.obj", "bunny.obj", "rob.obj"})
    benchmark::RegisterBenchmark(
        (std::string("paired_distance/") + file).c_str(), BM_PairedDistance,
        file);
  for (const char* file : {"env.obj", "bunny.obj", "rob.obj"})
    benchmark::RegisterBenchmark(
        (std::string("tricyl_distance/") + file).c_str(), BM_TricylDistance,
        file);
  for (const char* file : {"env.obj", "bunny.obj", "rob.obj"})
    for (bool exhaustive : {false, true})
      benchmark::RegisterBenchmark((std::string("paired_margin/") + file +
                                    (exhaustive ? "/exhaustive" : "/first_hit"))
                                       .c_str(),
                                   BM_PairedMargin, file, exhaustive);
}

}  // namespace

int main(int argc, char** argv) {
  registerAll();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
