// SPDX-License-Identifier: BSD-3-Clause
// tricyl::fcl for float through the installed package: tricyl::collide on
// float objects (a cylinder over a two-triangle floor, a BVHModel<OBBRSSf>),
// the same pair through fcl::collide with a tricyl::Solver<float>, and a
// TriangleP (which FCL 0.7 itself cannot collide with a cylinder).
#include <fcl/geometry/bvh/BVH_model.h>
#include <tricyl/fcl_solver.h>

#include <cstdio>
#include <memory>

int main() {
  using Tf = fcl::Transform3f;
  auto floor = std::make_shared<fcl::BVHModel<fcl::OBBRSSf>>();
  const std::vector<fcl::Vector3f> v = {
      {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<fcl::Triangle> t = {{0, 1, 2}, {0, 2, 3}};
  floor->beginModel();
  floor->addSubModel(v, t);
  floor->endModel();
  auto tri = std::make_shared<fcl::TrianglePf>(fcl::Vector3f(-1, -1, 0),
                                               fcl::Vector3f(1, -1, 0),
                                               fcl::Vector3f(0, 1, 0));
  auto cyl = std::make_shared<fcl::Cylinderf>(0.25f, 1.0f);
  const fcl::CollisionObjectf floor_obj(floor, Tf::Identity());
  const fcl::CollisionObjectf tri_obj(tri, Tf::Identity());
  const tricyl::Solver<float> solver;
  // The bottom cap exactly on the floor, one float step above it, below it.
  for (const float z : {0.5f, 0.50000006f, 0.25f}) {
    Tf tf = Tf::Identity();
    tf.translation() = fcl::Vector3f(0.25f, -0.5f, z);
    const fcl::CollisionObjectf cyl_obj(cyl, tf);
    const fcl::CollisionRequestf request;
    fcl::CollisionResultf a, b, c;
    tricyl::collide(&cyl_obj, &floor_obj, request, a);
    fcl::collide(&cyl_obj, &floor_obj, &solver, request, b);
    tricyl::collide(&tri_obj, &cyl_obj, request, c);
    std::printf("bottom %s: collide %s, Solver<float> %s, TriangleP %s\n",
                z == 0.5f  ? "on the floor"
                : z > 0.5f ? "one float step above"
                           : "0.25 below",
                a.isCollision() ? "collision" : "free",
                b.isCollision() ? "collision" : "free",
                c.isCollision() ? "collision" : "free");
  }
  return 0;
}
