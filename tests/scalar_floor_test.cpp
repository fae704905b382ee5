// SPDX-License-Identifier: BSD-3-Clause
// The floor benchmark's truncated first stages (bench/scalar_floor.h,
// BM_Floor) must do the kernel's real work, or the floor they measure would
// be a floor of something cheaper: every answer a certified level (3, 4, 5)
// gives is the kernel's, on the uniform cases BM_Floor times and on near
// cases (where an uncertified bound would claim early-outs the kernel does
// not take), and level 5 leaves open what the kernel's first branch leaves
// open, no more (about 14% of uniform). If the floor skipped a piece of the
// work (the bound, test (V)), these counts move.
#include "scalar_floor.h"

#include <gtest/gtest.h>

#include <cstdint>

#include "scenes.h"
#include "test_support.h"
#include "tricyl/triangle_cylinder.h"

#ifdef TRICYL_BENCH_FLOOR
namespace tricyl {
namespace {

namespace fl = bench::scalar_floor;

struct Counts {
  long early = 0, vertex = 0, open = 0, cases = 0;
};

// Runs the certified levels over `n` cases of family f (seed 7, as the
// benchmark) and checks every decided answer against the kernel.
Counts checkLevels(scenes::Family f, int n) {
  Counts c;
  for (int i = 0; i < n; ++i) {
    const auto k = scenes::generate(f, 7, std::uint64_t(i));
    SCOPED_TRACE("family " + std::string(scenes::familyName(f)) + ", case " +
                 std::to_string(i) + " (scenes::generate seed 7)");
    const bool hit = intersect(k.cyl, k.pose, k.tri);
    const int r3 = fl::query<3>(k.cyl, k.pose, k.tri);
    const int r4 = fl::query<4>(k.cyl, k.pose, k.tri);
    const int r5 = fl::query<5>(k.cyl, k.pose, k.tri);
    EXPECT_NE(r3, 2);  // level 3 has no (V)
    if (r3 == 1) {
      EXPECT_FALSE(hit);
    }
    EXPECT_NE(r4, 3);  // early-out and (V) never both
    if (r4 & 1) {
      EXPECT_FALSE(hit);
    }
    if (r4 & 2) {
      EXPECT_TRUE(hit);
    }
    // Level 5: 1 early-out, 2 (V), 3 or 4 open, and the same split as 4.
    EXPECT_EQ(r5 == 1, r4 == 1);
    EXPECT_EQ(r5 == 2, r4 == 2);
    c.early += r5 == 1;
    c.vertex += r5 == 2;
    c.open += r5 >= 3;
    ++c.cases;
  }
  return c;
}

TEST(ScalarFloor, CertifiedLevelsGiveTheKernelsAnswersOnUniform) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "needs AVX2";
  const Counts c = checkLevels(scenes::Family::kUniform, 4096);
  // BM_Floor's cases: about two thirds early-outs (the kernel's early-out
  // stage decides 66.06% of uniform at 10^6 cases), one in five (V), one in
  // seven open.
  EXPECT_GT(c.early, 4096 * 60 / 100);
  EXPECT_LT(c.early, 4096 * 72 / 100);
  EXPECT_GT(c.vertex, 4096 * 15 / 100);
  EXPECT_GT(c.open, 4096 * 10 / 100);
  EXPECT_LT(c.open, 4096 * 18 / 100);
}

TEST(ScalarFloor, CertifiedLevelsGiveTheKernelsAnswersNearTouching) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "needs AVX2";
  const Counts c = checkLevels(scenes::Family::kNear, 4096);
  EXPECT_GT(c.early + c.vertex, 0);
  EXPECT_GT(c.open, 0);
}

// The uncertified level 1 is not a kernel: touching cases pushed out by a
// few ulps make its early-outs and the kernel's differ somewhere in the near
// family, which is why the floor counts the bound (level 3) as work an
// exact answer needs.
TEST(ScalarFloor, UncertifiedTransformDiffersFromTheKernelNearTouching) {
  if (!__builtin_cpu_supports("avx2")) GTEST_SKIP() << "needs AVX2";
  long claimed_miss_of_hit = 0;
  for (int i = 0; i < 20000; ++i) {
    const auto k = scenes::generate(scenes::Family::kNear, 7, std::uint64_t(i));
    claimed_miss_of_hit += fl::query<1>(k.cyl, k.pose, k.tri) == 1 &&
                           intersect(k.cyl, k.pose, k.tri);
  }
  EXPECT_GT(claimed_miss_of_hit, 0);
}

}  // namespace
}  // namespace tricyl
#endif
