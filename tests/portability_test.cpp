// SPDX-License-Identifier: BSD-3-Clause
// Same answers on every compiler and platform (issue 20): regressions for
// the four defects found by building tricyl with clang-14, with a long
// double no wider than double (-mlong-double-64), and for AArch64. Each
// test keeps the literal failing input; each is written so that it fails
// wherever the defect can show, without relying on FP traps (which AArch64
// hardware and qemu do not deliver: feenableexcept fails there), by reading
// the sticky exception flags. The fourth defect (the running-stage test's
// exactly() dropping significand bits of a binary128) is pinned in
// tests/running_stage_test.cpp (RunningFrameExactly).
#include <fenv.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstring>
#include <limits>

#include "filter.h"
#include "test_support.h"
#include "tricyl/tricyl.h"

namespace tricyl {
namespace {

/// Clears the exception flags and keeps the traps off for its scope (so a
/// raised flag is reported by the test, not by SIGFPE); raised() reads
/// FE_INVALID and FE_DIVBYZERO, the two the library promises never to raise.
struct FlagWatch {
  test::NoFpTraps no_traps;
  FlagWatch() { feclearexcept(FE_ALL_EXCEPT); }
  int raised() const { return fetestexcept(FE_INVALID | FE_DIVBYZERO); }
};

// Defect a. MECHANISM: the running error bound (src/filter.h, Running<T>)
// adds to every product an absolute allowance kTiny for underflow. It was 0
// in long double (the type of the interval's second stage then) on the
// argument that the extended exponent range makes the loss negligible;
// where long double is double (MSVC, Apple silicon, 32-bit ARM;
// -mlong-double-64) dmin * dmin underflowed to 0 with bound 0, and the
// line interval (src/line_cylinder_interval.cpp) took A = Dy * Dy = 0 for a
// certified zero: the line through (1, 0, 0) with direction (0, dmin, 0),
// tangent to the side at s = 0, clipped to [-inf, +inf] instead of [0, 0].
// Now kTiny is the smallest subnormal, the interval certifies A = 0 from
// Dx = Dy = 0 (local coordinates with an exact zero factor in every term)
// instead of from A, and no stage uses long double at all (the second one
// is double-word). This test checks both the rule (it fails with kTiny = 0)
// and the literal query (which failed only with a long double of double
// width; the CI configuration "long double = double" runs it there).
template <class T>
void underflowIsNoCertifiedZero() {
  using N = detail::Running<T>;
  const T tiny = std::numeric_limits<T>::denorm_min();
  const N a{tiny, 0}, b{tiny, 0};
  const N p = a * b;
  // (Booleans: gtest would print a long double through libstdc++, across
  // the ABI of -mlong-double-64.)
  EXPECT_TRUE(p.v == 0);
  EXPECT_TRUE(p.e > 0) << "an underflowed product must not be a certified 0";
  const N z = N{0, 0} * b;  // a zero factor: the value is exactly 0
  EXPECT_TRUE(z.v == 0);
}

TEST(PortabilityIssue20, UnderflowedProductIsNoCertifiedZero) {
  underflowIsNoCertifiedZero<double>();
}

template <class S>
void tangentLineWithSubnormalDirection() {
  const Cylinder<S> c{1, 2};
  const Pose<S> I = identityPose<S>();
  const S dmin = std::numeric_limits<S>::denorm_min();
  const S inf = std::numeric_limits<S>::infinity();
  // The literal input of the report: tangent to the side at s = 0 only.
  Interval<S> iv{-1, -1};
  ASSERT_EQ(tryClip(c, I, Line<S>{{1, 0, 0}, {1, dmin, 0}}, &iv),
            Answer::kIntersect);
  EXPECT_EQ(iv.lo, S(0));
  EXPECT_EQ(iv.hi, S(0));
  // The same as a segment, and a few more of the degenerate family: the
  // direction's only non-zero component subnormal, in x and in y, on the
  // side and through the axis.
  ASSERT_EQ(tryClip(c, I, Segment<S>{{1, 0, 0}, {1, dmin, 0}}, &iv),
            Answer::kIntersect);
  EXPECT_EQ(iv.lo, S(0));
  EXPECT_EQ(iv.hi, S(0));
  ASSERT_EQ(tryClip(c, I, Line<S>{{0, 1, 0}, {dmin, 1, 0}}, &iv),
            Answer::kIntersect);
  EXPECT_EQ(iv.lo, S(0));
  EXPECT_EQ(iv.hi, S(0));
  // Through the axis: |s dmin| <= 1, beyond every finite S.
  ASSERT_EQ(tryClip(c, I, Line<S>{{0, 0, 0}, {0, dmin, 0}}, &iv),
            Answer::kIntersect);
  EXPECT_EQ(iv.lo, -inf);
  EXPECT_EQ(iv.hi, inf);
  ASSERT_EQ(tryClip(c, I, Segment<S>{{0, 0, 0}, {0, dmin, 0}}, &iv),
            Answer::kIntersect);
  EXPECT_EQ(iv.lo, S(0));
  EXPECT_EQ(iv.hi, S(1));
}

TEST(PortabilityIssue20, TangentLineWithSubnormalDirection) {
  tangentLineWithSubnormalDirection<double>();
  tangentLineWithSubnormalDirection<float>();
}

// Defect b. MECHANISM: the line interval resolved a crossing of its two
// approximated ends with
//   if (iv.lo > iv.hi) iv.lo = iv.hi = iv.lo / 2 + iv.hi / 2;
// on the final double ends, which are infinite for a whole-line clip.
// clang-14 if-converts the branch (it evaluates the midpoint unconditionally
// and selects), so -inf/2 + inf/2 raised FE_INVALID on a valid query: 11
// line_cylinder_test cases died with SIGFPE under the tests' traps. The
// crossing is now resolved inside stage 1, on finite values only, and no
// arithmetic is done on a possibly infinite end. The literal inputs: lines
// whose interval is all of R (in a cap plane; along a zero direction), and
// one whose ends are +-inf beyond the double range (direction dmin through
// the axis).
TEST(PortabilityIssue20, WholeLineClipRaisesNoFlag) {
  const double dmin = std::numeric_limits<double>::denorm_min();
  const double inf = std::numeric_limits<double>::infinity();
  const Cylinder<double> c{1, 2};
  const Pose<double> I = identityPose<double>();
  const Line<double> lines[] = {
      {{0, 0, 1}, {0, dmin, 1}},    // in the cap plane
      {{0, 0, -1}, {0, dmin, -1}},  // in the bottom cap plane
      {{0.5, 0, 0}, {0.5, 0, 0}},   // p == q inside: all s
      {{0, 0, 0}, {dmin, 0, 0}},    // through the axis, [-inf, inf]
      {{0, 0.5, 0.25}, {0, 0.5, 0.25}},
  };
  for (const Line<double>& l : lines) {
    Interval<double> iv{0, 0};
    FlagWatch w;
    const Answer a = tryClip(c, I, l, &iv);
    EXPECT_EQ(w.raised(), 0) << "FE_INVALID or FE_DIVBYZERO raised";
    ASSERT_EQ(a, Answer::kIntersect);
    EXPECT_EQ(iv.lo, -inf);
    EXPECT_EQ(iv.hi, inf);
  }
}

// Defect c. MECHANISM: the float queries widened their inputs to double
// before validating them; converting a signalling NaN raises FE_INVALID
// (SIGFPE with traps on), although the answer, kInvalidInput, was right.
// The triangle query read the floats' bits first and was clean; every
// query now does (detail::floatBitsFinite). The literal input: the cylinder
// {sNaN 0x7fa00000, 2}, identity pose; then an sNaN in each other input.
float sNaN() {
  const std::uint32_t bits = 0x7fa00000u;
  float f;
  std::memcpy(&f, &bits, sizeof f);
  return f;
}

TEST(PortabilityIssue20, FloatSignallingNaNRaisesNoFlag) {
  ASSERT_TRUE(std::numeric_limits<float>::has_signaling_NaN);
  const Pose<float> I = identityPose<float>();
  const Vec3<float> o{0, 0, 0}, x{1, 0, 0};
  auto check = [](const char* what, auto&& query) {
    FlagWatch w;
    const Answer a = query();
    EXPECT_EQ(w.raised(), 0) << what << ": FE_INVALID raised";
    EXPECT_EQ(a, Answer::kInvalidInput) << what;
  };
  for (int where = 0; where < 4; ++where) {
    // where 0: the cylinder's radius (the report's input); 1: a rotation
    // entry; 2: the translation; 3: the query's own point.
    Cylinder<float> cyl{1, 2};
    Pose<float> pose = I;
    Vec3<float> p = o;
    if (where == 0) cyl.radius = sNaN();
    if (where == 1) pose.R[1][2] = sNaN();
    if (where == 2) pose.t.y = sNaN();
    if (where == 3) p.z = sNaN();
    SCOPED_TRACE(where);
    check("point in cylinder", [&] { return tryContains(cyl, pose, p); });
    check("point in cone", [&] {
      return tryContains(Cone<float>{cyl.radius, cyl.lz}, pose, p);
    });
    check("sphere", [&] {
      return tryIntersect(cyl, pose, Sphere<float>{p, 0.5f});
    });
    check("segment", [&] {
      return tryIntersect(cyl, pose, Segment<float>{p, x});
    });
    check("segment clip", [&] {
      Interval<float> iv;
      return tryClip(cyl, pose, Segment<float>{x, p}, &iv);
    });
    check("line", [&] { return tryIntersect(cyl, pose, Line<float>{p, x}); });
    check("line clip", [&] {
      Interval<float> iv;
      return tryClip(cyl, pose, Line<float>{x, p}, &iv);
    });
    check("triangle", [&] {
      return tryIntersect(cyl, pose, Triangle<float>{p, x, {0, 1, 0}});
    });
  }
  // The sphere's own radius, last of its floats.
  check("sphere radius", [&] {
    return tryIntersect(Cylinder<float>{1, 2}, I, Sphere<float>{o, sNaN()});
  });
}

}  // namespace
}  // namespace tricyl
