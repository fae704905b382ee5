// SPDX-License-Identifier: BSD-3-Clause
// The triangle families' cases as FCL's libccd solver takes them (shared by
// bench_triangle_cylinder and tricyl-stage-costs).
#pragma once

#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <vector>

#include "scenes.h"
#include "walk.h"

namespace tricyl::bench {

// The cases as FCL takes them (structure of arrays), for the paired rows,
// and one pass over all of them in a walk's order: the FCL block of a
// paired iteration. Returns the number of hits.
struct FclCases {
  std::vector<fcl::Cylinderd> cyl;
  std::vector<fcl::Transform3d> tf;
  std::vector<fcl::Vector3d> p;  // three per case

  explicit FclCases(const std::vector<scenes::TriCase>& k) {
    for (const scenes::TriCase& c : k) {
      fcl::Transform3d t = fcl::Transform3d::Identity();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) t.linear()(i, j) = c.pose.R[i][j];
      t.translation() = fcl::Vector3d(c.pose.t.x, c.pose.t.y, c.pose.t.z);
      cyl.emplace_back(c.cyl.radius, c.cyl.lz);
      tf.push_back(t);
      for (const auto& q : {c.tri.a, c.tri.b, c.tri.c})
        p.emplace_back(q.x, q.y, q.z);
    }
  }
  long pass(const fcl::detail::GJKSolver_libccd<double>& solver,
            Walk& walk) const {
    long hits = 0;
    for (std::size_t n = 0; n < cyl.size(); ++n) {
      const std::size_t i = walk.next();
      hits += solver.shapeTriangleIntersect(cyl[i], tf[i], p[3 * i],
                                            p[3 * i + 1], p[3 * i + 2], nullptr,
                                            nullptr, nullptr);
    }
    return hits;
  }
};

}  // namespace tricyl::bench
