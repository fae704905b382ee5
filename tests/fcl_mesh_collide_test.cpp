// SPDX-License-Identifier: BSD-3-Clause
// tricyl's own BVHModel/Cylinder traversal (fcl_mesh_cylinder.h), which
// tricyl::collide runs for mesh/cylinder pairs: the same answers as
// fcl::collide with tricyl::Solver (FCL's traversal, exact leaves), contact
// for contact; the walk's order (nearer child first); exact
// touching found; the node test actually prunes; every request it does not
// handle goes back to FCL.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <vector>

#include "fcl_test_support.h"
#include "test_support.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using fcltest::Mesh;
using fcltest::Scene;
using fcltest::Tf;
using fcltest::V3;

constexpr std::size_t kMany = 100000;

template <class BV>
constexpr bool kAlignedBv = std::is_same_v<BV, fcl::AABB<double>> ||
                            std::is_same_v<BV, fcl::KDOP<double, 16>> ||
                            std::is_same_v<BV, fcl::KDOP<double, 18>> ||
                            std::is_same_v<BV, fcl::KDOP<double, 24>>;

/// Triangles the exact kernel says collide, with the world vertices FCL
/// hands the solver (tf * v; v itself for an AABB/KDOP mesh whose transform
/// Eigen's isIdentity accepts). Invalid input counts as colliding.
template <class BV>
std::set<std::size_t> bruteForce(const Mesh& m, const Tf& mesh_tf, double r,
                                 double lz, const Tf& cyl_tf) {
  const bool raw = kAlignedBv<BV> && mesh_tf.matrix().isIdentity();
  const Pose<double> pose = toPose(cyl_tf);
  std::set<std::size_t> ids;
  for (std::size_t i = 0; i < m.t.size(); ++i) {
    V3 p[3];
    for (int j = 0; j < 3; ++j)
      p[j] = raw ? m.v[m.t[i][j]] : V3(mesh_tf * m.v[m.t[i][j]]);
    if (tryIntersect(Cylinder<double>{r, lz}, pose,
                     fcltest::toTri(p[0], p[1], p[2])) != Answer::kDisjoint)
      ids.insert(i);
  }
  return ids;
}

std::vector<int> sequence(const fcl::CollisionResultd& res) {
  std::vector<int> ids;
  for (std::size_t i = 0; i < res.numContacts(); ++i)
    ids.push_back(res.getContact(i).b1);
  return ids;
}

template <class BV>
class MeshCollideTest : public ::testing::Test {};
TYPED_TEST_SUITE(MeshCollideTest, fcltest::AllBvs);

// Every request shape on seeded scenes (random, grazing face/edge/vertex,
// thin), half of them with an identity mesh transform: the exhaustive set is
// the brute-force set; FCL's (with tricyl::Solver) is a subset (its BV tests
// round) and, when equal, comes in the same order; the contact data are
// FCL's, bit for bit, for every triangle both report; a first-k query gives
// k distinct colliding triangles.
TYPED_TEST(MeshCollideTest, SameContactsAsFclTraversalWithSolver) {
  const std::uint64_t seed = test::baseSeed() ^ 0x6d657368u;
  SCOPED_TRACE(test::seedTrace(seed));
  const tricyl::Solver<double> solver;
  long scenes = 0, fcl_missed = 0, hits = 0;
  for (const Mesh& m : {fcltest::gridMesh(10), fcltest::sphereMesh(8)}) {
    auto model = fcltest::makeModel<TypeParam>(m);
    std::vector<Scene> all = fcltest::makeScenes(m, seed, 4);
    for (std::size_t k = 0; k < all.size(); ++k) {
      Scene s = all[k];
      if (k % 2 == 1) {  // identity mesh transform: the raw-vertex path
        s.cyl_tf = s.mesh_tf.inverse(Eigen::Isometry) * s.cyl_tf;
        s.mesh_tf = Tf::Identity();
      }
      SCOPED_TRACE(fcltest::describe(s));
      const std::set<std::size_t> truth =
          bruteForce<TypeParam>(m, s.mesh_tf, s.r, s.lz, s.cyl_tf);
      auto cyl = std::make_shared<fcl::Cylinderd>(s.r, s.lz);
      const bool same_tree =
          !kAlignedBv<TypeParam> || s.mesh_tf.matrix().isIdentity();
      ++scenes;
      hits += long(truth.size());
      for (bool contact : {false, true}) {
        fcl::CollisionRequestd all_req(kMany, contact);
        fcl::CollisionResultd ours, theirs;
        std::size_t n = 0;
        TraversalStats st;
        ASSERT_TRUE(collideMeshCylinder(model.get(), s.mesh_tf, cyl.get(),
                                        s.cyl_tf, all_req, ours, &n, &st));
        EXPECT_EQ(n, ours.numContacts());
        fcl::collide(model.get(), s.mesh_tf, cyl.get(), s.cyl_tf, &solver,
                     all_req, theirs);
        const std::set<std::size_t> got = fcltest::contactIds(ours, cyl.get());
        const std::set<std::size_t> fcl_got =
            fcltest::contactIds(theirs, cyl.get());
        ASSERT_EQ(got, truth) << "scene " << k;
        EXPECT_EQ(st.hits, truth.size());
        for (std::size_t id : fcl_got) EXPECT_EQ(truth.count(id), 1u);
        for (std::size_t i = 0; i < ours.numContacts(); ++i) {
          const fcl::Contactd& c = ours.getContact(i);
          EXPECT_EQ(c.o1, model.get());
          EXPECT_EQ(c.o2, cyl.get());
          EXPECT_EQ(c.b2, int(fcl::Contactd::NONE));
        }
        // FCL's contact data, for every triangle both report.
        std::map<int, const fcl::Contactd*> fcl_by_id;
        for (std::size_t i = 0; i < theirs.numContacts(); ++i)
          fcl_by_id[theirs.getContact(i).b1] = &theirs.getContact(i);
        const auto same_data = [&](const fcl::CollisionResultd& r) {
          if (!contact || !same_tree) return;
          for (std::size_t i = 0; i < r.numContacts(); ++i) {
            const fcl::Contactd& a = r.getContact(i);
            const auto it = fcl_by_id.find(a.b1);
            if (it == fcl_by_id.end()) continue;
            EXPECT_EQ(a.pos, it->second->pos);
            EXPECT_EQ(a.normal, it->second->normal);
            EXPECT_EQ(a.penetration_depth, it->second->penetration_depth);
          }
        };
        same_data(ours);
        // An exhaustive query keeps FCL's order (fcl_mesh_cylinder.h).
        if (fcl_got != got)
          ++fcl_missed;
        else if (same_tree) {
          ASSERT_EQ(sequence(ours), sequence(theirs)) << "scene " << k;
        }
        // A first-k query (the walk's own order): k distinct colliding
        // triangles, or all of them when fewer collide.
        for (std::size_t max_c : {std::size_t(1), std::size_t(3)}) {
          fcl::CollisionRequestd req(max_c, contact);
          fcl::CollisionResultd o;
          ASSERT_TRUE(collideMeshCylinder(model.get(), s.mesh_tf, cyl.get(),
                                          s.cyl_tf, req, o, &n));
          EXPECT_EQ(o.numContacts(), std::min(max_c, truth.size()))
              << "scene " << k << " max " << max_c;
          const std::vector<int> ids = sequence(o);
          EXPECT_EQ(std::set<int>(ids.begin(), ids.end()).size(), ids.size());
          for (int id : ids) EXPECT_EQ(truth.count(std::size_t(id)), 1u);
          same_data(o);
        }
      }
    }
  }
  std::printf("[ traversal] scenes=%ld hits=%ld fcl_pruned_a_hit=%ld\n", scenes,
              hits, fcl_missed);
}

// Touching that is exact in double: an integer grid in the plane z = 0 and
// axis-aligned cylinders whose cap, barrel or rim meets it exactly, under
// exact rigid motions (axis permutations, sign flips, integer translations)
// and power-of-two scalings. The traversal must report exactly the
// brute-force set, which is never empty.
TYPED_TEST(MeshCollideTest, ExactTouchingIsFound) {
  const Mesh m = fcltest::flatGridMesh(8, 0, 1);  // integer vertices
  auto model = fcltest::makeModel<TypeParam>(m);
  struct Touch {
    double r, lz;
    Eigen::Matrix3d R;
    V3 t;
    const char* what;
  };
  Eigen::Matrix3d axis_x;  // cylinder axis along world x
  axis_x << 0, 0, 1, 0, 1, 0, -1, 0, 0;
  const std::vector<Touch> touches = {
      {1.5, 2, Eigen::Matrix3d::Identity(), V3(3.25, 4.5, 1), "cap on plane"},
      {1, 2, Eigen::Matrix3d::Identity(), V3(4, 3, -1), "cap from below"},
      {1, 3, Eigen::Matrix3d::Identity(), V3(5, 4, 0), "barrel on vertices"},
      {1, 4, axis_x, V3(4.5, 3.25, 1), "barrel tangent to plane"},
      {0.5, 1, axis_x, V3(8.5, 8.5, 0), "rim on corner vertex"},
      {2, 1, Eigen::Matrix3d::Identity(), V3(10, 4, 0), "barrel on edge x=8"},
  };
  // Exact mesh motions: identity, a signed axis permutation with an integer
  // translation.
  Eigen::Matrix3d perm;
  perm << 0, -1, 0, 0, 0, 1, -1, 0, 0;
  const Tf motions[2] = {Tf::Identity(), [&] {
                           Tf tf = Tf::Identity();
                           tf.linear() = perm;
                           tf.translation() = V3(-7, 3, 12);
                           return tf;
                         }()};
  for (const Touch& touch : touches)
    for (const Tf& motion : motions)
      for (double scale : {1.0, 0x1p-20, 0x1p30, 0x1p-540, 0x1p-560}) {
        SCOPED_TRACE(std::string(touch.what) + " scale " +
                     std::to_string(scale));
        Mesh ms = m;
        for (V3& v : ms.v) v *= scale;
        auto scaled = scale == 1.0 ? model : fcltest::makeModel<TypeParam>(ms);
        Tf cyl_tf = Tf::Identity();
        cyl_tf.linear() = motion.linear() * touch.R;
        cyl_tf.translation() = motion * V3(touch.t * scale);
        const double r = touch.r * scale, lz = touch.lz * scale;
        const std::set<std::size_t> truth =
            bruteForce<TypeParam>(ms, motion, r, lz, cyl_tf);
        ASSERT_FALSE(truth.empty());
        auto cyl = std::make_shared<fcl::Cylinderd>(r, lz);
        fcl::CollisionRequestd req(kMany, false);
        fcl::CollisionResultd res;
        std::size_t count = 0;
        ASSERT_TRUE(collideMeshCylinder(scaled.get(), motion, cyl.get(), cyl_tf,
                                        req, res, &count));
        EXPECT_EQ(fcltest::contactIds(res, cyl.get()), truth);
        // Moved by one ulp along each world axis, both ways: the sets still
        // equal the brute force's (some lose the touched feature, some not).
        for (int axis = 0; axis < 3; ++axis)
          for (double dir : {-1.0, 1.0}) {
            Tf moved = cyl_tf;
            double& x = moved.translation()[axis];
            x = std::nextafter(x,
                               dir * std::numeric_limits<double>::infinity());
            fcl::CollisionResultd res2;
            ASSERT_TRUE(collideMeshCylinder(scaled.get(), motion, cyl.get(),
                                            moved, req, res2, &count));
            EXPECT_EQ(fcltest::contactIds(res2, cyl.get()),
                      bruteForce<TypeParam>(ms, motion, r, lz, moved))
                << "axis " << axis << " dir " << dir;
          }
      }
}

// ORDER (fcl_mesh_cylinder.h): of two subtrees that both may hold a hit,
// the one whose box centre is nearer the cylinder's centre is walked first,
// so a first-hit query reports a triangle of the cluster nearer the
// cylinder's centre, whichever side of the tree FCL's split put it on. Two
// clusters of two triangles, 10 apart along a cylinder that holds all four;
// its centre moved from one cluster to the other. An exhaustive query keeps
// FCL's order.
TYPED_TEST(MeshCollideTest, NearerSubtreeFirst) {
  Mesh m;
  for (double z : {0.0, 0.5, 10.0, 10.5}) {
    const int base = int(m.v.size());
    m.v.push_back(V3(-0.1, -0.1, z));
    m.v.push_back(V3(0.1, -0.1, z));
    m.v.push_back(V3(0.0, 0.1, z));
    m.t.push_back(fcl::Triangle(base, base + 1, base + 2));
  }
  auto model = fcltest::makeModel<TypeParam>(m);
  auto cyl = std::make_shared<fcl::Cylinderd>(0.5, 30.0);
  const tricyl::Solver<double> solver;
  for (double zc : {-4.0, 0.25, 4.0, 6.5, 10.25, 14.0}) {
    Tf at = Tf::Identity();
    at.translation() = V3(0.01, 0.02, zc);
    fcl::CollisionRequestd all(kMany, false), one(1, false);
    fcl::CollisionResultd res_all, res_one;
    std::size_t n = 0;
    ASSERT_TRUE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(), at,
                                    all, res_all, &n));
    ASSERT_EQ(n, 4u) << "zc " << zc;
    ASSERT_TRUE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(), at,
                                    one, res_one, &n));
    ASSERT_EQ(n, 1u);
    const int id = res_one.getContact(0).b1;
    const bool low = zc < 5.25;  // nearer the cluster at z = 0 .. 0.5
    EXPECT_EQ(id < 2, low) << "zc " << zc << " id " << id;
    // First three: that cluster's two, then one of the other.
    fcl::CollisionRequestd three(3, false);
    fcl::CollisionResultd res_three;
    ASSERT_TRUE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(), at,
                                    three, res_three, &n));
    ASSERT_EQ(n, 3u);
    EXPECT_EQ(res_three.getContact(0).b1 < 2, low) << "zc " << zc;
    EXPECT_EQ(res_three.getContact(1).b1 < 2, low) << "zc " << zc;
    EXPECT_EQ(res_three.getContact(2).b1 < 2, !low) << "zc " << zc;
    // The exhaustive query cannot stop early: FCL's order.
    fcl::CollisionResultd theirs;
    fcl::collide(model.get(), Tf::Identity(), cyl.get(), at, &solver, all,
                 theirs);
    EXPECT_EQ(sequence(res_all), sequence(theirs)) << "zc " << zc;
  }
}

// The node test prunes: a cylinder far from the mesh costs one node test
// and no leaf, one touching a single triangle's interior visits a small
// fraction of the leaves.
TYPED_TEST(MeshCollideTest, NodeTestPrunes) {
  const Mesh m = fcltest::gridMesh(24);  // 1152 triangles on [-1, 1]^2
  auto model = fcltest::makeModel<TypeParam>(m);
  auto cyl = std::make_shared<fcl::Cylinderd>(0.01, 0.02);
  fcl::CollisionRequestd req(kMany, false);
  std::size_t n = 0;
  {
    Tf far = Tf::Identity();
    far.translation() = V3(5, 5, 5);
    fcl::CollisionResultd res;
    TraversalStats st;
    ASSERT_TRUE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(), far,
                                    req, res, &n, &st));
    EXPECT_EQ(st.nodes_tested, 1u);
    EXPECT_EQ(st.nodes_skipped, 1u);
    EXPECT_EQ(st.leaves, 0u);
    EXPECT_EQ(n, 0u);
  }
  {
    const fcl::Triangle& t = m.t[300];
    Tf near = Tf::Identity();
    near.translation() = (m.v[t[0]] + m.v[t[1]] + m.v[t[2]]) / 3;
    fcl::CollisionResultd res;
    TraversalStats st;
    ASSERT_TRUE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(),
                                    near, req, res, &n, &st));
    EXPECT_GE(n, 1u);
    EXPECT_GT(st.nodes_skipped, 0u);
    EXPECT_LT(st.leaves, m.t.size() / 20);
    EXPECT_EQ(fcltest::contactIds(res, cyl.get()),
              bruteForce<TypeParam>(m, Tf::Identity(), 0.01, 0.02, near));
  }
}

// A box axis within a hair of the cylinder's axis. The cylinder is tilted
// by theta = 2^-30 about x (R as given: cos theta rounds to 1), so its top
// rim rises to h + r sin(theta) ~ h + 9.3e-10 r along z, the axis of a flat
// box around a horizontal triangle at z0 = h + 2^-31 r: the rim's highest
// point pierces the triangle. The cylinder's support along a box axis a is
// h |a.u| + r |a x u|; evaluated as r sqrt(1 - (a.u)^2), the rounding of
// a.u to 1 wipes out the radial term (an error of r sqrt(2 |error of a.u|),
// not a few ulps of r), and a node holding the colliding triangle was
// skipped (all eight BV types, before the fix). Several tilts and heights
// around the rim's top, each checked against the brute force.
TYPED_TEST(MeshCollideTest, BoxAxisNearlyParallelToTheCylinderAxis) {
  // The scene as built, then under exact signed axis permutations P (so the
  // box axis is x or y, and the triangle below or above the cylinder), both
  // applied to the data (P v, P R) and given as the mesh's transform.
  std::vector<fcl::Matrix3d> motions(3);
  motions[0].setIdentity();
  motions[1] << 0, 0, 1, 1, 0, 0, 0, 1, 0;    // z -> x, x -> y, y -> z
  motions[2] << 0, -1, 0, 0, 0, -1, 1, 0, 0;  // z -> -y, with a flip
  for (int e : {20, 26, 30, 34}) {
    const double s = std::ldexp(1.0, -e);  // sin(theta); cos(theta) = 1
    for (double f : {0.25, 0.5, 0.999, 1.001, 2.0}) {
      const double r = 1, lz = 2, h = 1;
      const double z0 = h + f * s * r;
      Mesh m;
      // Two triangles in the plane z = z0: every fitted box (the covariance
      // fit of OBB/RSS/kIOS/OBBRSS too) has the axis z exactly.
      m.v = {V3(-3, -3, z0), V3(3, -3, z0),  V3(0, 3, z0),
             V3(10, 10, z0), V3(11, 10, z0), V3(10, 11, z0)};
      m.t = {fcl::Triangle(0, 1, 2), fcl::Triangle(3, 4, 5)};
      fcl::Matrix3d tilt;
      tilt << 1, 0, 0, 0, 1, -s, 0, s, 1;
      for (std::size_t k = 0; k < motions.size(); ++k)
        for (bool as_transform : {false, true}) {
          SCOPED_TRACE("theta 2^-" + std::to_string(e) + " height " +
                       std::to_string(f) + " motion " + std::to_string(k) +
                       (as_transform ? " (mesh transform)" : " (data)"));
          const fcl::Matrix3d& P = motions[k];
          Mesh mk = m;
          Tf mesh_tf = Tf::Identity();
          if (as_transform) {
            mesh_tf.linear() = P;
          } else {
            for (V3& v : mk.v) v = P * v;
          }
          auto model = fcltest::makeModel<TypeParam>(mk);
          auto cyl = std::make_shared<fcl::Cylinderd>(r, lz);
          Tf cyl_tf = Tf::Identity();
          cyl_tf.linear() = P * tilt;
          const std::set<std::size_t> truth =
              bruteForce<TypeParam>(mk, mesh_tf, r, lz, cyl_tf);
          EXPECT_EQ(truth.count(0), f < 1 ? 1u : 0u);
          fcl::CollisionRequestd req(kMany, false);
          fcl::CollisionResultd res;
          std::size_t n = 0;
          ASSERT_TRUE(collideMeshCylinder(model.get(), mesh_tf, cyl.get(),
                                          cyl_tf, req, res, &n));
          EXPECT_EQ(fcltest::contactIds(res, cyl.get()), truth);
        }
    }
  }
}

// Seeded (300 cases, times TRICYL_CASES_SCALE): a flat grid (z = 0) and
// cylinders whose axis is tilted from z by 2^-16 .. 2^-44 about a random
// horizontal direction, placed above or below the grid so that the lowest
// (or highest) point of a rim lies within a few times r sin(theta) of the
// plane, on either side. Every box axis z of the
// grid's tree is then nearly parallel to the cylinder's axis; the contacts
// must be the brute force's.
TYPED_TEST(MeshCollideTest, NearlyAlignedCylindersOverAFlatGrid) {
  const std::uint64_t seed = test::baseSeed() ^ 0x616c69676eu;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  const Mesh m = fcltest::flatGridMesh(8, -1, 0.25);  // on [-1, 1]^2
  auto model = fcltest::makeModel<TypeParam>(m);
  int hits = 0, cases = 0;
  for (long k = 0; k < test::scaled(300); ++k) {
    const double r = 0.05 + 0.25 * u01(rng), lz = 0.1 + 0.9 * u01(rng);
    const double s = std::ldexp(1.0, -16 - int(29 * u01(rng)));
    const double phi = 6.283185307179586 * u01(rng);
    fcl::Matrix3d tilt, spin;
    tilt << 1, 0, 0, 0, 1, -s, 0, s, 1;  // cos(theta) rounds to 1
    spin << std::cos(phi), -std::sin(phi), 0, std::sin(phi), std::cos(phi), 0,
        0, 0, 1;
    // The rim's lowest point is h + r s below the centre (cos theta = 1):
    // put it f r s above the plane, f in (-2, 2) (and mirrored below).
    const double f = 4 * u01(rng) - 2;
    const double above = u01(rng) < 0.5 ? 1.0 : -1.0;
    Tf cyl_tf = Tf::Identity();
    cyl_tf.linear() = spin * tilt;
    cyl_tf.translation() = V3(1.4 * u01(rng) - 0.7, 1.4 * u01(rng) - 0.7,
                              above * (0.5 * lz + (1 + f) * r * s));
    const std::set<std::size_t> truth =
        bruteForce<TypeParam>(m, Tf::Identity(), r, lz, cyl_tf);
    auto cyl = std::make_shared<fcl::Cylinderd>(r, lz);
    fcl::CollisionRequestd req(kMany, false);
    fcl::CollisionResultd res;
    std::size_t count = 0;
    ASSERT_TRUE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(),
                                    cyl_tf, req, res, &count));
    EXPECT_EQ(fcltest::contactIds(res, cyl.get()), truth) << "case " << k;
    hits += !truth.empty();
    ++cases;
  }
  // Both outcomes occur (the placement straddles the touching height).
  EXPECT_GT(hits, cases / 5);
  EXPECT_LT(hits, cases - cases / 5);
}

// Requests and inputs the traversal leaves to FCL: collideMeshCylinder says
// so and touches nothing, and tricyl::collide then equals fcl::collide with
// tricyl::Solver.
TEST(MeshCollideFallback, UnhandledCasesGoToFcl) {
  const Mesh m = fcltest::gridMesh(6);
  auto model = fcltest::makeModel<fcl::OBBRSS<double>>(m);
  const tricyl::Solver<double> solver;
  Tf at = Tf::Identity();
  at.translation() = V3(0.1, 0.2, 0.0);
  struct Case {
    double r, lz;
    Tf tf;
    fcl::CollisionRequestd req;
    const char* what;
  };
  fcl::CollisionRequestd cost(kMany, false, 10, true);
  fcl::CollisionRequestd none(0, false);
  Tf skew = at;
  skew.linear() *= 2.0;  // far from orthonormal
  Tf nan_tf = at;
  nan_tf.translation()[1] = std::numeric_limits<double>::quiet_NaN();
  const std::vector<Case> cases = {
      {0.3, 0.4, at, cost, "enable_cost"},
      {0.3, 0.4, at, none, "num_max_contacts = 0"},
      {0.3, 0.4, skew, fcl::CollisionRequestd(kMany, false), "scaled R"},
      {std::numeric_limits<double>::quiet_NaN(), 0.4, at,
       fcl::CollisionRequestd(kMany, false), "NaN radius"},
      {0.3, -1, at, fcl::CollisionRequestd(kMany, false), "negative length"},
      {0.3, 0.4, nan_tf, fcl::CollisionRequestd(kMany, false), "NaN pose"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.what);
    auto cyl = std::make_shared<fcl::Cylinderd>(0.3, 0.4);
    cyl->radius = c.r;  // the constructor would accept these as well
    cyl->lz = c.lz;
    fcl::CollisionResultd res;
    std::size_t n = 12345;
    EXPECT_FALSE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(),
                                     c.tf, c.req, res, &n));
    EXPECT_EQ(n, 12345u);
    EXPECT_EQ(res.numContacts(), 0u);
    fcl::CollisionResultd ours, theirs;
    // FCL's own code computes with the NaN (its BV of the cylinder).
    test::NoFpTraps no_traps;
    tricyl::collide(model.get(), Tf::Identity(), cyl.get(), c.tf, c.req, ours);
    fcl::collide(model.get(), Tf::Identity(), cyl.get(), c.tf, &solver, c.req,
                 theirs);
    EXPECT_EQ(sequence(ours), sequence(theirs));
  }
  // A pair without a mesh and a cylinder is not the traversal's either.
  auto sphere = std::make_shared<fcl::Sphered>(0.3);
  fcl::CollisionResultd res;
  std::size_t n = 0;
  EXPECT_FALSE(collideMeshCylinder(model.get(), Tf::Identity(), sphere.get(),
                                   at, fcl::CollisionRequestd(), res, &n));
}

// Either argument order gives the same contacts, the mesh always o1 (as
// FCL, which swaps a shape/BVH pair); a result that already holds enough
// contacts is left alone, one that holds some is topped up.
TEST(MeshCollideOrder, BothOrdersAndPrefilledResults) {
  const Mesh m = fcltest::gridMesh(12);
  auto model = fcltest::makeModel<fcl::OBBRSS<double>>(m);
  auto cyl = std::make_shared<fcl::Cylinderd>(0.3, 0.5);
  Tf at = Tf::Identity();
  at.translation() = V3(0.05, -0.1, 0.0);
  fcl::CollisionObjectd o_mesh(model, Tf::Identity());
  fcl::CollisionObjectd o_cyl(cyl, at);
  fcl::CollisionRequestd req(kMany, true);
  fcl::CollisionResultd a, b;
  tricyl::collide(&o_mesh, &o_cyl, req, a);
  tricyl::collide(&o_cyl, &o_mesh, req, b);
  ASSERT_GT(a.numContacts(), 3u);
  EXPECT_EQ(sequence(a), sequence(b));
  for (std::size_t i = 0; i < b.numContacts(); ++i) {
    EXPECT_EQ(b.getContact(i).o1, model.get());
    EXPECT_EQ(b.getContact(i).normal, a.getContact(i).normal);
  }
  fcl::CollisionRequestd two(2, false);
  fcl::CollisionResultd pre;
  pre.addContact(fcl::Contactd(nullptr, nullptr, -7, -7));
  pre.addContact(fcl::Contactd(nullptr, nullptr, -8, -8));
  EXPECT_EQ(tricyl::collide(&o_mesh, &o_cyl, two, pre), 2u);
  fcl::CollisionRequestd three(3, false);
  EXPECT_EQ(tricyl::collide(&o_mesh, &o_cyl, three, pre), 3u);
  // Topped up with what a first-hit query on an empty result reports.
  fcl::CollisionRequestd one(1, false);
  fcl::CollisionResultd first;
  EXPECT_EQ(tricyl::collide(&o_mesh, &o_cyl, one, first), 1u);
  EXPECT_EQ(pre.getContact(2).b1, first.getContact(0).b1);
}

// A NaN vertex spoils FCL's fit of the root (its covariance): the boxes
// may then hold nothing, so the traversal leaves such a model to FCL's own
// (collideMeshCylinder says so), and tricyl::collide answers as
// fcl::collide with tricyl::Solver does.
TEST(MeshCollideInvalid, NanVertexModelGoesToFcl) {
  Mesh m = fcltest::gridMesh(4);
  m.v[7][2] = std::numeric_limits<double>::quiet_NaN();
  test::NoFpTraps no_traps;  // FCL's fit and traversal compute with the NaN
  auto model = fcltest::makeModel<fcl::OBBRSS<double>>(m);
  auto cyl = std::make_shared<fcl::Cylinderd>(0.01, 0.01);
  Tf at = Tf::Identity();
  at.translation() = m.v[6];
  fcl::CollisionRequestd req(kMany, false);
  fcl::CollisionResultd res, ours, theirs;
  std::size_t n = 0;
  EXPECT_FALSE(collideMeshCylinder(model.get(), Tf::Identity(), cyl.get(), at,
                                   req, res, &n));
  const tricyl::Solver<double> solver;
  tricyl::collide(model.get(), Tf::Identity(), cyl.get(), at, req, ours);
  fcl::collide(model.get(), Tf::Identity(), cyl.get(), at, &solver, req,
               theirs);
  EXPECT_EQ(sequence(ours), sequence(theirs));
}

// A triangle whose world coordinates overflow (tf * v = Inf, the model
// itself finite) is reported in collision, as the Solver answers it. An
// AABB mesh (boxes from min/max, finite for these vertices) moved by 10^308:
// triangle 1 (x = 1.5e308 in the model) goes to x = Inf, triangle 0 lands
// on the cylinder's centre (1e308 + 1 rounds to 1e308). The margin of the
// node test is then infinite (|t_m|_1 + |t_c|_1 overflows), so every node
// is visited and both leaves reach the kernel: one hit, one invalid.
TEST(MeshCollideInvalid, OverflowingWorldVertexIsReportedInCollision) {
  Mesh m;
  m.v = {V3(0, 0, 0),       V3(1, 0, 0),       V3(0, 1, 0),
         V3(1.5e308, 0, 0), V3(1.5e308, 1, 0), V3(1.5e308, 0, 1)};
  m.t = {fcl::Triangle(0, 1, 2), fcl::Triangle(3, 4, 5)};
  test::NoFpTraps no_traps;  // tf * v overflows (FE_OVERFLOW, FE_INEXACT)
  auto model = fcltest::makeModel<fcl::AABB<double>>(m);
  auto cyl = std::make_shared<fcl::Cylinderd>(1.0, 1.0);
  Tf mesh_tf = Tf::Identity();
  mesh_tf.translation() = V3(1e308, 0, 0);
  Tf cyl_tf = Tf::Identity();
  cyl_tf.translation() = V3(1e308, 0, 0);
  const std::set<std::size_t> truth =
      bruteForce<fcl::AABB<double>>(m, mesh_tf, 1.0, 1.0, cyl_tf);
  ASSERT_EQ(truth, (std::set<std::size_t>{0, 1}));
  ASSERT_EQ(tryIntersect(Cylinder<double>{1, 1}, toPose(cyl_tf),
                         fcltest::toTri(mesh_tf * m.v[3], mesh_tf * m.v[4],
                                        mesh_tf * m.v[5])),
            Answer::kInvalidInput);
  fcl::CollisionRequestd req(kMany, false);
  fcl::CollisionResultd res;
  std::size_t n = 0;
  ASSERT_TRUE(collideMeshCylinder(model.get(), mesh_tf, cyl.get(), cyl_tf, req,
                                  res, &n));
  EXPECT_EQ(fcltest::contactIds(res, cyl.get()), truth);
}

}  // namespace
}  // namespace tricyl
