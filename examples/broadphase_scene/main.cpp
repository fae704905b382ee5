// SPDX-License-Identifier: BSD-3-Clause
// Example 3: a broadphase scene checked the way a motion planner's state
// validity checker runs it: the environment (meshes) in one
// DynamicAABBTreeCollisionManager, the robot's links (cylinders) in
// another, and for every candidate state one manager-vs-manager collide
// with tricyl's callback.
//
// Switching from FCL's stock path is again one name per call site:
//   fcl::DefaultCollisionFunction<double> ->
//   tricyl::DefaultCollisionFunction<double> fcl::DefaultCollisionData<double>
//   -> tricyl::DefaultCollisionData<double>
// (the data struct is FCL's own; tricyl's name is an alias).
#include <fcl/broadphase/broadphase_dynamic_AABB_tree.h>
#include <tricyl/fcl_solver.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "example_mesh.h"

namespace {

fcl::Transform3d translation(double x, double y, double z) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.translation() = fcl::Vector3d(x, y, z);
  return tf;
}

// A two-link arm on a post: the post (vertical), the upper arm (horizontal,
// yawed by `yaw` degrees about +z) and the forearm hanging `drop` below the
// upper arm's end. Cylinders are centred in their frame, axis +z.
struct Arm {
  std::vector<fcl::CollisionObjectd*> links;

  void setState(double yaw_deg, double drop) const {
    const double pi = std::acos(-1.0);
    const double yaw = yaw_deg * pi / 180;
    const fcl::Vector3d top(0, -1.5, 0.85),
        dir(std::cos(yaw), std::sin(yaw), 0);
    links[0]->setTransform(translation(0, -1.5, 0.45));
    fcl::Transform3d upper = translation(0, 0, 0);
    upper.translation() = top + 0.6 * dir;
    upper.linear() = (Eigen::AngleAxisd(yaw, fcl::Vector3d::UnitZ()) *
                      Eigen::AngleAxisd(pi / 2, fcl::Vector3d::UnitY()))
                         .toRotationMatrix();
    links[1]->setTransform(upper);
    fcl::Transform3d fore = translation(0, 0, 0);
    fore.translation() = top + 1.2 * dir - fcl::Vector3d(0, 0, 0.3 + drop);
    links[2]->setTransform(fore);
    for (auto* link : links) link->computeAABB();
  }
};

// A planner's validity check: does any robot link touch the environment?
// FCL's stock version of this function differs only in the two names.
bool isValid(fcl::BroadPhaseCollisionManagerd& environment,
             fcl::BroadPhaseCollisionManagerd& robot) {
  tricyl::DefaultCollisionData<double> data;  // Boolean, stop at first hit
  environment.collide(&robot, &data, tricyl::DefaultCollisionFunction<double>);
  return !data.result.isCollision();
}

// A custom callback (what a planner writes to report WHICH links collide):
// the same shape as FCL's, with tricyl::collide for the narrow phase.
struct PairLog {
  std::vector<std::string> pairs;
};
bool logPair(fcl::CollisionObjectd* o1, fcl::CollisionObjectd* o2, void* data) {
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  if (tricyl::collide(o1, o2, request, result) > 0) {
    std::string a = static_cast<const char*>(o1->getUserData());
    std::string b = static_cast<const char*>(o2->getUserData());
    if (b < a) std::swap(a, b);
    static_cast<PairLog*>(data)->pairs.push_back(a + "/" + b);
  }
  return false;  // keep going: we want every pair
}

}  // namespace

int main() {
  // Environment: the terrain, a table and a shelf (triangle meshes).
  auto terrain = example::toBVH(example::pyramidTerrain());
  auto table = example::toBVH(example::boxMesh(0.3, 0.3, 0.2));
  auto shelf = example::toBVH(example::boxMesh(0.2, 0.5, 0.05));
  fcl::CollisionObjectd env_objs[] = {
      {terrain, translation(0, 0, 0)},
      {table, translation(1.4, -0.7, 0.2)},
      {shelf, translation(-1.0, -0.6, 0.5)},
  };
  const char* env_names[] = {"terrain", "table", "shelf"};

  // Robot: three cylinders.
  auto post = std::make_shared<fcl::Cylinderd>(0.1, 0.8);
  auto upper_arm = std::make_shared<fcl::Cylinderd>(0.08, 1.2);
  auto forearm = std::make_shared<fcl::Cylinderd>(0.06, 0.6);
  fcl::CollisionObjectd robot_objs[] = {
      {post, translation(0, 0, 0)},
      {upper_arm, translation(0, 0, 0)},
      {forearm, translation(0, 0, 0)},
  };
  const char* robot_names[] = {"post", "upper_arm", "forearm"};

  fcl::DynamicAABBTreeCollisionManagerd environment, robot;
  for (int i = 0; i < 3; ++i) {
    env_objs[i].setUserData(const_cast<char*>(env_names[i]));
    environment.registerObject(&env_objs[i]);
  }
  environment.setup();
  Arm arm{{&robot_objs[0], &robot_objs[1], &robot_objs[2]}};
  for (int i = 0; i < 3; ++i) {
    robot_objs[i].setUserData(const_cast<char*>(robot_names[i]));
    robot.registerObject(&robot_objs[i]);
  }

  struct State {
    double yaw_deg, drop;
  };
  const State states[] = {{0, 0},   {0, 0.3},   {35, 0.3}, {90, 0},
                          {150, 0}, {160, 0.2}, {200, 0},  {270, 0.4}};
  int valid = 0;
  for (const auto& s : states) {
    arm.setState(s.yaw_deg, s.drop);
    robot.update();  // the links moved: refit the robot's tree
    const bool ok = isValid(environment, robot);
    valid += ok;
    PairLog log;
    environment.collide(&robot, &log, logPair);
    std::printf("yaw %5.1f deg, drop %.1f: %-8s", s.yaw_deg, s.drop,
                ok ? "valid" : "invalid");
    for (const auto& p : log.pairs) std::printf(" %s", p.c_str());
    std::printf("\n");
  }
  std::printf("%d of %zu states valid\n", valid, std::size(states));
  return 0;
}
