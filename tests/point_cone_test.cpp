// SPDX-License-Identifier: BSD-3-Clause
// Point in cone (FCL's cone: apex at +lz/2, base disk of radius r at
// -lz/2): hand cases for every region and for lz = 0 and r = 0 (typed over
// float and double), the sources' apex form, invalid input, and seeded
// agreement with the exact oracle over the four families.
#include "tricyl/point_cone.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "query_test_support.h"

namespace tricyl {
namespace {

template <class S>
class PointConeTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PointConeTyped, Scalars);

template <class S>
S up(S x) {
  return std::nextafter(x, std::numeric_limits<S>::infinity());
}
template <class S>
S down(S x) {
  return std::nextafter(x, -std::numeric_limits<S>::infinity());
}

// r = 1, lz = 2: apex (0, 0, 1), base z = -1; the radius at height z is
// (1 - z) / 2, exact for the dyadic heights used here.
TYPED_TEST(PointConeTyped, Regions) {
  using S = TypeParam;
  const Cone<S> c{1, 2};
  const Pose<S> I = identityPose<S>();
  auto in = [&](S x, S y, S z) { return contains(c, I, Vec3<S>{x, y, z}); };
  EXPECT_TRUE(in(0, 0, 1));          // apex
  EXPECT_FALSE(in(0, 0, up(S(1))));  // just above the apex
  EXPECT_FALSE(in(std::numeric_limits<S>::denorm_min(), 0, 1));  // beside it
  EXPECT_TRUE(in(0, 0, 0));                                      // centre
  EXPECT_TRUE(in(0, 0, -1));                                     // base centre
  EXPECT_FALSE(in(0, 0, down(S(-1))));  // below the base
  EXPECT_TRUE(in(1, 0, -1));            // base rim
  EXPECT_FALSE(in(up(S(1)), 0, -1));    // beyond the rim
  EXPECT_TRUE(in(S(0.5), 0, 0));        // slant at mid-height
  EXPECT_FALSE(in(up(S(0.5)), 0, 0));
  EXPECT_TRUE(in(down(S(0.5)), 0, 0));
  EXPECT_TRUE(in(0, S(-0.25), S(0.5)));  // slant, three quarters up
  EXPECT_FALSE(in(0, S(-0.25), up(S(0.5))));
  EXPECT_TRUE(in(0, S(-0.25), down(S(0.5))));
  EXPECT_FALSE(in(S(0.75), 0, 0));  // inside the cylinder, outside the cone
  // Exactly on the slant with a Pythagorean point: radius 5/8 at z = -1/4.
  EXPECT_TRUE(in(S(0.375), S(0.5), S(-0.25)));
  EXPECT_FALSE(in(S(0.375), up(S(0.5)), S(-0.25)));
}

TYPED_TEST(PointConeTyped, DegenerateSizes) {
  using S = TypeParam;
  const Pose<S> I = identityPose<S>();
  const S tiny = std::numeric_limits<S>::denorm_min();
  // lz = 0: the base disk (the hull of apex and base, both at z = 0), not
  // the whole plane z = 0.
  const Cone<S> disk{1, 0};
  EXPECT_TRUE(contains(disk, I, Vec3<S>{S(0.5), 0, 0}));
  EXPECT_TRUE(contains(disk, I, Vec3<S>{0, 1, 0}));
  EXPECT_FALSE(contains(disk, I, Vec3<S>{0, up(S(1)), 0}));
  EXPECT_FALSE(contains(disk, I, Vec3<S>{2, 0, 0}));
  EXPECT_FALSE(contains(disk, I, Vec3<S>{0, 0, tiny}));
  // r = 0: the axis segment.
  const Cone<S> needle{0, 2};
  EXPECT_TRUE(contains(needle, I, Vec3<S>{0, 0, 1}));
  EXPECT_TRUE(contains(needle, I, Vec3<S>{0, 0, S(-0.5)}));
  EXPECT_FALSE(contains(needle, I, Vec3<S>{tiny, 0, 0}));
  EXPECT_FALSE(contains(needle, I, Vec3<S>{0, 0, up(S(1))}));
  // r = lz = 0: the point.
  EXPECT_TRUE(contains(Cone<S>{0, 0}, I, Vec3<S>{0, 0, 0}));
  EXPECT_FALSE(contains(Cone<S>{0, 0}, I, Vec3<S>{0, tiny, 0}));
}

TYPED_TEST(PointConeTyped, InvalidInput) {
  using S = TypeParam;
  const test::InvalidInputs<S> in;
  in.template expectBadSizesThrow<Cone>();
  EXPECT_THROW(contains(Cone<S>{1, 1}, in.I, Vec3<S>{0, 0, in.inf}),
               InvalidInput);
  Pose<S> bad = in.I;
  bad.R[0][0] = in.inf;
  EXPECT_EQ(tryContains(Cone<S>{1, 1}, bad, in.o), Answer::kInvalidInput);
}

// The sources' apex form: 0 <= (P-O).N <= L and the distance to the axis
// <= ((P-O).N) R / L, against coneFromApex, away from the boundary.
TYPED_TEST(PointConeTyped, ApexFormMatchesSourceFormula) {
  using S = TypeParam;
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed + 7);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto a = test::randomAxisForm<S>(g);
    const Vec3<S>& O = a.O;
    const S L = a.L, R = a.R;
    const Vec3<S> P{S(O.x + g.uniform(-3, 3)), S(O.y + g.uniform(-3, 3)),
                    S(O.z + g.uniform(-3, 3))};
    const auto [dp, t2] = test::axialCoords(a, P);
    const double t = std::sqrt(t2);
    const double rad = dp * R / L;
    const double margin =
        std::min({std::fabs(dp), std::fabs(dp - L), std::fabs(t - rad)});
    if (margin < 1e-3) continue;
    const bool source = dp >= 0 && dp <= L && t <= rad;
    const auto pc = coneFromApex(O, a.N, L, R);
    EXPECT_EQ(contains(pc.cone, pc.pose, P), source) << "case " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

class PointConeFamily : public ::testing::TestWithParam<test::Family> {};

TEST_P(PointConeFamily, AgreesWithOracle) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  const auto st = test::runAgreement(
      test::Query::kPointCone, GetParam(), test::scaled(100000),
      [](const auto& t) {
        using S = decltype(t.rho);
        return decideContains(Cone<S>{t.cyl.radius, t.cyl.lz}, t.pose, t.p);
      },
      [](const test::QueryCase& k) {
        return oracle::pointInCone({k.cyl.radius, k.cyl.lz}, k.pose, k.p);
      });
  EXPECT_EQ(st.failures, 0);
}

INSTANTIATE_TEST_SUITE_P(Families, PointConeFamily,
                         ::testing::ValuesIn(qscenes::kAllFamilies),
                         test::familyParamName);

}  // namespace
}  // namespace tricyl
