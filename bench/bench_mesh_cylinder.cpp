// SPDX-License-Identifier: BSD-3-Clause
// The batch mesh scan against the scalar kernel and FCL, in one
// binary. Counter `ns_per_tri`: wall time per triangle of the mesh.
//
//   Grid/<variant>/<N>   a wavy grid of N triangles (2 per cell, vertices
//                        shared), in cache up to N ~ 1e5; a tilted cylinder
//                        (r = 2 %, lz = 10 % of the grid's width) crossing
//                        the surface at the centre.
//   Mesh/<variant>/<k>   bunny.obj / env.obj (k = 0 / 1), the cylinder at a
//                        seeded grazing placement (compare/mesh_scenes.h).
// Variants:
//   Scalar           tryIntersect on every triangle (the kernel alone)
//   Batch{Cull,Local}{Portable,Avx2}
//                    intersectMask with the world-box cull / with the local
//                    outcodes, vertex pass in baseline or AVX2 code
//   BatchAny         intersectAny (stops at the first hit), cull on
//   FclMpr           FCL 0.7 GJKSolver_libccd::shapeTriangleIntersect per
//                    triangle, collision_tolerance 1e-6 (what fcl::collide
//                    sets): FCL's leaf test without its BVH
//   FclCollide{Stock,Tricyl}
//                    end-to-end exhaustive fcl::collide / tricyl::collide on
//                    a BVHModel<OBBRSS> of the same mesh (BVH built once)
// Run: ./build/bench/bench_mesh_cylinder --benchmark_min_time=0.2
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "mesh_scenes.h"
#include "tricyl/mesh_cylinder.h"
#include "tricyl/triangle_cylinder.h"

#if TRICYL_BENCH_WITH_FCL
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>

#include "tricyl/fcl_solver.h"
#endif

namespace {

using tricyl::BatchOptions;
using tricyl::Isa;
using V = tricyl::Vec3<double>;

struct Scene {
  std::vector<double> v;
  std::vector<std::uint32_t> f;
  tricyl::Cylinder<double> cyl{};
  tricyl::Pose<double> pose{};
  tricyl::MeshView<double> view() const {
    return {v.data(), v.size() / 3, f.data(), f.size() / 3};
  }
  tricyl::Triangle<double> tri(std::size_t i) const {
    auto at = [&](std::uint32_t k) {
      return V{v[3 * k], v[3 * k + 1], v[3 * k + 2]};
    };
    return {at(f[3 * i]), at(f[3 * i + 1]), at(f[3 * i + 2])};
  }
  std::size_t triangles() const { return f.size() / 3; }
};

/// A wavy grid with about n triangles over [-1, 1]^2.
Scene gridScene(std::int64_t n) {
  Scene s;
  const int cells = std::max(1, int(std::lround(std::sqrt(double(n) / 2))));
  for (int i = 0; i <= cells; ++i)
    for (int j = 0; j <= cells; ++j) {
      const double x = -1 + 2.0 * i / cells, y = -1 + 2.0 * j / cells;
      s.v.insert(s.v.end(), {x, y, 0.1 * std::sin(5 * x) * std::cos(4 * y)});
    }
  auto id = [cells](int i, int j) {
    return std::uint32_t(i * (cells + 1) + j);
  };
  for (int i = 0; i < cells; ++i)
    for (int j = 0; j < cells; ++j) {
      s.f.insert(s.f.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.f.insert(s.f.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  s.cyl = {0.04, 0.2};
  const double c = std::cos(0.5), sn = std::sin(0.5);
  s.pose = {{{1, 0, 0}, {0, c, -sn}, {0, sn, c}}, {0.013, -0.021, 0.01}};
  return s;
}

/// bunny.obj (k = 0) or env.obj (k = 1), merged into an indexed mesh; empty
/// when the file is absent.
Scene fileScene(int k) {
  Scene s;
  const std::string path =
      std::string(TRICYL_MESH_DIR) + (k == 0 ? "/bunny.obj" : "/env.obj");
  std::vector<tricyl::Triangle<double>> soup;
  try {
    soup = tricyl::compare::meshes::readObj(path);
  } catch (const std::exception&) {
    return s;
  }
  // Shared vertices merged again, as the file has them: the vertex pass
  // runs once per vertex.
  auto m = tricyl::compare::meshes::indexed(soup);
  s.v = std::move(m.v);
  s.f = std::move(m.f);
  V lo, hi;
  tricyl::compare::meshes::bounds(soup, &lo, &hi);
  const auto c = tricyl::compare::meshes::meshCase(soup, lo, hi, 20261122, 3);
  s.cyl = c.cyl;
  s.pose = c.pose;
  return s;
}

const Scene& cachedGrid(std::int64_t n) {
  static std::vector<std::pair<std::int64_t, Scene>> cache;
  for (const auto& [k, s] : cache)
    if (k == n) return s;
  cache.emplace_back(n, gridScene(n));
  return cache.back().second;
}

const Scene& cachedFile(int k) {
  static const Scene scenes[2] = {fileScene(0), fileScene(1)};
  return scenes[k];
}

void perTriangle(benchmark::State& state, const Scene& s) {
  state.counters["ns_per_tri"] =
      benchmark::Counter(double(s.triangles()) * 1e-9,
                         benchmark::Counter::kIsIterationInvariantRate |
                             benchmark::Counter::kInvert);
  state.counters["triangles"] = double(s.triangles());
}

// --------------------------------------------------------------- variants ---

void runScalar(benchmark::State& state, const Scene& s) {
  for (auto _ : state) {
    std::size_t hits = 0;
    for (std::size_t i = 0; i < s.triangles(); ++i)
      hits += tricyl::tryIntersect(s.cyl, s.pose, s.tri(i)) ==
              tricyl::Answer::kIntersect;
    benchmark::DoNotOptimize(hits);
  }
  perTriangle(state, s);
}

void runBatch(benchmark::State& state, const Scene& s, BatchOptions opt) {
  std::vector<std::uint64_t> mask((s.triangles() + 63) / 64);
  tricyl::BatchStats st;
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        tricyl::intersectMask(s.cyl, s.pose, s.view(), mask.data(), opt, &st));
    benchmark::ClobberMemory();
  }
  perTriangle(state, s);
  state.counters["hits"] = double(st.hits);
  state.counters["kernel_share"] =
      double(st.kernel) / double(std::max<std::size_t>(1, st.triangles));
  state.SetLabel(st.isa == Isa::kAvx2 ? "avx2" : "portable");
}

void runAny(benchmark::State& state, const Scene& s) {
  for (auto _ : state)
    benchmark::DoNotOptimize(tricyl::intersectAny(s.cyl, s.pose, s.view()));
  perTriangle(state, s);
}

#if TRICYL_BENCH_WITH_FCL
fcl::Transform3d toTransform(const tricyl::Pose<double>& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) tf.linear()(i, j) = p.R[i][j];
  tf.translation() = fcl::Vector3d(p.t.x, p.t.y, p.t.z);
  return tf;
}

void runFclMpr(benchmark::State& state, const Scene& s) {
  fcl::detail::GJKSolver_libccd<double> solver;
  solver.collision_tolerance = 1e-6;
  const fcl::Cylinderd cyl(s.cyl.radius, s.cyl.lz);
  const fcl::Transform3d tf = toTransform(s.pose);
  std::vector<fcl::Vector3d> pts;
  for (std::size_t k = 0; k < s.v.size(); k += 3)
    pts.emplace_back(s.v[k], s.v[k + 1], s.v[k + 2]);
  for (auto _ : state) {
    std::size_t hits = 0;
    for (std::size_t i = 0; i < s.triangles(); ++i)
      hits += solver.shapeTriangleIntersect(
          cyl, tf, pts[s.f[3 * i]], pts[s.f[3 * i + 1]], pts[s.f[3 * i + 2]],
          nullptr, nullptr, nullptr);
    benchmark::DoNotOptimize(hits);
  }
  perTriangle(state, s);
}

void runFclCollide(benchmark::State& state, const Scene& s, bool tricyl_path) {
  std::vector<fcl::Vector3d> pts;
  for (std::size_t k = 0; k < s.v.size(); k += 3)
    pts.emplace_back(s.v[k], s.v[k + 1], s.v[k + 2]);
  std::vector<fcl::Triangle> tris;
  for (std::size_t i = 0; i < s.triangles(); ++i)
    tris.emplace_back(s.f[3 * i], s.f[3 * i + 1], s.f[3 * i + 2]);
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel();
  model->addSubModel(pts, tris);
  model->endModel();
  const auto cyl = std::make_shared<fcl::Cylinderd>(s.cyl.radius, s.cyl.lz);
  const fcl::Transform3d tf = toTransform(s.pose);
  const fcl::CollisionRequestd request(1u << 20, false);
  for (auto _ : state) {
    fcl::CollisionResultd result;
    if (tricyl_path)
      tricyl::collide<double>(model.get(), fcl::Transform3d::Identity(),
                              cyl.get(), tf, request, result);
    else
      fcl::collide(model.get(), fcl::Transform3d::Identity(), cyl.get(), tf,
                   request, result);
    benchmark::DoNotOptimize(result.numContacts());
  }
  perTriangle(state, s);
}
#endif

// ------------------------------------------------------------ registration ---

constexpr BatchOptions kCullPortable{true, Isa::kPortable};
constexpr BatchOptions kCullAvx2{true, Isa::kAvx2};
constexpr BatchOptions kLocalPortable{false, Isa::kPortable};
constexpr BatchOptions kLocalAvx2{false, Isa::kAvx2};

void gridSizes(benchmark::internal::Benchmark* b) {
  for (std::int64_t n = 64; n <= (1 << 20); n *= 4) b->Arg(n);
}

template <class F>
void grid(benchmark::State& state, F f) {
  f(state, cachedGrid(state.range(0)));
}

template <class F>
void file(benchmark::State& state, F f) {
  const Scene& s = cachedFile(int(state.range(0)));
  if (s.f.empty()) {
    state.SkipWithError("mesh file not found in TRICYL_MESH_DIR");
    for (auto _ : state) {
    }
    return;
  }
  f(state, s);
}

#define TRICYL_BENCH_BOTH(Name, Lambda)                    \
  BENCHMARK_CAPTURE(grid, Name, Lambda)->Apply(gridSizes); \
  BENCHMARK_CAPTURE(file, Name, Lambda)->DenseRange(0, 1);

auto scalar = [](benchmark::State& st, const Scene& s) { runScalar(st, s); };
auto cull_portable = [](benchmark::State& st, const Scene& s) {
  runBatch(st, s, kCullPortable);
};
auto cull_avx2 = [](benchmark::State& st, const Scene& s) {
  runBatch(st, s, kCullAvx2);
};
auto local_portable = [](benchmark::State& st, const Scene& s) {
  runBatch(st, s, kLocalPortable);
};
auto local_avx2 = [](benchmark::State& st, const Scene& s) {
  runBatch(st, s, kLocalAvx2);
};
auto any = [](benchmark::State& st, const Scene& s) { runAny(st, s); };

TRICYL_BENCH_BOTH(Scalar, scalar)
TRICYL_BENCH_BOTH(BatchCullPortable, cull_portable)
TRICYL_BENCH_BOTH(BatchCullAvx2, cull_avx2)
TRICYL_BENCH_BOTH(BatchLocalPortable, local_portable)
TRICYL_BENCH_BOTH(BatchLocalAvx2, local_avx2)
TRICYL_BENCH_BOTH(BatchAny, any)

#if TRICYL_BENCH_WITH_FCL
auto fcl_mpr = [](benchmark::State& st, const Scene& s) { runFclMpr(st, s); };
auto fcl_stock = [](benchmark::State& st, const Scene& s) {
  runFclCollide(st, s, false);
};
auto fcl_tricyl = [](benchmark::State& st, const Scene& s) {
  runFclCollide(st, s, true);
};
TRICYL_BENCH_BOTH(FclMpr, fcl_mpr)
TRICYL_BENCH_BOTH(FclCollideStock, fcl_stock)
TRICYL_BENCH_BOTH(FclCollideTricyl, fcl_tricyl)
#endif

}  // namespace

BENCHMARK_MAIN();
