// SPDX-License-Identifier: BSD-3-Clause
// Shared by tests/ompl_planner_test.cpp and bench/bench_planning.cpp
// (issue 22): the scenes of examples/ompl_planner as the exact oracle of
// compare/ sees them, near-surface robot poses, and a dense re-check of a
// planned path. Not part of the example: this is the checking machinery.
#pragma once

#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "harness.h"      // compare/: Case, Mesh, oracleTruth
#include "mesh_scenes.h"  // compare/: frameWithAxis
#include "planner.h"      // examples/ompl_planner
#include "scene.h"        // examples/ompl_planner

namespace planning {

/// A scene's mesh as compare/ holds it (triangle soup, FCL model built).
inline tricyl::compare::Mesh oracleMesh(const std::string& name,
                                        const example::Mesh& m) {
  tricyl::compare::Mesh out;
  out.name = name;
  auto v = [&m](std::size_t i) {
    const fcl::Vector3d& p = m.vertices[i];
    return tricyl::Vec3<double>{p.x(), p.y(), p.z()};
  };
  for (const auto& t : m.triangles)
    out.tris.push_back({v(t[0]), v(t[1]), v(t[2])});
  tricyl::compare::prepareMesh(out);
  return out;
}

inline tricyl::Pose<double> toPose(const fcl::Transform3d& tf) {
  tricyl::Pose<double> p{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.R[i][j] = tf.linear()(i, j);
  p.t = {tf.translation().x(), tf.translation().y(), tf.translation().z()};
  return p;
}

inline fcl::Transform3d toTransform(const tricyl::Pose<double>& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) tf.linear()(i, j) = p.R[i][j];
  tf.translation() = fcl::Vector3d(p.t.x, p.t.y, p.t.z);
  return tf;
}

/// The exact answer (GMP oracle of compare/oracle.h, every triangle the
/// conservative cull keeps): does the cylinder (radius, length) at `tf`
/// touch the mesh?
inline bool oracleCollides(const tricyl::compare::Mesh& mesh, double radius,
                           double length, const fcl::Transform3d& tf) {
  tricyl::compare::Case c;
  c.mesh = &mesh;
  c.k.cyl = {radius, length};
  c.k.pose = toPose(tf);
  return tricyl::compare::oracleTruth(c);
}

/// A pose of the cylinder (radius r, length lz) tangent to a face of the
/// mesh, then pushed along the face's normal by `offset` (> 0 out, < 0 in):
/// a cap on the face (axis along the normal), the side on it (axis across
/// the normal) or a rim point on it (axis at 45 degrees), as `feature`
/// says. Other faces may be closer: the oracle settles every answer.
struct NearPose {
  fcl::Transform3d tf;
  double offset;
  const char* feature;
};

/// Near-surface pose `index` of a seeded sequence: a uniformly random face
/// and point on it, |offset| log-uniform in [1e-12, 1e-2] times the mesh's
/// bounding-box diagonal (env.obj: 9e-9 .. 90), either sign.
inline NearPose nearPose(const tricyl::compare::Mesh& mesh, double r, double lz,
                         std::uint64_t seed, std::uint64_t index) {
  using tricyl::compare::meshes::V;
  namespace mc = tricyl::compare::meshes;
  tricyl::scenes::Rng g(seed * 0x9e3779b97f4a7c15ULL ^
                        (index + 1) * 0xd1b54a32d192ed03ULL);
  const auto& t = mesh.tris[std::size_t(g.integer(int(mesh.tris.size())))];
  double u = g.uniform(), v = g.uniform();
  if (u + v > 1) u = 1 - u, v = 1 - v;
  const V e1 = mc::sub(t.b, t.a), e2 = mc::sub(t.c, t.a);
  const V p = {t.a.x + u * e1.x + v * e2.x, t.a.y + u * e1.y + v * e2.y,
               t.a.z + u * e1.z + v * e2.z};
  V n = mc::cross(e1, e2);
  const double nn = mc::norm(n);
  n = nn > 0 ? V{n.x / nn, n.y / nn, n.z / nn} : V{0, 0, 1};
  const double diag = mc::norm(mc::sub(mesh.hi, mesh.lo));
  const double offset = (g.coin() ? 1 : -1) * diag * g.logUniform(1e-12, 1e-2);
  const V hint = {g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)};
  const double h = lz / 2, c45 = std::sqrt(0.5);
  NearPose out{};
  out.offset = offset;
  tricyl::Pose<double> pose{};
  double lift = 0;
  switch (g.integer(3)) {
    case 0:
      pose = mc::frameWithAxis(n, hint);
      lift = h;
      out.feature = "cap";
      break;
    case 1: {
      V axis = mc::cross(n, hint);
      const double na = mc::norm(axis);
      axis = na > 1e-3 ? V{axis.x / na, axis.y / na, axis.z / na} : V{0, 0, 1};
      pose = mc::frameWithAxis(axis, n);
      lift = r;
      out.feature = "side";
      break;
    }
    default: {
      V w = mc::cross(n, hint);
      const double nw = mc::norm(w);
      w = nw > 1e-3 ? V{w.x / nw, w.y / nw, w.z / nw} : V{1, 0, 0};
      pose = mc::frameWithAxis(
          {c45 * (n.x + w.x), c45 * (n.y + w.y), c45 * (n.z + w.z)}, n);
      lift = (h + r) * c45;  // the lowest rim point's height over the face
      out.feature = "rim";
      break;
    }
  }
  const double d = lift + offset;
  pose.t = {p.x + d * n.x, p.y + d * n.y, p.z + d * n.z};
  out.tf = toTransform(pose);
  return out;
}

/// The states of `path` densely: each motion cut, by the validator's own
/// bound, into steps of at most `step` of motion of any robot point.
inline std::vector<fcl::Transform3d> densePath(
    const ompl::geometric::PathGeometric& path,
    const example::CylinderMotionValidator& motion, double step) {
  const auto& si = path.getSpaceInformation();
  std::vector<fcl::Transform3d> out;
  ompl::base::State* s = si->allocState();
  for (std::size_t i = 0; i + 1 < path.getStateCount(); ++i) {
    const auto* a = path.getState(i);
    const auto* b = path.getState(i + 1);
    const unsigned n = unsigned(std::ceil(motion.sweep(a, b) / step)) + 1;
    for (unsigned j = 0; j < n; ++j) {
      si->getStateSpace()->interpolate(a, b, double(j) / n, s);
      out.push_back(example::toTransform(s));
    }
  }
  if (path.getStateCount() > 0)
    out.push_back(
        example::toTransform(path.getState(path.getStateCount() - 1)));
  si->freeState(s);
  return out;
}

/// A scene's planning problem as examples/ompl_planner sets it up: SE(3)
/// over the scene's box, the grown cylinder checked by `checker` (made by
/// the caller from the space information, so that it can wrap
/// example::CylinderValidityChecker), the motion validator at the scene's
/// step, RRTConnect.
struct Problem {
  std::shared_ptr<ompl::geometric::SimpleSetup> setup;
  std::shared_ptr<example::CylinderMotionValidator> motion;
};

template <class MakeChecker>
Problem makeProblem(const example::Scene& scene, MakeChecker&& make_checker) {
  namespace ob = ompl::base;
  Problem p;
  p.setup = std::make_shared<ompl::geometric::SimpleSetup>(
      example::makeSpace(scene.lo, scene.hi, scene.reach()));
  const ob::SpaceInformationPtr si = p.setup->getSpaceInformation();
  si->setStateValidityChecker(make_checker(si));
  p.motion = std::make_shared<example::CylinderMotionValidator>(
      si, scene.reach(), scene.step);
  si->setMotionValidator(p.motion);
  ob::ScopedState<ob::SE3StateSpace> start(p.setup->getStateSpace()),
      goal(p.setup->getStateSpace());
  example::setState(start.get(), scene.start, scene.start_axis);
  example::setState(goal.get(), scene.goal, scene.goal_axis);
  p.setup->setStartAndGoalStates(start, goal);
  p.setup->setPlanner(std::make_shared<ompl::geometric::RRTConnect>(si));
  return p;
}

/// Runs the planner to its first solution or `max_iterations` evaluations
/// of the termination condition (once per RRTConnect iteration): a fixed
/// amount of work, whatever the speed of the checker. True if solved.
inline bool solveFirst(ompl::geometric::SimpleSetup& setup,
                       unsigned long max_iterations) {
  unsigned long asked = 0;
  const ompl::base::PlannerStatus status =
      setup.solve(ompl::base::PlannerTerminationCondition(
          [&asked, max_iterations] { return ++asked > max_iterations; }));
  return status == ompl::base::PlannerStatus::EXACT_SOLUTION;
}

}  // namespace planning
