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
  auto mantissa = [&g](int bits) {  // in [1, 2), `bits` significant bits
    return 1.0 + std::ldexp(double(g.next() >> (64 - (bits - 1))), 1 - bits);
  };
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
    const double d = 5 * e;
    for (std::int64_t u : {0, -1, 1, -4, 4}) {
      const double m = ulpsFrom(d, u);
      const bool want = u >= 0;
      SCOPED_TRACE("case " + std::to_string(i) + " ulps " + std::to_string(u) +
                   " " + describe(k, m));
      ASSERT_EQ(oracleWithin(k, m), want) << "oracle";
      const Decision dec = decideWithinDistance(k.cyl, k.pose, k.tri, m);
      stages.add(dec.stage);
      ASSERT_EQ(dec.answer, want ? Answer::kIntersect : Answer::kDisjoint);
      ++checked;
    }
  }
  std::printf("[ stats ] wide-spread ties: %ld margins checked; %s\n", checked,
              stages.summary(checked).c_str());
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
