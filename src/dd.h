// SPDX-License-Identifier: BSD-3-Clause
// A double-word number type with the arithmetic operators, on the building
// blocks of src/eft.h, so that a template written for double runs unchanged
// at about 106 bits (the distance kernel, src/triangle_cylinder_distance*).
//
// Error model (Joldes, Muller, Popescu, ACM TOMS 44(2), 2017; src/eft.h):
//   x + y, x - y : |err| <= 2^-104 (|x| + |y|)        (sloppy addition)
//   x * y        : |err| <= 2^-103 |x y|               (DWTimesDW1)
//   x / y        : |err| <= 2^-101 |x / y|             (two correction steps
//                  of a long division, each exact to the dwMul bound)
//   sqrt(x)      : |err| <= 2^-102 sqrt(x)             (one Newton step from
//                  the double root, whose residual is computed with an exact
//                  TwoProduct: the step doubles the 53 correct bits)
// plus, near the underflow threshold, kDwTiny absolute per operation.
// Comparisons are exact (on the normalised pair). No operation allocates,
// throws, loops or raises an FP exception on finite operands (sqrt of a
// non-positive value returns 0).
#pragma once

#include <cmath>

#include "eft.h"

namespace tricyl::detail {

/// The double-word number; kFma selects the TwoProduct: a fused
/// multiply-add (one instruction, for code compiled for a CPU that has it:
/// src/triangle_cylinder_distance.cpp dispatches at run time) or Dekker's
/// split (eft.h). Both are exact, so the two give the same bits.
template <bool kFma>
struct DDT {
  double hi = 0;
  double lo = 0;
  DDT() = default;
  constexpr DDT(double h) : hi(h), lo(0) {}  // NOLINT: implicit, as a number
  constexpr DDT(double h, double l) : hi(h), lo(l) {}
  explicit operator double() const { return hi + lo; }
};
using DD = DDT<false>;

template <bool F>
inline DDT<F> operator+(DDT<F> x, DDT<F> y) {
  const DW z = dwAdd({x.hi, x.lo}, {y.hi, y.lo});
  return {z.hi, z.lo};
}
template <bool F>
inline DDT<F> operator-(DDT<F> x) {
  return {-x.hi, -x.lo};
}
template <bool F>
inline DDT<F> operator-(DDT<F> x, DDT<F> y) {
  return x + (-y);
}
/// DWTimesDW1 (eft.h's dwMulT).
template <bool F>
inline DDT<F> operator*(DDT<F> x, DDT<F> y) {
  const DW z = dwMulT<F>({x.hi, x.lo}, {y.hi, y.lo});
  return {z.hi, z.lo};
}
/// Long division: q1 = x/y in double, then two corrections from the
/// residuals x - y q1 (each a double-word multiply and subtract).
template <bool F>
inline DDT<F> operator/(DDT<F> x, DDT<F> y) {
  const double q1 = x.hi / y.hi;
  const DDT<F> r1 = x - y * DDT<F>(q1);
  const double q2 = r1.hi / y.hi;
  const DDT<F> r2 = r1 - y * DDT<F>(q2);
  const double q3 = r2.hi / y.hi;
  double s, e;
  twoSum(q1, q2, s, e);
  return DDT<F>(s, e) + DDT<F>(q3);
}
/// x * b for a double b: TwoProduct of the high parts plus the low part's
/// product (error <= 2^-104 |x b|, as DWTimesFP1 of Joldes et al.).
template <bool F>
inline DDT<F> mulD(DDT<F> x, double b) {
  double p, e;
  twoProdT<F>(x.hi, b, p, e);
  double h, l;
  twoSum(p, e + x.lo * b, h, l);
  return {h, l};
}

template <bool F>
inline bool operator<(DDT<F> x, DDT<F> y) {
  return x.hi < y.hi || (x.hi == y.hi && x.lo < y.lo);
}
template <bool F>
inline bool operator>(DDT<F> x, DDT<F> y) {
  return y < x;
}
template <bool F>
inline bool operator<=(DDT<F> x, DDT<F> y) {
  return !(y < x);
}
template <bool F>
inline bool operator>=(DDT<F> x, DDT<F> y) {
  return !(x < y);
}
template <bool F>
inline bool operator==(DDT<F> x, DDT<F> y) {
  return x.hi == y.hi && x.lo == y.lo;
}
template <bool F>
inline bool operator!=(DDT<F> x, DDT<F> y) {
  return !(x == y);
}

template <bool F>
inline DDT<F> abs(DDT<F> x) {
  return x.hi < 0 || (x.hi == 0 && x.lo < 0) ? -x : x;
}

/// sqrt(x) = s + (x - s^2) / (2 s), s = fl(sqrt(x.hi)); s^2 by TwoProduct.
template <bool F>
inline DDT<F> sqrt(DDT<F> x) {
  if (!(x.hi > 0)) return DDT<F>(0);
  const double s = std::sqrt(x.hi);
  double p, e;
  twoProdT<F>(s, s, p, e);
  const double r = ((x.hi - p) - e + x.lo) / (2 * s);
  double h, l;
  twoSum(s, r, h, l);
  return {h, l};
}

}  // namespace tricyl::detail
