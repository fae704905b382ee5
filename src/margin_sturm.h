// SPDX-License-Identifier: BSD-3-Clause
// The exact root count behind withinDistance's torus edges
// (src/triangle_cylinder_margin.cpp): the number of distinct real roots of
// an integer polynomial in (0, 1) by Sturm's theorem, division-free.
// Tested against a rational Sturm sequence in tests/margin_sturm_test.cpp.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <cstddef>
#include <utility>
#include <vector>

namespace tricyl::detail::sturm {

using Poly = std::vector<mpz_class>;  // coefficients, lowest degree first

inline void trim(Poly& p) {
  while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}

/// Divides every coefficient of a by g > 0 (no-op for g = 1).
inline void divideExact(Poly& a, const mpz_class& g) {
  if (g == 1) return;
  for (auto& c : a) mpz_divexact(c.get_mpz_t(), c.get_mpz_t(), g.get_mpz_t());
}

/// True iff g > 1 divides every coefficient of a.
inline bool dividesAll(const Poly& a, const mpz_class& g) {
  for (const auto& c : a)
    if (!mpz_divisible_p(c.get_mpz_t(), g.get_mpz_t())) return false;
  return true;
}

/// The content (gcd of the coefficients) of a, >= 0.
inline mpz_class content(const Poly& a) {
  mpz_class g = 0;
  for (const auto& c : a) mpz_gcd(g.get_mpz_t(), g.get_mpz_t(), c.get_mpz_t());
  return g;
}

/// A positive multiple of the remainder of a by b (b trimmed, non-empty),
/// without division: the pseudo-remainder lc^(delta + 1) a mod b, lc = b's
/// leading coefficient and delta = deg a - deg b (one elimination step per
/// degree, also where a's coefficient is already 0, so that the factor is
/// exactly the one of the reduced PRS below), times sign(lc)^(delta + 1) so
/// that the multiple is positive (Sturm's sequence needs the signs of the
/// remainders, not their sizes). Not reduced: the caller divides out a
/// known positive factor or the content.
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
  }
  trim(a);
  if (sgn(lc) < 0 && k % 2 == 1)
    for (auto& c : a) c = -c;
  return a;
}

/// Above this coefficient size (bits) rootsInUnit divides each remainder by
/// its content rather than by the reduced PRS's factor (see there).
constexpr std::size_t kReducedPrsBits = 4096;

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
  // Each remainder is reduced by a POSITIVE factor, which leaves its signs
  // alone. Two ways, chosen by the size of p's coefficients:
  // - small (at most kReducedPrsBits bits: every input inside the range
  //   gate): by |lc(c_{i-1})|^(delta + 1), c_{i-1} the divisor of the
  //   previous step and delta the degree drop of that step (Collins'
  //   reduced PRS: the pseudo-remainder of c_{i-1} by c_i is divisible by
  //   it; Knuth, TAOCP vol. 2, 4.6.1, and Brown and Traub 1971). The
  //   divisibility is checked, not assumed; where it fails (never seen) the
  //   content is divided out instead. This keeps the coefficients near the
  //   size of the subresultants without a gcd, which cost more than the
  //   rest of the chain at these sizes;
  // - large (hostile inputs spanning thousands of binary orders): by the
  //   content, whose gcds are then cheap beside the products and which
  //   removes the large common factors that such inputs' polynomials carry
  //   (measured on the hostile set of tricyl-margin-stage-costs: the
  //   reduced chain was 2 to 3 times slower there).
  std::size_t bits = 0;
  for (const auto& c : p)
    bits = std::max(bits, mpz_sizeinbase(c.get_mpz_t(), 2));
  const bool reduced = bits <= kReducedPrsBits;
  mpz_class beta = 1;
  while (!d.empty()) {
    chain.push_back(d);
    Poly r = positiveRemainder(chain[chain.size() - 2], d);
    if (reduced && beta > 1 && dividesAll(r, beta))
      divideExact(r, beta);
    else if (!reduced || beta > 1)
      divideExact(r, content(r));
    for (auto& c : r) c = -c;
    trim(r);
    if (!r.empty()) {
      const Poly& prev = chain[chain.size() - 2];  // divided by d above
      const mpz_class lc = abs(d.back());
      mpz_pow_ui(beta.get_mpz_t(), lc.get_mpz_t(),
                 (unsigned long)(prev.size() - d.size() + 1));
    }
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

}  // namespace tricyl::detail::sturm
