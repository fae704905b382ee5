// SPDX-License-Identifier: BSD-3-Clause
// The entry/exit interval of a segment or a line against the cylinder,
// written once for both (src/line_cylinder_impl.h): a segment is the line
// restricted to [0, 1], i.e. two more candidates, 0 for the lower end and 1
// for the upper end.
//
// THE INTERVAL. In the cylinder frame (z doubled: Z = 2z, H = lz), with p0
// the local image of p and D = R^T (q - p) the local direction (computed
// from the input difference q - p, not as a difference of two local
// points, so that a short segment far from the pose keeps its relative
// accuracy):
//   slab:      |Z0 + s DZ| <= H: s in [(-H - Z0)/DZ, (H - Z0)/DZ] (swapped
//              if DZ < 0; all s if DZ = 0, in the slab by the Boolean);
//   cylinder:  A s^2 + 2 b s + C <= 0,  A = Dx^2 + Dy^2, b = x0 Dx + y0 Dy,
//              C = x0^2 + y0^2 - r^2,   roots (-b -+ sqrt(Delta)) / A with
//              Delta = b^2 - A C = r^2 A - c^2,  c = x0 Dy - y0 Dx
//              (Lagrange's identity; Delta >= 0 whenever the Boolean is
//              true). A = 0 (parallel to the axis): all s (C <= 0 by the
//              Boolean). Roots in the cancellation-free form q / A and
//              C / q, q = -(b + sign(b) sqrt(Delta)).
//   result:    [max(slab_lo, root_lo), min(slab_hi, root_hi)], and for a
//              segment max(0, ...), min(1, ...). For a line with DZ = 0 and
//              A = 0 (R^T (q - p) = 0: p == q, or a singular R) there is no
//              candidate at all: the set is all of R, [-inf, +inf].
// This is Freesteel's "intersection of two volumes" (the slab interval and
// the infinite-cylinder interval), not the three-surfaces method: there is
// no separate side/cap test, hence no crack at the rims.
// Emptiness is NOT read from these numbers: it is the exact Boolean.
//
// ERROR BOUND. Stage 1 evaluates every candidate with a running error
// bound, first from coefficients in double (filter.h's Rd, with an explicit
// underflow allowance), then, if that is not accurate enough, from the same
// coefficients in double-word (coefsDoubleWord), extended here by division
// and square root
// (derivations at flDiv and flSqrt), which gives each candidate an
// enclosure [v - e, v + e] of its exact value; its ends are computed with
// a widened e (see `ends`) so that their own rounding cannot shrink it.
// The exact max (min) of the candidates lies between the max (min) of the
// enclosures' lower ends and the max (min) of their upper ends: an
// enclosure [lo, hi] of the exact end s*. It is accepted when
//   hi - lo <= 2 * 2^-49 max(1, dist(0, [lo, hi]))          (kAccept)
// for both ends; since dist(0, [lo, hi]) <= |s*|, the midpoint is within
// 2^-49 max(1, |s*|) of s* (the rounding of hi - lo in the test adds a
// factor 1 + u). Forming the midpoint (halving is exact up to 2^-1075 in
// the subnormal range; one rounding of the sum in the running type, one to
// double) adds <= (2^-53 + 2^-64)(|s*| + 2^-49 max(1, |s*|)), so the double
// end is within 1.9e-15 max(1, |s*|) of s* (2^-49 + 2^-53 + 2^-64 =
// 1.8875e-15, plus second-order terms). For a segment every candidate
// enclosure is clipped by 0 and 1, so dist(0, [lo, hi]) <= 1 whenever the
// interval is non-empty and the criterion is the absolute 2^-49: the
// segment's ends are within 1.9e-15 absolutely.
// Otherwise (grazing lines, where Delta cancels and sqrt amplifies its
// error to ~sqrt(e); lines exactly parallel to the axis or to the cap planes
// in a general pose, whose A = 0 or DZ = 0 cannot be certified; quotients
// beyond max/4 in magnitude; inputs outside the range gate) stage 2
// computes A, b, C, Delta, Z0, DZ EXACTLY (GMP dyadics from ExactKernel) and
// the candidates in GMP mpf with (bits of the exact values + 128) bits (a
// relative error below 2^-120 for every candidate: no cancellation in the
// forms used), then truncates to double: relative error < 1 ulp <= 2^-52,
// or an absolute one below 2^-1022 for a result in the subnormal range; a
// value beyond the largest double in magnitude becomes an infinity.
#include <gmpxx.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "adaptive.h"
#include "line_cylinder_impl.h"

namespace tricyl::detail {
namespace {

// ---------------------------------------------------------------------------
// Stage 1: running error bounds, coefficients in double then double-word.

// The running error bound is filter.h's Rd (RunningDoubleKernel): every
// product (here also every quotient) adds the smallest subnormal for a
// possible underflow. No argument below depends on long double (issue 20:
// with a long double of double width and no underflow allowance, an
// underflowed Dy * Dy was taken for a certified A = 0). The only values
// taken as certified zeros are local coordinates with e = 0, which
// toLocalRunning gives only when every term has an exact zero factor.

/// Per running type (Rd): u', the absolute underflow allowance of a
/// product or quotient, and the floating type (filter.h's RunningTraits).
template <class N>
using Run = RunningTraits<decltype(N::v)>;

// Slack for the rounding of the bound computations themselves (each bound
// is a sum of non-negative rounded terms, short by at most (1 - u)^k).
constexpr double kInfl = 1 + 0x1p-40;

/// a / b for |B - b.v| <= b.e < |b.v|: with Q = A / B,
///   |Q - a.v/b.v| = |A b.v - a.v B| / (|B| |b.v|)
///                <= (a.e |b.v| + |a.v| b.e) / ((|b.v| - b.e) |b.v|)
///                 = (a.e + |a.v / b.v| b.e) / (|b.v| - b.e),
/// plus the rounding of the division, u' |v| (+ the underflow allowance),
/// and the underflow of |v| b.e in the numerator (kTiny / (|b.v| - b.e)).
/// Returns false if |b.v| <= b.e (the divisor's sign is not certain), if
/// the quotient exceeds max/4 in magnitude (a line's parameter can be
/// arbitrarily large; the exact stage takes it, and every later v +- e,
/// sum or difference of two such values stays finite) or the bound is not
/// at most max/4.
template <class N>
bool flDiv(const N& a, const N& b, N* out) {
  using T = typename Run<N>::T;
  constexpr T kBig = std::numeric_limits<T>::max() / 4;
  const T bv = std::fabs(b.v);
  const T be = b.e * T(kInfl);
  if (!(bv > be)) return false;
  const T v = a.v / b.v;
  if (!(std::fabs(v) <= kBig)) return false;
  // The numerator's product |v| be may underflow (a divisor and its
  // bound both subnormal: |v| be below the smallest subnormal rounds to
  // 0), losing at most kTiny absolutely, which the division by bv - be
  // (itself tiny then) amplifies: kTiny is added before the division.
  // Found by fuzz_line_cylinder (fuzz/corpus/line_cylinder/
  // underflowed-quotient-bound: a 3.4e-9 error accepted as 2^-48).
  const T e = (a.e + std::fabs(v) * be + Run<N>::kTiny) / (bv - be) +
              Run<N>::kU1 * std::fabs(v) + Run<N>::kTiny;
  if (!(e <= kBig)) return false;
  *out = {v, e * T(kInfl)};
  return true;
}

/// sqrt(a) for an exact value A >= 0 (known from the Boolean) with
/// |A - a.v| <= a.e: sqrt(A) lies in [sqrt(max(0, v - e)), sqrt(v + e)];
/// v = sqrt(max(v, 0)), e = the larger distance to those ends, plus
/// 3 u' sqrt(v + e) for the three correctly rounded square roots.
template <class N>
N flSqrt(const N& a) {
  using T = typename Run<N>::T;
  const T e = a.e * T(kInfl);
  const T lo = std::sqrt(std::max(a.v - e, T(0)));
  const T hi = std::sqrt(std::max(a.v + e, T(0)));
  const T v = std::sqrt(std::max(a.v, T(0)));
  const T err = std::max(v - lo, hi - v) + 3 * Run<N>::kU1 * hi;
  return {v, err * T(kInfl)};
}

/// The ends of [v - e, v + e], rounded OUTWARD in effect: e is widened to
/// ee = (e + u' |v|)(1 + 2^-40). The computed ee (three roundings) is at
/// least (e + u' |v|)(1 + 2^-40)(1 - u)^3 >= e + u (|v| + ee), and the
/// rounding of v -+ ee is at most u |v -+ ee| <= u (|v| + ee), so the
/// computed ends enclose the exact [v - e, v + e]. (Sums of doubles in the
/// subnormal range are exact; an underflowing u' |v| costs at most 2^-1075
/// absolutely, far below the bound.)
template <class N>
void ends(const N& x, typename Run<N>::T* lo, typename Run<N>::T* hi) {
  using T = typename Run<N>::T;
  const T ee = (x.e + Run<N>::kU1 * std::fabs(x.v)) * T(kInfl);
  *lo = x.v - ee;
  *hi = x.v + ee;
}

/// Lower and upper ends of an enclosure of the exact max (or min) of the
/// candidates added so far (`any` false: none yet); each candidate comes as
/// an enclosure [a, b] of its exact value.
template <class T>
struct Extremum {
  T lo, hi;
  bool is_max;
  bool any;
  void add(T a, T b) {
    if (!any) {
      lo = a;
      hi = b;
      any = true;
    } else if (is_max) {
      lo = std::max(lo, a);
      hi = std::max(hi, b);
    } else {
      lo = std::min(lo, a);
      hi = std::min(hi, b);
    }
  }
  /// The enclosure is narrow enough: hi - lo <= 2 kAccept max(1, d), d the
  /// distance of [lo, hi] from 0 (every value here is within max/2, so the
  /// difference is finite).
  bool accurate(T accept2) const {
    const T d = lo > 0 ? lo : (hi < 0 ? -hi : T(0));
    return hi - lo <= accept2 * std::max(T(1), d);
  }
  T mid() const { return lo / 2 + hi / 2; }
};

constexpr double kAccept = 0x1p-49;

/// Rounds an end to double; an end beyond the double range (a
/// line's parameter can reach 2^1100 with inputs inside the range gate)
/// becomes the infinity of its sign explicitly.
template <class T>
double endToDouble(T x) {
  constexpr T kMax = T(DBL_MAX);
  if (x > kMax) return std::numeric_limits<double>::infinity();
  if (x < -kMax) return -std::numeric_limits<double>::infinity();
  return double(x);
}

/// What stage 1 needs of a query, in a running type N (value v, bound e):
/// the numerators of the slab parameters, the direction's components and
/// the infinite cylinder's coefficients. `dz_zero` / `dxy_zero`: DZ, resp.
/// Dx and Dy, are certified exact zeros (e = 0 with v = 0: every term of
/// the local coordinate has a zero factor, so nothing rounded or
/// underflowed).
template <class N>
struct Coefs {
  N s_bot, s_top;  // -H - Z0 and H - Z0
  N DZ, A, b, C, delta;
  bool dz_zero, dxy_zero;
};

/// The coefficients in the running type of kernel K (RunningDoubleKernel).
template <class K>
Coefs<typename K::Num> coefsRunning(const LinearInputs& in) {
  using N = typename K::Num;
  N x0, y0, Z0, Dx, Dy, DZ;
  toLocal<K>(in.pose, in.p, 1.0, x0, y0, Z0);
  Pose<double> at_p = in.pose;
  at_p.t = in.p;  // R^T (q - p)
  toLocal<K>(at_p, in.q, 1.0, Dx, Dy, DZ);
  const N H = K::lift(in.cyl.lz);
  const N r = K::lift(in.cyl.radius);
  Coefs<N> k;
  k.s_bot = -H - Z0;
  k.s_top = H - Z0;
  k.DZ = DZ;
  k.dz_zero = DZ.v == 0 && DZ.e == 0;
  k.dxy_zero = Dx.v == 0 && Dx.e == 0 && Dy.v == 0 && Dy.e == 0;
  k.A = Dx * Dx + Dy * Dy;
  k.b = x0 * Dx + y0 * Dy;
  k.C = x0 * x0 + y0 * y0 - r * r;
  const N c = x0 * Dy - y0 * Dx;
  k.delta = r * r * k.A - c * c;
  return k;
}

/// The same coefficients in double-word (the adaptive stage's arithmetic,
/// src/adaptive.cpp: values and running bounds computed on a tape), each
/// rounded to an Rd: v = hi, e = (e_dw + |lo|)(1 + 2^-40) + 2^-600, which
/// bounds |hi - E| <= |hi + lo - E| + |lo| with the slack of the
/// double-word sign test (Tape::escalate). The quotients and the square
/// root after them then cost one double rounding each, relative: well
/// inside kAccept, where the plain double coefficients' cancellation was
/// not.
Coefs<Rd> coefsDoubleWord(const LinearInputs& in) {
  using K = AdaptiveKernel;
  Tape tape;
  TapeScope scope(&tape);
  An x0, y0, Z0, Dx, Dy, DZ;
  tape.toLocal(in.pose, in.p, x0, y0, Z0);
  Pose<double> at_p = in.pose;
  at_p.t = in.p;
  tape.toLocal(at_p, in.q, Dx, Dy, DZ);
  const An H = K::lift(in.cyl.lz);
  const An r = K::lift(in.cyl.radius);
  auto rd = [&tape](const An& v) {
    DW d;
    double e;
    tape.doubleWord(v.id, &d, &e);
    if (d.hi == 0 && d.lo == 0 && e == 0) return Rd{0, 0};
    return Rd{d.hi, (e + std::fabs(d.lo)) * (1 + 0x1p-40) + 0x1p-600};
  };
  const An A = Dx * Dx + Dy * Dy;
  const An c = x0 * Dy - y0 * Dx;
  Coefs<Rd> k;
  k.s_bot = rd(-H - Z0);
  k.s_top = rd(H - Z0);
  k.DZ = rd(DZ);
  k.dz_zero = k.DZ.v == 0 && k.DZ.e == 0;
  const Rd dx = rd(Dx), dy = rd(Dy);
  k.dxy_zero = dx.v == 0 && dx.e == 0 && dy.v == 0 && dy.e == 0;
  k.A = rd(A);
  k.b = rd(x0 * Dx + y0 * Dy);
  k.C = rd(x0 * x0 + y0 * y0 - r * r);
  k.delta = rd(r * r * A - c * c);
  return k;
}

/// Stage 1 from the coefficients in the running type N. False when a
/// bound exceeds kAccept (relative).
template <class N>
bool intervalFrom(const Coefs<N>& k, bool segment, Interval<double>* out) {
  using T = typename Run<N>::T;
  Extremum<T> lo{0, 0, true, false};
  Extremum<T> hi{0, 0, false, false};
  if (segment) {
    lo.add(0, 0);  // candidate 0
    hi.add(1, 1);  // candidate 1
  }

  // Slab. DZ exactly zero is recognised when its bound is zero too.
  if (!k.dz_zero) {
    N s_bot, s_top;  // parameters of Z = -H and Z = +H
    if (!flDiv(k.s_bot, k.DZ, &s_bot) || !flDiv(k.s_top, k.DZ, &s_top))
      return false;
    const bool up = k.DZ.v > 0;
    const N& a = up ? s_bot : s_top;
    const N& b = up ? s_top : s_bot;
    T a_lo, a_hi, b_lo, b_hi;
    ends(a, &a_lo, &a_hi);
    ends(b, &b_lo, &b_hi);
    lo.add(a_lo, a_hi);
    hi.add(b_lo, b_hi);
  }
  // Infinite cylinder. A = 0 exactly iff Dx = Dy = 0 exactly, which the
  // local frame certifies with e = 0 (toLocalRunning: every term has a zero
  // factor, so nothing rounded or underflowed). A itself is never tested for
  // a certified 0: Dy * Dy may underflow to 0, and whether its bound then
  // stays 0 would depend on the width of the type (issue 20: with long
  // double = double and no underflow allowance, Line{{1,0,0},{1,dmin,0}}
  // clipped to [-inf, +inf] instead of [0, 0]).
  if (!k.dxy_zero) {
    const N& A = k.A;
    if (!(A.v > A.e * T(kInfl))) return false;  // A > 0 not certain
    const N& b = k.b;
    const N& C = k.C;
    const N sq = flSqrt(k.delta);
    const N q = b.v >= 0 ? N(-(b + sq)) : N(sq - b);
    N r1, r2;
    if (!flDiv(q, A, &r1) || !flDiv(C, q, &r2)) return false;
    // The exact lower root is min(r1, r2), the upper max(r1, r2); both are
    // 1-Lipschitz, so enclosures of min/max come from the enclosures.
    T r1_lo, r1_hi, r2_lo, r2_hi;
    ends(r1, &r1_lo, &r1_hi);
    ends(r2, &r2_lo, &r2_hi);
    lo.add(std::min(r1_lo, r2_lo), std::min(r1_hi, r2_hi));
    hi.add(std::max(r1_lo, r2_lo), std::max(r1_hi, r2_hi));
  }
  if (!lo.any) {  // a line with R^T (q - p) = 0 exactly: a point, inside
    out->lo = -std::numeric_limits<double>::infinity();
    out->hi = std::numeric_limits<double>::infinity();
    return true;
  }
  if (!(lo.accurate(T(2 * kAccept)) && hi.accurate(T(2 * kAccept))))
    return false;
  // The exact interval is non-empty (the Boolean said so), so a crossing of
  // the two approximations is a rounding artefact of at most the bound: the
  // midpoint is then within the bound of both exact ends. Done here, where
  // both ends are finite (within max/2), and not on the double ends, which
  // may be infinite: clang if-converts such a branch and evaluates both
  // arms, and -inf/2 + inf/2 raised FE_INVALID on a valid whole-line clip
  // (issue 20). Every operation below is on finite values, so evaluating it
  // speculatively raises nothing.
  T a = lo.mid(), b = hi.mid();
  if (a > b) a = b = a / 2 + b / 2;
  out->lo = endToDouble(a);
  out->hi = endToDouble(b);
  return true;
}

// ---------------------------------------------------------------------------
// Stage 2: exact coefficients, multi-precision candidates.

size_t bitsOf(const Dyadic& d) { return mpz_sizeinbase(d.m.get_mpz_t(), 2); }

mpf_class toMpf(const Dyadic& d, mp_bitcnt_t prec) {
  mpf_class f(0, prec);
  mpf_set_z(f.get_mpf_t(), d.m.get_mpz_t());  // exact: prec >= bits of m
  if (d.e > 0)
    mpf_mul_2exp(f.get_mpf_t(), f.get_mpf_t(), mp_bitcnt_t(d.e));
  else if (d.e < 0)
    mpf_div_2exp(f.get_mpf_t(), f.get_mpf_t(), mp_bitcnt_t(-d.e));
  return f;
}

/// Truncation to double (< 1 ulp), and the infinity of the sign beyond the
/// double range (mpf_get_d's result is system dependent there).
double toDouble(const mpf_class& x) {
  if (mpf_cmp_d(x.get_mpf_t(), DBL_MAX) > 0)
    return std::numeric_limits<double>::infinity();
  if (mpf_cmp_d(x.get_mpf_t(), -DBL_MAX) < 0)
    return -std::numeric_limits<double>::infinity();
  return x.get_d();
}

Interval<double> intervalExact(const LinearInputs& in, bool segment) {
  using K = ExactKernel;
  Dyadic x0, y0, Z0, Dx, Dy, DZ;
  toLocal<K>(in.pose, in.p, 1.0, x0, y0, Z0);
  Pose<double> at_p = in.pose;
  at_p.t = in.p;
  toLocal<K>(at_p, in.q, 1.0, Dx, Dy, DZ);
  const Dyadic H = K::lift(in.cyl.lz);
  const Dyadic r = K::lift(in.cyl.radius);
  const Dyadic A = Dx * Dx + Dy * Dy;
  const Dyadic b = x0 * Dx + y0 * Dy;
  const Dyadic C = x0 * x0 + y0 * y0 - r * r;
  const Dyadic c = x0 * Dy - y0 * Dx;
  const Dyadic delta = r * r * A - c * c;
  const Dyadic nb = -H - Z0, nt = H - Z0;
  size_t bits = 64;
  for (const Dyadic* d :
       {&A, &b, &C, &delta, &nb, &nt, static_cast<const Dyadic*>(&DZ)})
    bits = std::max(bits, bitsOf(*d));
  const mp_bitcnt_t prec = mp_bitcnt_t(bits + 128);

  // A missing end (has_lo / has_hi false) is unbounded.
  mpf_class lo(0, prec), hi(1, prec);
  bool has_lo = segment, has_hi = segment;
  auto lower = [&](const mpf_class& v) {
    if (!has_lo || v > lo) lo = v;
    has_lo = true;
  };
  auto upper = [&](const mpf_class& v) {
    if (!has_hi || v < hi) hi = v;
    has_hi = true;
  };
  if (sgn(DZ.m) != 0) {
    const mpf_class dz = toMpf(DZ, prec);
    mpf_class sb(toMpf(nb, prec) / dz, prec), st(toMpf(nt, prec) / dz, prec);
    if (sgn(DZ.m) < 0) std::swap(sb, st);
    lower(sb);
    upper(st);
  }
  if (sgn(A.m) != 0 && sgn(delta.m) >= 0) {
    const mpf_class fA = toMpf(A, prec), fb = toMpf(b, prec);
    const mpf_class sq(sqrt(toMpf(delta, prec)), prec);
    const mpf_class q(
        sgn(b.m) >= 0 ? mpf_class(-(fb + sq), prec) : mpf_class(sq - fb, prec),
        prec);
    mpf_class r1(0, prec), r2(0, prec);
    if (sgn(q) != 0) {  // q = 0 iff b = 0 and Delta = 0: the double root 0
      r1 = q / fA;
      r2 = toMpf(C, prec) / q;
    }
    if (r1 > r2) std::swap(r1, r2);
    lower(r1);
    upper(r2);
  }
  constexpr double kInf = std::numeric_limits<double>::infinity();
  return {has_lo ? toDouble(lo) : -kInf, has_hi ? toDouble(hi) : kInf};
}

}  // namespace

Interval<double> linearInterval(const LinearInputs& in, bool segment) {
  Interval<double> iv{0, 1};
  const bool gate = rangeGateOk(in.max_len, in.max_unitless);
  if (!(gate &&
        (intervalFrom(coefsRunning<RunningDoubleKernel>(in), segment, &iv) ||
         intervalFrom(coefsDoubleWord(in), segment, &iv))))
    iv = intervalExact(in, segment);
  // No arithmetic on the ends here: they may be infinite (a line's), and a
  // compiler may evaluate a guarded operation speculatively. Stage 1 has
  // resolved a crossing of its ends (intervalFrom); stage 2 cannot cross
  // (truncation to double is monotone). Comparisons and min/max with an
  // infinity raise nothing.
  if (segment) {
    iv.lo = std::min(std::max(iv.lo, 0.0), 1.0);
    iv.hi = std::min(std::max(iv.hi, 0.0), 1.0);
  }
  return iv;
}

}  // namespace tricyl::detail
