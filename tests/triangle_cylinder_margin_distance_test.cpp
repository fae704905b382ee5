// SPDX-License-Identifier: BSD-3-Clause
// tricyl::withinDistance against the distance oracle of support/
// (distance_oracle.h: MPFR at 333 bits, a certified enclosure lo <= d <= hi
// of relative width <= 2^-200), which shares nothing with the margin kernel
// or its GMP oracle: on the six scene families, every margin below lo must
// answer false and every margin at or above hi true, at 1, 4 and 2^20 ulps
// either side. Built only when that oracle is (TRICYL_HAVE_DISTANCE_ORACLE).
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <string>

#include "distance_oracle.h"
#include "margin_test_support.h"
#include "scenes.h"
#include "test_support.h"
#include "tricyl/triangle_cylinder_margin.h"

namespace tricyl {
namespace {

using test::ulpsFrom;

class MarginVsDistanceOracle : public ::testing::TestWithParam<scenes::Family> {
};

TEST_P(MarginVsDistanceOracle, AgreesAroundTheEnclosure) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  const scenes::Family fam = GetParam();
  const long n = test::scaled(200);
  long checked = 0, loose = 0;
  for (long i = 0; i < n; ++i) {
    const scenes::TriCase k =
        scenes::generate(fam, seed ^ 0x3d15, std::uint64_t(i));
    const oracle::DistanceEnclosure e =
        oracle::distanceEnclosure(k.cyl, k.pose, k.tri);
    SCOPED_TRACE(std::string(scenes::familyName(fam)) + " case " +
                 std::to_string(i));
    auto within = [&](double m) {
      return tryWithinDistance(k.cyl, k.pose, k.tri, m) == Answer::kIntersect;
    };
    if (e.intersect) {
      ASSERT_TRUE(within(0.0));
      ++checked;
      continue;
    }
    if (!e.tight) {  // the oracle did not certify a tight enclosure
      ++loose;
      continue;
    }
    for (std::int64_t u : {1, 4, 1 << 20}) {
      const double below = ulpsFrom(e.lo, -u), above = ulpsFrom(e.hi, u);
      if (below < e.lo) {
        ASSERT_FALSE(within(below)) << "m = " << below;
      }
      ASSERT_TRUE(within(above)) << "m = " << above;
      checked += 2;
    }
    ASSERT_TRUE(within(e.hi)) << "m = hi = " << e.hi;
    if (e.lo == e.hi) {
      ASSERT_TRUE(within(e.lo));  // the distance is lo
    }
  }
  std::printf(
      "[ stats ] %s: %ld margins checked against the distance "
      "oracle, %ld cases without a tight enclosure\n",
      scenes::familyName(fam), checked, loose);
  EXPECT_EQ(loose, 0);
}

std::string familyName(const ::testing::TestParamInfo<scenes::Family>& p) {
  return scenes::familyName(p.param);
}

INSTANTIATE_TEST_SUITE_P(Families, MarginVsDistanceOracle,
                         ::testing::ValuesIn(scenes::kAllFamilies), familyName);

}  // namespace
}  // namespace tricyl
