// SPDX-License-Identifier: BSD-3-Clause
// tricyl::withinDistance (include/tricyl/triangle_cylinder_margin.h):
// hand-built cases, ties constructed exactly, margins a few ulps either side
// of a true distance, the six scene families with margins 0..10% of the
// size, margin 0 against intersect, and the decomposition itself against an
// independent numerical distance. Every answer is judged by the exact GMP
// oracle compare/margin_oracle.h.
#include "tricyl/triangle_cylinder_margin.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>

#include "margin_oracle.h"
#include "margin_test_support.h"
#include "scenes.h"
#include "test_support.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using V = Vec3<double>;
using scenes::TriCase;

bool oracleWithin(const TriCase& k, double m) {
  return margin_oracle::withinDistance(k.cyl, k.pose, k.tri, m);
}

using test::ulpsFrom;

std::string describe(const TriCase& k, double m) {
  char buf[512];
  const auto& t = k.tri;
  std::snprintf(buf, sizeof buf,
                "r=%a lz=%a m=%a tri=(%a %a %a)(%a %a %a)(%a %a %a) t=(%a %a "
                "%a) feature=%s",
                k.cyl.radius, k.cyl.lz, m, t.a.x, t.a.y, t.a.z, t.b.x, t.b.y,
                t.b.z, t.c.x, t.c.y, t.c.z, k.pose.t.x, k.pose.t.y, k.pose.t.z,
                k.feature);
  return buf;
}

TriCase local(double r, double lz, V a, V b, V c) {
  TriCase k;
  k.cyl = {r, lz};
  k.pose = identityPose<double>();
  k.tri = {a, b, c};
  return k;
}

// ---------------------------------------------------------------------------
// Hand-built cases (local frame, r = 1, lz = 2: h = 1).

TEST(Margin, HandBuilt) {
  struct Case {
    V a, b, c;
    double m;
    bool want;
    const char* what;
  };
  const Case cases[] = {
      {{1.5, 0, 0}, {3, 0, 0}, {3, 1, 0}, 0.5, true, "vertex 0.5 off barrel"},
      {{1.5, 0, 0}, {3, 0, 0}, {3, 1, 0}, 0.25, false, "vertex 0.5 off barrel"},
      {{0, 0, 1.5}, {0, 0, 3}, {1, 0, 3}, 0.5, true, "vertex 0.5 over cap"},
      {{0, 0, 1.5}, {0, 0, 3}, {1, 0, 3}, 0.375, false, "vertex over cap"},
      // The corner: (1.5, 0, 1.5) is sqrt(0.5) ~ 0.7071 from the rim point
      // (1, 0, 1); it is inside the grown box for m = 0.5 but not within 0.5.
      {{1.5, 0, 1.5}, {3, 0, 3}, {3, 1, 3}, 0.5, false, "corner, box says yes"},
      {{1.5, 0, 1.5}, {3, 0, 3}, {3, 1, 3}, 0.75, true, "corner within 0.75"},
      {{1.5, 0, 1.5}, {3, 0, 3}, {3, 1, 3}, 0.70703125, false, "corner < d"},
      // A large horizontal face above the cap: distance 0.25.
      {{-9, -9, 1.25}, {9, -9, 1.25}, {0, 9, 1.25}, 0.25, true, "face on cap"},
      {{-9, -9, 1.25}, {9, -9, 1.25}, {0, 9, 1.25}, 0.125, false, "face"},
      // A face in the plane x = z, nearest on its edge x = 1.5, sqrt(1/2)
      // from the rim point (1, 0, 1).
      {{1.5, -20, 1.5},
       {1.5, 20, 1.5},
       {40, 0, 40},
       0.70703125,
       false,
       "slanted face, just below"},
      {{1.5, -20, 1.5},
       {1.5, 20, 1.5},
       {40, 0, 40},
       0.7071075439453125,
       true,
       "slanted face, just above"},
      // A face whose interior alone comes near the rim: the plane
      // (p - (1, 0, 1)) . (3, 0, 4) / 5 = 0.3125 (distance 0.3125 from the
      // whole cylinder, whose support in that direction is the rim point),
      // with its foot (1.1875, 0, 1.25) inside the triangle.
      {{9.1875, 0, -4.75},
       {-6.8125, 10, 7.25},
       {-6.8125, -10, 7.25},
       0.3125,
       true,
       "face interior over rim, at d"},
      {{9.1875, 0, -4.75},
       {-6.8125, 10, 7.25},
       {-6.8125, -10, 7.25},
       0.31249999999999994,
       false,
       "face interior over rim, 1 ulp below"},
      // The torus around the bottom rim (mirror of the corner case).
      {{1.5, 0, -1.5}, {3, 0, -3}, {3, 1, -3}, 0.75, true, "bottom corner"},
      {{1.5, 0, -1.5}, {3, 0, -3}, {3, 1, -3}, 0.5, false, "bottom corner"},
  };
  for (const Case& c : cases) {
    const TriCase k = local(1, 2, c.a, c.b, c.c);
    SCOPED_TRACE(std::string(c.what) + " " + describe(k, c.m));
    EXPECT_EQ(oracleWithin(k, c.m), c.want) << "oracle";
    EXPECT_EQ(withinDistance(k.cyl, k.tri, c.m), c.want) << "kernel";
    EXPECT_EQ(withinDistance(k.cyl, k.pose, k.tri, c.m), c.want);
  }
}

TEST(Margin, DegenerateSizesAndTriangles) {
  // r = 0 (the axis segment) and lz = 0 (a disk); point and segment
  // triangles.
  const V p{3, 4, 0};  // 5 from the axis
  const TriCase seg = local(0, 0, p, p, p);
  EXPECT_TRUE(withinDistance(seg.cyl, seg.tri, 5.0));
  EXPECT_FALSE(withinDistance(seg.cyl, seg.tri, std::nextafter(5.0, 0.0)));
  const TriCase up = local(0, 2, {0, 3, 5}, {0, -3, 5}, {0, -3, 5});
  // A segment 4 over the top end (0, 0, 1) of the axis segment.
  EXPECT_TRUE(withinDistance(up.cyl, up.tri, 4.0));
  EXPECT_FALSE(withinDistance(up.cyl, up.tri, std::nextafter(4.0, 0.0)));
  // Over a disk of radius 1 (lz = 0): the point (4, 0, 4) is 5 from its rim.
  const TriCase disk = local(1, 0, {4, 0, 4}, {4, 0, 4}, {9, 0, 9});
  EXPECT_TRUE(withinDistance(disk.cyl, disk.tri, 5.0));
  EXPECT_FALSE(withinDistance(disk.cyl, disk.tri, std::nextafter(5.0, 0.0)));
  for (const TriCase& k : {seg, up, disk})
    for (double m : {0.0, 1.0, 4.0, 5.0, std::nextafter(5.0, 0.0)})
      EXPECT_EQ(withinDistance(k.cyl, k.tri, m), oracleWithin(k, m))
          << describe(k, m);
}

TEST(Margin, InvalidInput) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Cylinder<double> cyl{1, 2};
  const Triangle<double> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  const Pose<double> pose = identityPose<double>();
  for (double m : {nan, inf, -inf, -1.0, -0x1p-1074}) {
    EXPECT_EQ(tryWithinDistance(cyl, pose, tri, m), Answer::kInvalidInput);
    EXPECT_THROW(withinDistance(cyl, pose, tri, m), InvalidInput);
  }
  Pose<double> bad = pose;
  bad.R[1][2] = nan;
  EXPECT_EQ(tryWithinDistance(cyl, bad, tri, 1.0), Answer::kInvalidInput);
  EXPECT_EQ(tryWithinDistance(Cylinder<double>{-1, 2}, pose, tri, 1.0),
            Answer::kInvalidInput);
  Triangle<double> t2 = tri;
  t2.b.z = inf;
  EXPECT_EQ(tryWithinDistance(cyl, pose, t2, 1.0), Answer::kInvalidInput);
  {
    test::NoFpTraps no_traps;
    const float snan = std::numeric_limits<float>::signaling_NaN();
    const Triangle<float> tf{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    feclearexcept(FE_ALL_EXCEPT);
    EXPECT_EQ(tryWithinDistance(Cylinder<float>{1, 2}, identityPose<float>(),
                                tf, snan),
              Answer::kInvalidInput);
    EXPECT_EQ(fetestexcept(FE_INVALID | FE_DIVBYZERO), 0);
  }
  // Huge sizes: r + m and lz + 2m overflow double; still exact.
  const double big = 0x1.fffffffffffffp1023;
  EXPECT_TRUE(withinDistance(Cylinder<double>{big, big}, pose, tri, big));
  EXPECT_EQ(withinDistance(
                Cylinder<double>{1, 2}, pose,
                Triangle<double>{{big, 0, 0}, {big, 1, 0}, {big, 0, 1}}, big),
            true);
}

// ---------------------------------------------------------------------------
// Ties constructed exactly. Each configuration has a known distance d (a
// dyadic number), built in the cylinder frame and moved by an exact motion
// (a signed axis permutation of the world and a dyadic translation), so the
// pulled-back triangle is the constructed one bit for bit. At m = d the
// answer is true, one ulp below false; 1, 4 and 2^20 ulps either side too.

struct Tie {
  TriCase k;
  double d;
};

Tie makeTie(scenes::Rng& g, int kind) {
  const double r = std::ldexp(double(1 + g.integer(64)), -g.integer(8));
  const double h = std::ldexp(double(1 + g.integer(64)), -g.integer(8));
  const double k = std::ldexp(double(1 + g.integer(16)), -4 - g.integer(8));
  const double s = g.coin() ? 1 : -1;  // top or bottom
  Tie t;
  switch (kind) {
    case 0: {  // a vertex exactly 5k from the rim point (r, 0, s h)
      const V v{r + 3 * k, 0, s * (h + 4 * k)};
      t.k = local(r, 2 * h, v, {v.x + 3, 1, s * (v.z * s + 4)},
                  {v.x + 3, -1, s * (v.z * s + 4)});
      t.k.feature = "vertex-rim";
      t.d = 5 * k;
      break;
    }
    case 1: {  // an edge exactly 5k from the rim circle, along y
      const V a{r + 3 * k, -0.5, s * (h + 4 * k)};
      const V b{r + 3 * k, 0.5, s * (h + 4 * k)};
      t.k = local(r, 2 * h, a, b, {r + 3 * k + 3, 0, s * (h + 4 * k + 4)});
      t.k.feature = "edge-rim-tangent";
      t.d = 5 * k;
      break;
    }
    case 2: {  // an edge in the meridian plane, tangent to the tube
      const double x0 = r + 3 * k, z0 = h + 4 * k, T = std::min(r, k) / 4;
      const V a{x0 + 4 * T, 0, s * (z0 - 3 * T)};
      const V b{x0 - 4 * T, 0, s * (z0 + 3 * T)};
      t.k = local(r, 2 * h, a, b, {x0 + 3, 0.25, s * (z0 + 4)});
      t.k.feature = "edge-rim-meridian";
      t.d = 5 * k;
      break;
    }
    case 3: {  // an edge exactly d from the barrel (parallel to the axis)
      const double d = 4 * k;
      t.k = local(r, 2 * h, {r + d, 0, -h / 2}, {r + d, 0, h / 2},
                  {r + d + 1, 0.5, 0});
      t.k.feature = "edge-barrel";
      t.d = d;
      break;
    }
    case 4: {  // an edge tangent to the grown barrel in its projection
      const double d = 4 * k;
      t.k = local(r, 2 * h, {r + d, -2 * r, 0}, {r + d, 2 * r, 0},
                  {r + d + 1, 0, 0});
      t.k.feature = "edge-barrel-tangent";
      t.d = d;
      break;
    }
    case 5: {  // a face whose interior alone is 5k from the rim circle
      // The plane through f = (r + 3k, 0, s (h + 4k)) normal to
      // u = (3, 0, 4 s)/5 is 5k from the whole cylinder (its support in
      // direction u is attained at the rim point (r, 0, s h)); f is the
      // midpoint of a vertex and the midpoint of the opposite edge.
      const V f{r + 3 * k, 0, s * (h + 4 * k)};
      t.k = local(r, 2 * h, {f.x + 8, 0, f.z - 6 * s},
                  {f.x - 8, 10, f.z + 6 * s}, {f.x - 8, -10, f.z + 6 * s});
      t.k.feature = "face-rim";
      t.d = 5 * k;
      break;
    }
    default: {  // a face exactly d over a cap, covering the axis
      const double d = 4 * k, z = s * (h + d);
      t.k = local(r, 2 * h, {-3 * r, -3 * r, z}, {3 * r, -3 * r, z},
                  {0, 3 * r, z});
      t.k.feature = "face-cap";
      t.d = d;
      break;
    }
  }
  // An exact motion of the world: signed permutation and dyadic shift.
  const test::SignedPermutation P = test::SignedPermutation::nth(g.integer(48));
  const V shift{double(g.integer(64) - 32), double(g.integer(64) - 32),
                double(g.integer(64) - 32)};
  auto move = [&](V x) {
    const V y = P(x);
    return V{y.x + shift.x, y.y + shift.y, y.z + shift.z};
  };
  Pose<double> pose = P(identityPose<double>());
  pose.t = shift;
  t.k.pose = pose;
  t.k.tri = {move(t.k.tri.a), move(t.k.tri.b), move(t.k.tri.c)};
  return t;
}

TEST(Margin, ExactTies) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x7a11);
  const long n = test::scaled(350);
  long checked = 0;
  for (long i = 0; i < n; ++i) {
    const Tie t = makeTie(g, int(i % 7));
    for (std::int64_t u : {0, -1, 1, -4, 4, -(1 << 20), 1 << 20}) {
      const double m = ulpsFrom(t.d, u);
      const bool want = u >= 0;
      SCOPED_TRACE("case " + std::to_string(i) + " ulps " + std::to_string(u) +
                   " " + describe(t.k, m));
      ASSERT_EQ(oracleWithin(t.k, m), want) << "oracle";
      ASSERT_EQ(tryWithinDistance(t.k.cyl, t.k.pose, t.k.tri, m),
                want ? Answer::kIntersect : Answer::kDisjoint);
      ++checked;
    }
    // The float path: every constructed value is a float too when k, r, h
    // have few bits (they do: at most 7 significant bits).
    const Cylinder<float> cf{float(t.k.cyl.radius), float(t.k.cyl.lz)};
    Pose<float> pf;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) pf.R[a][b] = float(t.k.pose.R[a][b]);
    pf.t = {float(t.k.pose.t.x), float(t.k.pose.t.y), float(t.k.pose.t.z)};
    auto f3 = [](const V& v) {
      return Vec3<float>{float(v.x), float(v.y), float(v.z)};
    };
    const Triangle<float> tf{f3(t.k.tri.a), f3(t.k.tri.b), f3(t.k.tri.c)};
    const float df = float(t.d);
    EXPECT_TRUE(withinDistance(cf, pf, tf, df)) << describe(t.k, t.d);
    EXPECT_FALSE(withinDistance(cf, pf, tf, std::nextafter(df, 0.0f)))
        << describe(t.k, t.d);
  }
  std::printf("[ stats ] exact ties: %ld margins checked\n", checked);
}

// ---------------------------------------------------------------------------
// Margins 1, 4 and 2^20 ulps either side of a true distance of random
// scenes: the true distance is bracketed between two adjacent doubles lo <
// hi (bisection over the doubles' bit patterns, steered by the kernel for
// speed, the bracket itself then confirmed by the oracle: false at lo, true
// at hi), and the kernel must agree with the oracle at each margin around.

TEST(Margin, UlpsAroundTrueDistance) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  const long n = test::scaled(40);
  long checked = 0;
  for (scenes::Family fam : scenes::kAllFamilies) {
    for (long i = 0; i < n; ++i) {
      const TriCase k = scenes::generate(fam, seed ^ 0xd157, std::uint64_t(i));
      if (oracleWithin(k, 0)) continue;  // distance 0: nothing to bracket
      auto at = [](std::int64_t b) {
        double x;
        std::memcpy(&x, &b, sizeof x);
        return x;
      };
      auto kernel = [&](double m) {
        return tryWithinDistance(k.cyl, k.pose, k.tri, m) == Answer::kIntersect;
      };
      std::int64_t lo = 0, hi = 0x7fefffffffffffff;  // kernel(lo) false
      if (!kernel(at(hi))) continue;                 // farther than DBL_MAX
      while (hi - lo > 1) {
        const std::int64_t mid = lo + (hi - lo) / 2;
        (kernel(at(mid)) ? hi : lo) = mid;
      }
      SCOPED_TRACE(std::string(scenes::familyName(fam)) + " case " +
                   std::to_string(i) + " " + describe(k, at(lo)));
      ASSERT_FALSE(oracleWithin(k, at(lo))) << "bracket, low end";
      ASSERT_TRUE(oracleWithin(k, at(hi))) << "bracket, high end";
      for (std::int64_t u : {0, 1, 4, 1 << 20}) {
        for (double m : {ulpsFrom(at(lo), -u), ulpsFrom(at(hi), u)}) {
          SCOPED_TRACE(std::string(scenes::familyName(fam)) + " case " +
                       std::to_string(i) + " " + describe(k, m));
          ASSERT_EQ(
              tryWithinDistance(k.cyl, k.pose, k.tri, m),
              oracleWithin(k, m) ? Answer::kIntersect : Answer::kDisjoint);
          ++checked;
        }
      }
    }
  }
  std::printf("[ stats ] ulps around true distances: %ld margins checked\n",
              checked);
}

// ---------------------------------------------------------------------------
// Hostile inputs: every length, rotation entry and the margin with a random
// exponent, inside the range gate (lengths 2^-1070 .. 2^40, rotation
// entries below 2: the tori's filter then runs on inputs whose exact
// scaling fails, with certified rounding) and outside it (2^-1070 ..
// 2^1020: the same filter on rescaled inputs, then GMP), judged by the
// oracle.

TEST(Margin, HostileExponentsAgreeWithOracle) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x486f7374u);
  auto next = [&g] { return g.next(); };
  const long n = test::scaled(40);
  for (const int len_hi : {40, 1020}) {
    const int rot_hi = len_hi == 40 ? 0 : 1020;
    long within = 0;
    test::StageCounts stages;
    for (long i = 0; i < n; ++i) {
      const TriCase k = scenes::randomExponentCase(next, len_hi, rot_hi);
      double big = std::max(k.cyl.radius, k.cyl.lz);
      for (const V* p : {&k.tri.a, &k.tri.b, &k.tri.c, &k.pose.t})
        big =
            std::max({big, std::fabs(p->x), std::fabs(p->y), std::fabs(p->z)});
      // Relative to the largest length, or to the cylinder's size: both
      // answers occur, and the tori are reached.
      const double ref = i % 2 == 0 ? big : std::max(k.cyl.radius, k.cyl.lz);
      const double m = std::ldexp(
          std::fabs(scenes::randomExponent(next, -60, 0)), std::ilogb(ref));
      SCOPED_TRACE("case " + std::to_string(i) + " " + describe(k, m));
      const bool want = oracleWithin(k, m);
      const Decision d = decideWithinDistance(k.cyl, k.pose, k.tri, m);
      stages.add(d.stage);
      within += want;
      ASSERT_EQ(d.answer == Answer::kIntersect, want);
    }
    std::printf(
        "[ stats ] hostile exponents up to 2^%d: %ld cases, %ld "
        "within; %s\n",
        len_hi, n, within, stages.summary(n).c_str());
  }
}

/// A double in [1, 2) with `bits` significant bits.
double randomMantissa(scenes::Rng& g, int bits) {
  return 1.0 + std::ldexp(double(g.next() >> (64 - (bits - 1))), 1 - bits);
}

/// Margins at the distance d of case k (known by construction) and 1, 4
/// ulps either side: true iff >= d, by the oracle and by the kernel.
void checkMarginsAroundDistance(const TriCase& k, double d, long i,
                                test::StageCounts* stages, long* checked) {
  for (std::int64_t u : {0, -1, 1, -4, 4}) {
    const double m = ulpsFrom(d, u);
    const bool want = u >= 0;
    SCOPED_TRACE("case " + std::to_string(i) + " ulps " + std::to_string(u) +
                 " " + describe(k, m));
    ASSERT_EQ(oracleWithin(k, m), want) << "oracle";
    const Decision dec = decideWithinDistance(k.cyl, k.pose, k.tri, m);
    stages->add(dec.stage);
    ASSERT_EQ(dec.answer, want ? Answer::kIntersect : Answer::kDisjoint);
    ++*checked;
  }
}

// ---------------------------------------------------------------------------
// Ties whose coordinates span 2000 binary orders (outside the range gate:
// the torus edges' exact stage in GMP integers, the quartic's coefficients
// of about 12,000 bits). In the cylinder frame, with e a dyadic of at most
// 48 significant bits (so that 3e, 4e and 5e are exact) and (a, b) =
// (3, 4) or (4, 3), the point P = (r + a e, 0, h + b e) is exactly 5e from
// the rim point (r, 0, h), on the torus' outer upper quarter, where neither
// sized cylinder reaches it (rho > r, z > h). Two constructions:
//  - tangent: the edge through P along y (perpendicular to the meridian
//    plane, so tangent to the tube at P; every other point of the line is
//    farther from the rim), the third vertex higher up; the edge's ends are
//    +-A in y, A up to 2^1020, or 2^1020 times a rotation entry up to
//    2^1020 (the pulled-back triangle is what is judged);
//  - vertex: P a vertex (lz = 0, so h = 0 and A + b e is exact as the
//    pulled-back z), the other two at (r + a e, +-A, b e + A): along both
//    edges and across the face rho >= r + a e and z >= b e, so P is the
//    nearest point.
// The local coordinates come from world vertices and a translation
// t = (-a e, 0, -b e) (x - t is exact in the pull-back). Margins 5e and
// 1, 4 ulps either side: true iff >= 5e, by construction and by the oracle.
TEST(Margin, WideSpreadTiesAgreeWithConstruction) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x57696465u);
  auto mantissa = [&g](int bits) { return randomMantissa(g, bits); };
  const long n = test::scaled(24);
  long checked = 0;
  test::StageCounts stages;
  for (long i = 0; i < n; ++i) {
    const bool tangent = i % 2 == 0;
    const double a = (i / 2) % 2 == 0 ? 3 : 4, b = 7 - a;
    const double e =
        std::ldexp(mantissa(48), -1000 + int(g.next() % 200));  // tiny tube
    const double r = std::ldexp(mantissa(53), int(g.next() % 41) - 20);
    const double lz =
        tangent ? std::ldexp(mantissa(53), int(g.next() % 41) - 20) : 0.0;
    const double h = lz / 2;
    const double A = std::ldexp(mantissa(53), 900 + int(g.next() % 121));
    TriCase k;
    k.cyl = {r, lz};
    k.pose = identityPose<double>();
    k.pose.t = {-a * e, 0, -b * e};
    k.feature = tangent ? "wide tangent edge" : "wide vertex";
    // Half the tangent edges reach through R: world y = +-A is pulled back
    // to +-R11 A.
    if (tangent && g.next() % 2 == 0)
      k.pose.R[1][1] = std::ldexp(mantissa(53), 900 + int(g.next() % 121));
    if (tangent)
      k.tri = {{r, -A, h}, {r, A, h}, {r, A, h + std::max(lz, r)}};
    else
      k.tri = {{r, 0, 0}, {r, A, A}, {r, -A, A}};
    checkMarginsAroundDistance(k, 5 * e, i, &stages, &checked);
    if (HasFatalFailure()) return;
  }
  std::printf("[ stats ] wide-spread ties: %ld margins checked; %s\n", checked,
              stages.summary(checked).c_str());
}

// A wide horizontal triangle (corners 2^900 .. 2^1020 away) over a tiny
// cylinder whose axis passes through it, at height z0 = h + e above the
// centre: every point of the triangle is at least z0 - h = e from the
// cylinder (its plane is), and the point over the axis is exactly e from
// the top face, so the distance is e (h and e chosen so that z0 - h is
// exact). Margins e and 1, 4 ulps either side: true iff >= e. At e the
// axis certificate of the wide path (axisHit: the triangle meets the axis
// within |z| <= h + m) decides; below, every part must miss. The radius
// is far below or far above the margin (the ball test first or not).
TEST(Margin, WideTrianglesOverTheAxisAgreeWithConstruction) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x41786973u);
  test::StageCounts stages;
  long checked = 0;
  for (long i = 0, n = test::scaled(8); i < n; ++i) {
    // h's last bit and e's are both 2^-429: z0 = h + e is exact.
    const double h = std::ldexp(randomMantissa(g, 30), -400);
    const double e = std::ldexp(randomMantissa(g, 20), -410);
    const double z0 = h + e;
    const double r =
        std::ldexp(randomMantissa(g, 53), i % 2 == 0 ? -500 : -300);
    const double A =
        std::ldexp(randomMantissa(g, 53), 900 + int(g.next() % 121));
    TriCase k;
    k.cyl = {r, 2 * h};
    k.pose = identityPose<double>();
    k.feature = "wide triangle over the axis";
    k.tri = {{-A, -A, z0}, {A, -randomMantissa(g, 53) * A, z0}, {0, A, z0}};
    checkMarginsAroundDistance(k, e, i, &stages, &checked);
    if (HasFatalFailure()) return;
  }
  std::printf(
      "[ stats ] wide triangles over the axis: %ld margins checked; %s\n",
      checked, stages.summary(checked).c_str());
}

// Margins at the exact threshold of hostile inputs outside the range gate:
// the queries that pass every part but one by a hair (both sized cylinders,
// the torus edges and both faces decided before the answer), the slowest
// ones. The threshold is bracketed between two adjacent doubles by
// bisection steered by the kernel, and the bracket confirmed by the oracle
// (false at the low end, true at the high end). The oracle takes up to a
// few seconds on these inputs: few cases by default.
TEST(Margin, HostileThresholdsAgreeWithOracle) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x5468726573u);
  auto next = [&g] { return g.next(); };
  const long n = test::scaled(3);
  auto at = [](std::int64_t bits) {
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  };
  long found = 0;
  for (long tries = 0; found < n && tries < 400 * n; ++tries) {
    const TriCase k = scenes::randomExponentCase(next, 1020, 1020);
    auto kernel = [&](double m) {
      return tryWithinDistance(k.cyl, k.pose, k.tri, m) == Answer::kIntersect;
    };
    if (kernel(0)) continue;  // distance 0: no threshold
    std::int64_t lo = 0, hi = 0x7fefffffffffffff;
    if (!kernel(at(hi))) continue;
    while (hi - lo > 1) {
      const std::int64_t mid = lo + (hi - lo) / 2;
      (kernel(at(mid)) ? hi : lo) = mid;
    }
    // Only thresholds decided by a torus: at the high end neither sized
    // cylinder holds a point of the triangle.
    const double m = at(hi);
    if (margin_oracle::sizedCylinders(k.cyl, k.pose, k.tri, m)) continue;
    ++found;
    SCOPED_TRACE("case " + std::to_string(found) + " " + describe(k, at(lo)));
    ASSERT_FALSE(oracleWithin(k, at(lo))) << "bracket, low end";
    ASSERT_TRUE(oracleWithin(k, m)) << "bracket, high end";
  }
  std::printf("[ stats ] hostile thresholds decided by a torus: %ld\n", found);
  EXPECT_EQ(found, n) << "too few thresholds decided by a torus";
}

// The regression list bench/data/margin_worst.txt (the slowest threshold
// queries of tricyl-margin-stage-costs, margins 1 ulp below and above the
// flip: the wide torus edges' local certificate decides most of them, the
// capsule around the axis the last two): each answer
// against the exact oracle, with the margin and its two neighbours.
const char* const kRegressionList[] = {
    "0x1.59da3c8acde6bp+910 0x1.792ab0d8c910fp-125 -0x1.1f146a2310ebep+268 "
    "-0x1.429f00dbc4bddp+989 -0x1.e177a56fb5a99p-147 -0x1.ef42713212a28p-894 "
    "-0x1.3478f5a9b584ap-748 0x1.a9ac590a253f3p+71 -0x1.10c7022c64107p-322 "
    "-0x1.3a07648ba7d66p+273 0x1.66bfba253d61p-184 -0x1.95cf7783ad969p-704 "
    "-0x1.b4f8b686e38c7p-818 0x1.233bd579ff134p-209 -0x1.88aa86b5312b6p-602 "
    "0x1.b922a9aa8bf68p+577 -0x1.91b10f92eee6ap-473 -0x1.e3390a31578ebp+168 "
    "-0x1.385d846482a06p-66 -0x1.e19b8a60f548fp+219 0x1.7d569f1fa68b8p-556 "
    "0x1.e8cfc407fe6cbp-192 0x1.91e96a73d20d1p-307 0x1.90805642e76dfp-120",
    "0x1.7a313fbdd162p+1000 0x1.2690aa754be21p-385 0x1.3293bb3ec27eap-377 "
    "-0x1.6051b58f68653p-713 0x1.5cef68b190318p+580 -0x1.5fa87d095bccap+949 "
    "-0x1.2a07dba800a6cp+575 0x1.ace742fd5b66bp+141 0x1.f85905917e228p+1009 "
    "0x1.8f6b076ae998p-557 0x1.93b96dfe9eca8p+99 0x1.c0feba3d31014p+382 "
    "-0x1.706416ab004fep-208 -0x1.968b959f25438p-918 0x1.f41600420b481p+941 "
    "-0x1.842a78d9fc389p-457 -0x1.a0c7616ff68e1p+564 0x1.db565ec15506cp-952 "
    "0x1.068d1484a7221p-570 0x1.b66a15164f892p-699 -0x1.94f2435c1a7d3p-238 "
    "0x1.c8331e9c052f1p+503 0x1.eb14090413c0ep-461 0x1.31fca1645f0a1p+963",
    "0x1.f9cf21c3769c8p+732 0x0.0000000035d86p-1022 0x1.72108368efd7dp+759 "
    "-0x1.aabc0c52a953cp+690 0x1.a331877d77dbp+347 -0x1.754d1e7f9ca88p+444 "
    "-0x1.43e9c9b4cf058p+456 -0x1.383e932e29f27p-491 0x1.973b00e712639p-205 "
    "-0x1.093c91e735a6cp-770 -0x1.6fd639ef214a7p+139 -0x1.07497c7f897b9p-716 "
    "0x1.6742f436ab08p-533 0x1.92bae1bb62b47p+241 0x1.4b74065ccd0efp+281 "
    "-0x1.4e477c2eee94dp-91 -0x1.e0474198fa8f6p+452 -0x1.8f4145c077b4fp+636 "
    "0x1.6f4836d09f6a2p-633 -0x1.8f519a41f4259p-797 0x1.dffbe0fb6fcc2p+195 "
    "0x1.2a7fc05891f4bp+291 0x1.c214526807224p-784 0x1.59086b741ad9bp+592",
    "0x1.b68a87ef19129p+435 0x1.d2363cf333fcep-438 -0x1.eb49ac557b68ep-761 "
    "-0x1.633e3fb3cb1c6p+415 0x1.4b8adb6454e87p-384 -0x1.6c4c05799037fp-309 "
    "-0x1.77d9496e85c8cp-916 0x1.6a383438caa25p+408 0x1.0bbfa9bd8e53bp-924 "
    "0x1.fe4079c6d4fb5p+298 -0x1.2cf1f6d3aff0fp+325 -0x1.e669ebe4e849p-973 "
    "-0x1.bc4b5f72dfadep-833 0x1.f8c7fc1688edfp-666 0x1.0d411b2d6f902p-418 "
    "-0x1.bff93c7494023p-949 -0x1.4b55221109fep-50 -0x1.29bde39aa75cp-75 "
    "0x1.c78b406850977p-49 0x1.e798c7f204fabp+34 -0x1.0c4c19a98423ep+120 "
    "0x1.6800ec1944406p-902 0x1.fdf581a82cc12p-848 0x1.8580ee86d35e8p+275",
    "0x1.d842f5fa54dd1p+221 0x1.5453a206ac0b7p-192 -0x1.a55ce73143fd7p+1020 "
    "0x1.9bddaa6ee6f3ap+847 -0x1.01b85213be7c2p+955 0x1.4d1f163f04879p+385 "
    "0x1.be0841aeedb5cp+58 -0x1.17c85168bd599p-660 -0x1.aa684cdaf3959p+1015 "
    "-0x1.549d8c6476285p-156 0x1.0857f0ecf2477p-155 0x1.faae4ce075ff8p-127 "
    "0x1.eb1d5c43e8083p-959 -0x1.221404c7cf4c6p+884 0x1.bb252407d1b64p-44 "
    "-0x1.7e6992452d67dp-1009 0x1.a24d9f9267fb7p-3 0x1.a22ee4c73540ap+345 "
    "0x1.d07c3214abdc6p+493 -0x1.b0ff720cbc4a6p+949 -0x1.e3da3d15a5da5p+523 "
    "-0x1.26becf81da635p-266 -0x1.a153be2ae438p-607 0x1.0f147b736f7dcp+487",
    "0x1.4d223d5da856ep+516 0x0.007a7e5c1f987p-1022 0x1.be1cdd0f18c3fp-380 "
    "0x1.b5f855cee9d45p-517 -0x1.037b0bff535bfp-56 0x1.0192d802b9befp+422 "
    "-0x1.8db92f9686a46p+930 0x1.fd151a57006e4p-626 0x0.0000000000064p-1022 "
    "-0x1.a3fb1488d4c93p-198 -0x1.5a69e634e5d69p+33 0x1.eb8b24130c974p+512 "
    "-0x1.e736fc24cc126p-448 -0x1.05b5a02d63134p-936 "
    "-0x0.00000000938d5p-1022 -0x1.7a9d53f2c96fcp-404 "
    "-0x1.5dcc108e6a2b1p-888 0x1.5f20c8b43f9dap+472 0x1.234391e7ebbc3p+647 "
    "-0x1.a2986ae9ba593p-765 -0x1.c5eaa6ae3000ep-226 0x1.2e9b50c35b998p-14 "
    "-0x1.d1e857bcb0c3bp-671 0x1.f23a0862d5187p+456",
    "0x1.c0eaa86204022p-382 0x1.4b48bef50f70fp-969 0x1.b619266ed82f7p+190 "
    "0x1.21cad09f282c8p+828 -0x1.5d19c1c89da9ap+757 0x1.a46f3787397f4p+9 "
    "0x1.f6ed8de0216b6p-394 -0x1.e5b115f5c4759p+518 0x1.e5b1089222fb6p-1000 "
    "-0x1.ed69c331d84a9p-696 0x1.bd7a5ba0d50a8p+537 0x1.27046ac75442cp+745 "
    "-0x1.5303972aa32b8p+72 0x1.b2abb3ee96267p+283 0x1.1dedaae21e63dp-679 "
    "-0x1.01a0557a64e72p+978 0x1.9743e25a6340dp-188 0x1.1a5b4eda7c3f6p+939 "
    "0x1.fcf6bbecae1f1p+574 -0x1.634400bc7b58fp-603 -0x1.b1f9655185a14p-491 "
    "0x1.da1a516363f2dp-753 0x1.723252e30d2e1p+415 0x1.42193548528d7p+953",
    "0x1.b9553669e3a67p+384 0x1.59cecf7343874p+730 -0x1.e8dbdc88873d8p-957 "
    "0x1.3e3c48ed93f39p+963 -0x1.73ff181dbc90ep-225 -0x1.f818b74e6c6c7p+779 "
    "0x1.ce82549884d28p+926 0x1.e3b2d96f69ba4p+818 -0x1.91075461b97dbp-733 "
    "0x1.139ecf73e68adp-994 -0x1.c73b24f01caf2p-947 -0x1.312006ca710dap-235 "
    "0x1.6477a3999bac1p+100 0x1.6639925604a9bp+385 -0x1.6cb165719da4p-502 "
    "-0x1.690ddd25ee7efp+637 0x1.73b4b4e14b95ep-302 0x1.ee011a0148f8dp+1009 "
    "0x1.df41090417f55p+252 -0x1.f81568e643625p+70 -0x1.cab69a9befa38p-283 "
    "0x1.d448464c710fdp-93 -0x1.659d906746ab8p+702 0x1.50c361cf8f24cp+919",
    "0x1.b7e708bdda62bp-641 0x1.d3ab433251df5p-209 -0x1.4a22f80c6e6adp+317 "
    "-0x1.2dceb3ccedb35p+919 0x1.0c3255be3b294p-502 0x1.f7a58ccab86efp-282 "
    "0x1.a5f0324d98c02p-787 -0x1.052eaa648cd18p-975 -0x1.bb7610ed6471bp-496 "
    "0x1.08a484d43b4a6p+256 -0x1.1b5f567a0c13p+156 -0x1.5da5de94d0bedp-501 "
    "-0x1.9617411c4a2e7p-967 0x1.12a97b130d3cep-200 -0x1.042d6978bc77ap+800 "
    "0x1.8ca5f1269fef9p+122 0x1.fcabef3fb353fp+900 -0x1.cc9a74d7a8ba1p-531 "
    "-0x1.65e7789a81187p+570 -0x1.a49a251ea15c6p-133 -0x1.e00b25422f77ep-65 "
    "0x1.ed4beb8cb79d2p+176 -0x1.60027f44ddfa4p-872 0x1.6010a07f27d7bp+289",
    "0x1.5cb088c296307p-786 0x1.38e2945a3072p-400 -0x1.5a51500d67f2dp+797 "
    "-0x1.89330d8ce6d39p+860 -0x1.8d4e43d5eb042p+410 0x1.4c422105c2af8p-86 "
    "-0x1.a8be768fbddccp+388 -0x1.7febf8bada7b7p-204 0x1.961e08dd122d2p-186 "
    "0x1.da3adbfcf0094p-27 0x1.fb05563909127p+372 -0x1.54a958e87e882p+493 "
    "-0x1.a14e15a8a8356p+407 -0x1.7766ed6e0adap+517 0x1.98358998474bcp+806 "
    "0x1.8a7195f972d4p+646 0x1.b9e98bf6d5aadp-1022 -0x1.de0925f627be1p+485 "
    "-0x1.60283d11b5923p-875 0x1.4a49acd65ab05p+251 -0x1.1439e63a68e3p+553 "
    "0x1.ec5d450c5c151p+170 -0x1.92d481cc7a749p-884 0x1.73c055d5e4cfcp+890",
    "0x1.a2a3d7737ae5dp-660 0x1.9a381ad27da4fp+682 0x1.78f0fb694075fp+953 "
    "0x1.09d079eab1cddp-168 0x1.17c51664095ecp-16 0x1.78857f0282372p-810 "
    "-0x1.28f8bdb598ddcp-698 0x1.a5b9c6e537568p-327 -0x1.3a0b59c67ad9dp-894 "
    "-0x1.a0b8a443f0082p-420 -0x1.c44642810cb9bp+385 0x1.3f13aaf4597e3p+847 "
    "0x1.5fdef10e021afp+153 -0x1.8d013e9344d45p+358 0x1.c3f735d07d89cp+867 "
    "-0x1.4e1e96d0035a3p+127 0x1.1e9e6c540863ep-847 -0x1.4b410d04de3ccp+241 "
    "-0x1.74662b2973b24p+445 0x0.000000053aebfp-1022 0x1.fb02a2f070143p+433 "
    "0x1.2c22130df37a6p+67 0x1.e9b402df3993ep+410 0x1.5eb193facaa52p+744",
    "0x1.1e6b8b0fb90cdp-41 0x1.ae48d0a069a92p-555 -0x1.0c5c1fe71063fp+271 "
    "-0x1.4ab8e39bd86e8p+916 0x1.d59435f3bba92p+456 -0x1.56bfcd27e81a8p-411 "
    "-0x1.1000eaddee99cp+866 -0x1.234ef5a6898f6p+123 -0x1.ca51562380432p-650 "
    "0x1.2f0a129f56b41p+82 -0x1.a1e5f1b666265p-546 0x1.1375807472a58p+284 "
    "-0x1.221e294d65c4fp-329 -0x1.5a1a7ca4d2a0bp+459 0x1.3da85fad50798p-929 "
    "0x1.a93da8eb0864cp-642 0x1.52d4d336ea9cp+17 0x1.dd4803b2978b3p+466 "
    "0x1.ccd4ebdddd9efp+485 -0x1.7d1c6cf1ed0b7p-833 -0x1.7683dd047ed11p-986 "
    "-0x1.32c12ce121d64p+0 -0x0.00202f56e593ep-1022 0x1.913d9381cedddp+709",
    "0x1.39e0e76f66999p-801 0x1.02415754bc196p-947 0x1.e8a13ecef8153p-544 "
    "0x1.918dfadc46b49p+411 0x1.6860aa3475be3p+688 0x1.47d9203c7179ep+309 "
    "-0x1.58a1dcf72ba37p-424 -0x1.9cda02beb521ap-781 "
    "-0x1.484516dabad5bp+305 -0x1.a89d680258d11p-941 "
    "-0x1.8b172632e13b3p-1006 0x1.c29ac9f2ed1ffp+82 "
    "-0x1.1cf371dba08f6p+441 0x1.5ebfbd7b021a1p+294 0x1.a8f1f48b25f7dp+919 "
    "0x1.be9c46174af66p-964 -0x1.787b87f57f806p-985 "
    "0x1.c2af12c14ea52p-1021 0x1.c70770262a19ap+83 0x1.77e1e1c8d8707p-531 "
    "-0x1.c4d1d8b399a1ap-918 -0x1.eb17aa2203144p+525 "
    "0x1.166810bff91abp-779 0x1.d8caeaa1ffa6dp-134",
    "0x0.0000000000066p-1022 0x1.de64a5c8392e2p-481 "
    "-0x1.e47eaedd1e05cp-778 0x1.2a978e7f9ab21p+832 "
    "-0x1.7db80db0e41f8p-158 0x1.b13b9e7d07cbap+513 0x1.d16706b2b33c4p-460 "
    "-0x1.d3ee46168a3eap+1014 0x1.cf55ea81ad6dep-605 "
    "-0x1.ead7b0bad8b6dp-504 -0x1.a5d620b1ca65p+187 -0x1.013bf9c7fb6p+187 "
    "-0x1.1491263979849p-21 0x1.fe918a3a56bd1p-156 0x1.4c753a9625bc1p+971 "
    "0x1.840c6c52565acp+862 0x1.413e572af22d2p-869 -0x1.e809f72bc4a8ap+888 "
    "0x1.59584441afc2fp+486 -0x1.d92b59053dep-340 0x1.427f862dc0d3ep+1000 "
    "-0x1.4808464b9c8fcp+953 0x1.fcbcb752713f2p-359 0x1.8576efb20f1b2p-469",
};

// A line of kRegressionList: the cylinder r lz, R row-major, t, the three
// vertices, the margin. False if a number is missing.
bool parseListCase(const char* line, TriCase* k, double* m) {
  double v[24];
  const char* p = line;
  for (double& x : v) {
    char* end = nullptr;
    x = std::strtod(p, &end);
    if (end == p) return false;
    p = end;
  }
  *k = TriCase{};
  k->cyl = {v[0], v[1]};
  k->pose = identityPose<double>();
  for (int j = 0; j < 3; ++j)
    for (int c = 0; c < 3; ++c) k->pose.R[j][c] = v[2 + 3 * j + c];
  k->pose.t = {v[11], v[12], v[13]};
  k->tri = {
      {v[14], v[15], v[16]}, {v[17], v[18], v[19]}, {v[20], v[21], v[22]}};
  *m = v[23];
  return true;
}

TEST(Margin, RegressionListAgreesWithOracle) {
  for (const char* line : kRegressionList) {
    TriCase k;
    double m0 = 0;
    ASSERT_TRUE(parseListCase(line, &k, &m0)) << line;
    SCOPED_TRACE(line);
    for (double m : {std::nextafter(m0, 0.0), m0, std::nextafter(m0, 1e308)})
      EXPECT_EQ(
          tryWithinDistance(k.cyl, k.pose, k.tri, m) == Answer::kIntersect,
          oracleWithin(k, m))
          << "margin " << m;
  }
}

// Thresholds near the last two queries of kRegressionList (a cylinder
// 2^-600 and more below the margin, vertices' coordinates up to 2^1000:
// every part ties at the flip beyond the windows' 1,280 bits, and the
// capsule around the axis, capsulePart in src/triangle_cylinder_margin.cpp,
// decides both ways): r and lz each scaled by 2^-k (k < 200), or r set to
// m 2^-k (48 <= k < 60), the vertices in a random cyclic order, the
// threshold bracketed by bisection steered by the kernel and confirmed by
// the oracle at both ends.
TEST(Margin, TinyCylinderThresholdsAgreeWithOracle) {
  constexpr std::size_t kCount = sizeof kRegressionList / sizeof(char*);
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x43617073u);
  const long n = test::scaled(4);
  auto at = [](std::int64_t bits) {
    double x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  };
  for (long i = 0; i < n; ++i) {
    TriCase k;
    double m0 = 0;
    ASSERT_TRUE(parseListCase(kRegressionList[kCount - 2 + i % 2], &k, &m0));
    // Every other pair: r near the gap between the distance and the
    // threshold (an ulp of m), where the capsule's band of width r (neither
    // beyond r + m nor within m) decides some and leaves some to the parts.
    const double r = i % 4 < 2 ? std::ldexp(k.cyl.radius, -int(g.next() % 200))
                               : std::ldexp(m0, -48 - int(g.next() % 12));
    k.cyl = {r, std::ldexp(k.cyl.lz, -int(g.next() % 200))};
    const int s = int(g.next() % 3);
    const V w[3] = {k.tri.a, k.tri.b, k.tri.c};
    k.tri = {w[s], w[(s + 1) % 3], w[(s + 2) % 3]};
    auto kernel = [&](double m) {
      return tryWithinDistance(k.cyl, k.pose, k.tri, m) == Answer::kIntersect;
    };
    std::int64_t lo = 0, hi = 0x7fefffffffffffff;
    ASSERT_FALSE(kernel(0));
    ASSERT_TRUE(kernel(at(hi)));
    while (hi - lo > 1) {
      const std::int64_t mid = lo + (hi - lo) / 2;
      (kernel(at(mid)) ? hi : lo) = mid;
    }
    SCOPED_TRACE("case " + std::to_string(i) + " " + describe(k, at(lo)));
    ASSERT_FALSE(oracleWithin(k, at(lo))) << "bracket, low end";
    ASSERT_TRUE(oracleWithin(k, at(hi))) << "bracket, high end";
  }
}

// ---------------------------------------------------------------------------
// The six families, margins 0..10% of the size; margin 0 is intersect.

/// A case rounded to float, and the same float values widened (exactly).
struct FloatCase {
  Cylinder<float> cyl;
  Pose<float> pose;
  Triangle<float> tri;
  float m;
  TriCase widened;
};

/// double -> float through memory. A compiler bug, not ours: GCC 12.2
/// (Debian 12.2.0-14), at -O2 and -O3, miscompiles toFloat below with a
/// plain cast. The SLP vectorizer turns two adjacent narrowings and their
/// widenings into (vector(2) double)(vector(2) float) x, and a later pass
/// (fre5 in -fdump-tree-all) folds that pair to x: the widened values of
/// two lanes (the third vertex's x and y) were the original doubles, not
/// the floats the kernel answers for, so the oracle judged other inputs.
/// x86-64 SSE has no excess precision (FLT_EVAL_METHOD 0; -fexcess-precision
/// concerns x87 only), and the scalar (double)(float)x is kept; four lines
/// of C reproduce it (docs/margin.md, "Toolchain"), -fno-tree-slp-vectorize
/// or clang 14 do not. A volatile float forces the rounded value.
float narrow(double x) {
  volatile float f = static_cast<float>(x);
  return f;
}

FloatCase toFloat(const TriCase& k, double m) {
  FloatCase f;
  auto v3 = [](const V& v) {
    return Vec3<float>{narrow(v.x), narrow(v.y), narrow(v.z)};
  };
  auto w3 = [](const Vec3<float>& v) {
    return V{double(v.x), double(v.y), double(v.z)};
  };
  f.cyl = {narrow(k.cyl.radius), narrow(k.cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.pose.R[i][j] = narrow(k.pose.R[i][j]);
  f.pose.t = v3(k.pose.t);
  f.tri = {v3(k.tri.a), v3(k.tri.b), v3(k.tri.c)};
  f.m = narrow(m);
  f.widened.cyl = {double(f.cyl.radius), double(f.cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) f.widened.pose.R[i][j] = double(f.pose.R[i][j]);
  f.widened.pose.t = w3(f.pose.t);
  f.widened.tri = {w3(f.tri.a), w3(f.tri.b), w3(f.tri.c)};
  return f;
}

class MarginFamily : public ::testing::TestWithParam<scenes::Family> {};

TEST_P(MarginFamily, AgreesWithOracle) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  const scenes::Family fam = GetParam();
  scenes::Rng g(seed ^ 0x3a46 ^ std::uint64_t(fam));
  const long n = test::scaled(1500);
  long yes = 0, wrong = 0;
  test::StageCounts stages;
  for (long i = 0; i < n; ++i) {
    const TriCase k = scenes::generate(fam, seed, std::uint64_t(i));
    const double size = std::max(k.cyl.radius, k.cyl.lz);
    const double m = i % 8 == 0 ? 0.0 : 0.1 * size * g.uniform();
    SCOPED_TRACE(std::string(scenes::familyName(fam)) + " case " +
                 std::to_string(i) + " " + describe(k, m));
    const bool want = oracleWithin(k, m);
    const Decision d = decideWithinDistance(k.cyl, k.pose, k.tri, m);
    stages.add(d.stage);
    yes += want;
    if ((d.answer == Answer::kIntersect) != want) {
      ++wrong;
      ADD_FAILURE() << "kernel " << (want ? "false" : "true");
    }
    // Margin 0 is intersect, on every case.
    ASSERT_EQ(tryWithinDistance(k.cyl, k.pose, k.tri, 0.0),
              tryIntersect(k.cyl, k.pose, k.tri))
        << "margin 0";
    // The float path on the case rounded to float (judged on the widened
    // float values, which are the inputs it answers for).
    const FloatCase f = toFloat(k, m);
    const bool want_f = margin_oracle::withinDistance(
        f.widened.cyl, f.widened.pose, f.widened.tri, double(f.m));
    if ((tryWithinDistance(f.cyl, f.pose, f.tri, f.m) == Answer::kIntersect) !=
        want_f) {
      ++wrong;
      ADD_FAILURE() << "float kernel " << (want_f ? "false" : "true") << " on "
                    << describe(f.widened, double(f.m));
    }
  }
  std::printf(
      "[ stats ] %s: %ld cases (double and float), %ld within, %ld "
      "wrong; double: %s\n",
      scenes::familyName(fam), n, yes, wrong, stages.summary(n).c_str());
  EXPECT_EQ(wrong, 0);
}

std::string familyName(const ::testing::TestParamInfo<scenes::Family>& p) {
  return scenes::familyName(p.param);
}

INSTANTIATE_TEST_SUITE_P(Families, MarginFamily,
                         ::testing::ValuesIn(scenes::kAllFamilies), familyName);

// ---------------------------------------------------------------------------
// The decomposition itself, against a numerical distance that shares
// nothing with it: dist(T, C) = min over the triangle of the distance to C,
// a convex function of the barycentric coordinates, minimised by nested
// ternary search in double (converged far below the 1e-6 relative gap
// kept between the distance and the margin).

double pointDist(const V& p, double r, double h) {
  const double rho = std::sqrt(p.x * p.x + p.y * p.y);
  const double dr = std::max(rho - r, 0.0);
  const double dz = std::max(std::fabs(p.z) - h, 0.0);
  return std::sqrt(dr * dr + dz * dz);
}

double numericDistance(const Triangle<double>& t, double r, double h) {
  auto at = [&](double u, double v) {
    const double w = 1 - u - v;
    const V p{double(w * t.a.x + u * t.b.x + v * t.c.x),
              double(w * t.a.y + u * t.b.y + v * t.c.y),
              double(w * t.a.z + u * t.b.z + v * t.c.z)};
    return pointDist(p, r, h);
  };
  auto inner = [&](double u) {  // min over v in [0, 1 - u]
    double lo = 0, hi = 1 - u;
    for (int it = 0; it < 70; ++it) {
      const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
      if (at(u, a) <= at(u, b))
        hi = b;
      else
        lo = a;
    }
    return at(u, (lo + hi) / 2);
  };
  double lo = 0, hi = 1;
  for (int it = 0; it < 70; ++it) {
    const double a = lo + (hi - lo) / 3, b = hi - (hi - lo) / 3;
    if (inner(a) <= inner(b))
      hi = b;
    else
      lo = a;
  }
  return inner((lo + hi) / 2);
}

TEST(Margin, DecompositionAgainstNumericDistance) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed ^ 0x9d15);
  const long n = test::scaled(300);
  long compared = 0, torus_cases = 0;
  for (long i = 0; i < n; ++i) {
    // Local triangles around the rim, where the tori matter.
    const double r = g.uniform(0.2, 2), h = g.uniform(0.2, 2);
    auto pt = [&] {
      const double a = g.uniform(0, 6.283185307179586);
      const double rho = r + g.uniform(-0.5, 1.5);
      return V{rho * std::cos(a), rho * std::sin(a),
               (g.coin() ? 1 : -1) * (h + g.uniform(-0.5, 1.5))};
    };
    const TriCase k = local(r, 2 * h, pt(), pt(), pt());
    const double d = numericDistance(k.tri, r, h);
    for (int j = 0; j < 4; ++j) {
      const double m = double(d) * g.uniform(0.5, 1.5);
      if (std::fabs(m - d) <= 1e-6 * (1 + d)) continue;
      const bool want = m >= d;
      SCOPED_TRACE("case " + std::to_string(i) +
                   " d=" + std::to_string(double(d)) + " " + describe(k, m));
      ASSERT_EQ(oracleWithin(k, m), want) << "oracle";
      ASSERT_EQ(withinDistance(k.cyl, k.tri, m), want) << "kernel";
      const bool cyl_parts =
          intersect(Cylinder<double>{r + m, 2 * h}, k.tri) ||
          intersect(Cylinder<double>{r, 2 * h + 2 * m}, k.tri);
      torus_cases += want && !cyl_parts;
      ++compared;
    }
  }
  std::printf(
      "[ stats ] numeric cross-check: %ld margins, %ld decided by a "
      "torus\n",
      compared, torus_cases);
  EXPECT_GT(torus_cases, 0);
}

}  // namespace
}  // namespace tricyl
