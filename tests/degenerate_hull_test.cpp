// SPDX-License-Identifier: BSD-3-Clause
// Degenerate triangles in a general pose (src/triangle_cylinder.cpp,
// degenerateHull; docs/exactness.md, section 6). Three exactly collinear
// vertices (a repeated vertex and a single point included) are decided as
// the segment between the two extreme vertices. Mechanism: the triangle
// kernel meets such input through signs that are exactly zero (the
// projected area; for a repeated vertex an edge of length zero); in a
// general pose the local frame rounds, so no error bound certifies them,
// and every such query used to reach GMP
// (all 1335 exact queries of 10^5 sliver cases, seed 20261122). The
// segment kernel has no such sign.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>

#include "oracle.h"
#include "scenes.h"
#include "test_support.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

// Vertices at s = 0, 1 and 3 on the line a + s u (dyadic, so exactly
// collinear), the cylinder (r = 1/4, lz = 1, bounding radius < 0.56)
// centred beside s = 2, at distance 1 from the line, with a random axis: a
// miss, in every vertex order. A hit of a degenerate triangle is certified
// by an edge (test (E)) as for any triangle; a miss needs "the origin is
// not inside the projected triangle", whose area is exactly zero: this is
// the query that reached GMP. (That the hull's ends are the extreme
// vertices is pinned by the aligned family and the power-of-two scaling
// tests: a hull of the first two vertices fails both.)
TEST(DegenerateHull, MissesInAGeneralPoseNeedNoGmpInEveryVertexOrder) {
  const std::uint64_t seed = test::baseSeed() + 81;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  const Cylinder<double> cyl{0.25, 1.0};
  // Dyadic: every a + s u below is exact. n is a unit vector orthogonal to u.
  const Vec3<double> a{0.375, -1.25, 2.5}, u{0.125, 0.5, 0.75},
      n{0.0, 0.8320502943378437, -0.5547001962252291};
  auto at = [&](double s) {
    return Vec3<double>{a.x + s * u.x, a.y + s * u.y, a.z + s * u.z};
  };
  const Vec3<double> p[3] = {at(0), at(1), at(3)};
  long exact = 0;
  for (int trial = 0; trial < 50; ++trial) {
    Pose<double> pose = test::randomPose(g, 1.0);  // a general rotation
    const Vec3<double> c = at(2);
    pose.t = {c.x + n.x, c.y + n.y, c.z + n.z};
    const int order[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                             {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& o : order) {
      const Triangle<double> tri{p[o[0]], p[o[1]], p[o[2]]};
      const Decision d = decideIntersect(cyl, pose, tri);
      EXPECT_EQ(d.answer, Answer::kDisjoint)
          << "trial " << trial << ", order " << o[0] << o[1] << o[2];
      exact += d.stage == Stage::kExact;
    }
    EXPECT_FALSE(oracle::triangleCylinder(cyl, pose, {p[0], p[1], p[2]}));
  }
  EXPECT_EQ(exact, 0);
}

// Exactly degenerate triangles of the sliver family (collinear on a dyadic
// grid, a repeated vertex, a single point) in general poses: every answer
// is the oracle's, and (almost) none needs GMP. Before the reduction 2.2%
// of them did.
TEST(DegenerateHull, SliverDegeneratesAgreeWithTheOracleWithoutGmp) {
  const std::uint64_t seed = test::baseSeed() + 82;
  SCOPED_TRACE(test::seedTrace(seed));
  const long n = test::scaled(20000);
  long degenerate = 0, exact = 0, hits = 0, failures = 0;
  for (long i = 0; degenerate < n && failures < 10; ++i) {
    const scenes::TriCase k =
        scenes::generate(scenes::Family::kSliver, seed, std::uint64_t(i));
    const std::string f = k.feature;
    if (f != "collinear" && f != "repeated_vertex" && f != "point") continue;
    ++degenerate;
    const Decision d = decideIntersect(k.cyl, k.pose, k.tri);
    exact += d.stage == Stage::kExact;
    const bool truth = oracle::triangleCylinder(k.cyl, k.pose, k.tri);
    hits += truth;
    if ((d.answer == Answer::kIntersect) != truth) {
      ++failures;
      ADD_FAILURE() << "case " << i << " (" << f << "): oracle " << truth;
    }
  }
  std::printf(
      "[ stats    ] %ld degenerate sliver triangles, %ld hits, %ld exact\n",
      degenerate, hits, exact);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(hits, degenerate / 20);  // the hits are exercised too
  EXPECT_LE(exact, degenerate / 1000);
}

// Near-touching degenerate triangles: a near-family triangle with its third
// vertex replaced by its second (a segment through the near-touching
// configuration), or by the extension 2b - a (exactly collinear when its
// rounding is exact; otherwise a sliver). The segment
// query's own stages decide these; the answer is the oracle's.
TEST(DegenerateHull, NearTouchingDegeneratesAgreeWithTheOracle) {
  const std::uint64_t seed = test::baseSeed() + 83;
  SCOPED_TRACE(test::seedTrace(seed));
  const long n = test::scaled(4000);
  long failures = 0, hits = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    scenes::TriCase k =
        scenes::generate(scenes::Family::kNear, seed, std::uint64_t(i));
    if (i % 2 == 0) {
      k.tri.c = k.tri.b;
    } else {
      k.tri.c = {2 * k.tri.b.x - k.tri.a.x, 2 * k.tri.b.y - k.tri.a.y,
                 2 * k.tri.b.z - k.tri.a.z};
    }
    const bool truth = oracle::triangleCylinder(k.cyl, k.pose, k.tri);
    hits += truth;
    if ((tryIntersect(k.cyl, k.pose, k.tri) == Answer::kIntersect) != truth) {
      ++failures;
      ADD_FAILURE() << "case " << i << ": oracle " << truth;
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(hits, n / 10);
}

}  // namespace
}  // namespace tricyl
