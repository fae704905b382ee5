// The tracked stage (TrackedKernel, src/filter.h; docs/exactness.md,
// section 5): its exactness rules on literal values, and the scenes it
// exists for, exact zeros that no error bound certifies, decided without
// GMP and confirmed by the exact oracle under exact rigid motions.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>

#include "filter.h"
#include "oracle.h"
#include "test_support.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using detail::productIsExact;
using detail::Sign;
using detail::significantBits;
using detail::sumIsExact;
using detail::TrackedKernel;

TEST(TrackedRules, SignificantBits) {
  EXPECT_EQ(significantBits(1.0), 1);
  EXPECT_EQ(significantBits(-0x1p-1000), 1);
  EXPECT_EQ(significantBits(3.0), 2);
  EXPECT_EQ(significantBits(0.375), 2);
  EXPECT_EQ(significantBits(0.1), 53 - 1);  // 0x1.999999999999ap-4
  EXPECT_EQ(significantBits(0x1.fffffffffffffp0), 53);
  EXPECT_EQ(significantBits(0.0), 64);        // zero: the product rule's
  EXPECT_EQ(significantBits(0x1p-1074), 64);  // own case; subnormal: never
}

TEST(TrackedRules, SumsFlaggedExactlyWhenTheyDoNotRound) {
  auto exact = [](double a, double b) { return sumIsExact(a, b, a + b); };
  EXPECT_TRUE(exact(0.5, 0.25));
  EXPECT_TRUE(exact(0.35, -0.35));           // cancellation to 0 is exact
  EXPECT_TRUE(exact(0.7, -0.35));            // Sterbenz
  EXPECT_TRUE(exact(0x1p-1074, 0x1p-1074));  // subnormal sums are exact
  EXPECT_TRUE(exact(0x1p52, 1.0));
  EXPECT_FALSE(exact(0.1, 0.2));
  EXPECT_FALSE(exact(0x1p53, 1.0));  // 2^53 + 1 rounds to 2^53
  EXPECT_FALSE(exact(1.0, 0x1p-60));
  EXPECT_FALSE(exact(DBL_MAX, DBL_MAX));  // overflow
}

TEST(TrackedRules, ProductsFlaggedExactOnlyWhenTheyDoNotRound) {
  auto exact = [](double a, double b) { return productIsExact(a, b, a * b); };
  EXPECT_TRUE(exact(3.0, 5.0));
  EXPECT_TRUE(exact(0.35, 1.0));  // by +-1 and powers of two
  EXPECT_TRUE(exact(-0.35, 0x1p-20));
  EXPECT_TRUE(exact(0.0, 0.35));  // an exact zero
  EXPECT_TRUE(exact(0x1p-1074, 0.0));
  EXPECT_TRUE(exact(0x1.8p26, 0x1.8p26));  // 2 + 2 significant bits
  EXPECT_FALSE(exact(0.1, 0.1));
  // (2^27 + 1)(2^26 + 1) = 2^53 + 2^27 + 2^26 + 1 needs 54 bits.
  EXPECT_FALSE(exact(0x1p27 + 1, 0x1p26 + 1));
  // Underflow: a product of non-zero numbers that rounds to 0, one in the
  // subnormal range, and one just above it (below 2^-900, flagged inexact
  // although it is exact: the rule is sufficient, not necessary).
  EXPECT_FALSE(exact(0x1p-600, 0x1p-600));
  EXPECT_FALSE(exact(0x1p-537, 0x1p-537));
  EXPECT_FALSE(exact(0x1p-500, 0x1p-450));
  EXPECT_FALSE(exact(0x1p600, 0x1p600));  // overflow
}

TEST(TrackedRules, SignOfAnExactZeroIsZeroAndOfARoundedOneIsUnknown) {
  using Num = TrackedKernel::Num;
  const Num a = TrackedKernel::lift(0.7), b = TrackedKernel::lift(0.35);
  EXPECT_EQ(TrackedKernel::sign(a - (b + b)), Sign::kZero);
  // With the doubles 0.1 and 0.3, 3 * 0.1 - 0.3 = 2^-55 exactly, but the
  // product rounds and the computed value is 2^-54: not flagged exact, and
  // far below the filter's bound, so unknown (never a sign from rounding).
  const Num p = TrackedKernel::lift(0.1) * TrackedKernel::lift(3.0) -
                TrackedKernel::lift(0.3);
  EXPECT_FALSE(p.exact);
  EXPECT_EQ(TrackedKernel::sign(p), Sign::kUnknown);
  // An exact zero times a rounded value is an exact zero (a rotation
  // entry 0 times a rounded coordinate difference).
  const Num d = TrackedKernel::inputDiff(-5, 0.35);
  EXPECT_FALSE(d.exact);
  EXPECT_TRUE((TrackedKernel::lift(0.0) * d).exact);
  EXPECT_EQ(TrackedKernel::sign(TrackedKernel::lift(0.0) * d), Sign::kZero);
  EXPECT_FALSE((TrackedKernel::lift(1.0) * d).exact);
  // Inexact but far from zero: certified by FilterKernel's bound.
  EXPECT_EQ(
      TrackedKernel::sign(TrackedKernel::lift(0.1) * TrackedKernel::lift(0.1)),
      Sign::kPos);
}

// A cylinder standing exactly on a floor, the everyday exact-zero scene:
// decimal (not dyadic) coordinates, upright pose, bottom cap at z = 0
// exactly (t.z = lz / 2), floor triangles in z = 0. Every query touches
// (or misses) in the cap plane; no bound certifies a zero, so before this
// stage each went to GMP. Each expectation is confirmed by the oracle, and
// each runs under the exact rigid motions of the world below.
struct FloorCase {
  const char* name;
  Vec3<double> a, b, c;
  bool expected;
};

const FloorCase kFloor[] = {
    // r = 0.3, lz = 1.4, axis through (0.35, -1.2); floor z = 0.
    {"floor_under_the_cap", {-5, -5, 0}, {5, -5, 0}, {0, 5, 0}, true},
    {"floor_tile_inside_the_rim",
     {0.35, -1.2, 0},
     {0.45, -1.2, 0},
     {0.35, -1.1, 0},
     true},
    {"floor_tile_through_the_axis_edge",
     {0.35, -1.2, 0},
     {2, -1.2, 0},
     {2, 3, 0},
     true},
    {"floor_tile_beside_the_rim", {0.7, -5, 0}, {2, -5, 0}, {2, 5, 0}, false},
    {"wall_below_the_floor_its_top_edge_under_the_cap",
     {0.35, -1.5, 0},
     {0.35, 2, 0},
     {0.35, 2, -1},
     true},
    {"wall_below_the_floor_beside_the_cap",
     {1, -1.5, 0},
     {1, 2, 0},
     {1, 2, -1},
     false},
};

Cylinder<double> floorCylinder() { return {0.3, 1.4}; }
Pose<double> floorPose() {
  return {{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0.35, -1.2, 0.7}};
}

// Exact motions of the world: signed axis permutations (test_support.h),
// each with a power-of-two scaling.
struct Motion {
  test::SignedPermutation p;
  int scale_exp;
};
const Motion kMotions[] = {
    {{{0, 1, 2}, {1, 1, 1}}, 0},    {{{2, 0, 1}, {1, 1, 1}}, 0},
    {{{1, 0, 2}, {-1, 1, 1}}, 0},   {{{0, 2, 1}, {1, -1, -1}}, 3},
    {{{2, 1, 0}, {-1, -1, 1}}, -7}, {{{1, 2, 0}, {1, 1, -1}}, 20},
};

Vec3<double> scaled(const Vec3<double>& v, int e) {
  return {std::ldexp(v.x, e), std::ldexp(v.y, e), std::ldexp(v.z, e)};
}
Vec3<double> move(const Motion& m, const Vec3<double>& v) {
  return scaled(m.p(v), m.scale_exp);
}
Pose<double> move(const Motion& m, const Pose<double>& pose) {
  Pose<double> q = m.p(pose);
  q.t = scaled(q.t, m.scale_exp);
  return q;
}

TEST(TrackedStage, CylinderStandingOnAFloorIsDecidedWithoutGmp) {
  for (const Motion& m : kMotions) {
    const double s = std::ldexp(1.0, m.scale_exp);
    const Cylinder<double> cyl{floorCylinder().radius * s,
                               floorCylinder().lz * s};
    const Pose<double> pose = move(m, floorPose());
    for (const FloorCase& c : kFloor) {
      const Triangle<double> tri{move(m, c.a), move(m, c.b), move(m, c.c)};
      SCOPED_TRACE(std::string(c.name) + " perm " +
                   std::to_string(m.p.perm[0]) + std::to_string(m.p.perm[1]) +
                   std::to_string(m.p.perm[2]) + " scale 2^" +
                   std::to_string(m.scale_exp));
      ASSERT_EQ(oracle::triangleCylinder(cyl, pose, tri), c.expected);
      const Decision d = decideIntersect(cyl, pose, tri);
      EXPECT_EQ(d.answer, c.expected ? Answer::kIntersect : Answer::kDisjoint);
      EXPECT_NE(d.stage, Stage::kExact);
    }
  }
}

// Exact-zero scenes from random small dyadic data: vertices on the rim,
// triangles in a cap plane or through a rim point, under signed-permutation
// poses. Every answer agrees with the oracle, and the tracked stage decides
// a good share of them (the count proves this test exercises it).
TEST(TrackedStage, DyadicTouchingScenesAgreeWithTheOracle) {
  const std::uint64_t seed = test::baseSeed() + 55;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  auto small = [&g](int n) {
    return double(long(g() % std::uint64_t(2 * n + 1)) - n) * 0.125;
  };
  const long n = test::scaled(4000);
  long tracked = 0, exact = 0, failures = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    // r = 3/4 and rim points (3/5, 4/5) r scaled: (0.45, 0.6) has norm 0.75.
    const Cylinder<double> cyl{0.75, double(1 + g() % 8) * 0.5};
    const double h = cyl.lz / 2;
    const double z = (g() & 1) ? h : -h;
    Vec3<double> v[3];
    for (auto& p : v) p = {small(12), small(12), small(12)};
    switch (g() % 4) {
      case 0:  // a vertex on the rim
        v[0] = {(g() & 1) ? 0.45 : -0.6, (g() & 1) ? 0.6 : -0.45, z};
        break;
      case 1:  // in the cap plane
        for (auto& p : v) p.z = z;
        break;
      case 2:  // an edge through a rim point, mirrored about it
        v[0] = {0.75 + small(4), small(4), z + small(4)};
        v[1] = {2 * 0.75 - v[0].x, -v[0].y, 2 * z - v[0].z};
        break;
      default:  // a vertex on the side, inside the slab
        v[0] = {0.45, -0.6, small(2)};
        break;
    }
    Pose<double> pose{};
    const int perm = int(g() % 3);
    for (int k = 0; k < 3; ++k)
      pose.R[k][(k + perm) % 3] = (g() & 1) ? 1.0 : -1.0;
    pose.t = {small(16), small(16), small(16)};
    // World = R local + t (exact: signed permutation, small dyadics).
    Triangle<double> tri;
    Vec3<double>* w[3] = {&tri.a, &tri.b, &tri.c};
    for (int k = 0; k < 3; ++k) {
      const double l[3] = {v[k].x, v[k].y, v[k].z};
      double o[3];
      for (int r = 0; r < 3; ++r)
        o[r] = pose.R[r][0] * l[0] + pose.R[r][1] * l[1] + pose.R[r][2] * l[2] +
               (r == 0   ? pose.t.x
                : r == 1 ? pose.t.y
                         : pose.t.z);
      *w[k] = {o[0], o[1], o[2]};
    }
    const bool truth = oracle::triangleCylinder(cyl, pose, tri);
    const Decision d = decideIntersect(cyl, pose, tri);
    tracked += d.stage == Stage::kTracked;
    exact += d.stage == Stage::kExact;
    if ((d.answer == Answer::kIntersect) != truth) {
      ++failures;
      ADD_FAILURE() << "case " << i << ": oracle " << truth << ", stage "
                    << int(d.stage);
    }
  }
  std::printf(
      "[ stats    ] %ld dyadic touching scenes: tracked %ld, exact %ld\n", n,
      tracked, exact);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(tracked, n / 10);
}

}  // namespace
}  // namespace tricyl
