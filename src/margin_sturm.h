// SPDX-License-Identifier: BSD-3-Clause
// The exact root count behind withinDistance's torus edges
// (src/triangle_cylinder_margin.cpp): the number of distinct real roots of
// an integer polynomial in (0, 1) by Sturm's theorem, division-free.
// Tested against a rational Sturm sequence in tests/margin_sturm_test.cpp.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

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

}  // namespace tricyl::detail::sturm
