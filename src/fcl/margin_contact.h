// SPDX-License-Identifier: BSD-3-Clause
// The contact a margin collide reports for a triangle that lies within the
// margin of the cylinder without touching it (fcl_solver.h, MARGIN
// COLLIDE). Internal: shared by mesh_collide.cpp and fcl_solver_impl.h.
#pragma once

#include <fcl/common/types.h>

#include <cmath>

#include "tricyl/triangle_cylinder_distance.h"
#include "tricyl/types.h"

namespace tricyl {
namespace margin_detail {

/// pos: the midpoint of the two nearest points (world frame); normal: unit,
/// from the triangle's nearest point toward the cylinder's (FCL's Contact
/// convention, o1 = mesh toward o2 = cylinder); depth: minus the distance,
/// so -margin <= depth < 0 ("negative penetration", the clearance).
template <class S>
struct MarginContact {
  fcl::Vector3<S> pos;
  fcl::Vector3<S> normal;
  S depth;
};

template <class S>
MarginContact<S> marginContact(const Cylinder<S>& cyl, const Pose<S>& pose,
                               const Triangle<S>& tri) {
  MarginContact<S> c;
  DistanceResult<S> d;
  if (tryDistance(cyl, pose, tri, &d) != Answer::kDisjoint) {
    // Not reached for the inputs the callers pass (finite, disjoint); a
    // finite placeholder all the same.
    c.pos = fcl::Vector3<S>(pose.t.x, pose.t.y, pose.t.z);
    c.normal = fcl::Vector3<S>(0, 0, 1);
    c.depth = 0;
    return c;
  }
  const fcl::Vector3<S> pc(d.point_on_cylinder.x, d.point_on_cylinder.y,
                           d.point_on_cylinder.z);
  const fcl::Vector3<S> pt(d.point_on_triangle.x, d.point_on_triangle.y,
                           d.point_on_triangle.z);
  c.pos = S(0.5) * (pc + pt);
  const fcl::Vector3<S> n = pc - pt;
  const S len = n.norm();
  c.normal = (len > 0 && std::isfinite(len)) ? fcl::Vector3<S>(n / len)
                                             : fcl::Vector3<S>(0, 0, 1);
  c.depth = -d.distance;
  return c;
}

}  // namespace margin_detail
}  // namespace tricyl
