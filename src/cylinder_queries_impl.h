// SPDX-License-Identifier: BSD-3-Clause
// The cylinder query family, each predicate written ONCE over a kernel K of
// src/filter.h and decided by the same driver as the triangle kernel
// (runStages, src/stages.h): FilterKernel (certified double), then, for a
// query it leaves open, AdaptiveKernel (src/adaptive.h), which re-decides
// only the open signs in double-word, then exactly.
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
//   sphere 2 rho - (Z -+ H), s - (r + rho)^2      4      7      2^91
//   sphere T, 16 r^2 G - T^2                      8     11      2^190
//   segment (V), (X), (E): as the triangle kernel's (V), (X), (E):
//          degree <= 8, depth <= 11, magnitude <= 2^370 (docs/exactness.md)
//   line   (V), (X), (E) and its early-out r^2 L - c^2: the segment's
//          terms with the direction R^T (q - p) for b - a (the same
//          degree, depth and magnitude as a local coordinate), same bounds
// All inside the budget; no division and no square root anywhere.
#pragma once

#include <cstdint>
#include <cstring>
#include <initializer_list>
#include <type_traits>

#include "filter.h"
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
// Sphere vs cylinder. The sphere is the ball of radius rho about the local
// centre c = (x, y, z) (see include/tricyl/sphere_cylinder.h for what that
// means in the world). The closed sets meet iff dist(c, C) <= rho, and
//   dist(c, C)^2 = dr^2 + e^2,  dr = max(0, sqrt(s) - r),  s = x^2 + y^2,
//                               e  = max(0, |z| - lz/2).
// The source's case split on the centre's height (beyond the top cap,
// within the slab, beyond the bottom cap), squared with care:
// * Within the slab (e = 0): sqrt(s) <= r + rho  <=>  s <= (r + rho)^2.
// * Beyond a cap (e >= 0, in doubled units E = 2e = Z - H or -Z - H):
//   first e <= rho, i.e. 2 rho - E >= 0. Then with the source's slice
//   radius f = sqrt(rho^2 - e^2) the test is sqrt(s) <= r + f, and with
//   g = f^2, G = 4 g = 4 rho^2 - E^2 >= 0 and T = 4 (s - r^2) - G:
//     s <= r^2 + g + 2 r sqrt(g)  <=>  T <= 0  or  T^2 <= 16 r^2 G,
//   squaring only when both sides are non-negative (T > 0). The two
//   formulas agree at E = 0, so both branches may claim the plane Z = +-H.
// Every branch condition is itself a certified sign (Kleene logic): an
// undecided height only means the next stage decides.

template <class K>
Tri sphereBeyondCap(const typename K::Num& E, const typename K::Num& s,
                    const typename K::Num& r, const typename K::Num& rho) {
  using N = typename K::Num;
  Tri t = isNonNeg(K::sign((rho + rho) - E));
  if (t == Tri::kFalse) return t;
  const N G = (rho * rho) * K::lift(4.0) - E * E;
  const N T = (s - r * r) * K::lift(4.0) - G;
  const Tri t_neg = isNonPos(K::sign(T));
  if (t_neg == Tri::kTrue) return t;
  const Tri t_sq = isNonNeg(K::sign((r * r) * K::lift(16.0) * G - T * T));
  return kAnd(t, kOr(t_neg, t_sq));
}

template <class K>
Tri sphereCylinder(const LocalPoint<K>& c, const typename K::Num& H,
                   const typename K::Num& r, const typename K::Num& rho,
                   bool* early) {
  using N = typename K::Num;
  const N top = c.Z - H;   // E of the top branch
  const N bot = -c.Z - H;  // E of the bottom branch
  const N rho2 = rho + rho;
  // Early-out: the centre is more than rho beyond a cap plane.
  if (K::sign(top - rho2) == Sign::kPos || K::sign(bot - rho2) == Sign::kPos) {
    *early = true;
    return Tri::kFalse;
  }
  const N s = c.x * c.x + c.y * c.y;
  const Sign s_top = K::sign(top);
  const Sign s_bot = K::sign(bot);
  // Within the slab.
  Tri result = kAnd(kAnd(isNonPos(s_top), isNonPos(s_bot)),
                    isNonNeg(K::sign((r + rho) * (r + rho) - s)));
  if (result == Tri::kTrue) return result;
  if (isNonNeg(s_top) != Tri::kFalse)
    result =
        kOr(result, kAnd(isNonNeg(s_top), sphereBeyondCap<K>(top, s, r, rho)));
  if (result == Tri::kTrue) return result;
  if (isNonNeg(s_bot) != Tri::kFalse)
    result =
        kOr(result, kAnd(isNonNeg(s_bot), sphereBeyondCap<K>(bot, s, r, rho)));
  return result;
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

template <class K>
struct SegLocal {
  LocalPoint<K> p[2];  // the images of p and q
  LocalPoint<K> e;     // R^T (q - p), from the input differences
  typename K::Num H, r;
};

// Terms shared by the segment and the line predicates, in terms of a = the
// local image of p and the direction e = R^T (q - p) (Z doubled as
// everywhere). e is computed from the input differences q - p (toLocal
// with t = p), not as b - a: exactly the same value, but a short or a
// distant pair p, q keeps its relative accuracy, which the filter sees
// (measured on the segment's families, 10^5 cases each: near 2.15% -> 1.92%
// exact, far 5956 -> 3340 extended-stage cases). top/bot: signs of Z - H
// and Z + H at a point.

/// (V): the point v is in the solid.
template <class K>
inline Tri vertexInside(const LocalPoint<K>& v, Sign top, Sign bot,
                        const typename K::Num& r2) {
  const Tri slab = kAnd(isNonPos(top), isNonNeg(bot));
  if (slab == Tri::kFalse) return slab;
  return kAnd(slab, isNonNeg(K::sign(r2 - v.x * v.x - v.y * v.y)));
}

/// (X) without its precondition: the point where the line a + mu e meets
/// the plane Z = sH, with a0 = Z_a - sH at mu = -a0 / W, W = e_Z, i.e.
/// (x_a W - e_x a0, y_a W - e_y a0) / W, lies in the cap disk:
/// X^2 + Y^2 <= r^2 W^2. Meaningful only when W != 0 (for W = 0 the test
/// degenerates to a0^2 |e|^2 <= 0); the caller supplies that condition.
template <class K>
inline Tri capCrossingInDisk(const LocalPoint<K>& a, const LocalPoint<K>& e,
                             const typename K::Num& a0,
                             const typename K::Num& r2) {
  using N = typename K::Num;
  const N& W = e.Z;
  const N X = a.x * W - e.x * a0;
  const N Y = a.y * W - e.y * a0;
  return isNonNeg(K::sign(r2 * (W * W) - X * X - Y * Y));
}

/// The sign of r^2 L - c^2, L = e_x^2 + e_y^2, c = x_a e_y - y_a e_x: the
/// projected line through a along e comes within r of the axis (for
/// L > 0; its distance^2 is c^2 / L).
template <class K>
inline Sign axisDistance(const LocalPoint<K>& a, const LocalPoint<K>& e,
                         const typename K::Num& r2) {
  using N = typename K::Num;
  const N c = a.x * e.y - a.y * e.x;
  return K::sign(r2 * (e.x * e.x + e.y * e.y) - c * c);
}

/// (E): with L = |e_xy|^2 > 0, the foot of the perpendicular from the axis
/// to the projected line is at mu = g / L, g = -a.e, within r
/// (axisDistance); its height Z_a + mu e_Z is in the slab (times L > 0).
/// `interior` adds 0 <= g <= L (the foot within [a, a + e]: the segment's
/// form; the line has no such condition). `sep`, if not null, is
/// axisDistance computed already.
template <class K>
inline Tri axisApproach(const LocalPoint<K>& a, const LocalPoint<K>& e,
                        const typename K::Num& H, const typename K::Num& r2,
                        bool interior, const Sign* sep = nullptr) {
  using N = typename K::Num;
  const N L = e.x * e.x + e.y * e.y;
  Tri t = isPos(K::sign(L));
  if (t != Tri::kFalse)
    t = kAnd(t, isNonNeg(sep != nullptr ? *sep : axisDistance<K>(a, e, r2)));
  N g{}, zL{}, HL{};
  if (t != Tri::kFalse) {
    g = -(a.x * e.x + a.y * e.y);
    if (interior) t = kAnd(t, isNonNeg(K::sign(g)));
  }
  if (interior && t != Tri::kFalse) t = kAnd(t, isNonNeg(K::sign(L - g)));
  if (t != Tri::kFalse) {
    zL = a.Z * L + g * e.Z;
    HL = H * L;
    t = kAnd(t, isNonNeg(K::sign(HL - zL)));
  }
  if (t != Tri::kFalse) t = kAnd(t, isNonNeg(K::sign(HL + zL)));
  return t;
}

template <class K>
Tri segmentCylinder(const SegLocal<K>& q, bool* early) {
  using N = typename K::Num;
  const N& H = q.H;
  const LocalPoint<K>& a = q.p[0];
  const LocalPoint<K>& b = q.p[1];
  *early = false;
  const Sign top[2] = {K::sign(a.Z - H), K::sign(b.Z - H)};
  const Sign bot[2] = {K::sign(a.Z + H), K::sign(b.Z + H)};
  // Both endpoints strictly beyond the same cap plane.
  if ((top[0] == Sign::kPos && top[1] == Sign::kPos) ||
      (bot[0] == Sign::kNeg && bot[1] == Sign::kNeg)) {
    *early = true;
    return Tri::kFalse;
  }
  // Both endpoints strictly beyond one side of the disk's bounding square.
  {
    const N& r = q.r;
    auto beyond = [&](const N& u, const N& v) {
      return K::sign(u - r) == Sign::kPos && K::sign(v - r) == Sign::kPos;
    };
    if (beyond(a.x, b.x) || beyond(-a.x, -b.x) || beyond(a.y, b.y) ||
        beyond(-a.y, -b.y)) {
      *early = true;
      return Tri::kFalse;
    }
  }
  const N r2 = q.r * q.r;
  AnyOf any;
  // (V)
  for (int i = 0; i < 2; ++i)
    if (any.add(vertexInside<K>(q.p[i], top[i], bot[i], r2))) return Tri::kTrue;
  const LocalPoint<K>& e = q.e;
  // (X) a strict crossing of Z = sH at a point of the cap disk.
  for (int side = 0; side < 2; ++side) {
    const Sign* sa = side == 0 ? top : bot;
    const Tri crossing =
        kOr(kAnd(isNeg(sa[0]), isPos(sa[1])), kAnd(isPos(sa[0]), isNeg(sa[1])));
    if (crossing == Tri::kFalse) continue;
    const N a0 = side == 0 ? N(a.Z - H) : N(a.Z + H);
    if (any.add(kAnd(crossing, capCrossingInDisk<K>(a, e, a0, r2))))
      return Tri::kTrue;
  }
  // (E) the closest approach to the axis, interior to the segment.
  if (any.add(axisApproach<K>(a, e, H, r2, true))) return Tri::kTrue;
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

template <class K>
struct LineLocal {
  LocalPoint<K> a, e;  // a point of the line, its direction (Z doubled)
  typename K::Num H, r;
};

template <class K>
Tri lineCylinder(const LineLocal<K>& q, bool* early) {
  using N = typename K::Num;
  const N& H = q.H;
  const LocalPoint<K>& a = q.a;
  const LocalPoint<K>& e = q.e;
  *early = false;
  const N r2 = q.r * q.r;
  const Sign sep = axisDistance<K>(a, e, r2);
  if (sep == Sign::kNeg) {
    *early = true;
    return Tri::kFalse;
  }
  AnyOf any;
  // (V)
  if (any.add(vertexInside<K>(a, K::sign(a.Z - H), K::sign(a.Z + H), r2)))
    return Tri::kTrue;
  // (X) the crossing with Z = sH, if the line is not parallel to it, in the
  // cap disk.
  Tri slanted = Tri::kUnknown;
  bool have_slanted = false;
  for (int side = 0; side < 2; ++side) {
    const N a0 = side == 0 ? N(a.Z - H) : N(a.Z + H);
    Tri t = capCrossingInDisk<K>(a, e, a0, r2);
    if (t == Tri::kFalse) continue;
    if (!have_slanted) {
      slanted = kNot(isZero(K::sign(e.Z)));
      have_slanted = true;
    }
    if (any.add(kAnd(t, slanted))) return Tri::kTrue;
  }
  // (E) the closest approach to the axis, anywhere on the line.
  if (any.add(axisApproach<K>(a, e, H, r2, false, &sep))) return Tri::kTrue;
  return any.result();
}

}  // namespace tricyl::detail
