// SPDX-License-Identifier: BSD-3-Clause
// Shared by the FCL solver tests: meshes (OBJ files and procedural), seeded
// scene generation, the exact oracle's colliding set, and collide helpers.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <fstream>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "obj_mesh.h"
#include "oracle.h"
#include "test_support.h"
#include "tricyl/fcl_solver.h"

namespace tricyl::fcltest {

using V3 = fcl::Vector3d;
using Tf = fcl::Transform3d;

struct Mesh {
  std::string name;
  std::vector<V3> v;
  std::vector<fcl::Triangle> t;
};

/// Reads an OBJ file with the repository's reader (support/obj_mesh.h).
/// Returns false if the file cannot be read.
inline bool readObj(const std::string& path, Mesh* m) {
  obj::Mesh f;
  try {
    f = obj::read(path);
  } catch (const std::exception&) {
    return false;
  }
  for (std::size_t i = 0; i < f.numVertices(); ++i)
    m->v.emplace_back(f.vertices[3 * i], f.vertices[3 * i + 1],
                      f.vertices[3 * i + 2]);
  for (std::size_t t = 0; t < f.numTriangles(); ++t)
    m->t.emplace_back(f.indices[3 * t], f.indices[3 * t + 1],
                      f.indices[3 * t + 2]);
  return true;
}

inline std::string meshPath(const std::string& file) {
  return std::string(TRICYL_MESH_DIR) + "/" + file;
}

/// The 2 n^2 triangles of an (n + 1) x (n + 1) vertex grid, vertex (i, j) at
/// index i (n + 1) + j.
inline void addGridTriangles(int n, Mesh* m) {
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1,
                        d = c + 1;
      m->t.emplace_back(a, c, b);
      m->t.emplace_back(b, c, d);
    }
}

/// A wavy height field on [-1, 1]^2 (n x n quads, 2 n^2 triangles).
inline Mesh gridMesh(int n) {
  Mesh m;
  m.name = "grid";
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      m.v.emplace_back(x, y, 0.1 * std::sin(3 * x) * std::cos(2 * y));
    }
  addGridTriangles(n, &m);
  return m;
}

/// A flat grid in the plane z = 0: vertices (lo + step i, lo + step j, 0),
/// i, j = 0 .. n, and 2 n^2 triangles.
inline Mesh flatGridMesh(int n, double lo, double step) {
  Mesh m;
  m.name = "flat grid";
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      m.v.emplace_back(lo + step * i, lo + step * j, 0);
  addGridTriangles(n, &m);
  return m;
}

/// A UV sphere of radius 1 (closed, 2 n (n - 1) triangles).
inline Mesh sphereMesh(int n) {
  Mesh m;
  m.name = "sphere";
  const double pi = std::acos(-1.0);
  m.v.emplace_back(0, 0, 1);
  for (int i = 1; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double th = pi * i / n, ph = pi * j / n;
      m.v.emplace_back(std::sin(th) * std::cos(ph), std::sin(th) * std::sin(ph),
                       std::cos(th));
    }
  m.v.emplace_back(0, 0, -1);
  const std::size_t south = m.v.size() - 1;
  auto ring = [n](int i, int j) -> std::size_t {
    return 1 + std::size_t(i - 1) * 2 * n + std::size_t(j % (2 * n));
  };
  for (int j = 0; j < 2 * n; ++j) {
    m.t.emplace_back(0, ring(1, j), ring(1, j + 1));
    m.t.emplace_back(south, ring(n - 1, j + 1), ring(n - 1, j));
  }
  for (int i = 1; i < n - 1; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      m.t.emplace_back(ring(i, j), ring(i + 1, j), ring(i + 1, j + 1));
      m.t.emplace_back(ring(i, j), ring(i + 1, j + 1), ring(i, j + 1));
    }
  return m;
}

/// Every BV type FCL 0.7 builds meshes with, for typed tests.
using AllBvs = ::testing::Types<fcl::AABB<double>, fcl::OBB<double>,
                                fcl::RSS<double>, fcl::kIOS<double>,
                                fcl::OBBRSS<double>, fcl::KDOP<double, 16>,
                                fcl::KDOP<double, 18>, fcl::KDOP<double, 24>>;

template <class BV>
std::shared_ptr<fcl::BVHModel<BV>> makeModel(const Mesh& m) {
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  model->beginModel(int(m.t.size()), int(m.v.size()));
  model->addSubModel(m.v, m.t);
  model->endModel();
  return model;
}

inline Triangle<double> toTri(const V3& a, const V3& b, const V3& c) {
  return {{a[0], a[1], a[2]}, {b[0], b[1], b[2]}, {c[0], c[1], c[2]}};
}

/// One query: a cylinder and a mesh, both posed.
struct Scene {
  double r, lz;
  Tf cyl_tf;
  Tf mesh_tf;
  const char* kind;  // "random", "face", "edge", "vertex", "thin"
};

/// World-frame vertices exactly as FCL computes them (tf * v, Eigen).
inline std::vector<V3> worldVertices(const Mesh& m, const Tf& tf) {
  std::vector<V3> w;
  w.reserve(m.v.size());
  for (const V3& p : m.v) w.push_back(tf * p);
  return w;
}

/// Triangle ids that the exact oracle says meet the cylinder. A triangle
/// whose bounding box misses the cylinder's (enlarged) bounding box is
/// disjoint and skips the rational arithmetic.
inline std::set<std::size_t> oracleSet(const Mesh& m, const Scene& s) {
  const std::vector<V3> w = worldVertices(m, s.mesh_tf);
  const Pose<double> pose = toPose(s.cyl_tf);
  const Cylinder<double> cyl{s.r, s.lz};
  const Eigen::Matrix3d R = s.cyl_tf.linear();
  const V3 ext = R.cwiseAbs() * V3(s.r, s.r, s.lz / 2);
  const V3 c = s.cyl_tf.translation();
  const double slack =
      1e-6 * (ext.maxCoeff() + c.cwiseAbs().maxCoeff()) + 1e-300;
  const V3 lo = c - ext - V3::Constant(slack),
           hi = c + ext + V3::Constant(slack);
  std::set<std::size_t> ids;
  for (std::size_t i = 0; i < m.t.size(); ++i) {
    const V3& a = w[m.t[i][0]];
    const V3& b = w[m.t[i][1]];
    const V3& cc = w[m.t[i][2]];
    const V3 tlo = a.cwiseMin(b).cwiseMin(cc), thi = a.cwiseMax(b).cwiseMax(cc);
    if ((tlo.array() > hi.array()).any() || (thi.array() < lo.array()).any())
      continue;
    if (oracle::triangleCylinder(cyl, pose, toTri(a, b, cc))) ids.insert(i);
  }
  return ids;
}

inline Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> g;
  Eigen::Quaterniond q(g(rng), g(rng), g(rng), g(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// A rotation taking +z to the unit vector `axis`, with a random spin.
inline Eigen::Matrix3d rotationWithZ(const V3& axis, std::mt19937_64& rng) {
  const V3 z = axis.normalized();
  V3 x = z.unitOrthogonal();
  std::uniform_real_distribution<double> u(0, 2 * std::acos(-1.0));
  const double a = u(rng);
  x = std::cos(a) * x + std::sin(a) * z.cross(x);
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return R;
}

/// Seeded scenes for mesh `m`: random poses near the surface, poses whose
/// cylinder grazes a random triangle's face (cap or barrel), edge or vertex
/// (up to rounding, so both answers occur), and thin cylinders.
inline std::vector<Scene> makeScenes(const Mesh& m, std::uint64_t seed,
                                     int per_kind) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0, 1);
  V3 lo = m.v[0], hi = m.v[0];
  for (const V3& p : m.v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  const double diag = (hi - lo).norm();
  std::vector<Scene> out;
  auto meshPose = [&]() {
    Tf tf = Tf::Identity();
    tf.linear() = randomRotation(rng);
    tf.translation() =
        V3(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5) * diag;
    return tf;
  };
  auto randomTri = [&]() {
    return m.t[std::size_t(u01(rng) * double(m.t.size())) % m.t.size()];
  };
  for (int k = 0; k < per_kind; ++k) {
    // random: centre near a random triangle, random orientation and size.
    Scene s;
    s.kind = "random";
    s.mesh_tf = meshPose();
    s.r = diag * (0.002 + 0.05 * u01(rng));
    s.lz = diag * (0.005 + 0.15 * u01(rng));
    const fcl::Triangle t = randomTri();
    const V3 p =
        (m.v[t[0]] + m.v[t[1]] + m.v[t[2]]) / 3 +
        diag * 0.05 * V3(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5);
    s.cyl_tf = Tf::Identity();
    s.cyl_tf.linear() = randomRotation(rng);
    s.cyl_tf.translation() = s.mesh_tf * p;
    out.push_back(s);
  }
  const char* graze_kinds[] = {"face_cap", "face_barrel", "edge", "vertex"};
  for (int kind = 0; kind < 4; ++kind)
    for (int k = 0; k < per_kind; ++k) {
      Scene s;
      s.kind = graze_kinds[kind];
      s.mesh_tf = meshPose();
      s.r = diag * (0.002 + 0.03 * u01(rng));
      s.lz = diag * (0.005 + 0.1 * u01(rng));
      const double h = s.lz / 2;
      const fcl::Triangle t = randomTri();
      const V3 a = s.mesh_tf * m.v[t[0]], b = s.mesh_tf * m.v[t[1]],
               c = s.mesh_tf * m.v[t[2]];
      V3 n = (b - a).cross(c - a);
      if (!(n.norm() > 0)) n = V3::UnitZ();
      n.normalize();
      if (u01(rng) < 0.5) n = -n;
      Eigen::Matrix3d R;
      V3 centre;
      if (kind == 0) {  // cap plane on the face, touching at p
        double w0 = u01(rng), w1 = u01(rng);
        if (w0 + w1 > 1) {
          w0 = 1 - w0;
          w1 = 1 - w1;
        }
        const V3 p = a + w0 * (b - a) + w1 * (c - a);
        R = rotationWithZ(n, rng);
        centre = p + h * n;
      } else if (kind == 1) {  // barrel tangent to the face
        double w0 = u01(rng), w1 = u01(rng);
        if (w0 + w1 > 1) {
          w0 = 1 - w0;
          w1 = 1 - w1;
        }
        const V3 p = a + w0 * (b - a) + w1 * (c - a);
        const double ang = 6.283185307179586 * u01(rng);
        const V3 o = n.unitOrthogonal();
        R = rotationWithZ(std::cos(ang) * o + std::sin(ang) * n.cross(o), rng);
        centre = p + s.r * n;
      } else if (kind == 2) {  // barrel or rim against an edge
        const V3 p = a + u01(rng) * (b - a);
        const V3 e =
            (b - a).norm() > 0 ? V3((b - a).normalized()) : V3::UnitX();
        V3 out_dir = e.cross(n).normalized();
        if ((c - a).dot(out_dir) > 0) out_dir = -out_dir;  // away from c
        const V3 dir =
            (std::cos(0.7) * out_dir + std::sin(0.7) * n).normalized();
        R = rotationWithZ(e.cross(dir).normalized(), rng);
        centre = p + s.r * dir;
      } else {  // rim or barrel against a vertex
        V3 dir(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5);
        dir.normalize();
        R = rotationWithZ(dir.unitOrthogonal(), rng);
        centre = a + s.r * dir;
        if (u01(rng) < 0.5) {  // a rim corner on the vertex instead
          R = rotationWithZ(dir, rng);
          centre = a + h * dir + s.r * R.col(0);
        }
      }
      s.cyl_tf = Tf::Identity();
      s.cyl_tf.linear() = R;
      s.cyl_tf.translation() = centre;
      out.push_back(s);
    }
  for (int k = 0; k < per_kind; ++k) {
    // thin discs and needles crossing a random triangle.
    Scene s;
    s.kind = "thin";
    s.mesh_tf = meshPose();
    const bool disc = u01(rng) < 0.5;
    s.r = disc ? diag * 0.05 * (0.1 + u01(rng)) : diag * 1e-7;
    s.lz = disc ? diag * 1e-7 : diag * 0.05 * (0.1 + u01(rng));
    const fcl::Triangle t = randomTri();
    const V3 p = s.mesh_tf * ((m.v[t[0]] + m.v[t[1]] + m.v[t[2]]) / 3);
    s.cyl_tf = Tf::Identity();
    s.cyl_tf.linear() = randomRotation(rng);
    s.cyl_tf.translation() =
        p + diag * 0.01 * V3(u01(rng) - 0.5, u01(rng) - 0.5, u01(rng) - 0.5);
    out.push_back(s);
  }
  return out;
}

/// The mesh's triangle id of a contact, whichever side the mesh is on.
/// Identified through the CYLINDER's pointer: for AABB and KDOP meshes FCL
/// stores in Contact::o1 a temporary copy of the mesh (already deleted when
/// collide returns), not the user's BVHModel.
inline std::size_t meshId(const fcl::Contactd& c,
                          const fcl::CollisionGeometryd* cyl) {
  return std::size_t(c.o1 == cyl ? c.b2 : c.b1);
}

inline std::set<std::size_t> contactIds(const fcl::CollisionResultd& res,
                                        const fcl::CollisionGeometryd* cyl) {
  std::set<std::size_t> ids;
  for (std::size_t i = 0; i < res.numContacts(); ++i)
    ids.insert(meshId(res.getContact(i), cyl));
  return ids;
}

inline std::string describe(const Scene& s) {
  std::ostringstream os;
  os.precision(17);
  os << "kind=" << s.kind << " r=" << s.r << " lz=" << s.lz << "\ncyl R=\n"
     << s.cyl_tf.linear() << "\ncyl t=" << s.cyl_tf.translation().transpose()
     << "\nmesh R=\n"
     << s.mesh_tf.linear()
     << "\nmesh t=" << s.mesh_tf.translation().transpose();
  return os.str();
}

}  // namespace tricyl::fcltest
