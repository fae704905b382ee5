// The cylinder query family (issue 5), each predicate written ONCE over a
// kernel K of src/filter.h and run through the same three stages as the
// triangle kernel: FilterKernel (certified double), ExtendedKernel
// (certified long double, running error bound), ExactKernel (GMP dyadic).
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
// All inside the budget; no division and no square root anywhere.
#pragma once

#include <cstdint>
#include <cstring>
#include <initializer_list>

#include "filter.h"
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
struct KernelTag {
  using type = K;
};

inline Answer toAnswer(Tri t) {
  return t == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint;
}

/// Runs `pred(KernelTag<K>{}, &early) -> Tri` through the three stages: the
/// double filter and the extended filter inside the range gate, then the
/// exact kernel, which never answers kUnknown.
template <class Pred>
Decision runStages(const Pred& pred, double max_len, double max_unitless) {
  bool early = false;
  if (rangeGateOk(max_len, max_unitless)) {
    const Tri t = pred(KernelTag<FilterKernel>{}, &early);
    if (t != Tri::kUnknown)
      return {toAnswer(t), early ? Stage::kEarlyOut : Stage::kFastPath};
    const Tri e = pred(KernelTag<ExtendedKernel>{}, &early);
    if (e != Tri::kUnknown) return {toAnswer(e), Stage::kExtended};
  }
  return {toAnswer(pred(KernelTag<ExactKernel>{}, &early)), Stage::kExact};
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
  LocalPoint<K> p[2];
  typename K::Num H, r;
};

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
  for (int i = 0; i < 2; ++i) {
    const LocalPoint<K>& v = q.p[i];
    const Tri slab = kAnd(isNonPos(top[i]), isNonNeg(bot[i]));
    if (slab == Tri::kFalse) continue;
    if (any.add(kAnd(slab, isNonNeg(K::sign(r2 - v.x * v.x - v.y * v.y)))))
      return Tri::kTrue;
  }
  // (X) crossing of Z = sH at (x_0 a_1 - x_1 a_0, y_0 a_1 - y_1 a_0) / W,
  // W = a_1 - a_0 != 0, a = Z - sH; inside iff X^2 + Y^2 <= r^2 W^2.
  for (int side = 0; side < 2; ++side) {
    const Sign* sa = side == 0 ? top : bot;
    const Tri crossing =
        kOr(kAnd(isNeg(sa[0]), isPos(sa[1])), kAnd(isPos(sa[0]), isNeg(sa[1])));
    if (crossing == Tri::kFalse) continue;
    const N a0 = side == 0 ? N(a.Z - H) : N(a.Z + H);
    const N a1 = side == 0 ? N(b.Z - H) : N(b.Z + H);
    const N X = a.x * a1 - b.x * a0;
    const N Y = a.y * a1 - b.y * a0;
    const N W = a1 - a0;
    if (any.add(
            kAnd(crossing, isNonNeg(K::sign(r2 * (W * W) - X * X - Y * Y)))))
      return Tri::kTrue;
  }
  // (E) e = b - a projected, L = |e|^2 > 0, foot at mu = g / L with
  // g = -a.e; interior: 0 <= g <= L; distance^2 = c^2 / L with
  // c = a x b; height Z_a + mu (Z_b - Z_a) in the slab, times L > 0.
  {
    const N ex = b.x - a.x;
    const N ey = b.y - a.y;
    const N L = ex * ex + ey * ey;
    Tri t = isPos(K::sign(L));
    if (t != Tri::kFalse) {
      const N c = a.x * b.y - b.x * a.y;
      t = kAnd(t, isNonNeg(K::sign(r2 * L - c * c)));
    }
    N g{}, zL{}, HL{};
    if (t != Tri::kFalse) {
      g = -(a.x * ex + a.y * ey);
      t = kAnd(t, isNonNeg(K::sign(g)));
    }
    if (t != Tri::kFalse) t = kAnd(t, isNonNeg(K::sign(L - g)));
    if (t != Tri::kFalse) {
      zL = a.Z * L + g * (b.Z - a.Z);
      HL = H * L;
      t = kAnd(t, isNonNeg(K::sign(HL - zL)));
    }
    if (t != Tri::kFalse) t = kAnd(t, isNonNeg(K::sign(HL + zL)));
    if (any.add(t)) return Tri::kTrue;
  }
  return any.result();
}

}  // namespace tricyl::detail
