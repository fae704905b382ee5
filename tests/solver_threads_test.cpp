// SPDX-License-Identifier: BSD-3-Clause
// Thread safety (issue 7): one shared tricyl::Solver<double> and the kernel
// entry points hammered from 4 threads over shared meshes. Every thread's
// results must equal a single-threaded reference bit for bit (Boolean,
// contact count, contact position, normal and depth). Meant to run under
// ThreadSanitizer (TRICYL_TSAN=ON, scripts/test.sh's TSan stage), where any
// data race in tricyl's code is a test failure; it also runs in the normal
// builds as a determinism check.
//
// Meshes: a procedural wavy grid and a procedural sphere (always), plus
// bunny.obj from TRICYL_MESH_DIR when it is present (skipped otherwise).
// gtest_discover_tests runs every TEST in its own process, so
// ConcurrentFirstConstruction really constructs the first Solver<double> of
// its process from 4 threads at once (the collision-table registration).
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/narrowphase/collision.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <memory>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "fcl_test_support.h"
#include "test_support.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

constexpr int kThreads = 4;

using fcltest::Mesh;

Mesh gridMesh(int n) {
  Mesh m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      m.v.emplace_back(x, y, 0.15 * std::sin(4 * x) * std::cos(3 * y));
    }
  auto id = [n](int i, int j) { return std::size_t(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.t.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.t.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

Mesh sphereMesh(int n) {  // latitude/longitude, radius 0.8
  Mesh m;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = pi * i / n, ph = pi * j / n;
      m.v.emplace_back(0.8 * std::sin(th) * std::cos(ph),
                       0.8 * std::sin(th) * std::sin(ph), 0.8 * std::cos(th));
    }
  auto id = [n](int i, int j) { return std::size_t(i * 2 * n + j % (2 * n)); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      m.t.emplace_back(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      m.t.emplace_back(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  return m;
}

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> buildModel(const Mesh& m) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel();
  model->addSubModel(m.v, m.t);
  model->endModel();
  return model;
}

/// Cylinders placed around the mesh's bounding box (many touch it).
struct Query {
  std::shared_ptr<fcl::Cylinderd> cyl;
  fcl::Transform3d tf;
};

std::vector<Query> makeQueries(const Mesh& m, int n, std::uint64_t seed) {
  fcl::Vector3d lo = m.v[0], hi = m.v[0];
  for (const auto& p : m.v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double size = (hi - lo).norm();
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<Query> q;
  for (int i = 0; i < n; ++i) {
    const double r = size * (0.005 + 0.1 * u(rng));
    const double lz = size * (0.001 + 0.3 * u(rng));
    Query k{std::make_shared<fcl::Cylinderd>(r, lz),
            fcl::Transform3d::Identity()};
    Eigen::Quaterniond rot(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5,
                           u(rng) - 0.5);
    rot.normalize();
    k.tf.linear() = rot.toRotationMatrix();
    const fcl::Vector3d& p =
        m.v[std::size_t(u(rng) * double(m.v.size())) % m.v.size()];
    k.tf.translation() =
        p +
        fcl::Vector3d(u(rng) - 0.5, u(rng) - 0.5, u(rng) - 0.5) * size * 0.05;
    q.push_back(k);
  }
  return q;
}

/// Everything a collide call defines, compared bit for bit: the primitive
/// ids of every contact and, only when contact data was requested, its
/// position, normal and depth. (With enable_contact = false FCL builds each
/// Contact with Contact(o1, o2, b1, b2), which leaves pos, normal and
/// penetration_depth uninitialised: comparing them compared stack garbage,
/// and CI failed on 802 of 3072 calls that way.)
struct Outcome {
  std::size_t contacts = 0;
  std::vector<std::intptr_t> ids;  // b1, b2 of every contact
  std::vector<double> data;  // pos, normal, depth of every contact, if asked
  bool operator==(const Outcome& o) const {
    return contacts == o.contacts && ids == o.ids &&
           data.size() == o.data.size() &&
           (data.empty() || std::memcmp(data.data(), o.data.data(),
                                        data.size() * sizeof(double)) == 0);
  }
};

/// `own`: through tricyl::collide (tricyl's own mesh traversal,
/// fcl_mesh_cylinder.h) instead of fcl::collide with the shared solver.
Outcome collideOnce(const Solver<double>& solver,
                    const fcl::CollisionGeometryd* mesh, const Query& q,
                    bool contact, bool mesh_first, bool own = false) {
  fcl::CollisionRequestd request(contact ? 4 : 1, contact);
  fcl::CollisionResultd result;
  const fcl::Transform3d I = fcl::Transform3d::Identity();
  if (own && mesh_first)
    tricyl::collide(mesh, I, q.cyl.get(), q.tf, request, result);
  else if (own)
    tricyl::collide(q.cyl.get(), q.tf, mesh, I, request, result);
  else if (mesh_first)
    fcl::collide(mesh, I, q.cyl.get(), q.tf, &solver, request, result);
  else
    fcl::collide(q.cyl.get(), q.tf, mesh, I, &solver, request, result);
  Outcome o;
  o.contacts = result.numContacts();
  for (std::size_t i = 0; i < o.contacts; ++i) {
    const auto& c = result.getContact(i);
    o.ids.push_back(c.b1);
    o.ids.push_back(c.b2);
    if (!contact) continue;
    for (int k = 0; k < 3; ++k) o.data.push_back(c.pos[k]);
    for (int k = 0; k < 3; ++k) o.data.push_back(c.normal[k]);
    o.data.push_back(c.penetration_depth);
  }
  return o;
}

/// The kernel over every triangle of the mesh for one query: the answers
/// packed as 2 bits each.
std::vector<std::uint8_t> kernelAnswers(const Mesh& m, const Query& q) {
  const Pose<double> pose = toPose(q.tf);
  const Cylinder<double> cyl{q.cyl->radius, q.cyl->lz};
  std::vector<std::uint8_t> out;
  out.reserve(m.t.size());
  for (const auto& t : m.t) {
    auto v = [&](std::size_t i) {
      const auto& p = m.v[t[i]];
      return Vec3<double>{p[0], p[1], p[2]};
    };
    out.push_back(static_cast<std::uint8_t>(
        tryIntersect(cyl, pose, Triangle<double>{v(0), v(1), v(2)})));
  }
  return out;
}

struct Workload {
  std::string name;
  Mesh mesh;
  std::vector<Query> queries;
};

std::vector<Workload> workloads() {
  std::vector<Workload> w;
  w.push_back({"grid", gridMesh(24), {}});
  w.push_back({"sphere", sphereMesh(16), {}});
  Mesh bunny;
  if (fcltest::readObj(fcltest::meshPath("bunny.obj"), &bunny) &&
      !bunny.t.empty())
    w.push_back({"bunny", bunny, {}});
  std::uint64_t seed = test::baseSeed();
  for (auto& x : w) x.queries = makeQueries(x.mesh, 48, seed++);
  return w;
}

// The first Solver<double> of the process is constructed by 4 threads at
// once, each then colliding through tricyl::collide (which constructs its
// own Solver per call) and through the shared one.
TEST(SolverThreads, ConcurrentFirstConstruction) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  const Mesh mesh = gridMesh(12);
  const auto model = buildModel<fcl::OBBRSSd>(mesh);
  const auto queries = makeQueries(mesh, 16, test::baseSeed());
  std::vector<std::vector<std::size_t>> counts(kThreads);
  std::atomic<int> ready{0};
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t)
    threads.emplace_back([&, t] {
      ready.fetch_add(1);
      while (ready.load() < kThreads) {
      }
      const Solver<double> solver;
      for (const Query& q : queries) {
        fcl::CollisionRequestd request;
        fcl::CollisionResultd result;
        const std::size_t n =
            tricyl::collide<double>(model.get(), fcl::Transform3d::Identity(),
                                    q.cyl.get(), q.tf, request, result);
        counts[std::size_t(t)].push_back(n);
        counts[std::size_t(t)].push_back(
            collideOnce(solver, model.get(), q, false, false).contacts);
      }
    });
  for (auto& th : threads) th.join();
  const Solver<double> solver;
  std::vector<std::size_t> ref;
  for (const Query& q : queries) {
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    ref.push_back(tricyl::collide<double>(model.get(),
                                          fcl::Transform3d::Identity(),
                                          q.cyl.get(), q.tf, request, result));
    ref.push_back(collideOnce(solver, model.get(), q, false, false).contacts);
  }
  std::size_t hits = 0;
  for (std::size_t n : ref) hits += n;
  EXPECT_GT(hits, 0u) << "no query collides: the test exercises nothing";
  for (int t = 0; t < kThreads; ++t)
    EXPECT_EQ(counts[std::size_t(t)], ref) << "thread " << t;
}

// One shared Solver, one shared BVHModel per BV type (OBBRSS: the mesh-frame
// overload; AABB: the world-frame overload), contact off and on, both
// argument orders; each thread walks the queries from its own offset.
TEST(SolverThreads, SharedSolverMatchesSingleThreaded) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  const Solver<double> solver;
  for (const Workload& w : workloads()) {
    SCOPED_TRACE(w.name);
    const auto obbrss = buildModel<fcl::OBBRSSd>(w.mesh);
    const auto aabb = buildModel<fcl::AABBd>(w.mesh);
    const fcl::CollisionGeometryd* models[2] = {obbrss.get(), aabb.get()};
    const std::size_t nq = w.queries.size();
    // Reference, single-threaded: index = (((q * 2 + model) * 2 + contact) *
    // 2 + order) * 2 + own (FCL's traversal with the solver, or tricyl's).
    std::vector<Outcome> ref;
    for (std::size_t q = 0; q < nq; ++q)
      for (const auto* model : models)
        for (bool contact : {false, true})
          for (bool mesh_first : {true, false})
            for (bool own : {false, true})
              ref.push_back(collideOnce(solver, model, w.queries[q], contact,
                                        mesh_first, own));
    std::size_t hits = 0;
    for (const Outcome& o : ref) hits += o.contacts > 0;
    EXPECT_GT(hits, 0u) << "no query collides: the test exercises nothing";

    std::atomic<long> mismatches{0}, calls{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
      threads.emplace_back([&, t] {
        for (int round = 0; round < 2; ++round)
          for (std::size_t k = 0; k < nq; ++k) {
            const std::size_t q = (k + std::size_t(t) * nq / kThreads) % nq;
            std::size_t i = q * 16;
            for (const auto* model : models)
              for (bool contact : {false, true})
                for (bool mesh_first : {true, false})
                  for (bool own : {false, true}) {
                    const Outcome o = collideOnce(solver, model, w.queries[q],
                                                  contact, mesh_first, own);
                    calls.fetch_add(1, std::memory_order_relaxed);
                    if (!(o == ref[i]))
                      mismatches.fetch_add(1, std::memory_order_relaxed);
                    ++i;
                  }
          }
      });
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0) << "of " << calls.load() << " calls";
    EXPECT_EQ(calls.load(), long(kThreads) * 2 * long(nq) * 16);
  }
}

// The kernel entry point directly, from 4 threads, every triangle of the
// shared mesh against every query.
TEST(SolverThreads, TryIntersectMatchesSingleThreaded) {
  SCOPED_TRACE(test::seedTrace(test::baseSeed()));
  for (const Workload& w : workloads()) {
    SCOPED_TRACE(w.name);
    const std::size_t nq = std::min<std::size_t>(w.queries.size(), 16);
    std::vector<std::vector<std::uint8_t>> ref;
    for (std::size_t q = 0; q < nq; ++q)
      ref.push_back(kernelAnswers(w.mesh, w.queries[q]));
    std::atomic<long> mismatches{0};
    std::vector<std::thread> threads;
    for (int t = 0; t < kThreads; ++t)
      threads.emplace_back([&, t] {
        for (std::size_t k = 0; k < nq; ++k) {
          const std::size_t q = (k + std::size_t(t) * 5) % nq;
          if (kernelAnswers(w.mesh, w.queries[q]) != ref[q])
            mismatches.fetch_add(1, std::memory_order_relaxed);
        }
      });
    for (auto& th : threads) th.join();
    EXPECT_EQ(mismatches.load(), 0);
  }
}

}  // namespace
}  // namespace tricyl
