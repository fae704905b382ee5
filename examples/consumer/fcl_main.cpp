// SPDX-License-Identifier: BSD-3-Clause
// tricyl::fcl through the installed package: tricyl::collide on a cylinder
// and a two-triangle mesh, then the same pair in a broadphase manager with
// tricyl's callback.
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <tricyl/fcl_solver.h>

#include <cstdio>
#include <memory>

int main() {
  auto floor = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  const std::vector<fcl::Vector3d> v = {
      {-1, -1, 0}, {1, -1, 0}, {1, 1, 0}, {-1, 1, 0}};
  const std::vector<fcl::Triangle> t = {{0, 1, 2}, {0, 2, 3}};
  floor->beginModel();
  floor->addSubModel(v, t);
  floor->endModel();
  fcl::CollisionObjectd floor_obj(floor, fcl::Transform3d::Identity());
  auto cyl = std::make_shared<fcl::Cylinderd>(0.25, 1.0);
  for (const double z : {0.5, 0.5 + 1e-12, 0.25}) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.translation() = fcl::Vector3d(0.25, 0.5, z);
    fcl::CollisionObjectd cyl_obj(cyl, tf);
    fcl::CollisionRequestd request;
    fcl::CollisionResultd result;
    tricyl::collide(&cyl_obj, &floor_obj, request, result);
    tricyl::DefaultCollisionData<double> data;
    fcl::DynamicAABBTreeCollisionManagerd manager;
    manager.registerObject(&floor_obj);
    manager.registerObject(&cyl_obj);
    manager.setup();
    manager.collide(&data, tricyl::DefaultCollisionFunction<double>);
    std::printf("bottom at z=%s: collide %s, broadphase %s\n",
                z == 0.5    ? "0"
                : z == 0.25 ? "-0.25"
                            : "1e-12",
                result.isCollision() ? "collision" : "free",
                data.result.isCollision() ? "collision" : "free");
  }
  return 0;
}
