// SPDX-License-Identifier: BSD-3-Clause
// Point in cylinder: hand cases for every region (typed over float and
// double), the endpoint form of the sources, invalid input, and seeded
// agreement with the exact oracle over the four families.
#include "tricyl/point_cylinder.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <type_traits>

#include "query_test_support.h"

namespace tricyl {
namespace {

template <class S>
class PointCylinderTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(PointCylinderTyped, Scalars);

// Cylinder r = 1, lz = 4 (|z| <= 2), identity pose: every region, with the
// boundary inside. All values are exact in float and double.
TYPED_TEST(PointCylinderTyped, RegionsIdentityPose) {
  using S = TypeParam;
  const Cylinder<S> c{1, 4};
  const Pose<S> I = identityPose<S>();
  struct Case {
    S x, y, z;
    bool inside;
    const char* what;
  } cases[] = {
      {0, 0, 0, true, "centre"},
      {0, 0, 2, true, "top cap centre (on the axis end)"},
      {0, 0, -2, true, "bottom cap centre"},
      {S(0.5), S(0.5), S(1.5), true, "interior"},
      {1, 0, 0, true, "on the side"},
      {S(0.6), S(0.8), S(-1), false, "0.6^2 + 0.8^2 rounds above 1"},
      {S(0.75), S(0.5), 2, true, "on the top cap"},
      {1, 0, 2, true, "on the top rim"},
      {0, -1, -2, true, "on the bottom rim"},
      {S(1.0625), 0, 0, false, "beyond the side"},
      {0, 0, S(2.0625), false, "beyond the top cap"},
      {0, 0, S(-2.0625), false, "beyond the bottom cap"},
      {1, 1, 0, false, "beyond the side, diagonal"},
      {1, 0, S(2.0625), false, "beyond the rim"},
  };
  for (const auto& k : cases) {
    SCOPED_TRACE(k.what);
    if (std::string(k.what).find("rounds") != std::string::npos) {
      // Decided exactly on the rounded inputs: 0.6 and 0.8 are not exact.
      const double x = double(k.x), y = double(k.y);
      const bool truth = oracle::pointInCylinder(
          {1, 4}, identityPose<double>(), Vec3<double>{x, y, double(k.z)});
      EXPECT_EQ(contains(c, I, Vec3<S>{k.x, k.y, k.z}), truth);
      continue;
    }
    EXPECT_EQ(contains(c, I, Vec3<S>{k.x, k.y, k.z}), k.inside);
  }
}

// Exactly on the side in a posed frame: r = 5/8 with the point (3/8, 4/8)
// in a rotated (signed permutation) frame translated by (1, 0, 0.5).
TYPED_TEST(PointCylinderTyped, ExactBoundaryPosed) {
  using S = TypeParam;
  Pose<S> pose{};
  pose.R[0][2] = 1;   // local z -> world x
  pose.R[1][0] = -1;  // local x -> world -y
  pose.R[2][1] = 1;   // local y -> world z
  pose.t = {1, 0, S(0.5)};
  const Cylinder<S> c{S(0.625), 2};
  auto world = [&](S lx, S ly, S lz) {
    return Vec3<S>{lz + 1, -lx, ly + S(0.5)};
  };
  EXPECT_TRUE(contains(c, pose, world(S(0.375), S(0.5), 1)));  // rim
  EXPECT_TRUE(contains(c, pose, world(S(0.375), S(0.5), 0)));  // side
  EXPECT_FALSE(contains(c, pose, world(S(0.375), S(0.5), S(1.0078125))));
  const S x_out = std::nextafter(S(0.375), S(1));
  EXPECT_FALSE(contains(c, pose, world(x_out, S(0.5), 0)));
  const S x_in = std::nextafter(S(0.375), S(0));
  EXPECT_TRUE(contains(c, pose, world(x_in, S(0.5), 0)));
}

TYPED_TEST(PointCylinderTyped, DegenerateSizes) {
  using S = TypeParam;
  const Pose<S> I = identityPose<S>();
  // r = 0: the axis segment.
  EXPECT_TRUE(contains(Cylinder<S>{0, 2}, I, Vec3<S>{0, 0, 1}));
  EXPECT_TRUE(contains(Cylinder<S>{0, 2}, I, Vec3<S>{0, 0, S(-0.5)}));
  EXPECT_FALSE(contains(Cylinder<S>{0, 2}, I,
                        Vec3<S>{std::numeric_limits<S>::denorm_min(), 0, 0}));
  // lz = 0: the disk in z = 0.
  EXPECT_TRUE(contains(Cylinder<S>{1, 0}, I, Vec3<S>{S(0.5), 0, 0}));
  EXPECT_TRUE(contains(Cylinder<S>{1, 0}, I, Vec3<S>{0, 1, S(-0.0)}));
  EXPECT_FALSE(contains(Cylinder<S>{1, 0}, I,
                        Vec3<S>{0, 0, std::numeric_limits<S>::denorm_min()}));
  // Both: the origin only.
  EXPECT_TRUE(contains(Cylinder<S>{0, 0}, I, Vec3<S>{0, 0, 0}));
  EXPECT_FALSE(contains(Cylinder<S>{0, 0}, I, Vec3<S>{0, 0, S(1e-30)}));
}

TYPED_TEST(PointCylinderTyped, InvalidInput) {
  using S = TypeParam;
  const test::InvalidInputs<S> in;
  in.template expectBadSizesThrow<Cylinder>();
  const S nan = in.nan, inf = in.inf;
  const Pose<S>& I = in.I;
  const Vec3<S>& o = in.o;
  EXPECT_THROW(contains(Cylinder<S>{1, inf}, I, o), InvalidInput);
  EXPECT_THROW(contains(Cylinder<S>{1, 1}, I, Vec3<S>{nan, 0, 0}),
               InvalidInput);
  EXPECT_THROW(contains(Cylinder<S>{1, 1}, I, Vec3<S>{0, -inf, 0}),
               InvalidInput);
  Pose<S> bad = I;
  bad.R[1][2] = nan;
  EXPECT_EQ(tryContains(Cylinder<S>{1, 1}, bad, o), Answer::kInvalidInput);
  bad = I;
  bad.t.z = inf;
  EXPECT_EQ(tryContains(Cylinder<S>{1, 1}, bad, o), Answer::kInvalidInput);
  // -0 is a valid size.
  EXPECT_EQ(tryContains(Cylinder<S>{S(-0.0), S(-0.0)}, I, o),
            Answer::kIntersect);
}

// The sources' formula 0 <= (P-O).N <= L, |(P-O) - ((P-O).N) N| <= R on
// the endpoint form, against the converted pose, on cases far from the
// boundary (the conversion rounds; see endpoint_form.h).
TYPED_TEST(PointCylinderTyped, EndpointFormMatchesSourceFormula) {
  using S = TypeParam;
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const auto a = test::randomAxisForm<S>(g);
    const Vec3<S>&O = a.O, &N = a.N;
    const S L = a.L, R = a.R;
    const Vec3<S> P{S(g.uniform(-4, 4)), S(g.uniform(-4, 4)),
                    S(g.uniform(-4, 4))};
    const auto [dp, t2] = test::axialCoords(a, P);
    // Skip cases within 1e-3 of the boundary (formula and conversion round).
    const double margin = std::min(
        {std::fabs(dp), std::fabs(dp - L), std::fabs(std::sqrt(t2) - R)});
    if (margin < 1e-3) continue;
    const bool source = dp >= 0 && dp <= L && t2 <= double(R) * R;
    const auto pc = cylinderFromAxis(O, N, L, R);
    EXPECT_EQ(contains(pc.cylinder, pc.pose, P), source) << "case " << i;
    // The a-to-b form of the same cylinder.
    const Vec3<S> b{O.x + N.x * L, O.y + N.y * L, O.z + N.z * L};
    const auto pe = cylinderFromEndpoints(O, b, R);
    EXPECT_EQ(contains(pe.cylinder, pe.pose, P), source) << "case " << i;
    ++checked;
  }
  EXPECT_GT(checked, 1500);
}

// Exact conversions: an axis along +z (or -z, +x) with dyadic data gives an
// exact pose, so boundary points stay exactly on the boundary.
TYPED_TEST(PointCylinderTyped, EndpointFormExactCases) {
  using S = TypeParam;
  const auto pc =
      cylinderFromAxis(Vec3<S>{1, 2, 3}, Vec3<S>{0, 0, 1}, S(4), S(0.5));
  EXPECT_EQ(pc.pose.t.z, S(5));
  EXPECT_EQ(pc.cylinder.lz, S(4));
  EXPECT_TRUE(contains(pc.cylinder, pc.pose, Vec3<S>{S(1.5), 2, 7}));  // rim
  EXPECT_FALSE(contains(pc.cylinder, pc.pose,
                        Vec3<S>{S(1.5), 2, std::nextafter(S(7), S(8))}));
  EXPECT_TRUE(contains(pc.cylinder, pc.pose, Vec3<S>{1, 2, 3}));  // O itself
  const auto pe =
      cylinderFromEndpoints(Vec3<S>{0, 0, 0}, Vec3<S>{-2, 0, 0}, S(1));
  EXPECT_EQ(pe.cylinder.lz, S(2));
  EXPECT_TRUE(contains(pe.cylinder, pe.pose, Vec3<S>{-2, 0, 1}));  // rim
  EXPECT_FALSE(contains(pe.cylinder, pe.pose, Vec3<S>{S(0.25), 0, 0}));
  // a == b: the disk of radius R about a in the plane z = a.z.
  const auto pd =
      cylinderFromEndpoints(Vec3<S>{1, 1, 1}, Vec3<S>{1, 1, 1}, S(1));
  EXPECT_TRUE(contains(pd.cylinder, pd.pose, Vec3<S>{2, 1, 1}));
  EXPECT_FALSE(contains(pd.cylinder, pd.pose, Vec3<S>{1, 1, S(1.5)}));
}

// Regression (found by fuzz_point_cylinder, seeds axis_N_huge and
// axis_N_tiny). The helpers used to normalise N as N / sqrt(N.N): for
// |N| = 0x1.4e718d7d7625ap+664 the square overflows to +Inf, N / Inf is 0,
// and the pose's axis column was (0, 0, 0): a singular R, so every query
// answered for a degenerate solid. For |N| = 0x1.87e92154ef7acp-665 the
// square underflows to 0, and the "N = 0" branch silently replaced the axis
// by +z. cylinderFromEndpoints had the same fault in L = |b - a| (lz = 0 for
// a tiny b - a). N (and b - a) are now scaled by a power of two before they
// are squared. Also checked: huge/tiny directions in float, and a NaN
// direction gives a NaN axis (the query then reports invalid input).
TYPED_TEST(PointCylinderTyped, EndpointFormHugeAndTinyDirections) {
  using S = TypeParam;
  const int top = std::numeric_limits<S>::max_exponent - 2;  // 1022 / 126
  const int bottom = std::numeric_limits<S>::min_exponent -
                     std::numeric_limits<S>::digits + 1;  // subnormal
  const S huge = std::is_same_v<S, double> ? S(0x1.4e718d7d7625ap+664)
                                           : S(0x1.4e718ep+100f);
  const S tiny = std::is_same_v<S, double> ? S(0x1.87e92154ef7acp-665)
                                           : S(0x1.87e922p-100f);
  for (S n : {huge, tiny, std::ldexp(S(1.5), top), std::ldexp(S(1), bottom)}) {
    SCOPED_TRACE(testing::Message() << "N.x = " << n);
    const auto pc =
        cylinderFromAxis(Vec3<S>{0, 0, 0}, Vec3<S>{n, 0, 0}, S(2), S(1));
    // The axis is exactly +x (N / |N| with |N| = N.x), so the solid is
    // 0 <= x <= 2, y^2 + z^2 <= 1.
    EXPECT_EQ(pc.pose.R[0][2], S(1));
    EXPECT_EQ(pc.pose.R[1][2], S(0));
    EXPECT_EQ(pc.pose.R[2][2], S(0));
    EXPECT_TRUE(contains(pc.cylinder, pc.pose, Vec3<S>{S(2), 0, 1}));  // rim
    EXPECT_FALSE(contains(pc.cylinder, pc.pose, Vec3<S>{S(1), 0, S(1.25)}));
    // Endpoints n apart along y: lz is |b - a| = n exactly.
    const auto pe =
        cylinderFromEndpoints(Vec3<S>{0, 0, 0}, Vec3<S>{0, n, 0}, S(1));
    EXPECT_EQ(pe.cylinder.lz, n);
    EXPECT_EQ(pe.pose.R[1][2], S(1));
  }
  // A diagonal huge direction keeps unit length to a few ulps.
  const auto pd = cylinderFromAxis(Vec3<S>{0, 0, 0}, Vec3<S>{huge, huge, -huge},
                                   S(2), S(1));
  const S c = S(1) / std::sqrt(S(3));
  const S eps = std::numeric_limits<S>::epsilon();
  EXPECT_NEAR(pd.pose.R[0][2], c, 4 * eps);
  EXPECT_NEAR(pd.pose.R[1][2], c, 4 * eps);
  EXPECT_NEAR(pd.pose.R[2][2], -c, 4 * eps);
  // Non-finite directions: a NaN axis, reported by the query.
  test::NoFpTraps no_traps;
  const S inf = std::numeric_limits<S>::infinity();
  const auto pn =
      cylinderFromAxis(Vec3<S>{0, 0, 0}, Vec3<S>{inf, 0, 0}, S(2), S(1));
  EXPECT_TRUE(std::isnan(pn.pose.R[0][2]));
  EXPECT_THROW(contains(pn.cylinder, pn.pose, Vec3<S>{0, 0, 0}), InvalidInput);
}

class PointCylinderFamily : public ::testing::TestWithParam<test::Family> {};

TEST_P(PointCylinderFamily, AgreesWithOracle) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  const auto st = test::runAgreement(
      test::Query::kPointCylinder, GetParam(), test::scaled(100000),
      [](const auto& t) { return decideContains(t.cyl, t.pose, t.p); },
      [](const test::QueryCase& k) {
        return oracle::pointInCylinder(k.cyl, k.pose, k.p);
      });
  EXPECT_EQ(st.failures, 0);
}

INSTANTIATE_TEST_SUITE_P(Families, PointCylinderFamily,
                         ::testing::ValuesIn(qscenes::kAllFamilies),
                         test::familyParamName);

}  // namespace
}  // namespace tricyl
