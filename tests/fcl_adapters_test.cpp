// SPDX-License-Identifier: BSD-3-Clause
// fcl_adapters.h: every conversion is bit for bit, the converted values give
// the answers tricyl::Solver / tricyl::collide give on FCL's objects, and the
// batch scan over a BvhMeshView of a BVHModel gives the kernel's answer for
// every triangle (indices checked, copies and moves safe). float and double.
#include "tricyl/fcl_adapters.h"

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <vector>

#include "fcl_test_support.h"
#include "oracle.h"
#include "test_support.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/mesh_cylinder.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

template <class S>
using V3 = fcl::Vector3<S>;
template <class S>
using Tf = fcl::Transform3<S>;

template <class S>
class AdaptersTest : public ::testing::Test {};
using FloatAndDouble = ::testing::Types<float, double>;
TYPED_TEST_SUITE(AdaptersTest, FloatAndDouble);

template <class S>
Tf<S> randomTf(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> g;
  Tf<S> tf = Tf<S>::Identity();
  tf.linear() = fcltest::randomRotation(rng).cast<S>();
  tf.translation() =
      V3<S>(S(spread * g(rng)), S(spread * g(rng)), S(spread * g(rng)));
  return tf;
}

template <class S>
bool same(const Vec3<S>& a, const V3<S>& b) {
  return a.x == b[0] && a.y == b[1] && a.z == b[2];
}

TYPED_TEST(AdaptersTest, ConversionsAreBitForBit) {
  using S = TypeParam;
  const std::uint64_t seed = test::baseSeed() + 21;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> g;
  for (int k = 0; k < 100; ++k) {
    const Tf<S> tf = randomTf<S>(rng, 10);
    const Pose<S> pose = toPose(tf);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) ASSERT_EQ(pose.R[i][j], tf.linear()(i, j));
    ASSERT_TRUE(same(pose.t, V3<S>(tf.translation())));

    const fcl::Cylinder<S> fc(S(std::fabs(g(rng))), S(std::fabs(g(rng))));
    const Cylinder<S> c = toCylinder(fc);
    ASSERT_EQ(c.radius, fc.radius);
    ASSERT_EQ(c.lz, fc.lz);

    const V3<S> a(S(g(rng)), S(g(rng)), S(g(rng))),
        b(S(g(rng)), S(g(rng)), S(g(rng))), cc(S(g(rng)), S(g(rng)), S(g(rng)));
    ASSERT_TRUE(same(toVec3(a), a));
    const Triangle<S> t = toTriangle(a, b, cc);
    ASSERT_TRUE(same(t.a, a) && same(t.b, b) && same(t.c, cc));
    const fcl::TriangleP<S> tp(a, b, cc);
    const Triangle<S> local = toTriangle(tp);
    ASSERT_TRUE(same(local.a, a) && same(local.b, b) && same(local.c, cc));
    const Triangle<S> world = toTriangle(tp, tf);
    const V3<S> wa = tf * a, wb = tf * b, wc = tf * cc;
    ASSERT_TRUE(same(world.a, wa) && same(world.b, wb) && same(world.c, wc));
  }
}

/// The converted values give the answers of the FCL path: the kernel on
/// (toCylinder, toPose, toTriangle(t, tf)) is the oracle's answer on the same
/// numbers, and tricyl::collide's on the TriangleP/Cylinder objects (a pair
/// FCL 0.7 has no entry for; Solver<S> registers one) in both argument
/// orders, with and without contacts.
TYPED_TEST(AdaptersTest, ConvertedValuesGiveTheSolversAnswer) {
  using S = TypeParam;
  const std::uint64_t seed = test::baseSeed() + 22;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.2, 1.2);
  auto fc = std::make_shared<fcl::Cylinder<S>>(S(0.5), S(1.5));
  long hits = 0;
  for (int k = 0; k < 300; ++k) {
    auto tp = std::make_shared<fcl::TriangleP<S>>(
        V3<S>(S(u(rng)), S(u(rng)), S(u(rng))),
        V3<S>(S(u(rng)), S(u(rng)), S(u(rng))),
        V3<S>(S(u(rng)), S(u(rng)), S(u(rng))));
    const Tf<S> tri_tf = randomTf<S>(rng, 0.3), cyl_tf = randomTf<S>(rng, 0.3);
    const Triangle<S> tri = toTriangle(*tp, tri_tf);
    const bool kernel = intersect(toCylinder(*fc), toPose(cyl_tf), tri);
    const Pose<S> p = toPose(cyl_tf);
    Pose<double> pd;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) pd.R[i][j] = p.R[i][j];
    pd.t = {p.t.x, p.t.y, p.t.z};
    const bool exact =
        oracle::triangleCylinder({double(fc->radius), double(fc->lz)}, pd,
                                 {{tri.a.x, tri.a.y, tri.a.z},
                                  {tri.b.x, tri.b.y, tri.b.z},
                                  {tri.c.x, tri.c.y, tri.c.z}});
    ASSERT_EQ(kernel, exact) << "k " << k;
    const fcl::CollisionObject<S> o_tri(tp, tri_tf), o_cyl(fc, cyl_tf);
    for (int order = 0; order < 2; ++order)
      for (bool contact : {false, true}) {
        const fcl::CollisionRequest<S> req(1, contact);
        fcl::CollisionResult<S> res;
        if (order == 0)
          tricyl::collide(&o_tri, &o_cyl, req, res);
        else
          tricyl::collide(&o_cyl, &o_tri, req, res);
        ASSERT_EQ(res.isCollision(), kernel)
            << "k " << k << " order " << order << " contact " << contact;
      }
    hits += kernel;
  }
  EXPECT_GT(hits, 30);
  EXPECT_LT(hits, 270);
}

template <class S>
std::shared_ptr<fcl::BVHModel<fcl::OBBRSS<S>>> model(
    const std::vector<V3<S>>& v, const std::vector<fcl::Triangle>& t) {
  auto m = std::make_shared<fcl::BVHModel<fcl::OBBRSS<S>>>();
  m->beginModel(int(t.size()), int(v.size()));
  m->addSubModel(v, t);
  m->endModel();
  return m;
}

/// The batch scan over BvhMeshView(model): bit i set iff the kernel says
/// triangle i meets the cylinder, for a BVHModel and for the vectors it was
/// built from; with an identity mesh pose, the same set as tricyl::collide.
TYPED_TEST(AdaptersTest, BatchScanOverABvhModelIsTheKernelPerTriangle) {
  using S = TypeParam;
  const std::uint64_t seed = test::baseSeed() + 23;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 rng(seed);
  const fcltest::Mesh md = fcltest::sphereMesh(12);
  std::vector<V3<S>> v;
  for (const auto& p : md.v) v.push_back(p.template cast<S>());
  const auto m = model(v, md.t);
  const BvhMeshView<S> from_model(*m);
  const BvhMeshView<S> from_vectors(v, md.t);
  ASSERT_EQ(from_model.num_triangles, md.t.size());
  ASSERT_EQ(from_model.num_vertices, md.v.size());
  std::uniform_real_distribution<double> u(-1.2, 1.2), rr(0.05, 0.6);
  long hits = 0;
  for (int k = 0; k < 100; ++k) {
    Tf<S> tf = randomTf<S>(rng, 0);
    tf.translation() = V3<S>(S(u(rng)), S(u(rng)), S(u(rng)));
    const fcl::Cylinder<S> fc(S(rr(rng)), S(rr(rng)));
    const Cylinder<S> cyl = toCylinder(fc);
    const Pose<S> pose = toPose(tf);
    std::vector<std::uint64_t> mask((md.t.size() + 63) / 64),
        mask2(mask.size());
    const std::size_t n = intersectMask(cyl, pose, from_model, mask.data());
    intersectMask(cyl, pose, from_vectors, mask2.data());
    ASSERT_EQ(mask, mask2);
    std::set<std::size_t> expect;
    for (std::size_t i = 0; i < md.t.size(); ++i) {
      const bool hit = intersect(
          cyl, pose, toTriangle(v[md.t[i][0]], v[md.t[i][1]], v[md.t[i][2]]));
      ASSERT_EQ(bool(mask[i / 64] >> (i % 64) & 1u), hit) << "k " << k;
      if (hit) expect.insert(i);
    }
    ASSERT_EQ(n, expect.size());
    hits += long(n);
    // The model in the world frame (identity pose): tricyl::collide's set.
    fcl::CollisionRequest<S> req(100000, false);
    fcl::CollisionResult<S> res;
    tricyl::collide(m.get(), Tf<S>::Identity(), &fc, tf, req, res);
    std::set<std::size_t> got;
    for (std::size_t i = 0; i < res.numContacts(); ++i) {
      const fcl::Contact<S>& c = res.getContact(i);
      got.insert(std::size_t(c.o1 == &fc ? c.b2 : c.b1));
    }
    ASSERT_EQ(got, expect) << "k " << k;
    std::vector<std::uint32_t> ids;
    intersectIndices(cyl, pose, from_model, &ids);
    ASSERT_EQ(std::set<std::size_t>(ids.begin(), ids.end()), expect);
    const std::optional<std::size_t> first =
        intersectAny(cyl, pose, from_model);
    ASSERT_EQ(first.has_value(), !expect.empty());
    if (first) {
      ASSERT_EQ(*first, *expect.begin());
    }
  }
  EXPECT_GT(hits, 100);
}

TYPED_TEST(AdaptersTest, BadIndicesStayInvalidAndCopiesAreSafe) {
  using S = TypeParam;
  const std::vector<V3<S>> v = {V3<S>(-1, -1, 0), V3<S>(1, -1, 0),
                                V3<S>(1, 1, 0), V3<S>(-1, 1, 0)};
  const std::vector<fcl::Triangle> t = {fcl::Triangle(0, 1, 2),
                                        fcl::Triangle(0, 2, 3)};
  const Cylinder<S> cyl{S(0.25), S(1)};
  Pose<S> pose = identityPose<S>();
  pose.t = {S(5), S(5), S(0)};  // far from the square: no hit
  std::vector<std::uint64_t> mask(1);
  {
    // A copy outlives its original and still scans its own indices.
    auto original = std::make_unique<BvhMeshView<S>>(v, t);
    const BvhMeshView<S> copy(*original);
    BvhMeshView<S> assigned(std::vector<V3<S>>{}, {});
    assigned = *original;
    BvhMeshView<S> moved(std::move(*original));
    original.reset();
    const BvhMeshView<S>* views[] = {&copy, &assigned, &moved};
    for (const BvhMeshView<S>* view : views) {
      ASSERT_EQ(view->num_triangles, 2u);
      pose.t = {S(0), S(0), S(0)};
      EXPECT_EQ(intersectMask(cyl, pose, *view, mask.data()), 2u);
      EXPECT_EQ(mask[0], 3u);
    }
  }
  // An index past the vertices (here 4, and 2^32 + 1, which 32 bits would
  // wrap to 1) stays invalid: the checked scan throws, the try scan marks it.
  for (const std::size_t bad : {std::size_t(4), (std::size_t(1) << 32) + 1}) {
    const std::vector<fcl::Triangle> tb = {fcl::Triangle(0, 1, 2),
                                           fcl::Triangle(0, bad, 3)};
    const BvhMeshView<S> view(v, tb);
    pose.t = {S(5), S(5), S(0)};
    EXPECT_THROW(intersectMask(cyl, pose, view, mask.data()), InvalidInput);
    std::size_t hits = 0;
    EXPECT_EQ(tryIntersectMask(cyl, pose, view, mask.data(), &hits),
              Answer::kInvalidInput);
    EXPECT_EQ(mask[0], 2u) << "bad index " << bad;
    EXPECT_EQ(hits, 1u);
  }
  // 32-bit indices cannot address 2^32 - 1 vertices or more (the vertex
  // array is never read: the constructor refuses first).
  EXPECT_THROW(
      BvhMeshView<S>(v.data(), std::numeric_limits<std::uint32_t>::max(),
                     t.data(), 0),
      std::length_error);
  // A point cloud has no triangles.
  fcl::BVHModel<fcl::OBBRSS<S>> cloud;
  cloud.beginModel();
  cloud.addVertex(V3<S>(0, 0, 0));
  cloud.addVertex(V3<S>(1, 0, 0));
  cloud.endModel();
  EXPECT_EQ(BvhMeshView<S>(cloud).num_triangles, 0u);
}

}  // namespace
}  // namespace tricyl
