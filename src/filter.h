// SPDX-License-Identifier: BSD-3-Clause
// The one filter-and-fallback mechanism behind every exact query in tricyl.
//
// A query is written ONCE as a template over a kernel K, using only +, -, *
// on K::Num and K::sign(). It is then run with:
//   FilterKernel  Num = Fd (double value + magnitude), sign() certified by a
//                 derived error bound, kUnknown when the bound cannot decide;
//   AdaptiveKernel (src/adaptive.h)  the same double values, each sign the
//                 bound leaves open re-decided by itself in double-word,
//                 then exactly: never kUnknown;
//   RunningDoubleKernel  the filter with a running error bound (the line
//                 interval's first stage, src/line_cylinder_interval.cpp);
//   ExactKernel   Num = Dyadic (GMP integer times a power of two), exact;
//   NaiveKernel   Num = double, sign() of the rounded value (diagnostic only).
// The query returns a three-valued Tri; kUnknown from the filter sends the
// query to the adaptive run (src/stages.h). See docs/exactness.md for the
// derivation of the bound used in FilterKernel::sign(). Nothing here or in
// the stages after it uses long double.
#pragma once

#include <gmpxx.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>

namespace tricyl::detail {

static_assert(std::numeric_limits<double>::is_iec559,
              "tricyl's error bounds assume IEEE-754 binary64");
#if defined(__FAST_MATH__)
#error \
    "tricyl must not be compiled with -ffast-math: it breaks the error bounds"
#endif
#if defined(FLT_EVAL_METHOD) && FLT_EVAL_METHOD != 0
#error "tricyl needs FLT_EVAL_METHOD == 0 (no excess precision, e.g. SSE2)"
#endif

enum class Sign : signed char { kNeg = -1, kZero = 0, kPos = 1, kUnknown = 2 };

/// Kleene's three-valued logic: kUnknown means "the filter cannot tell".
enum class Tri : unsigned char { kFalse = 0, kTrue = 1, kUnknown = 2 };

constexpr Tri toTri(bool b) { return b ? Tri::kTrue : Tri::kFalse; }
constexpr Tri kAnd(Tri a, Tri b) {
  return (a == Tri::kFalse || b == Tri::kFalse) ? Tri::kFalse
         : (a == Tri::kTrue && b == Tri::kTrue) ? Tri::kTrue
                                                : Tri::kUnknown;
}
constexpr Tri kOr(Tri a, Tri b) {
  return (a == Tri::kTrue || b == Tri::kTrue)     ? Tri::kTrue
         : (a == Tri::kFalse && b == Tri::kFalse) ? Tri::kFalse
                                                  : Tri::kUnknown;
}
constexpr Tri kNot(Tri a) {
  return a == Tri::kUnknown ? Tri::kUnknown : toTri(a == Tri::kFalse);
}

// Sign -> predicate on the value.
constexpr Tri isPos(Sign s) {
  return s == Sign::kUnknown ? Tri::kUnknown : toTri(s == Sign::kPos);
}
constexpr Tri isNeg(Sign s) {
  return s == Sign::kUnknown ? Tri::kUnknown : toTri(s == Sign::kNeg);
}
constexpr Tri isZero(Sign s) {
  return s == Sign::kUnknown ? Tri::kUnknown : toTri(s == Sign::kZero);
}
constexpr Tri isNonNeg(Sign s) { return kNot(isNeg(s)); }
constexpr Tri isNonPos(Sign s) { return kNot(isPos(s)); }

/// A double with a running magnitude: v is the rounded value of an
/// expression E built from +, -, * on exact double inputs, and m is the
/// rounded value of the same expression with every input replaced by its
/// absolute value and every '-' by '+'. See FilterKernel::sign().
struct Fd {
  double v;
  double m;
};
inline Fd operator+(Fd a, Fd b) { return {a.v + b.v, a.m + b.m}; }
inline Fd operator-(Fd a, Fd b) { return {a.v - b.v, a.m + b.m}; }
inline Fd operator-(Fd a) { return {-a.v, a.m}; }
inline Fd operator*(Fd a, Fd b) { return {a.v * b.v, a.m * b.m}; }

struct FilterKernel {
  using Num = Fd;
  static constexpr bool kExact = false;

  static Num lift(double x) { return {x, std::fabs(x)}; }

  /// The difference of two INPUT doubles. fl(a - b) = (a - b)(1 + delta)
  /// with |delta| <= u: the rounding is relative to the result, so the
  /// computed difference can enter the error analysis as an exact input
  /// with one extra rounding along every path (depth + 1), and its magnitude
  /// is |fl(a - b)| instead of |a| + |b|. This is what keeps far-from-origin
  /// scenes (|a|, |b| ~ 1e9, |a - b| ~ 1) inside the filter. Only valid for
  /// exact operands; never for computed ones.
  static Num inputDiff(double a, double b) {
    const double d = a - b;
    return {d, std::fabs(d)};
  }

  // Certified sign. With u = 2^-53 and D the depth of E (longest chain of
  // operations from an input to the result), if no product underflows,
  //   |v - E| <= gamma_D * Etilde,  gamma_D = D u / (1 - D u),
  // and m >= Etilde (1 - u)^D because every operation on non-negative
  // values rounds by a factor in [1-u, 1+u]. Hence
  //   |v - E| <= D u / ((1 - D u)(1 - u)^D) * m <= 2^-47 m   for D <= 56.
  // Every predicate in tricyl has depth <= 20 (the triangle kernel's deepest
  // is 14; counted in docs/exactness.md), far inside 56.
  // Underflow: a product may lose up to 2^-1075 absolutely; with the range
  // gate (rangeGateOk: every length input <= 2^40 in magnitude, every
  // dimensionless input <= 2) the loss, multiplied by the sibling operands
  // on its way to the root, stays below 2^-680 for every predicate whose
  // a-priori magnitude bound is <= 2^380 (the triangle kernel's largest is
  // about 2^370; docs/exactness.md, "Underflow"), so an absolute slack of
  // 2^-600 covers it.
  // Overflow yields Inf or NaN in v or m, and every comparison below is
  // false for them, so the answer is kUnknown: overflow can only cost time.
  static constexpr double kRel = 0x1p-47;
  static constexpr double kAbs = 0x1p-600;
  static Sign sign(const Fd& a) {
    const double bound = a.m * kRel + kAbs;
    if (a.v > bound) return Sign::kPos;
    if (a.v < -bound) return Sign::kNeg;
    return Sign::kUnknown;
  }
};

/// A filter with a RUNNING error bound instead of a magnitude: each value
/// carries e >= |v - E|. The magnitude bound of FilterKernel is cheap but
/// pessimistic when a value is small after cancellation (a local coordinate
/// 1e-5 computed from world terms of 500 has m ~ 500, so x^2 gets
/// 2^-47 * 500^2 although its error is ~ 2 * 1e-5 * 500 u); the running
/// bound follows the actual values. Rules (u' = u (1 + 2 u) >= u / (1 - u)
/// covers the rounding of the operation itself, relative to the computed
/// result):
///   a + b:  e = e_a + e_b + u' |v|
///   a * b:  e = |v_a| e_b + |v_b| e_a + e_a e_b + u' |v| + kTiny
///     since |v_a v_b - A B| <= |v_a| |v_b - B| + |B| |v_a - A| and
///     |B| <= |v_b| + e_b.
///   input difference a - b of doubles: e = u' |v|; an input: e = 0.
/// e itself is computed with rounding to nearest from non-negative terms,
/// so it falls short of the exact bound by at most a factor (1 - u)^k,
/// k <= 4 roundings per operation times depth <= 56, i.e. below 1 + 2^-44
/// in relative terms: sign() inflates it by (1 + 2^-40).
/// Underflow: every product (and the line interval's quotients) adds the
/// smallest subnormal, kTiny, to its e (the loss of one rounded product is
/// below it), so an underflowed product is never a certified 0 (sums of
/// doubles are exact in the subnormal range). The bound computations' own
/// underflow losses (<= 2^-1075 each) propagate as in FilterKernel and stay
/// far below kAbs = 2^-600 under the range gate (docs/exactness.md,
/// "Underflow").
constexpr double kU1d = 0x1p-53 * (1 + 0x1p-52);  // u' for double

/// Per floating type of a running bound: u' (kU1), the absolute underflow
/// allowance of a product or quotient (kTiny: the type's smallest subnormal;
/// with 0 there, Dy * Dy = dmin^2 underflowed to a "certified" 0,
/// tests/portability_test.cpp) and the inflation of sign() for the rounding
/// of the bound computations themselves (kInflate). Only double is used.
template <class T>
struct RunningTraits;
template <>
struct RunningTraits<double> {
  using T = double;
  static constexpr T kU1 = kU1d;
  static constexpr T kTiny = std::numeric_limits<T>::denorm_min();
  static constexpr T kInflate = 1 + 0x1p-40;
  static T abs(T x) { return std::fabs(x); }
};

/// A value and its running error bound e >= |v - E| (the rules above).
template <class T>
struct Running {
  T v;
  T e;
};
template <class T>
inline Running<T> operator+(Running<T> a, Running<T> b) {
  using R = RunningTraits<T>;
  const T v = a.v + b.v;
  return {v, a.e + b.e + R::kU1 * R::abs(v)};
}
template <class T>
inline Running<T> operator-(Running<T> a, Running<T> b) {
  using R = RunningTraits<T>;
  const T v = a.v - b.v;
  return {v, a.e + b.e + R::kU1 * R::abs(v)};
}
template <class T>
inline Running<T> operator-(Running<T> a) {
  return {-a.v, a.e};
}
template <class T>
inline Running<T> operator*(Running<T> a, Running<T> b) {
  using R = RunningTraits<T>;
  const T v = a.v * b.v;
  const T e =
      R::abs(a.v) * b.e + R::abs(b.v) * a.e + a.e * b.e + R::kU1 * R::abs(v);
  return {v, e + R::kTiny};
}

/// The filter with a running bound, in T (RunningDoubleKernel: double).
template <class T>
struct RunningKernel {
  using R = RunningTraits<T>;
  using Num = Running<T>;
  static constexpr bool kExact = false;
  static Num lift(double x) { return {x, 0}; }
  static Num inputDiff(double a, double b) {
    const T d = static_cast<T>(a) - b;
    return {d, R::kU1 * R::abs(d)};
  }
  static constexpr T kAbs = 0x1p-600;
  static Sign sign(const Num& a) {
    const T bound = a.e * R::kInflate + kAbs;
    if (a.v > bound) return Sign::kPos;
    if (a.v < -bound) return Sign::kNeg;
    return Sign::kUnknown;
  }
};

/// The line interval's first stage (src/line_cylinder_interval.cpp), with
/// division and square root added there.
using Rd = Running<double>;
using RunningDoubleKernel = RunningKernel<double>;

/// The gate under which FilterKernel's absolute slack kAbs is valid.
/// `max_length`: the largest magnitude of any input with the dimension of a
/// length (coordinates, translations, radii, lengths); `max_unitless`: the
/// largest magnitude of a dimensionless input (rotation entries). Inputs
/// outside the gate go straight to the exact kernel.
inline bool rangeGateOk(double max_length, double max_unitless) {
  return max_length <= 0x1p40 && max_unitless <= 2.0;
}

/// An exact dyadic rational m * 2^e (m a GMP integer). Every value the
/// predicates meet is a polynomial in doubles, hence dyadic, so no gcd is
/// ever needed (mpq_class canonicalises after every operation and was
/// measured 3-4x slower here). Addition aligns the exponents exactly.
struct Dyadic {
  mpz_class m;
  long e = 0;
};
inline Dyadic operator+(const Dyadic& a, const Dyadic& b) {
  if (sgn(a.m) == 0) return b;
  if (sgn(b.m) == 0) return a;
  Dyadic r;
  if (a.e >= b.e) {
    mpz_mul_2exp(r.m.get_mpz_t(), a.m.get_mpz_t(),
                 static_cast<mp_bitcnt_t>(a.e - b.e));
    r.m += b.m;
    r.e = b.e;
  } else {
    mpz_mul_2exp(r.m.get_mpz_t(), b.m.get_mpz_t(),
                 static_cast<mp_bitcnt_t>(b.e - a.e));
    r.m += a.m;
    r.e = a.e;
  }
  return r;
}
inline Dyadic operator-(const Dyadic& a) { return {-a.m, a.e}; }
inline Dyadic operator-(const Dyadic& a, const Dyadic& b) { return a + (-b); }
inline Dyadic operator*(const Dyadic& a, const Dyadic& b) {
  Dyadic r;
  r.m = a.m * b.m;
  r.e = a.e + b.e;
  return r;
}

struct ExactKernel {
  using Num = Dyadic;
  static constexpr bool kExact = true;
  /// Exact for every finite double: x = f 2^k with 0.5 <= |f| < 1, and
  /// f 2^53 is an integer (also for subnormals, whose significand is
  /// shorter).
  static Num lift(double x) {
    Dyadic d;
    if (x == 0) return d;
    int k = 0;
    const double f = std::frexp(x, &k);
    d.m = mpz_class(std::ldexp(f, 53));  // an integer-valued double: exact
    d.e = long(k) - 53;
    return d;
  }
  static Num inputDiff(double a, double b) { return lift(a) - lift(b); }
  static Sign sign(const Num& a) {
    const int s = sgn(a.m);
    return s < 0 ? Sign::kNeg : (s > 0 ? Sign::kPos : Sign::kZero);
  }
};

/// Diagnostic only: signs of rounded values, never kUnknown. Not exact.
struct NaiveKernel {
  using Num = double;
  static constexpr bool kExact = false;
  static Num lift(double x) { return x; }
  static Num inputDiff(double a, double b) { return a - b; }
  static Sign sign(double a) {
    return a < 0 ? Sign::kNeg : (a > 0 ? Sign::kPos : Sign::kZero);
  }
};

/// True iff x is neither NaN nor infinite.
inline bool finite(double x) { return std::isfinite(x); }

}  // namespace tricyl::detail
