// SPDX-License-Identifier: BSD-3-Clause
// tricyl::distance (issue 23, part 1): hand-built cases with known
// distances, invariances, 0 exactly when intersect, and agreement with the
// certified MPFR oracle (support/distance_oracle.h) within 8 ulps on every
// family of compare/scenes.h and on constructed separations 1e-15 .. 1e3
// of the size. Seeds are printed on failure (TRICYL_SEED replays).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>

#include "distance_oracle.h"
#include "scenes.h"
#include "test_support.h"
#include "tricyl/tricyl.h"

namespace tricyl {
namespace {

using V = Vec3<double>;
constexpr double kUlp = 0x1p-52;

double ulpOf(double x) {
  int e = 0;
  (void)std::frexp(x, &e);
  return std::ldexp(1.0, (e - 1 < -1022 ? -1022 : e - 1) - 52);
}

// |d - expect| in ulps of expect (expect the correctly rounded value).
double ulpsFrom(double d, double expect) {
  return std::abs(d - expect) / ulpOf(expect);
}

struct Known {
  const char* name;
  Cylinder<double> cyl;
  Triangle<double> tri;
  double distance;  // the true distance, rounded to nearest
};

// Local-frame cases whose distance is known in closed form.
const Known kKnown[] = {
    {"vertex above cap", {1, 2}, {{0, 0, 3}, {5, 5, 10}, {-5, 5, 10}}, 2},
    {"vertex beside barrel", {1, 2}, {{3, 4, 0.5}, {9, 9, 0}, {9, 4, 1}}, 4},
    {"edge parallel to barrel",
     {1, 2},
     {{3, 0, -0.5}, {3, 0, 0.5}, {10, 0, 0}},
     2},
    {"edge crossing barrel", {1, 2}, {{3, -1, 0}, {3, 1, 0}, {9, 0, 0}}, 2},
    {"edge to rim",
     {1, 2},
     {{2, -5, 2}, {2, 5, 2}, {10, 0, 10}},
     1.4142135623730951},
    {"edge over cap",
     {1, 2},
     {{-5, 0.25, 1.75}, {5, 0.25, 1.75}, {0, 9, 9}},
     0.75},
    {"face over cap", {1, 2}, {{-5, -5, 1.5}, {5, -5, 1.5}, {0, 5, 1.5}}, 0.5},
    {"face over rim",
     {1, 2},
     {{0, -5, 4}, {0, 5, 4}, {6, 0, -2}},
     1.4142135623730951},
    {"face beside barrel", {1, 2}, {{3, -5, -5}, {3, 5, -5}, {3, 0, 5}}, 2},
    {"point above rim", {1, 2}, {{4, 0, 5}, {4, 0, 5}, {4, 0, 5}}, 5},
    {"segment below cap",
     {1, 2},
     {{-3, 0, -1.5}, {3, 0, -1.5}, {3, 0, -1.5}},
     0.5},
    {"axis (r = 0)", {0, 2}, {{3, 4, 0}, {3, 4, 0.5}, {3, 9, 0}}, 5},
    {"disk (lz = 0)", {1, 0}, {{0, 0, 2}, {5, 5, 9}, {-5, 5, 9}}, 2},
    {"tiny gap above cap",
     {1, 2},
     {{0, 0, 1 + 0x1p-50}, {5, 5, 9}, {-5, 5, 9}},
     0x1p-50},
};

TEST(TriangleCylinderDistance, KnownCases) {
  for (const Known& k : kKnown) {
    SCOPED_TRACE(k.name);
    const DistanceResult<double> r = distance(k.cyl, k.tri);
    EXPECT_LE(ulpsFrom(r.distance, k.distance), 8) << r.distance;
    EXPECT_GE(r.error_bound,
              std::abs(r.distance - k.distance) - ulpOf(k.distance) / 2);
    // The points are on their sets and as far apart as the distance.
    const Pose<double> id = identityPose<double>();
    EXPECT_LE(oracle::pointCylinderDistance(k.cyl, id, r.point_on_cylinder),
              4 * kUlp * 16);
    EXPECT_LE(oracle::pointTriangleDistance(k.tri, r.point_on_triangle),
              4 * kUlp * 16);
    const double dx = r.point_on_triangle.x - r.point_on_cylinder.x,
                 dy = r.point_on_triangle.y - r.point_on_cylinder.y,
                 dz = r.point_on_triangle.z - r.point_on_cylinder.z;
    EXPECT_NEAR(std::sqrt(dx * dx + dy * dy + dz * dz), k.distance,
                64 * kUlp * 16);
    // float: the same within 8 float ulps.
    const Cylinder<float> cf{float(k.cyl.radius), float(k.cyl.lz)};
    const Triangle<float> tf{
        {float(k.tri.a.x), float(k.tri.a.y), float(k.tri.a.z)},
        {float(k.tri.b.x), float(k.tri.b.y), float(k.tri.b.z)},
        {float(k.tri.c.x), float(k.tri.c.y), float(k.tri.c.z)}};
    if (double(float(k.distance)) == k.distance &&
        double(tf.a.z) == k.tri.a.z) {
      const DistanceResult<float> rf = distance(cf, tf);
      EXPECT_LE(std::abs(double(rf.distance) - k.distance),
                8 * double(std::numeric_limits<float>::epsilon()) * k.distance);
    }
  }
}

TEST(TriangleCylinderDistance, ZeroExactlyWhenIntersecting) {
  const Cylinder<double> c{1, 2};
  const Triangle<double> slab{{-5, -5, 0}, {5, -5, 0}, {0, 5, 0}};
  const DistanceResult<double> r = distance(c, slab);
  EXPECT_EQ(r.distance, 0);
  EXPECT_EQ(r.error_bound, 0);
  // Touching counts: a vertex exactly on the rim.
  const Triangle<double> touch{{1, 0, 1}, {5, 0, 5}, {5, 1, 5}};
  EXPECT_TRUE(intersect(c, touch));
  EXPECT_EQ(distance(c, touch).distance, 0);
  // The smallest gap a double allows above the cap is positive.
  const Triangle<double> gap{
      {0, 0, std::nextafter(1.0, 2.0)}, {5, 0, 5}, {5, 1, 5}};
  EXPECT_FALSE(intersect(c, gap));
  EXPECT_EQ(distance(c, gap).distance, 0x1p-52);
  // A flat disk (lz = 0) and subnormal lengths (the fuzz target's case
  // regress-subnormal-flat-witness): the double pass's pulled-back vertex
  // rounds into the disk's plane while the exact one is off it; its
  // a-priori error (6u S, S = 0 here: every product underflows) must not
  // make it an intersection witness.
  const Cylinder<double> disk{1, 0};
  Pose<double> p = identityPose<double>();
  p.R[0][0] = 0x0.03fep-1022;
  p.R[0][1] = 0x0.0003p-1022;
  p.R[0][2] = -0x1p-8;
  p.R[1][0] = -1;
  p.R[1][1] = 0x1.1fep+3;
  p.R[1][2] = 0x0.000000000004p-1022;
  p.R[2][0] = 0x0.000000000003fp-1022;
  p.R[2][1] = 0;
  p.R[2][2] = 0;
  p.t = {0, 0x0.000000000003fp-1022, 0x0.000000000002p-1022};
  const Triangle<double> tiny{
      {0x0.0002ep-1022, 0, 0x0.0004p-1022}, {0, 0, 0}, {0, 0, 0}};
  const bool meets = intersect(disk, p, tiny);
  DistanceResult<double> rt{};
  EXPECT_EQ(tryDistance(disk, p, tiny, &rt),
            meets ? Answer::kIntersect : Answer::kDisjoint);
  EXPECT_EQ(rt.distance == 0, meets);
}

TEST(TriangleCylinderDistance, InvalidInput) {
  test::NoFpTraps no_traps;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  const Pose<double> id = identityPose<double>();
  const Triangle<double> t{{3, 0, 0}, {4, 0, 0}, {4, 1, 0}};
  EXPECT_THROW(distance(Cylinder<double>{-1, 2}, t), InvalidInput);
  EXPECT_THROW(distance(Cylinder<double>{1, nan}, t), InvalidInput);
  Triangle<double> bad = t;
  bad.b.y = inf;
  EXPECT_THROW(distance(Cylinder<double>{1, 2}, id, bad), InvalidInput);
  Pose<double> p = id;
  p.R[1][2] = nan;
  DistanceResult<double> out{};
  out.distance = 42;
  EXPECT_EQ(tryDistance(Cylinder<double>{1, 2}, p, t, &out),
            Answer::kInvalidInput);
  EXPECT_EQ(out.distance, 42);
  EXPECT_EQ(tryDistance(Cylinder<double>{1, 2}, id, t,
                        static_cast<DistanceResult<double>*>(nullptr)),
            Answer::kDisjoint);
  EXPECT_THROW(distance(Cylinder<float>{1, -0.5f}, Triangle<float>{}),
               InvalidInput);
}

// Vertex order, exact rigid motions and power-of-two scaling.
TEST(TriangleCylinderDistance, Invariances) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  for (long i = 0; i < test::scaled(300); ++i) {
    const auto fam = scenes::kAllFamilies[i % 6];
    const scenes::TriCase k = scenes::generate(fam, seed, std::uint64_t(i));
    SCOPED_TRACE(std::string(scenes::familyName(fam)) + " #" +
                 std::to_string(i));
    const DistanceResult<double> r = distance(k.cyl, k.pose, k.tri);
    const V v[3] = {k.tri.a, k.tri.b, k.tri.c};
    static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                        {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    for (const auto& pm : kPerm) {
      const DistanceResult<double> q = distance(
          k.cyl, k.pose, Triangle<double>{v[pm[0]], v[pm[1]], v[pm[2]]});
      EXPECT_EQ(q.distance == 0, r.distance == 0);
      EXPECT_LE(std::abs(q.distance - r.distance),
                q.error_bound + r.error_bound);
    }
    const test::SignedPermutation m = test::SignedPermutation::nth(i % 48);
    const DistanceResult<double> q = distance(
        k.cyl, m(k.pose), Triangle<double>{m(k.tri.a), m(k.tri.b), m(k.tri.c)});
    EXPECT_EQ(q.distance, r.distance);
    for (int e : {-40, 7}) {
      const double s = std::ldexp(1.0, e);
      auto sc = [s](V x) { return V{x.x * s, x.y * s, x.z * s}; };
      Pose<double> p = k.pose;
      p.t = sc(p.t);
      const DistanceResult<double> w =
          distance(Cylinder<double>{k.cyl.radius * s, k.cyl.lz * s}, p,
                   Triangle<double>{sc(k.tri.a), sc(k.tri.b), sc(k.tri.c)});
      EXPECT_EQ(w.distance, r.distance * s);
    }
  }
}

// The run-time FMA dispatch returns the portable path's bits (both
// TwoProducts are exact; docs/distance.md, section 2).
TEST(TriangleCylinderDistance, FmaPathSameBitsAsPortable) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  for (const scenes::Family f : scenes::kAllFamilies)
    for (long i = 0; i < test::scaled(500); ++i) {
      SCOPED_TRACE(std::string(scenes::familyName(f)) + " #" +
                   std::to_string(i));
      const scenes::TriCase k = scenes::generate(f, seed, std::uint64_t(i));
      DistanceResult<double> a{}, b{};
      ASSERT_EQ(tryDistance(k.cyl, k.pose, k.tri, &a),
                diagnostic::tryDistancePortable(k.cyl, k.pose, k.tri, &b));
      EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0)
          << a.distance << " vs " << b.distance;
    }
}

// A case at a constructed separation: a boundary point q of the cylinder
// with an outward normal w (any direction of the normal cone at a rim
// point), p = q + gap w, and a triangle through p in the half-space
// w . (x - p) >= 0 touching the plane at a vertex, along an edge or with
// its face. The true distance is gap up to the rounding of the world
// coordinates (the oracle settles it).
scenes::TriCase separationCase(scenes::Rng& g, double rel_gap) {
  using scenes::internal::randomUnit;
  const double r = g.logUniform(0.1, 2), lz = g.logUniform(0.1, 4);
  const double h = lz / 2, size = std::max(r, h);
  const double th = g.uniform(0, 2 * M_PI);
  const double c = std::cos(th), s = std::sin(th);
  V q, w;
  const int where = g.integer(3);  // barrel, cap, rim
  const double sg = g.coin() ? 1 : -1;
  if (where == 0) {
    q = {r * c, r * s, g.uniform(-h, h)};
    w = {c, s, 0};
  } else if (where == 1) {
    const double rho = r * std::sqrt(g.uniform());
    q = {rho * c, rho * s, sg * h};
    w = {0, 0, sg};
  } else {
    q = {r * c, r * s, sg * h};
    const double a = g.uniform(0.05, 1.5);
    w = {std::cos(a) * c, std::cos(a) * s, sg * std::sin(a)};
  }
  const double gap = rel_gap * size;
  const V p{q.x + gap * w.x, q.y + gap * w.y, q.z + gap * w.z};
  // Two tangent directions orthogonal to w.
  V t1 = randomUnit(g);
  const double k1 = t1.x * w.x + t1.y * w.y + t1.z * w.z;
  t1 = {t1.x - k1 * w.x, t1.y - k1 * w.y, t1.z - k1 * w.z};
  const double n1 = std::sqrt(t1.x * t1.x + t1.y * t1.y + t1.z * t1.z);
  t1 = {t1.x / n1, t1.y / n1, t1.z / n1};
  const V t2{w.y * t1.z - w.z * t1.y, w.z * t1.x - w.x * t1.z,
             w.x * t1.y - w.y * t1.x};
  const double L = size * g.logUniform(0.2, 5);
  auto at = [&](double a, double b, double up) {
    return V{p.x + L * (a * t1.x + b * t2.x + up * w.x),
             p.y + L * (a * t1.y + b * t2.y + up * w.y),
             p.z + L * (a * t1.z + b * t2.z + up * w.z)};
  };
  V A, B, C;
  switch (g.integer(3)) {
    case 0:  // vertex
      A = p;
      B = at(g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(0.2, 1));
      C = at(g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(0.2, 1));
      break;
    case 1: {  // edge through p
      const double e = g.uniform(0.1, 1);
      A = at(e, 0, 0);
      B = at(-g.uniform(0.1, 1), 0, 0);
      C = at(g.uniform(-1, 1), g.uniform(0.2, 1), g.uniform(0.2, 1));
      break;
    }
    default:  // face around p
      A = at(1, -0.5, 0);
      B = at(-1, -0.6, 0);
      C = at(0.1, 1, 0);
      break;
  }
  const Pose<double> pose = g.coin() ? scenes::internal::exactPose(g)
                                     : scenes::internal::randomPose(g, 2);
  return scenes::internal::posed({r, lz}, pose, A, B, C);
}

struct Tally {
  long n = 0, zero = 0, wrong_zero = 0, over8 = 0, bound_violated = 0,
       untight = 0, escalate_bound = 0;
  long bound_over8 = 0;  // error_bound wider than 8 ulps (informational)
  long tight_over8 = 0;  // ... still, after tightenDistance
  long tightened = 0;    // results tightenDistance replaced
  long tiny = 0;         // distances below 1e-15 of the problem's size
  double tiny_max_ulps = 0;
  double max_ulps = 0, max_pt = 0;
  void print(const char* name) const {
    std::printf(
        "[ stats ] %-10s %5ld cases (%ld zero): max error %.3g ulps, >8 "
        "ulps %ld, bound violated %ld, sign disagreements %ld, oracle "
        "not tight %ld, point off its set <= %.3g ulps of the "
        "coordinates/size, "
        "error_bound > 8 ulps on %ld (after tightenDistance: %ld, %ld "
        "tightened); below 1e-15 of the size: %ld cases, max error %.3g "
        "ulps\n",
        name, n, zero, max_ulps, over8, bound_violated, wrong_zero, untight,
        max_pt, bound_over8, tight_over8, tightened, tiny, tiny_max_ulps);
  }
};

void judge(const scenes::TriCase& k, Tally* t) {
  const DistanceResult<double> r = distance(k.cyl, k.pose, k.tri);
  const oracle::DistanceEnclosure e =
      oracle::distanceEnclosure(k.cyl, k.pose, k.tri);
  ++t->n;
  if (!e.tight) {
    ++t->untight;
    ADD_FAILURE() << "oracle not tight, rel. width " << e.rel_width;
    return;
  }
  if (e.intersect) ++t->zero;
  if (e.intersect != (r.distance == 0)) {
    ++t->wrong_zero;
    ADD_FAILURE() << "zero disagreement: distance " << r.distance
                  << " oracle intersect " << e.intersect;
    return;
  }
  const double ulps = oracle::ulpsError(e, r.distance);
  // The issue's range: separations from 1e-15 of the size up. Below it
  // (ulp-level pushes of the near family, world rounding) the double-word
  // refinement's resolution, about 2^-100 of the size, is reported, not
  // asserted (docs/distance.md, section 6).
  double size = std::max(k.cyl.radius, k.cyl.lz / 2);
  for (const V& x : {k.tri.a, k.tri.b, k.tri.c})
    size = std::max({size, std::abs(x.x - k.pose.t.x),
                     std::abs(x.y - k.pose.t.y), std::abs(x.z - k.pose.t.z)});
  if (!e.intersect && r.distance < 1e-15 * size) {
    ++t->tiny;
    t->tiny_max_ulps = std::max(t->tiny_max_ulps, ulps);
  } else {
    t->max_ulps = std::max(t->max_ulps, ulps);
  }
  if (ulps > 8 && !(r.distance < 1e-15 * size)) {
    ++t->over8;
    ADD_FAILURE() << "error " << ulps << " ulps: distance " << r.distance
                  << " oracle " << e.mid_hi;
  }
  if (!e.intersect && r.error_bound > 8 * ulpOf(r.distance)) ++t->bound_over8;
  // tightenDistance: certified on its own (checked like r's bound below).
  DistanceResult<double> q = r;
  if (tightenDistance(k.cyl, k.pose, k.tri, &q)) {
    ++t->tightened;
    if (q.distance - q.error_bound > e.hi ||
        q.distance + q.error_bound < e.lo) {
      ++t->bound_violated;
      ADD_FAILURE() << "tightened error_bound " << q.error_bound
                    << " violated: distance " << q.distance << " oracle ["
                    << e.lo << ", " << e.hi << "]";
    }
    if (oracle::ulpsError(e, q.distance) > 8) {
      ++t->over8;
      ADD_FAILURE() << "tightened distance " << q.distance << " off by "
                    << oracle::ulpsError(e, q.distance) << " ulps";
    }
  }
  if (!e.intersect && q.error_bound > 8 * ulpOf(q.distance)) ++t->tight_over8;
  if (r.distance - r.error_bound > e.hi || r.distance + r.error_bound < e.lo) {
    ++t->bound_violated;
    ADD_FAILURE() << "error_bound " << r.error_bound << " violated: distance "
                  << r.distance << " oracle [" << e.lo << ", " << e.hi << "]";
  }
  // Points: on their sets within a few ulps of the world coordinates (the
  // map x = R y + t rounds; R is orthonormal only to rounding).
  auto mag = [](const V& x) {
    return std::max({std::abs(x.x), std::abs(x.y), std::abs(x.z)});
  };
  // Scale: the world coordinates and the problem's size (a witness point
  // of an intersecting pair is placed to a few ulps of the size).
  const double sc = std::max({mag(r.point_on_cylinder),
                              mag(r.point_on_triangle), mag(k.pose.t), size,
                              double(std::numeric_limits<double>::min())});
  const double pc =
      oracle::pointCylinderDistance(k.cyl, k.pose, r.point_on_cylinder);
  const double pt = oracle::pointTriangleDistance(k.tri, r.point_on_triangle);
  const double off = std::max(pc, pt) / (kUlp * sc);
  t->max_pt = std::max(t->max_pt, off);
  EXPECT_LE(off, 16) << "nearest point off its set: cylinder " << pc
                     << " triangle " << pt;
}

TEST(TriangleCylinderDistance, FamiliesAgainstOracle) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  for (const scenes::Family f : scenes::kAllFamilies) {
    Tally t;
    for (long i = 0; i < test::scaled(3000); ++i) {
      SCOPED_TRACE(std::string(scenes::familyName(f)) + " #" +
                   std::to_string(i));
      judge(scenes::generate(f, seed, std::uint64_t(i)), &t);
    }
    t.print(scenes::familyName(f));
    EXPECT_EQ(t.wrong_zero, 0);
    EXPECT_EQ(t.over8, 0);
  }
}

TEST(TriangleCylinderDistance, SeparationsAgainstOracle) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  for (int decade = -15; decade <= 3; ++decade) {
    Tally t;
    scenes::Rng g(seed ^ (std::uint64_t(decade + 100) << 40));
    for (long i = 0; i < test::scaled(300); ++i) {
      SCOPED_TRACE("separation 1e" + std::to_string(decade) + " #" +
                   std::to_string(i));
      const double rel = std::pow(10.0, decade) * g.uniform(1, 10);
      judge(separationCase(g, rel), &t);
    }
    char name[32];
    std::snprintf(name, sizeof name, "sep 1e%d", decade);
    t.print(name);
  }
}

// Separations from 1e-16 down to about 1e-33 of the problem's size, built
// exactly (every coordinate a double, poses signed permutations, so the
// world inputs are the local ones and the oracle's distance is the
// constructed one), one kind per nearest feature:
//   vertex-barrel: v = (3 + 4 delta, 4 - 3 delta, z) beside the barrel of
//     radius 5 (a Pythagorean point moved along the tangent: distance
//     sqrt(25 + 25 delta^2) - 5, about 2.5 delta^2, delta = 2^-26 .. 2^-50);
//   vertex-cap: a vertex 2^-52 k above the cap, the other two 2^m away;
//   edge-barrel: an edge on the line x = 5 + 2^-50, 2^m long, beside the
//     barrel of radius 5;
//   edge-cap: an edge 2^-52 above the cap, 2^m long, crossing over it;
//   face-barrel: a face in the plane x = 5 + 2^-50, 2^m wide.
// Reported per kind and decade of distance / size: the error in ulps, and
// error_bound in ulps of the distance (docs/distance.md, section 6). The
// bound is certified at every separation (0 violations, asserted), and,
// each kind being one of those tightenDistance re-evaluates exactly, after
// it the distance and its bound are within 8 ulps (asserted: tryDistance's
// double-word bound alone is up to 1e17 ulps wide).
struct TinyKindTally {
  long n = 0, over8 = 0, bound_over8 = 0, violated = 0, wrong_zero = 0;
  double max_ulps = 0, max_bound_ulps = 0;
  double max_bound_ulps_before = 0;  // tryDistance's own, before tightening
};

scenes::TriCase tinyCase(scenes::Rng& g, int kind, double* size) {
  const int m = g.integer(51);  // the big lengths: 2^m
  const double big = std::ldexp(1.0, m);
  V a, b, c;
  Cylinder<double> cyl{5, 4};
  switch (kind) {
    case 0: {  // vertex-barrel
      const double delta = std::ldexp(1.0, -26 - g.integer(25));
      const double z = 0.25 * (g.integer(13) - 6);
      a = {3 + 4 * delta, 4 - 3 * delta, z};
      b = {a.x + 8, a.y - 6, z};
      c = {a.x + 3, a.y + 4, z + 1};
      *size = 12;
      break;
    }
    case 1: {  // vertex-cap, the cap z = 2
      const double k = double(1 + g.integer(8));
      a = {0.25 * (g.integer(9) - 4), 0.25 * (g.integer(9) - 4),
           2 + std::ldexp(k, -51)};
      b = {a.x + big, a.y, a.z + big};
      c = {a.x, a.y + big, a.z + big};
      *size = 2 * big;
      break;
    }
    case 2: {  // edge-barrel
      const double x = 5 + std::ldexp(1.0, -50 + g.integer(3));
      a = {x, -big, 0.5};
      b = {x, big, -0.5};
      c = {x + big, 0.25 * (g.integer(9) - 4), 0};
      *size = 2 * big;
      break;
    }
    case 3: {  // edge-cap
      const double z = 2 + std::ldexp(1.0, -51 + g.integer(3));
      a = {-big, 0.25 * (g.integer(9) - 4), z};
      b = {big, 0.25 * (g.integer(9) - 4), z};
      c = {0.25 * (g.integer(9) - 4), 0, z + big};
      *size = 2 * big;
      break;
    }
    default: {  // face-barrel
      const double x = 5 + std::ldexp(1.0, -50 + g.integer(3));
      a = {x, -big, -big};
      b = {x, big, -big};
      c = {x, 0.25 * (g.integer(9) - 4), big};
      *size = 2 * big;
      break;
    }
  }
  Pose<double> pose = scenes::internal::exactPose(g);
  pose.t = {0, 0, 0};
  return scenes::internal::posed(cyl, pose, a, b, c);
}

TEST(TriangleCylinderDistance, TinySeparationsAgainstOracle) {
  const std::uint64_t seed = test::baseSeed() ^ 0x74696e79u;
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed);
  static const char* const kKinds[] = {
      "vertex-barrel", "vertex-cap", "edge-barrel", "edge-cap", "face-barrel"};
  constexpr int kDecades = 36;
  TinyKindTally tally[5][kDecades];
  for (long i = 0; i < test::scaled(2500); ++i) {
    const int kind = int(i % 5);
    double size = 0;
    const scenes::TriCase k = tinyCase(g, kind, &size);
    SCOPED_TRACE(std::string(kKinds[kind]) + " #" + std::to_string(i));
    DistanceResult<double> r = distance(k.cyl, k.pose, k.tri);
    const DistanceResult<double> before = r;
    const bool tightened = tightenDistance(k.cyl, k.pose, k.tri, &r);
    const oracle::DistanceEnclosure e =
        oracle::distanceEnclosure(k.cyl, k.pose, k.tri);
    ASSERT_TRUE(e.tight) << e.rel_width;
    // tryDistance's own bound holds too (it is wide: reported).
    EXPECT_FALSE(before.distance - before.error_bound > e.hi ||
                 before.distance + before.error_bound < e.lo);
    EXPECT_EQ(tightened, r.error_bound < before.error_bound);
    ASSERT_FALSE(e.intersect);
    const int decade =
        std::min(kDecades - 1, int(std::floor(-std::log10(e.hi / size))));
    TinyKindTally& t = tally[kind][std::max(0, decade)];
    ++t.n;
    if (r.distance == 0) {
      ++t.wrong_zero;
      ADD_FAILURE() << "distance 0 for a disjoint pair";
      continue;
    }
    t.max_bound_ulps_before = std::max(
        t.max_bound_ulps_before, before.error_bound / ulpOf(before.distance));
    const double ulps = oracle::ulpsError(e, r.distance);
    const double bound_ulps = r.error_bound / ulpOf(r.distance);
    t.max_ulps = std::max(t.max_ulps, ulps);
    t.max_bound_ulps = std::max(t.max_bound_ulps, bound_ulps);
    if (ulps > 8) ++t.over8;
    if (bound_ulps > 8) ++t.bound_over8;
    if (r.distance - r.error_bound > e.hi ||
        r.distance + r.error_bound < e.lo) {
      ++t.violated;
      ADD_FAILURE() << "error_bound " << r.error_bound << " violated: distance "
                    << r.distance << " oracle [" << e.lo << ", " << e.hi << "]";
    }
  }
  for (int kind = 0; kind < 5; ++kind)
    for (int d = 0; d < kDecades; ++d) {
      const TinyKindTally& t = tally[kind][d];
      if (t.n == 0) continue;
      std::printf(
          "[ tiny  ] %-13s 1e-%02d..: %4ld cases, tightened: max error "
          "%8.3g ulps (>8: %3ld), error_bound max %9.3g ulps (>8: %3ld), "
          "violated %ld; tryDistance's error_bound max %9.3g ulps\n",
          kKinds[kind], d + 1, t.n, t.max_ulps, t.over8, t.max_bound_ulps,
          t.bound_over8, t.violated, t.max_bound_ulps_before);
      EXPECT_EQ(t.violated, 0);
      EXPECT_EQ(t.wrong_zero, 0);
      // Every kind is one that tightenDistance certifies exactly: within
      // 8 ulps, and so is the bound.
      EXPECT_EQ(t.over8, 0) << kKinds[kind];
      EXPECT_EQ(t.bound_over8, 0) << kKinds[kind];
    }
}

}  // namespace
}  // namespace tricyl
