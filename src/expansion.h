// SPDX-License-Identifier: BSD-3-Clause
// Exact arithmetic on the stack: Shewchuk's floating-point expansions with
// a fixed capacity, for the exact stage of src/adaptive.h.
//
// An expansion is a sum of doubles e_0 + ... + e_{n-1}, non-overlapping and
// ordered by increasing magnitude, zero components eliminated; its value is
// the exact sum, and its sign is the sign of its largest component e_{n-1}
// (non-overlapping: |e_0 + ... + e_{n-2}| < |e_{n-1}|). Sums and products
// are formed with TwoSum and TwoProduct (src/eft.h), which are error-free,
// so the value is exact; the non-overlapping property is preserved by
// Fast-Expansion-Sum and Scale-Expansion in round-to-nearest-even arithmetic
// (J. R. Shewchuk, "Adaptive precision floating-point arithmetic and fast
// robust geometric predicates", Discrete Comput. Geom. 18 (1997), Theorems
// 10, 13 and 19) and by Compress (ibid., section 2.8).
//
// Where these arguments do not hold, the result is flagged invalid and the
// caller falls back to GMP (ExactKernel, src/filter.h); nothing is ever
// silently inexact:
//   - a product whose error term may not be a double (a non-zero product of
//     magnitude below kProdExactMin, i.e. near underflow; src/eft.h);
//   - a non-finite component (overflow: never under the range gate, the
//     only place tricyl uses expansions);
//   - more than kCapacity components, or a product of more than
//     kProductTerms component pairs (the capacity of the stack buffers).
// Under the range gate with inputs in an ordinary exponent window, none of
// these happens (tests/adaptive_stage_test.cpp counts the GMP fallbacks).
#pragma once

#include <cmath>
#include <cstdint>

#include "eft.h"

namespace tricyl::detail {

class Expansion {
 public:
  static constexpr int kCapacity = 96;
  /// m n for a product of an m- and an n-component expansion: its
  /// 2 m n partial components are accumulated in a kCapacity buffer after
  /// each Scale-Expansion, so the bound is on the intermediate sizes.
  static constexpr int kProductTerms = 256;

  Expansion() = default;
  // Copies move only the n_ live components (the buffer is kCapacity long).
  Expansion(const Expansion& o) : n_(o.n_), ok_(o.ok_) {
    for (int i = 0; i < n_; ++i) c_[i] = o.c_[i];
  }
  Expansion& operator=(const Expansion& o) {
    n_ = o.n_;
    ok_ = o.ok_;
    for (int i = 0; i < n_; ++i) c_[i] = o.c_[i];
    return *this;
  }
  explicit Expansion(double x) {
    if (!std::isfinite(x)) {
      ok_ = false;
    } else if (x != 0) {
      c_[0] = x;
      n_ = 1;
    }
  }
  /// From n components of a valid expansion (a memo's copy).
  static Expansion fromComponents(const double* c, int n) {
    Expansion r;
    r.n_ = n;
    for (int i = 0; i < n; ++i) r.c_[i] = c[i];
    return r;
  }
  static Expansion difference(double a, double b) {
    Expansion r;
    double s, e;
    twoSum(a, -b, s, e);
    if (!std::isfinite(s)) {
      r.ok_ = false;
      return r;
    }
    if (e != 0) r.c_[r.n_++] = e;
    if (s != 0) r.c_[r.n_++] = s;
    return r;
  }

  bool ok() const { return ok_; }
  int size() const { return n_; }
  /// The components, by increasing magnitude.
  const double* data() const { return c_; }
  /// -1, 0, +1 (valid expansions only).
  int sign() const {
    if (n_ == 0) return 0;
    return c_[n_ - 1] > 0 ? 1 : -1;
  }
  /// The same value in fewer non-overlapping components (Compress), so
  /// that the largest component approximates the value.
  Expansion compressed() const {
    Expansion r = *this;
    r.compress();
    return r;
  }
  double approx() const {
    double s = 0;
    for (int i = 0; i < n_; ++i) s += c_[i];
    return s;
  }

  Expansion operator-() const {
    Expansion r = *this;
    for (int i = 0; i < n_; ++i) r.c_[i] = -r.c_[i];
    return r;
  }
  friend Expansion operator+(const Expansion& a, const Expansion& b) {
    if (!a.ok_ || !b.ok_) return invalid();
    // Grow the longer one by each component of the shorter (Shewchuk's
    // Expansion-Sum): non-overlapping in, non-overlapping out.
    Expansion r = merged(a, b);
    r.compress();
    return r;
  }
  friend Expansion operator-(const Expansion& a, const Expansion& b) {
    return a + (-b);
  }
  friend Expansion operator*(const Expansion& a, const Expansion& b) {
    if (!a.ok_ || !b.ok_) return invalid();
    if (a.n_ == 0 || b.n_ == 0) return Expansion();
    if (a.n_ * b.n_ > kProductTerms) return invalid();
    const Expansion& big = a.n_ >= b.n_ ? a : b;
    const Expansion& small = a.n_ >= b.n_ ? b : a;
    Expansion r = big.scaled(small.c_[0]);
    for (int j = 1; j < small.n_ && r.ok_; ++j) {
      const Expansion t = big.scaled(small.c_[j]);
      if (!t.ok_) return invalid();
      r = merged(r, t);
      r.compress();
    }
    return r;
  }

 private:
  static Expansion invalid() {
    Expansion r;
    r.ok_ = false;
    return r;
  }

  void push(double v) {
    if (v == 0) return;
    if (n_ == kCapacity || !std::isfinite(v)) {
      ok_ = false;
      return;
    }
    c_[n_++] = v;
  }

  /// e + f in one pass (Shewchuk's Fast-Expansion-Sum with zero
  /// elimination, Theorem 13): the components of both, taken in order of
  /// increasing magnitude, are accumulated by a chain of TwoSums whose
  /// non-zero errors are the output, then the final sum. Each TwoSum is
  /// exact, so the value is exact; with round-to-nearest-even and strongly
  /// non-overlapping inputs (what Scale-Expansion and Compress produce) the
  /// output is strongly non-overlapping. (TwoSum gives the same pair as the
  /// FastTwoSum of the first step wherever FastTwoSum applies.) Linear in
  /// the lengths, where growing e by each component of f is quadratic: the
  /// products of long expansions of true ties spent most of their time
  /// there.
  static Expansion merged(const Expansion& e, const Expansion& f) {
    if (!e.ok_ || !f.ok_) return invalid();
    if (e.n_ + f.n_ > kCapacity) return invalid();
    if (e.n_ == 0) return f;
    if (f.n_ == 0) return e;
    Expansion h;
    int i = 0, j = 0;
    // The next component in order of magnitude (ties: e's first).
    auto next = [&]() {
      if (j == f.n_ || (i < e.n_ && std::fabs(e.c_[i]) <= std::fabs(f.c_[j])))
        return e.c_[i++];
      return f.c_[j++];
    };
    double q = next();
    while (i < e.n_ || j < f.n_) {
      double s, err;
      twoSum(q, next(), s, err);
      q = s;
      if (err != 0) h.c_[h.n_++] = err;
    }
    if (q != 0 || h.n_ == 0) h.c_[h.n_++] = q;
    if (h.n_ == 1 && h.c_[0] == 0) h.n_ = 0;
    for (int k = 0; k < h.n_; ++k)  // overflow: Inf, and NaN beside it
      if (!std::isfinite(h.c_[k])) h.ok_ = false;
    return h;
  }

  /// Scale-Expansion with zero elimination: this * b, exact unless a
  /// product falls below kProdExactMin (flagged invalid).
  Expansion scaled(double b) const {
    Expansion r;
    double q, h;
    if (!exactProd(c_[0], b, q, h)) return invalid();
    r.push(h);
    for (int i = 1; i < n_; ++i) {
      double T, t;
      if (!exactProd(c_[i], b, T, t)) return invalid();
      double s, e;
      twoSum(q, t, s, e);
      r.push(e);
      twoSum(T, s, q, e);
      r.push(e);
    }
    r.push(q);
    return r;
  }

  static bool exactProd(double a, double b, double& p, double& e) {
    twoProd(a, b, p, e);
    if (!std::isfinite(p)) return false;
    return p == 0 ? (a == 0 || b == 0) : std::fabs(p) >= kProdExactMin;
  }

  /// Shewchuk's Compress: the same value in fewer, non-overlapping
  /// components: a sweep down, then up, of exact TwoSums, in place (the
  /// down sweep writes at positions above the one it reads, the up sweep
  /// below).
  void compress() {
    if (!ok_ || n_ < 2) return;
    int bottom = n_ - 1;
    double q = c_[n_ - 1];
    for (int i = n_ - 2; i >= 0; --i) {
      double s, e;
      twoSum(q, c_[i], s, e);
      if (e != 0) {
        c_[bottom--] = s;
        q = e;
      } else {
        q = s;
      }
    }
    c_[bottom] = q;
    int top = 0;
    for (int i = bottom + 1; i < n_; ++i) {
      double s, e;
      twoSum(c_[i], q, s, e);
      q = s;
      if (e != 0) c_[top++] = e;
    }
    if (q != 0) c_[top++] = q;
    n_ = top;
    for (int i = 0; i < n_; ++i)  // overflow: Inf, and NaN beside it
      if (!std::isfinite(c_[i])) ok_ = false;
  }

  double c_[kCapacity];
  int n_ = 0;
  bool ok_ = true;
};

}  // namespace tricyl::detail
