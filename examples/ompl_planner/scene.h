// SPDX-License-Identifier: BSD-3-Clause
// The planning problems of the OMPL example, its test and the planning
// benchmark (issue 22): a rigid cylinder, sized from the mesh's bounding-box
// diagonal, between a start and a goal chosen in the mesh's own coordinates.
#pragma once

#include <cmath>
#include <string>

#include "example_mesh.h"

namespace example {

struct Scene {
  std::string name;
  double radius = 0, length = 0;  ///< the robot cylinder
  /// Motion resolution: no point of the robot moves more than `step`
  /// between two checked states; the checked cylinder is grown by step / 2.
  double step = 0;
  fcl::Vector3d lo, hi;  ///< the box the robot's centre stays in
  fcl::Vector3d start, start_axis, goal, goal_axis;

  double checkedRadius() const { return radius + step / 2; }
  double checkedLength() const { return length + step; }
  /// Farthest point of the checked cylinder from its centre.
  double reach() const {
    return std::hypot(checkedRadius(), checkedLength() / 2);
  }
};

/// The scene for a mesh file name: "env" (FCL's office environment:
/// from under one seat, lying between its legs, to under another; the seats
/// are 10 thick at z = 500..510 on 20-wide legs 300 apart) or "bunny"
/// (around the Stanford bunny inside its own bounding box, from a lower
/// front corner to the opposite lower back corner). Returns false for
/// another name.
inline bool sceneFor(const std::string& name, const Mesh& mesh, Scene* out) {
  fcl::Vector3d lo = mesh.vertices[0], hi = lo;
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const double diag = (hi - lo).norm();
  Scene s;
  s.name = name;
  s.radius = 0.009 * diag;
  s.length = 0.06 * diag;
  s.step = s.radius / 4;
  s.lo = lo;
  s.hi = hi;
  if (name == "env") {
    s.hi.z() = 1000;  // the furnished part of the room: twice seat height
    s.start = {-1500, 1300, 250};  // under the seat at x -1700..-1300
    s.start_axis = {1, 0, 0};
    s.goal = {-500, 1300, 250};  // under the seat at x -700..-300
    s.goal_axis = {0, 1, 0};
  } else if (name == "bunny") {
    const fcl::Vector3d m = fcl::Vector3d::Constant(1.2 * s.reach());
    s.start = lo + m;
    s.start_axis = {1, 0, 0};
    s.goal = {hi.x() - m.x(), lo.y() + m.y(), hi.z() - m.z()};
    s.goal_axis = {0, 0, 1};
  } else {
    return false;
  }
  *out = s;
  return true;
}

}  // namespace example
