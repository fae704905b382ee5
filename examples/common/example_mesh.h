// SPDX-License-Identifier: BSD-3-Clause
// Shared by the FCL examples: OBJ files (through the repository's reader), a
// procedural mesh
// and the fcl::BVHModel they become. Not part of tricyl's API.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <exception>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "obj_mesh.h"

namespace example {

struct Mesh {
  std::vector<fcl::Vector3d> vertices;
  std::vector<fcl::Triangle> triangles;
};

/// Reads the triangles of an OBJ file (the repository's shared reader,
/// support/obj_mesh.h, on tinyobjloader). Returns false when the file cannot
/// be read or holds no triangle.
inline bool readObj(const std::string& path, Mesh* mesh) {
  tricyl::obj::Mesh m;
  try {
    m = tricyl::obj::read(path);
  } catch (const std::exception&) {
    return false;
  }
  Mesh out;
  for (std::size_t i = 0; i < m.numVertices(); ++i)
    out.vertices.emplace_back(m.vertices[3 * i], m.vertices[3 * i + 1],
                              m.vertices[3 * i + 2]);
  for (std::size_t t = 0; t < m.numTriangles(); ++t)
    out.triangles.emplace_back(m.indices[3 * t], m.indices[3 * t + 1],
                               m.indices[3 * t + 2]);
  *mesh = std::move(out);
  return true;
}

/// A square terrain on [-2, 2]^2 (0.25 spacing) with a pyramid bump
/// z = max(0, 1 - |x| - |y|): every coordinate is a dyadic rational, so the
/// mesh, and every answer about it, is the same on every machine.
inline Mesh pyramidTerrain() {
  Mesh m;
  constexpr int n = 16;  // cells per side (a constant: no capture needed)
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = -2 + 0.25 * i, y = -2 + 0.25 * j;
      const double h = 1 - std::abs(x) - std::abs(y);
      m.vertices.emplace_back(x, y, h > 0 ? h : 0.0);
    }
  auto at = [](int i, int j) {
    return static_cast<std::size_t>(j * (n + 1) + i);
  };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      m.triangles.emplace_back(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      m.triangles.emplace_back(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  return m;
}

/// An axis-aligned box of half-extents (hx, hy, hz) centred at the origin,
/// as 12 triangles (a mesh, not fcl::Box: the pair tricyl answers is
/// cylinder vs mesh triangle).
inline Mesh boxMesh(double hx, double hy, double hz) {
  Mesh m;
  for (int k = 0; k < 8; ++k)
    m.vertices.emplace_back(k & 1 ? hx : -hx, k & 2 ? hy : -hy,
                            k & 4 ? hz : -hz);
  const std::size_t f[12][3] = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6},
                                {0, 1, 5}, {0, 5, 4}, {2, 6, 7}, {2, 7, 3},
                                {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  for (const auto& t : f) m.triangles.emplace_back(t[0], t[1], t[2]);
  return m;
}

/// The mesh split into its connected parts (triangles sharing a vertex
/// position, since OBJ files often repeat vertices per face), each a mesh of
/// its own: the bodies a planning scene registers one by one. Parts keep the
/// order of their first triangle.
inline std::vector<Mesh> connectedParts(const Mesh& mesh) {
  // One id per distinct position, then union-find over the triangles.
  std::map<std::array<double, 3>, std::size_t> ids;
  std::vector<std::size_t> id(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const auto& v = mesh.vertices[i];
    id[i] = ids.emplace(std::array<double, 3>{v.x(), v.y(), v.z()}, ids.size())
                .first->second;
  }
  std::vector<std::size_t> up(ids.size());
  for (std::size_t i = 0; i < up.size(); ++i) up[i] = i;
  auto root = [&up](std::size_t i) {
    while (up[i] != i) i = up[i] = up[up[i]];
    return i;
  };
  for (const auto& t : mesh.triangles)
    for (int k = 1; k < 3; ++k) up[root(id[t[k]])] = root(id[t[0]]);
  std::map<std::size_t, std::size_t> part_of;  // root -> part number
  std::vector<Mesh> parts;
  std::vector<std::map<std::size_t, std::size_t>> remap;  // vertex -> local
  for (const auto& t : mesh.triangles) {
    const auto [it, added] = part_of.emplace(root(id[t[0]]), parts.size());
    if (added) {
      parts.emplace_back();
      remap.emplace_back();
    }
    Mesh& part = parts[it->second];
    std::size_t local[3];
    for (int k = 0; k < 3; ++k) {
      const auto [v, fresh] =
          remap[it->second].emplace(t[k], part.vertices.size());
      if (fresh) part.vertices.push_back(mesh.vertices[t[k]]);
      local[k] = v->second;
    }
    part.triangles.emplace_back(local[0], local[1], local[2]);
  }
  return parts;
}

/// The mesh as FCL's usual BVH (OBBRSS, what MoveIt uses for meshes).
inline std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> toBVH(const Mesh& mesh) {
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel();
  model->addSubModel(mesh.vertices, mesh.triangles);
  model->endModel();
  return model;
}

}  // namespace example
