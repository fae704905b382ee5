// SPDX-License-Identifier: BSD-3-Clause
// The cylinder query family, each predicate written ONCE. The point and
// cone queries are written over a kernel K of src/filter.h and decided by
// runStages (src/stages.h): FilterKernel (certified double), then, for a
// query it leaves open, AdaptiveKernel (src/adaptive.h). The sphere, segment
// and line queries are written against a context (src/per_sign.h), each
// sign a closed-form polynomial of the query's frame: decided in double,
// and each sign the double bound leaves open re-decided by itself in the
// next arithmetic (runPerSign, the driver's per-sign policy).
//
// Frame: the cylinder frame of the triangle kernel, produced by the same
// toLocal<K> (src/triangle_cylinder_impl.h): y = R^T (x - t) evaluated
// exactly in K, with z DOUBLED (Z = 2 z, H = lz; the slab is |Z| <= H).
//
// Budget of src/filter.h (polynomials only, depth <= 20, degree <= 8, and
// a-priori magnitude <= 2^380 under the range gate for the underflow
// argument). Degrees count input factors (a local coordinate x, y, Z has
// degree 2: a rotation entry times a coordinate difference); depths count
// operations from an input, with x, y at depth 4 and Z at depth 5 (one
// extra rounding for the input difference included), as in
// docs/exactness.md. Under the gate every length is <= 2^40 and every
// rotation entry <= 2, so |x|, |y|, |Z| <= 2^44.
//
//   predicate                                   degree depth  magnitude
//   slab   Z -+ H                                 2      6      2^45
//   disk   r^2 - x^2 - y^2                        4      7      2^90
//   cone   r^2 (H - Z)^2 - 4 H^2 (x^2 + y^2)      6      9      2^172
//   sphere 2 rho - E, E = |Z| - H, s - (r+rho)^2  4      7      2^91
//   sphere T, 16 r^2 G - T^2                      8     12      2^190
//   segment (V), (X), (E): as the triangle kernel's (V), (X), (E):
//          degree <= 8, depth <= 11, magnitude <= 2^370 (docs/exactness.md)
//   line   (V), (X), (E) and its early-out r^2 L - c^2: the segment's
//          terms with the direction R^T (q - p) for b - a (the same
//          degree, depth and magnitude as a local coordinate), same bounds
// All inside the budget; no division and no square root anywhere. The
// per-sign filter of the sphere, segment and line (shallowSign,
// src/per_sign.h) uses their largest depth, 12, for a bound four times
// tighter than the filter's general one (depth <= 56).
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <optional>
#include <type_traits>
#include <utility>

#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
#include <emmintrin.h>
#endif

#include "filter.h"
#include "per_sign.h"
#include "stages.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/types.h"

namespace tricyl::detail {

// ---------------------------------------------------------------------------
// Validation and the stage driver, shared by every query of the family.

/// One pass over the bit patterns (as the triangle kernel's validate):
/// false if any value is NaN or infinite; otherwise the largest magnitudes
/// of the length inputs and of the rotation entries, for the range gate.
inline bool scanFinite(std::initializer_list<double> lengths,
                       const Pose<double>& pose, double* max_len,
                       double* max_unitless) {
  constexpr std::uint64_t kAbsMask = ~(std::uint64_t(1) << 63);
  constexpr std::uint64_t kInf = 0x7ff0000000000000ULL;
  auto bits = [](double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b & kAbsMask;
  };
  std::uint64_t ml = 0, mu = 0;
  for (double v : lengths) ml = ml > bits(v) ? ml : bits(v);
  for (double v : {pose.t.x, pose.t.y, pose.t.z})
    ml = ml > bits(v) ? ml : bits(v);
  for (const auto& row : pose.R)
    for (double v : row) mu = mu > bits(v) ? mu : bits(v);
  if (ml >= kInf || mu >= kInf) return false;
  std::memcpy(max_len, &ml, sizeof ml);
  std::memcpy(max_unitless, &mu, sizeof mu);
  return true;
}

/// The common case of validation and range gate in a few SSE2 operations
/// (the cylinder queries' inputs are 20 doubles; the scalar scan of
/// scanFinite costs about 80 instructions): true if every input is finite,
/// every length (cyl, t, u, v, w) below 2^40 and every rotation entry below
/// 2 in magnitude, and radius, lz and w carry no sign bit; then
/// *max_unitless = max |R_jk|, the value scanFinite gives. False means
/// "not known": the caller runs the full scan (which also accepts -0, 2^40
/// and 2 exactly), so the answers are those of the scan alone, as
/// TRICYL_PORTABLE_PROLOGUE's builds (no quick gate) check
/// (tests/answers_digest_check.sh). The top 16 bits of |x| (sign cleared)
/// order like |x|, so a signed 16-bit max of them is exact; |x| < 2^40 iff
/// they are <= 0x426f, |x| < 2 iff <= 0x3fff, and NaN and Inf (>= 0x7ff0)
/// exceed both.
#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
inline bool quickGate(const Cylinder<double>& cyl, const Pose<double>& pose,
                      const Vec3<double>& u, const Vec3<double>& v, double w,
                      double* max_unitless) {
  static_assert(sizeof(Pose<double>) == 12 * sizeof(double) &&
                    sizeof(Cylinder<double>) == 2 * sizeof(double) &&
                    sizeof(Vec3<double>) == 3 * sizeof(double),
                "arrays of doubles without padding");
  const __m128i top = _mm_set1_epi64x(0x7fff000000000000LL);
  auto hi = [top](__m128d x) {
    return _mm_and_si128(_mm_castpd_si128(x), top);
  };
  auto mx = [](__m128i a, __m128i b) { return _mm_max_epi16(a, b); };
  const double* R = &pose.R[0][0];
  const __m128d r0 = _mm_loadu_pd(R), r1 = _mm_loadu_pd(R + 2),
                r2 = _mm_loadu_pd(R + 4), r3 = _mm_loadu_pd(R + 6);
  const __m128d r4 = _mm_set_pd(pose.t.x, R[8]);  // R_22 | t.x
  const __m128d c = _mm_loadu_pd(&cyl.radius);    // radius | lz
  const __m128i len = mx(mx(mx(hi(c), hi(_mm_loadu_pd(&pose.t.y))),
                            mx(hi(_mm_loadu_pd(&u.x)), hi(_mm_set_pd(w, u.z)))),
                         mx(hi(_mm_loadu_pd(&v.x)), hi(_mm_set_sd(v.z))));
  const __m128i rot = mx(mx(hi(r0), hi(r1)), mx(hi(r2), hi(r3)));
  const __m128i bad = _mm_or_si128(
      _mm_or_si128(_mm_cmpgt_epi16(len, _mm_set1_epi16(0x426f)),
                   _mm_cmpgt_epi16(rot, _mm_set1_epi16(0x3fff))),
      _mm_cmpgt_epi16(hi(r4), _mm_set_epi16(0x426f, 0, 0, 0, 0x3fff, 0, 0, 0)));
  if ((_mm_movemask_epi8(bad) | _mm_movemask_pd(c) | std::signbit(w)) != 0)
    return false;
  const __m128d abs = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  __m128d m = _mm_max_pd(_mm_max_pd(_mm_and_pd(r0, abs), _mm_and_pd(r1, abs)),
                         _mm_max_pd(_mm_and_pd(r2, abs), _mm_and_pd(r3, abs)));
  m = _mm_max_sd(m, _mm_and_pd(r4, abs));
  m = _mm_max_sd(m, _mm_unpackhi_pd(m, m));
  *max_unitless = _mm_cvtsd_f64(m);
  return true;
}
#else
inline bool quickGate(const Cylinder<double>&, const Pose<double>&,
                      const Vec3<double>&, const Vec3<double>&, double,
                      double*) {
  return false;
}
#endif

/// The inputs of a float query are validated in float, by their bits, before
/// anything is widened: widening a signalling NaN raises FE_INVALID (issue
/// 20; the triangle query's floatBitsFinite does the same). True if no float
/// in the given aggregates (Cylinder, Pose, Vec3, Sphere, ...: arrays of
/// floats without padding) is NaN or infinite. For double there is no
/// conversion before scanFinite, which reads bits too.
template <class... Parts>
inline bool floatBitsFinite(const Parts&... parts) {
  auto one = [](const auto& x) {
    using T = std::decay_t<decltype(x)>;
    static_assert(std::is_trivially_copyable_v<T> && sizeof(T) % 4 == 0,
                  "an aggregate of floats");
    unsigned char bytes[sizeof(T)];
    std::memcpy(bytes, &x, sizeof(T));
    for (std::size_t i = 0; i < sizeof(T); i += 4) {
      std::uint32_t b;
      std::memcpy(&b, bytes + i, 4);
      if ((b & 0x7f800000u) == 0x7f800000u) return false;
    }
    return true;
  };
  return (one(parts) && ...);
}

// float -> double is exact, so every query runs in double on exact copies.
template <class S>
inline Vec3<double> widen(const Vec3<S>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}
template <class S>
inline Pose<double> widen(const Pose<S>& p) {
  Pose<double> w;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.R[i][j] = double(p.R[i][j]);
  w.t = widen(p.t);
  return w;
}

template <class K>
struct LocalPoint {
  typename K::Num x, y, Z;  // Z = 2 z
};

template <class K>
inline LocalPoint<K> localPoint(const Pose<double>& pose, const Vec3<double>& p,
                                double rho) {
  LocalPoint<K> q;
  toLocal<K>(pose, p, rho, q.x, q.y, q.Z);
  return q;
}

/// |Z| <= H: the slab of the cylinder (and of the cone).
template <class K>
inline Tri inSlab(const LocalPoint<K>& q, const typename K::Num& H) {
  const Tri below_top = isNonPos(K::sign(q.Z - H));
  if (below_top == Tri::kFalse) return below_top;
  return kAnd(below_top, isNonNeg(K::sign(q.Z + H)));
}

// ---------------------------------------------------------------------------
// Point in cylinder: |Z| <= H and x^2 + y^2 <= r^2 (boundary inside).

template <class K>
Tri pointInCylinder(const LocalPoint<K>& q, const typename K::Num& H,
                    const typename K::Num& r) {
  const Tri slab = inSlab<K>(q, H);
  if (slab == Tri::kFalse) return slab;
  return kAnd(slab, isNonNeg(K::sign(r * r - q.x * q.x - q.y * q.y)));
}

// ---------------------------------------------------------------------------
// Point in cone. FCL's cone: apex (0, 0, lz/2), base disk of radius r at
// z = -lz/2. DEFINITION (also for the degenerate sizes): the closed convex
// hull of the apex and the base disk. For lz > 0 its cross-section at
// height z is the disk of radius r (lz/2 - z) / lz; in doubled units
// (Z = 2z, H = lz) that radius is r (H - Z) / (2H), so, with H - Z >= 0 on
// the slab and both sides non-negative, "inside" is
//   |Z| <= H  and  4 H^2 (x^2 + y^2) <= r^2 (H - Z)^2.          (1)
// For lz = 0 the hull is the base disk itself {z = 0, x^2 + y^2 <= r^2},
// and (1) alone would accept the whole plane z = 0. The term
//   x^2 + y^2 <= r^2                                              (2)
// fixes that without a branch: for H > 0 it is implied by (1) on the slab
// (r (H - Z) / (2H) <= r), for H = 0 it is the disk. r = 0 gives the axis
// segment {x = y = 0, |z| <= lz/2}; r = lz = 0 the single point.

template <class K>
Tri pointInCone(const LocalPoint<K>& q, const typename K::Num& H,
                const typename K::Num& r) {
  using N = typename K::Num;
  Tri t = inSlab<K>(q, H);
  if (t == Tri::kFalse) return t;
  const N s = q.x * q.x + q.y * q.y;
  t = kAnd(t, isNonNeg(K::sign(r * r - s)));  // (2)
  if (t == Tri::kFalse) return t;
  const N rh = r * (H - q.Z);
  const N s4 = (s + s) + (s + s);  // exact scaling by 4
  return kAnd(t, isNonNeg(K::sign(rh * rh - (H * H) * s4)));  // (1)
}

// ---------------------------------------------------------------------------
// The sphere, segment and line queries: each sign a closed-form polynomial
// in the local data of the query (its Frame<N>), written once as a generic
// lambda and decided by a context C (src/per_sign.h): PerSign inside the
// range gate (double, then that sign alone in double-word, expansions,
// GMP), GMP alone outside it, or one kernel K of src/filter.h
// (KernelCtx<K>, for runStages). Kleene logic keeps every query correct
// for a context that may leave a sign open (KernelCtx<FilterKernel>).

/// r^2 - x^2 - y^2: v is in the infinite solid cylinder (>= 0).
template <class N>
inline N diskGap(const Pt<N>& v, const N& r) {
  return r * r - v.x * v.x - v.y * v.y;
}
/// 4 x (exact: two exact doublings; no overflow under the range gate).
template <class N>
inline N times4(const N& x) {
  const N d = x + x;
  return d + d;
}

// ---------------------------------------------------------------------------
// Sphere vs cylinder. The sphere is the ball of radius rho about the local
// centre c = (x, y, z) (see include/tricyl/sphere_cylinder.h for what that
// means in the world). The closed sets meet iff dist(c, C) <= rho, and
//   dist(c, C)^2 = dr^2 + e^2,  dr = max(0, sqrt(s) - r),  s = x^2 + y^2,
//                               e  = max(0, |z| - lz/2).
// The source's case split on the centre's height (beyond the top cap,
// within the slab, beyond the bottom cap), squared with care:
// In doubled units (Z = 2 z, H = lz) let E = |Z| - H = 2 (|z| - lz/2): the
// centre's doubled height beyond the nearer cap plane, <= 0 in the slab.
// |.| rounds nothing and keeps every error bound and magnitude (||a| - |b||
// <= |a - b|), so E is as good a value as Z - H in every arithmetic.
// * E > 2 rho: the centre is more than rho beyond a cap plane: disjoint
//   (the early-out, and the first sign of the cap branch).
// * Within the slab (E <= 0): sqrt(s) <= r + rho  <=>  s <= (r + rho)^2.
// * Beyond a cap (E >= 0) and E <= 2 rho: with the source's slice radius
//   f = sqrt(rho^2 - e^2) the test is sqrt(s) <= r + f, and with g = f^2,
//   G = 4 g = 4 rho^2 - E^2 >= 0 and T = 4 (s - r^2) - G:
//     s <= r^2 + g + 2 r sqrt(g)  <=>  T <= 0  or  T^2 <= 16 r^2 G,
//   squaring only when both sides are non-negative (T > 0). The two
//   formulas agree at E = 0, so both branches may claim the plane E = 0.
// Signs, in order: 2 rho - E, E, then s - (r + rho)^2 or T and
// 16 r^2 G - T^2. Every branch condition is itself a certified sign
// (Kleene logic: a context that may leave a sign open only evaluates both
// branches). Degree <= 8, depth <= 12 (16 r^2 G - T^2: Z at 5, E 6, E^2 7,
// G 8, T 10, T^2 11, the difference 12; the doublings of times4 are exact).

/// The local data of a sphere query: the centre, H = lz, r, rho.
struct SphereQuery {
  const Cylinder<double>& cyl;
  const Pose<double>& pose;
  const Sphere<double>& sph;
  double max_unitless;

  template <class A>
  struct Frame {
    using N = typename A::Num;
    explicit Frame(const SphereQuery& q)
        : c(A::local(q.pose, q.sph.center, q.max_unitless)),
          H(A::lift(q.cyl.lz)),
          r(A::lift(q.cyl.radius)),
          rho(A::lift(q.sph.radius)) {}
    Pt<N> c;
    N H, r, rho;
  };
};

/// E = |Z| - H.
template <class F>
inline auto sphereHeight(const F& f) {
  return absolute(f.c.Z) - f.H;
}
/// G = 4 rho^2 - E^2 and T = 4 (s - r^2) - G.
template <class F>
inline auto sphereT(const F& f) {
  const auto E = sphereHeight(f);
  const auto G = times4(f.rho * f.rho) - E * E;
  return times4(f.c.x * f.c.x + f.c.y * f.c.y - f.r * f.r) - G;
}

/// The sphere's signs one by one (a context whose signs may stay open:
/// KernelCtx).
template <class C, class P1, class P2, class P3, class P4, class P5>
Tri sphereCylinderBySign(C& c, bool* early, const P1& near_cap_p,
                         const P2& height_p, const P3& gap_p, const P4& t_p,
                         const P5& q_p) {
  const Sign near_cap = c.sign(near_cap_p);
  if (near_cap == Sign::kNeg) {
    *early = true;
    return Tri::kFalse;
  }
  const Sign height = c.sign(height_p);
  Tri result = Tri::kFalse;
  if (isNonPos(height) != Tri::kFalse) {  // within the slab
    result = kAnd(isNonPos(height), isNonNeg(c.sign(gap_p)));
    if (result == Tri::kTrue || isPos(height) == Tri::kFalse) return result;
  }
  // Beyond a cap: 2 rho - E >= 0, and T <= 0 or 16 r^2 G - T^2 >= 0.
  Tri t = kAnd(isNonNeg(height), isNonNeg(near_cap));
  const Tri t_neg = isNonPos(c.sign(t_p));
  if (t_neg != Tri::kTrue) t = kAnd(t, kOr(t_neg, isNonNeg(c.sign(q_p))));
  return kOr(result, t);
}

template <class C>
TRICYL_PER_SIGN_INLINE Tri sphereCylinder(C& c, bool* early) {
  *early = false;
  auto near_cap_p = [](const auto& f) {
    return (f.rho + f.rho) - sphereHeight(f);
  };
  auto height_p = [](const auto& f) { return sphereHeight(f); };
  auto gap_p = [](const auto& f) { return diskGap(f.c, f.r + f.rho); };
  auto t_p = [](const auto& f) { return sphereT(f); };
  auto q_p = [](const auto& f) {
    const auto E = sphereHeight(f);
    const auto G = times4(f.rho * f.rho) - E * E;
    const auto T = sphereT(f);
    return times4(times4(f.r * f.r)) * G - T * T;
  };
  if constexpr (C::kEagerFilter) {
    // First the whole formula below in double, all five signs at once and
    // combined without a branch (the near family's outcomes are coin
    // flips, which a branch per sign pays for); only where that leaves the
    // answer open, the open signs it needs, each certified (escalated) by
    // itself from its kept double value (resolve).
    enum { kA, kE, kG, kT, kQ };
    const Fp v[] = {c.value(near_cap_p), c.value(height_p), c.value(gap_p),
                    c.value(t_p), c.value(q_p)};
    const Verdicts d = C::verdicts(v);
    const Fp &va = v[kA], &ve = v[kE], &vg = v[kG], &vt = v[kT], &vq = v[kQ];
    // 2 rho - E >= 0 and (in the slab: E <= 0 and s <= (r + rho)^2, or
    // beyond a cap: E >= 0 and (T <= 0 or Q >= 0)), as three conjunctions.
    static constexpr Dnf kHit = makeDnf<3>({{bit(kA) | bit(kG), bit(kE)},
                                            {bit(kA) | bit(kE), bit(kT)},
                                            {bit(kA) | bit(kE) | bit(kQ), 0}});
    const DnfVerdicts terms = evalDnf(d, kHit);
    const KBool r = terms.any();
    const KBool in_slab = {false, terms.allFalse(1)};
    const KBool cap = {false, terms.allFalse(6)};
    if (r.t | r.f) {
      *early = d.isNeg(kA);
      return toTri(r.t);
    }
    // Exactly: 2 rho - E >= 0 and (E <= 0 and s <= (r + rho)^2, or E >= 0
    // and (T <= 0 or 16 r^2 G - T^2 >= 0)); a term whose filter verdict is
    // already false costs nothing more.
    if (c.resolve(near_cap_p, va) == Sign::kNeg) {
      *early = true;
      return Tri::kFalse;
    }
    Sign height = Sign::kUnknown;  // certified when first needed
    auto heightSign = [&] {
      if (height == Sign::kUnknown) height = c.resolve(height_p, ve);
      return height;
    };
    if (!in_slab.f && heightSign() != Sign::kPos &&
        c.resolve(gap_p, vg) != Sign::kNeg)
      return Tri::kTrue;
    if (!cap.f && heightSign() != Sign::kNeg &&
        (c.resolve(t_p, vt) != Sign::kPos || c.resolve(q_p, vq) != Sign::kNeg))
      return Tri::kTrue;
    return Tri::kFalse;
  } else {
    return sphereCylinderBySign(c, early, near_cap_p, height_p, gap_p, t_p,
                                q_p);
  }
}

// ---------------------------------------------------------------------------
// Segment vs cylinder (Boolean). The slab-clipped segment projects to a 2D
// segment (or point) that meets the disk iff one of its endpoints is in the
// disk or its closest point to the origin is interior and within r. The
// endpoints of the clipped piece are segment endpoints inside the slab or
// crossings with the cap planes, so the test is exactly the triangle
// kernel's (V), (X), (E) for a single edge (the degenerate triangle
// (p, q, q) is covered by these three alone, docs/exactness.md, section 2):
//   (V) an endpoint inside the solid;
//   (X) the segment crosses a cap plane Z = +-H strictly, at a point of the
//       cap disk;
//   (E) the foot of the perpendicular from the axis to the projected
//       segment is interior, within r, and its height is inside the slab.
// This is what the source's pseudo-code misses: it accepts only a root of
// the infinite-cylinder quadratic inside [0, 1] and so rejects a segment
// entirely inside (V), never checks that the root lies between the caps
// (the slab part of (E)), and never tests the cap disks (X).
//
// Terms shared by the segment and the line predicates, in terms of a = the
// local image of p and the direction e = R^T (q - p) (Z doubled as
// everywhere). e is computed from the input differences q - p (toLocal
// with t = p), not as b - a: exactly the same value, but a short or a
// distant pair p, q keeps its relative accuracy, which the filter sees
// (measured on the segment's families, 10^5 cases each: near 2.15% -> 1.92%
// exact, far 5956 -> 3340 extended-stage cases). The exact arithmetics
// take b - a (the same value, fewer operations).
//
// Every polynomial below reads a frame with the fields a (the point p's
// image), e (the direction), H and r.

/// (V): |Z| <= H (from the signs top = sign(Z - H), bot = sign(Z + H)) and
/// x^2 + y^2 <= r^2. `gap`: the disk term's polynomial.
template <class C, class P>
inline Tri vertexInside(C& c, Sign top, Sign bot, const P& gap) {
  const Tri slab = kAnd(isNonPos(top), isNonNeg(bot));
  if (slab == Tri::kFalse) return slab;
  return kAnd(slab, isNonNeg(c.sign(gap)));
}

/// (X) without its precondition: the point where the line a + mu e meets
/// the plane Z = sH, with a0 = Z_a - sH at mu = -a0 / W, W = e_Z, i.e.
/// (x_a W - e_x a0, y_a W - e_y a0) / W, lies in the cap disk:
/// X^2 + Y^2 <= r^2 W^2. Meaningful only when W != 0 (for W = 0 the test
/// degenerates to a0^2 |e|^2 <= 0); the caller supplies that condition.
template <class F>
inline auto capCrossingGap(const F& f, int side) {
  const auto a0 = side > 0 ? f.a().Z - f.H : f.a().Z + f.H;
  const auto& W = f.e().Z;
  const auto X = f.a().x * W - f.e().x * a0;
  const auto Y = f.a().y * W - f.e().y * a0;
  return (f.r * f.r) * (W * W) - X * X - Y * Y;
}

/// r^2 L - c^2, L = e_x^2 + e_y^2, c = x_a e_y - y_a e_x: the projected
/// line through a along e comes within r of the axis (for L > 0; its
/// distance^2 is c^2 / L).
template <class F>
inline auto axisDistanceGap(const F& f) {
  const auto c = f.a().x * f.e().y - f.a().y * f.e().x;
  return (f.r * f.r) * (f.e().x * f.e().x + f.e().y * f.e().y) - c * c;
}

/// (E): with L = |e_xy|^2 > 0, the foot of the perpendicular from the axis
/// to the projected line is at mu = g / L, g = -a.e, within r
/// (axisDistanceGap, whose sign is `sep`); its height Z_a + mu e_Z is in
/// the slab (times L > 0). `interior` adds 0 <= g <= L (the foot within
/// [a, a + e]: the segment's form; the line has no such condition).
/// L = e_x^2 + e_y^2.
template <class F>
inline auto axisLen(const F& f) {
  return f.e().x * f.e().x + f.e().y * f.e().y;
}
/// g = -a.e (in the xy-plane): the foot of the perpendicular is at g / L.
template <class F>
inline auto axisFoot(const F& f) {
  return -(f.a().x * f.e().x + f.a().y * f.e().y);
}
/// H L -+ (Z_a L + g e_Z): the foot's height (times L) below the top cap
/// (side +1) or above the bottom one (side -1).
template <class F>
inline auto axisFootHeight(const F& f, int side) {
  const auto L = axisLen(f);
  const auto zL = f.a().Z * L + axisFoot(f) * f.e().Z;
  return side > 0 ? f.H * L - zL : f.H * L + zL;
}

/// The direction's local x and y (e_x, e_y), as predicates.
struct DirX {
  template <class F>
  auto operator()(const F& f) const {
    return f.e().x;
  }
};
struct DirY {
  template <class F>
  auto operator()(const F& f) const {
    return f.e().y;
  }
};

/// L = e_x^2 + e_y^2 > 0, certified from the filter's value of L (PerSign):
/// L is a sum of squares, so L > 0 iff e_x != 0 or e_y != 0, exactly. The
/// two signs of degree 2 decide where L's own sign (degree 4) would take
/// the running double word: a direction nearly along the axis has L near
/// 1e-32 of its magnitude, below the a-priori stage's 2^-90.
template <class C>
inline bool axisLenPositive(C& c, const Fp& len_value) {
  return shallowSign(toFd(len_value)) == Sign::kPos ||
         c.resolve(DirX{}, c.value(DirX{})) != Sign::kZero ||
         c.resolve(DirY{}, c.value(DirY{})) != Sign::kZero;
}

/// e_x = e_y = 0 exactly: the segment or line is parallel to the axis, so
/// L = 0, g = -(x_a e_x + y_a e_y) = 0 and c = x_a e_y - y_a e_x = 0
/// exactly, and (E) is false. Certified (PerSign) only where the filter's
/// values of e_x and e_y are both 0, by their exact signs (each from the
/// direction alone: exact in double for an exact pose); false otherwise
/// (not known). For a query whose filter value of g or of r^2 L - c^2 is 0:
/// the exact-in-double check of that sign would certify the same tie from
/// the whole predicate on both frame points.
template <class C>
inline bool axisParallel(C& c) {
  const Fp vx = c.value(DirX{}), vy = c.value(DirY{});
  return toFd(vx).v == 0 && toFd(vy).v == 0 &&
         c.resolve(DirX{}, vx) == Sign::kZero &&
         c.resolve(DirY{}, vy) == Sign::kZero;
}

template <class C>
inline Tri axisApproach(C& c, bool interior, Sign sep) {
  Tri t = isPos(c.sign([](const auto& f) { return axisLen(f); }));
  if (t != Tri::kFalse) t = kAnd(t, isNonNeg(sep));
  if (interior && t != Tri::kFalse)
    t = kAnd(t, isNonNeg(c.sign([](const auto& f) { return axisFoot(f); })));
  if (interior && t != Tri::kFalse)
    t = kAnd(t, isNonNeg(c.sign(
                    [](const auto& f) { return axisLen(f) - axisFoot(f); })));
  for (int side : {1, -1}) {
    if (t == Tri::kFalse) break;
    t = kAnd(t, isNonNeg(c.sign([side](const auto& f) {
               return axisFootHeight(f, side);
             })));
  }
  return t;
}

/// Whether arithmetic A has localFrom (a frame point with its own origin).
template <class A>
constexpr auto hasLocalFrom(int)
    -> decltype(A::localFrom(std::declval<const Pose<double>&>(),
                             std::declval<const Vec3<double>&>(),
                             std::declval<const Vec3<double>&>(), 0.0),
                true) {
  return true;
}
template <class A>
constexpr bool hasLocalFrom(long) {
  return false;
}

/// The local data of a segment or line query: a = the image of p, b = the
/// image of q (the segment only), e = R^T (q - p), H = lz, r.
template <bool kSegment>
struct LinearQuery {
  LinearQuery(const Cylinder<double>& cyl_, const Pose<double>& pose_,
              const Vec3<double>& p_, const Vec3<double>& q_,
              double max_unitless_)
      : cyl(cyl_), pose(pose_), p(p_), q(q_), max_unitless(max_unitless_) {}
  const Cylinder<double>& cyl;
  const Pose<double>& pose;
  const Vec3<double>& p;
  const Vec3<double>& q;
  double max_unitless;

  /// The direction e = R^T (q - p) in arithmetic A: A::localFrom with the
  /// origin p where A has it; otherwise A::local on the pose moved to p,
  /// made once and kept here (a kernel's values may refer to their inputs:
  /// the adaptive kernel's tape does).
  template <class A>
  Pt<typename A::Num> direction() const {
    if constexpr (hasLocalFrom<A>(0)) {
      return A::localFrom(pose, p, q, max_unitless);
    } else {
      if (!at_p) {
        at_p.emplace(pose);
        at_p->t = p;
      }
      return A::local(*at_p, q, max_unitless);
    }
  }
  mutable std::optional<Pose<double>> at_p;  ///< see direction

  /// The double filter's frame: every point at once (every query reads
  /// them all). In PerSign's filter (PairFilterArith) the segment's second
  /// endpoint is b = a + e: the rounded value of R^T (p - t) + R^T (q - p),
  /// whose exact value is R^T (q - t), with the magnitude m_a + m_e (the
  /// same expression on magnitudes) and one more operation on the way
  /// (depth 5 for x and y, 6 for Z; no predicate reading b is deeper than
  /// 8, inside shallowSign's 12): three additions instead of a third frame
  /// point. FilterKernel itself (runStages' hand-off) keeps its general
  /// constant and the frame point.
  template <class A>
  class EagerFrame {
   public:
    using N = typename A::Num;
    explicit EagerFrame(const LinearQuery& q)
        : H(A::lift(q.cyl.lz)),
          r(A::lift(q.cyl.radius)),
          a_(A::local(q.pose, q.p, q.max_unitless)),
          e_(q.template direction<A>()) {
      if constexpr (kSegment && std::is_same_v<A, PairFilterArith>)
        b_ = {a_.x + e_.x, a_.y + e_.y, a_.Z + e_.Z};
      else if constexpr (kSegment)
        b_ = A::local(q.pose, q.q, q.max_unitless);
    }
    const Pt<N>& a() const { return a_; }
    const Pt<N>& b() const { return b_; }
    const Pt<N>& e() const { return e_; }
    N H, r;

   private:
    Pt<N> a_, e_, b_{};
  };
  /// The later stages' frames: each point computed when first read (an
  /// escalated sign usually reads one or two of the three).
  template <class A>
  class LazyFrame {
   public:
    using N = typename A::Num;
    explicit LazyFrame(const LinearQuery& q)
        : H(A::lift(q.cyl.lz)), r(A::lift(q.cyl.radius)), q_(q) {}
    const Pt<N>& a() const {
      if (!(have_ & 1)) {
        a_ = A::local(q_.pose, q_.p, q_.max_unitless);
        have_ |= 1;
      }
      return a_;
    }
    const Pt<N>& b() const {
      if (!(have_ & 2)) {
        b_ = A::local(q_.pose, q_.q, q_.max_unitless);
        have_ |= 2;
      }
      return b_;
    }
    const Pt<N>& e() const {
      if (!(have_ & 4)) {
        if constexpr (A::kExact) {  // the same value, three subtractions
          e_ = {b().x - a().x, b().y - a().y, b().Z - a().Z};
        } else {
          e_ = q_.template direction<A>();
        }
        have_ |= 4;
      }
      return e_;
    }
    N H, r;

   private:
    const LinearQuery& q_;
    // Zero until computed (have_): GCC cannot follow have_ through the
    // flattened open path (runOpen) and would warn of a read before a write.
    mutable Pt<N> a_{}, b_{}, e_{};
    mutable unsigned have_ = 0;
  };
  template <class A>
  using Frame =
      std::conditional_t<std::is_same_v<A, PairFilterArith> ||
                             std::is_same_v<A, KernelArith<FilterKernel>>,
                         EagerFrame<A>, LazyFrame<A>>;
};
using SegmentQuery = LinearQuery<true>;
using LineQuery = LinearQuery<false>;

template <class C>
TRICYL_PER_SIGN_INLINE Tri segmentCylinder(C& c, bool* early) {
  *early = false;
  auto top0 = [](const auto& f) { return f.a().Z - f.H; };
  auto top1 = [](const auto& f) { return f.b().Z - f.H; };
  auto bot0 = [](const auto& f) { return f.a().Z + f.H; };
  auto bot1 = [](const auto& f) { return f.b().Z + f.H; };
  auto gap0 = [](const auto& f) { return diskGap(f.a(), f.r); };
  auto gap1 = [](const auto& f) { return diskGap(f.b(), f.r); };
  auto cap_top = [](const auto& f) { return capCrossingGap(f, 1); };
  auto cap_bot = [](const auto& f) { return capCrossingGap(f, -1); };
  if constexpr (C::kEagerFilter) {
    // The whole test below in double at once, combined without a branch
    // per sign (as the sphere's and the line's: on the near family the
    // outcomes are coin flips, which a branch per sign pays for).
    auto len_p = [](const auto& f) { return axisLen(f); };
    auto sep_p = [](const auto& f) { return axisDistanceGap(f); };
    auto foot_p = [](const auto& f) { return axisFoot(f); };
    auto rest_p = [](const auto& f) { return axisLen(f) - axisFoot(f); };
    auto foot_top = [](const auto& f) { return axisFootHeight(f, 1); };
    auto foot_bot = [](const auto& f) { return axisFootHeight(f, -1); };
    enum { kT0, kT1, kB0, kB1, kG0, kG1, kXT, kXB, kL, kS, kF, kR, kHT, kHB };
    const Fp v[] = {c.value(top0),     c.value(top1),    c.value(bot0),
                    c.value(bot1),     c.value(gap0),    c.value(gap1),
                    c.value(cap_top),  c.value(cap_bot), c.value(len_p),
                    c.value(sep_p),    c.value(foot_p),  c.value(rest_p),
                    c.value(foot_top), c.value(foot_bot)};
    const Verdicts d = C::verdicts(v);
    // (V) for p, (V) for q, (X) for each cap plane as two conjunctions (the
    // endpoints strictly on opposite sides of it, one way or the other: a
    // certified sign is never zero), (E).
    static constexpr Dnf kHit = makeDnf<7>(
        {{bit(kB0) | bit(kG0), bit(kT0)},
         {bit(kB1) | bit(kG1), bit(kT1)},
         {bit(kT1) | bit(kXT), bit(kT0)},
         {bit(kT0) | bit(kXT), bit(kT1)},
         {bit(kB1) | bit(kXB), bit(kB0)},
         {bit(kB0) | bit(kXB), bit(kB1)},
         {bit(kL) | bit(kS) | bit(kF) | bit(kR) | bit(kHT) | bit(kHB), 0}});
    const DnfVerdicts terms = evalDnf(d, kHit);
    const bool v0_false = terms.allFalse(1), v1_false = terms.allFalse(2),
               x_top_false = terms.allFalse(12),
               x_bot_false = terms.allFalse(48), e_false = terms.allFalse(64);
    // Both endpoints strictly beyond the same cap plane.
    const unsigned t01 = bit(kT0) | bit(kT1), b01 = bit(kB0) | bit(kB1);
    const bool beyond_cap = ((d.pos & t01) == t01) | ((d.neg & b01) == b01);
    KBool r = terms.any();
    r.f = r.f | beyond_cap;
    if (r.t | r.f) {
      *early = beyond_cap;
      return toTri(r.t);
    }
    // Open: (V) or (X) or (E), exactly. A term whose filter verdict is
    // already false is skipped; otherwise its signs are certified one at a
    // time from their kept double values (resolve: escalated only if open),
    // each at most once, until the term is decided. PerSign::runOpen: the
    // compensated frame's points built when first read (an open sign of the
    // segment reads a, b or a and e), the a-priori stage in line. (The
    // closure holds one reference and small values: a capture by reference
    // of everything costs a copy of each pointer on entry, about 40
    // instructions an open query.)
    return c.template runOpen<false>(
        [&v, v0_false, v1_false, x_top_false, x_bot_false, e_false, top0, top1,
         bot0, bot1, gap0, gap1, cap_top, cap_bot, len_p, sep_p, foot_p, rest_p,
         foot_top, foot_bot](auto& oc) {
          const Fp &vt0 = v[kT0], &vt1 = v[kT1], &vb0 = v[kB0], &vb1 = v[kB1],
                   &vg0 = v[kG0], &vg1 = v[kG1], &vxt = v[kXT], &vxb = v[kXB],
                   &vl = v[kL], &vs = v[kS], &vf = v[kF], &vr = v[kR],
                   &vht = v[kHT], &vhb = v[kHB];
          Sign memo[4] = {Sign::kUnknown, Sign::kUnknown, Sign::kUnknown,
                          Sign::kUnknown};
          auto slab = [&](int k) {  // top0, top1, bot0, bot1, certified
            if (memo[k] == Sign::kUnknown) {
              switch (k) {
                case 0:
                  memo[0] = oc.resolve(top0, vt0);
                  break;
                case 1:
                  memo[1] = oc.resolve(top1, vt1);
                  break;
                case 2:
                  memo[2] = oc.resolve(bot0, vb0);
                  break;
                default:
                  memo[3] = oc.resolve(bot1, vb1);
              }
            }
            return memo[k];
          };
          auto nonNegR = [&oc](const auto& pred, const Fp& value) {
            return oc.resolve(pred, value) != Sign::kNeg;
          };
          auto apart = [&slab](int k0, int k1) {
            const Sign s0 = slab(k0);
            if (s0 == Sign::kZero) return false;
            const Sign s1 = slab(k1);
            return s1 != Sign::kZero && s1 != s0;
          };
          if (!v0_false && slab(0) != Sign::kPos && slab(2) != Sign::kNeg &&
              nonNegR(gap0, vg0))
            return Tri::kTrue;
          if (!v1_false && slab(1) != Sign::kPos && slab(3) != Sign::kNeg &&
              nonNegR(gap1, vg1))
            return Tri::kTrue;
          // (E) before (X): of the orders measured on the near family
          // (callgrind), (V) (E) (X) escalates least ((V) (X) (E) 1% more, (E)
          // (V) (X) 2%). Within (E) the low-degree conditions first (any of
          // them may be the one that fails). A segment parallel to the axis
          // (axisParallel, tried where the filter's g is 0): (E) false without
          // its signs.
          if (!e_false && !(toFd(vf).v == 0 && axisParallel(oc)) &&
              nonNegR(foot_p, vf) && nonNegR(rest_p, vr) &&
              oc.resolve(len_p, vl) == Sign::kPos && nonNegR(foot_top, vht) &&
              nonNegR(foot_bot, vhb) && nonNegR(sep_p, vs))
            return Tri::kTrue;
          if (!x_top_false && apart(0, 1) && nonNegR(cap_top, vxt))
            return Tri::kTrue;
          if (!x_bot_false && apart(2, 3) && nonNegR(cap_bot, vxb))
            return Tri::kTrue;
          return Tri::kFalse;
        });
  }
  const Sign top[2] = {c.sign(top0), c.sign(top1)};
  // Both endpoints strictly beyond the same cap plane.
  if (top[0] == Sign::kPos && top[1] == Sign::kPos) {
    *early = true;
    return Tri::kFalse;
  }
  const Sign bot[2] = {c.sign(bot0), c.sign(bot1)};
  if (bot[0] == Sign::kNeg && bot[1] == Sign::kNeg) {
    *early = true;
    return Tri::kFalse;
  }
  // Both endpoints strictly beyond one side of the disk's bounding square
  // (from the filter only: the terms below decide what it cannot).
  {
    auto beyond = [&c](auto u) {
      return c.cheapSign([&u](const auto& f) { return u(f.a()) - f.r; }) ==
                 Sign::kPos &&
             c.cheapSign([&u](const auto& f) { return u(f.b()) - f.r; }) ==
                 Sign::kPos;
    };
    if (beyond([](const auto& v) { return v.x; }) ||
        beyond([](const auto& v) { return -v.x; }) ||
        beyond([](const auto& v) { return v.y; }) ||
        beyond([](const auto& v) { return -v.y; })) {
      *early = true;
      return Tri::kFalse;
    }
  }
  AnyOf any;
  // (V)
  if (any.add(vertexInside(c, top[0], bot[0], gap0))) return Tri::kTrue;
  if (any.add(vertexInside(c, top[1], bot[1], gap1))) return Tri::kTrue;
  // (X) a strict crossing of Z = sH at a point of the cap disk.
  for (int side : {1, -1}) {
    const Sign* sa = side > 0 ? top : bot;
    const Tri crossing =
        kOr(kAnd(isNeg(sa[0]), isPos(sa[1])), kAnd(isPos(sa[0]), isNeg(sa[1])));
    if (crossing == Tri::kFalse) continue;
    const Sign gap = side > 0 ? c.sign(cap_top) : c.sign(cap_bot);
    if (any.add(kAnd(crossing, isNonNeg(gap)))) return Tri::kTrue;
  }
  // (E) the closest approach to the axis, interior to the segment.
  const Sign sep = c.sign([](const auto& f) { return axisDistanceGap(f); });
  if (any.add(axisApproach(c, true, sep))) return Tri::kTrue;
  return any.result();
}

// ---------------------------------------------------------------------------
// Line vs cylinder (Boolean): the line a + mu e, mu real, a the local
// image of p and e = R^T (q - p) (from the input differences q - p: a short
// or a distant pair p, q keeps the direction's relative accuracy, which
// the filter then sees; exactly, e = b - a for b the image of q).
// * e_Z != 0: the line meets the slab in the chord between its crossings
//   with Z = -H and Z = +H, which projects to a 2D segment (a point if the
//   line is parallel to the axis). That segment meets the disk iff an end
//   is in the disk, (X) for each cap plane, now with no crossing condition
//   beyond e_Z != 0, or the closest approach of the projected line to the
//   axis falls between the ends and within r, which is (E) without the
//   interior condition: the foot lies between the crossings iff its height
//   is in the slab (Z is monotone along the line).
// * e_Z = 0 (a line parallel to the cap planes): it is in the slab or not
//   as a whole; then for L > 0 it meets the disk iff c^2 <= r^2 L, which is
//   again (E) (its height condition reads |Z_a| <= H), and for L = 0
//   (e = 0: p == q, or a singular R) it is the point a: (V). (X) is unsound
//   for e_Z = 0 and carries e_Z != 0; it is evaluated first, so a line
//   parallel to the cap planes off them (X false by itself) needs no
//   certified sign of e_Z = 0, which no filter can give.
// Early-out: the projected line stays farther than r from the axis,
// r^2 L - c^2 < 0 (then no term can hold). Degrees, depths and magnitudes
// as the segment's terms (e has the degree, depth and gate magnitude of a
// local coordinate).

template <class C>
TRICYL_PER_SIGN_INLINE Tri lineCylinder(C& c, bool* early) {
  *early = false;
  auto sep_p = [](const auto& f) { return axisDistanceGap(f); };
  if constexpr (C::kEagerFilter) {
    // The terms below in double at once, combined without a branch per
    // sign (as the sphere's); an open answer certifies the open signs it
    // needs from their kept double values (as the segment's).
    auto len_p = [](const auto& f) { return axisLen(f); };
    auto foot_top = [](const auto& f) { return axisFootHeight(f, 1); };
    auto foot_bot = [](const auto& f) { return axisFootHeight(f, -1); };
    auto ez_p = [](const auto& f) { return f.e().Z; };
    auto cap_top = [](const auto& f) { return capCrossingGap(f, 1); };
    auto cap_bot = [](const auto& f) { return capCrossingGap(f, -1); };
    auto top_p = [](const auto& f) { return f.a().Z - f.H; };
    auto bot_p = [](const auto& f) { return f.a().Z + f.H; };
    auto gap_p = [](const auto& f) { return diskGap(f.a(), f.r); };
    enum { kS, kL, kHT, kHB, kEZ, kXT, kXB };
    const Fp v[] = {c.value(sep_p),    c.value(len_p), c.value(foot_top),
                    c.value(foot_bot), c.value(ez_p),  c.value(cap_top),
                    c.value(cap_bot)};
    const Verdicts d = C::verdicts(v);
    // Early-out: the projected line stays farther than r from the axis.
    const bool apart = d.isNeg(kS);
    // (E); (X) as four conjunctions (e_Z certainly > 0 or < 0, the crossing
    // of either cap plane in its disk).
    static constexpr Dnf kHit =
        makeDnf<5>({{bit(kS) | bit(kL) | bit(kHT) | bit(kHB), 0},
                    {bit(kEZ) | bit(kXT), 0},
                    {bit(kXT), bit(kEZ)},
                    {bit(kEZ) | bit(kXB), 0},
                    {bit(kXB), bit(kEZ)}});
    const DnfVerdicts terms = evalDnf(d, kHit);
    const KBool approach = {false, terms.allFalse(1)};
    const KBool cross = {false, terms.allFalse(30)};
    // e != 0 certified (L > 0 or e_Z != 0): the line is not a point, and
    // (V) adds nothing to (E) or (X) (see above), so its signs are left out
    // of the double test and read only for a line that may be a point.
    const bool moving = bool(d.isPos(kL) | d.isPos(kEZ) | d.isNeg(kEZ));
    KBool r = terms.any();
    r.f = (r.f & moving) | apart;
    if (r.t | r.f) {
      *early = apart;
      return toTri(r.t);
    }
    // Open: the signs it needs, certified one by one (PerSign::runOpen).
    // (The closure as the segment's.)
    return c.template runOpen<true>([&v, d, approach, cross, moving, early,
                                     sep_p, foot_top, foot_bot, ez_p, cap_top,
                                     cap_bot, top_p, bot_p, gap_p](auto& oc) {
      // r^2 L - c^2 with c = x_a e_y - y_a e_x cancelling far below its
      // magnitude (p far along the line from its closest approach to the
      // axis): the a-priori stage (PerSign), whose bound is relative to c's
      // magnitude squared, cannot decide it below a relative offset of
      // about 2^-90 (m_c / |c|)^2, i.e. for no offset below 2^-42 once m_c
      // > 2^24 |c| (the filter's c is then within 2^-25 of its value); the
      // running bound, relative to |c|, can. A choice of stage only
      // (measured on the line's near family: 757 -> 747 instructions a
      // query; thresholds 2^8 .. 2^40 gave 759 .. 746).
      auto cross_p = [](const auto& f) {
        return f.a().x * f.e().y - f.a().y * f.e().x;
      };
      // A line parallel to the axis (axisParallel): r^2 L - c^2 = 0 exactly
      // and (E) false.
      const bool axial = toFd(v[kS]).v == 0 && axisParallel(oc);
      auto nonNegR = [&oc](const auto& pred, const Fp& value) {
        return oc.resolve(pred, value) != Sign::kNeg;
      };
      // (E), (X), (V) as below, each skipped if the filter already said
      // false. r^2 L - c^2 >= 0 is read only by (E): the early-out it gives
      // is implied by every term ((X) and (V) put a point of the line
      // within r of the axis), and it is the dearest of (E)'s signs (degree
      // 8, and the running stage where c cancels), so it is certified last,
      // only where the others hold (measured on the line's near family: 643
      // -> 627 instructions a query; every sep escalation that took the
      // running stage there fell on queries whose (E) fails by a foot
      // height).
      if (!approach.f && !axial && axisLenPositive(oc, v[kL]) &&
          nonNegR(foot_top, v[kHT]) && nonNegR(foot_bot, v[kHB])) {
        const Fd cv = toFd(oc.value(cross_p));
        const Sign sep = cv.m > 0x1p24 * std::fabs(cv.v)
                             ? oc.resolveRunning(sep_p, v[kS])
                             : oc.resolve(sep_p, v[kS]);
        if (sep != Sign::kNeg) return Tri::kTrue;
        *early = true;
        return Tri::kFalse;
      }
      if (!cross.f && ((!d.isNeg(kXT) && nonNegR(cap_top, v[kXT])) ||
                       (!d.isNeg(kXB) && nonNegR(cap_bot, v[kXB]))))
        if (oc.resolve(ez_p, v[kEZ]) != Sign::kZero) return Tri::kTrue;
      if (!moving && oc.resolve(top_p, oc.value(top_p)) != Sign::kPos &&
          nonNegR(bot_p, oc.value(bot_p)) && nonNegR(gap_p, oc.value(gap_p)))
        return Tri::kTrue;
      return Tri::kFalse;
    });
  }
  const Sign sep = c.sign(sep_p);
  if (sep == Sign::kNeg) {
    *early = true;
    return Tri::kFalse;
  }
  AnyOf any;
  // (E) the closest approach to the axis, anywhere on the line: first, as
  // it decides most hits with a few low-degree signs.
  if (any.add(axisApproach(c, false, sep))) return Tri::kTrue;
  // (X) the crossing with Z = sH, if the line is not parallel to it, in the
  // cap disk.
  Tri slanted = Tri::kUnknown;
  bool have_slanted = false;
  for (int side : {1, -1}) {
    const Tri t = isNonNeg(
        c.sign([side](const auto& f) { return capCrossingGap(f, side); }));
    if (t == Tri::kFalse) continue;
    if (!have_slanted) {
      slanted = kNot(isZero(c.sign([](const auto& f) { return f.e().Z; })));
      have_slanted = true;
    }
    if (any.add(kAnd(t, slanted))) return Tri::kTrue;
  }
  // (V): needed only for e = 0 (the line is the point a), where (E) and (X)
  // are false.
  if (any.add(vertexInside(c,
                           c.sign([](const auto& f) { return f.a().Z - f.H; }),
                           c.sign([](const auto& f) { return f.a().Z + f.H; }),
                           [](const auto& f) { return diskGap(f.a(), f.r); })))
    return Tri::kTrue;
  return any.result();
}

}  // namespace tricyl::detail
