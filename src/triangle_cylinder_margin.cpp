// SPDX-License-Identifier: BSD-3-Clause
// Triangle vs the margin-neighbourhood of a cylinder: exact (docs/margin.md).
//
// With C the closed cylinder (radius r, half-length h = lz/2) and B_m the
// closed ball of radius m, the nearest point of C to any point p is on the
// barrel, on a cap's interior or on a rim circle, so
//   C + B_m = Cyl(r + m, h)  u  Cyl(r, h + m)  u  Tor(+h)  u  Tor(-h),
// Tor(c) the solid torus of tube radius m around the rim circle at z = c.
// The triangle meets C + B_m iff it meets one of the four parts.
//
// The cylinders: the exact triangle kernel (src/triangle_cylinder_impl.h)
// with r + m (resp. lz + 2m) as the SUM of its two inputs: first bracketed
// by the public intersect on the two neighbouring doubles of the rounded sum
// (a subset and a superset, both exact tests), and only where the bracket
// disagrees, i.e. where the true radius lies in one ulp of the triangle's
// radial reach, re-decided with the sum as a node of the adaptive kernel's
// tape (double-word, then exact expansions or GMP).
//
// The tori: a point (rho, z) is within m of the rim circle (radius r, height
// c) iff (rho - r)^2 + (z - c)^2 <= m^2. With
//   L = rho^2 + (z - c)^2 + r^2 - m^2,   Q = L^2 - 4 r^2 rho^2
// that is L <= 2 r rho, i.e. L <= 0 or Q <= 0 (both sides squared only where
// both are non-negative): no square root. Along an edge p(s) = a + s (b - a),
// L is a quadratic and Q a quartic in s; the edge meets the torus iff one of
// them is <= 0 somewhere on [0, 1]. The face interior is needed only when no
// edge meets the torus and the triangle misses C (so it misses the rim
// circle): then a component of torus-cap-plane lies inside the triangle and
// holds a local minimum of dist(., circle) on the plane, which (off the axis
// and off the circle) is the foot of a rim point where the plane's normal n
// lies in the meridian plane: the rim points r (n_x, n_y)/|n_xy| (+-), or any
// rim point when n_xy = 0 (docs/margin.md has the proof). Testing these two
// feet (inside the triangle, and within m of their rim point) is exact in
// Q(sqrt(n_x^2 + n_y^2)): sign(a + b sqrt(D)) from the signs of a, b and
// a^2 - b^2 D.
//
// Stages of the tori. Edges: a double filter with running error bounds (the
// rules of RunningDoubleKernel, src/filter.h) on the inputs scaled by a
// power of two to unit size, in which L and Q are decided by their Bernstein
// coefficients on [0, 1] (formed from the end points) with de Casteljau
// subdivision (all coefficients > 0: no point of the edge is inside; an end
// value < 0: a point is), to a fixed depth and a fixed number of intervals;
// the edges it leaves open the same in double-word (DoubleWordKernel), then
// in GMP integers, the quartic by its ends, its Bernstein coefficients and
// its Sturm sequence on (0, 1), the quadratic by its ends and vertex. Where
// the exact scaling fails or the inputs are outside the range gate, the
// filter runs on rescaled inputs in UnderflowKernel (no absolute slack)
// before GMP. The face: the stage driver of src/stages.h (FilterKernel, then
// the adaptive kernel) on the scaled inputs (UnderflowKernel, then GMP, in
// the other case). Every stage does a bounded amount of work;
// docs/margin.md has the derivations and the exactness argument.
#include "tricyl/triangle_cylinder_margin.h"

#include <gmpxx.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>
#include <utility>
#include <vector>

#include "cylinder_queries_impl.h"
#include "eft.h"
#include "filter.h"
#include "margin_sturm.h"
#include "stages.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using detail::kAnd;
using detail::kEdge;
using detail::kOr;
using detail::Sign;
using detail::Tri;

// ---------------------------------------------------------------------------
// Exact sums of two doubles: the rounded sum and its error (Knuth's TwoSum),
// and the neighbouring doubles below and above the exact sum.

/// The next double above x >= 0 (finite), and below x > 0, by the bits
/// (the sizes here are never negative).
double nextUp(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  b += 1;
  std::memcpy(&x, &b, sizeof b);
  return x;
}
double nextDown(double x) {
  std::uint64_t b;
  std::memcpy(&b, &x, sizeof b);
  b -= 1;
  std::memcpy(&x, &b, sizeof b);
  return x;
}

/// For a, b >= 0 (+0, never -0): the rounded sum s >= 0, its error e, and
/// the neighbouring doubles below and above the exact sum (e < 0 implies
/// s > 0; e > 0 with s the largest double gives +inf, checked by callers).
struct TwoSum {
  double s;     // fl(a + b), finite
  double e;     // a + b - s exactly
  bool finite;  // false: the rounded sum overflowed (e is then 0)
  double down() const { return e < 0 ? nextDown(s) : s; }
  double up() const { return e > 0 ? nextUp(s) : s; }
};

TwoSum twoSum(double a, double b) {
  const double s = a + b;
  if (!std::isfinite(s)) return {s, 0, false};  // no inf - inf below
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e, true};
}

// ---------------------------------------------------------------------------
// Kernels for the torus parts: the running-bound double filter of
// src/filter.h, and GMP integers (exact).

using Rk = detail::RunningDoubleKernel;

/// GMP integers: the exact stage of the torus edges, on the local
/// coordinates scaled by a power of two to integers (the torus test is
/// invariant under a common scaling).
struct ZKernel {
  using Num = mpz_class;
};

/// One torus in doubled local coordinates (X = 2x, Y = 2y, Z = 2z: the
/// doubled rim height c = +-lz stays a double): the triangle's vertices,
/// the doubled radius R = 2r, tube M = 2m, rim height C.
template <class K>
struct TorusInput {
  using N = typename K::Num;
  N X[3], Y[3], Z[3];
  N R, M, C;
};

/// sign(a + b sqrt(D)) for D > 0 (kUnknown where a needed sign is open).
template <class K>
Sign signWithRoot(const typename K::Num& a, const typename K::Num& b,
                  const typename K::Num& D) {
  const Sign sa = K::sign(a), sb = K::sign(b);
  if (sa == Sign::kUnknown || sb == Sign::kUnknown) return Sign::kUnknown;
  if (sb == Sign::kZero) return sa;
  if (sa == Sign::kZero || sa == sb) return sb;
  const Sign s2 = K::sign(a * a - b * b * D);  // |a| vs |b| sqrt(D)
  if (s2 == Sign::kUnknown || s2 == Sign::kZero) return s2;
  return s2 == Sign::kPos ? sa : sb;
}

/// |a| vs |b| sqrt(D) for a = ma 2^ea, b = mb 2^eb != 0 and D = md 2^ed > 0
/// (GMP integers m, exponents e), i.e. the sign of a^2 - b^2 D, first from
/// the leading 53 bits of each mantissa: mpz_get_d_2exp gives
/// |m| = f 2^k (1 + eps) with 0.5 <= f < 1 and 0 <= eps < 2^-52 (it
/// truncates), so a^2 / (b^2 D) = (fa^2 / (fb^2 fd)) 2^x times a factor
/// within (1 - 2^-50, 1 + 2^-50), x = 2 (ka + ea) - 2 (kb + eb) - (kd + ed),
/// and fa^2 / (fb^2 fd) is in (1/4, 8): x >= 4 decides >, x <= -4 decides
/// <, and otherwise the three rounded products (2^-53 each) with the slack
/// 2^-45 decide unless the two sides agree to about 2^-45. Only then the
/// exact squares (of about 40,000 bits for inputs that span 2000 binary
/// orders, where they were the bulk of the face part's cost). `exact`
/// returns the sign of a^2 - b^2 D.
template <class Exact>
int compareAbsWithRoot(const mpz_class& ma, long ea, const mpz_class& mb,
                       long eb, const mpz_class& md, long ed, Exact&& exact) {
  long ka = 0, kb = 0, kd = 0;
  const double fa = std::fabs(mpz_get_d_2exp(&ka, ma.get_mpz_t()));
  const double fb = std::fabs(mpz_get_d_2exp(&kb, mb.get_mpz_t()));
  const double fd = mpz_get_d_2exp(&kd, md.get_mpz_t());
  const long x = 2 * (ka + ea) - 2 * (kb + eb) - (kd + ed);
  if (x >= 4) return 1;
  if (x <= -4) return -1;
  const double lhs = std::ldexp(fa * fa, int(x));  // exact: x > -4
  const double rhs = fb * fb * fd;
  if (lhs > rhs * (1 + 0x1p-45)) return 1;
  if (lhs * (1 + 0x1p-45) < rhs) return -1;
  return exact();
}
/// signWithRoot in GMP dyadics (the face part's exact stage), with the
/// comparison of |a| and |b| sqrt(D) filtered on leading bits.
template <>
Sign signWithRoot<detail::ExactKernel>(const detail::Dyadic& a,
                                       const detail::Dyadic& b,
                                       const detail::Dyadic& D) {
  using K = detail::ExactKernel;
  const Sign sa = K::sign(a), sb = K::sign(b);
  if (sb == Sign::kZero) return sa;
  if (sa == Sign::kZero || sa == sb) return sb;
  const int c = compareAbsWithRoot(a.m, a.e, b.m, b.e, D.m, D.e,
                                   [&] { return sgn((a * a - b * b * D).m); });
  if (c == 0) return Sign::kZero;
  return c > 0 ? sa : sb;
}

/// The face part (see the file comment): does the foot on the triangle's
/// plane of one of the rim points +-r (n_x, n_y)/|n_xy| lie in the triangle
/// within m of that rim point? Only asked for a triangle that misses the rim
/// circle and whose edges miss the torus. Degree 24 in the inputs (12 in the
/// local coordinates): run on inputs scaled to unit size (see
/// ScaledInputs), where every magnitude stays below 2^90.
template <class K>
Tri faceFeet(const TorusInput<K>& t) {
  using N = typename K::Num;
  const N ex0 = t.X[1] - t.X[0], ey0 = t.Y[1] - t.Y[0], ez0 = t.Z[1] - t.Z[0];
  const N ex1 = t.X[2] - t.X[0], ey1 = t.Y[2] - t.Y[0], ez1 = t.Z[2] - t.Z[0];
  const N n[3] = {ey0 * ez1 - ez0 * ey1, ez0 * ex1 - ex0 * ez1,
                  ex0 * ey1 - ey0 * ex1};
  const Sign sn[3] = {K::sign(n[0]), K::sign(n[1]), K::sign(n[2])};
  bool any_unknown = false, nonzero = false;
  for (Sign s : sn) {
    if (s == Sign::kUnknown) any_unknown = true;
    if (s == Sign::kPos || s == Sign::kNeg) nonzero = true;
  }
  if (!nonzero) return any_unknown ? Tri::kUnknown : Tri::kFalse;  // segment
  const N D = n[0] * n[0] + n[1] * n[1];
  const Sign sD = K::sign(D);
  if (sD == Sign::kUnknown) return Tri::kUnknown;
  const N n2 = D + n[2] * n[2];
  const N R2 = t.R * t.R, M2 = t.M * t.M;
  // Edge normals in the plane, c_i = n x E_i, E_i = V_{i+1} - V_i.
  N c[3][3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const N ex = t.X[j] - t.X[i], ey = t.Y[j] - t.Y[i], ez = t.Z[j] - t.Z[i];
    c[i][0] = n[1] * ez - n[2] * ey;
    c[i][1] = n[2] * ex - n[0] * ez;
    c[i][2] = n[0] * ey - n[1] * ex;
  }
  // beta_i = c_i . ((0, 0, C) - V_i), beta_d = n . ((0, 0, C) - V_0).
  N beta[3];
  for (int i = 0; i < 3; ++i)
    beta[i] = c[i][2] * (t.C - t.Z[i]) - c[i][0] * t.X[i] - c[i][1] * t.Y[i];
  const N bd = n[2] * (t.C - t.Z[0]) - n[0] * t.X[0] - n[1] * t.Y[0];
  detail::AnyOf any;
  for (int sg = 0; sg < 2; ++sg) {
    Tri ok = Tri::kTrue;
    if (sD == Sign::kZero) {
      // Horizontal plane: every rim point is critical; take (+-R, 0, C).
      const N gx = sg == 0 ? t.R : N(-t.R);
      for (int i = 0; i < 3 && ok != Tri::kFalse; ++i) {
        // (E_i x (g - V_i)) . n = (g - V_i) . c_i
        const N s = c[i][0] * (gx - t.X[i]) - c[i][1] * t.Y[i] +
                    c[i][2] * (t.C - t.Z[i]);
        ok = kAnd(ok, detail::isNonNeg(K::sign(s)));
      }
      if (ok == Tri::kFalse) continue;
      const N dn = n[0] * (gx - t.X[0]) - n[1] * t.Y[0] + n[2] * (t.C - t.Z[0]);
      ok = kAnd(ok, detail::isNonPos(K::sign(dn * dn - M2 * n2)));
    } else {
      for (int i = 0; i < 3 && ok != Tri::kFalse; ++i) {
        N alpha = t.R * (c[i][0] * n[0] + c[i][1] * n[1]);
        if (sg == 1) alpha = -alpha;
        ok = kAnd(ok, detail::isNonNeg(signWithRoot<K>(alpha, beta[i], D)));
      }
      if (ok == Tri::kFalse) continue;
      // (s R w + beta_d)^2 <= M^2 |n|^2, w = sqrt(D), s = +-1:
      // R^2 D + beta_d^2 - M^2 |n|^2 + 2 s R beta_d w <= 0.
      const N a0 = R2 * D + bd * bd - M2 * n2;
      N a1 = (t.R + t.R) * bd;
      if (sg == 1) a1 = -a1;
      ok = kAnd(ok, detail::isNonPos(signWithRoot<K>(a0, a1, D)));
    }
    if (any.add(ok)) return Tri::kTrue;
  }
  return any.result();
}

// ---- The filter: Bernstein coefficients with subdivision ------------------

using Rd = detail::Rd;

/// The running-bound filter of src/filter.h with the underflow of the bound
/// computations themselves charged to the bounds, so that its signs need no
/// absolute slack (RunningKernel's kAbs = 2^-600, valid only for inputs
/// under the range gate) and values far below 2^-600 can be certified: the
/// torus filter on hostile inputs (torusRobustInput). Rules, with u' and
/// eta (the smallest subnormal) as in src/filter.h:
///   a + b:  e = e_a + e_b + u' |v| + eta
///   a * b:  e = |v_a| e_b + |v_b| e_a + e_a e_b + u' |v| + 4 eta.
/// The exact bound of a sum is e_a + e_b + |v - (v_a + v_b)|, the rounding
/// of a sum being within u' |v| (exact in the subnormal range); of a
/// product |v_a| e_b + |v_b| e_a + e_a e_b + u' |v| + eta / 2 (the last
/// for an underflowed v). Computing e rounds to nearest: relatively
/// (non-negative terms; at most 8 roundings per operation, a factor
/// (1 - u)^8 per operation, covered by the final inflation (1 + 2^-40) for
/// chains of up to 1000 operations: the deepest here, a Bernstein
/// coefficient after 24 halvings, is about 130), and absolutely by at most
/// eta / 2 per rounding that underflows (the product's four products, the
/// sum's one: covered by the added eta terms). sign() compares v with
/// fl(e (1 + 2^-40)) + eta, the last covering that product's underflow.
///
/// The same rules hold for any binary floating type F with gradual
/// underflow and u' = u (1 + 2u) (u = epsilon / 2 <= 2^-53, eta F's
/// smallest subnormal): UnderflowKernelT<double> is the filter on the
/// rescaled inputs, UnderflowKernelT<long double> (the x87 format on
/// x86-64: 64-bit significand, exponents down to 2^-16445; IEEE quadruple
/// on AArch64; double itself where long double is double, the stage then
/// only deciding less) the one on the exact local coordinates rounded once
/// (torusWideInput), whose exponent range holds the products of inputs
/// that span 2000 binary orders.
template <class F>
struct RuT {
  F v;
  F e;
};
template <class F>
constexpr F kEtaT = std::numeric_limits<F>::denorm_min();
template <class F>
constexpr F kU1T = std::numeric_limits<F>::epsilon() / 2 *
                   (1 + std::numeric_limits<F>::epsilon());
template <class F>
inline RuT<F> operator+(RuT<F> a, RuT<F> b) {
  const F v = a.v + b.v;
  return {v, a.e + b.e + kU1T<F> * std::fabs(v) + kEtaT<F>};
}
template <class F>
inline RuT<F> operator-(RuT<F> a, RuT<F> b) {
  const F v = a.v - b.v;
  return {v, a.e + b.e + kU1T<F> * std::fabs(v) + kEtaT<F>};
}
template <class F>
inline RuT<F> operator-(RuT<F> a) {
  return {-a.v, a.e};
}
template <class F>
inline RuT<F> operator*(RuT<F> a, RuT<F> b) {
  const F v = a.v * b.v;
  return {v, std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e +
                 kU1T<F> * std::fabs(v) + 4 * kEtaT<F>};
}
template <class F>
struct UnderflowKernelT {
  using Num = RuT<F>;
  static constexpr bool kExact = false;
  static Num lift(double x) { return {F(x), 0}; }
  static Sign sign(const Num& a) {
    const F bound = a.e * (1 + F(0x1p-40)) + kEtaT<F>;
    if (a.v > bound) return Sign::kPos;
    if (a.v < -bound) return Sign::kNeg;
    return Sign::kUnknown;
  }
};
using Ru = RuT<double>;
using Uk = UnderflowKernelT<double>;
using Ul = UnderflowKernelT<long double>;
static_assert(kU1T<double> == detail::kU1d, "u' of src/filter.h");
constexpr double kEta = kEtaT<double>;

/// Double-word values with a running bound: the intermediate stage of the
/// torus edges (Stage::kExtended), between the double filter and GMP, on
/// the exactly scaled inputs. The near-ties that the double filter cannot
/// separate (a margin a few ulps from an edge's distance to a rim, where Q's
/// minimum is about 2^-52 of its coefficients and below the double
/// filter's resolution) are mostly certified here, at a fraction of the
/// cost of the Sturm sequence. Rules, with the double-word error bounds of
/// src/eft.h (|x| read as |hi| + |lo|):
///   a + b:  e = e_a + e_b + 2^-104 (|a| + |b|) + 2^-1060
///   a * b:  e = |a| e_b + |b| e_a + e_a e_b + 2^-103 |a| |b| + 2^-1060
/// (2^-1060 = kDwTiny, each operation's absolute allowance for underflow,
/// which also covers the underflow of these bound computations: a few
/// times 2^-1075). e is computed in double rounded to nearest from
/// non-negative terms, short by at most (1 - u)^8 per operation: covered by
/// the inflation (1 + 2^-40) at the sign for chains of up to 1000
/// operations (the deepest Bernstein coefficient is about 130). sign():
/// hi + lo - E has the bound e, so hi > e + |lo| certifies a positive value
/// (the sum and the inflation rounded up by a further 2^-50).
struct Rw {
  detail::DW v;
  double e;
};
inline double mag(const Rw& a) { return std::fabs(a.v.hi) + std::fabs(a.v.lo); }
inline Rw operator+(Rw a, Rw b) {
  return {detail::dwAdd(a.v, b.v),
          a.e + b.e + detail::kDwAddRel * (mag(a) + mag(b)) + detail::kDwTiny};
}
inline Rw operator-(Rw a) { return {detail::dwNeg(a.v), a.e}; }
inline Rw operator-(Rw a, Rw b) { return a + (-b); }
inline Rw operator*(Rw a, Rw b) {
  const double ma = mag(a), mb = mag(b);
  return {detail::dwMul(a.v, b.v), ma * b.e + mb * a.e + a.e * b.e +
                                       detail::kDwRel * (ma * mb) +
                                       detail::kDwTiny};
}
struct DoubleWordKernel {
  using Num = Rw;
  static Num lift(double x) { return {{x, 0}, 0}; }
  /// a - b exactly as a double-word (TwoSum; the inputs are finite and
  /// scaled to unit size, so nothing overflows).
  static Num inputDiff(double a, double b) {
    Num d{{0, 0}, 0};
    detail::twoSum(a, -b, d.v.hi, d.v.lo);
    return d;
  }
  static Sign sign(const Num& a) {
    const double t =
        (a.e * (1 + 0x1p-40) + std::fabs(a.v.lo)) * (1 + 0x1p-50) + kEta;
    if (a.v.hi > t) return Sign::kPos;
    if (a.v.hi < -t) return Sign::kNeg;
    return Sign::kUnknown;
  }
};
using Wk = DoubleWordKernel;

/// Is some value of the polynomial with Bernstein coefficients b[0..n] on
/// an interval <= 0? kTrue if an end value is certainly < 0, kFalse if every
/// coefficient is certainly > 0 (convex-hull property), else subdivides at
/// the midpoint (de Casteljau; halving is exact but for underflow, which the
/// running bound's product rule covers), to `depth` more levels and at most
/// `*budget` intervals in all (a near-double root needs a few intervals per
/// level around it; a polynomial that is 0 within its bound everywhere, e.g.
/// a point edge on the torus, would need all 2^depth).
template <class K>
Tri bernsteinAnyNonPos(const typename K::Num* b, int n, int depth,
                       int* budget) {
  using N = typename K::Num;
  if (--*budget < 0) return Tri::kUnknown;
  const Sign s0 = K::sign(b[0]), sn = K::sign(b[n]);
  if (s0 == Sign::kNeg || sn == Sign::kNeg) return Tri::kTrue;
  bool all_pos = true, all_unknown = true;
  for (int i = 0; i <= n; ++i) {
    const Sign si = K::sign(b[i]);
    if (si != Sign::kPos) all_pos = false;
    if (si != Sign::kUnknown) all_unknown = false;
  }
  if (all_pos) return Tri::kFalse;
  // Every coefficient within its bound of 0: so is every coefficient of
  // every sub-interval (a convex combination of these, whose bound is at
  // least the same combination of their bounds), so halving cannot decide.
  if (all_unknown || depth == 0) return Tri::kUnknown;
  N left[5], right[5], w[5];
  for (int i = 0; i <= n; ++i) w[i] = b[i];
  const N half = K::lift(0.5);
  for (int k = 0; k <= n; ++k) {
    left[k] = w[0];
    right[n - k] = w[n - k];
    for (int i = 0; i < n - k; ++i) w[i] = (w[i] + w[i + 1]) * half;
  }
  const Tri l = bernsteinAnyNonPos<K>(left, n, depth - 1, budget);
  if (l == Tri::kTrue) return l;
  return kOr(l, bernsteinAnyNonPos<K>(right, n, depth - 1, budget));
}

/// Halving depth, and intervals per polynomial: the double filter gives up
/// sooner, since the double-word stage behind it resolves near-ties with
/// far fewer intervals (its coefficients are 2^50 times sharper); the
/// hostile path (UnderflowKernel) has no stage behind it but GMP.
constexpr int kBernsteinDepth = 24;
template <class K>
constexpr int kBernsteinBudget =
    std::is_same_v<K, detail::RunningDoubleKernel> ? 24 : 96;

/// The Bernstein coefficients on [0, 1] of L (lb) and 6 Q (qb) along the
/// edge a -> b, formed from the end points directly: with A and B the
/// vectors from the rim's centre, (X, Y, Z - C), at the ends,
/// K0 = R^2 - M^2 and rho^2 = (p0, p1, p2) in Bernstein form
/// (A_xy . A_xy, A_xy . B_xy, B_xy . B_xy),
///   L:  (A . A + K0, A . B + K0, B . B + K0),
/// and Q = L^2 - 4 R^2 rho^2 by the Bernstein product rule (degree 2 times
/// degree 2: c_k = sum_{i+j=k} C(2,i) C(2,j) / C(4,k) l_i l_j) and the
/// degree elevation of rho^2 to 4 ((p0, (p0+p1)/2, (p0+4p1+p2)/6, ...)).
/// The end coefficients are L and Q at the vertices, computed from that
/// vertex alone: a vertex close to a small torus keeps its tiny values
/// (the power basis would form them as differences of large coefficients).
template <class K>
void edgeBernstein(const TorusInput<K>& t, int a, int b, typename K::Num* lb,
                   typename K::Num* qb) {
  using N = typename K::Num;
  const N za = t.Z[a] - t.C, zb = t.Z[b] - t.C;
  const N p0 = t.X[a] * t.X[a] + t.Y[a] * t.Y[a];
  const N p1 = t.X[a] * t.X[b] + t.Y[a] * t.Y[b];
  const N p2 = t.X[b] * t.X[b] + t.Y[b] * t.Y[b];
  const N k0 = t.R * t.R - t.M * t.M;
  lb[0] = p0 + za * za + k0;
  lb[1] = p1 + za * zb + k0;
  lb[2] = p2 + zb * zb + k0;
  const N R2 = t.R * t.R;
  const N R4 = (R2 + R2) + (R2 + R2);
  const N R12 = (R4 + R4) + R4;
  const N six = K::lift(6), two = K::lift(2), four = K::lift(4);
  qb[0] = six * (lb[0] * lb[0]) - (R12 + R12) * p0;
  qb[1] = six * (lb[0] * lb[1]) - R12 * (p0 + p1);
  qb[2] = two * (lb[0] * lb[2]) + four * (lb[1] * lb[1]) -
          R4 * ((p0 + p2) + four * p1);
  qb[3] = six * (lb[1] * lb[2]) - R12 * (p1 + p2);
  qb[4] = six * (lb[2] * lb[2]) - (R12 + R12) * p2;
}

/// kTrue: the edge meets the torus; kFalse: it does not; kUnknown: open.
/// `l_positive` (if given) is set when L > 0 on the edge is certified
/// (then edgeBallHit, step 1 of the exact stage, would say no).
template <class K>
Tri edgeFilter(const TorusInput<K>& t, int a, int b,
               bool* l_positive = nullptr) {
  typename K::Num lb[3], qb[5];
  edgeBernstein<K>(t, a, b, lb, qb);
  int budget = kBernsteinBudget<K>;
  const Tri tq = bernsteinAnyNonPos<K>(qb, 4, kBernsteinDepth, &budget);
  if (tq == Tri::kTrue) return tq;
  budget = kBernsteinBudget<K>;
  const Tri tl = bernsteinAnyNonPos<K>(lb, 2, kBernsteinDepth, &budget);
  if (l_positive != nullptr && tl == Tri::kFalse) *l_positive = true;
  return kOr(tq, tl);
}

// ---- The exact stage: GMP integers, Sturm sequence ------------------------

using detail::sturm::cert::signSquaresPlusProduct;
using detail::sturm::cert::signSquaresPlusProductSquares;

/// The exact stage of one edge (GMP integers). With p(s) = A + s E,
/// rho^2 = p0 + p1 s + p2 s^2 and z - C = za + ez s, in this order:
///
/// 1. L <= 0 somewhere on [0, 1] (L = rho^2 + (z - C)^2 + R^2 - M^2, a
///    quadratic): a hit.
/// 2. The edge misses a simple set around the torus: a miss. Every point p
///    of Tor is p = g + w with g on the rim circle (radius R about
///    o = (0, 0, C) in the plane z = C) and |w| <= M, so Tor lies in the
///    slab |z - C| <= M, in the solid cylinder rho <= R + M
///    (|p_xy| <= |g_xy| + |w|) and in the ball |p - o| <= R + M. Along the
///    edge z - C is linear (a miss iff both ends are beyond the same face
///    of the slab), rho^2 and |p - o|^2 are quadratics (a miss iff the
///    quadratic minus the squared bound is positive on [0, 1]). The hole
///    rho < R - M needs no test: an edge inside it that reaches this stage
///    misses Cyl(r, h + m), so it lies wholly above or below that cylinder,
///    beyond one face of the slab. Products of the inputs' size only. On
///    the wide-exponent inputs outside the range gate (lengths spanning
///    2000 binary orders) this is what decides the edges that miss: their
///    quartic Q has coefficients of about 15,000 bits, and its Sturm
///    sequence cost milliseconds.
/// 3. Q = L^2 - 4 R^2 rho^2 <= 0 at an end: a hit; its Bernstein
///    coefficients on [0, 1] all > 0: a miss; else the Sturm sequence
///    counts its roots in (0, 1) (both ends > 0: a root is a point where
///    Q <= 0), which decides every tie (rootsInUnitTorus: its remainders
///    in closed form, no gcd; exact subdivision of the Bernstein form was
///    tried before it and dropped: on the wide inputs whose edges reach
///    this point it needed thousands of pieces).
/// The coefficient size (bits) above which edgeExactWide tries the local
/// certificate before the Sturm count.
constexpr std::size_t kWideQuarticBits = 10000;

/// Is f(s) = |A + s E|^2 + K > 0 on [0, 1], for f = a[0] + a[1] s + a[2] s^2
/// (a[0] = |A|^2 + K, a[1] = 2 A.E, a[2] = |E|^2)? As quadraticPositive
/// (src/margin_sturm.h),
/// with the vertex's discriminant in the form of Lagrange's identity,
/// 4 a0 a2 - a1^2 = 4 (|A x E|^2 + K |E|^2): `vertexSign()` gives the sign
/// of |A x E|^2 + K |E|^2. The power form cancels where the edge's line
/// passes close to o compared with |A| (a far edge of a wide triangle
/// grazing a small torus: a0 a2 and a1^2 then agree to thousands of bits,
/// and their exact products were most of this stage's cost); the cross
/// product is small there, and its squares' sum has no cancellation.
template <class VertexSign>
bool distancePositive(const mpz_class* a, VertexSign&& vertexSign) {
  if (sgn(a[0]) <= 0 || sgn(a[0] + a[1] + a[2]) <= 0) return false;
  if (sgn(a[2]) > 0 && sgn(a[1]) < 0 && a[1] + 2 * a[2] > 0)
    return vertexSign() > 0;
  return true;
}

/// One edge's polynomials, kept between the phases of its exact stage:
/// L, rho^2 = P and (from the second phase) Q, with the torus's R and M.
struct ExactEdge {
  mpz_class l[3], p[3], q[5], R, M;
  std::size_t bits = 0;  // Q's largest coefficient (bits)
};

/// The inner part of edgeBallHit in a filter kernel K (UnderflowKernelT on
/// the exact coordinates rounded once, torusWideInput): kTrue if the
/// vertex of L is certainly inside (0, 1) with |A x E|^2 + K |E|^2 < 0
/// (a hit), kFalse if the vertex is certainly outside or that value
/// certainly > 0, kUnknown else (the exact test decides; `inside`, if
/// given, is set where the vertex is certainly inside (0, 1)). Where the edge's
/// line passes far from o compared with the ball's radius, nothing here
/// cancels and the fifteen products of integers of thousands of bits are
/// not formed.
template <class K>
Tri edgeBallVertex(const TorusInput<K>& t, int a, int b,
                   bool* inside = nullptr) {
  using N = typename K::Num;
  const N za = t.Z[a] - t.C, zb = t.Z[b] - t.C;
  const N ex = t.X[b] - t.X[a], ey = t.Y[b] - t.Y[a], ez = t.Z[b] - t.Z[a];
  const Sign sa = K::sign(t.X[a] * ex + t.Y[a] * ey + za * ez);
  const Sign sb = K::sign(t.X[b] * ex + t.Y[b] * ey + zb * ez);
  if (sa == Sign::kPos || sa == Sign::kZero || sb == Sign::kNeg ||
      sb == Sign::kZero)
    return Tri::kFalse;
  if (sa == Sign::kUnknown || sb == Sign::kUnknown) return Tri::kUnknown;
  if (inside != nullptr) *inside = true;
  // A x E = A x B: the latter does not cancel where B is far smaller
  // than A (a vertex near o, the other far away).
  const N cx = t.Y[a] * zb - za * t.Y[b], cy = za * t.X[b] - t.X[a] * zb,
          cz = t.X[a] * t.Y[b] - t.Y[a] * t.X[b];
  const N v = ((cx * cx + cy * cy) + cz * cz) +
              ((t.R - t.M) * (t.R + t.M)) * ((ex * ex + ey * ey) + ez * ez);
  const Sign sv = K::sign(v);
  if (sv == Sign::kPos) return Tri::kFalse;
  if (sv == Sign::kNeg) return Tri::kTrue;
  return Tri::kUnknown;
}

/// Step 1 alone: does L = |p(s) - o|^2 + R^2 - M^2 take a value <= 0 on
/// [0, 1] (the edge meets the ball |p - o|^2 <= M^2 - R^2 about the rim's
/// centre o, inside the torus)? Never for R > M. Else, with A = p(0) - o,
/// B = p(1) - o, E = B - A and K = R^2 - M^2 = (R - M)(R + M): at an end
/// iff |A|^2 + K <= 0 or |B|^2 + K <= 0; inside iff the vertex
/// -A.E / |E|^2 is in (0, 1) (A.E < 0 < B.E) and |A x E|^2 + K |E|^2 <= 0
/// (Lagrange's identity, as distancePositive). Cheapest first: the cube
/// |x|, |y|, |z - C| <= M about o holds the ball (its radius
/// sqrt(M^2 - R^2) is at most M), so both ends beyond one of its faces is
/// a miss (comparisons); the ends, sums of squares against a product on
/// leading bits (signSquaresPlusProduct); the vertex in long double
/// (`vertexHint(&inside)`: edgeBallVertex). Where the hint abstains the
/// edge's line passes close to o compared with |A| (A x B cancels in
/// floating point) and the exact cross product is formed: six products of
/// the inputs' size, against K |E|^2 on leading bits
/// (signSquaresPlusProductSquares: |E|^2 itself is not formed), the dot
/// products only where the hint could not place the vertex. On the
/// random-exponent inputs outside the range gate, where for r <= m this
/// test runs before a sized part that then hits, the dot products and
/// |E|^2 were most of its cost. The same answer as step 1 of
/// edgeExactBounds, which decide() skips after it.
template <class VertexHint>
bool edgeBallHit(const TorusInput<ZKernel>& t, int a, int b,
                 VertexHint&& vertexHint) {
  if (t.R > t.M) return false;  // L >= R^2 - M^2 > 0
  const mpz_class za = t.Z[a] - t.C, zb = t.Z[b] - t.C;
  auto beyond = [&t](const mpz_class& u, const mpz_class& v) {
    return (u > t.M && v > t.M) || (u < -t.M && v < -t.M);
  };
  if (beyond(t.X[a], t.X[b]) || beyond(t.Y[a], t.Y[b]) || beyond(za, zb))
    return false;
  const mpz_class km = t.R - t.M, kp = t.R + t.M;
  if (signSquaresPlusProduct({&t.X[a], &t.Y[a], &za}, {&km, &kp}) <= 0 ||
      signSquaresPlusProduct({&t.X[b], &t.Y[b], &zb}, {&km, &kp}) <= 0)
    return true;
  bool inside = false;
  const Tri hint = vertexHint(&inside);
  if (hint != Tri::kUnknown) return hint == Tri::kTrue;
  const mpz_class ex = t.X[b] - t.X[a], ey = t.Y[b] - t.Y[a], ez = zb - za;
  if (!inside && (sgn(t.X[a] * ex + t.Y[a] * ey + za * ez) >= 0 ||
                  sgn(t.X[b] * ex + t.Y[b] * ey + zb * ez) <= 0))
    return false;  // the least value is at an end
  const mpz_class c[3] = {t.Y[a] * zb - za * t.Y[b], za * t.X[b] - t.X[a] * zb,
                          t.X[a] * t.Y[b] - t.Y[a] * t.X[b]};  // A x B
  return signSquaresPlusProductSquares({&c[0], &c[1], &c[2]}, {&km, &kp},
                                       {&ex, &ey, &ez}) <= 0;
}

/// Phase 1 of the exact stage (steps 1 and 2 above; step 1 not again if
/// `ball_done`: edgeBallHit said no, or a filter certified L > 0):
/// products of the inputs' size only.
/// 1: the edge meets the torus, 0: it does not; -1: not decided, L and P
/// left in *e for edgeExactQuartic.
int edgeExactBounds(const TorusInput<ZKernel>& t, int a, int b, ExactEdge* e,
                    bool ball_done = false) {
  const mpz_class za = t.Z[a] - t.C, zb = t.Z[b] - t.C;
  // The slab first: comparisons only.
  if ((za > t.M && zb > t.M) || (za < -t.M && zb < -t.M)) return 0;
  const mpz_class ex = t.X[b] - t.X[a], ey = t.Y[b] - t.Y[a],
                  ez = t.Z[b] - t.Z[a];
  const mpz_class p0 = t.X[a] * t.X[a] + t.Y[a] * t.Y[a];
  const mpz_class p1 = 2 * (t.X[a] * ex + t.Y[a] * ey);
  const mpz_class p2 = ex * ex + ey * ey;
  const mpz_class R2 = t.R * t.R, M2 = t.M * t.M;
  const mpz_class K = R2 - M2;
  const mpz_class l[3] = {p0 + za * za + K, p1 + 2 * za * ez, p2 + ez * ez};
  // A = p(0) - o, B = p(1) - o: A x E = A x B, made once when a vertex
  // test needs it.
  std::optional<std::array<mpz_class, 3>> axe;
  auto cross3 = [&]() -> const std::array<mpz_class, 3>& {
    if (!axe)
      axe = std::array<mpz_class, 3>{t.Y[a] * zb - za * t.Y[b],
                                     za * t.X[b] - t.X[a] * zb,
                                     t.X[a] * t.Y[b] - t.Y[a] * t.X[b]};
    return *axe;
  };
  if (!ball_done && !distancePositive(l, [&] {
        const auto& c = cross3();
        return signSquaresPlusProduct({&c[0], &c[1], &c[2]}, {&K, &l[2]});
      }))
    return 1;  // 1.
  const mpz_class rm2 = (t.R + t.M) * (t.R + t.M);
  const mpz_class nrm2 = -rm2;
  const mpz_class pm[3] = {p0 - rm2, p1, p2};
  if (distancePositive(pm, [&] {
        const auto& c = cross3();  // (A x E)_z = A_xy x E_xy
        return signSquaresPlusProduct({&c[2]}, {&nrm2, &p2});
      }))
    return 0;
  const mpz_class bm[3] = {p0 + za * za - rm2, l[1], l[2]};
  if (distancePositive(bm, [&] {
        const auto& c = cross3();
        return signSquaresPlusProduct({&c[0], &c[1], &c[2]}, {&nrm2, &l[2]});
      }))
    return 0;
  for (int i = 0; i < 3; ++i) e->l[i] = l[i];
  e->p[0] = p0;
  e->p[1] = p1;
  e->p[2] = p2;
  e->R = t.R;
  e->M = t.M;
  return -1;
}

/// Phase 2 (step 3 up to the Bernstein test; the Sturm count for narrow
/// quartics): Q, products of L's size. -1: a wide quartic (above
/// kWideQuarticBits), Q left in *e for edgeExactWide.
int edgeExactQuartic(ExactEdge* e) {
  const mpz_class* l = e->l;
  const mpz_class* p = e->p;
  const mpz_class R4 = 4 * e->R * e->R;
  mpz_class* q = e->q;
  q[0] = l[0] * l[0] - R4 * p[0];
  q[1] = 2 * l[0] * l[1] - R4 * p[1];
  q[2] = l[1] * l[1] + 2 * l[0] * l[2] - R4 * p[2];
  q[3] = 2 * l[1] * l[2];
  q[4] = l[2] * l[2];
  const mpz_class q_end = q[0] + q[1] + q[2] + q[3] + q[4];
  if (sgn(q[0]) <= 0 || sgn(q_end) <= 0) return 1;
  // Bernstein coefficients (times 12) all > 0: Q > 0 on [0, 1], no roots.
  const mpz_class q0 = 12 * q[0];
  if (sgn(q0 + 3 * q[1]) > 0 && sgn(q0 + 6 * q[1] + 2 * q[2]) > 0 &&
      sgn(q0 + 9 * q[1] + 6 * q[2] + 3 * q[3]) > 0)
    return 0;
  // Wide quartics: the local certificate at an approximate minimiser
  // first (torusEdgeCertificate, src/margin_sturm.h), the Sturm count where
  // it cannot decide (an exact tangency, for one): edgeExactWide. Narrow
  // quartics go to the Sturm count directly, which is cheap there.
  e->bits = 0;
  for (int i = 0; i < 5; ++i)
    e->bits = std::max(e->bits, mpz_sizeinbase(q[i].get_mpz_t(), 2));
  if (e->bits > kWideQuarticBits) return -1;
  return detail::sturm::rootsInUnitTorus(q, l[1], l[2]) > 0;
}

/// Phase 3, wide quartics: s0 gets at most a third of Q's bits (beyond
/// that, its floats cost about what the count does).
bool edgeExactWide(const ExactEdge& e,
                   detail::sturm::CertHint* hint = nullptr) {
  const int s = detail::sturm::torusEdgeCertificate(e.q, e.l, e.p, e.R, e.M,
                                                    long(e.bits) / 3, hint);
  if (s >= 0) return s == 1;
  return detail::sturm::rootsInUnitTorus(e.q, e.l[1], e.l[2]) > 0;
}

/// The whole exact stage of one edge, phases 1 - 3 in order.
bool edgeExact(const TorusInput<ZKernel>& t, int a, int b) {
  ExactEdge e;
  int r = edgeExactBounds(t, a, b, &e);
  if (r < 0) r = edgeExactQuartic(&e);
  if (r < 0) r = edgeExactWide(e);
  return r == 1;
}

/// The edges of one torus in the filter: kTrue if one certainly meets it,
/// kFalse if none does; `open[e]` flags the edges left open, `l_positive[e]`
/// those whose L > 0 is certified (edgeFilter).
template <class K>
Tri edgesFilter(const TorusInput<K>& t, bool* open, bool* l_positive) {
  detail::AnyOf any;
  for (int e = 0; e < 3; ++e) {
    const Tri r = edgeFilter<K>(t, kEdge[e][0], kEdge[e][1], &l_positive[e]);
    open[e] = r == Tri::kUnknown;
    if (any.add(r)) return Tri::kTrue;
  }
  return any.result();
}

// ---------------------------------------------------------------------------
// The query.

/// A query whose sizes are valid (finite, >= 0, +0 for zero). The pose and
/// the triangle are validated by the first call of the triangle kernel (or
/// by scan() where no call is made first); the largest lengths for the range
/// gate are computed by scan() on the slow paths only.
struct Query {
  Cylinder<double> cyl;
  const Pose<double>& pose;
  const Triangle<double>& tri;
  double m;
  double max_len = 0;
  double max_unitless = 0;
  /// False if some input is NaN or infinite.
  bool scan() {
    const Triangle<double>& t = tri;
    return detail::scanFinite({cyl.radius, cyl.lz, m, t.a.x, t.a.y, t.a.z,
                               t.b.x, t.b.y, t.b.z, t.c.x, t.c.y, t.c.z},
                              pose, &max_len, &max_unitless);
  }
};

/// A finite double as m 2^e with m an odd integer (|m| < 2^53), or m = 0.
struct Dyadic {
  std::int64_t m = 0;
  int e = 0;
};
Dyadic dyadic(double x) {
  if (x == 0) return {};
  int e = 0;
  const double f = std::frexp(x, &e);  // x = f 2^e, 0.5 <= |f| < 1
  std::int64_t m = std::int64_t(std::ldexp(f, 53));
  e -= 53;
  while ((m & 1) == 0) {
    m /= 2;
    ++e;
  }
  return {m, e};
}

/// The doubled local coordinates and sizes of the torus at height sgn * h,
/// exactly, mirrored in z for the bottom one (sgn = -1) so that its rim is
/// at +lz, all multiplied by one power of two that makes them integers.
/// Every length input is an integer times 2^eL (eL the least exponent of
/// the nonzero lengths' odd mantissas) and every rotation entry an integer
/// times 2^eR, so the local coordinates are integers times 2^(eL + eR):
/// the unit is 2^(eL + min(eR, 0)), in which the sizes are integers too.
/// Integer shifts only (no rationals, no gcd).
TorusInput<ZKernel> torusExactInput(const Query& q, int sgn) {
  const Vec3<double>* v[3] = {&q.tri.a, &q.tri.b, &q.tri.c};
  Dyadic len[14];  // the 9 vertex coordinates, t, then r, m, lz
  for (int i = 0; i < 3; ++i) {
    len[3 * i] = dyadic(v[i]->x);
    len[3 * i + 1] = dyadic(v[i]->y);
    len[3 * i + 2] = dyadic(v[i]->z);
  }
  len[9] = dyadic(q.pose.t.x);
  len[10] = dyadic(q.pose.t.y);
  len[11] = dyadic(q.pose.t.z);
  const Dyadic sizes[3] = {dyadic(q.cyl.radius), dyadic(q.m), dyadic(q.cyl.lz)};
  Dyadic rot[3][3];
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) rot[j][k] = dyadic(q.pose.R[j][k]);
  int eL = std::numeric_limits<int>::max(), eR = eL;
  for (const Dyadic& d : len)
    if (d.m != 0) eL = std::min(eL, d.e);
  for (const Dyadic& d : sizes)
    if (d.m != 0) eL = std::min(eL, d.e);
  for (const auto& row : rot)
    for (const Dyadic& d : row)
      if (d.m != 0) eR = std::min(eR, d.e);
  if (eL == std::numeric_limits<int>::max()) eL = 0;  // every length 0
  if (eR == std::numeric_limits<int>::max()) eR = 0;  // R = 0
  // x 2^(e - unit) as an integer (e >= unit).
  auto toInt = [](const Dyadic& d, int unit) {
    mpz_class z = static_cast<long>(d.m);
    if (d.m != 0)
      mpz_mul_2exp(z.get_mpz_t(), z.get_mpz_t(), mp_bitcnt_t(d.e - unit));
    return z;
  };
  mpz_class diff[3][3];  // v_i - t in units of 2^eL
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k)
      diff[i][k] = toInt(len[3 * i + k], eL) - toInt(len[9 + k], eL);
  mpz_class rz[3][3];  // R in units of 2^eR
  for (int j = 0; j < 3; ++j)
    for (int k = 0; k < 3; ++k) rz[j][k] = toInt(rot[j][k], eR);
  // Local coordinates in units of 2^(eL + eR), moved to the common unit
  // 2^(eL + min(eR, 0)), doubled (one more bit) for X, Y, Z.
  const mp_bitcnt_t local_shift = mp_bitcnt_t(std::max(eR, 0) + 1);
  const int unit = eL + std::min(eR, 0);
  TorusInput<ZKernel> t;
  for (int i = 0; i < 3; ++i) {
    mpz_class c[3];
    for (int k = 0; k < 3; ++k) {
      c[k] =
          rz[0][k] * diff[i][0] + rz[1][k] * diff[i][1] + rz[2][k] * diff[i][2];
      mpz_mul_2exp(c[k].get_mpz_t(), c[k].get_mpz_t(), local_shift);
    }
    t.X[i] = c[0];
    t.Y[i] = c[1];
    t.Z[i] = sgn < 0 ? mpz_class(-c[2]) : c[2];
  }
  // R = 2r, M = 2m, C = lz in the same unit.
  t.R = toInt(sizes[0], unit - 1);
  t.M = toInt(sizes[1], unit - 1);
  t.C = toInt(sizes[2], unit);
  // The unit above is a common one, not the largest: divide out the power
  // of two that all twelve share (the torus test is invariant under it),
  // so that the integers are no longer than the values need.
  mpz_class* all[12] = {&t.X[0], &t.X[1], &t.X[2], &t.Y[0], &t.Y[1], &t.Y[2],
                        &t.Z[0], &t.Z[1], &t.Z[2], &t.R,    &t.M,    &t.C};
  mp_bitcnt_t tz = ~mp_bitcnt_t(0);
  for (const mpz_class* z : all)
    if (mpz_sgn(z->get_mpz_t()) != 0)
      tz = std::min(tz, mpz_scan1(z->get_mpz_t(), 0));
  if (tz != ~mp_bitcnt_t(0) && tz > 0)
    for (mpz_class* z : all)
      mpz_tdiv_q_2exp(z->get_mpz_t(), z->get_mpz_t(), tz);
  return t;
}

/// The inputs scaled by 2^-k, k the exponent of the largest length, so
/// that every length is below 2 and the magnitudes of the torus tests
/// (degree <= 24 in the inputs) stay below 2^90: far inside the budget of
/// the filters' absolute slack (src/filter.h, "Underflow"). `ok` is false if
/// the scaling is not exact (a length would become subnormal) or the inputs
/// are outside the range gate; the tori are then decided in GMP alone.
struct ScaledInputs {
  Cylinder<double> cyl;
  Pose<double> pose;
  Triangle<double> tri;
  double m;
  bool ok;
};

ScaledInputs scaleInputs(const Query& q) {
  ScaledInputs s{q.cyl, q.pose, q.tri, q.m, false};
  if (!detail::rangeGateOk(q.max_len, q.max_unitless) || q.max_len == 0)
    return s;
  const int k = std::ilogb(q.max_len);
  bool exact = true;
  auto sc = [&](double& v) {
    const double w = std::ldexp(v, -k);
    if (std::ldexp(w, k) != v) exact = false;  // w became subnormal
    v = w;
  };
  sc(s.cyl.radius);
  sc(s.cyl.lz);
  sc(s.m);
  sc(s.pose.t.x);
  sc(s.pose.t.y);
  sc(s.pose.t.z);
  for (Vec3<double>* v : {&s.tri.a, &s.tri.b, &s.tri.c}) {
    sc(v->x);
    sc(v->y);
    sc(v->z);
  }
  s.ok = exact;
  return s;
}

/// The torus at +h (top) or -h, mirrored to +h, in kernel K from the local
/// frame of src/triangle_cylinder_impl.h (x, y, Z = 2z, H = lz): doubled
/// coordinates X = 2x, Y = 2y, Z, doubled sizes R = 2r, M = 2m, C = lz.
template <class K>
TorusInput<K> torusInput(const detail::TriCylLocal<K>& l, double m, bool top) {
  TorusInput<K> t;
  const auto two = K::lift(2.0);
  for (int i = 0; i < 3; ++i) {
    t.X[i] = two * l.x[i];
    t.Y[i] = two * l.y[i];
    t.Z[i] = top ? l.Z[i] : -l.Z[i];
  }
  t.R = l.r + l.r;
  t.M = K::lift(m) + K::lift(m);
  t.C = l.H;
  return t;
}

/// The tori's inputs for the filter when the exact scaling of scaleInputs
/// fails (a length would become subnormal) or the inputs are outside the
/// range gate: every length scaled by 2^-k (k the exponent of the largest
/// length), the rotation by 2^-j (j >= 0 the exponent of its largest
/// entry) and the sizes by 2^-(k + j) as well, so that the local
/// coordinates R^T (p - t) scale by the same 2^-(k + j) as the sizes (the
/// torus test is invariant under a common scaling), then all of them by a
/// last power of two that brings the largest to [1, 2). A scaled input that
/// rounded (it became subnormal) is off by less than the smallest
/// subnormal, which it carries as its error bound, and everything is in
/// UnderflowKernel, whose bounds need no absolute slack: values far below
/// 2^-600 are certified where their bounds allow it. Every magnitude stays
/// below 24 for the coordinates and 2^60 in the tests (no overflow). Needs
/// q.scan() first and q.max_len > 0.
TorusInput<Uk> torusRobustInput(const Query& q, bool top) {
  constexpr double eta = kEta;
  const int k = std::ilogb(q.max_len);
  const int j =
      q.max_unitless > 0 ? std::max(0, std::ilogb(q.max_unitless)) : 0;
  auto sc = [](double v, int e) -> Ru {
    const double w = std::ldexp(v, -e);
    return {w, std::ldexp(w, e) == v ? 0.0 : eta};
  };
  const Ru tx = sc(q.pose.t.x, k), ty = sc(q.pose.t.y, k),
           tz = sc(q.pose.t.z, k);
  Ru R[3][3];
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) R[a][b] = sc(q.pose.R[a][b], j);
  const Vec3<double>* v[3] = {&q.tri.a, &q.tri.b, &q.tri.c};
  const Ru two = Uk::lift(2.0);
  TorusInput<Uk> t;
  for (int i = 0; i < 3; ++i) {
    const Ru d[3] = {sc(v[i]->x, k) - tx, sc(v[i]->y, k) - ty,
                     sc(v[i]->z, k) - tz};
    Ru c[3];
    for (int b = 0; b < 3; ++b)
      c[b] = two * ((R[0][b] * d[0] + R[1][b] * d[1]) + R[2][b] * d[2]);
    t.X[i] = c[0];
    t.Y[i] = c[1];
    t.Z[i] = top ? c[2] : -c[2];
  }
  t.R = two * sc(q.cyl.radius, k + j);
  t.M = two * sc(q.m, k + j);
  t.C = sc(q.cyl.lz, k + j);
  // The largest length need not be one that the torus test sees (a huge
  // coordinate along an axis that a tiny rotation entry maps, a huge
  // margin on the other torus...): scale up once more so that the largest
  // of these values is in [1, 2). Scaling up by a power of two is exact for
  // the values and for their bounds (UnderflowKernel's bounds already hold
  // the absolute losses of underflow).
  double big = std::max({std::fabs(t.R.v), std::fabs(t.M.v), std::fabs(t.C.v)});
  for (int i = 0; i < 3; ++i)
    big = std::max(
        {big, std::fabs(t.X[i].v), std::fabs(t.Y[i].v), std::fabs(t.Z[i].v)});
  if (big > 0 && big < 1) {
    const int up = -std::ilogb(big);
    auto grow = [up](Ru& x) { x = {std::ldexp(x.v, up), std::ldexp(x.e, up)}; };
    for (int i = 0; i < 3; ++i) {
      grow(t.X[i]);
      grow(t.Y[i]);
      grow(t.Z[i]);
    }
    grow(t.R);
    grow(t.M);
    grow(t.C);
  }
  return t;
}

/// The exact torus input (torusExactInput) rounded once to long double for
/// UnderflowKernelT<long double>: each integer z as d 2^k with d its leading
/// 53 bits (mpz_get_d_2exp truncates: |z - d 2^k| < 2^-52 |d 2^k|, the
/// bound carried), all scaled by one power of two that brings the largest
/// below 1 (an underflowed scaled value is off by at most eta / 2, and eta
/// is added to every bound). The exact local coordinates rounded once are
/// what the rescaled double inputs (torusRobustInput) cannot be when the
/// inputs span more binary orders than double's exponents: there a torus
/// 2^-1200 the size of the triangle leaves every double filter sign open,
/// and the GMP stages behind it cost hundreds of microseconds.
/// v 2^e in long double. Where long double is double (MSVC, or a build
/// with -mlong-double-64, whose libm long double functions still take the
/// 80-bit format) the double ldexp: no libm long double function is called
/// there (scripts/test.sh checks the symbols).
long double ldexpWide(long double v, int e) {
  if constexpr (std::numeric_limits<long double>::digits ==
                std::numeric_limits<double>::digits)
    return static_cast<long double>(std::ldexp(static_cast<double>(v), e));
  else
    return std::ldexp(v, e);
}

TorusInput<Ul> torusWideInput(const TorusInput<ZKernel>& t) {
  using L = long double;
  const mpz_class* in[12] = {&t.X[0], &t.X[1], &t.X[2], &t.Y[0],
                             &t.Y[1], &t.Y[2], &t.Z[0], &t.Z[1],
                             &t.Z[2], &t.R,    &t.M,    &t.C};
  double d[12];
  long k[12];
  long top = std::numeric_limits<long>::min();
  for (int i = 0; i < 12; ++i) {
    d[i] = mpz_get_d_2exp(&k[i], in[i]->get_mpz_t());
    if (d[i] != 0) top = std::max(top, k[i]);
  }
  TorusInput<Ul> w;
  RuT<L>* out[12] = {&w.X[0], &w.X[1], &w.X[2], &w.Y[0], &w.Y[1], &w.Y[2],
                     &w.Z[0], &w.Z[1], &w.Z[2], &w.R,    &w.M,    &w.C};
  for (int i = 0; i < 12; ++i) {
    if (d[i] == 0) {
      *out[i] = {0, 0};  // an exact 0 (mpz_get_d_2exp of 0)
      continue;
    }
    // k[i] - top > -4,400 here (the integers have at most about 4,300
    // bits: lengths and rotation entries from 2^-1074 to 2^1024), inside long
    // double's exponents on x86-64 and AArch64; where long double is double,
    // ldexp underflows and eta covers the loss.
    const int e = int(std::max(k[i] - top, -20000L));
    const L v = ldexpWide(L(d[i]), e);
    *out[i] = {v, ldexpWide(std::fabs(L(d[i])) * L(0x1p-52), e) + kEtaT<L>};
  }
  return w;
}

/// The window-float kernel (src/margin_sturm.h, detail::window).
using Mk = detail::window::Kernel;

/// The exact torus input in window floats: each integer's leading p bits
/// (truncated, the rest its bound).
TorusInput<Mk> torusWindowInput(const TorusInput<ZKernel>& t, int p) {
  TorusInput<Mk> w;
  for (int i = 0; i < 3; ++i) {
    w.X[i] = detail::window::fromInteger(t.X[i], p);
    w.Y[i] = detail::window::fromInteger(t.Y[i], p);
    w.Z[i] = detail::window::fromInteger(t.Z[i], p);
  }
  w.R = detail::window::fromInteger(t.R, p);
  w.M = detail::window::fromInteger(t.M, p);
  w.C = detail::window::fromInteger(t.C, p);
  return w;
}

/// A sized part (grow_radius: Cyl(r + m, h), else Cyl(r, h + m)) by the
/// triangle kernel's predicate in window floats, on the exact torus input
/// `t` (torusExactInput(q, 1)): the geometry scaled by 2, so that the
/// kernel's frame (x, y, Z = 2z, H = lz, radius) is (X, Y, 2 Z, 2 C, R)
/// with R + M for the grown radius and 2 (C + M) for the grown length
/// (X = 2x, R = 2r, M = 2m, C = lz: a scaling leaves the test unchanged).
/// kUnknown: the exact run decides.
Tri sizedPartWindow(const TorusInput<Mk>& w, bool grow_radius) {
  using detail::window::twice;
  detail::TriCylLocal<Mk> l;
  for (int i = 0; i < 3; ++i) {
    l.x[i] = w.X[i];
    l.y[i] = w.Y[i];
    l.Z[i] = twice(w.Z[i]);
  }
  l.H = twice(grow_radius ? w.C : w.C + w.M);
  l.r = grow_radius ? w.R + w.M : w.R;
  bool early = false;
  return detail::triangleCylinder<Mk>(l, &early);
}

/// The window's precisions, tried in order: enough for most sized parts
/// and faces of the hostile thresholds (the decisive quantities cancel a
/// few hundred bits), then four times that (measured on the regression
/// list: the least window that decides is 64 to 1,024 bits there; a
/// window run costs mostly its operations' overhead at 320 bits, about
/// 1.8 times that at 1,280). Where both abstain the exact stage decides.
constexpr int kWindowBits[2] = {320, 1280};

/// The window stages of a sized part, at each precision in turn.
Tri sizedPartWindows(const TorusInput<ZKernel>& t, bool grow_radius) {
  Tri r = sizedPartWindow(torusWindowInput(t, kWindowBits[0]), grow_radius);
  if (r == Tri::kUnknown)
    r = sizedPartWindow(torusWindowInput(t, kWindowBits[1]), grow_radius);
  return r;
}

/// The superset Cyl(r + m, h + m) of C + B_m (every point within m of C
/// has rho <= r + m and |z| <= h + m) by the triangle kernel's predicate,
/// in the frame of sizedPartWindow with both sizes grown (R + M and
/// 2 (C + M), the sums formed in the kernel's own arithmetic: no rounding
/// up, the exact superset): in long double on the exact torus input
/// rounded once (`wide`: torusWideInput), then in window floats on the
/// exact input `t` at each precision in turn. kFalse: the triangle misses
/// it, an exact no for the query; kTrue: it meets it (the superset cannot
/// decide); kUnknown: every stage abstains.
template <class K>
Tri supersetPart(const TorusInput<K>& w) {
  detail::TriCylLocal<K> l;
  for (int i = 0; i < 3; ++i) {
    l.x[i] = w.X[i];
    l.y[i] = w.Y[i];
    l.Z[i] = w.Z[i] + w.Z[i];
  }
  const typename K::Num h = w.C + w.M;
  l.H = h + h;
  l.r = w.R + w.M;
  bool early = false;
  return detail::triangleCylinder<K>(l, &early);
}
Tri supersetStages(const TorusInput<ZKernel>& t, const TorusInput<Ul>& wide) {
  Tri r = supersetPart<Ul>(wide);
  for (const int bits : kWindowBits) {
    if (r != Tri::kUnknown) break;
    r = supersetPart<Mk>(torusWindowInput(t, bits));
  }
  return r;
}

/// The face part of one torus in window floats, at each precision in turn.
Tri faceWindows(const TorusInput<ZKernel>& t) {
  Tri r = faceFeet<Mk>(torusWindowInput(t, kWindowBits[0]));
  if (r == Tri::kUnknown) r = faceFeet<Mk>(torusWindowInput(t, kWindowBits[1]));
  return r;
}

/// The face part of one torus through the stage driver (src/stages.h):
/// FilterKernel, then the adaptive kernel, on the scaled inputs. Where the
/// scaling is not exact: UnderflowKernel on the rescaled inputs, then on
/// the exact local coordinates rounded once to long double (`wide()`, the
/// torus's torusWideInput), then GMP dyadics on the original inputs.
template <class Wide, class Exact>
Decision faceStage(const Query& q, const ScaledInputs& s, bool top, Wide&& wide,
                   Exact&& exact) {
  auto pred = [&](auto tag, bool*) {
    using K = typename decltype(tag)::type;
    const auto l =
        s.ok ? detail::makeLocal<K>(s.cyl, s.pose, s.tri, q.max_unitless)
             : detail::makeLocal<K>(q.cyl, q.pose, q.tri, q.max_unitless);
    return faceFeet<K>(torusInput<K>(l, s.ok ? s.m : q.m, top));
  };
  if (!s.ok) {
    if (q.max_len > 0) {
      const Tri f = faceFeet<Uk>(torusRobustInput(q, top));
      if (f != Tri::kUnknown)
        return {f == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint,
                Stage::kFastPath};
    }
    Tri f = faceFeet<Ul>(wide());
    if (f == Tri::kUnknown) f = faceWindows(exact());
    if (f != Tri::kUnknown)
      return {f == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint,
              Stage::kExtended};
    return detail::runAdaptive(pred, false);
  }
  return detail::runStages(pred, 2.0, q.max_unitless);
}

/// Cylinder part with the exact sum r + m (grow_radius) or lz + 2m as the
/// size, on the adaptive tape (or in GMP dyadics outside the range gate).
/// Reached only when the bracket of the two neighbouring doubles disagrees.
Decision cylinderPartExact(const Query& q, bool grow_radius) {
  auto pred = [&](auto tag, bool* early) {
    using K = typename decltype(tag)::type;
    auto loc = detail::makeLocal<K>(q.cyl, q.pose, q.tri, q.max_unitless);
    if (grow_radius)
      loc.r = loc.r + K::lift(q.m);
    else
      loc.H = loc.H + (K::lift(q.m) + K::lift(q.m));
    return detail::triangleCylinder<K>(loc, early);
  };
  // r + m and lz + 2m are at most 3 times the largest length: the gate is
  // taken on that, so the bounds behind the adaptive run hold for them.
  const bool gate = detail::rangeGateOk(4 * q.max_len, q.max_unitless);
  return detail::runAdaptive(pred, gate);
}

bool intersects(double r, double lz, const Query& q) {
  return tryIntersect(Cylinder<double>{r, lz}, q.pose, q.tri) ==
         Answer::kIntersect;
}

Stage stronger(Stage a, Stage b) {
  auto rank = [](Stage s) {
    switch (s) {
      case Stage::kEarlyOut:
        return 0;
      case Stage::kFastPath:
        return 1;
      case Stage::kRunning:
        return 2;
      case Stage::kExtended:
        return 3;
      case Stage::kExact:
        return 4;
      case Stage::kExactGmp:
        return 5;
      default:
        return 6;
    }
  };
  return rank(a) >= rank(b) ? a : b;
}

Decision yes(Stage s) { return {Answer::kIntersect, s}; }
Decision no(Stage s) { return {Answer::kDisjoint, s}; }

/// Inputs on which every call of the exact kernel is slow (its exact
/// stages on dyadics whose products leave the floating-point expansions'
/// exponent window, or inputs outside the range gate), read from the bits:
/// a nonzero size, margin or coordinate below 2^-400, their exponents
/// spanning more than 500, or one of them 2^40 or more. For
/// these a sized part goes to its one exact run instead of bracketing the
/// sum by kernel calls (measured by callgrind on the slowest queries of the
/// hostile set inside the range gate: the calls cost up to 1.5 times the
/// run). Only a cost decision: both ways are exact.
bool wideSpread(const Query& q) {
  static_assert(sizeof(Triangle<double>) == 9 * sizeof(double),
                "packed coordinates");
  // On the absolute values' bit patterns (monotone in the value): the
  // largest and the smallest nonzero (b - 1 wraps for 0 and drops out of
  // the minimum) of the sizes, the margin and the vertices' coordinates.
  // The translation and the rotation are not read (a cheaper test that
  // finds the hostile inputs of tricyl-margin-stage-costs as well).
  constexpr std::uint64_t kAbs = ~(std::uint64_t(1) << 63);
  std::uint64_t w[12];
  std::memcpy(w, &q.cyl.radius, sizeof(double));
  std::memcpy(w + 1, &q.cyl.lz, sizeof(double));
  std::memcpy(w + 2, &q.m, sizeof(double));
  std::memcpy(w + 3, &q.tri, 9 * sizeof(double));
  std::uint64_t hi = 0, lo = ~std::uint64_t(0);
  for (std::uint64_t b : w) {
    b &= kAbs;
    hi = b > hi ? b : hi;
    lo = b - 1 < lo ? b - 1 : lo;
  }
  const int ehi = int(hi >> 52);
  const int elo = lo == ~std::uint64_t(0) ? ehi : int((lo + 1) >> 52);
  return elo < 1023 - 400 || ehi - elo > 500 || ehi >= 1023 + 40;
}

/// Does the triangle certainly miss the sized part Cyl(r + m, h)
/// (grow_radius) or Cyl(r, h + m)? Exact comparisons of the exact torus
/// input `t` (torusExactInput(q, 1): doubled local coordinates X, Y, Z and
/// sizes R = 2r, M = 2m, C = lz in one unit), no products: every vertex
/// beyond one face of the part's slab (Z > C (+ M), or Z < -(C (+ M))), or
/// beyond one of the four planes x = +-(r (+ m)), y = +-(r (+ m)) that
/// touch the part's barrel (the part is convex and lies on the other
/// side). Only a shortcut: false says nothing.
bool sizedPartExcluded(const TorusInput<ZKernel>& t, bool grow_radius) {
  const mpz_class half = grow_radius ? t.C : mpz_class(t.C + t.M);
  const mpz_class rad = grow_radius ? mpz_class(t.R + t.M) : t.R;
  auto all = [](auto&& pred) { return pred(0) && pred(1) && pred(2); };
  return all([&](int i) { return t.Z[i] > half; }) ||
         all([&](int i) { return t.Z[i] < -half; }) ||
         all([&](int i) { return t.X[i] > rad; }) ||
         all([&](int i) { return t.X[i] < -rad; }) ||
         all([&](int i) { return t.Y[i] > rad; }) ||
         all([&](int i) { return t.Y[i] < -rad; });
}

/// Does the triangle certainly miss the torus at +h (top) or -h? As
/// sizedPartExcluded, for the torus's bounding box: the slab
/// |z -+ h| <= m and the planes x, y = +-(r + m) (every point of the torus
/// is a rim point plus a vector of length <= m).
bool torusExcluded(const TorusInput<ZKernel>& t, bool top) {
  const mpz_class hi = t.C + t.M, lo = t.C - t.M, rad = t.R + t.M;
  auto all = [](auto&& pred) { return pred(0) && pred(1) && pred(2); };
  // Z of the top torus's input; the bottom one's is -Z (torusExactInput).
  auto z = [&t, top](int i) { return top ? t.Z[i] : mpz_class(-t.Z[i]); };
  return all([&](int i) { return z(i) > hi; }) ||
         all([&](int i) { return z(i) < lo; }) ||
         all([&](int i) { return t.X[i] > rad; }) ||
         all([&](int i) { return t.X[i] < -rad; }) ||
         all([&](int i) { return t.Y[i] > rad; }) ||
         all([&](int i) { return t.Y[i] < -rad; });
}

/// A torus that the other one dominates on the triangle: for a point at
/// height z >= 0 and h >= 0, (z + h)^2 - (z - h)^2 = 4 z h >= 0, so its
/// distance to the bottom rim circle is at least that to the top one (the
/// radial terms are equal) and Tor(-h) meets the triangle only where
/// Tor(+h) does, if the whole triangle (convex) lies in z >= 0; the same
/// mirrored for z <= 0, and for h = 0 the two tori coincide. Returns the
/// torus (0: top, 1: bottom) that can be skipped, or -1. Comparisons of
/// the exact torus input `t` (torusExactInput(q, 1)).
int torusDominated(const TorusInput<ZKernel>& t) {
  if (sgn(t.C) == 0) return 1;
  auto all = [](auto&& pred) { return pred(0) && pred(1) && pred(2); };
  if (all([&](int i) { return sgn(t.Z[i]) >= 0; })) return 1;
  if (all([&](int i) { return sgn(t.Z[i]) <= 0; })) return 0;
  return -1;
}

/// A cheap hit certificate on the exact torus input `t` (torusExactInput(q,
/// 1): doubled local coordinates, C = lz, M = 2m): the triangle meets the
/// axis at a point with |z| <= h + m, which lies in Cyl(r, h + m), a part
/// of C + B_m. With the vertices' projections p_a, p_b, p_c on the plane
/// z = 0 and w_a = p_b x p_c, w_b = p_c x p_a, w_c = p_a x p_b (so
/// d = w_a + w_b + w_c is twice the projected signed area), the axis meets
/// the closed triangle iff d != 0 and the three w have no two of opposite
/// signs, at Z = (w_a Z_a + w_b Z_b + w_c Z_c) / d; then |Z| <= C + M.
/// Integer products of the inputs' size (nine, and one for the bound); a
/// triangle parallel to the axis (d = 0) is left to the parts.
/// axisCrossing: the axis meets the closed triangle and d != 0 (n and d
/// set, Z = n / d); axisHit: and |Z| <= C + M.
bool axisCrossing(const TorusInput<ZKernel>& t, mpz_class* n, mpz_class* d) {
  mpz_class w[3];
  int pos = 0, neg = 0;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    w[i] = t.X[j] * t.Y[k] - t.Y[j] * t.X[k];
    pos += sgn(w[i]) > 0;
    neg += sgn(w[i]) < 0;
  }
  if (pos > 0 && neg > 0) return false;  // the axis misses the triangle
  *d = w[0] + w[1] + w[2];
  if (sgn(*d) == 0) return false;
  *n = w[0] * t.Z[0] + w[1] * t.Z[1] + w[2] * t.Z[2];
  return true;
}
bool axisHit(const TorusInput<ZKernel>& t) {
  mpz_class n, d;
  return axisCrossing(t, &n, &d) && abs(n) <= (t.C + t.M) * abs(d);
}

/// a b <= c d for a b >= 0 and c, d >= 0, the products formed only where
/// the operands' bit lengths do not decide: for an i-bit and a j-bit
/// number, 2^(i + j - 2) <= |a b| < 2^(i + j).
bool productAtMost(const mpz_class& a, const mpz_class& b, const mpz_class& c,
                   const mpz_class& d) {
  if (sgn(a) == 0 || sgn(b) == 0) return true;
  if (sgn(c) == 0 || sgn(d) == 0) return false;
  auto bits = [](const mpz_class& z) {
    return long(mpz_sizeinbase(z.get_mpz_t(), 2));
  };
  const long ab = bits(a) + bits(b), cd = bits(c) + bits(d);
  if (ab + 2 <= cd) return true;  // a b < 2^ab <= 2^(cd - 2) <= c d
  if (cd + 2 <= ab) return false;
  return mpz_class(a * b) <= mpz_class(c * d);
}

/// The capsule around the axis. Every point of C lies within r of the
/// segment S = [-h, h] e_z, so C + B_m lies in S + B_(r + m), and
/// dist(S, T) > r + m gives |t - c| >= dist(t, S) - dist(c, S) > m for
/// every t in T and c in C: an exact no (kFalse). S lies in C, so a
/// distance at most m between a point of S and a point of T is an exact
/// yes (kTrue). Both decide where r is small beside the gap between the
/// distance and m, which is where the sized parts and the faces cancel
/// the most bits (docs/margin.md, "seventh pass"); kUnknown otherwise. On
/// the exact torus input `t` (torusExactInput(q, 1): doubled local
/// coordinates, so S runs from -C e_z to C e_z, the radius is R + M and
/// the margin M). dist(S, T) is attained at (i) a crossing of S and T
/// inside T, (ii) an end of S whose projection on T's plane lies in T, or
/// (iii) S against an edge of T (the closest pair of two convex polytopes
/// lies on a pair of their faces; with t interior to T and s interior to
/// S, either the distance is 0, case (i), or S is parallel to the plane and
/// sliding s to an end keeps the distance, cases (ii) and (iii)); each
/// candidate is tested only where it is realized, so the first one within
/// r + m is an actual distance. Integer products of up to six times the
/// inputs' size.
Tri capsulePart(const TorusInput<ZKernel>& t) {
  const mpz_class rho = t.R + t.M;
  const mpz_class rho2 = rho * rho, m2 = t.M * t.M;
  // A distance that some point of S and some point of T realize, at most
  // r + m (squared: a b <= (R + M)^2 c d): the capsule cannot exclude;
  // at most m, a hit.
  auto near = [&](const mpz_class& a, const mpz_class& b, const mpz_class& c,
                  const mpz_class& d) -> Tri {
    if (!productAtMost(a, b, rho2, mpz_class(c * d))) return Tri::kFalse;
    return productAtMost(a, b, m2, mpz_class(c * d)) ? Tri::kTrue
                                                     : Tri::kUnknown;
  };
  // (i) The axis meets the closed triangle (axisCrossing) at Z = n / d;
  // inside S iff |n| <= C |d|. For d = 0 the triangle's plane contains the
  // axis's direction: no transversal crossing.
  {
    mpz_class n, d;
    if (axisCrossing(t, &n, &d) && abs(n) <= t.C * abs(d))
      return Tri::kTrue;  // T meets S
  }
  // (ii) The ends p = +-C e_z of S whose projection on the plane lies in
  // the closed triangle: with n = (P_1 - P_0) x (P_2 - P_0), the plane's
  // distance (n . (p - P_0))^2 > (R + M)^2 |n|^2 is needed only where the
  // projection is inside: ((B - A) x (p - A)) . n >= 0 for the three edges
  // A -> B, that is k . n +- C (D_y n_x - D_x n_y) >= 0 with D = B - A and
  // k = A x D. First (on the hostile thresholds every failure of the
  // capsule at the true side was here); the inside test only for an end
  // whose plane distance fails. A degenerate triangle (n = 0) is its
  // edges.
  {
    const mpz_class e1[3] = {t.X[1] - t.X[0], t.Y[1] - t.Y[0], t.Z[1] - t.Z[0]};
    const mpz_class e2[3] = {t.X[2] - t.X[0], t.Y[2] - t.Y[0], t.Z[2] - t.Z[0]};
    const mpz_class n[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                            e1[2] * e2[0] - e1[0] * e2[2],
                            e1[0] * e2[1] - e1[1] * e2[0]};
    const mpz_class nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
    if (sgn(nn) != 0) {
      const mpz_class np0 = n[0] * t.X[0] + n[1] * t.Y[0] + n[2] * t.Z[0];
      const mpz_class cn = t.C * n[2];
      Tri plane[2];  // the end's plane distance: kFalse beyond R + M
      bool inside[2];
      for (int i = 0; i < 2; ++i) {
        const mpz_class pl =
            i == 0 ? mpz_class(cn - np0) : mpz_class(-cn - np0);
        plane[i] = near(pl, pl, 1, nn);
        inside[i] = plane[i] != Tri::kFalse;
      }
      for (int e = 0; e < 3 && (inside[0] || inside[1]); ++e) {
        const int ia = kEdge[e][0], ib = kEdge[e][1];
        const mpz_class &ax = t.X[ia], &ay = t.Y[ia], &az = t.Z[ia];
        const mpz_class dx = t.X[ib] - ax, dy = t.Y[ib] - ay, dz = t.Z[ib] - az;
        const mpz_class kn = (ay * dz - az * dy) * n[0] +
                             (az * dx - ax * dz) * n[1] +
                             (ax * dy - ay * dx) * n[2];
        const mpz_class cg = t.C * (dy * n[0] - dx * n[1]);
        inside[0] = inside[0] && sgn(kn + cg) >= 0;
        inside[1] = inside[1] && sgn(kn - cg) >= 0;
      }
      for (int i = 0; i < 2; ++i)  // inside: the plane's distance realized
        if (inside[i]) return plane[i];
    }
  }
  // Every vertex beyond r + m of S (the ends of the edges in (iii)):
  // rho_xy^2 + max(|Z| - C, 0)^2 > (R + M)^2.
  for (int i = 0; i < 3; ++i) {
    mpz_class d2 = t.X[i] * t.X[i] + t.Y[i] * t.Y[i];
    const mpz_class ez = abs(t.Z[i]) - t.C;
    if (sgn(ez) > 0) d2 += ez * ez;
    if (d2 <= rho2) return d2 <= m2 ? Tri::kTrue : Tri::kUnknown;
  }
  // (iii) S against each edge A + s D, s in [0, 1] (D = B - A, k = A x D,
  // a = -A_xy . D_xy): the squared distance |A + s D - z e_z|^2 is convex
  // on [0, 1] x [-C, C]; its minimum is at the free minimiser where that
  // lies in the rectangle (s* = a / |D_xy|^2, z* = A_z + s* D_z: the
  // distance k_z^2 / |D_xy|^2 of the origin to the edge's line in the xy
  // plane), else on the rectangle's boundary: the vertices against S
  // (above) or the ends p = +-C e_z of S against the edge. For u = p - A:
  // u . D = a - A_z D_z +- C D_z; a foot inside the edge (0 < u . D < |D|^2;
  // a foot at a vertex is the vertex's case: |p - A| >= dist(A, S)) needs
  // |u x D|^2 = |k|^2 + C^2 |D_xy|^2 +- 2 C (k_x D_y - k_y D_x)
  // > (R + M)^2 |D|^2.
  for (int e = 0; e < 3; ++e) {
    const int ia = kEdge[e][0], ib = kEdge[e][1];
    const mpz_class &ax = t.X[ia], &ay = t.Y[ia], &az = t.Z[ia];
    const mpz_class dx = t.X[ib] - ax, dy = t.Y[ib] - ay, dz = t.Z[ib] - az;
    const mpz_class dxy = dx * dx + dy * dy;
    const mpz_class dd = dxy + dz * dz;
    const mpz_class a = -(ax * dx + ay * dy);
    const mpz_class base = a - az * dz, cdz = t.C * dz;
    const mpz_class dot[2] = {base + cdz, base - cdz};
    const bool foot[2] = {sgn(dot[0]) > 0 && dot[0]<dd, sgn(dot[1])> 0 &&
                          dot[1] < dd};
    const bool free_min = sgn(dxy) != 0 && sgn(a) > 0 && a < dxy &&
                          abs(az * dxy + a * dz) <= t.C * dxy;
    if (!(foot[0] || foot[1] || free_min)) continue;
    const mpz_class kz = ax * dy - ay * dx;
    if (free_min) {
      const Tri r = near(kz, kz, 1, dxy);
      if (r != Tri::kFalse) return r;
    }
    if (foot[0] || foot[1]) {
      const mpz_class kx = ay * dz - az * dy, ky = az * dx - ax * dz;
      const mpz_class lhs = kx * kx + ky * ky + kz * kz + t.C * t.C * dxy;
      const mpz_class twice_cl = 2 * t.C * (kx * dy - ky * dx);
      for (int i = 0; i < 2; ++i) {
        if (!foot[i]) continue;
        const Tri r =
            near(i == 0 ? mpz_class(lhs + twice_cl) : mpz_class(lhs - twice_cl),
                 1, 1, dd);
        if (r != Tri::kFalse) return r;
      }
    }
  }
  return Tri::kFalse;
}

/// A sized part (grow_radius: Cyl(r + m, h), else Cyl(r, h + m)).
/// `stage` accumulates the strongest stage used; `wide` is wideSpread(q).
bool cylinderPart(const Query& q, bool grow_radius, bool wide, Stage* stage) {
  const TwoSum s =
      grow_radius ? twoSum(q.cyl.radius, q.m) : twoSum(q.cyl.lz, 2 * q.m);
  if (!wide && s.finite && std::isfinite(2 * q.m)) {
    const double r = grow_radius ? s.down() : q.cyl.radius;
    const double lz = grow_radius ? q.cyl.lz : s.down();
    if (intersects(r, lz, q)) return true;  // a subset: exact yes
    if (s.e == 0) return false;             // the sum itself: exact no
    const double r_up = grow_radius ? s.up() : q.cyl.radius;
    const double lz_up = grow_radius ? q.cyl.lz : s.up();
    if (std::isfinite(r_up) && std::isfinite(lz_up) &&
        !intersects(r_up, lz_up, q))
      return false;  // a superset: exact no
  }
  Query qs = q;
  qs.scan();
  const Decision d = cylinderPartExact(qs, grow_radius);
  *stage = stronger(*stage, d.stage);
  return d.answer == Answer::kIntersect;
}

/// The superset of decide() on wide inputs outside the range gate (q
/// scanned): first in double on the rescaled inputs (torusRobustInput: no
/// GMP), then on the exact input (supersetStages; the later stages form it
/// again: kept here, in decide's frame, it cost the queries inside the
/// gate 30 - 40 ns, measured); where every stage abstains and r <= m, the
/// capsule (capsulePart). kDisjoint: an exact no; kIntersect: the
/// triangle meets the superset (Stage::kExtended), or an exact yes by the
/// capsule (Stage::kExactGmp); kInvalidInput: not decided.
Decision wideSuperset(const Query& q) {
  Tri w = q.max_len > 0 ? supersetPart<Uk>(torusRobustInput(q, true))
                        : Tri::kUnknown;
  if (w == Tri::kFalse) return no(Stage::kEarlyOut);
  if (w == Tri::kUnknown) {
    const TorusInput<ZKernel> exact = torusExactInput(q, 1);
    w = supersetStages(exact, torusWideInput(exact));
    // Where every stage abstains and r <= m, the capsule around the axis
    // (capsulePart) before the kernel's call: exact in products of the
    // inputs' size where r is small beside the gap between the distance
    // and m, which is where the parts too go to their exact runs
    // (docs/margin.md, "seventh pass").
    if (w == Tri::kUnknown && q.cyl.radius <= q.m) {
      const Tri c = capsulePart(exact);
      if (c == Tri::kFalse) return no(Stage::kExactGmp);
      if (c == Tri::kTrue) return yes(Stage::kExactGmp);
    }
  }
  if (w == Tri::kFalse) return no(Stage::kExtended);
  if (w == Tri::kTrue) return yes(Stage::kExtended);
  return {Answer::kInvalidInput, Stage::kExtended};
}

Decision decide(Query& q) {
  if (q.m == 0) return decideIntersect(q.cyl, q.pose, q.tri);
  // A superset of C + B_m: Cyl(r + m, h + m), sizes rounded up. This first
  // call of the kernel also validates the pose and the triangle. For
  // x = fl(a + b) >= 0 normal, fl(x + fl(x 2^-51)) >= x (1 + 2^-52) >= a + b;
  // in the subnormal range the sum is exact and the bound still >= it.
  bool validated = false;
  const double two_m = 2 * q.m;
  const double r_sum = q.cyl.radius + q.m, l_sum = q.cyl.lz + two_m;
  const double r_up = r_sum + r_sum * 0x1p-51;
  const double lz_up = l_sum + l_sum * 0x1p-51;
  // Wide inputs outside the range gate (wideSpread, rangeGateOk): the same
  // superset, exactly, on the exact torus input (supersetStages) before
  // the kernel's call, which runs its own exact stages on these inputs (as
  // costly as `intersect` on them, whatever its answer, and its superset
  // rounded up by an ulp of r + m, which hides a margin many orders below
  // r); the call only where every stage abstains. scan() validates the
  // inputs instead of the call. Inside the gate the kernel's fast path
  // decides the superset at once.
  const bool wide = wideSpread(q);
  bool sized_first = !wide;
  bool superset_open = true;
  if (wide) {
    if (!q.scan()) return {Answer::kInvalidInput, Stage::kInvalid};
    validated = true;
    sized_first = detail::rangeGateOk(4 * q.max_len, q.max_unitless);
    if (!sized_first) {
      const Decision d = wideSuperset(q);
      if (d.answer == Answer::kDisjoint) return d;
      if (d.stage == Stage::kExactGmp) return d;          // the capsule's hit
      superset_open = d.answer == Answer::kInvalidInput;  // not decided
    }
  }
  if (superset_open && std::isfinite(r_up) && std::isfinite(lz_up)) {
    const Answer a = tryIntersect(Cylinder<double>{r_up, lz_up}, q.pose, q.tri);
    if (a == Answer::kInvalidInput) return {a, Stage::kInvalid};
    if (a == Answer::kDisjoint) return no(Stage::kEarlyOut);
    validated = true;
  }
  if (!validated && !q.scan()) return {Answer::kInvalidInput, Stage::kInvalid};
  Stage stage = Stage::kFastPath;
  // The order of the parts (every part is a subset of C + B_m, so a hit by
  // any one ends the query, in any order; a miss needs all four; the faces
  // need the triangle to miss C, so they come after the sized parts). Where
  // a sized part is cheap (inside the range gate: two or three kernel calls,
  // or one adaptive run on wide inputs) the sized parts first, as they
  // decide most queries. Outside the gate on wide inputs (wideSpread) each
  // is one exact kernel run on dyadics of thousands of bits, and for
  // r <= m the edges' ball test (edgeBallHit: comparisons and leading
  // bits, six products of the inputs' size where the long double hint
  // abstains) runs first: on the hostile thresholds every hit of the edges'
  // exact stage comes from it. Then the sized parts that the slab and
  // half-plane tests do not exclude, the rest of the edges, the faces
  // (docs/margin.md, "Wide inputs: the parts by cost").
  const bool ball_first = !sized_first && q.cyl.radius <= q.m;
  if (sized_first) {
    if (cylinderPart(q, true, wide, &stage)) return yes(stage);
    if (cylinderPart(q, false, wide, &stage)) return yes(stage);
  }
  // The tori: the edges' filters.
  q.scan();
  const ScaledInputs s = scaleInputs(q);
  bool open[2][3] = {{true, true, true}, {true, true, true}};
  bool l_pos[2][3] = {};  // L > 0 certified by a filter
  if (s.ok) {
    const auto l = detail::makeLocal<Rk>(s.cyl, s.pose, s.tri, q.max_unitless);
    for (int i = 0; i < 2; ++i)
      if (edgesFilter(torusInput<Rk>(l, s.m, i == 0), open[i], l_pos[i]) ==
          Tri::kTrue)
        return yes(stage);
  } else if (q.max_len > 0) {
    for (int i = 0; i < 2; ++i)
      if (edgesFilter(torusRobustInput(q, i == 0), open[i], l_pos[i]) ==
          Tri::kTrue)
        return yes(stage);
  }
  auto anyOpen = [&open](int i) {
    return open[i][0] || open[i][1] || open[i][2];
  };
  // The edges the double filter left open: double-word, on the same exactly
  // scaled inputs (the hostile path has no such stage: its inputs are
  // rounded, and its ties are rare).
  if (s.ok && (anyOpen(0) || anyOpen(1))) {
    stage = stronger(stage, Stage::kExtended);
    const auto lw = detail::makeLocal<Wk>(s.cyl, s.pose, s.tri, q.max_unitless);
    for (int i = 0; i < 2; ++i) {
      if (!anyOpen(i)) continue;
      const TorusInput<Wk> tw = torusInput<Wk>(lw, s.m, i == 0);
      for (int e = 0; e < 3; ++e) {
        if (!open[i][e]) continue;
        const Tri r =
            edgeFilter<Wk>(tw, kEdge[e][0], kEdge[e][1], &l_pos[i][e]);
        if (r == Tri::kTrue) return yes(stage);
        open[i][e] = r == Tri::kUnknown;
      }
    }
  }
  // The exact torus inputs (GMP integers) and, where the scaling is not
  // exact, their long double rounding, made once when first needed.
  std::optional<TorusInput<ZKernel>> exact_top;  // the bottom one mirrors it
  auto exactTorus = [&](int i) {
    if (!exact_top) exact_top = torusExactInput(q, 1);
    TorusInput<ZKernel> t = *exact_top;
    if (i == 1)
      for (auto& z : t.Z) z = -z;
    return t;
  };
  std::optional<TorusInput<Ul>> wide_in[2];
  auto wideTorus = [&](int i) -> const TorusInput<Ul>& {
    if (!wide_in[i]) wide_in[i] = torusWideInput(exactTorus(i));
    return *wide_in[i];
  };
  // The edges the rescaled double filter left open: the same filter in
  // long double on the exact coordinates (torusWideInput; it needs the
  // exact input, so it runs after the sized parts where those go first;
  // where the ball test goes first it runs after the ball test and the
  // sized parts: before them it cost the queries a sized part decides as
  // much as it saved the ball test). True: a hit.
  bool wide_filter_done = s.ok;
  auto wideFilter = [&]() {
    wide_filter_done = true;
    for (int i = 0; i < 2; ++i) {
      if (!anyOpen(i)) continue;
      stage = stronger(stage, Stage::kExtended);
      for (int e = 0; e < 3; ++e) {
        if (!open[i][e]) continue;
        const Tri r = edgeFilter<Ul>(wideTorus(i), kEdge[e][0], kEdge[e][1],
                                     &l_pos[i][e]);
        if (r == Tri::kTrue) return true;
        open[i][e] = r == Tri::kUnknown;
      }
    }
    return false;
  };
  if (!wide_filter_done && sized_first && wideFilter()) return yes(stage);
  bool slab_out[2] = {false, false};  // the triangle beyond a torus's slab
  if (!wide) {
    // The exact stage of the open edges, edge by edge.
    for (int i = 0; i < 2; ++i) {
      if (!anyOpen(i)) continue;
      const TorusInput<ZKernel> t = exactTorus(i);
      stage = Stage::kExactGmp;
      for (int e = 0; e < 3; ++e)
        if (open[i][e] && edgeExact(t, kEdge[e][0], kEdge[e][1]))
          return yes(stage);
    }
  } else {
    // Wide inputs, by cost: the ball test, the sized parts (when not run
    // first), the bounding sets (products of the inputs' size), the
    // quartics (twice that size), the wide quartics' local certificate.
    if (!exact_top) exact_top = torusExactInput(q, 1);
    if (!sized_first && axisHit(*exact_top))
      return yes(stronger(stage, Stage::kExactGmp));
    // One torus dominates the other where the triangle lies on one side of
    // z = 0 (torusDominated): the other's edges and face are skipped.
    const int dominated = torusDominated(*exact_top);
    if (dominated >= 0)
      for (bool& o : open[dominated]) o = false;
    if (ball_first)
      for (int i = 0; i < 2; ++i) {
        if (!anyOpen(i)) continue;
        const TorusInput<ZKernel> t = exactTorus(i);
        stage = Stage::kExactGmp;
        for (int e = 0; e < 3; ++e)
          if (open[i][e] && !l_pos[i][e] &&
              edgeBallHit(t, kEdge[e][0], kEdge[e][1], [&](bool* inside) {
                return edgeBallVertex<Ul>(wideTorus(i), kEdge[e][0],
                                          kEdge[e][1], inside);
              }))
            return yes(stage);
      }
    if (!sized_first) {
      if (!exact_top) exact_top = torusExactInput(q, 1);
      for (const bool grow_radius : {true, false}) {
        if (sizedPartExcluded(*exact_top, grow_radius)) continue;
        const Tri w = sizedPartWindows(*exact_top, grow_radius);
        if (w == Tri::kTrue) return yes(stronger(stage, Stage::kExtended));
        if (w == Tri::kFalse) continue;
        if (cylinderPart(q, grow_radius, true, &stage)) return yes(stage);
      }
    }
    if (!wide_filter_done && wideFilter()) return yes(stage);
    ExactEdge edge[2][3];
    for (int i = 0; i < 2; ++i) {
      if (!anyOpen(i)) continue;
      const TorusInput<ZKernel> t = exactTorus(i);
      stage = Stage::kExactGmp;
      for (int e = 0; e < 3; ++e) {
        if (!open[i][e]) continue;
        const int r = edgeExactBounds(t, kEdge[e][0], kEdge[e][1], &edge[i][e],
                                      ball_first || l_pos[i][e]);
        if (r == 1) return yes(stage);
        open[i][e] = r < 0;
      }
    }
    for (int i = 0; i < 2; ++i)
      for (int e = 0; e < 3; ++e) {
        if (!open[i][e]) continue;
        const int r = edgeExactQuartic(&edge[i][e]);
        if (r == 1) return yes(stage);
        open[i][e] = r < 0;
      }
    // The same edge against the two tori: the second starts where the
    // first resolved its minimum (CertHint).
    detail::sturm::CertHint hint[3];
    for (int i = 0; i < 2; ++i)
      for (int e = 0; e < 3; ++e)
        if (open[i][e] && edgeExactWide(edge[i][e], &hint[e]))
          return yes(stage);
    // The faces' exclusion where the exact input is at hand (comparisons).
    for (int i = 0; i < 2; ++i)
      slab_out[i] = i == dominated || torusExcluded(*exact_top, i == 0);
  }
  // The triangle misses C here (C is inside Cyl(r + m, h)), hence the rim
  // circles: the face part is complete.
  for (int i = 0; i < 2; ++i) {
    if (slab_out[i]) continue;
    const Decision d = faceStage(
        q, s, i == 0, [&]() -> const TorusInput<Ul>& { return wideTorus(i); },
        [&]() { return exactTorus(i); });
    stage = stronger(stage, d.stage);
    if (d.answer == Answer::kIntersect) return yes(stage);
  }
  return no(stage);
}

/// A size is valid iff finite and >= 0 (-0 included), read from its bits:
/// no floating-point operation touches a NaN.
bool validSize(double v) {
  std::uint64_t b;
  std::memcpy(&b, &v, sizeof b);
  const std::uint64_t abs = b & ~(std::uint64_t(1) << 63);
  return abs < 0x7ff0000000000000ULL && (abs == b || abs == 0);
}

Decision validateAndDecide(const Cylinder<double>& cyl,
                           const Pose<double>& pose,
                           const Triangle<double>& tri, double m) {
  if (!validSize(cyl.radius) || !validSize(cyl.lz) || !validSize(m))
    return {Answer::kInvalidInput, Stage::kInvalid};
  // -0 is 0 for every size (the bits of -0 would break nothing, but the
  // exact sums are clearer on +0).
  Query q{{cyl.radius + 0.0, cyl.lz + 0.0}, pose, tri, m + 0.0};
  return decide(q);
}

template <class S>
Decision decideAs(const Cylinder<S>& cyl, const Pose<S>& pose,
                  const Triangle<S>& tri, S m) noexcept {
  try {
    if constexpr (std::is_same_v<S, float>) {
      const Cylinder<float> mm{m, m};
      if (!detail::floatBitsFinite(cyl, pose, tri, mm))  // before widening
        return {Answer::kInvalidInput, Stage::kInvalid};
      return validateAndDecide(
          {double(cyl.radius), double(cyl.lz)}, detail::widen(pose),
          {detail::widen(tri.a), detail::widen(tri.b), detail::widen(tri.c)},
          double(m));
    } else {
      return validateAndDecide(cyl, pose, tri, m);
    }
  } catch (...) {  // std::bad_alloc from GMP or a vector: nothing else throws
    std::terminate();
  }
}

}  // namespace

template <class S>
Decision decideWithinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                              const Triangle<S>& triangle, S margin) noexcept {
  return decideAs(cylinder, pose, triangle, margin);
}

template <class S>
Answer tryWithinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Triangle<S>& triangle, S margin) noexcept {
  return decideAs(cylinder, pose, triangle, margin).answer;
}

template <class S>
bool withinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle, S margin) {
  const Answer a = decideAs(cylinder, pose, triangle, margin).answer;
  if (a == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::withinDistance: NaN or infinite input, or a negative "
        "radius, length or margin");
  return a == Answer::kIntersect;
}

template <class S>
bool withinDistance(const Cylinder<S>& cylinder, const Triangle<S>& triangle,
                    S margin) {
  return withinDistance(cylinder, identityPose<S>(), triangle, margin);
}

template bool withinDistance(const Cylinder<float>&, const Pose<float>&,
                             const Triangle<float>&, float);
template bool withinDistance(const Cylinder<double>&, const Pose<double>&,
                             const Triangle<double>&, double);
template bool withinDistance(const Cylinder<float>&, const Triangle<float>&,
                             float);
template bool withinDistance(const Cylinder<double>&, const Triangle<double>&,
                             double);
template Answer tryWithinDistance(const Cylinder<float>&, const Pose<float>&,
                                  const Triangle<float>&, float) noexcept;
template Answer tryWithinDistance(const Cylinder<double>&, const Pose<double>&,
                                  const Triangle<double>&, double) noexcept;
template Decision decideWithinDistance(const Cylinder<float>&,
                                       const Pose<float>&,
                                       const Triangle<float>&, float) noexcept;
template Decision decideWithinDistance(const Cylinder<double>&,
                                       const Pose<double>&,
                                       const Triangle<double>&,
                                       double) noexcept;

}  // namespace tricyl
