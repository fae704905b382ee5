// SPDX-License-Identifier: BSD-3-Clause
// Example 5: a cylinder robot planned through a triangle mesh with OMPL
// (SimpleSetup + RRTConnect), every state checked by tricyl::collide.
//
//   example_ompl_planner [--broadphase] [--stock] [--seed N] mesh.obj
//
// mesh.obj is env.obj or bunny.obj (scene.h; exit 77 when it cannot be
// read). --broadphase checks through FCL's dynamic AABB tree of the mesh's
// parts instead of one BVH; --stock uses fcl::collide (libccd) instead of
// tricyl::collide, for comparison. The planner is seeded (default 1), so
// the printed path is the same on every run.
#include <ompl/base/PlannerTerminationCondition.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/geometric/SimpleSetup.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "planner.h"
#include "scene.h"

namespace ob = ompl::base;
namespace og = ompl::geometric;
using example::CheckPath;
using example::NarrowPhase;

namespace {

void printPath(const og::PathGeometric& path) {
  for (std::size_t i = 0; i < path.getStateCount(); ++i) {
    const fcl::Transform3d tf = example::toTransform(path.getState(i));
    const fcl::Vector3d p = tf.translation(), a = tf.linear().col(2);
    std::printf(
        "  %2zu: centre (%9.3f %9.3f %9.3f)  axis (%6.3f %6.3f %6.3f)\n", i,
        p.x(), p.y(), p.z(), a.x(), a.y(), a.z());
  }
}

}  // namespace

int main(int argc, char** argv) {
  CheckPath check_path = CheckPath::kDirect;
  NarrowPhase narrow = NarrowPhase::kTricyl;
  unsigned seed = 1;
  std::string file;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--broadphase") == 0)
      check_path = CheckPath::kBroadphase;
    else if (std::strcmp(argv[i], "--stock") == 0)
      narrow = NarrowPhase::kStockFcl;
    else if (std::strcmp(argv[i], "--seed") == 0 && i + 1 < argc)
      seed = unsigned(std::strtoul(argv[++i], nullptr, 10));
    else
      file = argv[i];
  }
  // The seed of every OMPL random generator: set before any is created.
  ompl::RNG::setSeed(seed);
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);

  example::Mesh mesh;
  example::Scene scene;
  const std::string name =
      file.substr(file.find_last_of('/') + 1,
                  file.rfind(".obj") - file.find_last_of('/') - 1);
  if (!example::readObj(file, &mesh) ||
      !example::sceneFor(name, mesh, &scene)) {
    std::fprintf(stderr, "mesh %s not readable or no scene for it: skipped\n",
                 file.c_str());
    return 77;
  }
  std::printf(
      "%s: %zu triangles; cylinder r %.3f, length %.3f; checked "
      "every %.3f of motion (as r %.3f, length %.3f); %s, %s\n",
      name.c_str(), mesh.triangles.size(), scene.radius, scene.length,
      scene.step, scene.checkedRadius(), scene.checkedLength(),
      narrow == NarrowPhase::kTricyl ? "tricyl::collide" : "fcl::collide",
      check_path == CheckPath::kDirect ? "one BVH" : "broadphase");

  // The robot as FCL sees it: the grown cylinder (planner.h explains why).
  auto robot = std::make_shared<fcl::Cylinderd>(scene.checkedRadius(),
                                                scene.checkedLength());
  const example::Environment env(mesh);

  // SE(3) over the scene's box; the validity checker and the motion
  // validator replace OMPL's defaults.
  og::SimpleSetup setup(example::makeSpace(scene.lo, scene.hi, scene.reach()));
  const ob::SpaceInformationPtr si = setup.getSpaceInformation();
  si->setStateValidityChecker(
      std::make_shared<example::CylinderValidityChecker>(si, robot, env,
                                                         check_path, narrow));
  si->setMotionValidator(std::make_shared<example::CylinderMotionValidator>(
      si, scene.reach(), scene.step));

  ob::ScopedState<ob::SE3StateSpace> start(setup.getStateSpace()),
      goal(setup.getStateSpace());
  example::setState(start.get(), scene.start, scene.start_axis);
  example::setState(goal.get(), scene.goal, scene.goal_axis);
  setup.setStartAndGoalStates(start, goal);
  setup.setPlanner(std::make_shared<og::RRTConnect>(si));

  // A fixed amount of work, not a time budget: RRTConnect stops at its
  // first solution, or once the condition (evaluated once per iteration)
  // has been asked 100,000 times.
  unsigned long asked = 0;
  const ob::PlannerStatus status = setup.solve(
      ob::PlannerTerminationCondition([&asked] { return ++asked > 100000; }));
  if (status != ob::PlannerStatus::EXACT_SOLUTION) {
    std::printf("no solution (%s)\n", status.asString().c_str());
    return 1;
  }
  og::PathGeometric path = setup.getSolutionPath();
  std::printf("RRTConnect: solution of %zu states, length %.3f\n",
              path.getStateCount(), path.length());

  // Shorten it, then re-check: PathSimplifier can return a path that fails
  // its own check() (seen with OMPL 1.5's simplifyMax). A planner must never
  // hand such a path on; keep the unsimplified one instead.
  og::PathGeometric simplified = path;
  og::PathSimplifier(si).simplifyMax(simplified);
  if (simplified.check()) {
    path = simplified;
    std::printf("simplified: %zu states, length %.3f, re-checked valid\n",
                path.getStateCount(), path.length());
  } else {
    std::printf("simplified path fails its check(): keeping the planner's\n");
  }
  printPath(path);
  return path.check() ? 0 : 1;
}
