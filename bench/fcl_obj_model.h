// SPDX-License-Identifier: BSD-3-Clause
// An OBJ file of ../shared/data/meshes as an FCL BVHModel<OBBRSS>, with its
// vertices, triangles and bounding-box diagonal: shared by the FCL
// benchmarks (bench_fcl_collide, bench_fcl_distance).
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/math/bv/OBBRSS.h>

#include <exception>
#include <memory>
#include <string>
#include <vector>

#include "obj_mesh.h"

namespace tricyl::bench {

struct FclObjModel {
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> model;
  std::vector<fcl::Vector3d> v;
  std::vector<fcl::Triangle> t;
  double diag = 0;  // the bounding box's diagonal
};

/// Reads TRICYL_MESH_DIR/file (tinyobjloader, support/obj_mesh.h) and builds
/// the model; false (and `out` untouched) when the file cannot be read.
inline bool loadFclObj(const std::string& file, FclObjModel* out) {
  obj::Mesh f;
  try {
    f = obj::read(std::string(TRICYL_MESH_DIR) + "/" + file);
  } catch (const std::exception&) {
    return false;
  }
  FclObjModel d;
  for (std::size_t i = 0; i < f.numVertices(); ++i)
    d.v.emplace_back(f.vertices[3 * i], f.vertices[3 * i + 1],
                     f.vertices[3 * i + 2]);
  for (std::size_t k = 0; k < f.numTriangles(); ++k)
    d.t.emplace_back(f.indices[3 * k], f.indices[3 * k + 1],
                     f.indices[3 * k + 2]);
  if (d.v.empty()) return false;
  d.model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  d.model->beginModel(int(d.t.size()), int(d.v.size()));
  d.model->addSubModel(d.v, d.t);
  d.model->endModel();
  fcl::Vector3d lo = d.v[0], hi = d.v[0];
  for (const fcl::Vector3d& p : d.v) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
  d.diag = (hi - lo).norm();
  *out = std::move(d);
  return true;
}

}  // namespace tricyl::bench
