// SPDX-License-Identifier: BSD-3-Clause
#include "obj_mesh.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string>
#include <type_traits>

static_assert(std::is_same_v<tinyobj::real_t, double>,
              "link tinyobjloader::tinyobjloader_double: coordinates must not "
              "be rounded to float");

namespace tricyl::obj {

namespace {

/// The `v` lines' coordinates parsed with std::strtod (correctly rounded).
/// tinyobjloader's own number parser is not: on the shared bunny.obj it
/// differs from the nearest double on about half of the coordinates, by up
/// to 2 ulps, and a test of an exact predicate must take the file's numbers
/// as written. tinyobjloader still parses the structure (faces, negative
/// indices, polygons, groups); these values replace its coordinates, after
/// a check that both read the same vertices (same count, each value within
/// 8 ulps of tinyobjloader's).
std::vector<double> exactCoordinates(const std::string& path,
                                     const std::vector<double>& approx) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open mesh file " + path);
  std::vector<double> out;
  out.reserve(approx.size());
  std::string line;
  while (std::getline(in, line)) {
    std::size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line[i] != 'v' || i + 1 >= line.size() ||
        (line[i + 1] != ' ' && line[i + 1] != '\t'))
      continue;
    const char* p = line.c_str() + i + 1;
    for (int k = 0; k < 3; ++k) {
      char* end = nullptr;
      const double v = std::strtod(p, &end);
      if (end == p) throw std::runtime_error("bad vertex line in " + path);
      out.push_back(v);
      p = end;
    }
  }
  if (out.size() != approx.size())
    throw std::runtime_error("vertex count mismatch reading " + path);
  for (std::size_t k = 0; k < out.size(); ++k) {
    const double tol = 8 * std::ldexp(1.0, -52) * std::fabs(out[k]) + 1e-300;
    if (!(std::fabs(out[k] - approx[k]) <= tol))
      throw std::runtime_error("vertex values disagree reading " + path);
  }
  return out;
}

}  // namespace

Mesh read(const std::string& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  config.mtl_search_path = "";  // materials are not used
  tinyobj::ObjReader reader;
  if (!reader.ParseFromFile(path, config))
    throw std::runtime_error("cannot read mesh file " + path + ": " +
                             reader.Error());
  const auto& attrib = reader.GetAttrib();
  Mesh m;
  m.vertices = exactCoordinates(
      path,
      std::vector<double>(attrib.vertices.begin(), attrib.vertices.end()));
  const std::size_t nv = m.numVertices();
  for (const auto& shape : reader.GetShapes()) {
    const auto& mesh = shape.mesh;
    std::size_t at = 0;
    for (const unsigned char n : mesh.num_face_vertices) {
      // With triangulate = true every face has three vertices; a face
      // tinyobjloader could not split (fewer than three) is skipped.
      if (n == 3) {
        for (std::size_t k = 0; k < 3; ++k) {
          const int i = mesh.indices[at + k].vertex_index;
          if (i < 0 || std::size_t(i) >= nv)
            throw std::runtime_error("bad face index in " + path);
          m.indices.push_back(std::uint32_t(i));
        }
      }
      at += n;
    }
  }
  if (m.indices.empty()) throw std::runtime_error("no triangles in " + path);
  return m;
}

}  // namespace tricyl::obj
