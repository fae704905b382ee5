// SPDX-License-Identifier: BSD-3-Clause
// The exact root count behind withinDistance's torus edges
// (src/triangle_cylinder_margin.cpp): the number of distinct real roots of
// an integer polynomial in (0, 1) by Sturm's theorem, division-free.
// Tested against a rational Sturm sequence in tests/margin_sturm_test.cpp.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <limits>
#include <utility>
#include <vector>

#include "filter.h"

namespace tricyl::detail::sturm {

using Poly = std::vector<mpz_class>;  // coefficients, lowest degree first

inline void trim(Poly& p) {
  while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}

/// A positive multiple of the remainder of a by b (b trimmed, non-empty),
/// without division: the pseudo-remainder lc^k a mod b, lc = b's leading
/// coefficient and k the number of elimination steps, times sign(lc)^k so
/// that the multiple is positive (Sturm's sequence needs the signs of the
/// remainders, not their sizes). The content is divided out.
inline Poly positiveRemainder(Poly a, const Poly& b) {
  trim(a);
  const size_t nb = b.size();
  const mpz_class& lc = b.back();
  int k = 0;
  while (a.size() >= nb) {
    const mpz_class f = a.back();
    const size_t shift = a.size() - nb;
    for (auto& c : a) c *= lc;
    for (size_t i = 0; i < nb; ++i) a[shift + i] -= f * b[i];
    ++k;
    a.pop_back();  // its leading coefficient is now exactly 0
    trim(a);
  }
  if (sgn(lc) < 0 && k % 2 == 1)
    for (auto& c : a) c = -c;
  mpz_class g = 0;
  for (const auto& c : a) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), c.get_mpz_t());
  if (sgn(g) > 0 && g != 1)
    for (auto& c : a) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
  return a;
}

/// Number of distinct real roots of p in (0, 1), for p(0) != 0, p(1) != 0
/// (Sturm's theorem: sign variations of the sequence at 0 minus at 1; the
/// value of a polynomial at 0 is its constant term, at 1 the sum of its
/// coefficients). The sequence p, p', -rem(p, p'), ... is taken up to
/// positive factors, which leave every variation count unchanged.
inline int rootsInUnit(Poly p) {
  trim(p);
  if (p.size() <= 1) return 0;
  std::vector<Poly> chain;
  chain.push_back(p);
  Poly d;
  for (size_t i = 1; i < p.size(); ++i) d.push_back(p[i] * int(i));
  trim(d);
  // Every remainder loses its content (a gcd per step). Collins' reduced
  // PRS (dividing by lc^(delta + 1) of the previous divisor, no gcd) was
  // tried and measured slower, by callgrind, on the harness's tie-heavy
  // margins (1.6x the instructions in this function) and on hostile inputs
  // (2 to 3x): the pseudo-remainders of these quartics carry common
  // factors much larger than the reduced PRS's, which the content removes.
  while (!d.empty()) {
    chain.push_back(d);
    Poly r = positiveRemainder(chain[chain.size() - 2], d);
    for (auto& c : r) c = -c;
    d = std::move(r);
  }
  auto variations = [&](bool at_one) {
    int v = 0, last = 0;
    for (const Poly& q : chain) {
      mpz_class val = q[0];
      if (at_one)
        for (size_t i = 1; i < q.size(); ++i) val += q[i];
      const int s = sgn(val);
      if (s == 0) continue;
      if (last != 0 && s != last) ++v;
      last = s;
    }
    return v;
  };
  return variations(false) - variations(true);
}

/// Divides a, b (and c, if given) by the largest power of two they share
/// (a positive factor: Sturm's sequence keeps its signs).
inline void dropCommonTwos(mpz_class& a, mpz_class& b, mpz_class* c = nullptr) {
  mpz_class* x[3] = {&a, &b, c};
  mp_bitcnt_t tz = ~mp_bitcnt_t(0);
  for (mpz_class* v : x)
    if (v != nullptr && sgn(*v) != 0)
      tz = std::min(tz, mpz_scan1(v->get_mpz_t(), 0));
  if (tz == ~mp_bitcnt_t(0) || tz == 0) return;
  for (mpz_class* v : x)
    if (v != nullptr) mpz_tdiv_q_2exp(v->get_mpz_t(), v->get_mpz_t(), tz);
}

/// The sign of a w^2 - b u w + c u^2 (GMP integers), from the leading 53
/// bits of each first. mpz_get_d_2exp gives x = f 2^k (1 + eps) with
/// 0.5 <= |f| < 1 and 0 <= eps < 2^-52 (it truncates), so each term is
/// m 2^e (1 + eps') with m the rounded product of three f (1/8 <= |m| < 1,
/// two roundings) and |eps'| < 2^-49. Scaled by the largest 2^e (exactly,
/// a term more than 2^-1000 below it dropped and charged 2^-1000), summed
/// with two roundings (2^-52 of the sum of magnitudes): the computed sum S
/// is within 2^-48 sum|s_i| + 2^-998 of the true one, so |S| beyond
/// 2^-47 sum|s_i| + 2^-997 gives the sign. Else the exact products (of
/// about 60,000 bits in the near-tangencies of wide inputs).
inline int signQuadraticAtRoot(const mpz_class& a, const mpz_class& b,
                               const mpz_class& c, const mpz_class& u,
                               const mpz_class& w) {
  const mpz_class* x[5] = {&a, &b, &c, &u, &w};
  double f[5];
  long k[5];
  for (int i = 0; i < 5; ++i) f[i] = mpz_get_d_2exp(&k[i], x[i]->get_mpz_t());
  // a w^2, -b u w, c u^2 (zero factors give an exactly zero term).
  const double m[3] = {f[0] * f[4] * f[4], -(f[1] * f[3] * f[4]),
                       f[2] * f[3] * f[3]};
  const long e[3] = {k[0] + 2 * k[4], k[1] + k[3] + k[4], k[2] + 2 * k[3]};
  long top = std::numeric_limits<long>::min();
  for (int i = 0; i < 3; ++i)
    if (m[i] != 0) top = std::max(top, e[i]);
  if (top != std::numeric_limits<long>::min()) {
    double sum = 0, mag = 0, slack = 0x1p-997;
    for (int i = 0; i < 3; ++i) {
      if (m[i] == 0) continue;
      if (e[i] - top < -1000) {
        slack += 0x1p-1000;
        continue;
      }
      const double si = std::ldexp(m[i], int(e[i] - top));
      sum += si;
      mag += std::fabs(si);
    }
    if (sum > mag * 0x1p-47 + slack) return 1;
    if (sum < -(mag * 0x1p-47 + slack)) return -1;
  }
  return sgn(a * w * w - b * u * w + c * u * u);
}

/// rootsInUnit for the quartic of a torus edge, Q = L^2 - 4 R^2 P with
/// L = l0 + l1 s + l2 s^2 and l2 > 0, so that q4 = l2^2 and q3 = 2 l1 l2
/// (q = Q's coefficients, lowest first; Q(0), Q(1) != 0), without a gcd.
/// The Sturm sequence P0 = Q, P1 = Q' = d3 s^3 + d2 s^2 + d1 s + d0, then
/// positive multiples of the negated remainders, in closed form:
///  - Q = (s/4 + l1/(8 l2)) Q' + rem(Q, Q') (the quotient from q4 = l2^2
///    and q3 = 2 l1 l2), so P2 = (2 l2 s + l1) Q' - 8 l2 Q = -8 l2 rem, an
///    integer quadratic a s^2 + b s + c (its s^4 and s^3 terms cancel
///    identically). The generic pseudo-remainder is 2 l2^3 times it and
///    left the gcd to find that (of about 20,000 bits on inputs that span
///    2000 binary orders, the bulk of the sequence's cost).
///  - With s^2 = -(b s + c)/a and s^3 = ((b^2 - a c) s + b c)/a^2 modulo
///    P2, a^2 rem(Q', P2) = (d3 (b^2 - a c) - a b d2 + a^2 d1) s +
///    (d3 b c - a c d2 + a^2 d0), and P3 = u s + w is its negation.
///    (On those inputs u and w share the factor l2^2 R^2 as well; testing
///    and dividing it out cost more than it saved in the last step.)
///  - u^2 rem(P2, P3) = u^2 P2(-w/u) = a w^2 - b u w + c u^2, a constant,
///    and P4 is its negation (signQuadraticAtRoot; only when its sign can
///    change the count).
/// Common powers of two are dropped at each step. Where a degree drops
/// (a = 0 or u = 0: exact degeneracies) the generic rootsInUnit decides.
/// The sequence's values at 0 and 1 are its constant terms and its
/// coefficient sums.
inline int rootsInUnitTorus(const mpz_class* q, const mpz_class& l1,
                            const mpz_class& l2) {
  if (sgn(l2) <= 0) return rootsInUnit(Poly(q, q + 5));
  const mpz_class d0 = q[1], d1 = 2 * q[2], d2 = 3 * q[3], d3 = 4 * q[4];
  const mpz_class l2x2 = 2 * l2, l2x8 = 8 * l2;
  mpz_class a = l1 * d2 + l2x2 * d1 - l2x8 * q[2];
  mpz_class b = l1 * d1 + l2x2 * d0 - l2x8 * q[1];
  mpz_class c = l1 * d0 - l2x8 * q[0];
  if (sgn(a) == 0) return rootsInUnit(Poly(q, q + 5));
  dropCommonTwos(a, b, &c);
  const mpz_class aa = a * a;
  mpz_class u = a * b * d2 - d3 * (b * b - a * c) - aa * d1;
  mpz_class w = a * c * d2 - d3 * b * c - aa * d0;
  if (sgn(u) == 0) return rootsInUnit(Poly(q, q + 5));
  dropCommonTwos(u, w);
  const mpz_class q_one = q[0] + q[1] + q[2] + q[3] + q[4];
  const mpz_class d_one = d0 + d1 + d2 + d3;
  int at0[5] = {sgn(q[0]), sgn(d0), sgn(c), sgn(w), 0};
  int at1[5] = {sgn(q_one), sgn(d_one), sgn(a + b + c), sgn(u + w), 0};
  auto lastNonZero = [](const int* v) {
    int last = 0;
    for (int i = 0; i < 4; ++i)
      if (v[i] != 0) last = v[i];
    return last;
  };
  // P4 is a constant, the same at 0 and 1: it adds the same variation to
  // both counts unless the last nonzero sign before it differs.
  if (lastNonZero(at0) != lastNonZero(at1))
    at0[4] = at1[4] = -signQuadraticAtRoot(a, b, c, u, w);
  auto variations = [](const int* v) {
    int n = 0, last = 0;
    for (int i = 0; i < 5; ++i) {
      if (v[i] == 0) continue;
      if (last != 0 && v[i] != last) ++n;
      last = v[i];
    }
    return n;
  };
  return variations(at0) - variations(at1);
}

// ---- A local certificate for wide torus edges -----------------------------
//
// On wide inputs (coordinates spanning thousands of binary orders) Q's
// coefficients have 10,000 - 15,000 bits and its Sturm sequence's last
// constant (Q's discriminant, near zero at a near-tangency) 60,000 or more:
// milliseconds. torusEdgeCertificate decides most of those edges from one
// point instead. With L > 0 on [0, 1] (edgeExact's step 1) and rho =
// sqrt(P) >= 0, Q = (L - 2 R rho)(L + 2 R rho) and L + 2 R rho > 0, so
// Q <= 0 somewhere iff F = L - 2 R rho (the squared distance to the rim
// circle minus M^2, in the edge's parameter) is <= 0 somewhere:
//  - a hit: Q(s0) <= 0 at a dyadic s0 = m / 2^k in [0, 1], exactly;
//  - a miss: for any lambda > 0, 2 R rho <= lambda rho^2 + R^2 / lambda
//    (AM-GM), so lambda L - lambda^2 P - R^2 > 0 on [0, 1], a quadratic
//    in s (integer coefficients for a dyadic lambda = a / 2^j after a
//    factor 2^(2j)), gives L > 2 R rho: Q > 0 on [0, 1].
// The bound loses lambda (rho - R / lambda)^2, zero where rho = R / lambda:
// lambda = R / rho(s*) at F's minimiser s* makes the quadratic touch F from
// below there (its curvature exceeds F_lambda's where rho > R |E_xy|^2 /
// |E|^2, which covers edges outside the rim radius). s* is found in GMP
// floats (minima of Q at 128 bits to choose the branch, then Newton on F',
// whose minimum is simple where Q's may be a cluster: Q = F (F + 4 R rho)
// has three nearby critical points when R rho is small), at 2^-k with k
// doubling until a certificate holds; the floats only choose s0 and lambda,
// every decision is exact. An exact tangency (min F = 0), two near-zero
// minima, or an edge inside the rim radius where the bound is too loose is
// left to the Sturm count (-1), which decides every case.

namespace cert {

/// floor(log2 |x|) (a large negative value for 0).
inline long ilog2(const mpz_class& x) {
  return sgn(x) == 0 ? std::numeric_limits<long>::min() / 4
                     : long(mpz_sizeinbase(x.get_mpz_t(), 2)) - 1;
}
inline long ilog2(const mpf_class& x) {
  if (sgn(x) == 0) return std::numeric_limits<long>::min() / 4;
  long e = 0;
  mpf_get_d_2exp(&e, x.get_mpf_t());  // |x| = f 2^e, 0.5 <= |f| < 1
  return e - 1;
}

/// Horner on integer coefficients (lowest first, n of them) at x, in x's
/// precision.
inline mpf_class evalAt(const mpz_class* c, int n, const mpf_class& x) {
  mpf_class v(0, x.get_prec());
  for (int i = n; i-- > 0;) {
    v *= x;
    v += mpf_class(c[i], x.get_prec());
  }
  return v;
}

/// The coefficients of f(1 - s) for f of degree n - 1 (the edge walked from
/// its other end): a Taylor shift by 1, then odd coefficients negated.
inline void reversed(const mpz_class* f, int n, mpz_class* r) {
  for (int i = 0; i < n; ++i) r[i] = f[i];
  for (int i = 0; i + 1 < n; ++i)
    for (int j = n - 2; j >= i; --j) r[j] += r[j + 1];
  for (int i = 1; i < n; i += 2) r[i] = -r[i];
}

/// 2^x as a GMP float.
inline mpf_class pow2(long e, unsigned prec) {
  mpf_class x(1, prec);
  if (e >= 0)
    mpf_mul_2exp(x.get_mpf_t(), x.get_mpf_t(), mp_bitcnt_t(e));
  else
    mpf_div_2exp(x.get_mpf_t(), x.get_mpf_t(), mp_bitcnt_t(-e));
  return x;
}

inline int sgn(double v) { return (v > 0) - (v < 0); }

/// The bracketed search of both minima finders: a root of P' (increasing
/// on [a, b], P'(a) < 0 < P'(b)); Newton while |P'| drops eightfold a step
/// (its quadratic phase), else bisect with mid(a, b): far from the roots,
/// or near a cluster of them, Newton's steps shrink x by a constant ratio
/// only. `eval(c, n, x)` evaluates n coefficients at x, `num(v)` makes a
/// number of the working precision, `done(a, b)` ends the search.
template <class T, class C, class Eval, class Num, class Mid, class Done>
T bracketedRoot(const C* d, const C* e, T a, T b, Eval eval, Num num, Mid mid,
                Done done, int max_it) {
  using std::abs;
  T x = mid(a, b), prev = num(0);
  bool have_prev = false;
  for (int it = 0; it < max_it; ++it) {
    const T f = eval(d, 4, x);
    if (sgn(f) == 0) break;
    (sgn(f) < 0 ? a : b) = x;
    if (done(a, b)) break;
    const T fp = eval(e, 3, x);
    if (sgn(fp) > 0 && (!have_prev || abs(f) <= num(abs(prev) / 8))) {
      const T xn = num(x - f / fp);
      prev = f;
      have_prev = true;
      if (xn > a && xn < b) {
        x = xn;
        continue;
      }
    }
    have_prev = false;
    x = mid(a, b);
  }
  return x;
}

/// Approximate local minima of P (degree 4, P4 > 0) in (0, 1/2): the
/// roots of P' where it changes sign from - to +, between consecutive
/// roots of P'' (P' is monotone between them). Bracketed Newton with
/// bisection (geometric across binary orders: features near 0 may sit at
/// 2^-1000 of the edge), in `prec`-bit GMP floats, to about 2^-40 of x.
/// Heuristic by design: only the choice of s0 depends on it.
inline void minimaInHalf(const mpz_class* p, unsigned prec,
                         std::vector<mpf_class>* out) {
  const mpz_class d[4] = {p[1], 2 * p[2], 3 * p[3], 4 * p[4]};
  const mpz_class e[3] = {d[1], 2 * d[2], 3 * d[3]};
  std::vector<mpf_class> pts{mpf_class(0, prec)};
  const mpz_class disc = e[1] * e[1] - 4 * e[0] * e[2];
  if (sgn(disc) > 0 && sgn(e[2]) != 0) {
    mpf_class sq(disc, prec);
    sq = sqrt(sq);
    mpf_class qq(e[1], prec);
    qq = sgn(e[1]) >= 0 ? mpf_class(-(qq + sq) / 2, prec)
                        : mpf_class((sq - qq) / 2, prec);
    if (sgn(qq) != 0) {
      mpf_class r1(qq / mpf_class(e[2], prec), prec),
          r2(mpf_class(e[0], prec) / qq, prec);
      if (r1 > r2) std::swap(r1, r2);
      for (const mpf_class& r : {r1, r2})
        if (sgn(r) > 0 && r < 0.5) pts.push_back(r);
    }
  }
  pts.push_back(mpf_class(0.5, prec));
  long top = ilog2(d[0]);
  for (int i = 1; i < 4; ++i) top = std::max(top, ilog2(d[i]));
  // Positive roots of P' are >= |d0| / (|d0| + max |d_i|) (Cauchy).
  const long floor_e = ilog2(d[0]) - top - 3;
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    mpf_class a(pts[i], prec), b(pts[i + 1], prec);
    if (!(sgn(evalAt(d, 4, a)) < 0 && sgn(evalAt(d, 4, b)) > 0)) continue;
    auto mid = [&](const mpf_class& lo, const mpf_class& hi) {
      const long eb = ilog2(hi), ea = sgn(lo) == 0 ? floor_e : ilog2(lo);
      if (eb - ea > 2) return pow2((ea + eb) / 2, prec);
      return mpf_class((lo + hi) / 2, prec);
    };
    const mpf_class x = bracketedRoot(
        d, e, a, b, evalAt, [prec](auto v) { return mpf_class(v, prec); }, mid,
        [prec](const mpf_class& lo, const mpf_class& hi) {
          mpf_class w(hi, prec);
          mpf_div_2exp(w.get_mpf_t(), w.get_mpf_t(), 40);
          return hi - lo <= w;
        },
        200);
    out->push_back(x);
  }
}

/// Approximate local minima of T (t[0..4], t[4] > 0, as doubles after a
/// common power-of-two scale) in (lo, hi), features of order 1 (the window
/// below): as minimaInHalf, in doubles with arithmetic bisection, to about
/// 2^-40 (Newton in GMP floats refines it).
inline void minimaIn(const double* t, double lo, double hi,
                     std::vector<double>* out) {
  const double d[4] = {t[1], 2 * t[2], 3 * t[3], 4 * t[4]};
  const double e[3] = {d[1], 2 * d[2], 3 * d[3]};
  auto eval = [](const double* c, int n, double x) {
    double v = 0;
    for (int i = n; i-- > 0;) v = v * x + c[i];
    return v;
  };
  std::vector<double> pts{lo};
  const double disc = e[1] * e[1] - 4 * e[0] * e[2];
  if (disc > 0 && e[2] != 0) {
    const double sq = std::sqrt(disc);
    const double qq = e[1] >= 0 ? -(e[1] + sq) / 2 : (sq - e[1]) / 2;
    if (qq != 0) {
      double r1 = qq / e[2], r2 = e[0] / qq;
      if (r1 > r2) std::swap(r1, r2);
      for (double r : {r1, r2})
        if (r > lo && r < hi) pts.push_back(r);
    }
  }
  pts.push_back(hi);
  for (size_t i = 0; i + 1 < pts.size(); ++i) {
    double a = pts[i], b = pts[i + 1];
    if (!(eval(d, 4, a) < 0 && eval(d, 4, b) > 0)) continue;
    const double x = bracketedRoot(
        d, e, a, b, eval, [](double v) { return v; },
        [](double u, double v) { return (u + v) / 2; },
        [](double u, double v) { return v - u <= 0x1p-40; }, 120);
    out->push_back(x);
  }
}

/// Magnitudes A = fa 2^ea and B = fb 2^eb known to a relative error below
/// 2^-49 each, with fa, fb in [2^-4, 1): 1 if certainly A > B, -1 if
/// certainly A < B, 0 if they agree to about 2^-45. ea - eb >= 5 gives
/// A > B (A >= 2^(ea - 4) (1 - 2^-49) > 2^eb (1 + 2^-49) > B), and
/// symmetrically; else fa 2^(ea - eb) (exact: the shift is at most 4
/// either way and fa >= 2^-4) is compared with fb with a relative slack of
/// 2^-45, far above the two errors and the slack's own rounding (2^-53).
inline int compareLeading(double fa, long ea, double fb, long eb) {
  if (ea - eb >= 5) return 1;
  if (eb - ea >= 5) return -1;
  const double x = std::ldexp(fa, int(ea - eb));
  if (x > fb * (1 + 0x1p-45)) return 1;
  if (x * (1 + 0x1p-45) < fb) return -1;
  return 0;
}

/// |x_1 ... x_n| (n <= 4, every x nonzero) as f 2^e with f in [2^-4, 1) and
/// a relative error below 2^-49; returns the product's sign (0 if some x
/// is 0). mpz_get_d_2exp truncates, so |x| = g 2^k (1 + d) with
/// 0.5 <= g < 1 and 0 <= d < 2^-52; the product of the g's in double
/// (n - 1 <= 3 roundings of 2^-53, no underflow: each g >= 1/2) is the
/// product of the |x| / 2^k up to a factor in (1 - 2^-51, 1 + 2^-49):
/// (1 + 2^-52)^4 (1 + 2^-53)^3 < 1 + 2^-49.
inline int leadingProduct(std::initializer_list<const mpz_class*> xs, double* f,
                          long* e) {
  int s = 1;
  *f = 1;
  *e = 0;
  for (const mpz_class* x : xs) {
    const int sx = mpz_sgn(x->get_mpz_t());
    if (sx == 0) return 0;
    long k = 0;
    *f *= std::fabs(mpz_get_d_2exp(&k, x->get_mpz_t()));
    *e += k;
    s *= sx;
  }
  return s;
}

/// The sign of 2^sa (a_1 ... a_n) - 2^sb (b_1 ... b_m) for integers a_i,
/// b_j (1 <= n, m <= 4), from their leading 53 bits (leadingProduct,
/// compareLeading) where they decide it, else from the exact products
/// (`exact`, if given, flags that fallback). Only where the two sides agree
/// to about 2^-45 are the exact products formed: for the integers of
/// thousands of bits of the torus edges' exact stage that saves their
/// products in nearly every test.
inline int signProductDifference(std::initializer_list<const mpz_class*> a,
                                 long sa,
                                 std::initializer_list<const mpz_class*> b,
                                 long sb, bool* exact = nullptr) {
  double fa = 0, fb = 0;
  long ea = 0, eb = 0;
  const int sga = leadingProduct(a, &fa, &ea),
            sgb = leadingProduct(b, &fb, &eb);
  if (exact != nullptr) *exact = false;
  if (sga == 0 || sgb == 0 || sga != sgb) return sga != 0 ? sga : -sgb;
  const int c = compareLeading(fa, ea + sa, fb, eb + sb);
  if (c != 0) return c * sga;
  if (exact != nullptr) *exact = true;
  auto product = [](std::initializer_list<const mpz_class*> xs, long sh) {
    mpz_class p = 1;
    for (const mpz_class* x : xs) p *= *x;
    mpz_mul_2exp(p.get_mpz_t(), p.get_mpz_t(), mp_bitcnt_t(sh));
    return p;
  };
  // Both sides divided by 2^min(sa, sb) (a positive factor).
  const long m = std::min(sa, sb);
  return sgn(product(a, sa - m) - product(b, sb - m));
}

/// c_1^2 + ... + c_n^2 (n <= 3) from leading bits, as f 2^e with f in
/// [1/2, 1); false if every c is 0. The sum has no cancellation: with each
/// |c_i| = g_i 2^k_i (1 + d_i) as in leadingProduct, the terms g_i^2 2^(2 k_i -
/// E) (E the largest 2 k_i; each term at most 1, the largest at least 1/4)
/// summed in double are the sum over 2^E up to a factor in (1 - 2^-50, 1 +
/// 2^-49)
/// ((1 + 2^-52)^2 per square, 2^-53 per rounding, at most 5 roundings;
/// a term that underflows loses below 2^-1074, far below 2^-60 of the
/// sum); frexp brings it to [1/2, 1) exactly.
inline bool leadingSquares(std::initializer_list<const mpz_class*> c, double* f,
                           long* e) {
  long e_max = std::numeric_limits<long>::min();
  double g[3] = {0, 0, 0};
  long e2[3] = {0, 0, 0};
  int n = 0;
  for (const mpz_class* x : c) {
    if (mpz_sgn(x->get_mpz_t()) == 0) continue;
    long kx = 0;
    const double gx = mpz_get_d_2exp(&kx, x->get_mpz_t());
    g[n] = gx * gx;
    e2[n] = 2 * kx;
    e_max = std::max(e_max, e2[n]);
    ++n;
  }
  if (n == 0) return false;
  double sum = 0;
  for (int i = 0; i < n; ++i)
    sum += std::ldexp(g[i], int(std::max(e2[i] - e_max, -2000L)));
  int fe = 0;
  *f = std::frexp(sum, &fe);
  *e = e_max + fe;
  return true;
}

/// The sign of c_1^2 + ... + c_n^2 + k_1 ... k_m (n <= 3, 1 <= m <= 4),
/// leading bits first (leadingSquares, leadingProduct, compareLeading),
/// exact where the two sides agree to about 2^-45.
inline int signSquaresPlusProduct(std::initializer_list<const mpz_class*> c,
                                  std::initializer_list<const mpz_class*> k,
                                  bool* exact = nullptr) {
  if (exact != nullptr) *exact = false;
  double ft = 0, fs = 0;
  long et = 0, es = 0;
  const int st = leadingProduct(k, &ft, &et);
  if (!leadingSquares(c, &fs, &es)) return st;  // the squares are 0
  if (st >= 0) return 1;  // a positive sum and a term >= 0
  const int cmp = compareLeading(fs, es, ft, et);
  if (cmp != 0) return cmp;
  if (exact != nullptr) *exact = true;
  mpz_class v = 1;
  for (const mpz_class* x : k) v *= *x;
  for (const mpz_class* x : c) v += *x * *x;
  return sgn(v);
}

/// The sign of c_1^2 + ... + c_n^2 + k_1 ... k_m (e_1^2 + ... + e_l^2)
/// (n, l <= 3, 1 <= m <= 4), leading bits first: as signSquaresPlusProduct
/// with the product's last factor a sum of squares that is never formed
/// unless the two sides agree to about 2^-45 (for |A x E|^2 + K |E|^2 it
/// saves the three squares of |E|^2, each of the inputs' size squared).
/// The product side is k's leading product (relative error below 2^-49,
/// in [2^-4, 1)) times e's leading sum (below 2^-49, in [1/2, 1)), rounded
/// once (2^-53) and brought to [1/2, 1) by frexp (exact): its error is
/// below (1 + 2^-49)^2 (1 + 2^-53) - 1 < 2^-47.9, and compareLeading's
/// slack of 2^-45 still separates (1 + 2^-45) (1 - 2^-47.9) > 1 + 2^-47.9;
/// its shortcut for exponents 5 apart holds a fortiori.
inline int signSquaresPlusProductSquares(
    std::initializer_list<const mpz_class*> c,
    std::initializer_list<const mpz_class*> k,
    std::initializer_list<const mpz_class*> e, bool* exact = nullptr) {
  if (exact != nullptr) *exact = false;
  double ft = 0, fe = 0, fs = 0;
  long et = 0, ee = 0, es = 0;
  const int sk = leadingProduct(k, &ft, &et);
  const int st = leadingSquares(e, &fe, &ee) ? sk : 0;
  if (!leadingSquares(c, &fs, &es)) return st;  // the squares are 0
  if (st >= 0) return 1;  // a positive sum and a term >= 0
  int fp = 0;
  const double f = std::frexp(ft * fe, &fp);
  const int cmp = compareLeading(fs, es, f, et + ee + fp);
  if (cmp != 0) return cmp;
  if (exact != nullptr) *exact = true;
  mpz_class v = 1, w = 0;
  for (const mpz_class* x : k) v *= *x;
  for (const mpz_class* x : e) w += *x * *x;
  v *= w;
  for (const mpz_class* x : c) v += *x * *x;
  return sgn(v);
}

/// Is a0 + a1 s + a2 s^2 > 0 on [0, 1]? (At the ends, and at the vertex
/// -a1 / (2 a2) of a convex parabola when inside: 4 a0 a2 > a1^2, compared
/// on leading bits first.)
inline bool quadraticPositive(const mpz_class& a0, const mpz_class& a1,
                              const mpz_class& a2) {
  if (sgn(a0) <= 0 || sgn(a0 + a1 + a2) <= 0) return false;
  if (sgn(a2) > 0 && sgn(a1) < 0 && a1 + 2 * a2 > 0)
    return signProductDifference({&a0, &a2}, 2, {&a1, &a1}, 0) > 0;
  return true;
}

/// The hit test at s0 = m / 2^k: 2^(4k) Q(s0) = Ls^2 - 4 R^2 Ps 2^(2k)
/// <= 0, Ls = 2^(2k) L(s0) (> 0 by the precondition), Ps = 2^(2k) P(s0)
/// (Horner with shifts).
inline bool hitAt(const mpz_class* L, const mpz_class* P, const mpz_class& R2,
                  const mpz_class& m, long k) {
  auto at = [&m, k](const mpz_class* c) {
    mpz_class v = c[2] * m, t = c[1];
    mpz_mul_2exp(t.get_mpz_t(), t.get_mpz_t(), mp_bitcnt_t(k));
    v += t;
    v *= m;
    t = c[0];
    mpz_mul_2exp(t.get_mpz_t(), t.get_mpz_t(), mp_bitcnt_t(2 * k));
    return mpz_class(v + t);
  };
  const mpz_class ls = at(L), ps = at(P);
  return signProductDifference({&ls, &ls}, 0, {&R2, &ps}, 2 * k + 2) <= 0;
}

/// The AM-GM certificate with lambda = a / 2^j, a the leading `bits` bits
/// of `lam` (> 0): lambda L - lambda^2 P - R^2 > 0 on [0, 1], times
/// 2^(2j): a 2^j L - a^2 P - R^2 2^(2j), a quadratic with integer
/// coefficients. True: Q > 0 on [0, 1].
inline bool amgmCertificate(const mpz_class* L, const mpz_class* P,
                            const mpz_class& R2, const mpf_class& lam,
                            long bits) {
  long j = bits - ilog2(lam);
  mpf_class lam_s(lam, lam.get_prec());
  if (j >= 0)
    mpf_mul_2exp(lam_s.get_mpf_t(), lam_s.get_mpf_t(), mp_bitcnt_t(j));
  else
    mpf_div_2exp(lam_s.get_mpf_t(), lam_s.get_mpf_t(), mp_bitcnt_t(-j));
  mpz_class a(lam_s);
  if (sgn(a) <= 0) return false;
  if (j < 0) {
    mpz_mul_2exp(a.get_mpz_t(), a.get_mpz_t(), mp_bitcnt_t(-j));
    j = 0;
  }
  mpz_class a2j = a;  // a 2^j
  mpz_mul_2exp(a2j.get_mpz_t(), a2j.get_mpz_t(), mp_bitcnt_t(j));
  mpz_class r2j = R2;  // R^2 2^(2j)
  mpz_mul_2exp(r2j.get_mpz_t(), r2j.get_mpz_t(), mp_bitcnt_t(2 * j));
  const mpz_class aa = a * a;
  return quadraticPositive(a2j * L[0] - aa * P[0] - r2j, a2j * L[1] - aa * P[1],
                           a2j * L[2] - aa * P[2]);
}

/// The quartic certificate at s0 = m / 2^k: with P(tau) = 2^(4k)
/// Q((m + tau) / 2^k) = C0 + C1 tau + tau^2 H(tau), H = C2 + C3 tau +
/// C4 tau^2 (the Taylor shift of Q's scaled coefficients, integers), tau in
/// [lo, hi] = [-m, 2^k - m] (s in [0, 1]): H's least value there, h, is at
/// an end or at the vertex -C3 / (2 C4) (value (4 C2 C4 - C3^2) / (4 C4),
/// C4 = q4 > 0); h > 0 and C1^2 < 4 C0 h give P >= C0 + C1 tau + h tau^2
/// > 0. Returns 0 (Q > 0 on [0, 1]), 1 (C0 <= 0: Q(s0) <= 0), -1, or 2
/// when H < 0 at its vertex inside: Q has two more real roots near it,
/// whose position (in s) is put in *other.
/// Tight where Q's minimum is a cluster of critical points (the AM-GM
/// bound's blind spot, edges through the hole), loose only where Q has
/// another root region in [0, 1].
inline int taylorCertificate(const mpz_class* q, const mpz_class& m, long k,
                             mpf_class* other) {
  mpz_class c[5];
  for (int i = 0; i < 5; ++i)
    mpz_mul_2exp(c[i].get_mpz_t(), q[i].get_mpz_t(), mp_bitcnt_t(k) * (4 - i));
  for (int i = 0; i < 4; ++i)
    for (int j = 3; j >= i; --j) c[j] += m * c[j + 1];
  if (sgn(c[0]) <= 0) return 1;
  mpz_class lo = -m, hi = 1;
  mpz_mul_2exp(hi.get_mpz_t(), hi.get_mpz_t(), mp_bitcnt_t(k));
  hi -= m;
  // C1^2 against 4 C0 h and C1^2 C4 against C0 (4 C4 h) on leading bits
  // first (signProductDifference).
  for (const mpz_class* t : {&lo, &hi}) {
    const mpz_class h = c[2] + *t * (c[3] + c[4] * *t);
    if (sgn(h) <= 0 ||
        signProductDifference({&c[1], &c[1]}, 0, {&c[0], &h}, 2) >= 0)
      return -1;
  }
  const mpz_class v2 = -c[3];  // the vertex times 2 C4
  if (v2 > 2 * c[4] * lo && v2 < 2 * c[4] * hi) {
    const mpz_class hv = 4 * c[2] * c[4] - c[3] * c[3];  // 4 C4 h
    if (sgn(hv) <= 0) {
      // H ~ C4 (tau - r3)(tau - r4) for Q's other two roots: they are
      // real, near the vertex. It is where to look next.
      mpf_class t(v2, mp_bitcnt_t(k + 64));
      t /= mpf_class(2 * c[4], mp_bitcnt_t(k + 64));
      t += mpf_class(m, mp_bitcnt_t(k + 64));
      mpf_div_2exp(t.get_mpf_t(), t.get_mpf_t(), mp_bitcnt_t(k));
      *other = t;
      return 2;
    }
    if (signProductDifference({&c[1], &c[1], &c[4]}, 0, {&c[0], &hv}, 0) >= 0)
      return -1;
  }
  return 0;
}

}  // namespace cert

/// The torus edge with L = l0 + l1 s + l2 s^2 > 0 on [0, 1], rho^2 = P =
/// p0 + p1 s + p2 s^2 (>= 0), rim radius R >= 0, tube radius M >= 0 and
/// Q = L^2 - 4 R^2 P (q,
/// lowest first, q[4] > 0): 1 if Q <= 0 somewhere on [0, 1], 0 if not, -1
/// if not decided here (see above). `max_k` bounds the bits of s0.
/// What one edge's certificate learnt, for the same edge against the other
/// rim torus (the two differ only in the rim's height, and on the hostile
/// inputs where the certificate runs the cylinder's length is often
/// negligible: the two minima agree to many bits): the direction, the
/// minimiser, and the bits and value at which that minimum was resolved.
/// Only a starting point: the other torus's run uses it where its own search
/// lands within 2^-20 of it, and resolves its own value (a level whose value
/// agrees with the hint's to 2^-8, the test between two levels of one run).
struct CertHint {
  bool valid = false;
  int dir = 0;
  mpf_class x, v;
  long k = 0;
};

inline int torusEdgeCertificate(const mpz_class* q, const mpz_class* l,
                                const mpz_class* p, const mpz_class& R,
                                const mpz_class& M, long max_k,
                                CertHint* hint = nullptr) {
  if (sgn(R) == 0) return 0;  // Q = L^2 > 0
  if (sgn(q[4]) <= 0) return -1;
  mpz_class qr[5], lr[3], pr[3];
  cert::reversed(q, 5, qr);
  cert::reversed(l, 3, lr);
  cert::reversed(p, 3, pr);
  const mpz_class* qs[2] = {q, qr};
  // The candidate with the least value of Q chooses the direction. Q <= 0
  // only inside the ball |p - o| <= R + M, i.e. within (R + M) / |E| of
  // L's vertex s_c = -l1 / (2 l2) (L = |p - o|^2 + R^2 - M^2): where that
  // window is narrow (g binary orders below the edge), Q is searched in
  // it, as T(u) = Q(s_c + u 2^-g) on |u| <= 2 (features of order 1; its
  // coefficients formed once at the precision the cancellation needs),
  // else on [0, 1/2] from either end.
  int dir = -1;
  mpf_class x(0, 128), best_v(0, 128);
  const long g =
      (cert::ilog2(l[2]) - 1) / 2 - cert::ilog2(mpz_class(R + M)) - 2;
  if (g > 16) {
    const unsigned hp = unsigned(
        4 * g + 192 +
        std::max(0L, -cert::ilog2(mpf_class(l[1], 64) / mpf_class(l[2], 64))));
    const mpf_class sc(-mpf_class(l[1], hp) / (2 * mpf_class(l[2], hp)), hp);
    mpf_class t[5];
    for (int i = 0; i < 5; ++i) {
      t[i].set_prec(hp);
      t[i] = q[i];
    }
    for (int i = 0; i < 4; ++i)
      for (int j = 3; j >= i; --j) t[j] += sc * t[j + 1];
    // T's coefficients as doubles, scaled by a common power of two.
    long top_t = std::numeric_limits<long>::min();
    for (int i = 0; i < 5; ++i) {
      mpf_div_2exp(t[i].get_mpf_t(), t[i].get_mpf_t(), mp_bitcnt_t(g * i));
      if (sgn(t[i]) != 0) top_t = std::max(top_t, cert::ilog2(t[i]));
    }
    double tl[5];
    for (int i = 0; i < 5; ++i) {
      long ex = 0;
      const double f = mpf_get_d_2exp(&ex, t[i].get_mpf_t());
      tl[i] = ex - 1 - top_t < -1000 ? 0.0 : std::ldexp(f, int(ex - top_t));
    }
    std::vector<double> us;
    if (tl[4] > 0) cert::minimaIn(tl, -2, 2, &us);
    for (double u : us) {
      double v = 0;
      for (int i = 5; i-- > 0;) v = v * u + tl[i];
      mpf_class sv(u, hp);
      mpf_div_2exp(sv.get_mpf_t(), sv.get_mpf_t(), mp_bitcnt_t(g));
      sv += sc;
      if (sgn(sv) < 0 || sv > 1) continue;
      if (dir < 0 || v < best_v) {
        dir = sv > 0.5 ? 1 : 0;
        x.set_prec(hp);
        x = dir == 0 ? sv : mpf_class(1 - sv, hp);
        best_v = v;
      }
    }
  } else {
    for (int w = 0; w < 2; ++w) {
      std::vector<mpf_class> xs;
      cert::minimaInHalf(qs[w], 128, &xs);
      for (const mpf_class& xc : xs) {
        const mpf_class v = cert::evalAt(qs[w], 5, xc);
        if (dir < 0 || v < best_v) {
          dir = w;
          x = xc;
          best_v = v;
        }
      }
    }
  }
  if (dir < 0) return -1;
  bool seeded = false;
  if (hint != nullptr && hint->valid && hint->dir == dir && sgn(x) > 0 &&
      cert::ilog2(mpf_class(abs(x - hint->x), 64)) < cert::ilog2(x) - 20) {
    x.set_prec(hint->x.get_prec());
    x = hint->x;
    seeded = true;
  }
  const mpz_class R2 = R * R;
  // At most two moves to another root region that the Taylor certificate
  // points at (the 128-bit search can miss a minimum inside a cluster).
  for (int attempt = 0; attempt < 3; ++attempt) {
    const mpz_class* L = dir == 0 ? l : lr;
    const mpz_class* P = dir == 0 ? p : pr;
    const mpz_class* Q = qs[dir];
    const mpz_class dL[2] = {L[1], 2 * L[2]}, dP[2] = {P[1], 2 * P[2]};
    const mpz_class dQ[4] = {Q[1], 2 * Q[2], 3 * Q[3], 4 * Q[4]};
    const mpz_class eQ[3] = {dQ[1], 2 * dQ[2], 3 * dQ[3]};
    const long top_l = std::max(cert::ilog2(L[1]), cert::ilog2(L[2]) + 1);
    long top_q = cert::ilog2(dQ[0]);
    for (int i = 1; i < 4; ++i) top_q = std::max(top_q, cert::ilog2(dQ[i]));
    bool on_f = true, moved = false;
    const long lead = std::max(0L, -cert::ilog2(x));
    // k: the bits of s0 (absolute). Doubled (in floats only) until the
    // minimum's value v = F(s*) (Q(s*) where Newton runs on Q) is resolved
    // at the working precision; then k is set so that the curvature times
    // 2^-2k is about 2^-16 |v|, and the exact certificates run, with up to
    // two retries at more bits (the Taylor bound may need log2(C2 / h) / 2
    // more).
    long k = std::max(96 + lead, g + 96);
    // A miss needs two levels (above); if the second would pass max_k,
    // the floats cost about what the count does: leave it to the count.
    if (2 * k - lead > max_k) return -1;
    int tries = 0;
    bool resolved = false, have_prev_v = false, expect_hit = false;
    mpf_class prev_v(0, 64);
    if (seeded && attempt == 0) {  // the other torus's level and value
      k = std::max(k, std::min(hint->k, max_k));
      prev_v = hint->v;
      have_prev_v = sgn(prev_v) != 0;
    }
    while (k <= max_k && !moved) {
      // Newton on F' = L' - R P' / rho, F'' = L'' - R (P'' / rho -
      // P'^2 / (2 rho^3)), at a precision that resolves 2^-k in s after
      // the cancellation of F' 's terms (up to about 2^top_l). Where
      // F'' <= 0 (near the axis, where rho has a kink) on Q' instead.
      // Inside the window (g > 0) L and P cancel about 2g bits, Q 4g.
      const long gw = std::max(0L, g);
      long prec = k + 2 * gw + 64;
      mpf_class f2(0, mp_bitcnt_t(prec));
      for (int it = 0; it < 12; ++it) {
        x.set_prec(mp_bitcnt_t(prec));
        mpf_class f1(0, mp_bitcnt_t(prec));
        f2.set_prec(mp_bitcnt_t(prec));
        f2 = 0;
        long top = top_l;
        const mpf_class pv = cert::evalAt(P, 3, x);
        if (on_f && sgn(pv) > 0) {
          const mpf_class rho(sqrt(pv), mp_bitcnt_t(prec));
          const mpf_class pd = cert::evalAt(dP, 2, x);
          f1 = cert::evalAt(dL, 2, x) - R * pd / rho;
          f2 = mpf_class(2 * L[2], mp_bitcnt_t(prec)) -
               R * (2 * P[2] / rho - pd * pd / (2 * rho * rho * rho));
        }
        if (on_f && sgn(f2) <= 0) on_f = false;
        if (!on_f) {
          f1 = cert::evalAt(dQ, 4, x);
          f2 = cert::evalAt(eQ, 3, x);
          top = top_q;
          if (sgn(f2) <= 0) break;
        }
        const long want =
            k + std::max(0L, top - cert::ilog2(f2)) + (on_f ? 2 : 4) * gw + 64;
        if (want > prec + 8) {  // redo this step at the needed precision
          prec = want;
          continue;
        }
        const mpf_class step(f1 / f2, mp_bitcnt_t(prec));
        x -= step;
        if (sgn(step) == 0 || cert::ilog2(step) < -k - 2) break;
      }
      if (sgn(x) < 0) x = 0;
      if (x > 0.5) x = 0.5;
      if (sgn(f2) <= 0) return -1;
      if (!resolved) {
        // v and the size of the terms it cancels from, in floats.
        const mpf_class lv = cert::evalAt(L, 3, x), pv = cert::evalAt(P, 3, x);
        const mpf_class r2rho(2 * R * sqrt(abs(pv)), mp_bitcnt_t(prec));
        mpf_class v(lv - r2rho, mp_bitcnt_t(prec));
        mpf_class size(abs(lv) + r2rho, mp_bitcnt_t(prec));
        if (!on_f || sgn(pv) <= 0) {
          v = cert::evalAt(Q, 5, x);
          size = size * size;
        }
        // Resolved: above the rounding of its terms and equal (to 2^-8)
        // to the previous level's value (else x's own error, or rounding
        // the estimate misses, still dominates it).
        const bool same =
            have_prev_v && sgn(v) == sgn(prev_v) &&
            cert::ilog2(mpf_class(v - prev_v, 64)) < cert::ilog2(v) - 8;
        // A negative value needs no second level: F(x) < 0 already
        // (x's error only raises F above its minimum).
        // The bits s0 needs: x's error e raises F(x) by about F'' e^2 / 2,
        // to be kept below |v|. For AM-GM's quadratic G (below) it is
        // G's minimum that must stay positive: G touches F at s* with G'
        // = F', and at x its minimum lies G'(x)^2 / (2 G'') below G(x),
        // G'(x) about F'' e: F''^2 e^2 / G'' against |v|, where G''
        // = 2 (l2 - lambda p2) <= F'' (edges close to the blind case
        // G'' <= 0 need many more bits than F'' alone asks).
        long kn = sgn(v) == 0 ? k : (cert::ilog2(f2) - cert::ilog2(v)) / 2 + 8;
        bool convex = false;  // G'' > 0: AM-GM's case
        const bool above =
            sgn(v) != 0 && cert::ilog2(v) >= cert::ilog2(size) - prec + 40;
        if (above && sgn(v) > 0 && on_f && sgn(pv) > 0) {
          const mpf_class lam(R / sqrt(pv), mp_bitcnt_t(prec));
          const mpf_class g2(2 * (mpf_class(L[2], mp_bitcnt_t(prec)) -
                                  lam * mpf_class(P[2], mp_bitcnt_t(prec))),
                             mp_bitcnt_t(prec));
          convex = sgn(g2) > 0;
          if (convex && cert::ilog2(g2) < cert::ilog2(f2))
            kn = std::max(
                kn,
                (2 * cert::ilog2(f2) - cert::ilog2(g2) - cert::ilog2(v)) / 2 +
                    8);
        }
        if (!above || (!same && sgn(v) > 0)) {
          prev_v = v;
          have_prev_v = sgn(v) != 0;
          // Not resolved yet. Below the rounding: twice the bits. A
          // positive value above it, where AM-GM will be tried (G convex),
          // only waits for its confirmation at the next level: at the bits
          // it asks (kn) and at least 32 more, not twice as many (the
          // doubling cost up to 60 % of a wide edge's floats). Elsewhere
          // (the quartic's bound, whose needs kn does not model) twice.
          k = above && convex ? std::max(k + 32, std::min(kn, 2 * k - lead))
                              : 2 * k - lead;
          continue;
        }
        resolved = true;
        expect_hit = sgn(v) < 0;
        if (hint != nullptr) {
          hint->valid = true;
          hint->dir = dir;
          hint->x.set_prec(x.get_prec());
          hint->x = x;
          hint->v.set_prec(64);
          hint->v = v;
          hint->k = std::max(k, kn);
        }
        if (kn > k) {
          k = kn;
          continue;
        }
      }
      mpf_class scaled(x, mp_bitcnt_t(prec));
      mpf_mul_2exp(scaled.get_mpf_t(), scaled.get_mpf_t(), mp_bitcnt_t(k));
      const mpz_class m(scaled);  // 0 <= m <= 2^(k-1)
      // The estimate's sign picks the certificate to try (both exact; the
      // other one only on the last try).
      const bool last = tries == 2;
      if (expect_hit || last) {
        if (cert::hitAt(L, P, R2, m, k)) return 1;
      }
      // Miss: the AM-GM bound (integers of L's size), else the quartic's.
      x.set_prec(mp_bitcnt_t(prec));
      const mpf_class pv = cert::evalAt(P, 3, x);
      // AM-GM's quadratic G = L - lambda P - R^2 / lambda touches F at s*
      // with G' = F' there, so it is positive on [0, 1] only if convex:
      // G'' = 2 (l2 - lambda p2) > 0. Where lambda p2 >= l2 (an edge
      // through the hole, rho(s*) <= R |E_xy|^2 / |E|^2) no k makes it
      // hold: the quartic's bound at once (the floats only choose).
      bool amgm_blind = !on_f;
      if ((!expect_hit || last) && sgn(pv) > 0) {
        const mpf_class lam(R / sqrt(pv), mp_bitcnt_t(prec));
        amgm_blind =
            amgm_blind || lam * mpf_class(P[2], 64) >= mpf_class(L[2], 64);
        if (!amgm_blind && cert::amgmCertificate(L, P, R2, lam, k + 32))
          return 0;
      }
      // The quartic's bound costs more (Q's integers, shifted): where
      // Newton runs on F (AM-GM's domain) only on the last try, or where
      // AM-GM cannot hold.
      mpf_class other;
      const int t = (!amgm_blind && !last) || (expect_hit && !last)
                        ? -1
                        : cert::taylorCertificate(Q, m, k, &other);
      if (t == 0) return 0;
      // A vertex within about 2^-k of s0 is C0 and C1's doing (s0 not yet
      // close enough), not another root region.
      if (t == 2 &&
          cert::ilog2(mpf_class(other - x, mp_bitcnt_t(prec))) > 16 - k) {
        if (sgn(other) < 0 || other > 1) return -1;
        if (other > 0.5) {
          dir = 1 - dir;
          other = 1 - other;
        }
        x = other;
        moved = true;
      } else if (++tries > 2) {
        return -1;
      } else {
        k += 32 * tries + (k - lead) / 4;
      }
    }
    if (!moved) return -1;
  }
  return -1;
}

}  // namespace tricyl::detail::sturm

// ---------------------------------------------------------------------------
// Window floats: the intermediate stage of withinDistance's sized parts and
// faces on wide inputs (src/triangle_cylinder_margin.cpp, docs/margin.md
// "Window floats").
//
// On inputs whose exponents span thousands of binary orders, the exact torus
// input is integers of about 4,300 bits (one common unit for values of
// wildly different sizes), and the long double filter on them rounded once
// (53 bits) cannot resolve what a margin at a hostile threshold asks: the
// decisive quantities cancel a few hundred bits, not thousands. Here every
// value is m 2^x with m an integer of at most P bits (the window: the
// leading P bits of the value, wherever its exponent lies) and carries an
// upper bound e of its distance to the true value, as the running-bound
// filters do (src/filter.h), with no absolute slack and no exponent range:
//   a + b:  exact sum, then truncated to P bits: e = e_a + e_b + 2^x
//           (2^x the new unit; a term below a quarter of the other's unit
//           is not formed: its magnitude joins the bound instead);
//   a * b:  exact product, then truncated: e = |a| e_b + |b| e_a + e_a e_b
//           + 2^x, |a| an upper bound of the computed value's magnitude.
// A truncation toward zero to the unit 2^x is off by less than 2^x. The
// bounds are doubles with a separate exponent (Bound: f 2^k, f in
// [1/2, 1)), every operation on them rounded up: one or two roundings to
// nearest (each within a factor 1 -+ 2^-53) times (1 + 2^-50), rounded too,
// is at least the exact value ((1 - 2^-53)^3 (1 + 2^-50) > 1); a term
// 2^-200 or more below the other in a sum is replaced by 2^-200 times the
// other's exponent (an upper bound). sign(): |m 2^x| from its leading bits
// truncated (a lower bound) against e: certain when strictly above, an
// exact zero when m = 0 and e = 0. A certain sign is the true sign; an
// uncertain one is kUnknown, and the caller goes on to exact arithmetic.
namespace tricyl::detail::window {

/// An upper bound f 2^k, f in [1/2, 1) (or f = 0: the bound 0).
struct Bound {
  double f = 0;
  long k = 0;
};

/// f 2^k, f >= 0 computed with at most two roundings, times (1 + 2^-50)
/// (rounded): an upper bound of the exact value, normalised (frexp is
/// exact).
inline Bound up(double f, long k) {
  if (f == 0) return {};
  int e = 0;
  const double g = std::frexp(f * (1 + 0x1p-50), &e);
  return {g, k + e};
}

inline Bound add(const Bound& a, const Bound& b) {
  if (a.f == 0) return b;
  if (b.f == 0) return a;
  const Bound& hi = a.k >= b.k ? a : b;
  const Bound& lo = a.k >= b.k ? b : a;
  const long d = lo.k - hi.k;  // <= 0
  // lo.f 2^d < 2^d <= 2^-200 when d <= -200; ldexp is exact otherwise
  // (lo.f >= 1/2, no underflow at d > -200).
  const double t = d <= -200 ? 0x1p-200 : std::ldexp(lo.f, int(d));
  return up(hi.f + t, hi.k);
}

inline Bound mul(const Bound& a, const Bound& b) {
  if (a.f == 0 || b.f == 0) return {};
  return up(a.f * b.f, a.k + b.k);
}

/// 2^x as a bound.
inline Bound pow2(long x) { return {0.5, x + 1}; }

/// A value m 2^x (m at most p bits) and the bound e of its error. The
/// window p is the inputs' (fromInteger), the larger of the operands' in
/// an operation; p = 0 (a constant lifted from a double, 53 bits) is never
/// truncated.
struct Num {
  mpz_class m;
  long x = 0;
  Bound e;
  int p = 0;
};

/// An upper bound of |m 2^x|: mpz_get_d_2exp truncates, |m| = g 2^k
/// (1 + d) with 1/2 <= |g| < 1 and 0 <= d < 2^-52.
inline Bound magnitude(const mpz_class& m, long x) {
  if (sgn(m) == 0) return {};
  long k = 0;
  const double g = std::fabs(mpz_get_d_2exp(&k, m.get_mpz_t()));
  return up(g * (1 + 0x1p-51), k + x);
}

/// Truncates m to its leading p bits (toward zero), the error to e.
inline void fit(Num* a) {
  if (sgn(a->m) == 0 || a->p <= 0) return;
  const long n = long(mpz_sizeinbase(a->m.get_mpz_t(), 2));
  if (n <= a->p) return;
  const mp_bitcnt_t s = mp_bitcnt_t(n - a->p);
  mpz_tdiv_q_2exp(a->m.get_mpz_t(), a->m.get_mpz_t(), s);
  a->x += long(s);
  a->e = add(a->e, pow2(a->x));
}

/// The value z 2^x (an exact integer input), truncated to p > 0 bits.
inline Num fromInteger(const mpz_class& z, int p, long x = 0) {
  Num a{z, x, {}, p};
  fit(&a);
  return a;
}

/// |m 2^x| < 2^top (a 0 gives a very small top).
inline long top(const mpz_class& m, long x) {
  if (sgn(m) == 0) return std::numeric_limits<long>::min() / 4;
  return x + long(mpz_sizeinbase(m.get_mpz_t(), 2));
}

inline Num operator+(const Num& a, const Num& b) {
  Num r;
  const bool za = sgn(a.m) == 0, zb = sgn(b.m) == 0;
  if (za || zb) {
    r = za ? b : a;
    r.e = add(a.e, b.e);
    r.p = std::max(a.p, b.p);
    return r;
  }
  // A term below a quarter of the other's unit: its magnitude (< 2^top)
  // joins the bound instead of a long exact sum.
  if (top(b.m, b.x) < a.x - 2) {
    r = a;
    r.e = add(add(a.e, b.e), pow2(top(b.m, b.x)));
    r.p = std::max(a.p, b.p);
    return r;
  }
  if (top(a.m, a.x) < b.x - 2) {
    r = b;
    r.e = add(add(a.e, b.e), pow2(top(a.m, a.x)));
    r.p = std::max(a.p, b.p);
    return r;
  }
  // The shift is at most about P + 2 bits here.
  if (a.x >= b.x) {
    mpz_mul_2exp(r.m.get_mpz_t(), a.m.get_mpz_t(), mp_bitcnt_t(a.x - b.x));
    r.m += b.m;
    r.x = b.x;
  } else {
    mpz_mul_2exp(r.m.get_mpz_t(), b.m.get_mpz_t(), mp_bitcnt_t(b.x - a.x));
    r.m += a.m;
    r.x = a.x;
  }
  r.e = add(a.e, b.e);
  r.p = std::max(a.p, b.p);
  fit(&r);
  return r;
}

inline Num operator-(const Num& a) {
  Num r = a;
  mpz_neg(r.m.get_mpz_t(), r.m.get_mpz_t());
  return r;
}

inline Num operator-(const Num& a, const Num& b) { return a + (-b); }

inline Num operator*(const Num& a, const Num& b) {
  Num r;
  mpz_mul(r.m.get_mpz_t(), a.m.get_mpz_t(), b.m.get_mpz_t());
  r.x = a.x + b.x;
  r.e = add(add(mul(magnitude(a.m, a.x), b.e), mul(magnitude(b.m, b.x), a.e)),
            mul(a.e, b.e));
  r.p = std::max(a.p, b.p);
  fit(&r);
  return r;
}

/// a times 2 (exact: the unit and the bound move up one binary order).
inline Num twice(Num a) {
  ++a.x;
  if (a.e.f != 0) ++a.e.k;
  return a;
}

/// The kernel (the interface of src/filter.h's kernels: Num, lift, sign).
struct Kernel {
  using Num = window::Num;
  static constexpr bool kExact = false;
  static Num lift(double v) {
    int e = 0;
    const double f = std::frexp(v, &e);  // exact: v = f 2^e
    return {mpz_class(std::ldexp(f, 53)), long(e) - 53, {}, 0};
  }
  static Sign sign(const Num& a) {
    const int s = sgn(a.m);
    if (a.e.f == 0)
      return s > 0 ? Sign::kPos : s < 0 ? Sign::kNeg : Sign::kZero;
    if (s == 0) return Sign::kUnknown;
    long k = 0;
    const double g = std::fabs(mpz_get_d_2exp(&k, a.m.get_mpz_t()));
    // g 2^(k + x) <= |m 2^x|, g in [1/2, 1): above e certainly when its
    // exponent is larger, or equal with a larger fraction.
    const long kv = k + a.x;
    if (kv > a.e.k || (kv == a.e.k && g > a.e.f))
      return s > 0 ? Sign::kPos : Sign::kNeg;
    return Sign::kUnknown;
  }
};

}  // namespace tricyl::detail::window
