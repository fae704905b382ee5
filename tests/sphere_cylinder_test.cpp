// SPDX-License-Identifier: BSD-3-Clause
// Sphere vs cylinder: hand cases for every region of the source's case
// split (typed over float and double), the meaning of the radius for a
// non-orthonormal R, invalid input, and seeded agreement with the exact
// oracle over the four families.
#include "tricyl/sphere_cylinder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "query_test_support.h"

namespace tricyl {
namespace {

template <class S>
class SphereCylinderTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(SphereCylinderTyped, Scalars);

template <class S>
S down(S x) {
  return std::nextafter(x, S(0));
}

// r = 1, lz = 2 (|z| <= 1), identity pose. Touching configurations are
// exact (dyadic, Pythagorean for the rim) and flip with one ulp of rho.
TYPED_TEST(SphereCylinderTyped, Regions) {
  using S = TypeParam;
  const Cylinder<S> c{1, 2};
  const Pose<S> I = identityPose<S>();
  auto hit = [&](S x, S y, S z, S rho) {
    return intersect(c, I, Sphere<S>{Vec3<S>{x, y, z}, rho});
  };
  EXPECT_TRUE(hit(0, 0, 0, S(0.5)));        // centre inside
  EXPECT_TRUE(hit(S(0.25), 0, S(0.5), 0));  // rho = 0, point inside
  // Within the slab, beyond the side: s <= (r + rho)^2.
  EXPECT_TRUE(hit(S(1.5), 0, 0, S(0.5)));
  EXPECT_FALSE(hit(S(1.5), 0, 0, down(S(0.5))));
  EXPECT_TRUE(hit(0, S(-1.5), S(0.999), S(0.5)));
  // Beyond the top cap, above the cap disk: e <= rho.
  EXPECT_TRUE(hit(S(0.5), 0, S(1.5), S(0.5)));
  EXPECT_FALSE(hit(S(0.5), 0, S(1.5), down(S(0.5))));
  // Beyond the bottom cap.
  EXPECT_TRUE(hit(0, S(0.75), S(-1.25), S(0.25)));
  EXPECT_FALSE(hit(0, S(0.75), S(-1.25), down(S(0.25))));
  // Beyond a cap AND beyond the side: the rim, via the slice radius
  // f = sqrt(rho^2 - e^2). Centre (1 + 3/8, 0, 1 + 1/2), rho = 5/8.
  EXPECT_TRUE(hit(S(1.375), 0, S(1.5), S(0.625)));
  EXPECT_FALSE(hit(S(1.375), 0, S(1.5), down(S(0.625))));
  EXPECT_TRUE(hit(0, S(-1.375), S(-1.5), S(0.625)));
  EXPECT_FALSE(hit(0, S(-1.375), S(-1.5), down(S(0.625))));
  // Close to the rim radially but too high: e > rho.
  EXPECT_FALSE(hit(1, 0, S(2.5), S(1.25)));
  EXPECT_TRUE(hit(1, 0, S(2.25), S(1.25)));
  // The source's (R + r) test alone would accept this: within the slab's
  // radial reach but beyond the cap, where the slice radius is 0.
  EXPECT_FALSE(hit(S(1.5), 0, S(1.5), S(0.5)));
}

TYPED_TEST(SphereCylinderTyped, DegenerateSizes) {
  using S = TypeParam;
  const Pose<S> I = identityPose<S>();
  // r = 0: the axis segment |z| <= 1.
  EXPECT_TRUE(intersect(Cylinder<S>{0, 2}, I,
                        Sphere<S>{Vec3<S>{S(0.5), 0, 0}, S(0.5)}));
  EXPECT_FALSE(intersect(Cylinder<S>{0, 2}, I,
                         Sphere<S>{Vec3<S>{S(0.5), 0, 0}, down(S(0.5))}));
  EXPECT_TRUE(intersect(Cylinder<S>{0, 2}, I,
                        Sphere<S>{Vec3<S>{S(0.375), 0, S(1.5)}, S(0.625)}));
  EXPECT_FALSE(intersect(Cylinder<S>{0, 2}, I,
                         Sphere<S>{Vec3<S>{S(0.5), 0, S(1.5)}, S(0.5)}));
  // lz = 0: the unit disk.
  EXPECT_TRUE(intersect(Cylinder<S>{1, 0}, I,
                        Sphere<S>{Vec3<S>{0, 0, S(0.5)}, S(0.5)}));
  EXPECT_FALSE(intersect(Cylinder<S>{1, 0}, I,
                         Sphere<S>{Vec3<S>{0, 0, S(0.5)}, down(S(0.5))}));
  // rho = 0 on the rim; r = lz = 0 with a sphere through the origin.
  EXPECT_TRUE(
      intersect(Cylinder<S>{1, 2}, I, Sphere<S>{Vec3<S>{0, 1, -1}, S(0)}));
  EXPECT_TRUE(intersect(Cylinder<S>{0, 0}, I,
                        Sphere<S>{Vec3<S>{S(0.375), S(0.5), 0}, S(0.625)}));
  EXPECT_FALSE(
      intersect(Cylinder<S>{0, 0}, I,
                Sphere<S>{Vec3<S>{S(0.375), S(0.5), 0}, down(S(0.625))}));
}

// "The radius is taken in the cylinder's frame": with R = 2 I (not a
// rotation), the world centre (1, 0, 0) maps to the local (2, 0, 0), and a
// local radius 1 touches the side x = 1. In the world this is the ellipsoid
// |R^T (x - c)| <= rho, i.e. the world ball of radius 1/2 about (1, 0, 0),
// which touches the world cylinder (local radius 1 = world radius 1/2).
TYPED_TEST(SphereCylinderTyped, RadiusInCylinderFrame) {
  using S = TypeParam;
  Pose<S> p{};
  p.R[0][0] = p.R[1][1] = p.R[2][2] = 2;
  const Cylinder<S> c{1, 2};
  EXPECT_TRUE(intersect(c, p, Sphere<S>{Vec3<S>{1, 0, 0}, S(1)}));
  EXPECT_FALSE(intersect(c, p, Sphere<S>{Vec3<S>{1, 0, 0}, down(S(1))}));
}

TYPED_TEST(SphereCylinderTyped, InvalidInput) {
  using S = TypeParam;
  test::NoFpTraps no_traps;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S inf = std::numeric_limits<S>::infinity();
  const Pose<S> I = identityPose<S>();
  const Cylinder<S> c{1, 1};
  EXPECT_THROW(intersect(c, I, Sphere<S>{Vec3<S>{0, 0, 0}, S(-1)}),
               InvalidInput);
  EXPECT_THROW(intersect(c, I, Sphere<S>{Vec3<S>{0, 0, 0}, nan}), InvalidInput);
  EXPECT_THROW(intersect(c, I, Sphere<S>{Vec3<S>{0, 0, 0}, inf}), InvalidInput);
  EXPECT_THROW(intersect(c, I, Sphere<S>{Vec3<S>{nan, 0, 0}, 1}), InvalidInput);
  EXPECT_THROW(intersect(Cylinder<S>{-1, 1}, I, Sphere<S>{Vec3<S>{}, 1}),
               InvalidInput);
  EXPECT_EQ(tryIntersect(Cylinder<S>{1, inf}, I, Sphere<S>{Vec3<S>{}, 1}),
            Answer::kInvalidInput);
}

class SphereCylinderFamily : public ::testing::TestWithParam<test::Family> {};

TEST_P(SphereCylinderFamily, AgreesWithOracle) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  const auto st = test::runAgreement(
      test::Query::kSphere, GetParam(), test::scaled(100000),
      [](const auto& t) {
        using S = decltype(t.rho);
        return decideIntersect(t.cyl, t.pose, Sphere<S>{t.p, t.rho});
      },
      [](const test::QueryCase& k) {
        return oracle::sphereCylinder(k.cyl, k.pose, {k.p, k.rho});
      });
  EXPECT_EQ(st.failures, 0);
}

INSTANTIATE_TEST_SUITE_P(Families, SphereCylinderFamily,
                         ::testing::ValuesIn(qscenes::kAllFamilies),
                         test::familyParamName);

}  // namespace
}  // namespace tricyl
