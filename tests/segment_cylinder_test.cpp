// SPDX-License-Identifier: BSD-3-Clause
// Segment vs cylinder: the exact Boolean and the entry/exit interval.
// Hand cases for every region (typed over float and double), the source
// pseudo-code's failing cases as regressions, lines parallel/perpendicular
// to the axis, through the axis, tangent to the side and through the rim,
// invalid input, and seeded agreement with the exact oracle over the four
// families, with every interval endpoint checked against a 2^-200 reference.
#include "tricyl/segment_cylinder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "query_test_support.h"

namespace tricyl {
namespace {

template <class S>
class SegmentCylinderTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SegmentCylinderTyped, Scalars);

template <class S>
S up(S x) {
  return std::nextafter(x, std::numeric_limits<S>::infinity());
}

/// The source's pseudo-code (seeds/001, "Line Segment & Cylinder"),
/// transcribed literally in double with O = the bottom centre, N = +z and
/// L = lz, for an identity pose. It is WRONG; kept to show the regressions.
bool sourceSegment(double R, double L, Vec3<double> P0, Vec3<double> P1) {
  const double O[3] = {0, 0, -L / 2};
  const double V[3] = {P1.x - P0.x, P1.y - P0.y, P1.z - P0.z};
  const double d0[3] = {P0.x - O[0], P0.y - O[1], P0.z - O[2]};
  const double dp0 = d0[2];
  if (dp0 > L) return false;
  const double dp1 = d0[2] + V[2];
  if (dp1 < 0) return false;
  const double F[2] = {d0[0], d0[1]};  // (P0 - O) - ((P0 - O).N) N
  const double G[2] = {V[0], V[1]};    // V - (V.N) N
  const double A = G[0] * G[0] + G[1] * G[1];
  const double B = 2 * (F[0] * G[0] + F[1] * G[1]);
  const double C = F[0] * F[0] + F[1] * F[1] - R * R;
  if (A > 0) {
    const double disc = B * B - 4 * A * C;
    if (disc < 0) return false;
    for (double sg : {-1.0, 1.0}) {
      const double t = (-B + sg * std::sqrt(disc)) / (2 * A);
      if (t >= 0 && t <= 1) return true;
    }
    return false;
  }
  return C <= 0;
}

// The source's failures (issue 5), cylinder r = 1, lz = 2 (|z| <= 1).
TEST(SegmentCylinderRegression, SourcePseudoCodeFailures) {
  const Cylinder<double> c{1, 2};
  const Pose<double> I = identityPose<double>();
  struct Case {
    Vec3<double> p, q;
    bool truth;
    const char* why;
  } cases[] = {
      // Entirely inside: both roots of the infinite-cylinder quadratic lie
      // outside [0, 1], so the source answers "no".
      {{0.25, 0, -0.5}, {-0.25, 0.25, 0.5}, true, "segment entirely inside"},
      // A root inside [0, 1] but above the top cap: x = -2 + 4s meets
      // |x| <= 1 for s in [1/4, 3/4], where z = 0.5 + 3s >= 1.25 > 1. The
      // source never checks the root's height and answers "yes".
      {{-2, 0, 0.5}, {2, 0, 3.5}, false, "root outside the caps"},
      // Through both cap disks, nearly parallel to the axis: no root in
      // [0, 1] (the endpoints are inside the infinite cylinder) and the
      // source never tests the caps: "no".
      {{0.125, 0, -3}, {-0.125, 0, 3}, true, "through both cap disks"},
      // Starting above the top cap going down through it: the source's
      // early-out "dp0 > L" answers "no" without looking at q.
      {{0.25, 0, 3.5}, {0.25, 0.25, 0}, true, "from above through the cap"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.why);
    EXPECT_NE(sourceSegment(1, 2, k.p, k.q), k.truth) << "source is right?";
    EXPECT_EQ(oracle::segmentCylinder(c, I, {k.p, k.q}), k.truth);
    EXPECT_EQ(intersect(c, I, Segment<double>{k.p, k.q}), k.truth);
    EXPECT_EQ(clip(c, I, Segment<double>{k.p, k.q}).has_value(), k.truth);
  }
}

// Cylinder r = 1, lz = 2, identity pose; every expected interval is exact
// in float and double except where noted.
TYPED_TEST(SegmentCylinderTyped, HandCases) {
  using S = TypeParam;
  const Cylinder<S> c{1, 2};
  const Pose<S> I = identityPose<S>();
  const double third = 1.0 / 3;
  struct Case {
    Vec3<S> p, q;
    bool hit;
    double lo, hi;
    const char* what;
  } cases[] = {
      {{S(0.25), 0, S(-0.5)},
       {S(-0.25), S(0.25), S(0.5)},
       true,
       0,
       1,
       "entirely inside"},
      {{0, 0, 0}, {0, 0, 0}, true, 0, 1, "a point inside"},
      {{2, 0, 0}, {2, 0, 0}, false, 0, 0, "a point outside"},
      {{-2, 0, 0}, {2, 0, 0}, true, 0.25, 0.75, "perpendicular, through axis"},
      {{-2, S(1.5), 0}, {2, S(1.5), 0}, false, 0, 0, "perpendicular, missing"},
      {{S(0.5), 0, -3},
       {S(0.5), 0, 3},
       true,
       third,
       2 * third,
       "parallel to the axis, inside"},
      {{0, 0, -2}, {0, 0, 2}, true, 0.25, 0.75, "along the axis"},
      {{1, 0, -2}, {1, 0, 2}, true, 0.25, 0.75, "parallel, on the side"},
      {{up(S(1)), 0, -2},
       {up(S(1)), 0, 2},
       false,
       0,
       0,
       "parallel, one ulp outside the side"},
      {{1, -1, 0}, {1, 1, 0}, true, 0.5, 0.5, "tangent to the side"},
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
      {{0, 0, 0}, {2, 0, 2}, true, 0, 0.5, "from inside out through the rim"},
      {{2, 0, 0},
       {0, 0, 2},
       true,
       0.5,
       0.5,
       "touching only the rim (Freesteel's crack)"},
      {{1, -1, 1}, {1, 1, 1}, true, 0.5, 0.5, "grazing the rim horizontally"},
      {{1, -1, up(S(1))},
       {1, 1, up(S(1))},
       false,
       0,
       0,
       "one ulp above the rim"},
      {{-2, 0, 1}, {2, 0, 1}, true, 0.25, 0.75, "in the top cap plane"},
      {{-2, 0, -1}, {2, 0, -1}, true, 0.25, 0.75, "in the bottom cap plane"},
      {{0, 0, 3}, {0, 0, 1}, true, 1, 1, "ending on the top cap"},
      {{S(0.5), 0, 3},
       {S(0.5), 0, -3},
       true,
       third,
       2 * third,
       "through both caps"},
      {{-2, 0, S(0.5)}, {2, 0, S(3.5)}, false, 0, 0, "root beyond the cap"},
  };
  const double tol = std::is_same<S, float>::value ? 0x1p-24 : 1e-14;
  for (const auto& k : cases) {
    SCOPED_TRACE(k.what);
    const Segment<S> seg{k.p, k.q};
    EXPECT_EQ(intersect(c, I, seg), k.hit);
    const auto iv = clip(c, I, seg);
    ASSERT_EQ(iv.has_value(), k.hit);
    if (!k.hit) continue;
    EXPECT_NEAR(double(iv->lo), k.lo, tol);
    EXPECT_NEAR(double(iv->hi), k.hi, tol);
    EXPECT_LE(iv->lo, iv->hi);
    // Reversing the segment reverses the interval: s -> 1 - s.
    const auto rv = clip(c, I, Segment<S>{k.q, k.p});
    ASSERT_TRUE(rv.has_value());
    EXPECT_NEAR(double(rv->lo), 1 - k.hi, tol);
    EXPECT_NEAR(double(rv->hi), 1 - k.lo, tol);
  }
}

TYPED_TEST(SegmentCylinderTyped, DegenerateSizes) {
  using S = TypeParam;
  const Pose<S> I = identityPose<S>();
  // r = 0: the axis segment |z| <= 1. A segment crossing it exactly.
  const Cylinder<S> needle{0, 2};
  auto iv = clip(needle, I, Segment<S>{{-1, 0, S(0.5)}, {1, 0, S(0.5)}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.5));
  EXPECT_EQ(iv->hi, S(0.5));
  // Crosses the axis at x = 0, z = 0.75: a hit.
  EXPECT_TRUE(intersect(needle, I, Segment<S>{{-1, 0, S(0.5)}, {1, 0, 1}}));
  EXPECT_FALSE(
      intersect(needle, I, Segment<S>{{-1, S(1e-3), 0}, {1, S(1e-3), 0}}));
  // lz = 0: the unit disk in z = 0.
  const Cylinder<S> disk{1, 0};
  iv = clip(disk, I, Segment<S>{{0, 0, -1}, {0, 0, 1}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.5));
  EXPECT_EQ(iv->hi, S(0.5));
  iv = clip(disk, I, Segment<S>{{-2, 0, 0}, {2, 0, 0}});
  ASSERT_TRUE(iv.has_value());
  EXPECT_EQ(iv->lo, S(0.25));
  EXPECT_EQ(iv->hi, S(0.75));
  EXPECT_FALSE(intersect(disk, I, Segment<S>{{2, 0, -1}, {2, 0, 1}}));
}

TYPED_TEST(SegmentCylinderTyped, InvalidInput) {
  using S = TypeParam;
  test::NoFpTraps no_traps;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S inf = std::numeric_limits<S>::infinity();
  const Pose<S> I = identityPose<S>();
  const Segment<S> seg{{0, 0, 0}, {1, 0, 0}};
  EXPECT_THROW(intersect(Cylinder<S>{-1, 1}, I, seg), InvalidInput);
  EXPECT_THROW(clip(Cylinder<S>{1, -1}, I, seg), InvalidInput);
  EXPECT_THROW(clip(Cylinder<S>{1, 1}, I, Segment<S>{{0, nan, 0}, {1, 0, 0}}),
               InvalidInput);
  EXPECT_THROW(
      intersect(Cylinder<S>{1, 1}, I, Segment<S>{{0, 0, 0}, {inf, 0, 0}}),
      InvalidInput);
  Interval<S> out{S(7), S(7)};
  Pose<S> bad = I;
  bad.R[2][2] = nan;
  EXPECT_EQ(tryClip(Cylinder<S>{1, 1}, bad, seg, &out), Answer::kInvalidInput);
  EXPECT_EQ(out.lo, S(7));  // untouched
  EXPECT_EQ(tryIntersect(Cylinder<S>{inf, 1}, I, seg), Answer::kInvalidInput);
}

class SegmentCylinderFamily : public ::testing::TestWithParam<test::Family> {};

TEST_P(SegmentCylinderFamily, AgreesWithOracle) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  const auto st = test::runAgreement(
      test::Query::kSegment, GetParam(), test::scaled(100000),
      [](const auto& t) {
        using S = decltype(t.rho);
        return decideIntersect(t.cyl, t.pose, Segment<S>{t.p, t.q});
      },
      [](const test::QueryCase& k) {
        return oracle::segmentCylinder(k.cyl, k.pose, {k.p, k.q});
      });
  EXPECT_EQ(st.failures, 0);
}

// clip: non-empty iff the oracle says so, and both endpoints within 1e-14
// (double) of the exact ones, measured against the 2^-200 reference; float
// on every 4th case within 2^-24 + 1e-14 of the float-rounded input's exact
// endpoints.
TEST_P(SegmentCylinderFamily, IntervalWithinBound) {
  const std::uint64_t seed = test::baseSeed() + 3;
  SCOPED_TRACE(test::seedTrace(seed));
  const long n = test::scaled(100000);
  long failures = 0, nonempty = 0, degenerate = 0;
  double worst = 0, worst_f = 0;
  for (long i = 0; i < n && failures < 5; ++i) {
    const test::QueryCase k =
        qscenes::generate(test::Query::kSegment, GetParam(), seed, i);
    const auto ref = oracle::segmentInterval(k.cyl, k.pose, {k.p, k.q});
    const auto iv = clip(k.cyl, k.pose, Segment<double>{k.p, k.q});
    if (iv.has_value() == ref.empty) {
      ++failures;
      ADD_FAILURE() << "emptiness, index " << i << "\n" << test::dump(k);
      continue;
    }
    if (iv) {
      ++nonempty;
      oracle::Q lo, hi;
      oracle::referenceEndpoints(ref, &lo, &hi);
      degenerate += lo == hi;
      const double e =
          std::max(std::fabs(oracle::Q(oracle::Q(iv->lo) - lo).get_d()),
                   std::fabs(oracle::Q(oracle::Q(iv->hi) - hi).get_d()));
      worst = std::max(worst, e);
      if (!(e <= 1e-14) || !(iv->lo <= iv->hi) || iv->lo < 0 || iv->hi > 1) {
        ++failures;
        ADD_FAILURE() << "endpoint error " << e << " [" << iv->lo << ", "
                      << iv->hi << "] vs [" << lo.get_d() << ", " << hi.get_d()
                      << "], index " << i << "\n"
                      << test::dump(k);
      }
    }
    if (i % 4 == 0) {
      const test::QueryCase kf = test::roundedTo<float>(k);
      const auto t = test::typed<float>(k);
      const auto ref_f = oracle::segmentInterval(kf.cyl, kf.pose, {kf.p, kf.q});
      const auto ivf = clip(t.cyl, t.pose, Segment<float>{t.p, t.q});
      if (ivf.has_value() == ref_f.empty) {
        ++failures;
        ADD_FAILURE() << "float emptiness, index " << i << "\n"
                      << test::dump(kf);
      } else if (ivf) {
        oracle::Q lo, hi;
        oracle::referenceEndpoints(ref_f, &lo, &hi);
        const double e = std::max(
            std::fabs(oracle::Q(oracle::Q(double(ivf->lo)) - lo).get_d()),
            std::fabs(oracle::Q(oracle::Q(double(ivf->hi)) - hi).get_d()));
        worst_f = std::max(worst_f, e);
        if (!(e <= 0x1p-24 + 1e-14) || !(ivf->lo <= ivf->hi)) {
          ++failures;
          ADD_FAILURE() << "float endpoint error " << e << ", index " << i
                        << "\n"
                        << test::dump(kf);
        }
      }
    }
  }
  std::printf(
      "[ stats    ] %s: %ld cases, %ld non-empty (%ld single points); worst "
      "endpoint error %.3g (double), %.3g (float)\n",
      qscenes::familyName(GetParam()), n, nonempty, degenerate, worst, worst_f);
  EXPECT_EQ(failures, 0);
}

// Properties of the contract: reversing the segment maps the interval to
// [1 - hi, 1 - lo]; an exact rigid motion of the world (a signed axis
// permutation applied to pose and segment) and scaling every length by
// 2^e leave the exact answer unchanged. Intervals are compared within
// twice the bound (each is within 1e-14 of the same exact values).
TEST_P(SegmentCylinderFamily, Invariances) {
  test::expectIntervalInvariances<Segment>(
      test::Query::kSegment, GetParam(),
      [](double got, double base) { return std::fabs(got - base) <= 2e-14; });
}

INSTANTIATE_TEST_SUITE_P(Families, SegmentCylinderFamily,
                         ::testing::ValuesIn(qscenes::kAllFamilies),
                         test::familyParamName);

}  // namespace
}  // namespace tricyl
