// SPDX-License-Identifier: BSD-3-Clause
// The cylinder query family against the straightforward formulas
// of the sources (seeds/001 pseudo-code, Freesteel's slab-and-quadratic
// interval for the segment and the line, and Freesteel's three-surfaces
// method for the line) in plain double. Inputs: 4096 pre-generated cases of one
// family (compare/query_scenes.h, fixed seed), cycled; the figure is ns per
// query. The source formulas take the endpoint form (O, N, L, R), derived once
// per case from the pose (N = third column of R, O = t - N L/2), outside the
// timed loop; tricyl takes the pose as given.
//
//   ./bench_queries --benchmark_repetitions=5
//   --benchmark_report_aggregates_only
#include <benchmark/benchmark.h>

#ifdef TRICYL_BENCH_WITH_FCL
#include "fcl_sphere_cases.h"
#endif

#include <cmath>
#include <vector>

#include "query_cases.h"
#include "query_scenes.h"
#include "tricyl/line_cylinder.h"
#include "tricyl/tricyl.h"
#include "walk.h"

namespace {

using tricyl::qscenes::Family;
using tricyl::qscenes::Query;
using tricyl::qscenes::QueryCase;
using V = tricyl::Vec3<double>;

struct Src {  // the sources' endpoint form
  V O, N;
  double L, R, rho;
  V p, q;
};

constexpr int kCases = tricyl::bench::kQueryCases;

std::vector<QueryCase> cases(Query q, Family f) {
  return tricyl::bench::queryCases(q, f);
}

std::vector<Src> sources(const std::vector<QueryCase>& cs, bool cone) {
  std::vector<Src> out;
  for (const auto& k : cs) {
    Src s;
    const auto& R = k.pose.R;
    s.N = {R[0][2], R[1][2], R[2][2]};
    s.L = k.cyl.lz;
    s.R = k.cyl.radius;
    const double h = s.L / 2;
    // Cylinder: O at the bottom (local z = -h). Cone: the apex (local
    // z = +h), N pointing into the cone (-z).
    if (cone) {
      s.O = {k.pose.t.x + s.N.x * h, k.pose.t.y + s.N.y * h,
             k.pose.t.z + s.N.z * h};
      s.N = {-s.N.x, -s.N.y, -s.N.z};
    } else {
      s.O = {k.pose.t.x - s.N.x * h, k.pose.t.y - s.N.y * h,
             k.pose.t.z - s.N.z * h};
    }
    s.rho = k.rho;
    s.p = k.p;
    s.q = k.q;
    out.push_back(s);
  }
  return out;
}

inline V sub(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline V axpy(V a, double s, V b) {
  return {a.x + s * b.x, a.y + s * b.y, a.z + s * b.z};
}

// --- The sources, transcribed (seeds/001) ---------------------------------

bool srcPointInCylinder(const Src& c, V P) {
  const V v = sub(P, c.O);
  const double dp = dot(v, c.N);
  if (dp < 0 || dp > c.L) return false;
  const V t = axpy(v, -dp, c.N);
  return !(dot(t, t) > c.R * c.R);
}

bool srcPointInCone(const Src& c, V P) {
  const V v = sub(P, c.O);
  const double dp = dot(v, c.N);
  if (dp < 0 || dp > c.L) return false;
  const V t = axpy(v, -dp, c.N);
  const double r = dp * c.R / c.L;
  return !(dot(t, t) > r * r);
}

bool srcSphereCylinder(const Src& c, V C, double r) {
  const V oc = sub(C, c.O);
  const double dp = dot(oc, c.N);
  if (dp > c.L + r || dp < -r) return false;
  const V t = axpy(oc, -dp, c.N);
  const double t2 = dot(t, t);
  if (dp > c.L) {
    const double f = std::sqrt(r * r - (dp - c.L) * (dp - c.L));
    return !(t2 > (c.R + f) * (c.R + f));
  } else if (dp >= 0) {
    return !(t2 > (c.R + r) * (c.R + r));
  }
  const double f = std::sqrt(r * r - dp * dp);
  return !(t2 > (c.R + f) * (c.R + f));
}

// The source's segment test (incomplete: it misses some hits), as written.
bool srcSegmentCylinder(const Src& c, V P0, V P1) {
  const V V1 = sub(P1, P0);
  const V d0 = sub(P0, c.O);
  const double dp0 = dot(d0, c.N);
  if (dp0 > c.L) return false;
  if (dot(sub(P1, c.O), c.N) < 0) return false;
  const V F = axpy(d0, -dp0, c.N);
  const V G = axpy(V1, -dot(V1, c.N), c.N);
  const double A = dot(G, G), B = 2 * dot(F, G), C = dot(F, F) - c.R * c.R;
  if (A > 0) {
    const double disc = B * B - 4 * A * C;
    if (disc < 0) return false;
    const double sq = std::sqrt(disc);
    const double t0 = (-B - sq) / (2 * A), t1 = (-B + sq) / (2 * A);
    return (t0 >= 0 && t0 <= 1) || (t1 >= 0 && t1 <= 1);
  }
  return C <= 0;
}

// Freesteel's "intersection of two volumes" in plain double: the slab
// interval and the infinite-cylinder interval, intersected with [0, 1].
bool srcClip(const Src& c, V P0, V P1, double* lo, double* hi) {
  const V d = sub(P1, P0);
  const V w = sub(P0, c.O);
  const double m0 = dot(w, c.N), md = dot(d, c.N);
  double a = 0, b = 1;
  if (md != 0) {
    double s0 = -m0 / md, s1 = (c.L - m0) / md;
    if (s0 > s1) std::swap(s0, s1);
    a = std::max(a, s0);
    b = std::min(b, s1);
  } else if (m0 < 0 || m0 > c.L) {
    return false;
  }
  const V F = axpy(w, -m0, c.N), G = axpy(d, -md, c.N);
  const double A = dot(G, G), B = dot(F, G), C = dot(F, F) - c.R * c.R;
  if (A > 0) {
    const double disc = B * B - A * C;
    if (disc < 0) return false;
    const double sq = std::sqrt(disc);
    a = std::max(a, (-B - sq) / A);
    b = std::min(b, (-B + sq) / A);
  } else if (C > 0) {
    return false;
  }
  *lo = a;
  *hi = b;
  return a <= b;
}

// --- Freesteel, "Line intersecting a finite cylinder" (seeds/002) --------
// The line p (1 - s) + q s, every real s. For p == q the first returns
// [-inf, inf] or nothing, the second (no surface crossed) nothing.

// "The finite cylinder expressed as an intersection of two volumes": the
// slab interval and the infinite-cylinder interval, intersected.
bool srcLineSlab(const Src& c, V P0, V P1, double* lo, double* hi) {
  const V d = sub(P1, P0);
  const V w = sub(P0, c.O);
  const double m0 = dot(w, c.N), md = dot(d, c.N);
  double a = -INFINITY, b = INFINITY;
  if (md != 0) {
    double s0 = -m0 / md, s1 = (c.L - m0) / md;
    if (s0 > s1) std::swap(s0, s1);
    a = s0;
    b = s1;
  } else if (m0 < 0 || m0 > c.L) {
    return false;
  }
  const V F = axpy(w, -m0, c.N), G = axpy(d, -md, c.N);
  const double A = dot(G, G), B = dot(F, G), C = dot(F, F) - c.R * c.R;
  if (A > 0) {
    const double disc = B * B - A * C;
    if (disc < 0) return false;
    const double sq = std::sqrt(disc);
    a = std::max(a, (-B - sq) / A);
    b = std::min(b, (-B + sq) / A);
  } else if (C > 0) {
    return false;
  }
  *lo = a;
  *hi = b;
  return a <= b;
}

// "The cylinder considered as independent surfaces": the roots on the side
// surface with 0 <= m <= L, and the two end-disk crossings within r; the
// interval is [min, max] of what was found. Cracks at the rims.
bool srcLineSurfaces(const Src& c, V P0, V P1, double* lo, double* hi) {
  const V d = sub(P1, P0);
  const V w = sub(P0, c.O);
  const double m0 = dot(w, c.N), md = dot(d, c.N);
  const V F = axpy(w, -m0, c.N), G = axpy(d, -md, c.N);
  double a = INFINITY, b = -INFINITY;
  auto found = [&](double s) {
    a = std::min(a, s);
    b = std::max(b, s);
  };
  const double A = dot(G, G), B = dot(F, G), C = dot(F, F) - c.R * c.R;
  if (A > 0) {
    const double disc = B * B - A * C;
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      for (double s : {(-B - sq) / A, (-B + sq) / A}) {
        const double m = m0 + s * md;
        if (m >= 0 && m <= c.L) found(s);
      }
    }
  }
  if (md != 0) {
    for (double plane : {0.0, c.L}) {
      const double s = (plane - m0) / md;
      const V x = axpy(F, s, G);
      if (dot(x, x) <= c.R * c.R) found(s);
    }
  }
  *lo = a;
  *hi = b;
  return a <= b;
}

// --- Benchmarks ------------------------------------------------------------

Family familyOf(const benchmark::State& st) { return Family(st.range(0)); }

void setLabel(benchmark::State& st) {
  st.SetLabel(tricyl::qscenes::familyName(familyOf(st)));
}

// Cases in a new order on every pass (bench/walk.h): a fixed sequence of a
// few thousand queries is one the branch predictor learns.
template <class F>
void run(benchmark::State& st, const F& f) {
  tricyl::bench::Walk walk(kCases);
  for (auto _ : st) benchmark::DoNotOptimize(f(int(walk.next())));
  st.SetItemsProcessed(st.iterations());
  setLabel(st);
}

void BM_PointCylinder_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kPointCylinder, familyOf(st));
  run(st,
      [&](int i) { return tricyl::contains(cs[i].cyl, cs[i].pose, cs[i].p); });
}
void BM_PointCylinder_source(benchmark::State& st) {
  const auto ss = sources(cases(Query::kPointCylinder, familyOf(st)), false);
  run(st, [&](int i) { return srcPointInCylinder(ss[i], ss[i].p); });
}
void BM_PointCone_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kPointCone, familyOf(st));
  run(st, [&](int i) {
    return tricyl::contains(
        tricyl::Cone<double>{cs[i].cyl.radius, cs[i].cyl.lz}, cs[i].pose,
        cs[i].p);
  });
}
void BM_PointCone_source(benchmark::State& st) {
  const auto ss = sources(cases(Query::kPointCone, familyOf(st)), true);
  run(st, [&](int i) { return srcPointInCone(ss[i], ss[i].p); });
}
void BM_Sphere_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kSphere, familyOf(st));
  run(st, [&](int i) {
    return tricyl::intersect(cs[i].cyl, cs[i].pose,
                             tricyl::Sphere<double>{cs[i].p, cs[i].rho});
  });
}
#ifdef TRICYL_BENCH_WITH_FCL
// FCL 0.7's own sphere-cylinder test (primitive_shape_algorithm,
// tolerance-based), the one fcl::collide uses for this pair.
void BM_Sphere_fcl(benchmark::State& st) {
  const tricyl::bench::FclSphereCases fc(cases(Query::kSphere, familyOf(st)));
  run(st, [&](int i) { return fc.intersect(std::size_t(i)); });
}
#endif
void BM_Sphere_source(benchmark::State& st) {
  const auto ss = sources(cases(Query::kSphere, familyOf(st)), false);
  run(st, [&](int i) { return srcSphereCylinder(ss[i], ss[i].p, ss[i].rho); });
}
void BM_Segment_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kSegment, familyOf(st));
  run(st, [&](int i) {
    return tricyl::intersect(cs[i].cyl, cs[i].pose,
                             tricyl::Segment<double>{cs[i].p, cs[i].q});
  });
}
void BM_Segment_source(benchmark::State& st) {
  const auto ss = sources(cases(Query::kSegment, familyOf(st)), false);
  run(st, [&](int i) { return srcSegmentCylinder(ss[i], ss[i].p, ss[i].q); });
}
void BM_Clip_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kSegment, familyOf(st));
  run(st, [&](int i) {
    const auto iv = tricyl::clip(cs[i].cyl, cs[i].pose,
                                 tricyl::Segment<double>{cs[i].p, cs[i].q});
    return iv ? iv->lo + iv->hi : -1.0;
  });
}
void BM_Clip_source(benchmark::State& st) {
  const auto ss = sources(cases(Query::kSegment, familyOf(st)), false);
  run(st, [&](int i) {
    double lo = 0, hi = 0;
    return srcClip(ss[i], ss[i].p, ss[i].q, &lo, &hi) ? lo + hi : -1.0;
  });
}

// The line: tricyl's clip against the two formulas of the source. The
// counter "disagree" is the fraction of the 4096 cases whose Boolean
// differs from tricyl's exact one (computed outside the timed loop).
template <class F>
void lineSource(benchmark::State& st, const F& f) {
  const auto cs = cases(Query::kLine, familyOf(st));
  const auto ss = sources(cs, false);
  long disagree = 0;
  for (int i = 0; i < kCases; ++i) {
    double lo = 0, hi = 0;
    disagree += f(ss[i], ss[i].p, ss[i].q, &lo, &hi) !=
                tricyl::intersect(cs[i].cyl, cs[i].pose,
                                  tricyl::Line<double>{cs[i].p, cs[i].q});
  }
  run(st, [&](int i) {
    double lo = 0, hi = 0;
    return f(ss[i], ss[i].p, ss[i].q, &lo, &hi) ? lo + hi : -1.0;
  });
  st.counters["disagree"] = double(disagree) / kCases;
}
void BM_LineClip_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kLine, familyOf(st));
  run(st, [&](int i) {
    const auto iv = tricyl::clip(cs[i].cyl, cs[i].pose,
                                 tricyl::Line<double>{cs[i].p, cs[i].q});
    return iv ? iv->lo + iv->hi : -1.0;
  });
}
void BM_LineClip_sourceSlab(benchmark::State& st) {
  lineSource(st, srcLineSlab);
}
void BM_LineClip_sourceSurfaces(benchmark::State& st) {
  lineSource(st, srcLineSurfaces);
}
void BM_Line_tricyl(benchmark::State& st) {
  const auto cs = cases(Query::kLine, familyOf(st));
  run(st, [&](int i) {
    return tricyl::intersect(cs[i].cyl, cs[i].pose,
                             tricyl::Line<double>{cs[i].p, cs[i].q});
  });
}

void families(benchmark::internal::Benchmark* b) {
  for (Family f : tricyl::qscenes::kAllFamilies) b->Arg(int(f));
}

BENCHMARK(BM_PointCylinder_tricyl)->Apply(families);
BENCHMARK(BM_PointCylinder_source)->Apply(families);
BENCHMARK(BM_PointCone_tricyl)->Apply(families);
BENCHMARK(BM_PointCone_source)->Apply(families);
BENCHMARK(BM_Sphere_tricyl)->Apply(families);
BENCHMARK(BM_Sphere_source)->Apply(families);
#ifdef TRICYL_BENCH_WITH_FCL
BENCHMARK(BM_Sphere_fcl)->Apply(families);
#endif
BENCHMARK(BM_Segment_tricyl)->Apply(families);
BENCHMARK(BM_Segment_source)->Apply(families);
BENCHMARK(BM_Clip_tricyl)->Apply(families);
BENCHMARK(BM_Clip_source)->Apply(families);
BENCHMARK(BM_Line_tricyl)->Apply(families);
BENCHMARK(BM_LineClip_tricyl)->Apply(families);
BENCHMARK(BM_LineClip_sourceSlab)->Apply(families);
BENCHMARK(BM_LineClip_sourceSurfaces)->Apply(families);

}  // namespace
