// SPDX-License-Identifier: BSD-3-Clause
// The sphere cases of compare/query_scenes.h in FCL's types, for FCL 0.7's
// own sphere-cylinder test (primitive_shape_algorithm, tolerance-based:
// the one fcl::collide uses for this pair). Shared by bench_queries and
// tricyl-query-stage-costs.
#pragma once

#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/narrowphase/detail/primitive_shape_algorithm/sphere_cylinder.h>

#include <cstddef>
#include <vector>

#include "query_scenes.h"

namespace tricyl::bench {

class FclSphereCases {
 public:
  explicit FclSphereCases(const std::vector<qscenes::QueryCase>& cs) {
    for (const qscenes::QueryCase& c : cs) {
      sph_.emplace_back(c.rho);
      cyl_.emplace_back(c.cyl.radius, c.cyl.lz);
      fcl::Transform3d s = fcl::Transform3d::Identity();
      s.translation() = fcl::Vector3d(c.p.x, c.p.y, c.p.z);
      X_FS_.push_back(s);
      fcl::Transform3d t = fcl::Transform3d::Identity();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t.linear()(i, j) = c.pose.R[i][j];
      t.translation() = fcl::Vector3d(c.pose.t.x, c.pose.t.y, c.pose.t.z);
      X_FC_.push_back(t);
    }
  }
  /// FCL's answer for case i.
  bool intersect(std::size_t i) const {
    return fcl::detail::sphereCylinderIntersect<double>(
        sph_[i], X_FS_[i], cyl_[i], X_FC_[i], nullptr);
  }

 private:
  std::vector<fcl::Sphered> sph_;
  std::vector<fcl::Cylinderd> cyl_;
  std::vector<fcl::Transform3d> X_FS_, X_FC_;
};

}  // namespace tricyl::bench
