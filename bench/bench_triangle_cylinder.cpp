// Scalar triangle-cylinder Boolean: tricyl (exact, double and float) against
// FCL 0.7's GJKSolver_libccd<double>::shapeTriangleIntersect with
// collision_tolerance = 1e-6 (the value fcl::collide sets), on the same
// pre-generated cases of compare/scenes.h, in the same binary.
// Reported time is per query (items_per_second inverted).
#include <benchmark/benchmark.h>

#include <vector>

#include "scenes.h"
#include "tricyl/triangle_cylinder.h"

#ifdef TRICYL_BENCH_WITH_FCL
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>
#endif

namespace {

using tricyl::scenes::Family;
using tricyl::scenes::TriCase;

constexpr int kCases = 4096;

const std::vector<TriCase>& cases(Family f) {
  static std::vector<TriCase> store[6];
  auto& v = store[int(f)];
  if (v.empty())
    for (int i = 0; i < kCases; ++i)
      v.push_back(tricyl::scenes::generate(f, 7, std::uint64_t(i)));
  return v;
}

template <class S>
struct Narrowed {
  tricyl::Cylinder<S> cyl;
  tricyl::Pose<S> pose;
  tricyl::Triangle<S> tri;
};

template <class S>
std::vector<Narrowed<S>> narrowed(Family f) {
  std::vector<Narrowed<S>> out;
  auto n = [](const tricyl::Vec3<double>& v) {
    return tricyl::Vec3<S>{S(v.x), S(v.y), S(v.z)};
  };
  for (const TriCase& k : cases(f)) {
    Narrowed<S> c;
    c.cyl = {S(k.cyl.radius), S(k.cyl.lz)};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) c.pose.R[i][j] = S(k.pose.R[i][j]);
    c.pose.t = n(k.pose.t);
    c.tri = {n(k.tri.a), n(k.tri.b), n(k.tri.c)};
    out.push_back(c);
  }
  return out;
}

template <class S>
void BM_Tricyl(benchmark::State& state) {
  const auto v = narrowed<S>(Family(state.range(0)));
  size_t i = 0;
  long hits = 0;
  for (auto _ : state) {
    const auto& c = v[i];
    hits += tricyl::tryIntersect(c.cyl, c.pose, c.tri) ==
            tricyl::Answer::kIntersect;
    i = (i + 1 == v.size()) ? 0 : i + 1;
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(tricyl::scenes::familyName(Family(state.range(0))));
}

#ifdef TRICYL_BENCH_WITH_FCL
void BM_FclLibccd(benchmark::State& state) {
  const auto& v = cases(Family(state.range(0)));
  struct F {
    fcl::Cylinderd cyl;
    fcl::Transform3d tf;
    fcl::Vector3d a, b, c;
  };
  std::vector<F> fv;
  for (const TriCase& k : v) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) tf.linear()(i, j) = k.pose.R[i][j];
    tf.translation() = fcl::Vector3d(k.pose.t.x, k.pose.t.y, k.pose.t.z);
    fv.push_back({fcl::Cylinderd(k.cyl.radius, k.cyl.lz),
                  tf,
                  {k.tri.a.x, k.tri.a.y, k.tri.a.z},
                  {k.tri.b.x, k.tri.b.y, k.tri.b.z},
                  {k.tri.c.x, k.tri.c.y, k.tri.c.z}});
  }
  fcl::detail::GJKSolver_libccd<double> solver;
  solver.collision_tolerance = 1e-6;
  size_t i = 0;
  long hits = 0;
  for (auto _ : state) {
    const F& c = fv[i];
    hits += solver.shapeTriangleIntersect(c.cyl, c.tf, c.a, c.b, c.c, nullptr,
                                          nullptr, nullptr);
    i = (i + 1 == fv.size()) ? 0 : i + 1;
  }
  benchmark::DoNotOptimize(hits);
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(tricyl::scenes::familyName(Family(state.range(0))));
}
// Not thin or aligned: libccd can loop forever there (issue 9); the harness
// runs those under a time limit instead.
BENCHMARK(BM_FclLibccd)
    ->Arg(int(Family::kUniform))
    ->Arg(int(Family::kNear))
    ->Arg(int(Family::kFar))
    ->Arg(int(Family::kSliver));
#endif

BENCHMARK_TEMPLATE(BM_Tricyl, double)->DenseRange(0, 5);
BENCHMARK_TEMPLATE(BM_Tricyl, float)
    ->Arg(int(Family::kUniform))
    ->Arg(int(Family::kNear));

}  // namespace

BENCHMARK_MAIN();
