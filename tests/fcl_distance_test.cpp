// SPDX-License-Identifier: BSD-3-Clause
// Distance and margins through FCL (fcl_solver.h, DISTANCE and MARGIN
// COLLIDE): tricyl::distance (the wrapper, its own traversal) and
// fcl::distance with tricyl::Solver, on every BV type and in both argument
// orders, against brute force over the triangles with tricyl::distance per
// triangle; the signed distance; the margin collide against brute force
// with tricyl::withinDistance per triangle; TriangleP; float. Meshes: env,
// bunny, rob (../shared/data/meshes, skipped with a message when absent)
// and a built-in sphere, so the suite never runs empty.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "fcl/mesh_traversal.h"
#include "fcl_test_support.h"
#include "test_support.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"
#include "tricyl/triangle_cylinder_margin.h"

namespace tricyl {
namespace {

using fcltest::Mesh;
using fcltest::Scene;
using fcltest::Tf;
using fcltest::V3;

template <class BV>
constexpr bool kAlignedBv = std::is_same_v<BV, fcl::AABB<double>> ||
                            std::is_same_v<BV, fcl::KDOP<double, 16>> ||
                            std::is_same_v<BV, fcl::KDOP<double, 18>> ||
                            std::is_same_v<BV, fcl::KDOP<double, 24>>;

/// The meshes: the three shared ones that exist, and a built-in sphere.
std::vector<Mesh> meshes() {
  std::vector<Mesh> out;
  for (const char* f : {"env.obj", "bunny.obj", "rob.obj"}) {
    Mesh m;
    m.name = f;
    if (fcltest::readObj(fcltest::meshPath(f), &m)) {
      out.push_back(std::move(m));
    } else {
      std::printf("[ note ] %s not found under %s: skipped\n", f,
                  TRICYL_MESH_DIR);
    }
  }
  Mesh s = fcltest::sphereMesh(12);
  s.name = "builtin sphere";
  out.push_back(std::move(s));
  return out;
}

/// The world triangle the Solver sees for triangle i (fcl_solver.h, FRAMES).
template <class BV>
Triangle<double> worldTri(const Mesh& m, const Tf& mesh_tf, std::size_t i) {
  const bool raw = kAlignedBv<BV> && mesh_tf.matrix().isIdentity();
  V3 p[3];
  for (int j = 0; j < 3; ++j)
    p[j] = raw ? m.v[m.t[i][j]] : V3(mesh_tf * m.v[m.t[i][j]]);
  return fcltest::toTri(p[0], p[1], p[2]);
}

/// Brute force over the triangles: the smallest tricyl::distance, the first
/// triangle reaching it, and whether any triangle meets the cylinder.
struct Brute {
  double min = std::numeric_limits<double>::max();
  std::size_t arg = 0;
  bool collides = false;
  std::set<std::size_t> colliding;
  // Per triangle: the distance and its error_bound (+Inf and 0 for a
  // colliding one); U = min (d + e), an upper bound of the true minimum.
  std::vector<double> d, e;
  double upper = std::numeric_limits<double>::infinity();
};

template <class BV>
Brute bruteForce(const Mesh& m, const Scene& s) {
  Brute b;
  const Cylinder<double> cyl{s.r, s.lz};
  const Pose<double> pose = toPose(s.cyl_tf);
  for (std::size_t i = 0; i < m.t.size(); ++i) {
    DistanceResult<double> d;
    const Answer a = tryDistance(cyl, pose, worldTri<BV>(m, s.mesh_tf, i), &d);
    if (a != Answer::kDisjoint) {
      b.collides = true;
      b.colliding.insert(i);
      b.d.push_back(std::numeric_limits<double>::infinity());
      b.e.push_back(0);
      continue;
    }
    b.d.push_back(d.distance);
    b.e.push_back(d.error_bound);
    b.upper = std::min(b.upper, d.distance + d.error_bound);
    if (d.distance < b.min) {
      b.min = d.distance;
      b.arg = i;
    }
  }
  return b;
}

/// The diagonal of the mesh's bounding box.
double diagonal(const Mesh& m) {
  V3 lo = m.v[0], hi = m.v[0];
  for (const V3& p : m.v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  return (hi - lo).norm();
}

/// Seeded scenes: fcltest::makeScenes' (grazing and random, many touching),
/// and the same moved apart by 10^-12 .. 1 of the mesh's diagonal (disjoint).
std::vector<Scene> scenes(const Mesh& m, std::uint64_t seed, int per_kind) {
  std::vector<Scene> base = fcltest::makeScenes(m, seed, per_kind);
  std::mt19937_64 rng(seed ^ 0x61706172u);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> g;
  const double diag = diagonal(m);
  std::vector<Scene> out = base;
  for (std::size_t k = 0; k < base.size(); ++k) {
    Scene s = base[k];
    const V3 dir = V3(g(rng), g(rng), g(rng)).normalized();
    s.cyl_tf.translation() += dir * diag * std::pow(10.0, -12 * u01(rng));
    s.kind = "apart";
    out.push_back(s);
  }
  for (std::size_t k = 0; k < out.size(); k += 2)
    out[k].mesh_tf = Tf::Identity();  // the raw-vertex paths
  return out;
}

V3 fclPoint(const Vec3<double>& p) { return V3(p.x, p.y, p.z); }

template <class BV>
struct BvTag {
  using type = BV;
};

/// A length of the scene (for absolute tolerances on FCL's own traversal).
double sceneScale(const Mesh& m, const Scene& s) {
  double a = s.r + s.lz + s.cyl_tf.translation().cwiseAbs().maxCoeff() +
             s.mesh_tf.translation().cwiseAbs().maxCoeff();
  for (const V3& p : m.v) a = std::max(a, p.cwiseAbs().maxCoeff());
  return a;
}

template <class BV>
class FclDistanceTest : public ::testing::Test {};
TYPED_TEST_SUITE(FclDistanceTest, fcltest::AllBvs);

// The wrapper (own traversal) gives exactly the brute-force minimum, the
// triangle reaching it and its nearest points, in both argument orders, and
// prunes; fcl::distance with tricyl::Solver gives the same minimum (FCL's
// own traversals for RSS/kIOS/OBBRSS round their BV distances: within
// 1e-12 relative there) and the points of the triangle it reports; both
// are <= 0 exactly when brute force finds a colliding triangle.
TYPED_TEST(FclDistanceTest, MinimumAndNearestPointsEqualBruteForce) {
  using BV = TypeParam;
  const std::uint64_t seed = test::baseSeed() ^ 0x64697374u;
  SCOPED_TRACE(test::seedTrace(seed));
  const Solver<double> solver;
  long checked = 0, apart = 0;
  TraversalStats stats;
  for (const Mesh& m : meshes()) {
    SCOPED_TRACE(m.name);
    auto model = fcltest::makeModel<BV>(m);
    for (const Scene& s : scenes(m, seed, 2)) {
      SCOPED_TRACE(fcltest::describe(s));
      const Brute b = bruteForce<BV>(m, s);
      auto cyl = std::make_shared<fcl::Cylinderd>(s.r, s.lz);
      const fcl::CollisionObjectd mesh_obj(model, s.mesh_tf);
      const fcl::CollisionObjectd cyl_obj(cyl, s.cyl_tf);
      for (int order = 0; order < 2; ++order) {
        const fcl::CollisionObjectd* o1 = order ? &cyl_obj : &mesh_obj;
        const fcl::CollisionObjectd* o2 = order ? &mesh_obj : &cyl_obj;
        fcl::DistanceRequestd req(true);
        fcl::DistanceResultd w;
        const double ret = tricyl::distance(o1, o2, req, w);
        EXPECT_EQ(ret, w.min_distance);
        fcl::DistanceResultd f;
        fcl::distance(o1, o2, &solver, req, f);
        ++checked;
        if (b.collides) {
          EXPECT_LT(w.min_distance, 0);
          // FCL's RSS/kIOS/OBBRSS traversals prune with rounded BV
          // distances: a grazing triangle may be missed by rounding.
          EXPECT_LE(f.min_distance, 1e-12 * sceneScale(m, s));
          EXPECT_TRUE(b.colliding.count(std::size_t(w.b1))) << w.b1;
          EXPECT_EQ(w.nearest_points[0], w.nearest_points[1]);
          continue;
        }
        ++apart;
        ASSERT_EQ(w.min_distance, b.min) << "order " << order;
        ASSERT_GE(w.b1, 0);
        const Cylinder<double> c{s.r, s.lz};
        const Pose<double> pose = toPose(s.cyl_tf);
        const DistanceResult<double> at =
            tricyl::distance(c, pose, worldTri<BV>(m, s.mesh_tf, w.b1));
        EXPECT_EQ(at.distance, b.min);
        EXPECT_EQ(w.nearest_points[0], fclPoint(at.point_on_triangle));
        EXPECT_EQ(w.nearest_points[1], fclPoint(at.point_on_cylinder));
        // fcl::distance with the Solver.
        EXPECT_NEAR(f.min_distance, b.min,
                    1e-12 * b.min + 1e-14 * sceneScale(m, s));
        ASSERT_GE(f.b1, 0);
        const DistanceResult<double> atf =
            tricyl::distance(c, pose, worldTri<BV>(m, s.mesh_tf, f.b1));
        EXPECT_EQ(atf.distance, f.min_distance);
        EXPECT_EQ(f.nearest_points[0], fclPoint(atf.point_on_triangle));
        EXPECT_EQ(f.nearest_points[1], fclPoint(atf.point_on_cylinder));
      }
      fcl::DistanceResultd w;
      distanceMeshCylinder(model.get(), s.mesh_tf, cyl.get(), s.cyl_tf,
                           fcl::DistanceRequestd(), w, &stats);
    }
  }
  EXPECT_GT(apart, checked / 4);
  // The node bound prunes: far fewer triangles measured than exist.
  EXPECT_GT(stats.nodes_skipped, 0u);
  std::printf(
      "[ info ] %ld queries (%ld apart); traversal: %zu bounds, %zu "
      "pruned, %zu triangles measured\n",
      checked, apart, stats.nodes_tested, stats.nodes_skipped, stats.leaves);
}

// Scenes of 1e154 and up (mesh_traversal.h, SCALE): both walks equal brute
// force, under the FP traps (FE_INVALID, FE_DIVBYZERO). Before the scale
// fall-back, a node 1.4e154 or more from the cylinder's axis line got the
// bound +Inf (its squared distance to the line overflowed): "spread" and
// one of the two "far" scenes then reported a triangle that was not the
// nearest (the other one was pruned); near 1e308 the node margin or b - c
// overflowed and the bound computed Inf - Inf or 0 * Inf ("near max",
// "model at 3e307": FE_INVALID, a trap). FCL fits the oriented boxes of
// the "spread" and "3e307" models with a covariance that overflows: those
// models go to FCL's own traversal (the walks decline them), and are
// checked here only for the aligned types.
TYPED_TEST(FclDistanceTest, HugeCoordinates) {
  using BV = TypeParam;
  struct Case {
    const char* what;
    Mesh m;
    Scene s;
    bool fit_overflows;  // FCL's oriented fit overflows: aligned types only
  };
  std::vector<Case> cases;
  const Scene at_origin{1.0, 2.0, Tf::Identity(), Tf::Identity(), "huge"};
  {
    Case c{"spread", {}, at_origin, true};
    c.m.v = {V3(0, 0, 1.4e154),  V3(1, 0, 1.4e154),  V3(0, 1, 1.4e154),
             V3(1.35e154, 0, 0), V3(1.35e154, 1, 0), V3(1.35e154, 0, 1)};
    c.m.t = {fcl::Triangle(0, 1, 2), fcl::Triangle(3, 4, 5)};
    cases.push_back(c);
  }
  for (const double delta : {1e141, -1e141}) {
    Case c{"far", {}, at_origin, false};
    c.m.v = {V3(0, 0, 0),     V3(0, 1, 0),     V3(0, 0, 1),
             V3(delta, 5, 0), V3(delta, 6, 0), V3(delta, 5, 1)};
    c.m.t = {fcl::Triangle(0, 1, 2), fcl::Triangle(3, 4, 5)};
    c.s.mesh_tf.translation() = V3(1.5e154, 0, 0);
    cases.push_back(c);
  }
  {
    std::mt19937_64 rng(7);
    Case c{"near max", fcltest::sphereMesh(8), at_origin, false};
    for (V3& v : c.m.v) v *= 1e100;
    c.s.mesh_tf.linear() = fcltest::randomRotation(rng);
    c.s.mesh_tf.translation() = V3(1e308, 0, 0);
    c.s.cyl_tf.translation() = V3(-5e307, 0, 0);
    c.s.r = 1e307;
    c.s.lz = 1e307;
    cases.push_back(c);
  }
  {
    const double sc = 3e307;
    Case c{"model at 3e307", fcltest::sphereMesh(6), at_origin, true};
    for (V3& v : c.m.v) v *= sc;
    c.s.cyl_tf.translation() = V3(-1.7e308, 0.2 * sc, 0);
    c.s.r = 0.3 * sc;
    c.s.lz = 0.5 * sc;
    cases.push_back(c);
  }
  // A touching pose at 1e300: the collide walk's contacts.
  {
    Case c{"touching at 1e300", fcltest::sphereMesh(6), at_origin, true};
    for (V3& v : c.m.v) v *= 1e300;
    c.s.cyl_tf.translation() = V3(1e300, 0, 0);
    c.s.r = 0.25e300;
    c.s.lz = 1e300;
    cases.push_back(c);
  }
  long touching = 0;
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    if (c.fit_overflows && !kAlignedBv<BV>) continue;
    std::shared_ptr<fcl::BVHModel<BV>> model;
    {
      test::NoFpTraps no_traps;  // FCL's fit (squares of the coordinates)
      model = fcltest::makeModel<BV>(c.m);
    }
    const Brute b = bruteForce<BV>(c.m, c.s);
    auto cyl = std::make_shared<fcl::Cylinderd>(c.s.r, c.s.lz);
    fcl::DistanceResultd w;
    ASSERT_TRUE(distanceMeshCylinder(model.get(), c.s.mesh_tf, cyl.get(),
                                     c.s.cyl_tf, fcl::DistanceRequestd(true), w,
                                     nullptr));
    if (b.collides) {
      ++touching;
      EXPECT_LE(w.min_distance, 0);
      EXPECT_TRUE(b.colliding.count(std::size_t(w.b1))) << w.b1;
    } else {
      ASSERT_TRUE(std::isfinite(b.min));
      EXPECT_EQ(w.min_distance, b.min);
      EXPECT_EQ(std::size_t(w.b1), b.arg);
    }
    fcl::CollisionResultd res;
    std::size_t n = 0;
    ASSERT_TRUE(
        collideMeshCylinder(model.get(), c.s.mesh_tf, cyl.get(), c.s.cyl_tf,
                            fcl::CollisionRequestd(1000, false), res, &n));
    EXPECT_EQ(fcltest::contactIds(res, cyl.get()), b.colliding);
  }
  if (kAlignedBv<BV>) {
    EXPECT_EQ(touching, 1);  // "touching at 1e300"
  }
}

// Exact ties over a large region: a cylinder standing above an integer
// grid, its cap parallel to it at height 1/4, so every triangle under the
// cap is exactly 1/4 away and none can be pruned. The walk's queue then
// holds far more entries than it keeps in place (mesh_distance.cpp,
// EntryQueue: 256) and moves them to the heap and back; the answer is the
// brute-force minimum, with a triangle reaching it and its points.
TYPED_TEST(FclDistanceTest, ManyTiesOverflowTheQueue) {
  using BV = TypeParam;
  const Mesh m = fcltest::flatGridMesh(48, 0, 1);  // 4608 triangles
  auto model = fcltest::makeModel<BV>(m);
  Scene s;
  s.r = 20;
  s.lz = 2;
  s.kind = "ties";
  s.cyl_tf = Tf::Identity();
  s.cyl_tf.translation() = V3(24.5, 23.5, 1.25);  // cap at z = 1/4
  s.mesh_tf = Tf::Identity();
  const Brute b = bruteForce<BV>(m, s);
  ASSERT_FALSE(b.collides);
  ASSERT_EQ(b.min, 0.25);
  auto cyl = std::make_shared<fcl::Cylinderd>(s.r, s.lz);
  fcl::DistanceResultd w;
  TraversalStats stats;
  ASSERT_TRUE(distanceMeshCylinder(model.get(), s.mesh_tf, cyl.get(), s.cyl_tf,
                                   fcl::DistanceRequestd(true), w, &stats));
  EXPECT_EQ(w.min_distance, 0.25);
  ASSERT_GE(w.b1, 0);
  const DistanceResult<double> at =
      tricyl::distance(Cylinder<double>{s.r, s.lz}, toPose(s.cyl_tf),
                       worldTri<BV>(m, s.mesh_tf, std::size_t(w.b1)));
  EXPECT_EQ(at.distance, 0.25);
  EXPECT_EQ(w.nearest_points[0], fclPoint(at.point_on_triangle));
  EXPECT_EQ(w.nearest_points[1], fclPoint(at.point_on_cylinder));
  // Every triangle under the cap was measured: more than the queue's
  // in-place entries were open at once.
  EXPECT_GT(stats.leaves, 2000u);
}

// enable_signed_distance: minus the depth of the contact tricyl::collide
// reports (FCL's signed step, with the same contact), and both points at it.
TYPED_TEST(FclDistanceTest, SignedDistanceIsMinusTheContactDepth) {
  using BV = TypeParam;
  const std::uint64_t seed = test::baseSeed() ^ 0x7369676eu;
  SCOPED_TRACE(test::seedTrace(seed));
  const Solver<double> solver;
  long colliding = 0;
  for (const Mesh& m : meshes()) {
    SCOPED_TRACE(m.name);
    auto model = fcltest::makeModel<BV>(m);
    for (const Scene& s : fcltest::makeScenes(m, seed, 3)) {
      SCOPED_TRACE(fcltest::describe(s));
      auto cyl = std::make_shared<fcl::Cylinderd>(s.r, s.lz);
      const fcl::CollisionObjectd mesh_obj(model, s.mesh_tf);
      const fcl::CollisionObjectd cyl_obj(cyl, s.cyl_tf);
      fcl::CollisionRequestd creq;
      creq.enable_contact = true;
      fcl::CollisionResultd cres;
      tricyl::collide(&mesh_obj, &cyl_obj, creq, cres);
      fcl::DistanceRequestd req(true, true);
      fcl::DistanceResultd w, f;
      tricyl::distance(&cyl_obj, &mesh_obj, req, w);
      fcl::distance(&mesh_obj, &cyl_obj, &solver, req, f);
      if (!cres.isCollision()) {
        EXPECT_GT(w.min_distance, 0);
        EXPECT_GT(f.min_distance, 0);
        continue;
      }
      ++colliding;
      const fcl::Contactd& c = cres.getContact(0);
      EXPECT_GT(c.penetration_depth, 0);
      EXPECT_EQ(w.min_distance, -c.penetration_depth);
      EXPECT_EQ(w.nearest_points[0], c.pos);
      EXPECT_EQ(w.nearest_points[1], c.pos);
      // FCL's own step: minus the depth of the first contact of
      // fcl::collide with the Solver (for AABB/KDOP with a moved mesh,
      // possibly another colliding triangle's).
      EXPECT_LT(f.min_distance, 0);
      EXPECT_EQ(f.nearest_points[0], f.nearest_points[1]);
    }
  }
  EXPECT_GT(colliding, 0);
}

// The margin collide: exactly the triangles tricyl::withinDistance accepts
// (margins 0 .. 10 % of the cylinder's size, and 1, 4, 2^20 ulps either side
// of a triangle's distance), in both argument orders; margin 0 is
// tricyl::collide; contact data: depth > 0 for a triangle that meets the
// cylinder, in [-margin, 0) for one only within the margin.
TYPED_TEST(FclDistanceTest, MarginCollideEqualsBruteForceWithinDistance) {
  using BV = TypeParam;
  const std::uint64_t seed = test::baseSeed() ^ 0x6d61726727u;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  long with_margin_only = 0;
  for (const Mesh& m : meshes()) {
    SCOPED_TRACE(m.name);
    auto model = fcltest::makeModel<BV>(m);
    for (const Scene& s : scenes(m, seed, 1)) {
      SCOPED_TRACE(fcltest::describe(s));
      const Cylinder<double> c{s.r, s.lz};
      const Pose<double> pose = toPose(s.cyl_tf);
      const double size = std::max(s.r, s.lz);
      std::vector<double> margins = {0, 0.001 * size, 0.01 * size,
                                     0.1 * size * u01(rng)};
      // Ties: margins at a triangle's distance, 1, 4, 2^20 ulps either side.
      const Brute b = bruteForce<BV>(m, s);
      if (!b.collides && b.min < size) {
        for (double k : {1.0, 4.0, 1048576.0}) {
          const double ulp = std::nextafter(b.min, 2 * b.min + 1) - b.min;
          margins.push_back(b.min - k * ulp);
          margins.push_back(b.min + k * ulp);
        }
        margins.push_back(b.min);
      }
      auto cyl = std::make_shared<fcl::Cylinderd>(s.r, s.lz);
      const fcl::CollisionObjectd mesh_obj(model, s.mesh_tf);
      const fcl::CollisionObjectd cyl_obj(cyl, s.cyl_tf);
      for (double margin : margins) {
        if (!(margin >= 0)) continue;
        std::set<std::size_t> expect;
        for (std::size_t i = 0; i < m.t.size(); ++i)
          if (tryWithinDistance(c, pose, worldTri<BV>(m, s.mesh_tf, i),
                                margin) != Answer::kDisjoint)
            expect.insert(i);
        for (int order = 0; order < 2; ++order) {
          fcl::CollisionRequestd req(std::numeric_limits<int>::max(),
                                     order == 1);
          fcl::CollisionResultd res;
          tricyl::collide(order ? &cyl_obj : &mesh_obj,
                          order ? &mesh_obj : &cyl_obj, req, res,
                          CollideOptions<double>{margin});
          std::set<std::size_t> got;
          for (std::size_t i = 0; i < res.numContacts(); ++i) {
            const fcl::Contactd& ct = res.getContact(i);
            got.insert(std::size_t(ct.b1));
            if (!req.enable_contact) continue;
            const Answer a =
                tryIntersect(c, pose, worldTri<BV>(m, s.mesh_tf, ct.b1));
            if (a == Answer::kIntersect) {
              EXPECT_GT(ct.penetration_depth, 0);
            } else {
              ++with_margin_only;
              EXPECT_LT(ct.penetration_depth, 0);
              // -distance, the computed distance within its error bound of
              // the true one, which withinDistance (exact) puts <= margin.
              DistanceResult<double> d;
              const Triangle<double> tri = worldTri<BV>(m, s.mesh_tf, ct.b1);
              ASSERT_EQ(tryDistance(c, pose, tri, &d), Answer::kDisjoint);
              EXPECT_EQ(ct.penetration_depth, -d.distance);
              EXPECT_GE(ct.penetration_depth, -(margin + d.error_bound))
                  << std::hexfloat << "margin " << margin << " distance "
                  << d.distance << " bound " << d.error_bound << " triangle "
                  << tri.a.x << " " << tri.a.y << " " << tri.a.z << " "
                  << tri.b.x << " " << tri.b.y << " " << tri.b.z << " "
                  << tri.c.x << " " << tri.c.y << " " << tri.c.z;
              EXPECT_NEAR(ct.normal.norm(), 1, 1e-12);
            }
          }
          ASSERT_EQ(got, expect) << "margin " << margin << " order " << order;
          if (margin == 0) {
            fcl::CollisionResultd plain;
            tricyl::collide(&mesh_obj, &cyl_obj, req, plain);
            EXPECT_EQ(plain.numContacts(), res.numContacts());
          }
        }
      }
    }
  }
  EXPECT_GT(with_margin_only, 0);
}

// TriangleP vs Cylinder, both orders: fcl::distance with the Solver (the
// entries this solver registers), the wrapper, and the margin collide give
// tricyl::distance / withinDistance's answers for the world triangle.
TEST(FclDistanceShapes, TrianglePBothOrders) {
  const std::uint64_t seed = test::baseSeed() ^ 0x74726970u;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  const Solver<double> solver;
  long apart = 0, meeting = 0;
  for (int k = 0; k < 2000; ++k) {
    const double scale = std::pow(10.0, 3 * u(rng));
    auto tri = std::make_shared<fcl::TrianglePd>(
        V3(u(rng), u(rng), u(rng)) * scale, V3(u(rng), u(rng), u(rng)) * scale,
        V3(u(rng), u(rng), u(rng)) * scale);
    auto cyl = std::make_shared<fcl::Cylinderd>(0.5 + 0.5 * u(rng),
                                                1.0 + 0.9 * u(rng));
    Tf tf_tri = Tf::Identity(), tf_cyl = Tf::Identity();
    tf_tri.linear() = fcltest::randomRotation(rng);
    tf_tri.translation() = V3(u(rng), u(rng), u(rng));
    tf_cyl.linear() = fcltest::randomRotation(rng);
    tf_cyl.translation() = V3(u(rng), u(rng), u(rng));
    const Triangle<double> world =
        fcltest::toTri(tf_tri * tri->a, tf_tri * tri->b, tf_tri * tri->c);
    const Cylinder<double> c{cyl->radius, cyl->lz};
    const Pose<double> pose = toPose(tf_cyl);
    DistanceResult<double> d;
    const Answer a = tryDistance(c, pose, world, &d);
    const fcl::CollisionObjectd ot(tri, tf_tri), oc(cyl, tf_cyl);
    for (int order = 0; order < 2; ++order) {
      SCOPED_TRACE("case " + std::to_string(k) + " order " +
                   std::to_string(order));
      const fcl::CollisionObjectd* o1 = order ? &oc : &ot;
      const fcl::CollisionObjectd* o2 = order ? &ot : &oc;
      fcl::DistanceRequestd req(true);
      fcl::DistanceResultd f, w;
      fcl::distance(o1, o2, &solver, req, f);
      tricyl::distance(o1, o2, req, w);
      EXPECT_EQ(f.min_distance, w.min_distance);
      if (a == Answer::kDisjoint) {
        ++apart;
        EXPECT_EQ(f.min_distance, d.distance);
        const V3 on_tri = fclPoint(d.point_on_triangle);
        const V3 on_cyl = fclPoint(d.point_on_cylinder);
        EXPECT_EQ(f.nearest_points[0], order ? on_cyl : on_tri);
        EXPECT_EQ(f.nearest_points[1], order ? on_tri : on_cyl);
      } else {
        ++meeting;
        EXPECT_LT(f.min_distance, 0);
      }
      // Margin collide at the distance itself and just below it.
      if (a == Answer::kDisjoint) {
        for (double margin :
             {d.distance, std::nextafter(d.distance, 0.0), 0.5 * d.distance}) {
          fcl::CollisionRequestd creq(1, true);
          fcl::CollisionResultd cres;
          tricyl::collide(o1, o2, creq, cres, CollideOptions<double>{margin});
          EXPECT_EQ(
              cres.isCollision(),
              tryWithinDistance(c, pose, world, margin) != Answer::kDisjoint)
              << margin;
          if (cres.isCollision()) {
            const fcl::Contactd& ct = cres.getContact(0);
            EXPECT_EQ(ct.penetration_depth, -d.distance);
            // Normal from o1 toward o2.
            const V3 to_cyl =
                fclPoint(d.point_on_cylinder) - fclPoint(d.point_on_triangle);
            EXPECT_GT(ct.normal.dot(order ? V3(-to_cyl) : to_cyl), 0);
          }
        }
      }
    }
  }
  EXPECT_GT(apart, 100);
  EXPECT_GT(meeting, 10);
}

// The broadphase callback: DynamicAABBTree manager over a mesh and a box,
// queried with a cylinder: tricyl::DefaultDistanceFunction gives the
// smaller of tricyl::distance to the mesh and fcl::distance to the box.
TEST(FclDistanceShapes, BroadphaseDefaultDistanceFunction) {
  const Mesh m = fcltest::sphereMesh(10);
  auto model = fcltest::makeModel<fcl::OBBRSS<double>>(m);
  auto box = std::make_shared<fcl::Boxd>(0.5, 0.5, 0.5);
  auto cyl = std::make_shared<fcl::Cylinderd>(0.2, 0.6);
  Tf tb = Tf::Identity(), tc = Tf::Identity();
  tb.translation() = V3(4, 0, 0);
  fcl::CollisionObjectd om(model, Tf::Identity()), ob(box, tb);
  fcl::DynamicAABBTreeCollisionManagerd manager;
  manager.registerObject(&om);
  manager.registerObject(&ob);
  manager.setup();
  for (double x : {1.5, 2.0, 2.8, 3.2}) {
    tc.translation() = V3(x, 0.1, -0.05);
    fcl::CollisionObjectd oc(cyl, tc);
    DefaultDistanceData<double> data;
    manager.distance(&oc, &data, DefaultDistanceFunction<double>);
    fcl::DistanceResultd to_mesh, to_box;
    tricyl::distance(&om, &oc, fcl::DistanceRequestd(), to_mesh);
    fcl::distance(&ob, &oc, fcl::DistanceRequestd(), to_box);
    // The box pair is libccd's (tolerance 1e-6), whose answer may depend
    // on the argument order the manager uses.
    if (to_mesh.min_distance < to_box.min_distance - 1e-5)
      EXPECT_EQ(data.result.min_distance, to_mesh.min_distance) << x;
    else
      EXPECT_NEAR(data.result.min_distance, to_box.min_distance, 1e-5) << x;
  }
}

// Invalid margins are refused; a huge finite margin takes every triangle.
TEST(FclDistanceShapes, MarginArgument) {
  Mesh m = fcltest::sphereMesh(6);
  auto model = fcltest::makeModel<fcl::OBBRSS<double>>(m);
  auto cyl = std::make_shared<fcl::Cylinderd>(0.1, 0.2);
  Tf tf = Tf::Identity();
  tf.translation() = V3(5, 0, 0);
  const fcl::CollisionObjectd om(model, Tf::Identity()), oc(cyl, tf);
  fcl::CollisionRequestd req(100000);
  fcl::CollisionResultd res;
  for (double bad : {-1.0, std::numeric_limits<double>::infinity(),
                     std::numeric_limits<double>::quiet_NaN()})
    EXPECT_THROW(
        tricyl::collide(&om, &oc, req, res, CollideOptions<double>{bad}),
        InvalidInput);
  tricyl::collide(&om, &oc, req, res, CollideOptions<double>{100.0});
  EXPECT_EQ(res.numContacts(), m.t.size());
  res.clear();
  tricyl::collide(&om, &oc, req, res, CollideOptions<double>{3.5});
  EXPECT_EQ(res.numContacts(), 0u);
}

// The distance walk's certified triangle bounds (mesh_traversal.h:
// triangleLowerBound, and triangleSupportBound, which decides which
// triangles the walk measures) never exceed the distance tricyl::distance
// certifies, and are not positive for a triangle that meets the cylinder:
// random triangles near a random cylinder (offsets 1 .. 1e-14 of the size
// and touching), slivers and degenerate triangles, zero radius or length,
// at scales 2^-520 .. 2^300 (below the underflow threshold and past the
// support bound's range). And the support bound is tight where it is
// meant to be: within 1 % of the distance on most separated cases.
TEST(FclDistanceBounds, TriangleBoundsNeverExceedTheDistance) {
  const std::uint64_t seed = test::baseSeed() ^ 0x626f756eu;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  std::normal_distribution<double> g;
  long disjoint = 0, tight = 0, meeting = 0, unscaled = 0;
  for (int i = 0; i < 20000; ++i) {
    const int scale_pick = i % 8;
    const int ex = scale_pick == 0 ? -520 : (scale_pick == 1 ? 300 : 0);
    const double r = (i % 17 == 0) ? 0 : 0.05 + 2 * u01(rng);
    const double lz = (i % 19 == 0) ? 0 : 0.05 + 4 * u01(rng);
    const double h = 0.5 * lz;
    // A point on the cylinder's boundary (local frame), pushed out along
    // a random direction by a log-uniform offset (or not at all).
    const double phi = 2 * M_PI * u01(rng);
    const double rho = u01(rng) < 0.5 ? r : r * std::sqrt(u01(rng));
    const double z =
        rho == r ? h * (2 * u01(rng) - 1) : (u01(rng) < 0.5 ? -h : h);
    V3 local(rho * std::cos(phi), rho * std::sin(phi), z);
    V3 dir(g(rng), g(rng), g(rng));
    dir.normalize();
    const double offset = i % 23 == 0 ? 0 : std::pow(10.0, -14 * u01(rng));
    local += dir * offset;
    // The triangle around it: random size and shape, some slivers and
    // degenerate ones.
    const double size = std::pow(10.0, -3 + 3 * u01(rng));
    V3 p[3];
    for (int k = 0; k < 3; ++k)
      p[k] = local + size * V3(g(rng), g(rng), g(rng));
    if (i % 11 == 0) p[2] = p[0] + (p[1] - p[0]) * u01(rng);  // collinear
    if (i % 13 == 0) p[1] = p[0];                             // repeated
    if (i % 7 == 0) {  // the nearest part of the triangle at `local`
      const V3 side = dir.cross(V3(g(rng), g(rng), g(rng))).normalized();
      p[0] = local;
      p[1] = local + size * (dir + side);
      p[2] = local + size * (dir - side);
    }
    Tf tf = Tf::Identity();
    tf.linear() = fcltest::randomRotation(rng);
    tf.translation() = V3(g(rng), g(rng), g(rng)) * 10;
    const double f = std::ldexp(1.0, ex);
    for (int k = 0; k < 3; ++k) p[k] = f * (tf * p[k]);
    tf.translation() *= f;
    const Cylinder<double> cyl{f * r, f * lz};
    const Pose<double> pose = toPose(tf);
    const Triangle<double> tri = fcltest::toTri(p[0], p[1], p[2]);
    const double x[3][3] = {{p[0][0], p[0][1], p[0][2]},
                            {p[1][0], p[1][1], p[1][2]},
                            {p[2][0], p[2][1], p[2][2]}};
    const double t[3] = {pose.t.x, pose.t.y, pose.t.z};
    const traversal::LocalTriangle lt =
        traversal::toCylinderFrame(x, pose.R, t, cyl.radius, 0.5 * cyl.lz);
    const double cheap =
        traversal::triangleLowerBound(lt, cyl.radius, 0.5 * cyl.lz);
    const double support =
        traversal::triangleSupportBound(lt, cyl.radius, 0.5 * cyl.lz);
    EXPECT_EQ(cheap, traversal::triangleLowerBound(x, pose.R, t, cyl.radius,
                                                   0.5 * cyl.lz));
    DistanceResult<double> d;
    const Answer a = tryDistance(cyl, pose, tri, &d);
    ASSERT_NE(a, Answer::kInvalidInput) << i;
    if (a != Answer::kDisjoint) {
      ++meeting;
      EXPECT_FALSE(cheap > 0) << i << " " << cheap;
      EXPECT_FALSE(support > 0) << i << " " << support;
      continue;
    }
    ++disjoint;
    const double upper = d.distance + d.error_bound;
    EXPECT_FALSE(cheap > upper) << i << " " << cheap << " " << d.distance;
    EXPECT_FALSE(support > upper) << i << " " << support << " " << d.distance;
    if (ex == 0) {
      ++unscaled;
      if (support >= 0.99 * d.distance) ++tight;
    }
  }
  std::printf(
      "[ info ] %ld disjoint, %ld meeting; support bound within 1 %% of the "
      "distance on %ld of %ld at scale 1\n",
      disjoint, meeting, tight, unscaled);
  EXPECT_GT(meeting, 1000);
  EXPECT_GT(disjoint, 5000);
  EXPECT_GT(tight, unscaled / 2);
}

// float: fcl::distance with Solver<float> and the wrapper (FCL's traversal
// or, for AABB/OBB/KDOP, every triangle) give the float brute-force minimum.
TEST(FclDistanceShapes, FloatModels) {
  const std::uint64_t seed = test::baseSeed() ^ 0x666c6f61u;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> u(-1, 1);
  const Mesh md = fcltest::sphereMesh(10);
  std::vector<fcl::Vector3f> v;
  for (const V3& p : md.v) v.push_back(p.cast<float>());
  const auto check = [&](auto tag) {
    using BV = typename decltype(tag)::type;
    auto model = std::make_shared<fcl::BVHModel<BV>>();
    model->beginModel(int(md.t.size()), int(v.size()));
    model->addSubModel(v, md.t);
    model->endModel();
    const Solver<float> solver;
    for (int k = 0; k < 20; ++k) {
      auto cyl = std::make_shared<fcl::Cylinderf>(0.2f, 0.5f);
      fcl::Transform3f tf = fcl::Transform3f::Identity();
      tf.linear() = fcltest::randomRotation(rng).cast<float>();
      tf.translation() = fcl::Vector3f(u(rng), u(rng), u(rng)) * 2.0f;
      float best = std::numeric_limits<float>::max();
      bool hit = false;
      for (const fcl::Triangle& t : md.t) {
        DistanceResult<float> d;
        const Triangle<float> tri{toVec3(v[t[0]]), toVec3(v[t[1]]),
                                  toVec3(v[t[2]])};
        if (tryDistance(Cylinder<float>{0.2f, 0.5f}, toPose(tf), tri, &d) !=
            Answer::kDisjoint)
          hit = true;
        else
          best = std::min(best, d.distance);
      }
      const fcl::CollisionObjectf om(model, fcl::Transform3f::Identity()),
          oc(cyl, tf);
      fcl::DistanceRequestf req(true);
      fcl::DistanceResultf f, w;
      fcl::distance(&om, &oc, &solver, req, f);
      tricyl::distance(&oc, &om, req, w);
      if (hit) {
        EXPECT_LE(f.min_distance, 0);
        EXPECT_LE(w.min_distance, 0);
      } else {
        EXPECT_NEAR(f.min_distance, best, 1e-5f * best);
        EXPECT_EQ(w.min_distance, f.min_distance);
      }
    }
  };
  check(BvTag<fcl::OBBRSS<float>>{});
  check(BvTag<fcl::AABB<float>>{});
  check(BvTag<fcl::OBB<float>>{});
  check(BvTag<fcl::KDOP<float, 16>>{});
}

// TINY DISTANCES (docs/distance.md, section 6; mesh_distance.cpp, PRUNING).
// Below about 2^-45 of the problem's size tricyl::distance's error_bound is
// the double-word allowance (about 2^-95 of the size), wider than the 2^-40
// relative slack the walk's pruning once assumed. Scenes: a cylinder of
// radius and half length 2^-60 whose cap (or barrel, the axis along y)
// lies delta = 1e-12 .. 1e-30 of the mesh's size below the mesh's lowest
// vertex, put at the origin; poses exact (a permutation rotation, dyadic
// translations), so these distances are the true ones. Meshes: a synthetic
// "spikes" mesh (triangles with one vertex near the origin at heights
// delta (1 + q) above it, q in {0, 2^-52, 2^-44, 2^-30, 1}, or all but the
// first lifted by a further 2^-20 delta (a unique minimum), some spanning
// 4 r, some 0.5, the size: the narrow ones have tight bounds and a tiny
// error_bound, the wide ones a loose bound and an error_bound of 2^-95 of
// the size, many distances exactly equal), and the shared meshes moved so
// that their lowest vertex is at the origin (every triangle around it at
// exactly delta: a tie of six or so).
//
// What "agree" means. Every triangle i has a computed distance d_i and a
// certified e_i: its true distance is in [d_i - e_i, d_i + e_i], so the
// true minimum m is in [L, U], L = min (d_i - e_i), U = min (d_i + e_i).
// The brute-force answer is b = min d_i (triangle j, the first reaching
// it). Triangles whose intervals overlap cannot be told apart by the
// kernel, so a walk that measures fewer triangles may return another of
// them. Asserted for the wrapper (both orders, every BV type) and for
// fcl::distance with tricyl::Solver: (1) the value returned is the
// kernel's d_w of the triangle w returned, with that triangle's nearest
// points; (2) b <= d_w <= b + e_j (the walk's value is a kernel value no
// smaller than the brute-force one, and above it by no more than the
// brute-force triangle's own error bound); (3) d_w - e_w <= U (w may be
// the nearest triangle: none is certainly nearer); (4) when the minimum is
// certified unique (d_j + e_j < d_i - e_i for every other i), w = j and
// d_w = b exactly. The count of d_w == b is printed.
struct TinyMesh {
  Mesh m;
  double size;  // the mesh's bounding-box diagonal
};

/// The synthetic spikes mesh, its lowest vertex at the origin. `r` is the
/// cylinder's radius (the narrow spikes' width scale); delta the scene's
/// separation; `lift` (0 or 2^-20) raises every spike but the first by
/// delta lift (a unique nearest triangle where the bounds allow it).
Mesh spikesMesh(double r, double delta, double lift, std::mt19937_64& rng) {
  Mesh m;
  m.name = "spikes";
  std::uniform_real_distribution<double> u(-1, 1);
  const double qs[] = {0, 0x1p-52, 0x1p-44, 0x1p-30, 1};
  const auto add = [&m](const V3& a, const V3& b, const V3& c) {
    const int k = int(m.v.size());
    m.v.push_back(a);
    m.v.push_back(b);
    m.v.push_back(c);
    m.t.emplace_back(k, k + 1, k + 2);
  };
  // The size (lifted with the spikes after the first).
  add(V3(0, 0, delta * lift), V3(0.5, 0.25, 0.5), V3(-0.25, 0.5, 0.5));
  for (int i = 0; i < 40; ++i) {
    const double q = qs[i % 5];
    // (delta q is exact relative to delta: q a power of two or 0, 1.)
    const V3 p(0, 0, delta * q + (i > 0 ? delta * lift : 0.0));
    const double w = (i / 5) % 2 ? 0.5 : 4 * r;  // wide or narrow
    add(p, p + V3(w * u(rng), w * u(rng), w * (1 + u(rng)) + w),
        p + V3(w * u(rng), w * u(rng), w * (1 + u(rng)) + w));
  }
  // Filler: a grid of triangles 0.01 .. 1 above the origin (prunable).
  for (int i = 0; i < 60; ++i) {
    const V3 p(0.5 * u(rng), 0.5 * u(rng), 0.01 + 0.5 * (1 + u(rng)));
    add(p, p + V3(0.05, 0, 0.01), p + V3(0, 0.05, 0.02));
  }
  return m;
}

/// A shared mesh moved so that its lowest vertex (smallest z, then the
/// first) is at the origin: every vertex then has z >= 0 exactly (x - v
/// is rounded monotonically), so every triangle around it is exactly as
/// far from the cylinder as that vertex.
bool lowestAtOrigin(Mesh* m) {
  if (m->v.empty()) return false;
  std::size_t lo = 0;
  for (std::size_t i = 1; i < m->v.size(); ++i)
    if (m->v[i][2] < m->v[lo][2]) lo = i;
  const V3 o = m->v[lo];
  for (V3& p : m->v) p = p - o;
  return true;
}

/// Brute force (bruteForce) and whether its minimum is certified unique:
/// d_j + e_j < d_i - e_i for every other triangle i.
struct TinyBrute {
  Brute f;
  bool unique = false;
};

template <class BV>
TinyBrute tinyBrute(const Mesh& m, const Scene& s) {
  TinyBrute t{bruteForce<BV>(m, s)};
  const Brute& f = t.f;
  if (f.collides) return t;
  t.unique = true;
  for (std::size_t i = 0; i < m.t.size(); ++i)
    if (i != f.arg && !(f.d[f.arg] + f.e[f.arg] < f.d[i] - f.e[i]))
      t.unique = false;
  return t;
}

/// FCL's own traversal (fcl::distance with the Solver, for the types it
/// does not hand to the wrapper) prunes with its rounded BV distances and
/// no allowance: it may miss the nearest triangle by an absolute rounding
/// of its boxes (about 1e-16 of the scene's size; 1e-14 is asserted, as in
/// MinimumAndNearestPointsEqualBruteForce), far above these distances.
template <class BV>
constexpr bool kFclOwnTraversal = std::is_same_v<BV, fcl::RSS<double>> ||
                                  std::is_same_v<BV, fcl::kIOS<double>> ||
                                  std::is_same_v<BV, fcl::OBBRSS<double>>;

/// Asserts (1)-(4) of TINY DISTANCES for one answer; `slack` is 0 for the
/// wrapper, FCL's rounding (above) for FCL's own traversal (whose (3) and
/// (4) are then not asserted).
template <class BV>
void checkTinyAnswer(const Mesh& m, const Scene& s, const TinyBrute& t,
                     const fcl::DistanceResultd& w, const char* who,
                     double slack, long* equal) {
  SCOPED_TRACE(who);
  ASSERT_GE(w.b1, 0);
  ASSERT_LT(std::size_t(w.b1), m.t.size());
  const Cylinder<double> c{s.r, s.lz};
  const DistanceResult<double> at =
      tricyl::distance(c, toPose(s.cyl_tf), worldTri<BV>(m, s.mesh_tf, w.b1));
  // (1)
  EXPECT_EQ(w.min_distance, at.distance);
  EXPECT_EQ(w.nearest_points[0], fclPoint(at.point_on_triangle));
  EXPECT_EQ(w.nearest_points[1], fclPoint(at.point_on_cylinder));
  // (2)
  EXPECT_LE(t.f.min, w.min_distance);
  EXPECT_LE(w.min_distance, t.f.min + t.f.e[t.f.arg] + slack)
      << "brute force " << t.f.min;
  *equal += w.min_distance == t.f.min;
  if (slack > 0) return;
  // (3)
  EXPECT_LE(at.distance - at.error_bound, t.f.upper);
  // (4)
  if (t.unique) {
    EXPECT_EQ(std::size_t(w.b1), t.f.arg);
    EXPECT_EQ(w.min_distance, t.f.min);
  }
}

TYPED_TEST(FclDistanceTest, TinyDistancesAgreeWithBruteForceWithinBounds) {
  using BV = TypeParam;
  const std::uint64_t seed = test::baseSeed() ^ 0x74696e79u;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  const Solver<double> solver;
  const double r = 0x1p-60, h = 0x1p-60;
  long checked = 0, wrapper_equal = 0, fcl_equal = 0, unique = 0, wide = 0;
  TraversalStats stats;
  std::vector<Mesh> shared;
  for (Mesh& mm : meshes())
    if (mm.name != "builtin sphere" && lowestAtOrigin(&mm))
      shared.push_back(std::move(mm));
  for (const double rel : {1e-12, 1e-16, 1e-20, 1e-25, 1e-30}) {
    for (int which = -2; which < int(shared.size()); ++which) {
      for (int barrel = 0; barrel < 2; ++barrel) {
        // The mesh and delta (rel of its size, on a 2^-112 grid so that
        // the cylinder's translation below is exact).
        const double size = which < 0 ? 1.0 : diagonal(shared[which]);
        const double delta =
            std::max(std::ldexp(std::round(std::ldexp(rel * size, 112)), -112),
                     0x1p-112);
        const Mesh m =
            which < 0 ? spikesMesh(r, delta, which == -2 ? 0x1p-20 : 0, rng)
                      : shared[std::size_t(which)];
        char what[96];
        std::snprintf(what, sizeof what, "%s%s, %s, delta %.17g (%g of %g)",
                      m.name.c_str(), which == -2 ? " (unique)" : "",
                      barrel ? "barrel" : "cap", delta, rel, size);
        SCOPED_TRACE(what);
        Scene s;
        s.r = r;
        s.lz = 2 * h;
        s.kind = "tiny";
        s.mesh_tf = Tf::Identity();
        s.cyl_tf = Tf::Identity();
        if (barrel) {
          // Axis along y (columns e_z, e_x, e_y: det +1), the barrel's
          // nearest line at z = -delta.
          fcl::Matrix3d R;
          R << 0, 1, 0, 0, 0, 1, 1, 0, 0;
          s.cyl_tf.linear() = R;
          s.cyl_tf.translation() = V3(0, 0, -(r + delta));
        } else {
          s.cyl_tf.translation() = V3(0, 0, -(h + delta));
        }
        auto model = fcltest::makeModel<BV>(m);
        const TinyBrute t = tinyBrute<BV>(m, s);
        ASSERT_FALSE(t.f.collides);
        unique += t.unique;
        for (const double e : t.f.e) wide += e > 0x1p-40 * t.f.min;
        auto cyl = std::make_shared<fcl::Cylinderd>(s.r, s.lz);
        // Both argument orders: (mesh, cylinder), then (cylinder, mesh).
        const fcl::CollisionObjectd objs[2] = {{model, s.mesh_tf},
                                               {cyl, s.cyl_tf}};
        for (const bool cyl_first : {false, true}) {
          const fcl::DistanceRequestd req(true);
          fcl::DistanceResultd w, f;
          tricyl::distance(&objs[cyl_first], &objs[!cyl_first], req, w);
          checkTinyAnswer<BV>(
              m, s, t, w,
              cyl_first ? "wrapper, cylinder first" : "wrapper, mesh first",
              0.0, &wrapper_equal);
          fcl::distance(&objs[cyl_first], &objs[!cyl_first], &solver, req, f);
          checkTinyAnswer<BV>(
              m, s, t, f, cyl_first ? "fcl, cylinder first" : "fcl, mesh first",
              kFclOwnTraversal<BV> ? 1e-14 * size : 0.0, &fcl_equal);
          checked += 2;
        }
        fcl::DistanceResultd w;
        distanceMeshCylinder(model.get(), s.mesh_tf, cyl.get(), s.cyl_tf,
                             fcl::DistanceRequestd(), w, &stats);
      }
    }
  }
  // The scenes do what they are for: error bounds wider than 2^-40 of the
  // minimum (the old pruning's assumption), pruning still at work, and
  // unique minima too (assertion (4) at work).
  EXPECT_GT(wide, 0);
  EXPECT_GT(unique, 0);
  EXPECT_GT(stats.nodes_skipped, 0u);
  std::printf(
      "[ info ] %ld answers, equal to brute force's value: wrapper %ld, "
      "fcl::distance %ld; %ld scenes with a certified unique minimum; %ld "
      "triangle bounds wider than 2^-40 of the minimum; traversal: %zu "
      "bounds, %zu pruned, %zu triangles measured\n",
      checked, wrapper_equal, fcl_equal, unique, wide, stats.nodes_tested,
      stats.nodes_skipped, stats.leaves);
}

}  // namespace
}  // namespace tricyl
