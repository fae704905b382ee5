// SPDX-License-Identifier: BSD-3-Clause
// src/margin_sturm.h, the division-free Sturm count behind withinDistance's
// exact torus edges: against polynomials built from known roots, and
// against a textbook Sturm sequence in rationals (true remainders) on random
// small-integer polynomials, whose many degenerate chains (degree drops of
// two, common factors, negative leading coefficients) exercise the sign
// bookkeeping of the pseudo-remainders.
#include "margin_sturm.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "scenes.h"
#include "test_support.h"

namespace tricyl {
namespace {

using detail::sturm::Poly;

std::vector<mpq_class> toRational(const Poly& p) {
  std::vector<mpq_class> q;
  for (const auto& c : p) q.push_back(mpq_class(c));
  return q;
}

void trimQ(std::vector<mpq_class>& p) {
  while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}

mpq_class evalQ(const std::vector<mpq_class>& p, const mpq_class& x) {
  mpq_class v = 0;
  for (size_t i = p.size(); i-- > 0;) v = v * x + p[i];
  return v;
}

/// The textbook sequence: p, p', -rem(p_{k-1}, p_k) with exact rational
/// division; distinct roots in (0, 1) for p(0), p(1) != 0.
int referenceRootsInUnit(std::vector<mpq_class> p) {
  trimQ(p);
  if (p.size() <= 1) return 0;
  std::vector<std::vector<mpq_class>> chain{p};
  std::vector<mpq_class> d;
  for (size_t i = 1; i < p.size(); ++i) d.push_back(p[i] * long(i));
  trimQ(d);
  while (!d.empty()) {
    chain.push_back(d);
    std::vector<mpq_class> a = chain[chain.size() - 2];
    while (a.size() >= d.size()) {
      const mpq_class f = a.back() / d.back();
      const size_t shift = a.size() - d.size();
      for (size_t i = 0; i < d.size(); ++i) a[shift + i] -= f * d[i];
      a.pop_back();
      trimQ(a);
    }
    for (auto& c : a) c = -c;
    d = a;
  }
  auto variations = [&](const mpq_class& x) {
    int v = 0, last = 0;
    for (const auto& q : chain) {
      const int s = sgn(evalQ(q, x));
      if (s == 0) continue;
      if (last != 0 && s != last) ++v;
      last = s;
    }
    return v;
  };
  return variations(0) - variations(1);
}

Poly multiply(const Poly& a, const Poly& b) {
  Poly c(a.size() + b.size() - 1, mpz_class(0));
  for (size_t i = 0; i < a.size(); ++i)
    for (size_t j = 0; j < b.size(); ++j) c[i + j] += a[i] * b[j];
  return c;
}

std::string show(const Poly& p) {
  std::string s;
  for (const auto& c : p) s += c.get_str() + " ";
  return s;
}

TEST(MarginSturm, KnownRoots) {
  // Linear factors (b s - a), root a/b; (s^2 + 1) has no real root.
  const Poly half{-1, 2}, third{-1, 3}, two{-2, 1}, minus{1, 1}, none{1, 0, 1};
  struct Case {
    std::vector<Poly> factors;
    int roots;
  };
  const Case cases[] = {
      {{half}, 1},
      {{half, half}, 1},               // a double root: counted once
      {{half, half, third}, 2},        // tangency and a crossing
      {{half, half, half, half}, 1},   // a quadruple root
      {{half, third, two, minus}, 2},  // two inside, two outside
      {{none, none}, 0},               // no real root
      {{none, half, half}, 1},         // the torus-edge tie's shape
      {{two, minus, two, minus}, 0},   // double roots outside
      {{{-3, 7}, {-4, 7}, none}, 2},   // close roots 3/7 and 4/7
      {{{-1000, 2001}, {-1001, 2001}, {5, 1}, {7, 1}}, 2},
  };
  for (const Case& c : cases) {
    Poly p{1};
    for (const Poly& f : c.factors) p = multiply(p, f);
    for (int sign : {1, -1}) {
      Poly q = p;
      for (auto& x : q) x *= sign;
      EXPECT_EQ(detail::sturm::rootsInUnit(q), c.roots) << show(q);
      EXPECT_EQ(referenceRootsInUnit(toRational(q)), c.roots) << show(q);
    }
  }
}

TEST(MarginSturm, AgreesWithRationalSturmOnRandomPolynomials) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x57u);
  const long n = test::scaled(8000);
  long compared = 0, with_roots = 0;
  for (long i = 0; i < n; ++i) {
    const int deg = 1 + g.integer(4);
    const int range = i % 2 == 0 ? 3 : 40;
    Poly p(std::size_t(deg + 1));
    for (auto& c : p) c = g.integer(2 * range + 1) - range;
    mpz_class at1 = 0;
    for (const auto& c : p) at1 += c;
    if (sgn(p[0]) == 0 || sgn(at1) == 0) continue;  // the documented domain
    const int want = referenceRootsInUnit(toRational(p));
    ASSERT_EQ(detail::sturm::rootsInUnit(p), want) << show(p);
    ++compared;
    with_roots += want > 0;
  }
  std::printf("[ stats ] %ld random polynomials, %ld with roots in (0, 1)\n",
              compared, with_roots);
  EXPECT_GT(with_roots, compared / 20);
}

/// A random integer of 1 .. max_bits bits (either sign, or 0 one time in
/// 32), built from 64-bit limbs of the generator.
mpz_class randomInteger(scenes::Rng& g, int max_bits) {
  if (g.integer(32) == 0) return 0;
  const int bits = 1 + g.integer(max_bits);
  mpz_class z = 0;
  for (int b = 0; b < bits; b += 32) {
    z <<= 32;
    z += static_cast<unsigned long>(g.next() >> 32);
  }
  z >>= (((bits + 31) / 32) * 32 - bits);
  return g.integer(2) == 0 ? z : mpz_class(-z);
}

// signProductDifference, signSquaresPlusProduct and
// signSquaresPlusProductSquares (the leading-bits
// filters in front of the torus edges' exact products) against the exact
// signs: random integers of up to 6,000 bits, and near-ties made exactly
// (one side equal to the other plus a tiny integer, or exactly equal)
// where only the exact fallback can decide; both branches must be taken.
TEST(MarginSturm, LeadingBitsSignsAgreeWithExact) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x6c656164u);
  using detail::sturm::cert::signProductDifference;
  using detail::sturm::cert::signSquaresPlusProduct;
  using detail::sturm::cert::signSquaresPlusProductSquares;
  const long n = test::scaled(6000);
  long fallbacks[3] = {0, 0, 0}, filtered[3] = {0, 0, 0};
  for (long i = 0; i < n; ++i) {
    const int bits = i % 3 == 0 ? 64 : 6000;
    // 2^sa a0 a1 a2 - 2^sb b0 b1.
    mpz_class a[3], b[2];
    for (auto& x : a) x = randomInteger(g, bits);
    for (auto& x : b) x = randomInteger(g, bits);
    long sa = g.integer(8), sb = g.integer(8);
    const int kind = g.integer(4);
    if (kind >= 2) {  // b0 b1 2^sb = a0 a1 a2 2^sa + delta (delta tiny or 0)
      sb = 0;
      b[1] = 1;
      b[0] = a[0] * a[1] * a[2];
      b[0] <<= sa;
      if (kind == 3) b[0] += g.integer(7) - 3;
    }
    mpz_class lhs = a[0] * a[1] * a[2], rhs = b[0] * b[1];
    lhs <<= sa;
    rhs <<= sb;
    bool exact = false;
    const int got = signProductDifference({&a[0], &a[1], &a[2]}, sa,
                                          {&b[0], &b[1]}, sb, &exact);
    ASSERT_EQ(got, sgn(lhs - rhs)) << "i = " << i << ", kind " << kind;
    (exact ? fallbacks : filtered)[0]++;
    // c0^2 + c1^2 + c2^2 + k l, k l near -(sum of squares) for kind >= 2.
    mpz_class c[3], k = randomInteger(g, bits), l = randomInteger(g, bits);
    for (auto& x : c) x = randomInteger(g, bits);
    const mpz_class sq = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    if (kind >= 2) {
      l = 1 + g.integer(3);  // k l = -sq exactly, or within a few units
      k = -sq;
      mpz_tdiv_q(k.get_mpz_t(), k.get_mpz_t(), l.get_mpz_t());
      if (kind == 3) k += g.integer(7) - 3;
    }
    const int want = sgn(sq + k * l);
    ASSERT_EQ(signSquaresPlusProduct({&c[0], &c[1], &c[2]}, {&k, &l}, &exact),
              want)
        << "i = " << i << ", kind " << kind;
    (exact ? fallbacks : filtered)[1]++;
    // c0^2 + c1^2 + c2^2 + k l (e0^2 + e1^2 + e2^2); for kind >= 2,
    // c = t e and k l = -t^2 (an exact 0), then k moved by -3 .. 3.
    mpz_class e[3];
    for (auto& x : e) x = randomInteger(g, bits);
    if (kind >= 2) {
      const mpz_class t = randomInteger(g, bits);
      for (int j = 0; j < 3; ++j) c[j] = t * e[j];
      l = 1;
      k = -t * t;
      if (kind == 3) k += g.integer(7) - 3;
    }
    const mpz_class se = e[0] * e[0] + e[1] * e[1] + e[2] * e[2];
    const mpz_class sc = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
    ASSERT_EQ(signSquaresPlusProductSquares({&c[0], &c[1], &c[2]}, {&k, &l},
                                            {&e[0], &e[1], &e[2]}, &exact),
              sgn(sc + k * l * se))
        << "i = " << i << ", kind " << kind;
    (exact ? fallbacks : filtered)[2]++;
  }
  std::printf(
      "[ stats ] leading bits decided %ld, %ld and %ld, exact fallback %ld, "
      "%ld and %ld\n",
      filtered[0], filtered[1], filtered[2], fallbacks[0], fallbacks[1],
      fallbacks[2]);
  for (int j = 0; j < 3; ++j) {
    EXPECT_GT(fallbacks[j], n / 10) << "helper " << j;
    EXPECT_GT(filtered[j], n / 4) << "helper " << j;
  }
}

/// A window float's value m 2^x and its bound f 2^k as rationals.
mpq_class windowValue(const detail::window::Num& a) {
  mpq_class v(a.m);
  mpz_class p = 1;
  mpz_mul_2exp(p.get_mpz_t(), p.get_mpz_t(), mp_bitcnt_t(std::labs(a.x)));
  if (a.x >= 0)
    v *= p;
  else
    v /= p;
  return v;
}
mpq_class windowBound(const detail::window::Num& a) {
  mpq_class e(a.e.f);
  mpz_class p = 1;
  mpz_mul_2exp(p.get_mpz_t(), p.get_mpz_t(), mp_bitcnt_t(std::labs(a.e.k)));
  if (a.e.k >= 0)
    e *= p;
  else
    e /= p;
  return e;
}

// The window floats (src/margin_sturm.h, detail::window: P-bit mantissas
// with a running error bound, the intermediate stage of withinDistance's
// sized parts and faces on wide inputs) against exact rationals: sums and
// products of inputs spanning thousands of binary orders (integers of up
// to 4,000 bits times 2^-60 .. 2^60), and near-ties made exactly
// (a b - c d with c d = a b + delta, delta tiny or 0) where the window must
// abstain. Every bound must hold (|exact - value| <= e), every certified
// sign must be the exact one, and both outcomes must occur.
TEST(MarginSturm, WindowFloatsBoundTheExactValue) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x77696e64u);
  using K = detail::window::Kernel;
  using N = K::Num;
  const long n = test::scaled(4000);
  long certain = 0, unknown = 0, wrong = 0;
  auto input = [&g](mpq_class* exact) {
    const mpz_class z = randomInteger(g, 1 + g.integer(4000));
    const long x = long(g.integer(121)) - 60;
    const N a = detail::window::fromInteger(z, 320, x);
    *exact = windowValue(N{z, x, {}, 0});
    return a;
  };
  auto check = [&](const N& v, const mpq_class& exact, long i) {
    const mpq_class err = abs(exact - windowValue(v));
    EXPECT_LE(err, windowBound(v)) << "i = " << i;
    const detail::Sign s = K::sign(v);
    if (s == detail::Sign::kUnknown) {
      ++unknown;
      return;
    }
    ++certain;
    if (int(s) != sgn(exact)) ++wrong;
  };
  for (long i = 0; i < n; ++i) {
    mpq_class ea, eb, ec, ed, ee;
    const N a = input(&ea), b = input(&eb), e = input(&ee);
    N c = input(&ec), d = input(&ed);
    const int kind = g.integer(3);
    if (kind > 0) {  // c d = a b (+ delta): c = a b 2^-x + delta, d = 2^x
      const long x = long(g.integer(41)) - 20;
      const mpq_class ab = ea * eb;
      mpz_class num = ab.get_num(), den = ab.get_den();
      // ab is an integer times a power of two: write it as c 2^x.
      long sh = 0;
      while (den > 1) {
        den >>= 1;
        --sh;
      }
      mpz_class cz = num;
      if (kind == 2) cz += g.integer(7) - 3;
      c = detail::window::fromInteger(cz, 320, sh - x);
      ec = windowValue(N{cz, sh - x, {}, 0});
      d = detail::window::fromInteger(1, 320, x);
      ed = windowValue(N{mpz_class(1), x, {}, 0});
    }
    const N v = a * b - c * d;
    check(v, ea * eb - ec * ed, i);
    const N w = (a + e) * (b - e) + K::lift(0.75) * e;
    check(w, (ea + ee) * (eb - ee) + mpq_class(3, 4) * ee, i);
    const N u = (v * v + w) * a - detail::window::twice(c);
    check(u,
          ((ea * eb - ec * ed) * (ea * eb - ec * ed) + (ea + ee) * (eb - ee) +
           mpq_class(3, 4) * ee) *
                  ea -
              2 * ec,
          i);
  }
  std::printf("[ stats ] window signs certified %ld, abstained %ld\n", certain,
              unknown);
  EXPECT_EQ(wrong, 0);
  EXPECT_GT(certain, n / 2);
  EXPECT_GT(unknown, n / 20);
}

/// The torus quartic Q = L^2 - 4 R^2 P from the quadratics L, P (lowest
/// first) and R.
Poly torusQuartic(const Poly& l, const Poly& pp, const mpz_class& R) {
  Poly q = multiply(l, l);
  const Poly rp = multiply(Poly{4 * R * R}, pp);
  for (size_t i = 0; i < rp.size(); ++i) q[i] -= rp[i];
  return q;
}

// rootsInUnitTorus (the closed-form chain of the torus edges) against the
// rational reference: an edge tangent to the tube (a double root, counted
// once), just missing it and just crossing it, at scales up to 2^100; then
// random torus quartics, whose small ranges make exact degeneracies (a
// remainder's degree dropping, common factors) frequent.
TEST(MarginSturm, TorusChainAgreesWithRationalSturm) {
  // Rim radius R = 5k at height 0, the edge (8k, -2k + 4k s, 4k), s in
  // [0, 1]: at s = 1/2 the point (8k, 0, 4k) is 5k from the rim point
  // (5k, 0, 0) along the meridian, and the edge is perpendicular to the
  // meridian plane there: tangent to the tube of radius 5k. rho^2 =
  // 68k^2 - 16k^2 s + 16k^2 s^2, (z - C)^2 = 16k^2; the tube's squared
  // radius M^2 = 25k^2 + dm (only M^2 enters L): Q(1/2) = dm^2 - 160k^2 dm,
  // Q(0) = Q(1) = 256k^4 - 168k^2 dm + dm^2.
  for (const mpz_class& k : {mpz_class(1), mpz_class(10), mpz_class(1000),
                             mpz_class(mpz_class(1) << 100)}) {
    const mpz_class k2 = k * k, R = 5 * k;
    const Poly pp{68 * k2, -16 * k2, 16 * k2};
    for (int dm : {-1, 0, 1}) {
      const Poly l{pp[0] + 16 * k2 - dm, pp[1], pp[2]};  // R^2 - M^2 = -dm
      const Poly q = torusQuartic(l, pp, R);
      const int want = dm < 0 ? 0 : (dm == 0 ? 1 : 2);
      EXPECT_EQ(referenceRootsInUnit(toRational(q)), want) << show(q);
      EXPECT_EQ(detail::sturm::rootsInUnitTorus(q.data(), l[1], l[2]), want)
          << show(q);
    }
  }
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x7475u);
  const long n = test::scaled(8000);
  long compared = 0, with_roots = 0;
  for (long i = 0; i < n; ++i) {
    const int range = i % 3 == 0 ? 3 : (i % 3 == 1 ? 12 : 1000);
    auto draw = [&] { return mpz_class(g.integer(2 * range + 1) - range); };
    const Poly l{draw(), draw(), mpz_class(1 + g.integer(range))};  // l2 > 0
    const Poly pp{draw(), draw(), draw()};
    const mpz_class R = g.integer(range + 1);
    const Poly q = torusQuartic(l, pp, R);
    mpz_class at1 = 0;
    for (const auto& c : q) at1 += c;
    if (sgn(q[0]) == 0 || sgn(at1) == 0) continue;  // the documented domain
    const int want = referenceRootsInUnit(toRational(q));
    ASSERT_EQ(detail::sturm::rootsInUnitTorus(q.data(), l[1], l[2]), want)
        << show(q) << " l1 " << l[1].get_str() << " l2 " << l[2].get_str()
        << " R " << R.get_str();
    ++compared;
    with_roots += want > 0;
  }
  std::printf("[ stats ] %ld random torus quartics, %ld with roots in (0, 1)\n",
              compared, with_roots);
  EXPECT_GT(with_roots, compared / 20);
}

// The three exact tests of torusEdgeCertificate on the exactly tangent edge
// of TorusChainAgreesWithRationalSturm (R = 5k, the edge (8k, -2k + 4k s,
// 4k), M^2 = 25k^2 + dm): at s0 = 1/2, F = L - 2 R rho = -dm, rho = 8k, so
// lambda = R / rho = 5/8 makes the AM-GM quadratic (3/8) P - 24k^2 - dm,
// whose least value is -dm: it certifies the miss (dm = -1) and must not
// certify the hit (dm = +1); Q(1/2) <= 0 exactly for the hit; the shifted
// quartic must not contradict either.
TEST(MarginSturm, CertificatesOnTheExactTangent) {
  for (const mpz_class& k :
       {mpz_class(1), mpz_class(10), mpz_class(mpz_class(1) << 100)}) {
    const mpz_class k2 = k * k, R = 5 * k;
    const Poly pp{68 * k2, -16 * k2, 16 * k2};
    for (int dm : {-1, 1}) {
      const Poly l{pp[0] + 16 * k2 - dm, pp[1], pp[2]};
      const Poly q = torusQuartic(l, pp, R);
      const mpf_class lam(0.625, 64);
      EXPECT_EQ(detail::sturm::cert::amgmCertificate(l.data(), pp.data(), R * R,
                                                     lam, 8),
                dm < 0)
          << "dm " << dm << " k " << k.get_str();
      for (long bits : {1L, 40L}) {  // s0 = 1/2 as 1/2 and as 2^39 / 2^40
        const mpz_class m = mpz_class(1) << (bits - 1);
        EXPECT_EQ(
            detail::sturm::cert::hitAt(l.data(), pp.data(), R * R, m, bits),
            dm > 0);
        mpf_class other;
        const int t =
            detail::sturm::cert::taylorCertificate(q.data(), m, bits, &other);
        EXPECT_NE(t, dm > 0 ? 0 : 1) << "dm " << dm << " bits " << bits;
      }
    }
  }
}

// torusEdgeCertificate (the local certificate in front of the Sturm count
// on wide torus edges) against rootsInUnitTorus: whenever it decides, its
// answer must be the count's. Edges of 2^(300 .. 1500) times the rim
// radius, passing the tube at random heights and offsets (over the hole,
// outside the rim, near the axis), with the tube's squared radius M2 at the
// exact threshold where the answer flips (bisection on M2, each step
// decided by the count where the certificate abstains) and one either
// side, and at random values; also how often it decides (it must, on most
// near-threshold edges: that is what it is for).
TEST(MarginSturm, TorusEdgeCertificateAgreesWithSturm) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x63657274u);
  auto big = [&g](int bits) {  // a random integer of about `bits` bits
    mpz_class z = 1;
    for (int b = 0; b < bits; b += 30) z = (z << 30) + g.integer(1 << 30);
    return mpz_class(z >> (z.get_str(2).size() - std::size_t(bits)));
  };
  struct Edge {
    Poly pp, lz;  // rho^2, and (z - C)^2 + rho^2 (L without R^2 - M2)
    mpz_class R;
  };
  // Exact answer (the count), and the certificate's (-1: abstains).
  auto answers = [](const Edge& e, const mpz_class& m2, int* cert) {
    const Poly l{e.lz[0] + e.R * e.R - m2, e.lz[1], e.lz[2]};
    *cert = -2;  // not asked: L <= 0 somewhere, or an end inside
    if (!detail::sturm::cert::quadraticPositive(l[0], l[1], l[2])) return 1;
    const Poly q = torusQuartic(l, e.pp, e.R);
    mpz_class at1 = 0;
    for (const auto& c : q) at1 += c;
    if (sgn(q[0]) <= 0 || sgn(at1) <= 0) return 1;
    mpz_class m = sqrt(m2) + 1;
    long bits = 0;
    for (const auto& c : q)
      bits = std::max(bits, long(mpz_sizeinbase(c.get_mpz_t(), 2)));
    *cert = detail::sturm::torusEdgeCertificate(q.data(), l.data(), e.pp.data(),
                                                e.R, m, bits);
    return detail::sturm::rootsInUnitTorus(q.data(), l[1], l[2]) > 0 ? 1 : 0;
  };
  const long n = test::scaled(10);
  long asked = 0, decided = 0;
  for (long i = 0; i < n; ++i) {
    const int rb = 200 + g.integer(400);        // rim radius bits
    const int wb = rb + 300 + g.integer(1200);  // edge half-length bits
    const mpz_class R = big(rb);
    // A = (x0, -W + y0, z0), E = (ex, 2W, ez): passes near (x0, 0, z0)
    // at about s = 1/2; x0 from near the axis to outside the rim.
    const int kind = g.integer(4);
    const mpz_class x0 = kind == 0 ? mpz_class(big(rb - 40 - g.integer(100)))
                         : kind == 1
                             ? mpz_class(R - big(rb - 2 - g.integer(60)))
                             : mpz_class(R + big(rb - 2 - g.integer(60)));
    const mpz_class z0 = big(rb - 1 - g.integer(80)) * (g.integer(2) ? 1 : -1);
    const mpz_class W = big(wb);
    const mpz_class ex = big(rb - g.integer(rb)), ez = big(rb - g.integer(rb));
    const mpz_class ax = x0 - ex / 2, ay = -W, az = z0 - ez / 2;
    Edge e;
    e.R = R;
    e.pp = Poly{ax * ax + ay * ay, 2 * (ax * ex + ay * 2 * W),
                ex * ex + 4 * W * W};
    e.lz = Poly{e.pp[0] + az * az, e.pp[1] + 2 * az * ez, e.pp[2] + ez * ez};
    // Bisection on M2 for the flip: 0 (a miss unless the edge crosses
    // the circle) .. (R + |x0| + |z0|)^2 * 4 (a hit).
    mpz_class lo = 0,
              hi = 4 * (R + abs(x0) + abs(z0)) * (R + abs(x0) + abs(z0));
    int c = 0;
    if (answers(e, lo, &c) == 1) continue;
    ASSERT_EQ(answers(e, hi, &c), 1);
    while (hi - lo > 1) {
      const mpz_class mid = (lo + hi) / 2;
      int cm = 0;
      const int want = answers(e, mid, &cm);
      if (cm >= 0) {
        ASSERT_EQ(cm, want) << "M2 " << mid.get_str() << " R " << R.get_str();
        ++asked;
        decided += 1;
      } else if (cm == -1) {
        ++asked;
      }
      (want == 1 ? hi : lo) = mid;
    }
    for (const mpz_class& m2 : {lo, hi, mpz_class(lo - 1), mpz_class(hi + 1)}) {
      int cm = 0;
      const int want = answers(e, m2, &cm);
      if (cm == -1) ++asked;
      if (cm >= 0) {
        ++asked;
        ++decided;
        ASSERT_EQ(cm, want) << "M2 " << m2.get_str() << " R " << R.get_str()
                            << " kind " << kind;
      }
    }
  }
  std::printf(
      "[ stats ] %ld certificate calls on wide torus edges, %ld decided\n",
      asked, decided);
  EXPECT_GT(asked, 0);
  EXPECT_GT(decided, asked / 2);
}

}  // namespace
}  // namespace tricyl
