// SPDX-License-Identifier: BSD-3-Clause
// Escalation per sign for the cylinder queries (sphere, segment, line):
// the policy of the stage driver for queries whose predicates are short
// closed-form polynomials in the local coordinates of a few points.
//
// A query of this kind is written once against a context C with
//   C::sign(pred)       the certified sign of pred(frame), never kUnknown
//                       from PerSign below;
//   C::cheapSign(pred)  the same, but only from the double filter (may be
//                       kUnknown): for early-outs, which the later signs
//                       decide anyway;
//   C::kEagerFilter, C::value(pred), C::verdicts(values),
//   C::resolve(pred, value)  (PerSign only) the filter's values and their
//                       verdicts without a branch, for a query that first
//                       tries its whole formula in double at once, and the
//                       certified sign from a kept value (escalated if
//                       open);
// where pred is a generic lambda from a frame (the query's local data) to
// the value of one polynomial. The query describes its frame (Q below):
//   template <class A> struct/class Frame, constructed from the query, in
//   arithmetic A (A::Num with +, -, * and absolute(); A::lift, A::local).
//
// PerSign (inside the range gate) evaluates pred in double on a frame
// computed once (FilterKernel's Fd: value and magnitude, certified by the
// a-priori bound of src/filter.h with the constant of the queries' depth,
// shallowSign); only a sign that bound leaves open is re-decided, by
// itself, in the next arithmetic, from a frame of that arithmetic computed
// when first needed (for the segment and the line, point by point), while
// the query goes on in double with the certified sign (CGAL's
// Filtered_predicate, Shewchuk's adaptive predicates: the expensive
// evaluation only for the expression that failed). No tape, no second run
// of the query. The arithmetics, in order:
//   1. for a double value that is exactly 0 (most often a true tie), the
//      double evaluation re-done with every operation checked for
//      exactness (Xd below);
//   2. double word (about 106 bits, src/eft.h): first a compensated
//      evaluation on the double-word frame (the double value and its
//      error estimate side by side, not renormalised: DwPt below),
//      certified by an a-priori bound from the filter's magnitude of the
//      same predicate; then, for what that leaves, renormalised double
//      words with the running bound of the adaptive kernel
//      (src/adaptive.cpp); with the CPU's FMA chosen at run time on x86-64
//      builds without it (the same bits either way);
//   3. exact stack expansions (src/expansion.h);
//   4. GMP dyadics (ExactKernel), where the expansions give up.
// (A double stage with a running bound between the filter and double word,
// RunningDoubleKernel, decided half of the escalated signs but cost about
// as much as the a-priori stage that decides them all: dropped.)
// Outside the range gate the query runs on GMP dyadics alone
// (KernelCtx<ExactKernel>), as in runStages (src/stages.h). KernelCtx<K>
// runs the same query code with one kernel K of src/filter.h, for
// runStages itself (the triangle's degenerate hand-off calls the segment
// query that way). tests/per_sign_test.cpp checks every stage's signs
// against GMP.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <optional>
#include <type_traits>

#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
#include <emmintrin.h>
#endif
#if (defined(__x86_64__) || defined(__i386__)) && \
    (defined(__GNUC__) || defined(__clang__)) &&  \
    !defined(TRICYL_PORTABLE_PROLOGUE)
#include <immintrin.h>
#endif

#include "adaptive.h"
#include "eft.h"
#include "expansion.h"
#include "filter.h"
#include "stages.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/types.h"

// The escalation paths are out of line (one copy of the frames' code for
// every sign of a query) but not "cold": on the near-touching families a
// third of the queries take them.
#if defined(__GNUC__) || defined(__clang__)
#define TRICYL_PER_SIGN_NOINLINE __attribute__((noinline))
#define TRICYL_PER_SIGN_INLINE inline __attribute__((always_inline))
#else
#define TRICYL_PER_SIGN_NOINLINE
#define TRICYL_PER_SIGN_INLINE inline
#endif

namespace tricyl::detail {

/// A local point (x, y, Z), Z = 2 z (the frame of the triangle kernel).
template <class N>
struct Pt {
  N x, y, Z;
};

// ---------------------------------------------------------------------------
// Double-word values with a running error bound (the rules of the adaptive
// kernel's double-word stage, derived in src/adaptive.cpp): each value
// carries a double word v and a bound e >= |v - E| on its distance to the
// exact value E, so that a product of two small values (the square of a
// nearly cancelling term: c^2 in r^2 L - c^2 for a grazing line) keeps a
// bound relative to its own size, which no a-priori bound does.
//
// TwoProduct and the double-word product with or without a fused
// multiply-add (src/eft.h, twoProdT and dwMulT): error-free either way, so
// both give the same double words, bit for bit; the choice changes the
// speed, never a value. On x86-64 built without FMA
// the FMA copy of the double-word stage is chosen at run time, as the
// adaptive kernel's (TRICYL_FMA_DISPATCH and fmaAtRunTime, src/eft.h).
#if TRICYL_FMA_DISPATCH
#define TRICYL_TARGET_FMA __attribute__((target("fma"), flatten))
#endif

template <bool kFma>
struct DwEt {
  DW v;
  double e;
};
template <bool kFma>
inline DwEt<kFma> operator+(const DwEt<kFma>& a, const DwEt<kFma>& b) {
  return {dwAdd(a.v, b.v),
          a.e + b.e + kDwAddRel * (std::fabs(a.v.hi) + std::fabs(b.v.hi))};
}
template <bool kFma>
inline DwEt<kFma> operator-(const DwEt<kFma>& a) {
  return {dwNeg(a.v), a.e};
}
template <bool kFma>
inline DwEt<kFma> operator-(const DwEt<kFma>& a, const DwEt<kFma>& b) {
  return a + (-b);
}
template <bool kFma>
inline DwEt<kFma> operator*(const DwEt<kFma>& a, const DwEt<kFma>& b) {
  const DW v = dwMulT<kFma>(a.v, b.v);
  const double ma = std::fabs(a.v.hi) + std::fabs(a.v.lo);
  const double mb = std::fabs(b.v.hi) + std::fabs(b.v.lo);
  return {v,
          ma * b.e + mb * a.e + a.e * b.e + kDwRel * std::fabs(v.hi) + kDwTiny};
}
template <bool kFma>
inline DwEt<kFma> absolute(const DwEt<kFma>& a) {
  return a.v.hi < 0 ? -a : a;
}
using DwE = DwEt<TRICYL_HAVE_FMA != 0>;

/// The certified sign of a double-word value (src/adaptive.cpp: the bound
/// inflated for its own rounding, and the absolute slack of the range
/// gate), or kUnknown.
template <bool kFma>
inline Sign dwSign(const DwEt<kFma>& d) {
  const double b = (d.e + std::fabs(d.v.lo)) * (1 + 0x1p-40) + 0x1p-600;
  if (d.v.hi > b) return Sign::kPos;
  if (d.v.hi < -b) return Sign::kNeg;
  return Sign::kUnknown;
}

// The double-word frame point in lanes (x, y, z of the point in the lanes
// of one AVX register; a spare fourth lane), for the FMA copies on x86-64:
// lane j runs exactly dwLocal's operations for coordinate j below, in its
// order, the TwoProduct by FMA (exact, as Dekker's), so the same bits as
// the scalar loop (tests/per_sign_test.cpp compares the two paths). Row k
// of R, (R_k0, R_k1, R_k2), is contiguous in Pose; the load of its fourth
// lane reads the next double of the Pose (R_{k+1,0}, or t.x for k = 2),
// whose lane is discarded.
#if (defined(__x86_64__) || defined(__i386__)) && \
    (defined(__GNUC__) || defined(__clang__)) &&  \
    !defined(TRICYL_PORTABLE_PROLOGUE) &&         \
    (TRICYL_FMA_DISPATCH || (defined(__FMA__) && defined(__AVX__)))
#define TRICYL_DW_LANES 1
#if TRICYL_FMA_DISPATCH
#define TRICYL_DW_LANES_FN __attribute__((target("fma")))
#else
#define TRICYL_DW_LANES_FN
#endif
// (GCC's and clang's vector operators on __m256d: one IEEE operation per
// lane, as written.)
TRICYL_DW_LANES_FN inline void twoSumLanes(__m256d a, __m256d b, __m256d& s,
                                           __m256d& e) {
  s = a + b;
  const __m256d bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}
template <bool kBound>
TRICYL_DW_LANES_FN inline void dwLocalLanes(const Pose<double>& pose,
                                            const Vec3<double>& origin,
                                            const Vec3<double>& p, DW v[3],
                                            double e_out[3]) {
  static_assert(sizeof(Pose<double>) == 12 * sizeof(double),
                "R's rows and t contiguous");
  const double pp[3] = {p.x, p.y, p.z};
  const double tt[3] = {origin.x, origin.y, origin.z};
  const __m256d zero = _mm256_setzero_pd();
  const __m256d abs =
      _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  __m256d P[3], e[3], q[3], m = zero;
  __m256d nonzero = _mm256_castsi256_pd(_mm256_setzero_si256());
  for (int k = 0; k < 3; ++k) {
    double Dk, lk;
    twoSum(pp[k], -tt[k], Dk, lk);
    const __m256d R = _mm256_loadu_pd(&pose.R[k][0]);
    const __m256d D = _mm256_set1_pd(Dk);
    P[k] = _mm256_mul_pd(R, D);
    e[k] = _mm256_fmsub_pd(R, D, P[k]);
    q[k] = _mm256_mul_pd(R, _mm256_set1_pd(lk));
    if constexpr (kBound) {
      m = _mm256_add_pd(m, _mm256_mul_pd(_mm256_and_pd(R, abs),
                                         _mm256_set1_pd(std::fabs(Dk))));
      // Term k is not a zero product: R_kj != 0 and D_k != 0.
      if (Dk != 0)
        nonzero = _mm256_or_pd(nonzero, _mm256_cmp_pd(R, zero, _CMP_NEQ_UQ));
    }
  }
  __m256d s1, f1, s, f2, hi, lo;
  twoSumLanes(P[0], P[1], s1, f1);
  twoSumLanes(s1, P[2], s, f2);
  const __m256d low =
      ((((f1 + f2) + (e[0] + e[1])) + e[2]) + (q[0] + q[1])) + q[2];
  twoSumLanes(s, low, hi, lo);
  alignas(32) double H[4], L[4];
  _mm256_store_pd(H, hi);
  _mm256_store_pd(L, lo);
  v[0] = {H[0], L[0]};
  v[1] = {H[1], L[1]};
  v[2] = {H[2] * 2, L[2] * 2};  // exact
  if constexpr (kBound) {
    const __m256d err = _mm256_and_pd(
        nonzero, _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(0x1p-100), m),
                               _mm256_set1_pd(kDwTiny)));
    alignas(32) double E[4];
    _mm256_store_pd(E, err);
    e_out[0] = E[0];
    e_out[1] = E[1];
    e_out[2] = E[2] * 2;
  }
}
#else
#define TRICYL_DW_LANES 0
#endif

/// The double-word local coordinates of DwArith (and DwPrioriArith, which
/// takes the values only: kBound false, no bookkeeping), Z doubled: v[j]
/// and, with kBound, its bound e[j] (derivation at DwArith::local).
/// `origin` stands for pose.t (the segment's and line's direction
/// R^T (q - p) takes p). The FMA copies on x86-64 take dwLocalLanes (the
/// same bits).
template <bool kFma, bool kBound>
inline void dwLocal(const Pose<double>& pose, const Vec3<double>& origin,
                    const Vec3<double>& p, DW v[3], double e_out[3]) {
#if TRICYL_DW_LANES
  if constexpr (kFma) {
    dwLocalLanes<kBound>(pose, origin, p, v, e_out);
    return;
  }
#endif
  const double pp[3] = {p.x, p.y, p.z};
  const double tt[3] = {origin.x, origin.y, origin.z};
  double D[3], l[3];
  for (int k = 0; k < 3; ++k) twoSum(pp[k], -tt[k], D[k], l[k]);
  for (int j = 0; j < 3; ++j) {
    double P[3], e[3], q[3], m = 0;
    bool zero = true;
    for (int k = 0; k < 3; ++k) {
      const double R = pose.R[k][j];
      twoProdT<kFma>(R, D[k], P[k], e[k]);
      q[k] = R * l[k];
      if constexpr (kBound) {
        m += std::fabs(R) * std::fabs(D[k]);
        zero = zero && (R == 0 || D[k] == 0);
      }
    }
    double s1, f1, s, f2;
    twoSum(P[0], P[1], s1, f1);
    twoSum(s1, P[2], s, f2);
    const double low =
        ((((f1 + f2) + (e[0] + e[1])) + e[2]) + (q[0] + q[1])) + q[2];
    twoSum(s, low, v[j].hi, v[j].lo);
    if constexpr (kBound) e_out[j] = zero ? 0.0 : 0x1p-100 * m + kDwTiny;
  }
  v[2] = {v[2].hi * 2, v[2].lo * 2};  // exact
  if constexpr (kBound) e_out[2] *= 2;
}

template <bool kFma>
struct DwArith {
  using Num = DwEt<kFma>;
  static constexpr bool kExact = false;
  static Num lift(double x) { return {{x, 0.0}, 0.0}; }
  /// y = R^T (p - t), Z doubled, each within e = 2^-100 M + kDwTiny of the
  /// exact value, M = sum_k |R_kj| |D_k|: (D_k, l_k) = TwoSum(p_k, -t_k),
  /// (P_k, e_k) = TwoProd(R_kj, D_k), q_k = fl(R_kj l_k), the P_k summed
  /// by two TwoSums and the low-order terms in double; an exact 0 (every
  /// term with a zero factor) has e = 0. The same sequence and bound as
  /// the adaptive kernel's (src/adaptive.cpp, Tape::dwCoord, derives it).
  static Pt<Num> local(const Pose<double>& pose, const Vec3<double>& p,
                       double rho) {
    return localFrom(pose, pose.t, p, rho);
  }
  /// The same with `origin` for pose.t: R^T (p - origin).
  static Pt<Num> localFrom(const Pose<double>& pose, const Vec3<double>& origin,
                           const Vec3<double>& p, double /*rho*/) {
    DW v[3];
    double e[3];
    dwLocal<kFma, true>(pose, origin, p, v, e);
    return {{v[0], e[0]}, {v[1], e[1]}, {v[2], e[2]}};
  }
};

// ---------------------------------------------------------------------------
// Compensated values with an a-priori bound (the double-word stage's first
// attempt). Each value is an unevaluated pair h + l: h is the predicate
// evaluated in double on the leaves' high words, l a running double
// estimate of h's error, built from the error-free transformations of each
// operation (TwoSum, TwoProduct; the compensated evaluation of Ogita, Rump
// and Oishi's Sum2/Dot2 and of Graillat, Langlois and Louvet's compensated
// Horner scheme, applied node by node to the predicate's tree):
//   x + y:  (h, t) = TwoSum(x_h, y_h),  l = fl(fl(x_l + y_l) + t);
//   x * y:  (h, t) = TwoProduct(x_h, y_h),
//           l = fl(t + fl(fl(x_h y_l) + fl(x_l y_h)))   (x_l y_l dropped);
//   -x, times4 (exact scalings of both words), |x| (the sign of fl(h + l),
//   which is the sign of h + l, so ||X| - |h + l|| <= |X - (h + l)|).
// No renormalisation: the h chain is the double evaluation's (one IEEE
// operation per node), the l chain two to three operations per node
// beside it, where a double-word operation chains six to eleven dependent
// operations (its TwoSums and the final renormalisation). The escalated
// sign's latency, not its instruction count, is what the near families
// pay (bench/results/2026-11-26-queries-3x-d.md).
//
// Bound. A sign escalated from the double filter carries the filter's
// magnitude m^ of its predicate (FilterKernel: the same expression on the
// absolute values of its leaves, each local coordinate with its one
// magnitude rho (|d_0| + |d_1| + |d_2|), computed in double). For a node
// with exact value X and magnitude M (the magnitude polynomial at the
// exact leaf magnitudes; M <= m^ (1 - u)^-(N + 3), rho >= |R_kj|) write
// |l| <= a M and |X - (h + l)| <= b M (+ the underflow term below), so
// |h| <= (1 + a + b) M. Leaves: a local coordinate is DwArith's double
// word (hi, lo) = (h, l) (dwLocal: normalised, within eta M_c + kDwTiny of
// the exact value, eta = 2^-100), so a <= u (1 + 2^-50), b = eta; r, lz
// and the sphere's radius are exact (a = b = 0). With A >= every a and u
// = 2^-53, one rounding each of the operations that build l:
//   sum:     X + Y - (h + l) = dX + dY + (x_l + y_l - s) + (s + t - l),
//            |t| <= u (|x_h| + |y_h|):
//            a_z <= max(a_x, a_y) + u (1 + 3A) (1 + 3u),
//            b_z <= max(b_x, b_y) + u A (1 + u) + u a_z;
//   product: X Y - (h + l) = X dY + dX (y_h + y_l) + x_l y_l
//            + (x_h y_l + x_l y_h - s) + (t + s - l), |t| <= u |x_h y_h|:
//            a_z <= a_x + a_y + u + 3 A^2 + 9 u A,
//            b_z <= b_x + b_y + b_x b_y + a_x a_y + 6 u A + 2 u^2.
// So a node's a is at most u (1 + 2^-30) times the number n of operations
// and coordinate leaves in its subtree, and for a predicate with N
// operations and K local coordinates among its leaves (with
// multiplicity, as written: N = 45 and K = 10 for the sphere's
// 16 r^2 G - T^2, N = 23 and K = 18 for the cap crossing; n = N + K <= 55),
// summing the increments over the tree: b <= K eta + sum over products of
// a_x a_y (each pair of the n operations and leaves meets at most at one
// product: <= n^2 / 2 u^2 = 1513 u^2) + N (6 * 55 + 2) u^2 (<= 14940 u^2):
// b <= 18 * 2^-100 + 16453 u^2 < 2^-91.9, and b M < 0x1.2p-92 m^
// (2^-91.83; tests/per_sign_test.cpp checks the error against it).
// Underflow: the t of a product and the roundings of l lose at most
// 2^-1074 absolutely each when subnormal (the double filter's kDwTiny per
// operation, amplified by at most the predicate's magnitude under the
// range gate: below 2^-600, the same allowance as before). So the sign of
// X is certain where |fl(h + l)| > 2^-90 m^ + 2^-600 (dwPrioriSign; the
// 2^-90 leaves a factor 3.4 over the bound, which the few roundings of the
// test need only to the extent of a few u). It decides
// every sign whose value is not below about 2^-90 of its magnitude: an
// offset of one ulp (2^-52 relative) is far inside it, and the double
// filter's pessimism after a cancellation (a line given by two points far
// from the cylinder) does not matter at this precision. What it leaves
// (true ties, second-order values) goes to the running bound (DwEt), then
// expansions. kFma: the TwoProduct by FMA or by Dekker's splits, exact
// either way, so the same pairs (tests/per_sign_test.cpp compares them).
template <bool kFma>
struct DwPt {
  double h, l;
};
template <bool kFma>
inline DwPt<kFma> operator+(const DwPt<kFma>& a, const DwPt<kFma>& b) {
  DwPt<kFma> z;
  double t;
  twoSum(a.h, b.h, z.h, t);
  z.l = (a.l + b.l) + t;
  return z;
}
template <bool kFma>
inline DwPt<kFma> operator-(const DwPt<kFma>& a) {
  return {-a.h, -a.l};
}
template <bool kFma>
inline DwPt<kFma> operator-(const DwPt<kFma>& a, const DwPt<kFma>& b) {
  return a + (-b);
}
template <bool kFma>
inline DwPt<kFma> operator*(const DwPt<kFma>& a, const DwPt<kFma>& b) {
  DwPt<kFma> z;
  double t;
  twoProdT<kFma>(a.h, b.h, z.h, t);
  z.l = t + (a.h * b.l + a.l * b.h);
  return z;
}
template <bool kFma>
inline DwPt<kFma> absolute(const DwPt<kFma>& a) {
  return a.h + a.l < 0 ? -a : a;
}
/// 4 x (times4 of src/cylinder_queries_impl.h, (x + x) + (x + x)): both
/// words scaled by 4, exact (no overflow under the range gate; a subnormal
/// low word scales exactly), the exact value and magnitude scaled by 4: the
/// invariants above hold with the same a and b, and no error term is added
/// where the count above charges two additions.
template <bool kFma>
inline DwPt<kFma> times4(const DwPt<kFma>& a) {
  return {a.h * 4, a.l * 4};
}
/// The certified sign of an a-priori compensated value whose predicate has
/// the double filter's magnitude m (see above), or kUnknown: the sign of
/// s = fl(h + l) where |s| > b = fl(fl(m 2^-90) + 2^-600). Then |h + l| >=
/// |s| / (1 + u) > (2^-90 m + 2^-600)(1 - 3u), more than |X - (h + l)|
/// (< 0x1.2p-92 m plus the underflow allowance), so X has s's sign. (Not
/// |h| > b + |l|: h is the double evaluation, whose error l is often larger
/// than a near-tie's value; h + l is accurate to about 2^-92 of m.)
template <bool kFma>
inline Sign dwPrioriSign(const DwPt<kFma>& d, double m) {
  const double b = m * 0x1p-90 + 0x1p-600;
  const double s = d.h + d.l;
  if (s > b) return Sign::kPos;
  if (s < -b) return Sign::kNeg;
  return Sign::kUnknown;
}
template <bool kFma>
struct DwPrioriArith {
  using Num = DwPt<kFma>;
  static constexpr bool kExact = false;
  static Num lift(double x) { return {x, 0.0}; }
  /// DwArith's double words as leaves (h, l) = (hi, lo) (its bound is the
  /// eta above; not computed here).
  static Pt<Num> local(const Pose<double>& pose, const Vec3<double>& p,
                       double rho) {
    return localFrom(pose, pose.t, p, rho);
  }
  static Pt<Num> localFrom(const Pose<double>& pose, const Vec3<double>& origin,
                           const Vec3<double>& p, double /*rho*/) {
    DW v[3];
    dwLocal<kFma, false>(pose, origin, p, v, nullptr);
    return {{v[0].hi, v[0].lo}, {v[1].hi, v[1].lo}, {v[2].hi, v[2].lo}};
  }
};

// ---------------------------------------------------------------------------
// Exact in double? For a sign whose double value is exactly 0 (almost
// always a true tie: exact data in an exact pose), the double evaluation
// is re-done with every operation checked: a sum by its TwoSum error being
// 0, a product by its TwoProduct error being 0 with the product at least
// kProdExactMin (so that the error term is itself exact, src/eft.h), or by
// an exact 0 factor. If every operation was exact, the double value is the
// exact value (the adaptive kernel's exactInDouble, src/adaptive.cpp, does
// the same on its tape).
// kFma: the TwoProduct by a fused multiply-add (the FMA copy, chosen at run
// time as the double word's, TRICYL_FMA_DISPATCH) or by Dekker's splits:
// exact either way, so the same values and the same verdicts.
template <bool kFma>
struct XdT {
  double v;
  bool exact;
};
using Xd = XdT<TRICYL_HAVE_FMA != 0>;
template <bool kFma>
inline XdT<kFma> operator+(const XdT<kFma>& a, const XdT<kFma>& b) {
  double s, e;
  twoSum(a.v, b.v, s, e);
  return {s, a.exact && b.exact && e == 0 && std::isfinite(s)};
}
template <bool kFma>
inline XdT<kFma> operator-(const XdT<kFma>& a) {
  return {-a.v, a.exact};
}
template <bool kFma>
inline XdT<kFma> operator-(const XdT<kFma>& a, const XdT<kFma>& b) {
  return a + (-b);
}
template <bool kFma>
inline XdT<kFma> operator*(const XdT<kFma>& a, const XdT<kFma>& b) {
  if ((a.exact && a.v == 0) || (b.exact && b.v == 0)) return {0.0, true};
  double p, e;
  twoProdT<kFma>(a.v, b.v, p, e);
  return {p, a.exact && b.exact && e == 0 && std::fabs(p) >= kProdExactMin &&
                 std::isfinite(p)};
}

template <bool kFma>
struct ExactDoubleArithT {
  using Num = XdT<kFma>;
  static constexpr bool kExact = false;
  static Num lift(double x) { return {x, true}; }
  static Pt<Num> local(const Pose<double>& pose, const Vec3<double>& p,
                       double rho) {
    return localFrom(pose, pose.t, p, rho);
  }
  static Pt<Num> localFrom(const Pose<double>& pose, const Vec3<double>& origin,
                           const Vec3<double>& p, double /*rho*/) {
    const Num d[3] = {Num{p.x, true} - Num{origin.x, true},
                      Num{p.y, true} - Num{origin.y, true},
                      Num{p.z, true} - Num{origin.z, true}};
    Num out[3];
    for (int j = 0; j < 3; ++j)
      out[j] =
          (Num{pose.R[0][j], true} * d[0] + Num{pose.R[1][j], true} * d[1]) +
          Num{pose.R[2][j], true} * d[2];
    return {out[0], out[1], out[2] + out[2]};
  }
};
using ExactDoubleArith = ExactDoubleArithT<TRICYL_HAVE_FMA != 0>;

// ---------------------------------------------------------------------------
// Stage 2: exact stack expansions; stage 3: GMP.

struct ExpansionArith {
  using Num = Expansion;
  static constexpr bool kExact = true;
  static Num lift(double x) { return Expansion(x); }
  static Pt<Num> local(const Pose<double>& pose, const Vec3<double>& p,
                       double /*rho*/) {
    const double pp[3] = {p.x, p.y, p.z};
    const double tt[3] = {pose.t.x, pose.t.y, pose.t.z};
    Expansion d[3];
    for (int k = 0; k < 3; ++k) d[k] = Expansion::difference(pp[k], tt[k]);
    Expansion out[3];
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        out[j] = out[j] + Expansion(pose.R[k][j]) * d[k];
    return {out[0], out[1], out[2] + out[2]};
  }
};

/// |x| in each arithmetic: no rounding, the same error bound and magnitude
/// (||a| - |b|| <= |a - b|).
inline Fd absolute(const Fd& a) { return {std::fabs(a.v), a.m}; }
inline Rd absolute(const Rd& a) { return {std::fabs(a.v), a.e}; }
template <bool kFma>
inline XdT<kFma> absolute(const XdT<kFma>& a) {
  return {std::fabs(a.v), a.exact};
}
inline Expansion absolute(const Expansion& a) { return a.sign() < 0 ? -a : a; }
inline Dyadic absolute(const Dyadic& a) { return sgn(a.m) < 0 ? -a : a; }

/// The arithmetic of a kernel K of src/filter.h (its own toLocal).
template <class K>
struct KernelArith {
  using Num = typename K::Num;
  static constexpr bool kExact = K::kExact;
  static Num lift(double x) { return K::lift(x); }
  static Pt<Num> local(const Pose<double>& pose, const Vec3<double>& p,
                       double rho) {
    Pt<Num> q;
    toLocal<K>(pose, p, rho, q.x, q.y, q.Z);
    return q;
  }
};

/// The double filter's arithmetic for PerSign: FilterKernel's Fd (value
/// and magnitude) with both lanes in one SSE2 register, so that every
/// operation is one instruction on the pair (a difference: the value lane
/// plus the negated other, which IEEE defines as the same operation) and a
/// value takes one register instead of two. The same IEEE operations lane
/// by lane as Fd's, so the same bits (portable builds use Fd itself).
#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
struct Fp {
  __m128d x;  // lane 0: value, lane 1: magnitude
};
inline __m128d negValueLane() { return _mm_set_pd(0.0, -0.0); }
inline Fp operator+(const Fp& a, const Fp& b) { return {_mm_add_pd(a.x, b.x)}; }
inline Fp operator-(const Fp& a) { return {_mm_xor_pd(a.x, negValueLane())}; }
inline Fp operator-(const Fp& a, const Fp& b) {
  return {_mm_add_pd(a.x, _mm_xor_pd(b.x, negValueLane()))};
}
inline Fp operator*(const Fp& a, const Fp& b) { return {_mm_mul_pd(a.x, b.x)}; }
inline Fp absolute(const Fp& a) {
  return {_mm_andnot_pd(_mm_set_pd(0.0, -0.0), a.x)};
}
inline Fp toFp(const Fd& a) { return {_mm_set_pd(a.m, a.v)}; }
inline Fd toFd(const Fp& a) {
  return {_mm_cvtsd_f64(a.x), _mm_cvtsd_f64(_mm_unpackhi_pd(a.x, a.x))};
}
#else
using Fp = Fd;
inline Fp toFp(const Fd& a) { return a; }
inline Fd toFd(const Fp& a) { return a; }
#endif
struct PairFilterArith {
  using Num = Fp;
  static constexpr bool kExact = false;
  static Num lift(double x) { return toFp(FilterKernel::lift(x)); }
  static Pt<Num> local(const Pose<double>& pose, const Vec3<double>& p,
                       double rho) {
    return localFrom(pose, pose.t, p, rho);
  }
  /// FilterKernel's frame (toLocal<FilterKernel>, src/triangle_cylinder_impl.h:
  /// the same IEEE operations in the same order, so the same values and
  /// magnitudes) with `origin` for pose.t: x and y in the two lanes of one
  /// SSE2 register (R's rows hold (R_k0, R_k1) side by side).
  static Pt<Num> localFrom(const Pose<double>& pose, const Vec3<double>& origin,
                           const Vec3<double>& p, double rho) {
    const double d0 = p.x - origin.x;
    const double d1 = p.y - origin.y;
    const double d2 = p.z - origin.z;
    const auto& R = pose.R;
    const double m = rho * (std::fabs(d0) + std::fabs(d1) + std::fabs(d2));
    const double z = R[0][2] * d0 + R[1][2] * d1 + R[2][2] * d2;
#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
    const __m128d xy = _mm_add_pd(
        _mm_add_pd(_mm_mul_pd(_mm_loadu_pd(&R[0][0]), _mm_set1_pd(d0)),
                   _mm_mul_pd(_mm_loadu_pd(&R[1][0]), _mm_set1_pd(d1))),
        _mm_mul_pd(_mm_loadu_pd(&R[2][0]), _mm_set1_pd(d2)));
    const __m128d mm = _mm_set1_pd(m);
    return {{_mm_unpacklo_pd(xy, mm)},
            {_mm_unpackhi_pd(xy, mm)},
            {_mm_set_pd(m + m, z + z)}};
#else
    return {{R[0][0] * d0 + R[1][0] * d1 + R[2][0] * d2, m},
            {R[0][1] * d0 + R[1][1] * d1 + R[2][1] * d2, m},
            {z + z, m + m}};
#endif
  }
};

/// Kleene's and/or on {certainly true, certainly false} pairs, without
/// branches.
struct KBool {
  bool t, f;
};
inline KBool kbAnd(KBool a, KBool b) {
  return {bool(a.t & b.t), bool(a.f | b.f)};
}
inline KBool kbOr(KBool a, KBool b) {
  return {bool(a.t | b.t), bool(a.f & b.f)};
}
/// The filter's verdicts on a set of values, one bit per value: pos
/// (certainly > 0), neg (certainly < 0); neither: open. A certified sign is
/// never zero, so "> 0" and ">= 0" have the same certificate, and so have
/// "< 0" and "<= 0".
struct Verdicts {
  unsigned pos, neg;
  /// Every value in `nonneg` >= 0 and every value in `nonpos` <= 0 (bit
  /// masks of the values' indices).
  KBool all(unsigned nonneg, unsigned nonpos) const {
    return {(pos & nonneg) == nonneg && (neg & nonpos) == nonpos,
            ((neg & nonneg) | (pos & nonpos)) != 0};
  }
  /// Bit k of pos / neg (0 or 1; unsigned, for bitwise Kleene logic).
  unsigned isPos(int k) const { return (pos >> k) & 1u; }
  unsigned isNeg(int k) const { return (neg >> k) & 1u; }
};
/// The bit of value k.
constexpr unsigned bit(int k) { return 1u << k; }

/// One conjunction of filter verdicts: every value in `nonneg` >= 0 and
/// every value in `nonpos` <= 0 (bit masks of the values' indices, as in
/// Verdicts::all).
struct Conj {
  unsigned nonneg, nonpos;
};
/// A formula in disjunctive normal form over a query's filter values: up to
/// 8 conjunctions of values 0..14, as 16-bit lanes (lane i: conjunction i;
/// the unused lanes require bit 15, which no value has, and are masked out
/// of the "false" test). Built at compile time (makeDnf).
struct Dnf {
  alignas(16) unsigned short nonneg[8];
  alignas(16) unsigned short nonpos[8];
  unsigned used;  ///< bit i: lane i is a conjunction
};
template <std::size_t n>
constexpr Dnf makeDnf(const Conj (&c)[n]) {
  static_assert(n >= 1 && n <= 8, "one 16-bit lane per conjunction");
  Dnf f{{}, {}, (1u << n) - 1};
  for (std::size_t i = 0; i < 8; ++i) {
    const bool in = i < n;
    // Values 0..14 only (bit 15 marks the unused lanes); a constant
    // expression fails to compile here otherwise.
    if (in && ((c[i].nonneg | c[i].nonpos) >> 15) != 0) throw "value > 14";
    f.nonneg[i] = static_cast<unsigned short>(in ? c[i].nonneg : 0x8000u);
    f.nonpos[i] = static_cast<unsigned short>(in ? c[i].nonpos : 0x8000u);
  }
  return f;
}
/// Each conjunction of a Dnf under the filter's verdicts: bit i of t, it is
/// certainly true (every value in it certified on its side); bit i of f,
/// certainly false (a value in it certified on the wrong side).
struct DnfVerdicts {
  unsigned t, f, used;
  /// Kleene's OR of the conjunctions: certainly true if one is, certainly
  /// false if all are (the same as kbOr over Verdicts::all of each).
  KBool any() const { return {t != 0, (f & used) == used}; }
  /// Kleene's OR of the conjunctions in `mask` is certainly false.
  bool allFalse(unsigned mask) const { return (f & mask) == mask; }
};
/// All conjunctions at once, without a branch: a handful of SSE2
/// operations on the eight lanes (scalar loop in portable builds; the same
/// bits either way).
inline DnfVerdicts evalDnf(const Verdicts& d, const Dnf& form) {
#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
  const __m128i nn =
      _mm_load_si128(reinterpret_cast<const __m128i*>(form.nonneg));
  const __m128i np =
      _mm_load_si128(reinterpret_cast<const __m128i*>(form.nonpos));
  const __m128i pos = _mm_set1_epi16(static_cast<short>(d.pos));
  const __m128i neg = _mm_set1_epi16(static_cast<short>(d.neg));
  const __m128i zero = _mm_setzero_si128();
  // Certainly true: no required value lacks its certificate.
  const __m128i miss =
      _mm_or_si128(_mm_andnot_si128(pos, nn), _mm_andnot_si128(neg, np));
  // Certainly false: some value certified on the wrong side.
  const __m128i hit =
      _mm_or_si128(_mm_and_si128(neg, nn), _mm_and_si128(pos, np));
  const __m128i t_words = _mm_cmpeq_epi16(miss, zero);
  const __m128i open_words = _mm_cmpeq_epi16(hit, zero);
  const unsigned t =
      unsigned(_mm_movemask_epi8(_mm_packs_epi16(t_words, zero)));
  const unsigned open =
      unsigned(_mm_movemask_epi8(_mm_packs_epi16(open_words, zero)));
  return {t, ~open & 0xffu, form.used};
#else
  unsigned t = 0, f = 0;
  for (unsigned i = 0; i < 8; ++i) {
    const unsigned nn = form.nonneg[i], np = form.nonpos[i];
    t |= unsigned(((~d.pos & nn) | (~d.neg & np)) == 0) << i;
    f |= unsigned(((d.neg & nn) | (d.pos & np)) != 0) << i;
  }
  return {t, f, form.used};
#endif
}

/// One kernel K for every sign (runStages' stages; outside the range gate,
/// K = ExactKernel).
template <class K, class Q>
class KernelCtx {
 public:
  explicit KernelCtx(const Q& q) : f_(q) {}
  template <class P>
  Sign sign(const P& pred) const {
    return K::sign(pred(f_));
  }
  template <class P>
  Sign cheapSign(const P& pred) const {
    return K::sign(pred(f_));
  }
  static constexpr bool kEagerFilter = false;

 private:
  typename Q::template Frame<KernelArith<K>> f_;
};

/// FilterKernel::sign (src/filter.h) for the shallow predicates of the
/// cylinder queries. Its bound |v - E| <= D u / ((1 - D u)(1 - u)^D) m holds
/// for any depth D (the longest chain of operations from an input); the
/// filter's 2^-47 covers D <= 56, and every predicate of the sphere, the
/// segment and the line has D <= 12 (counted in src/cylinder_queries_impl.h),
/// for which the factor is below 13 u < 2^-49. Four times tighter, at no
/// cost: the same Fd values, another constant. The absolute slack is the
/// filter's (underflow under the range gate).
inline Sign shallowSign(const Fd& a) {
  const double bound = a.m * 0x1p-49 + FilterKernel::kAbs;
  if (a.v > bound) return Sign::kPos;
  if (a.v < -bound) return Sign::kNeg;
  return Sign::kUnknown;
}

/// Inside the range gate: double, then each open sign by itself in
/// double-word, expansions, GMP.
template <class Q>
class PerSign {
 public:
  explicit PerSign(const Q& q) : q_(q), fd_(q) {}
  PerSign(const PerSign&) = delete;
  PerSign& operator=(const PerSign&) = delete;

  template <class P>
  Sign sign(const P& pred) {
    const Fd v = toFd(pred(fd_));
    const Sign s = shallowSign(v);
    if (s != Sign::kUnknown) return s;
    return escalate(pred, v);
  }
  template <class P>
  Sign cheapSign(const P& pred) const {
    return shallowSign(toFd(pred(fd_)));
  }
  /// The filter's verdict on pred without a branch: {certainly > 0,
  /// certainly < 0} (shallowSign's test; both false: open).
  static constexpr bool kEagerFilter = true;
  /// The filter's value of pred (value and magnitude), for a query that
  /// keeps it: verdicts reads the filter's verdicts on a set of them at
  /// once, resolve the certified sign of one (escalated only if the filter
  /// left it open), with no second evaluation in double.
  template <class P>
  Fp value(const P& pred) const {
    return pred(fd_);
  }
  template <std::size_t n>
  static Verdicts verdicts(const Fp (&v)[n]) {
    static_assert(n <= 32, "one bit per value");
    Verdicts out{0, 0};
    std::size_t i = 0;
#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
    // Two values per operation: shallowSign's bound m 2^-49 + kAbs and its
    // two comparisons, lane by lane the same IEEE operations.
    const __m128d k = _mm_set1_pd(0x1p-49), a = _mm_set1_pd(FilterKernel::kAbs);
    for (; i + 1 < n; i += 2) {
      const __m128d vals = _mm_unpacklo_pd(v[i].x, v[i + 1].x);
      const __m128d mags = _mm_unpackhi_pd(v[i].x, v[i + 1].x);
      const __m128d b = _mm_add_pd(_mm_mul_pd(mags, k), a);
      out.pos |= unsigned(_mm_movemask_pd(_mm_cmpgt_pd(vals, b))) << i;
      out.neg |= unsigned(_mm_movemask_pd(
                     _mm_cmplt_pd(vals, _mm_xor_pd(b, _mm_set1_pd(-0.0)))))
                 << i;
    }
    if constexpr (n % 2 == 1) {  // the last value paired with itself
      const __m128d vals = _mm_unpacklo_pd(v[i].x, v[i].x);
      const __m128d mags = _mm_unpackhi_pd(v[i].x, v[i].x);
      const __m128d b = _mm_add_pd(_mm_mul_pd(mags, k), a);
      out.pos |= unsigned(_mm_movemask_pd(_mm_cmpgt_pd(vals, b)) & 1) << i;
      out.neg |= unsigned(_mm_movemask_pd(_mm_cmplt_pd(
                              vals, _mm_xor_pd(b, _mm_set1_pd(-0.0)))) &
                          1)
                 << i;
      ++i;
    }
#endif
    for (; i < n; ++i) {
      const Fd d = toFd(v[i]);
      const double b = d.m * 0x1p-49 + FilterKernel::kAbs;
      out.pos |= unsigned(d.v > b) << i;
      out.neg |= unsigned(d.v < -b) << i;
    }
    return out;
  }
  template <class P>
  Sign resolve(const P& pred, const Fp& value) {
    const Fd v = toFd(value);
    const Sign s = shallowSign(v);
    if (s != Sign::kUnknown) return s;
    return escalate(pred, v);
  }
  /// resolve for a sign whose a-priori stage is known to fail (a
  /// square of a term that cancels far below its magnitude: the a-priori
  /// bound is relative to the magnitude squared): the same stages without
  /// that one. Only the order of stages changes, never a sign.
  template <class P>
  Sign resolveRunning(const P& pred, const Fp& value) {
    const Fd v = toFd(value);
    const Sign s = shallowSign(v);
    if (s != Sign::kUnknown) return s;
    return escalate<false>(pred, v);
  }
  /// The strongest arithmetic any sign needed: 0 double, 1 double-word,
  /// 2 expansions, 3 GMP.
  int level() const { return level_; }

  /// A query's open answer (what its double test left open), run as
  /// open(ctx) with an OpenCtx: the same resolve, value and resolveRunning,
  /// but the compensated frame (DwPrioriArith) is built once on entry
  /// (kEager: every point at once, Q::EagerFrame; otherwise each point when
  /// first read) and a sign the filter leaves open is evaluated on it in
  /// line, the later stages (escalate) called only where that fails. One
  /// copy compiled for FMA (chosen at run time, as the double-word stage's)
  /// and one without: the same signs from the same stages as resolve's,
  /// without a call, a check of the frame and a check of the CPU per sign.
  template <bool kEager, class Open>
  Tri runOpen(const Open& open) {
#if TRICYL_FMA_DISPATCH
    if (fmaAtRunTime()) return runOpenFma<kEager>(open);
    return runOpenWith<false, kEager>(open);
#else
    return runOpenWith<TRICYL_HAVE_FMA != 0, kEager>(open);
#endif
  }

  template <bool kFma, bool kEager>
  class OpenCtx {
   public:
    static constexpr bool kEagerFilter = true;
    explicit OpenCtx(PerSign& p) : p_(p), f_(p.q_) {}
    template <class P>
    Fp value(const P& pred) const {
      return p_.value(pred);
    }
    template <class P>
    Sign resolve(const P& pred, const Fp& value) {
      const Fd v = toFd(value);
      const Sign s = shallowSign(v);
      if (s != Sign::kUnknown) return s;
      // escalate's order: an exact 0 first to the exact-in-double test,
      // then the a-priori compensated stage (here, on this frame), then the
      // stages after it.
      if (v.v == 0) {
        const Sign sx = p_.exactZero(pred);
        if (sx != Sign::kUnknown) return sx;
      }
      if (p_.level_ < 1) p_.level_ = 1;
      const Sign sp = dwPrioriSign(pred(f_), v.m);
      if (sp != Sign::kUnknown) return sp;
      return p_.template escalate<false, false>(pred, v);
    }
    template <class P>
    Sign resolveRunning(const P& pred, const Fp& value) {
      return p_.resolveRunning(pred, value);
    }

   private:
    PerSign& p_;
    std::conditional_t<kEager,
                       typename Q::template EagerFrame<DwPrioriArith<kFma>>,
                       typename Q::template Frame<DwPrioriArith<kFma>>>
        f_;
  };

 private:
  template <bool kFma, bool kEager, class Open>
  TRICYL_PER_SIGN_NOINLINE Tri runOpenWith(const Open& open) {
    OpenCtx<kFma, kEager> ctx(*this);
    return open(ctx);
  }
#if TRICYL_FMA_DISPATCH
  template <bool kEager, class Open>
  TRICYL_TARGET_FMA TRICYL_PER_SIGN_NOINLINE Tri runOpenFma(const Open& open) {
    OpenCtx<true, kEager> ctx(*this);
    return open(ctx);
  }
#endif

  template <class A>
  using Frame = typename Q::template Frame<A>;

  /// escalate's first step for an exact 0 (out of line: the exact-in-double
  /// frame is large).
  template <class P>
  TRICYL_PER_SIGN_NOINLINE Sign exactZero(const P& pred) {
#if TRICYL_FMA_DISPATCH
    const Sign s =
        fmaAtRunTime() ? exactInDoubleFma(pred) : exactInDouble(pred, xd_);
#else
    const Sign s = exactInDouble(pred, xd_);
#endif
    if (s != Sign::kUnknown && level_ < 2) level_ = 2;
    return s;
  }
  /// kExactZero: try the exact-in-double test on an exact 0 (false: the
  /// caller has, OpenCtx::resolve); kPriori: the a-priori compensated stage.
  template <bool kPriori = true, bool kExactZero = true, class P>
  TRICYL_PER_SIGN_NOINLINE Sign escalate(const P& pred, const Fd& v) {
    Sign s = Sign::kUnknown;
    if (kExactZero && v.v == 0) {
      // A double value that is exactly 0 is most often a true tie (exact
      // data in an exact pose), which no bound certifies: was the double
      // evaluation exact?
#if TRICYL_FMA_DISPATCH
      s = fmaAtRunTime() ? exactInDoubleFma(pred) : exactInDouble(pred, xd_);
#else
      s = exactInDouble(pred, xd_);
#endif
      if (s != Sign::kUnknown) {
        if (level_ < 2) level_ = 2;
        return s;
      }
    }
    // Double word: first the compensated evaluation with the a-priori
    // bound from the filter's magnitude (it decides nearly every sign that
    // is not a tie: about 2^-90 of the magnitude against the filter's
    // 2^-49), then renormalised double words with the running bound.
    if (level_ < 1) level_ = 1;
    if constexpr (kPriori) {
#if TRICYL_FMA_DISPATCH
      s = fmaAtRunTime() ? dwPrioriSignFma(pred, v.m)
                         : dwPrioriSignWith<false>(pred, v.m, dwp_);
#else
      s = dwPrioriSignWith<TRICYL_HAVE_FMA != 0>(pred, v.m, dwp_);
#endif
      if (s != Sign::kUnknown) return s;
    }
#if TRICYL_FMA_DISPATCH
    s = fmaAtRunTime() ? dwSignFma(pred) : dwSignWith<false>(pred, dw_);
#else
    s = dwSignWith<TRICYL_HAVE_FMA != 0>(pred, dw_);
#endif
    if (s != Sign::kUnknown) return s;
    if (!ex_) build(ex_);
    const Expansion x = pred(*ex_);
    if (x.ok()) {
      if (level_ < 2) level_ = 2;
      s = Sign(x.sign());
      return s;
    }
    if (!gmp_) build(gmp_);
    level_ = 3;
    return ExactKernel::sign(pred(*gmp_));
  }

  /// The exact sign of pred if its double evaluation, every operation
  /// checked, was exact (with FMA or not), else kUnknown; on a frame built
  /// when first needed.
  template <bool kFma, class P>
  static Sign exactInDoubleSign(const XdT<kFma>& x) {
    if (!x.exact) return Sign::kUnknown;
    return x.v > 0 ? Sign::kPos : (x.v < 0 ? Sign::kNeg : Sign::kZero);
  }
  template <class P>
  Sign exactInDouble(const P& pred,
                     std::optional<Frame<ExactDoubleArith>>& frame) {
    if (!frame) build(frame);
    return exactInDoubleSign<TRICYL_HAVE_FMA != 0, P>(pred(*frame));
  }
#if TRICYL_FMA_DISPATCH
  template <class P>
  TRICYL_TARGET_FMA Sign exactInDoubleFma(const P& pred) {
    if (!xdf_) buildXdFma();
    return exactInDoubleSign<true, P>(pred(*xdf_));
  }
  TRICYL_TARGET_FMA TRICYL_PER_SIGN_NOINLINE void buildXdFma() {
    xdf_.emplace(q_);
  }
  std::optional<Frame<ExactDoubleArithT<true>>> xdf_;
#endif
  /// The compensated stage with the a-priori bound (with FMA or not), on a
  /// frame built when first needed; m: the filter's magnitude of pred.
  template <bool kFma, class P>
  Sign dwPrioriSignWith(const P& pred, double m,
                        std::optional<Frame<DwPrioriArith<kFma>>>& frame) {
    if (!frame) build(frame);
    return dwPrioriSign(pred(*frame), m);
  }
#if TRICYL_FMA_DISPATCH
  template <class P>
  TRICYL_TARGET_FMA Sign dwPrioriSignFma(const P& pred, double m) {
    if (!dwpf_) buildPrioriFma();
    return dwPrioriSign(pred(*dwpf_), m);
  }
  TRICYL_TARGET_FMA TRICYL_PER_SIGN_NOINLINE void buildPrioriFma() {
    dwpf_.emplace(q_);
  }
  std::optional<Frame<DwPrioriArith<true>>> dwpf_;
#endif
  /// The double-word stage (with FMA or not), on a frame built when first
  /// needed.
  template <bool kFma, class P>
  Sign dwSignWith(const P& pred, std::optional<Frame<DwArith<kFma>>>& frame) {
    if (!frame) build(frame);
    return dwSign(pred(*frame));
  }
#if TRICYL_FMA_DISPATCH
  /// The same, compiled for a CPU with FMA (everything it calls inlined,
  /// so that __builtin_fma is one instruction).
  template <class P>
  TRICYL_TARGET_FMA Sign dwSignFma(const P& pred) {
    if (!dwf_) buildFma();
    return dwSign(pred(*dwf_));
  }
  TRICYL_TARGET_FMA TRICYL_PER_SIGN_NOINLINE void buildFma() {
    dwf_.emplace(q_);
  }
  std::optional<Frame<DwArith<true>>> dwf_;
#endif

  // The frames of the later stages, built when a sign first needs them;
  // one copy of the code for all the query's signs.
  template <class F>
  TRICYL_PER_SIGN_NOINLINE void build(std::optional<F>& frame) {
    frame.emplace(q_);
  }

  const Q& q_;
  Frame<PairFilterArith> fd_;
  int level_ = 0;
  std::optional<Frame<DwArith<TRICYL_HAVE_FMA != 0>>> dw_;
  std::optional<Frame<DwPrioriArith<TRICYL_HAVE_FMA != 0>>> dwp_;
  std::optional<Frame<ExactDoubleArith>> xd_;
  std::optional<Frame<ExpansionArith>> ex_;
  std::optional<Frame<KernelArith<ExactKernel>>> gmp_;
};

/// The driver's per-sign policy (runStages' counterpart, src/stages.h):
/// inside the range gate one run of `query(ctx, &early)` with PerSign,
/// which always decides; outside it one run on GMP dyadics.
/// Outside the range gate: one run on GMP dyadics (out of line, so that
/// the common path below stays small enough to inline).
template <class Q, class Query>
TRICYL_PER_SIGN_NOINLINE Decision runGmp(const Q& q, const Query& query) {
  bool early = false;
  KernelCtx<ExactKernel, Q> ctx(q);
  return {toAnswer(query(ctx, &early)), Stage::kExactGmp};
}
template <class Q, class Query>
TRICYL_PER_SIGN_INLINE Decision runPerSign(const Q& q, bool gate,
                                           const Query& query) {
  if (!gate) return runGmp(q, query);
  bool early = false;
  PerSign<Q> ctx(q);
  const Tri t = query(ctx, &early);
  // Never kUnknown: every sign of PerSign is decided.
  const int level = ctx.level();
  if (level == 0)
    return {toAnswer(t), early ? Stage::kEarlyOut : Stage::kFastPath};
  return {toAnswer(t), stageOfLevel(level)};
}

}  // namespace tricyl::detail
