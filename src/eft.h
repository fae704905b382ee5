// SPDX-License-Identifier: BSD-3-Clause
// Error-free transformations and double-word ("double-double") arithmetic:
// the portable building blocks of the intermediate stage (src/adaptive.h)
// and of the stack-resident exact stage (src/expansion.h). Every operation
// here is an IEEE-754 binary64 operation in round-to-nearest-even; nothing
// depends on the width of long double or on x87 (docs/exactness.md,
// section 4).
//
// References:
//   D. E. Knuth, TAOCP vol. 2, 4.2.2 (TwoSum).
//   T. J. Dekker, "A floating-point technique for extending the available
//     precision", Numer. Math. 18 (1971) (Split, TwoProduct without FMA).
//   S. Boldo, "Pitfalls of a full floating-point proof: example on the
//     formal proof of the Veltkamp/Dekker algorithms" (IJCAR 2006): the
//     exactness conditions under underflow.
//   M. Joldes, J.-M. Muller, V. Popescu, "Tight and rigorous error bounds
//     for basic building blocks of double-word arithmetic", ACM TOMS 44(2),
//     2017: relative error of DWTimesDW1 (Algorithm 10) <= 7u^2, u = 2^-53,
//     in the absence of underflow and overflow. The addition is their
//     sloppy one, with its own bound (dwAdd).
#pragma once

#include <cmath>
#include <cstdlib>

#if defined(__FP_FAST_FMA) || defined(FP_FAST_FMA) || defined(__FMA__) || \
    defined(__aarch64__)
#define TRICYL_HAVE_FMA 1
#else
#define TRICYL_HAVE_FMA 0
#endif

// On x86-64 builds that do not assume FMA (the default: SSE2), the
// double-word stages pick, once per process, copies compiled for FMA when
// the CPU has one (src/adaptive.cpp, src/per_sign.h): TRICYL_FMA_DISPATCH.
#if (defined(__x86_64__) || defined(__i386__)) && \
    (defined(__GNUC__) || defined(__clang__)) && !TRICYL_HAVE_FMA
#define TRICYL_FMA_DISPATCH 1
#else
#define TRICYL_FMA_DISPATCH 0
#endif

namespace tricyl::detail {

#if TRICYL_FMA_DISPATCH
/// Whether to take the FMA copies: the CPU has FMA, and
/// TRICYL_SCALAR_BASELINE=1 is not in the environment (it keeps the plain
/// path; tests/answers_digest_check.sh compares the two paths' digests).
/// TwoProduct is exact either way: the choice changes no bit.
inline bool fmaAtRunTime() {
  static const bool k = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("fma") != 0 &&
           std::getenv("TRICYL_SCALAR_BASELINE") == nullptr;
  }();
  return k;
}
#endif

/// s = fl(a + b) and e = (a + b) - s EXACTLY, for any finite a, b whose sum
/// does not overflow, with no condition on their order (Knuth). Gradual
/// underflow cannot make it inexact: the error of a sum is always a double.
inline void twoSum(double a, double b, double& s, double& e) {
  s = a + b;
  const double bb = s - a;
  e = (a - (s - bb)) + (b - bb);
}

/// Dekker's split: a = hi + lo with hi, lo of at most 26 significant bits
/// each (|a| < 2^996, so that 134217729 a does not overflow).
inline void split(double a, double& hi, double& lo) {
  const double c = 134217729.0 * a;  // 2^27 + 1
  hi = c - (c - a);
  lo = a - hi;
}

/// p = fl(a b) and e = a b - p. EXACT when a b is finite and either p = 0
/// with a = 0 or b = 0, or |p| >= kProdExactMin (then the exponents of a
/// and b add up to at least emin + 53, so the error, a multiple of the
/// product of their last bits' weights below ulp(p) / 2, is a double;
/// Boldo 2006 for the split variant). Callers that need exactness test
/// that condition (Expansion); the double-word operations below count a
/// possible violation as an absolute error instead (kDwTiny).
inline constexpr double kProdExactMin = 0x1p-900;
/// kFma: with a fused multiply-add (call it with true only from code
/// compiled for a CPU that has one: src/adaptive.cpp dispatches), else
/// Dekker's product of splits. Both give the exact error term, so the same
/// bits.
template <bool kFma>
inline void twoProdT(double a, double b, double& p, double& e) {
  p = a * b;
  if constexpr (kFma) {
    e = std::fma(a, b, -p);
  } else {
    double ah, al, bh, bl;
    split(a, ah, al);
    split(b, bh, bl);
    e = ((ah * bh - p) + ah * bl + al * bh) + al * bl;
  }
}
inline void twoProd(double a, double b, double& p, double& e) {
  twoProdT<TRICYL_HAVE_FMA != 0>(a, b, p, e);
}

/// A double-word number hi + lo with |lo| <= ulp(hi) / 2 (normalised by a
/// final FastTwoSum in every operation below).
struct DW {
  double hi;
  double lo;
};

/// x + y with an error bounded by the operands' magnitudes (the "sloppy"
/// double-word addition, with a TwoSum at the end so that no ordering of
/// the final pair is assumed): (sh, sl) = TwoSum(xh, yh) is exact;
/// v = fl(xl + yl) and w = fl(sl + v) round once each; (zh, zl) =
/// TwoSum(sh, w) is exact. So z - (x + y) = (xl + yl) d1 + (sl + v) d2 with
/// |d1|, |d2| <= u, and with |xl| <= u |xh|, |yl| <= u |yh|, |sl| <= u |sh|,
/// |sh| <= (1 + u)(|xh| + |yh|):
///   |z - (x + y)| <= 3 u^2 (1 + u) (|xh| + |yh|) <= kDwAddRel (|xh| + |yh|).
/// Additions of doubles are exact in the subnormal range: no underflow
/// term. (Not accurate relative to a cancelling sum, which the running
/// bound of src/adaptive.cpp does not need: it is 2^-104 of the operands,
/// where a double filter has 2^-47.)
inline DW dwAdd(DW x, DW y) {
  double sh, sl;
  twoSum(x.hi, y.hi, sh, sl);
  const double v = x.lo + y.lo;
  const double w = sl + v;
  DW z;
  twoSum(sh, w, z.hi, z.lo);
  return z;
}
inline constexpr double kDwAddRel = 0x1p-104;  // 4 u^2

inline DW dwNeg(DW x) { return {-x.hi, -x.lo}; }

/// FastTwoSum (Dekker): s = fl(a + b) and e = (a + b) - s EXACTLY when
/// |a| >= |b| or a = 0 (and always when the sum is subnormal: such sums are
/// exact). Three operations instead of TwoSum's six.
inline void fastTwoSum(double a, double b, double& s, double& e) {
  s = a + b;
  e = b - (s - a);
}

/// x * y: Algorithm 10 of Joldes, Muller and Popescu (DWTimesDW1, as
/// published: relative error <= 7u^2 of the exact product x y, without
/// underflow). Its TwoProduct is exact with or without FMA, and nothing
/// else in it could be fused (-ffp-contract=off), so the result is the
/// same bits on every platform.
/// PRECONDITION: both operands normalised, |lo| <= u |hi| (hi = fl(hi +
/// lo)); every double word of the library is (each operation of this file
/// ends in a TwoSum or a FastTwoSum, a TwoProduct's (p, e) is, lift gives
/// (x, 0), and the callers scale only by powers of 2 and negate; checked
/// caller by caller in src/dw_kernel.h, src/per_sign.h, src/dd.h,
/// src/adaptive.cpp and src/triangle_cylinder_margin.cpp). Then the final
/// FastTwoSum is exact: cl3 = cl1 + (x_h y_l + x_l y_h) has |cl3| <= 3u (1
/// + 5u) |ch| < |ch| (|cl1| <= u |ch|, each cross term <= u (1 + u) |ch|,
/// two roundings), and ch = 0 (a zero factor, or a product below 2^-1075)
/// is FastTwoSum's other exact case; under underflow a sum with a
/// subnormal result is exact anyway. So (z.hi, z.lo) is the exact pair
/// that TwoSum(ch, cl3) returns (z.hi = fl(ch + cl3) by both; z.lo the
/// exact remainder, up to the sign of a zero, which no later sum, product
/// or sign test tells apart): the double words of the general form with a
/// cheaper last step, and the same error bound kDwRel.
template <bool kFma>
inline DW dwMulT(DW x, DW y) {
  double ch, cl1;
  twoProdT<kFma>(x.hi, y.hi, ch, cl1);
  DW z;
  fastTwoSum(ch, cl1 + (x.hi * y.lo + x.lo * y.hi), z.hi, z.lo);
  return z;
}
inline DW dwMul(DW x, DW y) { return dwMulT<TRICYL_HAVE_FMA != 0>(x, y); }

/// The relative error bound of dwMul used by the running bound of
/// src/adaptive.cpp: 2^-103 = 8u^2 covers 7u^2 with room for the (1 + u)
/// between |x y| and |z.hi|.
inline constexpr double kDwRel = 0x1p-103;
/// The absolute allowance per double-word operation for underflow: each of
/// its at most 12 IEEE operations loses at most 2^-1075 absolutely when its
/// result is subnormal (and a TwoProduct's error term may then be inexact
/// by as much), and nothing in the short straight-line sequences amplifies
/// such a loss by more than a factor 4: 2^-1060 covers 2^-1075 * 12 * 4
/// with ample room. Sums of doubles are exact in the subnormal range.
inline constexpr double kDwTiny = 0x1p-1060;

}  // namespace tricyl::detail
