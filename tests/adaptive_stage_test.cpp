// SPDX-License-Identifier: BSD-3-Clause
// The adaptive stages (src/adaptive.h, src/eft.h, src/expansion.h;
// docs/exactness.md, section 4): the exact expansion arithmetic against GMP,
// the double-word running bound against the exact value, the tape of the
// real kernels within its capacity on every family, and the scenes the
// exact stage exists for, exact zeros that no error bound certifies,
// decided without GMP and confirmed by the exact oracle under exact rigid
// motions.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "adaptive.h"
#include "cylinder_queries_impl.h"
#include "expansion.h"
#include "filter.h"
#include "oracle.h"
#include "scenes.h"
#include "stages.h"
#include "test_support.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using detail::AdaptiveKernel;
using detail::DW;
using detail::Dyadic;
using detail::ExactKernel;
using detail::Expansion;
using detail::Sign;
using detail::Tape;
using detail::TapeScope;

int dyadicSign(const Dyadic& d) { return sgn(d.m); }

// A random double with a random exponent in [lo, hi] and a random sign
// (zero one time in 16).
double randomDouble(std::mt19937_64& g, int lo, int hi) {
  if (g() % 16 == 0) return 0.0;
  const double f = 1.0 + double(g() >> 11) * 0x1p-53;
  const int e = lo + int(g() % std::uint64_t(hi - lo + 1));
  return (g() & 1 ? -1.0 : 1.0) * std::ldexp(f, e);
}

// Random expression trees of depth <= 4 over random doubles, evaluated as
// an Expansion and as GMP dyadics: same sign, and the expansion's value is
// the exact value (compared by subtracting it, exactly, from the dyadic).
struct Expr {
  Expansion x;
  Dyadic d;
};
Expr randomExpr(std::mt19937_64& g, int depth, int lo, int hi) {
  if (depth == 0 || g() % 4 == 0) {
    const double a = randomDouble(g, lo, hi), b = randomDouble(g, lo, hi);
    if (g() & 1) return {Expansion(a), ExactKernel::lift(a)};
    return {Expansion::difference(a, b), ExactKernel::inputDiff(a, b)};
  }
  const Expr l = randomExpr(g, depth - 1, lo, hi);
  const Expr r = randomExpr(g, depth - 1, lo, hi);
  switch (g() % 3) {
    case 0:
      return {l.x + r.x, l.d + r.d};
    case 1:
      return {l.x - r.x, l.d - r.d};
    default:
      return {l.x * r.x, l.d * r.d};
  }
}

// The weight of x's lowest set bit (x finite, non-zero).
double lowestBit(double x) {
  int e = 0;
  double f = std::frexp(std::fabs(x), &e);  // f in [0.5, 1)
  // f 2^53 is an integer; strip its trailing zeros.
  double m = std::ldexp(f, 53);
  int tz = 0;
  while (std::fmod(m, 2.0) == 0) {
    m /= 2;
    ++tz;
  }
  return std::ldexp(1.0, e - 53 + tz);
}

// Shewchuk's invariant that sign() rests on: components in increasing
// magnitude, none zero, each smaller than the lowest set bit of the next
// (non-overlapping).
bool nonOverlapping(const Expansion& x) {
  for (int k = 0; k < x.size(); ++k)
    if (x.data()[k] == 0) return false;
  for (int k = 0; k + 1 < x.size(); ++k)
    if (!(std::fabs(x.data()[k]) < lowestBit(x.data()[k + 1]))) return false;
  return true;
}

TEST(Expansion, ExactAgainstGmpOnRandomExpressions) {
  const std::uint64_t seed = test::baseSeed() + 91;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  long valid = 0;
  const long n = test::scaled(20000);
  for (long i = 0; i < n; ++i) {
    const Expr e = randomExpr(g, 4, -60, 60);
    if (!e.x.ok()) continue;
    ++valid;
    ASSERT_EQ(e.x.sign(), dyadicSign(e.d)) << "case " << i;
    ASSERT_TRUE(nonOverlapping(e.x)) << "case " << i;
    // The value itself: the expansion's components, summed exactly in GMP,
    // minus the GMP value is 0.
    Dyadic sum;
    for (int k = 0; k < e.x.size(); ++k)
      sum = sum + ExactKernel::lift(e.x.data()[k]);
    ASSERT_EQ(dyadicSign(sum - e.d), 0) << "case " << i;
  }
  // Inside this exponent window nothing should fall back.
  EXPECT_EQ(valid, n);
}

TEST(Expansion, CancellationToZeroAndTiesAreExact) {
  // 0.1 * 3 - 0.3 = 2^-55 exactly (rounded double arithmetic gives 2^-54).
  const Expansion p = Expansion(0.1) * Expansion(3.0) - Expansion(0.3);
  ASSERT_TRUE(p.ok());
  EXPECT_EQ(p.sign(), 1);
  EXPECT_EQ(p.approx(), 0x1p-55);
  // (a - b)^2 - (a^2 - 2ab + b^2) = 0 for far-apart a, b.
  const double a = 0x1.23456789abcdep40, b = -0x1.fedcba9876543p-30;
  const Expansion d = Expansion::difference(a, b);
  const Expansion lhs = d * d;
  const Expansion rhs = Expansion(a) * Expansion(a) -
                        Expansion(2.0) * Expansion(a) * Expansion(b) +
                        Expansion(b) * Expansion(b);
  const Expansion z = lhs - rhs;
  ASSERT_TRUE(z.ok());
  EXPECT_EQ(z.sign(), 0);
  EXPECT_EQ(z.size(), 0);
}

TEST(Expansion, FlagsWhatItCannotComputeExactly) {
  // A product near underflow: its error term may not be a double.
  EXPECT_FALSE((Expansion(0x1p-500) * Expansion(0x1p-450)).ok());
  // Overflow (never met by the library, which uses expansions under the
  // range gate only, where magnitudes stay below 2^760: here it raises the
  // overflow and invalid flags, so the traps are off).
  {
    test::NoFpTraps no_traps;
    EXPECT_FALSE((Expansion(0x1p600) * Expansion(0x1p600)).ok());
    EXPECT_FALSE(Expansion(std::numeric_limits<double>::infinity()).ok());
  }
  // A zero factor is exact whatever the other one is.
  const Expansion z = Expansion(0.0) * Expansion(0x1p-1074);
  ASSERT_TRUE(z.ok());
  EXPECT_EQ(z.sign(), 0);
}

// The double-word running bound (Tape::dw through the public escalate:
// here directly on a tape): for random expressions of the kernels' shape,
// |value - exact| <= e, checked exactly with GMP.
TEST(DoubleWordStage, BoundEnclosesTheExactValue) {
  const std::uint64_t seed = test::baseSeed() + 92;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  const long n = test::scaled(3000);
  double worst = 0;
  for (long i = 0; i < n; ++i) {
    Tape tape;
    TapeScope scope(&tape);
    using K = AdaptiveKernel;
    // A degree-4 predicate of local coordinates from inputs <= 2^20.
    auto coord = [&]() {
      const auto d0 =
          K::inputDiff(randomDouble(g, -20, 20), randomDouble(g, -20, 20));
      const auto d1 =
          K::inputDiff(randomDouble(g, -20, 20), randomDouble(g, -20, 20));
      return K::lift(randomDouble(g, -30, 0)) * d0 +
             K::lift(randomDouble(g, -30, 0)) * d1;
    };
    const auto x = coord(), y = coord(), r = K::lift(randomDouble(g, -5, 5));
    const auto v = r * r - x * x - y * y;
    DW dw;
    double e;
    tape.doubleWord(v.id, &dw, &e);
    const Dyadic exact = tape.exact(v.id);
    // |dw - exact| as a dyadic, compared with e.
    const Dyadic diff =
        ExactKernel::lift(dw.hi) + ExactKernel::lift(dw.lo) - exact;
    const Dyadic slack = ExactKernel::lift(e) - diff;
    const Dyadic slack2 = ExactKernel::lift(e) + diff;
    ASSERT_GE(dyadicSign(slack), 0) << "case " << i;
    ASSERT_GE(dyadicSign(slack2), 0) << "case " << i;
    if (e > 0) {
      const double err =
          std::fabs(diff.m.get_d()) * std::ldexp(1.0, int(diff.e));
      worst = std::max(worst, err / e);
    }
  }
  std::printf("[ stats    ] double-word error / bound: worst %.3g\n", worst);
}

// The tape of the real kernels stays far inside its capacity on every
// triangle family (the driver falls back to GMP for the whole query if it
// did not: never on these).
TEST(AdaptiveTape, TriangleKernelRecordsFarFewerNodesThanTheCapacity) {
  int most = 0;
  const std::uint64_t seed = test::baseSeed() + 93;
  SCOPED_TRACE(test::seedTrace(seed));
  for (scenes::Family fam : scenes::kAllFamilies) {
    for (long i = 0; i < test::scaled(2000); ++i) {
      const scenes::TriCase c = scenes::generate(fam, seed, std::uint64_t(i));
      Tape tape;
      TapeScope scope(&tape);
      bool early = false;
      const auto q =
          detail::makeLocal<AdaptiveKernel>(c.cyl, c.pose, c.tri, 2.0);
      (void)detail::triangleCylinder<AdaptiveKernel>(q, &early);
      ASSERT_FALSE(tape.overflowed());
      most = std::max(most, tape.size());
    }
  }
  std::printf("[ stats    ] most tape nodes in a triangle query: %d of %d\n",
              most, Tape::kMaxNodes);
  EXPECT_LT(most, Tape::kMaxNodes / 2);
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

TEST(AdaptiveStage, CylinderStandingOnAFloorIsDecidedWithoutGmp) {
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
      EXPECT_NE(d.stage, Stage::kExactGmp);
    }
  }
}

// Exact-zero scenes from random small dyadic data: vertices on the rim,
// triangles in a cap plane or through a rim point, under signed-permutation
// poses. Every answer agrees with the oracle, the exact stage decides a
// good share of them on the stack (the count proves this test exercises
// it), and none needs GMP.
TEST(AdaptiveStage, DyadicTouchingScenesAgreeWithTheOracle) {
  const std::uint64_t seed = test::baseSeed() + 55;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  auto small = [&g](int n) {
    return double(long(g() % std::uint64_t(2 * n + 1)) - n) * 0.125;
  };
  const long n = test::scaled(4000);
  long exact = 0, gmp = 0, failures = 0;
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
    exact += d.stage == Stage::kExact;
    gmp += d.stage == Stage::kExactGmp;
    if ((d.answer == Answer::kIntersect) != truth) {
      ++failures;
      ADD_FAILURE() << "case " << i << ": oracle " << truth << ", stage "
                    << int(d.stage);
    }
  }
  std::printf("[ stats    ] %ld dyadic touching scenes: exact %ld, GMP %ld\n",
              n, exact, gmp);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(exact, n / 10);
  EXPECT_EQ(gmp, 0);
}

}  // namespace
}  // namespace tricyl
