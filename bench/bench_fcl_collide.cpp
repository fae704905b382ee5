// SPDX-License-Identifier: BSD-3-Clause
// End-to-end collide of a cylinder against env.obj and bunny.obj
// (BVHModel<OBBRSS>), in the same binary, first hit (num_max_contacts = 1)
// and exhaustive, contact data off and on; and paired rows on grazing
// scenes of env, bunny and rob (half the poses tangent to a face, pushed in
// or out by up to 1e-3 of the diagonal), cold and warm:
// - tricyl/    tricyl::collide: tricyl's own traversal (fcl_mesh_cylinder.h)
// - solver/    fcl::collide with tricyl::Solver: FCL's traversal, exact leaves
// - stock/     fcl::collide: FCL's traversal and libccd's MPR
// - traversal/ fcl::collide with a solver whose Cylinder/triangle test is a
//   no-op: what FCL's traversal alone costs in the exhaustive case, where
//   the set of visited node pairs does not depend on the leaf answers.
//
// Each benchmark iteration is one collide call; the calls cycle through a
// fixed, seeded set of cylinder poses near the mesh surface (about half of
// them in contact). Counters: hits = colliding triangles per call
// (exhaustive) or the fraction of calls in collision (first hit).
//
//   cmake --build build --target bench_fcl_collide
//   ./build/bench/bench_fcl_collide --benchmark_repetitions=5
//       --benchmark_report_aggregates_only=true   (one line)
#include <benchmark/benchmark.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "fcl_mesh_scenes.h"
#include "tricyl/fcl_solver.h"
#include "walk.h"

namespace {

using V3 = fcl::Vector3d;
using Tf = fcl::Transform3d;

constexpr int kPoses = 256;  // cylinder poses per mesh, a power of two

/// No narrow phase for Cylinder/triangle: every leaf answers "no". Other
/// pairs are libccd's. Used only to time the traversal.
struct TraversalOnlySolver : fcl::detail::GJKSolver_libccd<double> {
  using Base = fcl::detail::GJKSolver_libccd<double>;
  using Base::shapeTriangleIntersect;
  bool shapeTriangleIntersect(const fcl::Cylinderd&, const Tf&, const V3&,
                              const V3&, const V3&, V3* = nullptr,
                              double* = nullptr, V3* = nullptr) const {
    return false;
  }
  bool shapeTriangleIntersect(const fcl::Cylinderd&, const Tf&, const V3&,
                              const V3&, const V3&, const Tf&, V3* = nullptr,
                              double* = nullptr, V3* = nullptr) const {
    return false;
  }
};

struct MeshData {
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model;
  std::vector<std::shared_ptr<fcl::Cylinderd>> cyls;
  std::vector<Tf> poses;
  bool ok = false;
};

/// The mesh and its poses (bench/fcl_mesh_scenes.h, nearSurfacePoses).
MeshData load(const std::string& file, std::uint64_t seed,
              bool grazing = false) {
  MeshData d;
  tricyl::bench::FclObjModel fm;
  if (!tricyl::bench::loadFclObj(file, &fm)) return d;
  d.model = fm.model;
  tricyl::bench::CylinderPoses p =
      tricyl::bench::nearSurfacePoses(fm, seed, kPoses, grazing);
  d.cyls = std::move(p.cyls);
  d.poses = std::move(p.poses);
  d.ok = true;
  return d;
}

const MeshData& mesh(const std::string& file, bool grazing = false) {
  static MeshData env = load("env.obj", 42);
  static MeshData bunny = load("bunny.obj", 43);
  static MeshData genv = load("env.obj", 44, true);
  static MeshData gbunny = load("bunny.obj", 45, true);
  static MeshData grob = load("rob.obj", 46, true);
  if (grazing)
    return file == "env.obj" ? genv : (file == "bunny.obj" ? gbunny : grob);
  return file == "env.obj" ? env : bunny;
}

enum class Which { kTricyl, kSolver, kStock, kTraversal };

/// One collision object per cylinder pose of the mesh's scene.
std::vector<std::unique_ptr<fcl::CollisionObjectd>> cylinderObjects(
    const MeshData& d) {
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> cyls;
  for (std::size_t i = 0; i < d.poses.size(); ++i)
    cyls.push_back(
        std::make_unique<fcl::CollisionObjectd>(d.cyls[i], d.poses[i]));
  return cyls;
}

// The poses in a new order on every pass (tricyl::bench::Walk): a fixed
// cycle of 256 calls is a sequence the branch predictor can partly learn.
static_assert(tricyl::bench::Walk::valid(kPoses));

void BM_Collide(benchmark::State& state, std::string file, Which which,
                bool exhaustive, bool contact) {
  const MeshData& d = mesh(file);
  if (!d.ok) {
    state.SkipWithError("mesh not found (../shared/data/meshes)");
    return;
  }
  fcl::CollisionRequestd req(exhaustive ? 100000 : 1, contact);
  fcl::CollisionObjectd o_mesh(d.model, Tf::Identity());
  const auto cyls = cylinderObjects(d);
  const TraversalOnlySolver null_solver;
  const tricyl::Solver<double> solver;
  tricyl::bench::Walk walk(kPoses);
  double hits = 0;
  tricyl::TraversalStats stats;
  for (auto _ : state) {
    const std::size_t i = walk.next();
    fcl::CollisionResultd res;
    const fcl::CollisionObjectd* o_cyl = cyls[i].get();
    switch (which) {
      case Which::kTricyl: {
        std::size_t n = 0;  // tricyl::collide's path, with statistics
        if (!tricyl::collideMeshCylinder(
                o_mesh.collisionGeometry().get(), o_mesh.getTransform(),
                o_cyl->collisionGeometry().get(), o_cyl->getTransform(), req,
                res, &n, &stats))
          state.SkipWithError("pair not handled by the traversal");
        break;
      }
      case Which::kSolver:
        fcl::collide(&o_mesh, o_cyl, &solver, req, res);
        break;
      case Which::kStock:
        fcl::collide(&o_mesh, o_cyl, req, res);
        break;
      case Which::kTraversal:
        fcl::collide(&o_mesh, o_cyl, &null_solver, req, res);
        break;
    }
    hits += double(res.numContacts());
    benchmark::DoNotOptimize(res);
  }
  state.counters["hits"] =
      benchmark::Counter(hits, benchmark::Counter::kAvgIterations);
  if (which == Which::kTricyl) {
    state.counters["nodes"] = benchmark::Counter(
        double(stats.nodes_tested), benchmark::Counter::kAvgIterations);
    state.counters["leaves"] = benchmark::Counter(
        double(stats.leaves), benchmark::Counter::kAvgIterations);
  }
}

// Paired: each iteration runs one pose through tricyl::collide and through
// the stock fcl::collide (alternating which goes first), each call timed on
// its own, so both see the same clock: this VM's effective clock drifts by
// tens of percent within seconds, which rows measured apart carry into their
// ratio. Counters: tricyl_us and stock_us per call, ratio = stock / tricyl
// (sums over the iterations); best_* the same from the fastest call per
// pose.
void BM_PairedCollide(benchmark::State& state, std::string file,
                      bool exhaustive, bool grazing, bool warm) {
  const MeshData& d = mesh(file, grazing);
  if (!d.ok) {
    state.SkipWithError("mesh not found (../shared/data/meshes)");
    return;
  }
  fcl::CollisionRequestd req(exhaustive ? 100000 : 1, false);
  fcl::CollisionObjectd o_mesh(d.model, Tf::Identity());
  const auto cyls = cylinderObjects(d);
  using Clock = std::chrono::steady_clock;
  tricyl::bench::Walk walk(kPoses);
  double t_tricyl = 0, t_stock = 0, n = 0;
  std::vector<double> best_tricyl(kPoses, 1e300), best_stock(kPoses, 1e300);
  bool tricyl_first = true;
  for (auto _ : state) {
    const std::size_t i = walk.next();
    const fcl::CollisionObjectd* o_cyl = cyls[i].get();
    for (int k = 0; k < 2; ++k) {
      const bool run_tricyl = (k == 0) == tricyl_first;
      fcl::CollisionResultd res;
      // Warm: the same pose twice before the timed call (caches and
      // predictors primed by this very query).
      for (int w = 0; warm && w < 2; ++w) {
        fcl::CollisionResultd r0;
        if (run_tricyl)
          tricyl::collide(&o_mesh, o_cyl, req, r0);
        else
          fcl::collide(&o_mesh, o_cyl, req, r0);
        benchmark::DoNotOptimize(r0);
      }
      const auto t0 = Clock::now();
      if (run_tricyl)
        tricyl::collide(&o_mesh, o_cyl, req, res);
      else
        fcl::collide(&o_mesh, o_cyl, req, res);
      const auto t1 = Clock::now();
      benchmark::DoNotOptimize(res);
      const double us =
          std::chrono::duration<double, std::micro>(t1 - t0).count();
      (run_tricyl ? t_tricyl : t_stock) += us;
      double& best = (run_tricyl ? best_tricyl : best_stock)[i];
      best = std::min(best, us);
    }
    tricyl_first = !tricyl_first;
    n += 1;
  }
  state.counters["tricyl_us"] = t_tricyl / n;
  state.counters["stock_us"] = t_stock / n;
  state.counters["ratio"] = t_stock / t_tricyl;
  // The fastest call per pose, summed over the poses: what each path costs
  // when nothing else interrupts it (a call preempted by the hypervisor
  // counts in the means above, not here). Needs every pose run at least
  // once on each path, which a run of >= 256 iterations gives.
  if (n >= kPoses) {
    double bt = 0, bs = 0;
    for (int p = 0; p < kPoses; ++p) {
      bt += best_tricyl[std::size_t(p)];
      bs += best_stock[std::size_t(p)];
    }
    state.counters["best_tricyl_us"] = bt / kPoses;
    state.counters["best_stock_us"] = bs / kPoses;
    state.counters["best_ratio"] = bs / bt;
  }
}

void registerAll() {
  // Grazing scenes (half the poses touching a face at offsets 0 .. 1e-3 of
  // the diagonal), cold (each call a new pose) and warm (third call).
  for (const char* file : {"env.obj", "bunny.obj", "rob.obj"})
    for (bool exhaustive : {false, true})
      for (bool warm : {false, true})
        benchmark::RegisterBenchmark(
            (std::string("paired_grazing/") + file +
             (exhaustive ? "/exhaustive" : "/first_hit") +
             (warm ? "/warm" : "/cold"))
                .c_str(),
            BM_PairedCollide, file, exhaustive, true, warm);
  for (const char* file : {"env.obj", "bunny.obj"})
    for (bool exhaustive : {false, true})
      benchmark::RegisterBenchmark((std::string("paired/") + file +
                                    (exhaustive ? "/exhaustive" : "/first_hit"))
                                       .c_str(),
                                   BM_PairedCollide, file, exhaustive, false,
                                   false);

  for (const char* file : {"env.obj", "bunny.obj"})
    for (bool exhaustive : {false, true})
      for (bool contact : {false, true}) {
        const std::string base = std::string(file) + "/" +
                                 (exhaustive ? "exhaustive" : "first_hit") +
                                 (contact ? "/contact" : "/bool");
        benchmark::RegisterBenchmark(("tricyl/" + base).c_str(), BM_Collide,
                                     file, Which::kTricyl, exhaustive, contact);
        benchmark::RegisterBenchmark(("solver/" + base).c_str(), BM_Collide,
                                     file, Which::kSolver, exhaustive, contact);
        benchmark::RegisterBenchmark(("stock/" + base).c_str(), BM_Collide,
                                     file, Which::kStock, exhaustive, contact);
        if (exhaustive && !contact)
          benchmark::RegisterBenchmark(("traversal/" + base).c_str(),
                                       BM_Collide, file, Which::kTraversal,
                                       exhaustive, contact);
      }
}

}  // namespace

int main(int argc, char** argv) {
  registerAll();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
