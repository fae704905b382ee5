// SPDX-License-Identifier: BSD-3-Clause
// The kernel that tracks exact values (a K of src/filter.h): the
// straight-line double-word stage (DwKernel); no tape.
//
// Where the double filter leaves some tests of a query undecided, the query
// re-runs THOSE TESTS (its predicates, not the whole query) with DwKernel:
// every value is a double word (about 106 bits, src/eft.h) with a bound on
// its distance to the exact value, each operation computed as it comes, in
// the order the query's code gives. A sign the bound certifies is final; a
// sign it cannot certify (a true tie, or within about 2^-100 of one
// relative to the operands) comes back kUnknown and leaves its test to the
// tape's exact stage (src/adaptive.h), which re-decides only the signs that
// failed. This costs a few times a double evaluation of the same tests and
// none of the tape's bookkeeping (a node store per operation in double,
// then an interpreted walk of the failing sign's sub-DAG).
//
// Exact values. A value whose bound is 0 is an EXACT DOUBLE: v.lo = 0 and
// v.hi is the exact value of the expression. Inputs are; a sum or a product
// of two exact doubles is exact through TwoSum or TwoProduct (the latter
// when no underflow can touch its error term: |p| >= kProdExactMin, or a
// zero factor), and stays an exact double when its low part is 0. Exact
// poses with exact data (signed permutations, dyadic coordinates: the
// aligned scenes) keep most of their values exact doubles, so their ties,
// which no bound certifies, get their sign here without the exact stage.
//
// The bound rules (inexact values; e >= |v - E|, E the exact value):
//   a +- b:  v = dwAdd(a, +-b), e = e_a + e_b + kDwAddRel (|a.hi| + |b.hi|);
//   a * b:   v = dwMul(a, b),
//            e = |a| e_b + |b| e_a + e_a e_b + kDwRel |v.hi| + kDwTiny,
//            |a| = |a.hi| + |a.lo|,
// and the local coordinates' a-priori bound (dwCoordinate below). These are
// the rules of the tape's double-word stage, derived in src/adaptive.cpp
// with the rounding of e itself; the sign test is the same:
//   b = (e + |v.lo|) (1 + 2^-40) + 2^-600, sign(v.hi) when |v.hi| > b.
// Only inputs inside the range gate (rangeGateOk) reach this kernel.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstring>

#include "eft.h"
#include "expansion.h"
#include "filter.h"
#include "tricyl/types.h"

#if defined(__GNUC__) || defined(__clang__)
#define TRICYL_DW_INLINE inline __attribute__((always_inline))
#else
#define TRICYL_DW_INLINE inline
#endif

namespace tricyl::detail {

/// A double-word value and its bound (0: exact). kFma selects TwoProduct's
/// implementation (src/eft.h; the same bits either way): the copy with
/// kFma = true runs only in code compiled for FMA (TRICYL_FMA_DISPATCH).
template <bool kFma>
struct Dwe {
  DW v;
  double e;
};

/// A double-word value and its bound, as the tape's double-word stage
/// stores it (src/adaptive.h).
struct DwRun {
  DW v;
  double e;
};

/// The running rules for inexact values (the header comment), shared by
/// DwKernel and the tape (src/adaptive.cpp). T: Dwe or DwRun.
template <class T>
TRICYL_DW_INLINE T dwRunAdd(const T& a, const T& b) {
  T r;
  r.v = dwAdd(a.v, b.v);
  r.e = a.e + b.e + kDwAddRel * (std::fabs(a.v.hi) + std::fabs(b.v.hi));
  return r;
}
template <bool kFma, class T>
TRICYL_DW_INLINE T dwRunMul(const T& a, const T& b) {
  T r;
  r.v = dwMulT<kFma>(a.v, b.v);
  const double ma = std::fabs(a.v.hi) + std::fabs(a.v.lo);
  const double mb = std::fabs(b.v.hi) + std::fabs(b.v.lo);
  r.e = ma * b.e + mb * a.e + a.e * b.e + kDwRel * std::fabs(r.v.hi) + kDwTiny;
  return r;
}

// Exact results of exact doubles: TwoSum and TwoProduct give hi + lo, and
// lo = 0 keeps the bound 0; lo != 0 gets the bound kNotDouble (any bound
// is valid for an exact value; this one only says "not a lone double").
constexpr double kNotDouble = 0x1p-1074;

template <bool kFma>
TRICYL_DW_INLINE Dwe<kFma> dweAdd(const Dwe<kFma>& a, const Dwe<kFma>& b) {
  Dwe<kFma> r;
  if (a.e + b.e == 0) {  // both exact doubles (e >= 0; e = 0 implies lo = 0)
    twoSum(a.v.hi, b.v.hi, r.v.hi, r.v.lo);  // exact (no overflow in gate)
    r.e = r.v.lo == 0 ? 0.0 : kNotDouble;
    return r;
  }
  return dwRunAdd(a, b);
}

template <bool kFma>
TRICYL_DW_INLINE Dwe<kFma> operator+(const Dwe<kFma>& a, const Dwe<kFma>& b) {
  return dweAdd(a, b);
}
template <bool kFma>
TRICYL_DW_INLINE Dwe<kFma> operator-(const Dwe<kFma>& a) {
  return {dwNeg(a.v), a.e};
}
template <bool kFma>
TRICYL_DW_INLINE Dwe<kFma> operator-(const Dwe<kFma>& a, const Dwe<kFma>& b) {
  return dweAdd(a, -b);
}
template <bool kFma>
TRICYL_DW_INLINE Dwe<kFma> operator*(const Dwe<kFma>& a, const Dwe<kFma>& b) {
  Dwe<kFma> r;
  if (a.e + b.e == 0) {  // both exact doubles
    double p, err;
    twoProdT<kFma>(a.v.hi, b.v.hi, p, err);
    if (p == 0 && (a.v.hi == 0 || b.v.hi == 0)) {  // a zero factor
      r.v = {p, 0.0};
      r.e = 0;
      return r;
    }
    if (std::fabs(p) >= kProdExactMin) {  // the error term is exact
      r.v = {p, err};
      r.e = err == 0 ? 0.0 : kNotDouble;
      return r;
    }
  }
  return dwRunMul<kFma>(a, b);
}

/// Set when a kernel that tracks exact values certified an exact zero (a
/// true tie: no error bound can), so that the driver reports the query as
/// decided exactly (Stage::kExact). Statistics only; per thread.
inline thread_local bool tls_exact_zero = false;

/// The local coordinate x = sum_k R_k d_k, d_k = p_k - t_k (R_k = R_kj for
/// the coordinate's column j), from the exact differences d_k = D_k + l_k
/// (TwoSum), as one double word:
///   (P_k, e_k) = TwoProd(R_k, D_k)        R_k D_k = P_k + e_k exactly;
///   q_k = fl(R_k l_k);
///   (s1, f1) = TwoSum(P_0, P_1), (s, f2) = TwoSum(s1, P_2)   exact;
///   low = fl(f1 + f2 + e_0 + e_1 + e_2 + q_0 + q_1 + q_2);
///   v = TwoSum(s, low)                                        exact.
/// So x - v = (the rounding of low's seven additions) + sum_k (R_k l_k -
/// q_k). With M = sum_k |R_k| |D_k|: |l_k| <= u |D_k|, |e_k| <= u |P_k|,
/// |f1| <= u |s1|, |f2| <= u |s|, so low's terms sum to at most about
/// 5 u M in magnitude, its additions err by at most 7 u (1 + 7u) 5 u M
/// (the classic gamma_7 bound of recursive summation), and the q_k by
/// u^2 M (1 + u): in all below 37 u^2 M < 2^-100 M' with M' the computed
/// magnitude (three roundings of non-negative terms, (1 - u)^3 M <= M').
/// Underflow (a product or an error term below the normal range) adds at
/// most a few 2^-1075 absolutely: kDwTiny.
/// Exact cases, bound 0: every term with a zero factor (R_k = 0 or
/// d_k = 0: an exact 0, which the line interval's tests Dx = Dy = 0 need);
/// or every term a zero factor or exact (l_k = 0, e_k = 0 with no underflow:
/// |P_k| >= kProdExactMin) and f1 = f2 = 0: then x = s exactly (an exact
/// pose on exact data).
template <bool kFma>
TRICYL_DW_INLINE DwRun dwCoordinate(const double R[3], const double D[3],
                                    const double l[3]) {
  double Pk[3], e[3], q[3];
  double m = 0;
  for (int k = 0; k < 3; ++k) {
    twoProdT<kFma>(R[k], D[k], Pk[k], e[k]);
    q[k] = R[k] * l[k];
    m += std::fabs(R[k]) * std::fabs(D[k]);
  }
  double s1, f1, s, f2;
  twoSum(Pk[0], Pk[1], s1, f1);
  twoSum(s1, Pk[2], s, f2);
  const double low =
      ((((f1 + f2) + (e[0] + e[1])) + e[2]) + (q[0] + q[1])) + q[2];
  DwRun r;
  twoSum(s, low, r.v.hi, r.v.lo);
  r.e = 0x1p-100 * m + kDwTiny;
  // Exact? Only possible with low = 0 (its terms all zero); checked then.
  if (low == 0) {
    bool exact = (f1 == 0) & (f2 == 0);
    for (int k = 0; k < 3; ++k) {
      // A zero factor makes the term an exact 0 (D_k = 0 means p_k = t_k,
      // so l_k = 0 too; R_k = 0 makes q_k = 0).
      const bool zf = (R[k] == 0) | (D[k] == 0);
      exact &= zf | ((l[k] == 0) & (e[k] == 0) &
                     (std::fabs(Pk[k]) >= kProdExactMin));
    }
    if (exact) r.e = 0;  // then r.v = (s, 0): x = s exactly
  }
  return r;
}

/// A compressed expansion (src/expansion.h) rounded to its two largest
/// components, (hi, lo) = TwoSum(c_n-1, c_n-2), with the bound e = (sum of
/// the other components' magnitudes) (1 + 2^-40): at most 96 non-negative
/// doubles, whose rounded sum is below the exact one by less than that
/// factor, and the components are exact. For a compressed expansion the
/// bound is about 2^-104 of the value itself. Shared by the tape
/// (Tape::dwCoordAccurate, src/adaptive.cpp) and dwCoordinateAccurate.
inline DwRun dwFromExpansion(const Expansion& x) {
  const int n = x.size();
  const double* c = x.data();
  DwRun r{{0.0, 0.0}, 0.0};
  if (n == 0) return r;
  twoSum(c[n - 1], n >= 2 ? c[n - 2] : 0.0, r.v.hi, r.v.lo);
  double rest = 0;
  for (int m = 0; m + 2 < n; ++m) rest += std::fabs(c[m]);
  r.e = rest * (1 + 0x1p-40);
  return r;
}

/// Coordinate j of y = R^T (p - t) (doubled for j = 2: Z = 2 z) to within
/// about 2^-104 of ITS OWN magnitude, where dwCoordinate's bound is 2^-100
/// of the terms' magnitude M (the tape's dwCoordAccurate, src/adaptive.cpp,
/// for the straight-line stage): the exact value as a stack expansion,
/// compressed and rounded by dwFromExpansion. An exact pair with lo != 0 is
/// not a double: bound kNotDouble (DwKernel's convention). Returns false,
/// and leaves `out` alone, where the expansion cannot be formed (near
/// underflow). Needles and discs have local coordinates far below the terms
/// they cancel from: their near ties fail in double word for dwCoordinate's
/// bound alone.
inline bool dwCoordinateAccurate(const Pose<double>& pose,
                                 const Vec3<double>& p, int j, DwRun* out) {
  const double pp[3] = {p.x, p.y, p.z};
  const double tt[3] = {pose.t.x, pose.t.y, pose.t.z};
  Expansion x;
  for (int k = 0; k < 3; ++k)
    x = x + Expansion(pose.R[k][j]) * Expansion::difference(pp[k], tt[k]);
  if (j == 2) x = x + x;
  x = x.compressed();
  if (!x.ok()) return false;
  DwRun r = dwFromExpansion(x);
  if (r.e == 0 && r.v.lo != 0) r.e = kNotDouble;
  *out = r;
  return true;
}

/// The kernel (src/filter.h's interface). sign() returns kUnknown where the
/// bound cannot certify the sign; the caller leaves that test to the exact
/// stage.
template <bool kFma>
struct DwKernel {
  using Num = Dwe<kFma>;
  static constexpr bool kExact = false;
  static TRICYL_DW_INLINE Num lift(double x) { return {{x, 0.0}, 0.0}; }
  /// A coordinate of the double-word frame (value and bound) as a value.
  static TRICYL_DW_INLINE Num leaf(const DwRun& c) { return {c.v, c.e}; }
  static TRICYL_DW_INLINE Num inputDiff(double a, double b) {
    Num r;
    twoSum(a, -b, r.v.hi, r.v.lo);
    r.e = r.v.lo == 0 ? 0.0 : kNotDouble;  // exact either way
    return r;
  }
  static TRICYL_DW_INLINE Sign sign(const Num& a) {
    // e = 0: an exact double, hi.
    const double b =
        a.e == 0 ? 0.0 : (a.e + std::fabs(a.v.lo)) * (1 + 0x1p-40) + 0x1p-600;
    if (a.v.hi > b) return Sign::kPos;
    if (a.v.hi < -b) return Sign::kNeg;
    if (a.e != 0) return Sign::kUnknown;
    tls_exact_zero = true;  // a true tie
    return Sign::kZero;
  }
  /// The local coordinates of p (y = R^T (p - t), z doubled: Z = 2 z, an
  /// exact scaling).
  static TRICYL_DW_INLINE void toLocal(const Pose<double>& pose,
                                       const Vec3<double>& p, Num& x, Num& y,
                                       Num& Z) {
    const double pp[3] = {p.x, p.y, p.z},
                 tt[3] = {pose.t.x, pose.t.y, pose.t.z};
    double D[3], l[3];
    for (int k = 0; k < 3; ++k) twoSum(pp[k], -tt[k], D[k], l[k]);
    Num* out[3] = {&x, &y, &Z};
    for (int j = 0; j < 3; ++j) {
      const double R[3] = {pose.R[0][j], pose.R[1][j], pose.R[2][j]};
      const DwRun c = dwCoordinate<kFma>(R, D, l);
      out[j]->v = c.v;
      out[j]->e = c.e;
    }
    Z.v.hi *= 2;
    Z.v.lo *= 2;
    Z.e *= 2;
  }
};

/// The double-word FILTER (the triangle's stage between the running pass
/// and DwKernel for rounded poses, src/triangle_cylinder.cpp):
/// FilterKernel's rules (src/filter.h), a value and a magnitude, with the
/// value in double word. No running bound and no exact values: a few
/// operations per step instead of DwKernel's dozen, and a bound about 2^-94
/// of the magnitude instead of the filter's 2^-47. What it leaves open
/// (exact ties above all) goes on to DwKernel.
///
/// Invariant: |v - E| <= eps m^ and m >= m^ (1 - u)^D, E the exact value, m^
/// the exact magnitude (the same expression on |leaves|, '-' read as '+'),
/// D the depth. Leaves: H, r and exact coordinates with eps = 0 and
/// m = |v|; a double-word coordinate of the frame (dwCoordinate: error <=
/// e = 2^-100 M + kDwTiny) with m = e 2^100 + |hi| >= |E| (1 - 2^-52),
/// so eps <= 2^-100 (the kDwTiny part is absolute: below). Steps:
///   a +- b: dwAdd errs by <= 4u^2 (|a.hi| + |b.hi|), so eps <= max(eps_a,
///           eps_b) + 4u^2 (1 + eps);
///   a * b:  |ab - AB| <= |A| eps_b m_b + |B| eps_a m_a + eps_a eps_b m_a m_b,
///           and dwMul errs by <= 7u^2 |a b|, so eps <= eps_a + eps_b +
///           eps_a eps_b + 7u^2 (1 + eps_a)(1 + eps_b).
/// So eps <= d 2^-100 + D 7u^2 (first order) for a polynomial of degree d
/// in the coordinates and depth D: the triangle's tests have d <= 8 and
/// D <= 14 (docs/exactness.md), eps <= 2^-97 + 2^-100.2 < 2^-96.5, and
/// with m's own rounding ((1 - u)^-D < 1 + 2^-48) below 2^-96.4 m. kRel =
/// 2^-94 leaves a factor 5 of room. Underflow: kDwTiny per leaf and per
/// step, carried to the root by sibling magnitudes below 2^380 under the
/// range gate (FilterKernel's argument), stays below 2^-600 = kAbs. The
/// value's own low part is added to the bound (sign(hi) is certified when
/// |hi| - |lo| > bound).
template <bool kFma>
struct Dwm {
  DW v;
  double m;
};
template <bool kFma>
TRICYL_DW_INLINE Dwm<kFma> operator+(const Dwm<kFma>& a, const Dwm<kFma>& b) {
  return {dwAdd(a.v, b.v), a.m + b.m};
}
template <bool kFma>
TRICYL_DW_INLINE Dwm<kFma> operator-(const Dwm<kFma>& a) {
  return {dwNeg(a.v), a.m};
}
template <bool kFma>
TRICYL_DW_INLINE Dwm<kFma> operator-(const Dwm<kFma>& a, const Dwm<kFma>& b) {
  return {dwAdd(a.v, dwNeg(b.v)), a.m + b.m};
}
template <bool kFma>
TRICYL_DW_INLINE Dwm<kFma> operator*(const Dwm<kFma>& a, const Dwm<kFma>& b) {
  return {dwMulT<kFma>(a.v, b.v), a.m * b.m};
}

template <bool kFma>
struct DwFilterKernel {
  using Num = Dwm<kFma>;
  static constexpr bool kExact = false;
  static constexpr double kRel = 0x1p-94;
  static constexpr double kAbs = 0x1p-600;
  static TRICYL_DW_INLINE Num lift(double x) {
    return {{x, 0.0}, std::fabs(x)};
  }
  /// A coordinate of the double-word frame (value, bound e): see above.
  static TRICYL_DW_INLINE Num leaf(const DwRun& c) {
    return {c.v, c.e * 0x1p100 + std::fabs(c.v.hi)};
  }
  static TRICYL_DW_INLINE Sign sign(const Num& a) {
    const double b = a.m * kRel + kAbs + std::fabs(a.v.lo);
    if (a.v.hi > b) return Sign::kPos;
    if (a.v.hi < -b) return Sign::kNeg;
    return Sign::kUnknown;
  }
};

}  // namespace tricyl::detail
