// SPDX-License-Identifier: BSD-3-Clause
// The one Wavefront OBJ reader of the repository's tools (tricyl-compare,
// the tests, the benchmarks and the examples), on tinyobjloader. Not part of
// tricyl's API or install.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tricyl::obj {

/// An indexed triangle mesh as read from a file.
struct Mesh {
  std::vector<double> vertices;        ///< x y z per vertex
  std::vector<std::uint32_t> indices;  ///< three vertex numbers per triangle
  std::size_t numVertices() const { return vertices.size() / 3; }
  std::size_t numTriangles() const { return indices.size() / 3; }
};

/// Reads the vertices and faces of an OBJ file (every object and group;
/// polygons are split into triangles by tinyobjloader; normals, texture
/// coordinates and materials are ignored). Vertex coordinates are parsed
/// in double. Throws std::runtime_error when the file cannot be read, has
/// an index outside its vertices, or holds no triangle.
Mesh read(const std::string& path);

}  // namespace tricyl::obj
