// SPDX-License-Identifier: BSD-3-Clause
// Line vs cylinder: the exact Boolean and the entry/exit interval along the
// unbounded line p (1 - s) + q s. Hand cases with known answers (typed over
// float and double): parallel to the axis inside / outside / on the side,
// perpendicular through the axis, oblique through the axis and through both
// rims, tangent to the side, through a rim point only (Freesteel's crack),
// in a cap plane, grazing the rim, features at s outside [0, 1], p == q,
// degenerate sizes, overflowing parameters, invalid input. Then lines
// exactly through rim points in exact poses (no crack), and seeded
// agreement with the exact oracle (compare/query_oracles.h) over the four
// families, every interval end checked against a 2^-200 reference with the
// relative bound, the segment with the same p, q checked against the line
// (clip(segment) == clip(line) n [0, 1], and the segment's Boolean equal to
// "the exact line interval meets [0, 1]"), and invariances (reversal
// s -> 1 - s, exact rigid motions, power-of-two scaling).
#include "tricyl/line_cylinder.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <limits>

#include "query_test_support.h"
#include "tricyl/segment_cylinder.h"

namespace tricyl {
namespace {

template <class S>
class LineCylinderTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(LineCylinderTyped, Scalars);

template <class S>
S up(S x) {
  return std::nextafter(x, std::numeric_limits<S>::infinity());
}

constexpr double kInf = std::numeric_limits<double>::infinity();

/// The documented bound: |s - s*| <= tol * max(1, |s*|) with tol = 1e-14
/// for double and 2^-24 + 1e-14 for float.
template <class S>
double tolOf() {
  return std::is_same<S, float>::value ? 0x1p-24 + 1e-14 : 1e-14;
}

/// Within `tol` relative to max(1, |expect|); infinities must match.
bool near(double got, double expect, double tol) {
  if (std::isinf(expect) || std::isinf(got)) return got == expect;
  return std::fabs(got - expect) <= tol * std::max(1.0, std::fabs(expect));
}

// Cylinder r = 1, lz = 2 (|z| <= 1), identity pose. Every expected interval
// is exact in float and double (dyadic or a third).
TYPED_TEST(LineCylinderTyped, HandCases) {
  using S = TypeParam;
  const Cylinder<S> c{1, 2};
  const Pose<S> I = identityPose<S>();
  const double third = 1.0 / 3;
  const S tiny = S(0x1p-40);
  struct Case {
    Vec3<S> p, q;
    bool hit;
    double lo, hi;
    const char* what;
  } cases[] = {
      {{S(0.5), 0, -3},
       {S(0.5), 0, 3},
       true,
       third,
       2 * third,
       "parallel to the axis, inside, through both caps"},
      {{S(0.5), 0, 0},
       {S(0.5), 0, S(0.25)},
       true,
       -4,
       4,
       "parallel to the axis, inside, p and q between the caps"},
      {{2, 0, 0}, {2, 0, 1}, false, 0, 0, "parallel to the axis, outside"},
      {{1, 0, -2}, {1, 0, 2}, true, 0.25, 0.75, "parallel, on the side"},
      {{0, 1, 5}, {0, 1, 6}, true, -6, -4, "parallel, on the side, above"},
      {{up(S(1)), 0, -2},
       {up(S(1)), 0, 2},
       false,
       0,
       0,
       "parallel, one ulp outside the side"},
      {{0, 0, 0}, {0, 0, 1}, true, -1, 1, "the axis"},
      {{-2, 0, 0}, {2, 0, 0}, true, 0.25, 0.75, "perpendicular, through axis"},
      {{2, 0, 0}, {3, 0, 0}, true, -3, -1, "perpendicular, cylinder behind p"},
      {{0, -3, S(0.5)},
       {0, -2, S(0.5)},
       true,
       2,
       4,
       "perpendicular, cylinder beyond q"},
      {{-2, S(1.5), 0}, {2, S(1.5), 0}, false, 0, 0, "perpendicular, missing"},
      {{0, 0, 0}, {1, 1, 4}, true, -0.25, 0.25, "oblique through the axis"},
      {{0, 0, 0}, {2, 0, 2}, true, -0.5, 0.5, "through both rims"},
      {{0, 0, 0},
       {1, 0, 1},
       true,
       -1,
       1,
       "through both rims, p and q at the centre and a rim"},
      {{1, -1, 0}, {1, 1, 0}, true, 0.5, 0.5, "tangent to the side"},
      {{1, 1, 0}, {1, 2, 0}, true, -1, -1, "tangent to the side, behind p"},
      {{up(S(1)), -1, 0},
       {up(S(1)), 1, 0},
       false,
       0,
       0,
       "one ulp beyond the tangent"},
      {{-1, 1, S(-0.5)},
       {1, 1, S(0.5)},
       true,
       0.5,
       0.5,
       "slanted tangent to the side"},
      {{2, 0, 0},
       {0, 0, 2},
       true,
       0.5,
       0.5,
       "touching only the rim (Freesteel's crack)"},
      {{3, 0, -1}, {4, 0, -2}, true, -2, -2, "touching only the rim, behind p"},
      {{1, -1, 1}, {1, 1, 1}, true, 0.5, 0.5, "grazing the rim horizontally"},
      {{1, -1, up(S(1))},
       {1, 1, up(S(1))},
       false,
       0,
       0,
       "one ulp above the rim"},
      {{-2, 0, 1}, {2, 0, 1}, true, 0.25, 0.75, "in the top cap plane"},
      {{-2, 0, -1}, {2, 0, -1}, true, 0.25, 0.75, "in the bottom cap plane"},
      {{-2, S(1.5), 1},
       {2, S(1.5), 1},
       false,
       0,
       0,
       "in the cap plane, missing the disk"},
      {{-2, 0, S(1.5)}, {2, 0, S(1.5)}, false, 0, 0, "horizontal, above"},
      {{0, 0, 3}, {0, 0, 1}, true, 1, 2, "the axis, from above"},
      {{0, 0, 0}, {tiny, 0, 0}, true, -0x1p40, 0x1p40, "p and q 2^-40 apart"},
      {{0, 0, 0}, {0, 0, 0}, true, -kInf, kInf, "p == q inside: all of R"},
      {{1, 0, 1}, {1, 0, 1}, true, -kInf, kInf, "p == q on the rim"},
      {{2, 0, 0}, {2, 0, 0}, false, 0, 0, "p == q outside"},
  };
  const double tol = tolOf<S>();
  for (const auto& k : cases) {
    SCOPED_TRACE(k.what);
    const Line<S> line{k.p, k.q};
    EXPECT_EQ(intersect(c, I, line), k.hit);
    const auto iv = clip(c, I, line);
    ASSERT_EQ(iv.has_value(), k.hit);
    if (!k.hit) continue;
    EXPECT_TRUE(near(double(iv->lo), k.lo, tol)) << iv->lo << " vs " << k.lo;
    EXPECT_TRUE(near(double(iv->hi), k.hi, tol)) << iv->hi << " vs " << k.hi;
    EXPECT_LE(iv->lo, iv->hi);
    // Reversing the line reverses the interval: s -> 1 - s.
    const auto rv = clip(c, I, Line<S>{k.q, k.p});
    ASSERT_TRUE(rv.has_value());
    EXPECT_TRUE(near(double(rv->lo), 1 - k.hi, 2 * tol)) << rv->lo;
    EXPECT_TRUE(near(double(rv->hi), 1 - k.lo, 2 * tol)) << rv->hi;
    // The segment is the line restricted to [0, 1].
    const bool meets = k.lo <= 1 && k.hi >= 0;
    const auto sv = clip(c, I, Segment<S>{k.p, k.q});
    ASSERT_EQ(sv.has_value(), meets);
    if (meets) {
      EXPECT_TRUE(near(double(sv->lo), std::max(k.lo, 0.0), tol));
      EXPECT_TRUE(near(double(sv->hi), std::min(k.hi, 1.0), tol));
    }
  }
}

TYPED_TEST(LineCylinderTyped, DegenerateSizes) {
  using S = TypeParam;
  const Pose<S> I = identityPose<S>();
  // r = 0: the axis segment |z| <= 1.
  const Cylinder<S> needle{0, 2};
  auto iv = clip(needle, I, Line<S>{{-1, 0, S(0.5)}, {1, 0, S(0.5)}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.5));
  EXPECT_EQ(iv->hi, S(0.5));
  iv = clip(needle, I, Line<S>{{0, 0, 0}, {0, 0, S(0.5)}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(-2));
  EXPECT_EQ(iv->hi, S(2));
  EXPECT_FALSE(
      intersect(needle, I, Line<S>{{-1, S(1e-3), 0}, {1, S(1e-3), 0}}));
  EXPECT_FALSE(intersect(needle, I, Line<S>{{-1, 0, 3}, {1, 0, 3}}));
  // lz = 0: the unit disk in z = 0.
  const Cylinder<S> disk{1, 0};
  iv = clip(disk, I, Line<S>{{0, 0, -1}, {0, 0, 1}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.5));
  EXPECT_EQ(iv->hi, S(0.5));
  iv = clip(disk, I, Line<S>{{-2, 0, 0}, {2, 0, 0}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.25));
  EXPECT_EQ(iv->hi, S(0.75));
  EXPECT_FALSE(intersect(disk, I, Line<S>{{2, 0, -1}, {2, 0, 1}}));
  EXPECT_FALSE(intersect(disk, I, Line<S>{{-2, 0, S(0.5)}, {2, 0, S(0.5)}}));
  // r = lz = 0: the origin.
  const Cylinder<S> point{0, 0};
  iv = clip(point, I, Line<S>{{-1, -1, -1}, {1, 1, 1}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.5));
  EXPECT_EQ(iv->hi, S(0.5));
  EXPECT_FALSE(intersect(point, I, Line<S>{{-1, -1, -1}, {1, 1, up(S(1))}}));
  iv = clip(point, I, Line<S>{{0, 0, 0}, {0, 0, 0}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, -std::numeric_limits<S>::infinity());
  EXPECT_EQ(iv->hi, std::numeric_limits<S>::infinity());
  // A singular R (all zero): every s maps to the local point 0 (inside).
  Pose<S> zero{};
  iv = clip(Cylinder<S>{1, 2}, zero, Line<S>{{5, 0, 0}, {7, 1, 0}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, -std::numeric_limits<S>::infinity());
  EXPECT_EQ(iv->hi, std::numeric_limits<S>::infinity());
}

// A parameter beyond the range of S: the end is the infinity of its sign,
// without a trap (invalid / divide-by-zero traps are on in every test).
TYPED_TEST(LineCylinderTyped, OverflowingParameter) {
  using S = TypeParam;
  const Cylinder<S> c{1, 2};
  const Pose<S> I = identityPose<S>();
  const S inf = std::numeric_limits<S>::infinity();
  const S dmin = std::numeric_limits<S>::denorm_min();
  // |x(s)| = s dmin <= 1: |s| <= 1 / dmin = 2^1074 (2^149 for float).
  auto iv = clip(c, I, Line<S>{{0, 0, 0}, {dmin, 0, 0}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, -inf);
  EXPECT_EQ(iv->hi, inf);
  // Large but finite: p on the side, moving inward by eps / 2 per unit of
  // s: [0, 4 / eps].
  const S eps = std::numeric_limits<S>::epsilon();
  iv = clip(c, I, Line<S>{{1, 0, 0}, {S(1) - eps / 2, 0, 0}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0));
  EXPECT_TRUE(near(double(iv->hi), 4 / double(eps), tolOf<S>())) << iv->hi;
  // Along the axis from the top cap, up by eps per unit: [-2 / eps, 0].
  iv = clip(c, I, Line<S>{{0, 0, 1}, {0, 0, up(S(1))}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_TRUE(near(double(iv->lo), -2 / double(eps), tolOf<S>())) << iv->lo;
  EXPECT_EQ(iv->hi, S(0));
  iv = clip(c, I, Line<S>{{1, 0, 0}, {1, dmin, 0}});  // tangent at s = 0
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0));
  EXPECT_EQ(iv->hi, S(0));
  iv = clip(c, I, Line<S>{{0, 0, 1}, {0, dmin, 1}});  // in the cap plane
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, -inf);
  EXPECT_EQ(iv->hi, inf);
  // One end finite, the other beyond the range: the cylinder posed so that
  // its top cap centre is the world origin, p there, direction -dmin z:
  // [0, 2 / dmin].
  Pose<S> down_one = I;
  down_one.t = {0, 0, -1};
  iv = clip(c, down_one, Line<S>{{0, 0, 0}, {0, 0, -dmin}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0));
  EXPECT_EQ(iv->hi, inf);
  iv = clip(c, down_one, Line<S>{{0, 0, -dmin}, {0, 0, 0}});  // reversed
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, -inf);
  EXPECT_EQ(iv->hi, S(1));
  // Float: |s| = 2^100 is finite in float; 2^140 (double end) is not.
  if (std::is_same<S, float>::value) {
    iv = clip(c, I, Line<S>{{0, 0, 0}, {S(0x1p-100), 0, 0}});
    ASSERT_TRUE(iv.has_value());
    EXPECT_EQ(iv->lo, S(-0x1p100));
    EXPECT_EQ(iv->hi, S(0x1p100));
    iv = clip(c, I, Line<S>{{0, 0, 0}, {S(0x1p-140), 0, 0}});
    ASSERT_TRUE(iv.has_value());
    EXPECT_EQ(iv->lo, -inf);
    EXPECT_EQ(iv->hi, inf);
  }
  // Outside the range gate: a huge cylinder, a subnormal direction.
  const Cylinder<S> big{std::numeric_limits<S>::max() / 4,
                        std::numeric_limits<S>::max() / 4};
  iv = clip(big, I, Line<S>{{0, 0, 0}, {0, 0, dmin}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, -inf);
  EXPECT_EQ(iv->hi, inf);
}

TYPED_TEST(LineCylinderTyped, InvalidInput) {
  using S = TypeParam;
  test::NoFpTraps no_traps;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S inf = std::numeric_limits<S>::infinity();
  const Pose<S> I = identityPose<S>();
  const Line<S> line{{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(intersect(Cylinder<S>{-1, 1}, I, line), InvalidInput);
  EXPECT_THROW(clip(Cylinder<S>{1, -1}, I, line), InvalidInput);
  EXPECT_THROW(clip(Cylinder<S>{1, 1}, I, Line<S>{{0, nan, 0}, {1, 0, 0}}),
               InvalidInput);
  EXPECT_THROW(intersect(Cylinder<S>{1, 1}, I, Line<S>{{0, 0, 0}, {inf, 0, 0}}),
               InvalidInput);
  Interval<S> out{S(7), S(7)};
  Pose<S> bad = I;
  bad.R[2][2] = nan;
  EXPECT_EQ(tryClip(Cylinder<S>{1, 1}, bad, line, &out), Answer::kInvalidInput);
  EXPECT_EQ(out.lo, S(7));  // untouched
  EXPECT_EQ(tryClip(Cylinder<S>{1, 1}, I, Line<S>{{5, 5, 5}, {6, 5, 5}}, &out),
            Answer::kDisjoint);
  EXPECT_EQ(out.lo, S(7));  // untouched
  EXPECT_EQ(tryIntersect(Cylinder<S>{inf, 1}, I, line), Answer::kInvalidInput);
  EXPECT_EQ(
      decideIntersect(Cylinder<S>{1, 1}, I, Line<S>{{0, 0, nan}, {}}).stage,
      Stage::kInvalid);
}

// A subnormal direction (DZ ~ 2^-1057, its bound 2^-1071) and a tiny slab:
// the quotient H / DZ's error bound, (|v| e_DZ) / (|DZ| - e_DZ), lost its
// numerator to underflow, so stage 1 accepted an end 3.4e-9 off (the
// fuzz_line_cylinder case fuzz/corpus/line_cylinder/underflowed-quotient-
// bound). The line is parallel to the axis (Dx = Dy = 0 exactly) and
// Z0 = 0, so the ends are exactly -+H / DZ, DZ = 2 R_02 p_x exactly.
TEST(LineCylinderRegression, UnderflowedQuotientBound) {
  const Cylinder<double> cyl{0x0.008p-1022, 0x0.00000000002p-1022};
  Pose<double> pose;
  const double R[3][3] = {{0, 0, 0x1.03f20f001p-31},
                          {0x0.04p-1022, 0x0.03ffp-1022, 0x0.0b1p-1022},
                          {0x0.0bff0000027p-1022, 0, 0}};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) pose.R[i][j] = R[i][j];
  pose.t = {0, 0, 0x1p-1007};
  const Vec3<double> p{0x0.0800000000ap-1022, 0, 0}, q{0, 0, 0};
  // s* = H / (2 R_02 p_x), H = 2^-1065. With a = 2 R_02 2^1000 and
  // b = p_x 2^100 (exact scalings), a b = 2 R_02 p_x 2^1100 = ph + pl
  // exactly (fma), and s* = 2^35 / (ph + pl) = (2^35 / ph)(1 - pl / ph)
  // to about 2^-100 relative.
  const double a = 2 * R[0][2] * 0x1p1000, b = p.x * 0x1p100;
  const double ph = a * b;
  const double pl = std::fma(a, b, -ph);
  const double s = 0x1p35 / ph * (1 - pl / ph);
  const auto rev = clip(cyl, pose, Line<double>{q, p});
  ASSERT_TRUE(rev.has_value());
  EXPECT_NEAR(rev->lo, -s, 1e-14);
  EXPECT_NEAR(rev->hi, s, 1e-14);
  const auto fwd = clip(cyl, pose, Line<double>{p, q});
  ASSERT_TRUE(fwd.has_value());
  EXPECT_NEAR(fwd->lo, 1 - s, 1e-14);
  EXPECT_NEAR(fwd->hi, 1 + s, 1e-14);
}

// Freesteel's crack: lines exactly through a rim point, in every direction
// (small integer components, so the line and the rim point are exact), in
// exact poses (signed axis permutations, half-integer translations, a
// power-of-two scale). The three-surfaces method can miss such a line in
// floating point; the exact Boolean may not, and the interval must contain
// the rim point's parameter. Lines through the rim that are tangent to the
// solid there (grazing) give a single point.
TEST(LineCylinderRim, NoCrackAtTheRim) {
  const std::uint64_t seed = test::baseSeed() + 11;
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed);
  const long n = test::scaled(20000);
  long failures = 0, single = 0;
  for (long i = 0; i < n && failures < 5; ++i) {
    const double u = std::ldexp(1.0, g.integer(20) - 10);
    const double h = double(1 + g.integer(6)) * u;
    const Cylinder<double> cyl{5 * u, 2 * h};
    const double sx = g.coin() ? 1 : -1, sy = g.coin() ? 1 : -1;
    const double sz = g.coin() ? 1 : -1;
    const Vec3<double> rim{sx * 3 * u, sy * 4 * u, sz * h};
    const Vec3<double> d{double(g.integer(9) - 4) * u,
                         double(g.integer(9) - 4) * u,
                         double(g.integer(9) - 4) * u};
    if (d.x == 0 && d.y == 0 && d.z == 0) continue;
    const double a = double(g.integer(9) - 4), b = a + double(1 + g.integer(4));
    // The rim point is at s0 = -a / (b - a).
    const Vec3<double> p{rim.x + a * d.x, rim.y + a * d.y, rim.z + a * d.z};
    const Vec3<double> q{rim.x + b * d.x, rim.y + b * d.y, rim.z + b * d.z};
    const double s0 = -a / (b - a);
    const Pose<double> pose = scenes::internal::exactPose(g);
    const Vec3<double> wp = scenes::internal::toWorld(pose, p);
    const Vec3<double> wq = scenes::internal::toWorld(pose, q);
    const auto iv = clip(cyl, pose, Line<double>{wp, wq});
    const bool hit = intersect(cyl, pose, Line<double>{wp, wq});
    bool ok = hit && iv.has_value();
    if (ok) {
      ok = iv->lo <= s0 + 1e-14 * std::max(1.0, std::fabs(s0)) &&
           iv->hi >= s0 - 1e-14 * std::max(1.0, std::fabs(s0));
      single += iv->lo == iv->hi;
    }
    if (!ok) {
      ++failures;
      ADD_FAILURE() << "rim line " << i << ": hit " << hit << ", s0 " << s0;
    }
  }
  std::printf(
      "[ stats    ] %ld lines through a rim point, %ld touching only "
      "there (single-point intervals)\n",
      n, single);
  EXPECT_EQ(failures, 0);
}

class LineCylinderFamily : public ::testing::TestWithParam<test::Family> {};

/// Relative error of `got` against the reference `ref` (2^-200 accurate).
/// An infinite `got` (an end beyond the range of the type, whose largest
/// finite value is `max`) counts as exact when `ref` has its sign and is
/// at least max (1 - 2^-20) in magnitude (within the bound of the limit),
/// and as infinitely wrong otherwise.
double relErr(double got, const oracle::Q& ref, double max) {
  if (std::isinf(got)) {
    const oracle::Q lim = oracle::Q(max) * (1 - 0x1p-20);
    return (got > 0 ? ref >= lim : ref <= -lim) ? 0 : kInf;
  }
  const double e = std::fabs(oracle::Q(oracle::Q(got) - ref).get_d());
  return e / std::max(1.0, std::fabs(ref.get_d()));
}

// Per case: the oracle's exact interval (once), then
// - decideIntersect (double) against its emptiness (stages counted);
// - clip (double): non-empty iff the oracle's is, each end within
//   1e-14 max(1, |s*|) of the 2^-200 reference ([-inf, inf] when the
//   oracle has no candidate: a point);
// - the segment with the same p, q: its Boolean equals "the exact line
//   interval meets [0, 1]" (decided from the line oracle's candidates), and
//   its clip equals clip(line) n [0, 1] within twice the bound;
// - every 4th case in float (inputs rounded to float, oracle re-run):
//   Boolean, emptiness and ends within (2^-24 + 1e-14) max(1, |s*|).
TEST_P(LineCylinderFamily, AgreesWithOracle) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  const long n = test::scaled(100000);
  long failures = 0, hits = 0, unbounded = 0, single = 0, outside01 = 0,
       float_cases = 0, seg_hits = 0;
  test::StageCounts stages;
  double worst = 0, worst_f = 0, worst_seg = 0, max_s = 0;
  auto fail = [&](const char* what, long i, const test::QueryCase& k) {
    ++failures;
    ADD_FAILURE() << what << ", index " << i << "\n" << test::dump(k);
  };
  for (long i = 0; i < n && failures < 5; ++i) {
    const test::QueryCase k =
        qscenes::generate(test::Query::kLine, GetParam(), seed, i);
    const Line<double> line{k.p, k.q};
    const auto ref = oracle::lineInterval(k.cyl, k.pose, line);
    const Decision d = decideIntersect(k.cyl, k.pose, line);
    stages.add(d.stage);
    if ((d.answer == Answer::kIntersect) == ref.empty) {
      fail("Boolean", i, k);
      continue;
    }
    const auto iv = clip(k.cyl, k.pose, line);
    if (iv.has_value() == ref.empty) {
      fail("clip emptiness", i, k);
      continue;
    }
    oracle::Q lo, hi;
    const bool bounded = !ref.empty && !ref.lower.empty();
    if (iv) {
      ++hits;
      if (!(iv->lo <= iv->hi)) fail("lo > hi", i, k);
      if (!bounded) {
        ++unbounded;
        if (!(iv->lo == -kInf && iv->hi == kInf)) fail("unbounded", i, k);
      } else {
        oracle::referenceEndpoints(ref, &lo, &hi);
        single += lo == hi;
        outside01 += hi < 0 || lo > 1;
        max_s = std::max({max_s, std::fabs(lo.get_d()), std::fabs(hi.get_d())});
        const double e =
            std::max(relErr(iv->lo, lo, DBL_MAX), relErr(iv->hi, hi, DBL_MAX));
        worst = std::max(worst, e);
        if (!(e <= 1e-14)) {
          ++failures;
          ADD_FAILURE() << "endpoint error " << e << " [" << iv->lo << ", "
                        << iv->hi << "] vs [" << lo.get_d() << ", "
                        << hi.get_d() << "], index " << i << "\n"
                        << test::dump(k);
        }
      }
    }
    // The segment with the same p and q.
    const Segment<double> seg{k.p, k.q};
    const bool seg_truth = oracle::lineMeetsUnit(ref);
    const auto sv = clip(k.cyl, k.pose, seg);
    seg_hits += seg_truth;
    if (intersect(k.cyl, k.pose, seg) != seg_truth ||
        sv.has_value() != seg_truth) {
      fail("segment Boolean vs line interval n [0, 1]", i, k);
    } else if (sv) {
      // iv exists: the segment's hit implies the line's.
      const double elo =
          std::fabs(sv->lo - std::min(std::max(iv->lo, 0.0), 1.0));
      const double ehi =
          std::fabs(sv->hi - std::min(std::max(iv->hi, 0.0), 1.0));
      worst_seg = std::max({worst_seg, elo, ehi});
      if (!(elo <= 2e-14 && ehi <= 2e-14))
        fail("segment clip vs line clip", i, k);
    }
    if (i % 4 == 0) {
      ++float_cases;
      const test::QueryCase kf = test::roundedTo<float>(k);
      const auto t = test::typed<float>(k);
      const Line<float> lf{t.p, t.q};
      const auto ref_f = oracle::lineInterval(kf.cyl, kf.pose, {kf.p, kf.q});
      const bool hit_f = intersect(t.cyl, t.pose, lf);
      const auto ivf = clip(t.cyl, t.pose, lf);
      if (hit_f == ref_f.empty || ivf.has_value() == ref_f.empty) {
        fail("float emptiness", i, kf);
      } else if (ivf) {
        if (ref_f.lower.empty()) {
          if (!(std::isinf(ivf->lo) && std::isinf(ivf->hi)))
            fail("float unbounded", i, kf);
        } else {
          oracle::Q flo, fhi;
          oracle::referenceEndpoints(ref_f, &flo, &fhi);
          const double e = std::max(relErr(double(ivf->lo), flo, FLT_MAX),
                                    relErr(double(ivf->hi), fhi, FLT_MAX));
          worst_f = std::max(worst_f, e);
          if (!(e <= 0x1p-24 + 1e-14) || !(ivf->lo <= ivf->hi))
            fail("float endpoint error", i, kf);
        }
      }
    }
  }
  std::printf(
      "[ stats    ] %s: %ld lines (+%ld float), %ld hits (%ld unbounded, %ld "
      "single points, %ld entirely outside [0, 1], max |s| %.3g); %s; worst "
      "relative end "
      "error %.3g (double), %.3g (float); %ld segment hits, worst |segment - "
      "line n [0, 1]| %.3g\n",
      qscenes::familyName(GetParam()), n, float_cases, hits, unbounded, single,
      outside01, max_s, stages.summary(n).c_str(), worst, worst_f, seg_hits,
      worst_seg);
  EXPECT_EQ(failures, 0);
}

// Reversing the line maps the interval to [1 - hi, 1 - lo]; an exact rigid
// motion of the world (a signed axis permutation applied to pose and line)
// and scaling every length by 2^e leave the exact answer unchanged.
// Intervals are compared within twice the bound (each end is within
// 1e-14 max(1, |s*|) of the same exact value), infinite ends exactly.
TEST_P(LineCylinderFamily, Invariances) {
  test::expectIntervalInvariances<Line>(test::Query::kLine, GetParam(),
                                        [](double got, double base) {
                                          // 1 - x adds one rounding, relative
                                          // to max(1, |x|).
                                          return near(got, base, 4e-14);
                                        });
}

INSTANTIATE_TEST_SUITE_P(Families, LineCylinderFamily,
                         ::testing::ValuesIn(qscenes::kAllFamilies),
                         test::familyParamName);

}  // namespace
}  // namespace tricyl
