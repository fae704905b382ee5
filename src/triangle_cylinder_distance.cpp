// SPDX-License-Identifier: BSD-3-Clause
// tricyl::distance: a double pass that finds the nearest pair, a lean
// re-evaluation of its best candidate with double-word vertices (which
// usually certifies the distance to 8 ulps and, with it, that the pair is
// disjoint), the exact Boolean for the zero test whenever no certified
// lower bound proves the pair disjoint, and a double-word refinement of the
// nearest candidates when the lean one does not certify. Method and error
// bound: docs/distance.md; the generic algorithm:
// src/triangle_cylinder_distance_impl.h.
#include "tricyl/triangle_cylinder_distance.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <utility>

#include "dd.h"
#include "eft.h"
#include "triangle_cylinder_distance_impl.h"
#include "tricyl/triangle_cylinder.h"

// `flatten` (inline the whole query into one function) except under the
// sanitizers, where the instrumented flattened function takes GCC tens of
// minutes and gigabytes to compile.
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define TRICYL_DIST_NO_FLATTEN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define TRICYL_DIST_NO_FLATTEN 1
#endif
#endif
#if defined(TRICYL_DIST_NO_FLATTEN)
// Under the sanitizers also no FMA clone, and GCC's -O1 for this file: the
// instrumented -O2 build of the double-word templates took GCC over ten
// minutes and 5 GB (the sanitizer jobs test behaviour, not speed); the
// large steps are kept out of line there (TRICYL_DIST_NOINLINE): 7 s.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC optimize("O1")
#endif
#define TRICYL_DIST_FLATTEN
#define TRICYL_DIST_FLATTEN_ONLY noinline
#define TRICYL_DIST_NOINLINE __attribute__((noinline))
#else
#define TRICYL_DIST_FLATTEN , flatten
#define TRICYL_DIST_FLATTEN_ONLY flatten
#define TRICYL_DIST_NOINLINE
#endif

// The FMA copy of the kernel (distanceDoubleFma below), and the rare steps
// kept out of line from the flattened kernel (TRICYL_DIST_RARE): each is
// its own function, flattened in turn and compiled for the same target as
// the kernel that calls it (FMA for detail::DDT<true>), so the kernel's
// usual path (validation, the double pass, the double-word vertices and
// the lean bound) stays compact in the instruction cache, and every step
// computes the same bits as when it was inlined (-ffp-contract=off: each
// operation is rounded as written wherever it is compiled).
#if TRICYL_FMA_DISPATCH && !defined(TRICYL_DIST_NO_FLATTEN)
#define TRICYL_DIST_FMA_DISPATCH 1
#else
#define TRICYL_DIST_FMA_DISPATCH 0
#endif
#if defined(TRICYL_DIST_NO_FLATTEN)
#define TRICYL_DIST_RARE __attribute__((noinline))
#define TRICYL_DIST_RARE_FMA __attribute__((noinline))
#else
#define TRICYL_DIST_RARE __attribute__((noinline, flatten))
#define TRICYL_DIST_RARE_FMA __attribute__((noinline, flatten, target("fma")))
#endif
// Which step answered a query, for a profiling driver that defines it
// (docs/distance.md, section 8): empty otherwise.
#ifndef TRICYL_DIST_PATH
#define TRICYL_DIST_PATH(k)
#endif

namespace tricyl {
namespace {

using detail::DD;
using detail::dist::Candidate;
using detail::dist::P3;
using detail::dist::Problem;

// Unit roundoffs of the two passes, as used by the error bound: double
// (u = 2^-53) and double-word, where every operation of src/dd.h is within
// 2^-101 of its operands' magnitudes (dd.h's error model, rounded up).
constexpr double kU = 0x1p-53;
constexpr double kUdd = 0x1p-101;
// The algorithm's rounding, in units of u_T times the problem's magnitude
// Mx = max |v_i| coordinate * sqrt 3 + r + h: docs/distance.md, section 4.
constexpr double kAlg = 32;
// The double pass is accepted when its certified error is at most this
// fraction of the distance (4 ulps at worst).
constexpr double kAcceptRel = 0x1p-50;
constexpr double kTightGap = 0x1p-52;
constexpr int kSolveIter = 100;
constexpr int kRefineIter = 240;
// Newton steps of the usual refinement (each doubles the correct bits
// from the double pass's parameter; it stops at a step below 2^-90).
constexpr int kFastNewton = 5;

inline double absd(double x) { return std::fabs(x); }
inline double maxd(double a, double b) { return a > b ? a : b; }

// a + b + c summed in a canonical order (least and greatest first, then
// the middle one; branch-free min and max): the same double for any order
// of the terms, so that an exact signed permutation of the world axes
// (which permutes the terms of R^T (x - t)) leaves the double pulled-back
// triangle, and with it the whole double pass, unchanged. (A +-0 pair may
// come out either way, but a sum with a +0 term is not -0.) Its error is
// that of any order: within 2u (|a| + |b| + |c|).
inline double sum3(double a, double b, double c) {
  auto mn = [](double x, double y) { return x < y ? x : y; };
  auto mx = [](double x, double y) { return x > y ? x : y; };
  const double lo = mn(mn(a, b), c), hi = mx(mx(a, b), c);
  const double mid = mx(mn(a, b), mn(mx(a, b), c));
  return (lo + hi) + mid;
}

// The inputs `intersect` accepts: every number finite, r >= 0, lz >= 0
// (-0 passes; NaN fails every comparison). x - x is 0 exactly for a
// finite x and NaN for an infinite or NaN one.
bool validInputs(const Cylinder<double>& c, const Pose<double>& p,
                 const Triangle<double>& t) {
  double z = c.radius - c.radius + (c.lz - c.lz);
  for (const auto& row : p.R)
    for (double x : row) z += x - x;
  const Vec3<double>* v[4] = {&t.a, &t.b, &t.c, &p.t};
  for (const auto* x : v) z += (x->x - x->x) + (x->y - x->y) + (x->z - x->z);
  return z == 0 && c.radius >= 0 && c.lz >= 0;
}

// v 2^e (std::ldexp: no power of two is formed, so e may exceed the
// exponent range of a double).
Vec3<double> scaled(const Vec3<double>& v, int e) {
  return {std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)};
}

struct Pass {
  // Edges 0..2 (each written whole by doublePass), face 3 (by addFace, or
  // invalid): not zeroed first.
  Candidate<double> cand[4] = {Candidate<double>(Candidate<double>::Unset{}),
                               Candidate<double>(Candidate<double>::Unset{}),
                               Candidate<double>(Candidate<double>::Unset{}),
                               Candidate<double>(Candidate<double>::Unset{})};
  bool face_cut = false;
  bool face_pending = false;  // cand[3] not computed yet (addFace)
  int best = -1;
};

// The face's candidate (faceCandidate) into the pass.
void addFace(const Problem<double>& P, Pass* pass) {
  bool cut = false;
  pass->cand[3] = detail::dist::faceCandidate(P, &cut);
  pass->face_cut = cut;
  pass->face_pending = false;
  if (pass->cand[3].valid &&
      (pass->best < 0 || pass->cand[3].f < pass->cand[pass->best].f))
    pass->best = 3;
}

// The vertex index of a candidate at an edge's end, else -1.
int vertexOf(const Candidate<double>& c) {
  if (c.kind > 2) return -1;
  if (c.s == 0) return detail::dist::kEdgeA[c.kind];
  if (c.s == 1) return detail::dist::kEdgeB[c.kind];
  return -1;
}

// The vertices' gradients g_i = v_i - P(v_i) and distances f_i = |g_i|,
// computed first: they decide whether the Boolean is needed before the
// rest of the double pass (solve).
struct VertexPass {
  P3<double> g[3];
  double f[3];
};

VertexPass vertexPass(const Problem<double>& P) {
  VertexPass out;
  for (int i = 0; i < 3; ++i) {
    out.g[i] = P.v[i] - detail::dist::project(P.v[i], P.r, P.h);
    out.f[i] = detail::dist::norm(out.g[i]);
  }
  return out;
}

// The double pass, from the vertices' g_i = v_i - P(v_i), f_i = |g_i|
// (vertexPass). An edge's phi'(0) and phi'(1) are g_a . d and g_b . d, so an
// edge whose minimum is at an end costs nothing more. For the others, the
// tangents of the convex f at both ends bound f from below (f >= f_a + s f'(0)
// and f >= f_b - (1 - s) f'(1), f' = phi' / f); where the two lines meet is a
// lower bound of the edge's minimum (the edge is skipped when it cannot
// beat the best so far) and the start of the Newton iteration.
TRICYL_DIST_NOINLINE Pass doublePass(const Problem<double>& P,
                                     const VertexPass& vp, double prune_slack) {
  Pass out;
  const P3<double>* g = vp.g;
  const double* f = vp.f;
  auto vertex = [&](int k, int i) {  // vertex i as edge k's candidate
    Candidate<double>& c = out.cand[k];
    c.valid = true;
    c.kind = k;
    c.s = i == detail::dist::kEdgeA[k] ? 0.0 : 1.0;
    c.p = P.v[i];
    c.q = P.v[i] - g[i];
    c.w = g[i];
    c.f = f[i];
  };
  // The best so far: the nearer end of the first edge that has the nearest
  // vertex (each edge's candidate is written once, below).
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k) {
    const int i = detail::dist::kEdgeA[k], j = detail::dist::kEdgeB[k];
    const double fk = f[i] <= f[j] ? f[i] : f[j];
    if (fk < best) {
      best = fk;
      out.best = k;
    }
  }
  for (int k = 0; k < 3; ++k) {
    const int i = detail::dist::kEdgeA[k], j = detail::dist::kEdgeB[k];
    const P3<double> d = P.v[j] - P.v[i];
    const double ga = detail::dist::dot(g[i], d),
                 gb = detail::dist::dot(g[j], d);
    if (!(ga < 0) || !(gb > 0)) {  // the minimum is at an end
      vertex(k, ga < 0 ? j : i);
      continue;
    }
    double s0 = 0.5;
    // (Only where both ends are well clear of the double pass's error:
    // near 0 the slopes f' = phi' / f are not accurate.)
    if (f[i] > 64 * prune_slack && f[j] > 64 * prune_slack) {
      const double sa = ga / f[i], sb = gb / f[j];  // f'(0) < 0 < f'(1)
      const double den = sb - sa;  // > 0 unless both slopes underflow
      const double t = den > 0 ? (f[i] + sb - f[j]) / den : 0.5;
      const double lb = f[i] + sa * (t < 0 ? 0 : (t > 1 ? 1 : t));
      if (lb > best * (1 + 0x1p-40) + prune_slack) {
        vertex(k, f[i] <= f[j] ? i : j);
        continue;
      }
      if (t > 0 && t < 1) s0 = t;
    }
    // The closed form first: where the edge's root lies in the barrel's
    // region (|z| <= h, rho > r), phi' = (1 - r/rho) p_xy . d_xy vanishes
    // exactly where p_xy . d_xy = 0, a linear equation in s; so it does
    // for an edge of constant z (d_z = 0: the slab's term (z - clamp(z))
    // d_z of phi' is 0) over the rim, where Newton's iteration would
    // crawl near a tangency (phi' of order (s - s*)^2 as rho -> r: a
    // triangle in or just off a cap plane). Otherwise the safeguarded
    // Newton iteration.
    double s = -1;
    const double dxy2 = d.x * d.x + d.y * d.y;
    if (dxy2 > detail::dist::kTinyDen) {
      const P3<double>& a = P.v[i];
      const double sb = -(a.x * d.x + a.y * d.y) / dxy2;
      if (sb > 0 && sb < 1) {
        const P3<double> p = a + d * sb;
        if ((absd(p.z) <= P.h || d.z == 0) && p.x * p.x + p.y * p.y > P.r * P.r)
          s = sb;
      }
    }
    if (!(s >= 0))
      s = detail::dist::edgeSolveIn(P.v[i], d, P.r, P.h, 0.0, 1.0, s0,
                                    kSolveIter, 0x1p-53, 0x1p-40);
    out.cand[k] = detail::dist::edgeCandidate(P, k, s);
    if (out.cand[k].f < best) {
      best = out.cand[k].f;
      out.best = k;
    }
  }
  // The face last, and only when the best vertex or edge point p fails
  // the optimality test of the convex f over T in double: its direction
  // w (p - P(p), orthogonal to the edge for an edge point) has w . (v - p)
  // >= 0 for the vertices v off its feature (then p is the minimiser, up
  // to the double pass's rounding, and the face's candidate cannot beat
  // it). The test only saves work: the refinements certify the result,
  // and complete the face (addFace) before anything but the lean one.
  {
    const Candidate<double>& c = out.cand[out.best];
    const int vb = vertexOf(c);
    bool kkt = c.f > 0;
    for (int v = 0; v < 3 && kkt; ++v) {
      if (v == vb || (vb < 0 && (v == detail::dist::kEdgeA[c.kind] ||
                                 v == detail::dist::kEdgeB[c.kind])))
        continue;
      kkt = detail::dist::dot(c.w, P.v[v] - c.p) > 0;
    }
    if (kkt)
      out.face_pending = true;
    else
      addFace(P, &out);
  }
  return out;
}

// The map back to the world, x = R y + t, in the units of the scaled
// problem: R and y may both have been scaled (distanceDouble), so R y is
// scaled back by 2^rexp.
struct WorldMap {
  const Pose<double>* pose;
  int rexp;
};

// x = R y + t in double from y rounded to double: within a few ulps of
// the world coordinates' magnitude (docs/distance.md, section 5).
Vec3<double> toWorld(const WorldMap& wm, const P3<double>& y) {
  const Pose<double>& pose = *wm.pose;
  const double c[3] = {y.x, y.y, y.z};
  const double t[3] = {pose.t.x, pose.t.y, pose.t.z};
  double out[3];
  for (int i = 0; i < 3; ++i) {
    const double ry =
        pose.R[i][0] * c[0] + pose.R[i][1] * c[1] + pose.R[i][2] * c[2];
    out[i] = t[i] + (wm.rexp == 0 ? ry : std::ldexp(ry, wm.rexp));
  }
  return {out[0], out[1], out[2]};
}
template <class DDx>
Vec3<double> toWorld(const WorldMap& wm, const P3<DDx>& y) {
  return toWorld(wm, P3<double>{double(y.x), double(y.y), double(y.z)});
}

template <class DDx>
DDx hSupport(const P3<DDx>& w, const DDx& r, const DDx& h) {
  return r * sqrt(w.x * w.x + w.y * w.y) + h * abs(w.z);
}

// The distance of a double-word point p to C and the direction of
// p - P(p), finished in double from the double-word differences where
// the cancellation is: e = rho - r = (rho^2 - r^2) / (rho + r) outside the
// barrel (rho = |p_xy|; rho^2 - r^2 in double-word), ez = |p_z| - h outside
// the slab, U = |(e, ez)|. Relative error of U (first order, from the
// roundings of rho, rho + r, the quotient, the squares, the sum and the
// square root): below 3.3 u (kLeanU rounds it up), plus the double-word
// roundings (absolute, within the slack of section 4). w = p - P(p) to a
// few ulps of its norm (its direction only matters to second order).
struct LeanPoint {
  double U;
  P3<double> w;
};
template <class DDx>
LeanPoint leanPoint(const P3<DDx>& p, double r, double h) {
  LeanPoint out{0, {0, 0, 0}};
  double ez = 0;
  if (p.z > DDx(h)) ez = double(p.z - DDx(h));
  if (p.z < DDx(-h)) ez = double(p.z + DDx(h));
  const DDx rho2 = p.x * p.x + p.y * p.y;
  const double t = double(rho2 - detail::mulD(DDx(r), r));
  double e = 0;
  if (t > 0) {
    const double rho = std::sqrt(double(rho2));
    e = t / (rho + r);
    const double k = e / rho;  // 1 - r / rho, in (0, 1]
    out.w = {double(p.x) * k, double(p.y) * k, 0};
  }
  out.w.z = ez;
  out.U = std::sqrt(e * e + ez * ez);
  return out;
}
constexpr double kLeanU = 4 * kU;  // relative error of LeanPoint::U
constexpr double kLeanL = 3 * kU;  // of the quotient num / |w| (leanRefine)

// The lean bounds' verdict (leanRefine, leanFace) for an upper bound U and
// a lower bound L of d, with their relative roundings (kLeanU, kLeanL) and
// the double-word allowance slack_dd: `consistent` when L_lo > 0 (the
// result proves the pair disjoint: the caller may not have asked the
// Boolean) and L_lo <= U_hi; then d = (U + L) / 2 with the bound
// max(U_hi - d, d - L_lo) + u d, `accepted` within kAcceptRel, or, as in
// refineFast, when U and L met (to their own final roundings) and it is
// the a-priori double-word allowance that is wider (d below about
// 2^-45 Mx).
struct LeanVerdict {
  bool consistent, accepted;
  double dist, err;
};
inline LeanVerdict leanVerdict(double U, double L, double slack_dd) {
  LeanVerdict v{false, false, 0, 0};
  const double u_hi = U * (1 + kLeanU) + slack_dd;
  const double l_lo = L * (1 - kLeanL) - slack_dd;
  if (!(l_lo > 0) || !(l_lo <= u_hi)) return v;
  v.consistent = true;
  v.dist = 0.5 * (U + L);
  v.err = maxd(u_hi - v.dist, v.dist - l_lo) + kU * v.dist;
  v.accepted = v.err <= kAcceptRel * v.dist ||
               (slack_dd > kTightGap * v.dist &&
                U - L <= (kLeanU + kLeanL + kTightGap) * v.dist);
  return v;
}

// An accepted lean result into *out: the point pd of T and pd - w of C
// (w = pd - P(pd), leanPoint) mapped to the world.
inline void writeLean(const LeanVerdict& v, const P3<double>& pd,
                      const P3<double>& w, const WorldMap& wm,
                      DistanceResult<double>* out) {
  if (!out) return;
  out->distance = v.dist;
  out->error_bound = v.err * (1 + 0x1p-50);
  out->point_on_triangle = toWorld(wm, pd);
  out->point_on_cylinder = toWorld(wm, pd - w);
}

// The lean refinement (the usual case, no iteration in double-word): the
// double pass's best candidate re-evaluated at its double parameter with
// the double-word vertices: U = leanPoint(p).U, an upper bound (p is a
// point of the triangle), and the separating-plane bound L of the
// direction w = leanPoint(p).w, made orthogonal to the edge in double-word
// for an edge point (W = w - D c, c = (w . D) / |D|^2: the residual W . D
// is 2u |w . D|, so min(W . a, W . b) loses nothing to first order),
//   L = (min_i W . v_i - r |W_xy| - h |W_z|) / |W|,
// numerator in double-word, quotient in double (relative error < 2.75 u).
// The distance is returned as (U + L) / 2 with the bound
// max(U_hi - d, d - L_lo) + u d. Accepted when that is within kAcceptRel
// of d; otherwise (a face candidate, an edge parameter too far from the
// root for its second-order error, bounds that do not meet) the caller
// runs refineFast. The vertices outside the plane's contact enter L only
// when a double evaluation cannot place them beyond it (as in
// refineFast). An accepted result also proves the pair disjoint (L_lo > 0).
template <class DDx, class VertexFn>
TRICYL_DIST_NOINLINE bool leanRefine(const Pass& pass, const Problem<double>& P,
                                     VertexFn&& vertex, double eps_y_d,
                                     double M, double slack_dd,
                                     const WorldMap& wm,
                                     DistanceResult<double>* out) {
  if (pass.best < 0 || pass.best > 2) return false;
  const Candidate<double>& cb = pass.cand[pass.best];
  if (!cb.valid) return false;
  const int vb = vertexOf(cb);
  const int i = vb >= 0 ? vb : detail::dist::kEdgeA[cb.kind];
  const int j = vb >= 0 ? vb : detail::dist::kEdgeB[cb.kind];
  const P3<DDx>& a = vertex(i);
  P3<DDx> d{};
  if (vb < 0) d = vertex(j) - a;
  // An edge point is a + d s: first (attempt 1) at the double pass's
  // parameter s. Where that does not certify and the double pass's point
  // lies in the slab |z| <= h, next (attempt 0) the barrel's closed form,
  // s* with p_xy . d_xy = 0, in double-word (s* = s_hi + s_lo): where the
  // edge's minimum is in the barrel's region, phi' = (1 - r/rho) p_xy .
  // d_xy vanishes exactly there. Near a tangency (rho - r tiny) phi' is
  // below the double pass's resolution over an interval of width about
  // sqrt(u M / |d|^2 / rho), and f grows by (s - s*)^2 |d|^2 / (2 rho)
  // across it, so the double parameter does not certify 8 ulps of a small
  // distance (and Newton's steps only shrink s - s* by 2/3 each in that
  // cubic regime). Last (attempt 2) s + sc, sc a Newton correction from
  // phi'(s) = w . d (w = p - P(p) to a few ulps, the product in
  // double-word) and the double phi''(s). Each attempt is certified on its
  // own (U: a point of T; L: a separating plane), whichever parameter it
  // used.
  double sc = 0, s_hi = cb.s, s_lo = 0;
  // (The closed form second: its double-word quotient is a long latency
  // chain, wasted where the double parameter certifies.)
  bool closed_open = vb < 0 && absd(cb.p.z) <= P.h, newton_open = false;
  int attempt = 1;
  for (int step = 0; step < 3; ++step) {
    if (step > 0) {
      attempt = -1;
      if (closed_open) {
        closed_open = false;
        const DDx dxy2 = d.x * d.x + d.y * d.y;
        if (dxy2.hi > detail::dist::kTinyDen) {
          const DDx sb = (a.x * d.x + a.y * d.y) / dxy2;  // -s*
          const double sh = sb.hi, sl = sb.lo;
          if (sh < 0 && sh > -1) {
            s_hi = -sh;
            s_lo = -sl;
            attempt = 0;
          }
        }
      }
      if (attempt < 0 && newton_open) {
        newton_open = false;
        attempt = 2;
      }
      if (attempt < 0) return false;
    }
    P3<DDx> p = a;
    if (vb < 0) {
      const double s = attempt == 0 ? s_hi : cb.s;
      p = {a.x + detail::mulD(d.x, s), a.y + detail::mulD(d.y, s),
           a.z + detail::mulD(d.z, s)};
      if (attempt == 0 && s_lo != 0)
        p = {p.x + DDx(d.x.hi * s_lo), p.y + DDx(d.y.hi * s_lo),
             p.z + DDx(d.z.hi * s_lo)};
      if (attempt == 2)
        p = {p.x + detail::mulD(d.x, sc), p.y + detail::mulD(d.y, sc),
             p.z + detail::mulD(d.z, sc)};
    }
    const LeanPoint lp = leanPoint(p, P.r, P.h);
    if (!(lp.U > 0)) {
      continue;
    }
    P3<DDx> W{DDx(lp.w.x), DDx(lp.w.y), DDx(lp.w.z)};
    DDx m;
    if (vb >= 0) {
      m = detail::mulD(a.x, lp.w.x) + detail::mulD(a.y, lp.w.y) +
          detail::mulD(a.z, lp.w.z);
    } else {
      // In the slab (w_z = 0) W stays horizontal: W_xy = w_xy - d_xy c.
      // Made orthogonal to the whole d, W would tilt by the rounding of
      // w . d (about u |w| |d|), and the cap's term h |W_z| of the
      // support function would cost L an absolute u h, not a relative one.
      const bool slab = lp.w.z == 0;
      const DDx wd = detail::mulD(d.x, lp.w.x) + detail::mulD(d.y, lp.w.y) +
                     (slab ? DDx(0) : detail::mulD(d.z, lp.w.z));
      const double dx = double(d.x), dy = double(d.y),
                   dz = slab ? 0.0 : double(d.z);
      const double dd = dx * dx + dy * dy + dz * dz;
      if (!(dd > detail::dist::kTinyDen)) {
        continue;
      }
      const double c = double(wd) / dd;
      W = {DDx(lp.w.x) - detail::mulD(d.x, c),
           DDx(lp.w.y) - detail::mulD(d.y, c),
           slab ? DDx(0) : DDx(lp.w.z) - detail::mulD(d.z, c)};
      const DDx ma = detail::dist::dot(W, a),
                mb = detail::dist::dot(W, vertex(j));
      m = ma < mb ? ma : mb;
    }
    const P3<double> wd{double(W.x), double(W.y), double(W.z)};
    const double w1 = absd(wd.x) + absd(wd.y) + absd(wd.z);
    const double margin = w1 * (eps_y_d + 5 * kU * M) * (1 + 0x1p-50);
    int in_bound = (1 << i) | (1 << j);  // the vertices in m
    for (int v = 0; v < 3; ++v) {
      if (v == i || v == j) continue;
      if (!(detail::dist::dot(wd, P.v[v]) - margin >=
            m.hi + 4 * kU * absd(m.hi))) {
        const DDx x = detail::dist::dot(W, vertex(v));
        if (x < m) m = x;
        in_bound |= 1 << v;
      }
    }
    const double ww = wd.x * wd.x + wd.y * wd.y + wd.z * wd.z;
    if (!(ww > detail::dist::kTinyDen)) {
      continue;
    }
    double L, U = lp.U;
    LeanPoint lq = lp;
    if (W.x == DDx(0) && W.y == DDx(0)) {
      // A vertical W (a point over a cap, W made orthogonal to an edge
      // parallel to it): the plane's bound is min_i sg z_i - h (sg the sign
      // of W_z) over the vertices in m, one rounding of a double-word
      // difference, with none of the products' roundings at the scale of
      // |W| |v| (which, for a distance far below the coordinates, would
      // exceed 8 ulps of it). When the vertex attaining it lies over the
      // cap's disk its distance is that same difference: U = L, the
      // vertex is the nearest point (a face parallel to the cap ties
      // every vertex; the double pass's choice among them may be off by
      // its own rounding).
      const double sg = W.z.hi > 0 ? 1.0 : -1.0;
      int vm = -1;
      DDx mz;
      for (int v = 0; v < 3; ++v) {
        if (!(in_bound & (1 << v))) continue;
        const DDx z = sg > 0 ? vertex(v).z : -vertex(v).z;
        if (vm < 0 || z < mz) {
          mz = z;
          vm = v;
        }
      }
      const DDx gap_z = mz - DDx(P.h);
      L = double(gap_z);
      const P3<DDx>& y = vertex(vm);
      if (L > 0 && !(detail::mulD(DDx(P.r), P.r) < y.x * y.x + y.y * y.y)) {
        U = L;
        p = y;
        lq.w = {0, 0, sg * L};
      }
    } else {
      const DDx hc = detail::mulD(sqrt(W.x * W.x + W.y * W.y), P.r) +
                     detail::mulD(abs(W.z), P.h);
      L = double(m - hc) / std::sqrt(ww);
    }
    if (!(L > 0)) {
      continue;
    }
    const LeanVerdict lv = leanVerdict(U, L, slack_dd);
    if (!lv.consistent) continue;
    if (!lv.accepted) {
      if (vb >= 0 || attempt != 1) continue;
      const int ki = detail::dist::kEdgeA[cb.kind];
      const P3<double> dd = P.v[detail::dist::kEdgeB[cb.kind]] - P.v[ki];
      const double g2 = detail::dist::edgeDphi(P.v[ki], dd, cb.s, P.r, P.h).g2;
      const DDx wdd = detail::mulD(d.x, lp.w.x) + detail::mulD(d.y, lp.w.y) +
                      detail::mulD(d.z, lp.w.z);
      if (!(g2 > detail::dist::kTinyDen)) continue;
      sc = -double(wdd) / g2;
      newton_open = absd(sc) < 0x1p-20;
      continue;
    }
    writeLean(lv, {double(p.x), double(p.y), double(p.z)}, lq.w, wm, out);
    return true;
  }
  return false;
}

// The lean refinement of a face candidate: the double pass's best is the
// face, whose plane H misses C (docs/distance.md, section 2, step 5). The
// separating plane is H itself: with n = e_a x e_b from the double-word
// vertices (the two shorter edges, as faceCandidate), in double-word,
// W = +-n towards the triangle and
//   L = (min_i W . v_i - r |W_xy| - h |W_z|) / |W|,
// numerator in double-word, quotient in double, as in leanRefine (the
// three W . v_i agree to the double-word rounding of n, so L is tight).
// U is the distance of a point of T: the double pass's face point p, as
// the barycentric coordinates (a, b) of the double triangle, rounded to
// double and kept inside T exactly (a, b >= 0, a + b <= 1 checked with a
// TwoSum), p = v0 + a (v1 - v0) + b (v2 - v0) in double-word. f is C^1
// with its gradient normal to H at the face's minimiser, so p's offset in
// the plane (a few ulps of the edges) costs U only its square. Accepted
// as leanRefine's results (within kAcceptRel, or bounds that met where
// the double-word allowance is the wider); an accepted result proves the
// pair disjoint (L_lo > 0). Otherwise refineFast runs.
template <class DDx, class VertexFn>
TRICYL_DIST_NOINLINE bool leanFace(const Pass& pass, const Problem<double>& P,
                                   VertexFn&& vertex, double slack_dd,
                                   const WorldMap& wm,
                                   DistanceResult<double>* out) {
  if (pass.best != 3 || pass.face_cut) return false;
  const Candidate<double>& cf = pass.cand[3];
  if (!cf.valid) return false;
  using detail::dist::dot;
  // Barycentric coordinates of the double face point in the double
  // triangle (Gram system of the edges from v0).
  const P3<double> f1 = P.v[1] - P.v[0], f2 = P.v[2] - P.v[0],
                   fp = cf.p - P.v[0];
  const double d00 = dot(f1, f1), d01 = dot(f1, f2), d11 = dot(f2, f2);
  const double d20 = dot(fp, f1), d21 = dot(fp, f2);
  const double den = d00 * d11 - d01 * d01;
  if (!(den > detail::dist::kTinyDen)) return false;
  const double ba = (d11 * d20 - d01 * d21) / den;
  const double bb = (d00 * d21 - d01 * d20) / den;
  double bs, be;
  detail::twoSum(ba, bb, bs, be);
  if (!(ba >= 0 && bb >= 0 && (bs < 1 || (bs == 1 && be <= 0)))) return false;
  const P3<DDx>& v0 = vertex(0);
  const P3<DDx>& v1 = vertex(1);
  const P3<DDx>& v2 = vertex(2);
  const P3<DDx> e01 = v1 - v0, e12 = v2 - v1, e20 = v0 - v2;
  // The longest edge from the double triangle (as faceCandidate; any two
  // edges give the same plane, the shorter ones cancel least).
  const P3<double> g12 = P.v[2] - P.v[1];
  const double l0 = d00, l1 = dot(g12, g12), l2 = d11;
  const int longest = l1 > l0 ? (l2 > l1 ? 2 : 1) : (l2 > l0 ? 2 : 0);
  const P3<DDx> n = longest == 0   ? detail::dist::cross(e12, e20)
                    : longest == 1 ? detail::dist::cross(e20, e01)
                                   : detail::dist::cross(e01, e12);
  const P3<double> nd{double(n.x), double(n.y), double(n.z)};
  // W points from C towards the triangle, as the double pass's w.
  const bool flip = dot(nd, cf.w) < 0;
  const P3<DDx> W = flip ? P3<DDx>{-n.x, -n.y, -n.z} : n;
  const P3<double> wd = flip ? P3<double>{-nd.x, -nd.y, -nd.z} : nd;
  const double ww = dot(wd, wd);
  if (!(ww > detail::dist::kTinyDen)) return false;
  DDx m = dot(W, v0);
  const DDx m1 = dot(W, v1), m2 = dot(W, v2);
  if (m1 < m) m = m1;
  if (m2 < m) m = m2;
  const DDx hc = detail::mulD(sqrt(W.x * W.x + W.y * W.y), P.r) +
                 detail::mulD(abs(W.z), P.h);
  const double L = double(m - hc) / std::sqrt(ww);
  if (!(L > 0)) return false;
  const P3<DDx> p{v0.x + detail::mulD(e01.x, ba) - detail::mulD(e20.x, bb),
                  v0.y + detail::mulD(e01.y, ba) - detail::mulD(e20.y, bb),
                  v0.z + detail::mulD(e01.z, ba) - detail::mulD(e20.z, bb)};
  const LeanPoint lp = leanPoint(p, P.r, P.h);
  const LeanVerdict lv = leanVerdict(lp.U, L, slack_dd);
  if (!lv.accepted) return false;
  writeLean(lv, {double(p.x), double(p.y), double(p.z)}, lp.w, wm, out);
  return true;
}

// The double-word pulled-back vertices, each formed once, when first
// asked for (by the lean refinement, refineFast or the general one).
template <class DDx, class MakeFn>
struct DDVertices {
  MakeFn& make;
  P3<DDx> y[3]{};
  bool have[3] = {false, false, false};
  const P3<DDx>& operator()(int v) {
    if (!have[v]) {
      y[v] = make(v);
      have[v] = true;
    }
    return y[v];
  }
  bool has(int v) const { return have[v]; }
};

// The usual refinement: the candidates of the double pass within its
// error of the best (usually the best alone), each re-solved in
// double-word: a vertex as it is, an edge point by two Newton steps from
// the double parameter, a face point in closed form. U is the least of
// their distances, L the greatest of their separating-plane bounds (each
// is a valid lower bound). The vertices outside a candidate enter its
// bound only if a double evaluation cannot show that they lie beyond the
// candidate's points along w (|w . v_j - fl(w_d . v_j)| <= |w_d|_1
// (eps_y + 5 u M), w_d = w rounded to double). Returns false when the
// result is not within kAcceptRel: the general refinement then runs.
template <class DDx, class VertexFn>
TRICYL_DIST_NOINLINE bool refineFast(const Pass& pass, const Problem<double>& P,
                                     VertexFn& ddVertex, double U, double tie,
                                     double eps_y_d, double M, double slack_dd,
                                     const WorldMap& wm,
                                     DistanceResult<double>* out) {
  const DDx r(P.r), h(P.h);
  auto& vertex = ddVertex;
  DDx Ubest(std::numeric_limits<double>::infinity()), Lbest(-1);
  P3<DDx> pb{}, qb{};
  bool done_vertex[3] = {false, false, false};
  for (int k = 0; k < 4; ++k) {
    const Candidate<double>& cb = pass.cand[k];
    if (!cb.valid || !(cb.f <= U + tie)) continue;
    const int vb = vertexOf(cb);
    if (vb >= 0) {
      if (done_vertex[vb]) continue;
      done_vertex[vb] = true;
    }
    DDx Ud, Ld;
    P3<DDx> p, q;
    if (cb.kind == 3) {
      Problem<DDx> Q;
      Q.r = r;
      Q.h = h;
      for (int v = 0; v < 3; ++v) Q.v[v] = vertex(v);
      bool cut = false;
      const Candidate<DDx> c = detail::dist::faceCandidate(Q, &cut);
      if (cut || !c.valid) return false;
      Ud = c.f;
      Ld = detail::dist::certify(Q, c.w);
      p = c.p;
      q = c.q;
    } else {
      P3<DDx> w;
      DDx m;
      if (vb >= 0) {
        p = vertex(vb);
        q = detail::dist::project(p, r, h);
        w = p - q;
        m = detail::dist::dot(w, p);
      } else {
        const int i = detail::dist::kEdgeA[cb.kind],
                  j = detail::dist::kEdgeB[cb.kind];
        const P3<DDx>& a = vertex(i);
        const P3<DDx> d = vertex(j) - a;
        DDx s(cb.s);
        for (int it = 0; it < kFastNewton; ++it) {
          const auto e = detail::dist::edgeDphi(a, d, s, r, h);
          if (!(e.g2 > DDx(detail::dist::kTinyDen))) break;
          const double step = double(e.g) / double(e.g2);
          if (!(absd(step) < 2)) break;
          s = s - DDx(step);
          if (s < DDx(0)) s = DDx(0);
          if (s > DDx(1)) s = DDx(1);
          // Quadratic convergence: after a step below 2^-45 the next one
          // would be below about 2^-90 (the certificate checks it).
          if (!(absd(step) > 0x1p-45)) break;
        }
        p = a + d * s;
        q = detail::dist::project(p, r, h);
        w = p - q;
        const DDx dd = detail::dist::dot(d, d);
        if (s > DDx(0) && s < DDx(1) && dd > DDx(detail::dist::kTinyDen))
          w = w - d * (detail::dist::dot(w, d) / dd);
        const DDx ma = detail::dist::dot(w, a),
                  mb = detail::dist::dot(w, vertex(j));
        m = ma < mb ? ma : mb;
      }
      Ud = detail::dist::norm(p - q);
      const P3<double> wd{double(w.x), double(w.y), double(w.z)};
      const double w1 = absd(wd.x) + absd(wd.y) + absd(wd.z);
      const double margin = w1 * (eps_y_d + 5 * kU * M) * (1 + 0x1p-50);
      for (int v = 0; v < 3; ++v) {
        if (vertex.has(v)) {
          const DDx x = detail::dist::dot(w, vertex(v));
          if (x < m) m = x;
        } else if (!(detail::dist::dot(wd, P.v[v]) - margin >=
                     m.hi + 4 * kU * absd(m.hi))) {
          const DDx x = detail::dist::dot(w, vertex(v));
          if (x < m) m = x;
        }
      }
      const DDx ww = detail::dist::dot(w, w);
      if (!(ww > DDx(detail::dist::kTinyDen))) return false;
      Ld = (m - hSupport(w, r, h)) / sqrt(ww);
    }
    if (Ud < Ubest) {
      Ubest = Ud;
      pb = p;
      qb = q;
    }
    if (Ld > Lbest) Lbest = Ld;
  }
  const double dist = double(Ubest);
  const double gap = double(Ubest - Lbest);
  const double err = (gap > 0 ? gap : 0) + slack_dd + kU * dist;
  // Accepted when certified within kAcceptRel, and also when the two
  // bounds met (the search found the minimum) but the a-priori rounding
  // allowance of double-word arithmetic is what exceeds kAcceptRel (a
  // distance below about 2^-45 of the problem's magnitude): the general
  // refinement, in the same arithmetic, could not do better.
  if (!(dist > 0) || !(gap >= -slack_dd) ||
      !(err <= kAcceptRel * dist || gap <= kTightGap * dist))
    return false;
  if (out) {
    out->distance = dist;
    out->error_bound = err * (1 + 0x1p-50);
    out->point_on_triangle = toWorld(wm, pb);
    out->point_on_cylinder = toWorld(wm, qb);
  }
  return true;
}

// One coordinate of a double-word pulled-back vertex, sum_k (s_k + e_k) R_k
// with s_k + e_k = x_k - t_k exactly (TwoSum): the three products s_k R_k
// split exactly (TwoProduct: p_k + q_k), the p_k summed by two TwoSums
// (exact: p_0 + p_1 + p_2 = s2 + t1 + t2), and every low-order term
// (t1, t2, q_k + e_k R_k) summed in double, then one TwoSum. With
// |q_k|, |e_k| <= u |p_k| (1 + u), |t1| <= u |p_0 + p_1|, |t2| <= u |s2|,
// the low-order sum's terms total at most 4u (|p_0| + |p_1| + |p_2|) and
// its five roundings (and those of e_k R_k, q_k + e_k R_k) cost at most
// 25 u^2 sum_k |R_k (x_k - t_k)| < 2^-101 S: the double-word vertices'
// bound of docs/distance.md, section 4, at half the operations of three
// double-word products and two double-word sums.
template <class DDx>
inline DDx pullBackDW(const double s[3], const double e[3], double r0,
                      double r1, double r2) {
  constexpr bool kF = std::is_same_v<DDx, detail::DDT<true>>;
  double p0, q0, p1, q1, p2, q2;
  detail::twoProdT<kF>(s[0], r0, p0, q0);
  detail::twoProdT<kF>(s[1], r1, p1, q1);
  detail::twoProdT<kF>(s[2], r2, p2, q2);
  double s1, t1, s2, t2;
  detail::twoSum(p0, p1, s1, t1);
  detail::twoSum(s1, p2, s2, t2);
  const double lo =
      ((t1 + t2) + (q0 + e[0] * r0)) + ((q1 + e[1] * r1) + (q2 + e[2] * r2));
  double h, l;
  detail::twoSum(s2, lo, h, l);
  return DDx(h, l);
}

// True when the double point p, within e (per coordinate) of a point of the
// exact pulled-back triangle, is certainly inside C with that point: h -
// |p_z| >= 2e (one rounding: the true |z| stays below h), and p_xy^2 <=
// (r - 2e)^2 (1 - 2^-50) (the roundings of the squares, the sums and r -
// 2e are below 6u relative, 2^-50 = 8u), so the exact point's rho, within
// sqrt 2 e of p's, is below r. Then `intersect` is true: a witness that
// needs no Boolean. The relative bounds behind e miss underflow (an
// operation in the subnormal range errs by up to 2^-1075 absolute, and the
// vertices of tiny inputs may be formed from subnormal products, with S
// itself 0): e is widened by 2^-1060, far above the few such errors of a
// point, and r - 2e >= 2^-500 keeps rr^2 normal, so that an underflowed
// square (2^-1075 absolute) stays inside the 2u rr^2 left by the factor
// 1 - 2^-50. (Found by the fuzz target: lz = 0 and subnormal lengths.)
inline bool certainlyInside(const P3<double>& p, const Problem<double>& P,
                            double e) {
  e += 0x1p-1060;
  const double rr = P.r - 2 * e;
  return P.h - absd(p.z) >= 2 * e && rr >= 0x1p-500 &&
         p.x * p.x + p.y * p.y <= rr * rr * (1 - 0x1p-50);
}

// As certainlyInside, for a point whose double z coordinate is that of the
// exact triangle's point (zExact in solve: a triangle in a cap plane under
// an exactly representable pose): 2 |p_z| <= lz decides the slab exactly
// (doubling is exact; h = lz / 2 may have rounded for a subnormal lz), the
// disk as in certainlyInside. The closed sets touch at a point on the cap
// plane: `intersect` is true there too.
inline bool certainlyInsideExactZ(const P3<double>& p, const Problem<double>& P,
                                  double lz, double e) {
  e += 0x1p-1060;
  const double rr = P.r - 2 * e;
  return 2 * absd(p.z) <= lz && rr >= 0x1p-500 &&
         p.x * p.x + p.y * p.y <= rr * rr * (1 - 0x1p-50);
}

// A point of edge k of the double triangle certainly inside C (with
// certainlyInside's allowance e for p = fl(a + s fl(b - a)), any s in
// [0, 1]): the middle of the edge's chord through C in double, the
// intersection of its parameter intervals in the slab (|a_z + s d_z| <= h)
// and in the disk (A s^2 + 2 B s + C <= 0). The double pass's edge point
// at distance 0 is a root of phi', which is 0 all along the chord, and the
// search usually stops next to the chord's end, where certainlyInside's
// margin fails: the chord's middle is the deepest point of the edge in
// most crossings. A quotient that overflows (d_z tiny) gives +-inf, which
// the clamps to [0, 1] absorb; no 0 / 0 (d_z != 0, A > kTinyDen).
inline bool chordWitness(const Problem<double>& P, int k, double e,
                         P3<double>* out) {
  const P3<double>& a = P.v[detail::dist::kEdgeA[k]];
  const P3<double>& b = P.v[detail::dist::kEdgeB[k]];
  // Cheap rejections first (tried on every query that has no vertex in
  // C): both ends beyond the same cap, or both outside the disk's
  // cylinder with the quadratic's minimum at an end (B >= 0 or A + B <= 0).
  // (Rejecting only costs the witness: the double pass and the Boolean
  // follow.)
  if ((a.z > P.h && b.z > P.h) || (a.z < -P.h && b.z < -P.h)) return false;
  const P3<double> d = b - a;
  const double A = d.x * d.x + d.y * d.y, B = a.x * d.x + a.y * d.y;
  const double C = a.x * a.x + a.y * a.y - P.r * P.r;
  if (C > 0 && C + 2 * B + A > 0 && (B >= 0 || A + B <= 0)) return false;
  double lo = 0, hi = 1;
  if (d.z != 0) {
    const double t1 = (-P.h - a.z) / d.z, t2 = (P.h - a.z) / d.z;
    lo = maxd(lo, t1 < t2 ? t1 : t2);
    const double th = t1 < t2 ? t2 : t1;
    hi = th < hi ? th : hi;
  } else if (!(absd(a.z) <= P.h)) {
    return false;
  }
  if (A > detail::dist::kTinyDen) {
    const double disc = B * B - A * C;
    if (!(disc > 0)) return false;
    const double sq = std::sqrt(disc);
    lo = maxd(lo, (-B - sq) / A);
    const double th = (sq - B) / A;
    hi = th < hi ? th : hi;
  } else if (!(C < 0)) {
    return false;
  }
  if (!(lo < hi)) return false;
  const P3<double> p = a + d * (0.5 * (lo + hi));
  if (!certainlyInside(p, P, e)) return false;
  *out = p;
  return true;
}

// The rare refinements (section 2, steps 6 and 7): refineFast, then the
// general refinement when refineFast does not certify; the pair is
// disjoint. `tie`: twice the double pass's error.
template <class DDx, class VertexFn>
inline void refineSlow(const Pass& pass, const Problem<double>& P,
                       VertexFn& vertex, double U, double tie, double eps_y_d,
                       double M, double slack_dd, const WorldMap& wm,
                       DistanceResult<double>* out) {
  if (refineFast<DDx>(pass, P, vertex, U, tie, eps_y_d, M, slack_dd, wm, out)) {
    TRICYL_DIST_PATH(6);
    return;
  }
  TRICYL_DIST_PATH(7);

  // The general refinement: every candidate within the double pass's
  // error of the best, each edge re-solved in a bracket.
  Problem<DDx> Q;
  Q.r = DDx(P.r);
  Q.h = DDx(P.h);
  for (int v = 0; v < 3; ++v) Q.v[v] = vertex(v);
  DDx Ubest(std::numeric_limits<double>::infinity());
  DDx Lbest(0);
  Candidate<DDx> best;
  bool face_cut = false;
  const Candidate<DDx> face = detail::dist::faceCandidate(Q, &face_cut);
  if (!face_cut) Lbest = detail::dist::certify(Q, face.w);
  if (face.valid) {
    Ubest = face.f;
    best = face;
  }
  for (int k = 0; k < 3; ++k) {
    const Candidate<double>& c = pass.cand[k];
    if (!c.valid || !(c.f <= U + tie)) continue;
    const P3<DDx>& a = Q.v[detail::dist::kEdgeA[k]];
    const P3<DDx> d = Q.v[detail::dist::kEdgeB[k]] - a;
    DDx at[7] = {DDx(0), DDx(0), DDx(1)};
    const int n = 3 + detail::dist::edgeKinks(a, d, Q.r, Q.h, at + 3);
    at[0] = detail::dist::edgeRefine(a, d, Q.r, Q.h, DDx(c.s), DDx(0x1p-24),
                                     kRefineIter, DDx(0x1p-104), at + 3, n - 3);
    for (int i = 0; i < n; ++i) {
      const Candidate<DDx> e = detail::dist::edgeCandidate(Q, k, at[i]);
      const DDx l = detail::dist::certify(Q, e.w);
      if (l > Lbest) Lbest = l;
      if (e.f < Ubest) {
        Ubest = e.f;
        best = e;
      }
    }
  }
  if (!best.valid) {  // cannot happen: the double best is refined
    best = detail::dist::edgeCandidate(Q, 0, DDx(0));
    Ubest = best.f;
  }
  double dist = double(Ubest);
  const double gap = double(Ubest - Lbest);
  double err = (gap > 0 ? gap : 0) + slack_dd + kU * dist;
  if (!(dist > 0)) {  // below double-word resolution: still positive
    err += std::numeric_limits<double>::denorm_min();
    dist = std::numeric_limits<double>::denorm_min();
  }
  if (out) {
    out->distance = dist;
    out->error_bound = err * (1 + 0x1p-50);
    out->point_on_triangle = toWorld(wm, best.p);
    out->point_on_cylinder = toWorld(wm, best.q);
  }
}

#if TRICYL_DIST_FMA_DISPATCH
// Whether DDx is the FMA kernel's double-word type.
template <class DDx>
constexpr bool kFmaKernel = std::is_same_v<DDx, detail::DDT<true>>;
#endif

// f() out of line, one copy per kernel (TRICYL_DIST_RARE): f's body is
// flattened into a function compiled for the kernel's target.
template <class F>
TRICYL_DIST_RARE auto rarePlain(F& f) {
  return f();
}
#if TRICYL_DIST_FMA_DISPATCH
template <class F>
TRICYL_DIST_RARE_FMA auto rareFma(F& f) {
  return f();
}
#endif
template <class DDx, class F>
inline auto outOfLine(F&& f) {
#if TRICYL_DIST_FMA_DISPATCH
  if constexpr (kFmaKernel<DDx>)
    return rareFma(f);
  else
#endif
    return rarePlain(f);
}

// The distance for valid double inputs of moderate magnitude (no
// overflow of products of up to six lengths: every length below 2^100).
// `booleanOf()` returns the exact Boolean (kIntersect or kDisjoint) of the
// query; it is called only when no certified lower bound proves the pair
// disjoint (the lean refinement's, or the double pass's above its own
// error), and first when the double pass puts a vertex, an edge point or
// the face in C (then the pair usually intersects, and that point is the
// witness). `exact_frame`: the local problem is the inputs' own (not a
// scaled one that may have lost parts below the underflow threshold), so a
// point of the double pass certainly inside C is a witness of intersection
// without the Boolean (certainlyInside).
template <class DDx, class BooleanFn>
TRICYL_DIST_NOINLINE Answer solve(const Cylinder<double>& cyl,
                                  const Pose<double>& pose,
                                  const Triangle<double>& tri,
                                  BooleanFn&& booleanOf, int rexp,
                                  bool exact_frame,
                                  DistanceResult<double>* out) {
  const WorldMap wm{&pose, rexp};
  // The vertices in order of increasing magnitude of their local
  // coordinates (kEdge: every edge then starts at its smaller end).
  const Vec3<double>* X[3] = {&tri.a, &tri.b, &tri.c};
  const double tt[3] = {pose.t.x, pose.t.y, pose.t.z};
  // The double pulled-back triangle, and S = max sum_k |R_ki| |x_k - t_k|.
  Problem<double> P;
  P.r = cyl.radius;
  P.h = cyl.lz * 0.5;
  double S = 0, absR[3][3], mag[3];  // mag: each vertex's largest |y_i|
  for (int k = 0; k < 3; ++k)
    for (int i = 0; i < 3; ++i) absR[k][i] = absd(pose.R[k][i]);
  for (int v = 0; v < 3; ++v) {
    const double x[3] = {X[v]->x, X[v]->y, X[v]->z};
    const double dx[3] = {x[0] - tt[0], x[1] - tt[1], x[2] - tt[2]};
    const double adx[3] = {absd(dx[0]), absd(dx[1]), absd(dx[2])};
    double y[3];
    for (int i = 0; i < 3; ++i) {
      y[i] = sum3(pose.R[0][i] * dx[0], pose.R[1][i] * dx[1],
                  pose.R[2][i] * dx[2]);
      S = maxd(S,
               absR[0][i] * adx[0] + absR[1][i] * adx[1] + absR[2][i] * adx[2]);
    }
    P.v[v] = {y[0], y[1], y[2]};
    mag[v] = maxd(absd(y[0]), maxd(absd(y[1]), absd(y[2])));
  }
  const double M = maxd(mag[0], maxd(mag[1], mag[2]));
  for (int pass = 0; pass < 2; ++pass)
    for (int v = 0; v + 1 < 3; ++v)
      if (mag[v + 1] < mag[v]) {
        std::swap(mag[v], mag[v + 1]);
        std::swap(P.v[v], P.v[v + 1]);
        std::swap(X[v], X[v + 1]);
      }
  // Mx bounds every point's norm and the cylinder's extent (section 4).
  const double Mx = (M * 1.75 + P.r + P.h) * (1 + 0x1p-50);
  // The double pass: y computed with <= 5 roundings relative to S.
  const double eps_y_d = 6 * kU * S;
  const double slack_d = 2 * eps_y_d + kAlg * kU * Mx;
  const VertexPass vp = vertexPass(P);
  auto intersecting = [&](const P3<double>& p, const P3<double>& q) {
    if (out) {
      out->distance = 0;
      out->error_bound = 0;
      out->point_on_triangle = toWorld(wm, p);
      out->point_on_cylinder = toWorld(wm, q);
    }
    return Answer::kIntersect;
  };
  int vmin = 0;
  for (int i = 1; i < 3; ++i)
    if (vp.f[i] < vp.f[vmin]) vmin = i;
  // A vertex in C in double (f = 0): usually an intersecting pair, which
  // the Boolean decides first, the vertex the witness. (A vertex just
  // outside in double, 0 < f <= slack_d, is nearly always disjoint:
  // the lean refinement below is tried before the Boolean.)
  // A vertex certainly inside C (its double coordinates within eps_y_d of
  // the exact ones): intersecting, no Boolean needed.
  if (vp.f[vmin] == 0 && exact_frame &&
      certainlyInside(P.v[vmin], P, eps_y_d * (1 + 0x1p-50))) {
    TRICYL_DIST_PATH(11);
    return intersecting(P.v[vmin], P.v[vmin]);
  }
  // The double z coordinate of vertex v is the exact pulled-back one: x_k -
  // t_k exact (TwoSum), each product by R_k2 exact (TwoProduct, away from
  // underflow, where its error term could itself round), and their sum exact
  // and equal to the double (two TwoSums with zero errors). Then a vertex,
  // or a point of an edge whose ends have the same exact z, lies on the
  // plane z = y_z exactly: a triangle in a cap plane under an exactly
  // representable pose (the aligned family) is decided here, where
  // certainlyInside's margin 2e below h cannot hold.
  auto zExact = [&](int v) {
    constexpr bool kF = std::is_same_v<DDx, detail::DDT<true>>;
    const double x[3] = {X[v]->x, X[v]->y, X[v]->z};
    double pr[3];
    for (int k = 0; k < 3; ++k) {
      double dx, e, q;
      detail::twoSum(x[k], -tt[k], dx, e);
      if (e != 0) return false;
      detail::twoProdT<kF>(dx, pose.R[k][2], pr[k], q);
      if (q != 0) return false;
      if (pr[k] == 0 ? !(dx == 0 || pose.R[k][2] == 0)
                     : !(absd(pr[k]) >= 0x1p-900))
        return false;
    }
    double s1, t1, s2, t2;
    detail::twoSum(pr[0], pr[1], s1, t1);
    detail::twoSum(s1, pr[2], s2, t2);
    return t1 == 0 && t2 == 0 && s2 == P.v[v].z;
  };
  if (vp.f[vmin] == 0 && exact_frame &&
      certainlyInsideExactZ(P.v[vmin], P, cyl.lz, eps_y_d * (1 + 0x1p-50)) &&
      zExact(vmin)) {
    TRICYL_DIST_PATH(14);
    return intersecting(P.v[vmin], P.v[vmin]);
  }
  // An edge's chord through C deep inside it (chordWitness): tried before
  // the double pass, whose edge point at distance 0 would usually lie
  // next to the chord's end (phi' vanishes all along the chord), and for
  // a vertex on C's boundary in double.
  if (exact_frame) {
    P3<double> p;
    for (int k = 0; k < 3; ++k)
      if (chordWitness(P, k, (eps_y_d + 8 * kU * Mx) * (1 + 0x1p-50), &p)) {
        TRICYL_DIST_PATH(16);
        return intersecting(p, p);
      }
  }
  if (vp.f[vmin] == 0 && booleanOf() == Answer::kIntersect) {
    TRICYL_DIST_PATH(1);
    return intersecting(P.v[vmin], P.v[vmin]);
  }
  Pass pass = doublePass(P, vp, slack_d);

  // Double-word refinement. x - t is exact as a pair (TwoSum); the sum
  // of three double-word products is within 2^-101 S (dd.h).
  // Formed out of line (one copy, not one at each of the lean steps' uses):
  // a smaller kernel for calls that start with a cold instruction cache.
  auto ddVertex = [&](int v) {
    return outOfLine<DDx>([&] {
      const double x[3] = {X[v]->x, X[v]->y, X[v]->z};
      double ds[3], de[3];
      for (int k = 0; k < 3; ++k) detail::twoSum(x[k], -tt[k], ds[k], de[k]);
      return P3<DDx>{
          pullBackDW<DDx>(ds, de, pose.R[0][0], pose.R[1][0], pose.R[2][0]),
          pullBackDW<DDx>(ds, de, pose.R[0][1], pose.R[1][1], pose.R[2][1]),
          pullBackDW<DDx>(ds, de, pose.R[0][2], pose.R[1][2], pose.R[2][2])};
    });
  };
  const double slack_dd = 2 * kUdd * S + kAlg * kUdd * Mx;
  // A best candidate of the double pass within its error of C: at
  // distance 0 in double (an edge or the face through C), usually an
  // intersecting pair, which the Boolean decides before any refinement;
  // at a positive double distance (0 < f <= 2 slack_d), nearly always a
  // disjoint one (a pair at a distance below the double pass's error),
  // which the lean refinement usually proves disjoint without the
  // Boolean; if it does not, the Boolean decides next.
  const bool near_c = !(pass.cand[pass.best].f > 2 * slack_d);
  auto intersectingBest = [&]() {
    if (pass.face_pending) addFace(P, &pass);
    const Candidate<double>& c = pass.cand[pass.best];
    return intersecting(c.p, c.q);
  };
  // An edge point at distance 0 in double: p = fl(a + s fl(b - a)) is
  // within eps_y_d + 8u Mx of the exact triangle's point at s (the
  // vertices' error, and three roundings of coordinates below 3M, M the
  // largest vertex coordinate, Mx > 1.75 M); certainly inside C, it is a
  // witness as above.
  if (near_c && pass.cand[pass.best].f == 0 && exact_frame && pass.best < 3 &&
      certainlyInside(pass.cand[pass.best].p, P,
                      (eps_y_d + 8 * kU * Mx) * (1 + 0x1p-50))) {
    TRICYL_DIST_PATH(12);
    return intersectingBest();
  }
  // The same for a point on a cap plane (zExact): a vertex, or an edge
  // point between two vertices of the same exact z (then fl(b_z - a_z) = 0
  // and p_z = a_z, the exact point's z at every parameter).
  if (near_c && pass.cand[pass.best].f == 0 && exact_frame && pass.best < 3) {
    const Candidate<double>& c = pass.cand[pass.best];
    const int vb = vertexOf(c);
    const int ia = vb >= 0 ? vb : detail::dist::kEdgeA[c.kind];
    const int ib = vb >= 0 ? vb : detail::dist::kEdgeB[c.kind];
    if (P.v[ia].z == P.v[ib].z &&
        certainlyInsideExactZ(c.p, P, cyl.lz,
                              (eps_y_d + 8 * kU * Mx) * (1 + 0x1p-50)) &&
        zExact(ia) && (ib == ia || zExact(ib))) {
      TRICYL_DIST_PATH(15);
      return intersectingBest();
    }
  }
  if (near_c && pass.cand[pass.best].f == 0 &&
      booleanOf() == Answer::kIntersect) {
    TRICYL_DIST_PATH(2);
    return intersectingBest();
  }
  DDVertices<DDx, decltype(ddVertex)> vertex{ddVertex};
  // Accepted: L_lo > 0 proves the pair disjoint, no Boolean needed.
  if (leanRefine<DDx>(pass, P, vertex, eps_y_d, M, slack_dd, wm, out)) {
    TRICYL_DIST_PATH(3);
    return Answer::kDisjoint;
  }
  if (leanFace<DDx>(pass, P, vertex, slack_dd, wm, out)) {
    TRICYL_DIST_PATH(13);
    return Answer::kDisjoint;
  }
  if (near_c && booleanOf() == Answer::kIntersect) {
    TRICYL_DIST_PATH(8);
    return intersectingBest();
  }
  if (pass.face_pending) addFace(P, &pass);

  double U = std::numeric_limits<double>::infinity(), L = 0;
  for (int k = 0; k < 4; ++k)
    if (pass.cand[k].valid && pass.cand[k].f < U) U = pass.cand[k].f;
  // The separating-plane bound of the best candidate first (usually the
  // tight one); the others only if it leaves a gap.
  auto bound = [&](int k) {
    const Candidate<double>& c = pass.cand[k];
    if (k == 3 ? !pass.face_cut : c.valid)
      L = maxd(L, detail::dist::certify(P, c.w));
  };
  if (pass.best >= 0) bound(pass.best);
  if (!(U - L <= 2 * slack_d))
    for (int k = 0; k < 4; ++k)
      if (k != pass.best) bound(k);
  // Separation: d >= L - slack_d (section 4) proves the Boolean false.
  // Otherwise the Boolean decides (it was already known to be false if a
  // vertex was within slack_d of C: the call is then cached by booleanOf).
  if (!(L > slack_d * (1 + 0x1p-40)) && booleanOf() == Answer::kIntersect) {
    TRICYL_DIST_PATH(4);
    const Candidate<double>& c = pass.cand[pass.best >= 0 ? pass.best : 0];
    return intersecting(c.p, c.q);
  }
  // (L > U beyond the rounding allowance cannot happen for consistent
  // bounds; such a pass is not accepted.)
  const double err_d = maxd(U - L, 0.0) + slack_d + kU * U;
  if (U > 0 && L <= U + slack_d && err_d <= kAcceptRel * U) {
    if (out) {
      const Candidate<double>& c = pass.cand[pass.best];
      out->distance = U;
      out->error_bound = err_d * (1 + 0x1p-50);
      out->point_on_triangle = toWorld(wm, c.p);
      out->point_on_cylinder = toWorld(wm, c.q);
    }
    TRICYL_DIST_PATH(5);
    return Answer::kDisjoint;
  }

  outOfLine<DDx>([&] {
    refineSlow<DDx>(pass, P, vertex, U, 2 * err_d, eps_y_d, M, slack_dd, wm,
                    out);
  });
  return Answer::kDisjoint;
}

// The inputs outside the usual case (distanceDouble): validated, scaled
// by powers of two when they need it. mr, mw, mc: the largest |R_ij|,
// world coordinate and cylinder length.
template <class DDx, class BooleanFn>
inline Answer distanceWide(const Cylinder<double>& cyl,
                           const Pose<double>& pose,
                           const Triangle<double>& tri, double mr, double mw,
                           double mc, BooleanFn& booleanOf,
                           DistanceResult<double>* out) {
  if (!validInputs(cyl, pose, tri)) return Answer::kInvalidInput;
  int ea = 0, ew = 0, ec = 0;
  if (mr > 0) (void)std::frexp(mr, &ea);
  if (mw > 0) (void)std::frexp(mw, &ew);
  (void)std::frexp(mc, &ec);
  int eM = mr > 0 && mw > 0 ? ea + 2 + ew : -2000;
  if (!(mr > 0)) ea = 0;
  if (mc > 0 && ec > eM) eM = ec;
  if (eM == -2000) eM = 0;  // everything 0: nothing to scale
  if (eM >= -80 && eM <= 80 && ea >= -40 && ea <= 40)
    return solve<DDx>(cyl, pose, tri, booleanOf, 0, true, out);
  // The world lengths' scale, kept so that they stay within 2^+-100 (with
  // R = 0, or a tiny R, the world lengths hardly matter); the local
  // frame's scale is then 2^-(ea + el) (>= 2^-eM).
  int el = eM - ea;
  if (mw > 0 && el < ew - 100) el = ew - 100;
  if (mw > 0 && el > ew + 100) el = ew + 100;
  eM = ea + el;
  // r and lz are capped at 2^110: beyond the clamp above they can only
  // exceed the local triangle's extent (|y| < 2^104), where C's barrel
  // (or slab) constraint is slack for every point of the triangle and the
  // distance does not depend on them.
  const Cylinder<double> c2{std::fmin(std::ldexp(cyl.radius, -eM), 0x1p110),
                            std::fmin(std::ldexp(cyl.lz, -eM), 0x1p111)};
  Pose<double> p2;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p2.R[i][j] = std::ldexp(pose.R[i][j], -ea);
  p2.t = scaled(pose.t, -el);
  const Triangle<double> t2{scaled(tri.a, -el), scaled(tri.b, -el),
                            scaled(tri.c, -el)};
  DistanceResult<double> r2{};
  // The scaled problem may lose parts below the underflow threshold, so its
  // double pass cannot prove separation for the inputs as given: the
  // Boolean (of the unscaled inputs) comes first here.
  const Answer exact = booleanOf();
  const Answer a = solve<DDx>(
      c2, p2, t2, [exact]() { return exact; }, 2 * ea, false, &r2);
  if (out) {
    out->distance = std::ldexp(r2.distance, eM);
    out->error_bound = std::ldexp(r2.error_bound, eM);
    out->point_on_cylinder = scaled(r2.point_on_cylinder, el);
    out->point_on_triangle = scaled(r2.point_on_triangle, el);
    if (a == Answer::kDisjoint && !(out->distance > 0))
      out->distance = std::numeric_limits<double>::denorm_min();
  }
  return a;
}

template <class DDx>
Answer distanceDouble(const Cylinder<double>& cyl, const Pose<double>& pose,
                      const Triangle<double>& tri,
                      DistanceResult<double>* out) {
  // The exact Boolean of the inputs as given, computed at most once and
  // only when solve asks for it (most disjoint pairs are proved disjoint
  // by the double pass's certificate alone).
  Answer boolean = Answer::kInvalidInput;
  auto booleanOf = [&]() {
    if (boolean == Answer::kInvalidInput) {
      TRICYL_DIST_PATH(10);
      boolean = tryIntersect(cyl, pose, tri);
    }
    return boolean;
  };
  // Power-of-two scaling keeps the products of up to six local lengths
  // finite and normal. The local problem's magnitude is at most
  // M = max(4 max|R_ij| * (world lengths), r, lz) = 2^eM (exponents
  // added: the product may overflow). R is scaled by 2^-ea (to about 1),
  // the world lengths by 2^-(eM - ea), so the local frame (y, r, lz) by
  // 2^-eM. Exact, except that parts below the scaled underflow threshold
  // are lost (docs/distance.md, section 6).
  //
  // The usual case, validated and classified in one pass of comparisons:
  // every |R_ij| <= 2^30 and every length <= 2^60 (which NaN and Inf fail:
  // the inputs are then valid), r, lz >= 0, and the largest of each group
  // 0 or above 2^-30, 2^-60 (then eM and ea below are inside the window).
  double mr = 0, mw = 0;
  bool small = true;
  for (const auto& row : pose.R)
    for (double x : row) {
      const double a = absd(x);
      small &= a <= 0x1p30;
      mr = maxd(mr, a);
    }
  for (const Vec3<double>* v : {&tri.a, &tri.b, &tri.c, &pose.t})
    for (double x : {v->x, v->y, v->z}) {
      const double a = absd(x);
      small &= a <= 0x1p60;
      mw = maxd(mw, a);
    }
  const double mc = maxd(cyl.radius, cyl.lz);
  small &= cyl.radius >= 0 && cyl.lz >= 0 && mc <= 0x1p60;
  auto aboveOrZero = [](double x, double lim) { return x == 0 || x >= lim; };
  if (small && aboveOrZero(mr, 0x1p-30) && aboveOrZero(mw, 0x1p-60) &&
      aboveOrZero(mc, 0x1p-60))
    return solve<DDx>(cyl, pose, tri, booleanOf, 0, true, out);
  return outOfLine<DDx>([&] {
    return distanceWide<DDx>(cyl, pose, tri, mr, mw, mc, booleanOf, out);
  });
}

// The same computation with a fused multiply-add for the double-word
// TwoProducts, on CPUs that have one (x86-64 with FMA3: one instruction
// instead of Dekker's seventeen). The results are the same bits (both
// TwoProducts are exact, and -ffp-contract=off keeps every other operation
// as written); `flatten` inlines the whole query into this one function,
// compiled for the FMA target. Chosen as the other double-word stages'
// (fmaAtRunTime, src/eft.h: TRICYL_SCALAR_BASELINE=1 keeps the portable one).
#if TRICYL_DIST_FMA_DISPATCH
__attribute__((target("fma") TRICYL_DIST_FLATTEN)) Answer distanceDoubleFma(
    const Cylinder<double>& cyl, const Pose<double>& pose,
    const Triangle<double>& tri, DistanceResult<double>* out) {
  return distanceDouble<detail::DDT<true>>(cyl, pose, tri, out);
}
#endif

// The portable path, also inlined into one function.
#if defined(__GNUC__) || defined(__clang__)
__attribute__((flatten))
#endif
Answer
distanceDoubleGeneric(const Cylinder<double>& cyl, const Pose<double>& pose,
                      const Triangle<double>& tri,
                      DistanceResult<double>* out) {
  return distanceDouble<DD>(cyl, pose, tri, out);
}

Answer distanceAny(const Cylinder<double>& cyl, const Pose<double>& pose,
                   const Triangle<double>& tri, DistanceResult<double>* out) {
#if TRICYL_DIST_FMA_DISPATCH
  if (detail::fmaAtRunTime()) return distanceDoubleFma(cyl, pose, tri, out);
#endif
  return distanceDoubleGeneric(cyl, pose, tri, out);
}

Vec3<double> widen(const Vec3<float>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}
Vec3<float> narrow(const Vec3<double>& v) {
  return {float(v.x), float(v.y), float(v.z)};
}

template <class S>
Answer dispatch(const Cylinder<S>& cyl, const Pose<S>& pose,
                const Triangle<S>& tri, DistanceResult<S>* out) {
  if constexpr (std::is_same_v<S, double>) {
    return distanceAny(cyl, pose, tri, out);
  } else {
    // float -> double is exact: the double result for the same inputs,
    // rounded once more (its error added to the bound).
    const Cylinder<double> c{double(cyl.radius), double(cyl.lz)};
    Pose<double> p;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) p.R[i][j] = double(pose.R[i][j]);
    p.t = widen(pose.t);
    const Triangle<double> t{widen(tri.a), widen(tri.b), widen(tri.c)};
    DistanceResult<double> r{};
    const Answer a = distanceAny(c, p, t, &r);
    if (a != Answer::kInvalidInput && out) {
      float d = float(r.distance);
      if (a == Answer::kDisjoint && !(d > 0))
        d = std::numeric_limits<float>::denorm_min();
      const double err = r.error_bound + absd(double(d) - r.distance);
      float ef = float(err);
      if (double(ef) < err)
        ef = std::nextafter(ef, std::numeric_limits<float>::infinity());
      out->distance = d;
      out->error_bound = ef;
      out->point_on_cylinder = narrow(r.point_on_cylinder);
      out->point_on_triangle = narrow(r.point_on_triangle);
    }
    return a;
  }
}

[[noreturn]] void throwInvalid() {
  throw InvalidInput(
      "tricyl::distance(cylinder, triangle): NaN or infinite input, or a "
      "negative radius or length");
}

}  // namespace

template <class S>
Answer tryDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                   const Triangle<S>& triangle,
                   DistanceResult<S>* out) noexcept {
  return dispatch(cylinder, pose, triangle, out);
}

template <class S>
DistanceResult<S> distance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                           const Triangle<S>& triangle) {
  DistanceResult<S> r{};
  if (dispatch(cylinder, pose, triangle, &r) == Answer::kInvalidInput)
    throwInvalid();
  return r;
}

template <class S>
DistanceResult<S> distance(const Cylinder<S>& cylinder,
                           const Triangle<S>& triangle) {
  return distance(cylinder, identityPose<S>(), triangle);
}

namespace diagnostic {
template <class S>
Answer tryDistancePortable(const Cylinder<S>& cylinder, const Pose<S>& pose,
                           const Triangle<S>& triangle,
                           DistanceResult<S>* out) noexcept {
  static_assert(std::is_same_v<S, double>);
  return distanceDoubleGeneric(cylinder, pose, triangle, out);
}
template Answer tryDistancePortable(const Cylinder<double>&,
                                    const Pose<double>&,
                                    const Triangle<double>&,
                                    DistanceResult<double>*) noexcept;
}  // namespace diagnostic

template DistanceResult<float> distance(const Cylinder<float>&,
                                        const Pose<float>&,
                                        const Triangle<float>&);
template DistanceResult<double> distance(const Cylinder<double>&,
                                         const Pose<double>&,
                                         const Triangle<double>&);
template DistanceResult<float> distance(const Cylinder<float>&,
                                        const Triangle<float>&);
template DistanceResult<double> distance(const Cylinder<double>&,
                                         const Triangle<double>&);
template Answer tryDistance(const Cylinder<float>&, const Pose<float>&,
                            const Triangle<float>&,
                            DistanceResult<float>*) noexcept;
template Answer tryDistance(const Cylinder<double>&, const Pose<double>&,
                            const Triangle<double>&,
                            DistanceResult<double>*) noexcept;

}  // namespace tricyl
