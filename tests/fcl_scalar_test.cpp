// SPDX-License-Identifier: BSD-3-Clause
// tricyl::Solver<S>, tricyl::collide<S> and tricyl::DefaultCollisionFunction
// for S = float and S = double: every BV type, both argument orders, against
// the exact oracle on the very world-frame triangles (in S) that FCL hands
// the solver (TriangleP: fcl_adapters_test.cpp); the broadphase callback;
// and request.gjk_solver_type, which tricyl::collide honours for every pair
// it does not answer itself.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/geometric_shape_to_BVH_model.h>
#include <fcl/geometry/shape/box.h>
#include <fcl/geometry/shape/ellipsoid.h>
#include <fcl/geometry/shape/sphere.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <string>
#include <type_traits>
#include <vector>

#include "fcl_test_support.h"
#include "oracle.h"
#include "test_support.h"
#include "tricyl/fcl_solver.h"

namespace tricyl {
namespace {

constexpr std::size_t kMany = 100000;  // "exhaustive" num_max_contacts

#if !defined(NDEBUG) || defined(__SANITIZE_ADDRESS__)
constexpr int kScenesPerKind = 2;
#else
constexpr int kScenesPerKind = 6;
#endif

template <class S>
using V3 = fcl::Vector3<S>;
template <class S>
using Tf = fcl::Transform3<S>;

template <class S>
const char* scalarName() {
  return std::is_same_v<S, float> ? "float" : "double";
}

/// A double transform rounded entrywise to S (for float, R is then
/// orthonormal only to about 1e-7; FCL and tricyl both use it as given).
template <class S>
Tf<S> castTf(const fcltest::Tf& tf) {
  Tf<S> out = Tf<S>::Identity();
  out.linear() = tf.linear().cast<S>();
  out.translation() = tf.translation().cast<S>();
  return out;
}

template <class S>
struct MeshS {
  std::string name;
  std::vector<V3<S>> v;
  std::vector<fcl::Triangle> t;
};

template <class S>
MeshS<S> castMesh(const fcltest::Mesh& m) {
  MeshS<S> out{m.name, {}, m.t};
  for (const fcltest::V3& p : m.v) out.v.push_back(p.cast<S>());
  return out;
}

Vec3<double> widen(const V3<float>& p) { return {p[0], p[1], p[2]}; }
Vec3<double> widen(const V3<double>& p) { return {p[0], p[1], p[2]}; }

/// An S pose, exactly, in double (float -> double is exact).
template <class S>
Pose<double> widenPose(const Tf<S>& tf) {
  const Pose<S> p = toPose(tf);
  Pose<double> q;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) q.R[i][j] = p.R[i][j];
  q.t = {p.t.x, p.t.y, p.t.z};
  return q;
}

/// One scene in S.
template <class S>
struct SceneS {
  S r, lz;
  Tf<S> cyl_tf, mesh_tf;
  std::string kind;
};

/// Triangle ids that the exact oracle says meet the cylinder, for the
/// world-frame triangles mesh_tf * v evaluated in S by Eigen (the
/// expression FCL uses for AABB/KDOP meshes and tricyl::Solver for the
/// others). Triangles whose box misses the cylinder's world box (enlarged by
/// a relative 1e-6, far above the rounding of that box) are disjoint.
template <class S>
std::set<std::size_t> oracleIds(const MeshS<S>& m, const SceneS<S>& s) {
  std::vector<V3<S>> w;
  for (const V3<S>& p : m.v) w.push_back(s.mesh_tf * p);
  const Cylinder<double> cyl{double(s.r), double(s.lz)};
  const Pose<double> pose = widenPose(s.cyl_tf);
  const Eigen::Matrix3d R = s.cyl_tf.linear().template cast<double>();
  const Eigen::Vector3d ext =
      R.cwiseAbs() * Eigen::Vector3d(s.r, s.r, double(s.lz) / 2);
  const Eigen::Vector3d c = s.cyl_tf.translation().template cast<double>();
  const double slack = 1e-6 * (ext.maxCoeff() + c.cwiseAbs().maxCoeff());
  const Eigen::Vector3d lo = c - ext - Eigen::Vector3d::Constant(slack),
                        hi = c + ext + Eigen::Vector3d::Constant(slack);
  std::set<std::size_t> ids;
  for (std::size_t i = 0; i < m.t.size(); ++i) {
    const Eigen::Vector3d a = w[m.t[i][0]].template cast<double>(),
                          b = w[m.t[i][1]].template cast<double>(),
                          cc = w[m.t[i][2]].template cast<double>();
    const Eigen::Vector3d tlo = a.cwiseMin(b).cwiseMin(cc),
                          thi = a.cwiseMax(b).cwiseMax(cc);
    if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any())
      continue;
    const Triangle<double> tri{widen(w[m.t[i][0]]), widen(w[m.t[i][1]]),
                               widen(w[m.t[i][2]])};
    if (oracle::triangleCylinder(cyl, pose, tri)) ids.insert(i);
  }
  return ids;
}

/// The mesh's triangle id of every contact (identified through the
/// cylinder's pointer: for AABB/KDOP meshes FCL's o1 is a temporary copy).
template <class S>
std::set<std::size_t> contactIds(const fcl::CollisionResult<S>& res,
                                 const fcl::CollisionGeometry<S>* cyl) {
  std::set<std::size_t> ids;
  for (std::size_t i = 0; i < res.numContacts(); ++i) {
    const fcl::Contact<S>& c = res.getContact(i);
    ids.insert(std::size_t(c.o1 == cyl ? c.b2 : c.b1));
  }
  return ids;
}

/// Seeded scenes (fcl_test_support.h's grazing, random and thin kinds) on a
/// procedural mesh, rounded to S, with their oracle sets.
template <class S>
struct Case {
  MeshS<S> mesh;
  std::vector<SceneS<S>> scenes;
  std::vector<std::set<std::size_t>> oracle;
};

template <class S>
const Case<S>& meshCase(const std::string& name) {
  static std::map<std::string, Case<S>> cache;
  auto it = cache.find(name);
  if (it != cache.end()) return it->second;
  const fcltest::Mesh md =
      name == "grid" ? fcltest::gridMesh(12) : fcltest::sphereMesh(10);
  Case<S> c;
  c.mesh = castMesh<S>(md);
  const std::uint64_t seed = test::baseSeed() ^ std::hash<std::string>{}(name);
  for (const fcltest::Scene& s :
       fcltest::makeScenes(md, seed, int(test::scaled(kScenesPerKind)))) {
    SceneS<S> t{S(s.r), S(s.lz), castTf<S>(s.cyl_tf), castTf<S>(s.mesh_tf),
                s.kind};
    c.scenes.push_back(t);
    c.oracle.push_back(oracleIds(c.mesh, t));
  }
  return cache.emplace(name, std::move(c)).first->second;
}

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> makeModel(const MeshS<typename BV::S>& m) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(int(m.t.size()), int(m.v.size()));
  model->addSubModel(m.v, m.t);
  model->endModel();
  return model;
}

// Every BV type FCL 0.7 builds meshes with, over float and over double.
template <class BV>
class ScalarBvTest : public ::testing::Test {};
using FloatAndDoubleBvs = ::testing::Types<
    fcl::AABB<float>, fcl::OBB<float>, fcl::RSS<float>, fcl::kIOS<float>,
    fcl::OBBRSS<float>, fcl::KDOP<float, 16>, fcl::KDOP<float, 18>,
    fcl::KDOP<float, 24>, fcl::AABB<double>, fcl::OBB<double>, fcl::RSS<double>,
    fcl::kIOS<double>, fcl::OBBRSS<double>, fcl::KDOP<double, 16>,
    fcl::KDOP<double, 18>, fcl::KDOP<double, 24>>;
TYPED_TEST_SUITE(ScalarBvTest, FloatAndDoubleBvs);

/// fcl::collide with a Solver<S> and tricyl::collide (geometry and object
/// forms), both argument orders, contacts off and on, against the oracle:
/// the same set of triangles every time; with num_max_contacts = 1, the
/// same Boolean and a colliding triangle.
template <class BV>
void checkMesh(const std::string& name) {
  using S = typename BV::S;
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  SCOPED_TRACE(std::string(scalarName<S>()) + " " + name);
  const Case<S>& c = meshCase<S>(name);
  auto model = makeModel<BV>(c.mesh);
  const Solver<S> solver;
  long hits = 0, checked = 0;
  for (std::size_t k = 0; k < c.scenes.size(); ++k) {
    const SceneS<S>& s = c.scenes[k];
    const std::set<std::size_t>& expect = c.oracle[k];
    hits += long(expect.size());
    auto cyl = std::make_shared<fcl::Cylinder<S>>(s.r, s.lz);
    const fcl::CollisionObject<S> o_mesh(model, s.mesh_tf),
        o_cyl(cyl, s.cyl_tf);
    for (int route = 0; route < 3; ++route)
      for (int order = 0; order < 2; ++order)
        for (std::size_t max_c : {std::size_t(1), kMany})
          for (bool contact : {false, true}) {
            const fcl::CollisionRequest<S> req(max_c, contact);
            fcl::CollisionResult<S> res;
            const bool mesh_first = order == 0;
            const fcl::CollisionGeometry<S>* g1 =
                mesh_first
                    ? static_cast<const fcl::CollisionGeometry<S>*>(model.get())
                    : cyl.get();
            const fcl::CollisionGeometry<S>* g2 =
                mesh_first
                    ? static_cast<const fcl::CollisionGeometry<S>*>(cyl.get())
                    : model.get();
            const Tf<S>& tf1 = mesh_first ? s.mesh_tf : s.cyl_tf;
            const Tf<S>& tf2 = mesh_first ? s.cyl_tf : s.mesh_tf;
            if (route == 0)
              fcl::collide(g1, tf1, g2, tf2, &solver, req, res);
            else if (route == 1)
              tricyl::collide(g1, tf1, g2, tf2, req, res);
            else
              tricyl::collide(mesh_first ? &o_mesh : &o_cyl,
                              mesh_first ? &o_cyl : &o_mesh, req, res);
            const std::set<std::size_t> got = contactIds<S>(res, cyl.get());
            const bool ok =
                max_c == 1 ? res.isCollision() == !expect.empty() &&
                                 (got.empty() || expect.count(*got.begin()))
                           : got == expect;
            ++checked;
            if (!ok)
              ADD_FAILURE() << "scene " << k << " (" << s.kind << ") route "
                            << (route == 0   ? "fcl::collide+Solver"
                                : route == 1 ? "tricyl::collide(geometry)"
                                             : "tricyl::collide(object)")
                            << " order " << order << " max_contacts " << max_c
                            << " contact " << contact << ": got " << got.size()
                            << " ids, oracle " << expect.size();
          }
  }
  // The scenes must exercise both answers, or the comparison proves little.
  EXPECT_GT(hits, long(c.scenes.size()) / 4);
  EXPECT_GT(checked, 0);
}

TYPED_TEST(ScalarBvTest, GridMatchesOracleEveryRouteBothOrders) {
  checkMesh<TypeParam>("grid");
}
TYPED_TEST(ScalarBvTest, SphereMatchesOracleEveryRouteBothOrders) {
  checkMesh<TypeParam>("sphere");
}

// ------------------------------------------------- per scalar, not per BV ---

template <class S>
class ScalarTest : public ::testing::Test {};
using FloatAndDouble = ::testing::Types<float, double>;
TYPED_TEST_SUITE(ScalarTest, FloatAndDouble);

/// tricyl::DefaultCollisionFunction<S> in a broadphase manager: a mesh and
/// three cylinders; the manager reports a collision iff the oracle finds a
/// colliding triangle for some cylinder, and every reported contact is one.
TYPED_TEST(ScalarTest, BroadphaseCallbackMatchesOracle) {
  using S = TypeParam;
  const MeshS<S> grid = castMesh<S>(fcltest::gridMesh(10));
  auto model = makeModel<fcl::OBBRSS<S>>(grid);
  fcl::CollisionObject<S> o_mesh(model, Tf<S>::Identity());
  for (const S z : {S(0.05), S(0.5)}) {  // touching the terrain, then above
    std::vector<std::unique_ptr<fcl::CollisionObject<S>>> cyls;
    std::set<std::size_t> expect;
    for (int i = 0; i < 3; ++i) {
      Tf<S> tf = Tf<S>::Identity();
      tf.translation() = V3<S>(S(-0.6 + 0.6 * i), S(0.1 * i), z);
      cyls.push_back(std::make_unique<fcl::CollisionObject<S>>(
          std::make_shared<fcl::Cylinder<S>>(S(0.15), S(0.4)), tf));
      const SceneS<S> s{S(0.15), S(0.4), tf, Tf<S>::Identity(), "broadphase"};
      const std::set<std::size_t> ids = oracleIds(grid, s);
      expect.insert(ids.begin(), ids.end());
    }
    fcl::DynamicAABBTreeCollisionManager<S> manager;
    manager.registerObject(&o_mesh);
    for (auto& c : cyls) manager.registerObject(c.get());
    manager.setup();
    DefaultCollisionData<S> data;
    data.request.num_max_contacts = kMany;
    manager.collide(&data, DefaultCollisionFunction<S>);
    EXPECT_EQ(data.result.isCollision(), !expect.empty()) << "z " << z;
    for (std::size_t i = 0; i < data.result.numContacts(); ++i) {
      const fcl::Contact<S>& ct = data.result.getContact(i);
      const std::size_t id = std::size_t(ct.o1 == model.get() ? ct.b1 : ct.b2);
      EXPECT_EQ(expect.count(id), 1u) << "z " << z << " triangle " << id;
    }
  }
}

// ------------------------------------------------ request.gjk_solver_type ---

/// The placements of FCL 0.7's own consistency test for ellipsoids under
/// GST_INDEP: a (20, 40, 50) ellipsoid at the origin and a radius-10 ball
/// (an ellipsoid) on the x axis. At x = +-30 the two exactly touch;
/// GJKSolver_indep reports that as a collision (libccd does not).
/// tricyl::collide answers no ellipsoid pair itself, so it must give
/// fcl::collide's answer for every placement, shape and mesh form and both
/// argument orders, under either solver type; and the touching shape pairs
/// collide under GST_INDEP.
TYPED_TEST(ScalarTest, GjkSolverTypeIsHonouredForPairsTricylDoesNotAnswer) {
  using S = TypeParam;
  const test::NoFpTraps no_traps;  // FCL's own GJK/EPA, not under test
  const fcl::Ellipsoid<S> big(S(20), S(40), S(50));
  const fcl::Ellipsoid<S> ball(S(10), S(10), S(10));
  fcl::BVHModel<fcl::AABB<S>> big_aabb, ball_aabb;
  fcl::BVHModel<fcl::OBB<S>> big_obb, ball_obb;
  fcl::generateBVHModel(big_aabb, big, Tf<S>::Identity(), 16, 16);
  fcl::generateBVHModel(ball_aabb, ball, Tf<S>::Identity(), 16, 16);
  fcl::generateBVHModel(big_obb, big, Tf<S>::Identity(), 16, 16);
  fcl::generateBVHModel(ball_obb, ball, Tf<S>::Identity(), 16, 16);
  const fcl::CollisionGeometry<S>* bigs[] = {&big, &big_aabb, &big_obb};
  const fcl::CollisionGeometry<S>* balls[] = {&ball, &ball_aabb, &ball_obb};
  const Tf<S> I = Tf<S>::Identity();
  long compared = 0;
  for (const fcl::GJKSolverType type : {fcl::GST_INDEP, fcl::GST_LIBCCD})
    for (const double x : {0.0, 40.0, 30.0, 29.9, -29.9, -30.0}) {
      Tf<S> pose = I;
      pose.translation() = V3<S>(S(x), S(0), S(0));
      for (const auto* g1 : bigs)
        for (const auto* g2 : balls)
          for (int order = 0; order < 2; ++order) {
            fcl::CollisionRequest<S> req;
            req.gjk_solver_type = type;
            fcl::CollisionResult<S> stock, ours, ours_obj;
            if (order == 0) {
              fcl::collide(g1, I, g2, pose, req, stock);
              tricyl::collide(g1, I, g2, pose, req, ours);
            } else {
              fcl::collide(g2, pose, g1, I, req, stock);
              tricyl::collide(g2, pose, g1, I, req, ours);
            }
            // The object form, on shared copies of the same geometries.
            auto sp1 = std::shared_ptr<fcl::CollisionGeometry<S>>(
                const_cast<fcl::CollisionGeometry<S>*>(g1),
                [](fcl::CollisionGeometry<S>*) {});
            auto sp2 = std::shared_ptr<fcl::CollisionGeometry<S>>(
                const_cast<fcl::CollisionGeometry<S>*>(g2),
                [](fcl::CollisionGeometry<S>*) {});
            const fcl::CollisionObject<S> o1(sp1, I), o2(sp2, pose);
            if (order == 0)
              tricyl::collide(&o1, &o2, req, ours_obj);
            else
              tricyl::collide(&o2, &o1, req, ours_obj);
            const std::string what =
                std::string(type == fcl::GST_INDEP ? "GST_INDEP"
                                                   : "GST_LIBCCD") +
                " x=" + std::to_string(x) + " types " +
                std::to_string(g1->getNodeType()) + "/" +
                std::to_string(g2->getNodeType()) + " order " +
                std::to_string(order);
            EXPECT_EQ(ours.isCollision(), stock.isCollision()) << what;
            EXPECT_EQ(ours.numContacts(), stock.numContacts()) << what;
            EXPECT_EQ(ours_obj.isCollision(), stock.isCollision()) << what;
            ++compared;
            const bool shapes = g1 == &big && g2 == &ball;
            if (type == fcl::GST_INDEP && shapes && (x == 30.0 || x == -30.0)) {
              EXPECT_TRUE(ours.isCollision())
                  << "exactly touching ellipsoids under GST_INDEP: " << what;
            }
          }
    }
  EXPECT_EQ(compared, 2 * 6 * 9 * 2);
}

/// For the pairs tricyl answers, the request's solver type changes nothing:
/// a cylinder standing exactly on a flat grid (touching, which libccd's MPR
/// misses) collides under either type, in both orders, and a cylinder one
/// step above it does not.
TYPED_TEST(ScalarTest, GjkSolverTypeDoesNotChangeTheExactPairs) {
  using S = TypeParam;
  const MeshS<S> grid = castMesh<S>(fcltest::flatGridMesh(8, -1, 0.25));
  auto model = makeModel<fcl::OBBRSS<S>>(grid);
  auto cyl = std::make_shared<fcl::Cylinder<S>>(S(0.3), S(1));
  for (const fcl::GJKSolverType type : {fcl::GST_INDEP, fcl::GST_LIBCCD})
    for (const S z : {S(0.5), std::nextafter(S(0.5), S(1))}) {
      Tf<S> tf = Tf<S>::Identity();
      tf.translation() = V3<S>(S(0.1), S(0.2), z);
      for (int order = 0; order < 2; ++order) {
        fcl::CollisionRequest<S> req;
        req.gjk_solver_type = type;
        fcl::CollisionResult<S> res;
        if (order == 0)
          tricyl::collide(model.get(), Tf<S>::Identity(), cyl.get(), tf, req,
                          res);
        else
          tricyl::collide(cyl.get(), tf, model.get(), Tf<S>::Identity(), req,
                          res);
        EXPECT_EQ(res.isCollision(), z == S(0.5))
            << (type == fcl::GST_INDEP ? "GST_INDEP" : "GST_LIBCCD") << " z "
            << z << " order " << order;
      }
    }
}

}  // namespace
}  // namespace tricyl
