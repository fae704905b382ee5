// SPDX-License-Identifier: BSD-3-Clause
// The exact root count behind withinDistance's torus edges
// (src/triangle_cylinder_margin.cpp): the number of distinct real roots of
// an integer polynomial in (0, 1) by Sturm's theorem, division-free.
// Tested against a rational Sturm sequence in tests/margin_sturm_test.cpp.
#pragma once

#include <gmpxx.h>

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

}  // namespace tricyl::detail::sturm
