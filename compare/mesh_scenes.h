// SPDX-License-Identifier: BSD-3-Clause
// The `mesh` family of tricyl-compare: a cylinder against a triangle mesh.
// Header-only, no FCL: built-in procedural meshes, OBJ files as triangle
// soups (support/obj_mesh.h: link tricyl_obj_mesh), the seeded
// placement of a cylinder near a mesh, and the conservative bounding-sphere
// cull shared by the oracle and the brute-force tricyl mesh scan.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "obj_mesh.h"
#include "scenes.h"
#include "tricyl/types.h"

namespace tricyl::compare::meshes {

using V = Vec3<double>;
using T = Triangle<double>;

/// An OBJ file (obj::read) as a triangle soup, in the file's face order.
/// Throws std::runtime_error (obj::read).
inline std::vector<T> readObj(const std::string& path) {
  const obj::Mesh m = obj::read(path);
  std::vector<T> tris;
  tris.reserve(m.numTriangles());
  auto vertex = [&m](std::uint32_t i) {
    return V{m.vertices[3 * i], m.vertices[3 * i + 1], m.vertices[3 * i + 2]};
  };
  for (std::size_t t = 0; t < m.numTriangles(); ++t)
    tris.push_back({vertex(m.indices[3 * t]), vertex(m.indices[3 * t + 1]),
                    vertex(m.indices[3 * t + 2])});
  return tris;
}

/// The axis-aligned bounding box of a triangle soup (non-empty).
inline void bounds(const std::vector<T>& tris, V* lo, V* hi) {
  *lo = *hi = tris.at(0).a;
  for (const T& t : tris)
    for (const V& p : {t.a, t.b, t.c}) {
      *lo = {std::fmin(lo->x, p.x), std::fmin(lo->y, p.y),
             std::fmin(lo->z, p.z)};
      *hi = {std::fmax(hi->x, p.x), std::fmax(hi->y, p.y),
             std::fmax(hi->z, p.z)};
    }
}

/// A triangle soup as an indexed mesh, equal vertices merged (as a mesh file
/// has them: readObj expands faces into triangles): `v` holds xyz per
/// vertex, `f` three vertex numbers per triangle, in the soup's order.
struct IndexedMesh {
  std::vector<double> v;
  std::vector<std::uint32_t> f;
};

inline IndexedMesh indexed(const std::vector<T>& tris) {
  IndexedMesh m;
  std::map<std::array<double, 3>, std::uint32_t> ids;
  for (const T& t : tris)
    for (const V& p : {t.a, t.b, t.c}) {
      const auto [it, added] = ids.emplace(std::array<double, 3>{p.x, p.y, p.z},
                                           std::uint32_t(m.v.size() / 3));
      if (added) m.v.insert(m.v.end(), {p.x, p.y, p.z});
      m.f.push_back(it->second);
    }
  return m;
}

/// A grid surface (u, v) -> point, split into two triangles per cell.
template <class F>
std::vector<T> gridSurface(int nu, int nv, F point) {
  std::vector<T> tris;
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      const V p00 = point(i, j), p10 = point(i + 1, j);
      const V p01 = point(i, j + 1), p11 = point(i + 1, j + 1);
      tris.push_back({p00, p10, p11});
      tris.push_back({p00, p11, p01});
    }
  return tris;
}

/// Built-in meshes: a UV sphere (radius 1), a torus (1, 0.3) and a wavy
/// terrain (4 x 4, amplitude 0.2), each about a thousand triangles.
inline std::vector<std::pair<std::string, std::vector<T>>> builtinMeshes() {
  const double pi = std::acos(-1.0);
  std::vector<std::pair<std::string, std::vector<T>>> out;
  out.emplace_back("sphere", gridSurface(32, 16, [&](int i, int j) {
                     const double u = 2 * pi * i / 32, v = pi * j / 16;
                     return V{std::cos(u) * std::sin(v),
                              std::sin(u) * std::sin(v), std::cos(v)};
                   }));
  out.emplace_back(
      "torus", gridSurface(36, 16, [&](int i, int j) {
        const double u = 2 * pi * i / 36, v = 2 * pi * j / 16;
        const double w = 1 + 0.3 * std::cos(v);
        return V{w * std::cos(u), w * std::sin(u), 0.3 * std::sin(v)};
      }));
  out.emplace_back("terrain", gridSurface(24, 24, [&](int i, int j) {
                     const double x = -2 + 4.0 * i / 24, y = -2 + 4.0 * j / 24;
                     return V{x, y,
                              0.2 * std::sin(3 * x) * std::cos(2 * y) +
                                  0.05 * std::sin(7 * x + 5 * y)};
                   }));
  return out;
}

inline V sub(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
inline V cross(V a, V b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double norm(V a) { return std::sqrt(a.x * a.x + a.y * a.y + a.z * a.z); }

/// Rotation whose third column (the cylinder's axis in the world) is `z`.
inline Pose<double> frameWithAxis(V z, V hint) {
  V x = cross(hint, z);
  if (norm(x) < 1e-3) x = cross(V{1, 0, 0}, z);
  if (norm(x) < 1e-3) x = cross(V{0, 1, 0}, z);
  const double nx = norm(x);
  x = {x.x / nx, x.y / nx, x.z / nx};
  const V y = cross(z, x);
  Pose<double> p{};
  const V cols[3] = {x, y, z};
  for (int j = 0; j < 3; ++j) {
    p.R[0][j] = cols[j].x;
    p.R[1][j] = cols[j].y;
    p.R[2][j] = cols[j].z;
  }
  return p;
}

/// Places a cylinder near the surface of a mesh (box `lo`..`hi`) at a random
/// point p of a random triangle with unit normal n; the cylinder's size is
/// 0.2 % .. 10 % of the box diagonal. Half the cases are loose (a random
/// rotation, centre moved along n by up to one cylinder size either way);
/// half touch the triangle's plane at p with a cap (axis along n, centre at
/// p + n h (1 + delta)), the side (axis across n, centre at p + n r (1 +
/// delta)) or a rim (axis tilted by 45 degrees), pushed out or in by a
/// relative offset delta drawn as in the near family. Other triangles of the
/// mesh may be closer, so delta is only the intent: error sizes of mesh
/// cases are measured by the oracle (errorSize), not taken from delta.
/// Deterministic per (seed, index).
inline scenes::TriCase meshCase(const std::vector<T>& tris, V lo, V hi,
                                std::uint64_t seed, std::uint64_t index) {
  scenes::Rng g(seed * 0xd1b54a32d192ed03ULL ^ 0x6d657368ULL ^
                (index * 0x9e3779b97f4a7c15ULL));
  const double diag = norm(sub(hi, lo));
  const T& t = tris[size_t(g.integer(int(tris.size())))];
  double u = g.uniform(0, 1), v = g.uniform(0, 1);
  if (u + v > 1) u = 1 - u, v = 1 - v;
  const V e1 = sub(t.b, t.a), e2 = sub(t.c, t.a);
  V p = {t.a.x + u * e1.x + v * e2.x, t.a.y + u * e1.y + v * e2.y,
         t.a.z + u * e1.z + v * e2.z};
  V n = cross(e1, e2);
  const double nn = norm(n);
  n = nn > 0 ? V{n.x / nn, n.y / nn, n.z / nn} : V{0, 0, 1};
  const double size = diag * g.logUniform(0.002, 0.1);
  scenes::TriCase k;
  k.cyl = {size * g.uniform(0.1, 0.5), size * g.uniform(0.1, 1.0)};
  k.tri = {p, p, p};  // unused for mesh cases
  const double r = k.cyl.radius, h = k.cyl.lz / 2;
  auto at = [&](double off) {
    return V{p.x + off * n.x, p.y + off * n.y, p.z + off * n.z};
  };
  const int kind = g.integer(6);
  if (kind < 3) {
    k.pose = scenes::internal::randomPose(g, 0);
    k.pose.t = at(size * g.uniform(-1, 1));
    k.feature = "loose";
    return k;
  }
  const double s = 1 + scenes::internal::nearDelta(g);
  const V hint = scenes::internal::randomUnit(g);
  if (kind == 3) {  // a cap on the plane
    k.pose = frameWithAxis(n, hint);
    k.pose.t = at(h * s);
    k.feature = "cap_on_face";
  } else if (kind == 4) {  // the side on the plane: axis across n
    V axis = cross(n, hint);
    const double na = norm(axis);
    axis = na > 1e-3 ? V{axis.x / na, axis.y / na, axis.z / na} : V{0, 0, 1};
    k.pose = frameWithAxis(axis, n);
    k.pose.t = at(r * s);
    k.feature = "side_on_face";
  } else {  // a rim point on the plane: axis at 45 degrees to n
    V w = cross(n, hint);
    const double nw = norm(w);
    w = nw > 1e-3 ? V{w.x / nw, w.y / nw, w.z / nw} : V{1, 0, 0};
    const double c = std::sqrt(0.5);
    const V axis = {c * (n.x + w.x), c * (n.y + w.y), c * (n.z + w.z)};
    k.pose = frameWithAxis(axis, n);
    // The rim point nearest the plane is at distance (h + r) cos 45 from
    // the centre along n.
    k.pose.t = at((h + r) * c * s);
    k.feature = "rim_on_face";
  }
  return k;
}

/// A conservative cull: false only if the triangle certainly misses the
/// cylinder. The cylinder lies in the ball about t of radius
/// sqrt(r^2 + (lz/2)^2) (for any R within 1e-6 of orthonormal); the test
/// compares the distance from t to the triangle's box with that radius
/// inflated by 1e-6 relative plus 1e-12 of the coordinates' magnitude, far
/// above the rounding of this double arithmetic.
struct Cull {
  V c;
  double reach;
  explicit Cull(const scenes::TriCase& k) : c(k.pose.t) {
    const double h = k.cyl.lz / 2;
    const double mag =
        std::fmax(std::fabs(c.x), std::fmax(std::fabs(c.y), std::fabs(c.z)));
    reach = std::sqrt(k.cyl.radius * k.cyl.radius + h * h) * (1 + 1e-6) +
            1e-12 * mag;
  }
  bool mayTouch(const T& t) const {
    auto axis = [](double p, double a, double b, double cc) {
      const double lo = std::fmin(a, std::fmin(b, cc));
      const double hi = std::fmax(a, std::fmax(b, cc));
      const double slack = 1e-12 * std::fmax(std::fabs(lo), std::fabs(hi));
      return p < lo ? lo - p - slack : (p > hi ? p - hi - slack : 0.0);
    };
    const double dx = axis(c.x, t.a.x, t.b.x, t.c.x);
    const double dy = axis(c.y, t.a.y, t.b.y, t.c.y);
    const double dz = axis(c.z, t.a.z, t.b.z, t.c.z);
    if (dx > reach || dy > reach || dz > reach) return false;
    return dx * dx + dy * dy + dz * dz <= reach * reach * (1 + 1e-9);
  }
};

}  // namespace tricyl::compare::meshes
