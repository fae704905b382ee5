// SPDX-License-Identifier: BSD-3-Clause
// One call per pose of the FCL mesh benchmarks' scenes (bench/
// fcl_mesh_scenes.h: bench_fcl_collide's grazing scenes, bench_fcl_distance's
// clearance scenes), through tricyl's own traversal or through stock FCL,
// with the traversal's statistics per call. Meant for callgrind, whose
// instruction counts are the A/B metric that a loaded machine does not
// blur (timings: the paired rows of the two benchmarks):
//
//   valgrind --tool=callgrind --callgrind-out-file=/dev/null
//     --toggle-collect='tricyl::collideMeshCylinderWithin*'
//     ./build/bench/fcl_walk_counts first rob tricyl      (one line)
//   (distance: --toggle-collect='tricyl::distanceMeshCylinder*';
//    stock:    --toggle-collect='*fcl::collide<double>(fcl::CollisionObject*'
//              or '*fcl::distance<double>(fcl::CollisionObject*')
//
// and divide the total by the calls printed. Arguments: first | exhaustive
// | distance, env | bunny | rob, tricyl | stock, [passes over the poses].
// Exit status 77 when the mesh file is absent.
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

#include "fcl_mesh_scenes.h"
#include "tricyl/fcl_mesh_cylinder.h"

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr,
                 "usage: %s first|exhaustive|distance env|bunny|rob "
                 "tricyl|stock [passes]\n",
                 argv[0]);
    return 2;
  }
  const std::string mode = argv[1], mesh = argv[2], impl = argv[3];
  const int passes = argc > 4 ? std::atoi(argv[4]) : 1;
  const bool distance = mode == "distance", tricyl = impl == "tricyl";
  tricyl::bench::FclObjModel fm;
  if (!tricyl::bench::loadFclObj(mesh + ".obj", &fm)) {
    std::fprintf(stderr, "%s.obj not found under %s: skipped\n", mesh.c_str(),
                 TRICYL_MESH_DIR);
    return 77;  // ctest's SKIP_RETURN_CODE (bench/fcl.cmake)
  }
  // The seeds of bench_fcl_collide's paired_grazing rows (44, 45, 46) and
  // of bench_fcl_distance's paired_distance rows (52, 53, 54).
  const std::uint64_t k = mesh == "env" ? 0 : (mesh == "bunny" ? 1 : 2);
  constexpr int kPoses = 256;
  const tricyl::bench::CylinderPoses p =
      distance ? tricyl::bench::clearancePoses(fm, 52 + k, kPoses)
               : tricyl::bench::nearSurfacePoses(fm, 44 + k, kPoses, true);
  const fcl::Transform3d id = fcl::Transform3d::Identity();
  const fcl::CollisionObjectd o_mesh(fm.model, id);
  std::vector<std::unique_ptr<fcl::CollisionObjectd>> cyls;
  for (std::size_t i = 0; i < p.poses.size(); ++i)
    cyls.push_back(
        std::make_unique<fcl::CollisionObjectd>(p.cyls[i], p.poses[i]));
  tricyl::TraversalStats st;
  std::size_t calls = 0, in_collision = 0, contacts = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int pass = 0; pass < passes; ++pass)
    for (const auto& oc : cyls) {
      ++calls;
      if (distance) {
        const fcl::DistanceRequestd req;
        fcl::DistanceResultd res;
        if (tricyl)
          tricyl::distanceMeshCylinder(fm.model.get(), id,
                                       oc->collisionGeometry().get(),
                                       oc->getTransform(), req, res, &st);
        else
          fcl::distance(&o_mesh, oc.get(), req, res);
        in_collision += res.min_distance <= 0;
        continue;
      }
      const fcl::CollisionRequestd req(mode == "first" ? 1 : 100000, false);
      fcl::CollisionResultd res;
      std::size_t n = 0;
      if (tricyl)
        tricyl::collideMeshCylinder(fm.model.get(), id,
                                    oc->collisionGeometry().get(),
                                    oc->getTransform(), req, res, &n, &st);
      else
        fcl::collide(&o_mesh, oc.get(), req, res);
      in_collision += res.numContacts() > 0;
      contacts += res.numContacts();
    }
  const auto t1 = std::chrono::steady_clock::now();
  const double c = double(calls);
  std::printf(
      "%s %s %s: %zu calls, %.2f us a call, in collision %zu, contacts "
      "%.2f a call; traversal per call: bounds or node tests %.1f, pruned "
      "%.1f, triangles to the kernel %.2f, hits or improvements %.2f\n",
      mode.c_str(), mesh.c_str(), impl.c_str(), calls,
      std::chrono::duration<double, std::micro>(t1 - t0).count() / c,
      in_collision, double(contacts) / c, double(st.nodes_tested) / c,
      double(st.nodes_skipped) / c, double(st.leaves) / c, double(st.hits) / c);
  return 0;
}
