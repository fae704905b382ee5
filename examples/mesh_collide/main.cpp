// SPDX-License-Identifier: BSD-3-Clause
// Example 2: a cylinder against a triangle mesh through tricyl::collide, the
// drop-in replacement for fcl::collide.
//
//   example_mesh_collide [--stock] [--require] [mesh.obj]
//
// Without a file (or when it cannot be read) the mesh is a procedural
// terrain, so the checked output never depends on a data file; --require
// exits 77 instead (ctest: skipped). --stock runs fcl::collide, FCL's own
// GJK/libccd path, on the same objects, for comparison: the call is the
// same, only the function's name differs.
#include <tricyl/fcl_solver.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <string>

#include "example_mesh.h"

int main(int argc, char** argv) {
  bool stock = false, require = false;
  std::string path;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--stock") == 0)
      stock = true;
    else if (std::strcmp(argv[i], "--require") == 0)
      require = true;
    else
      path = argv[i];
  }

  example::Mesh mesh;
  std::string label = "procedural terrain";
  if (!path.empty() && example::readObj(path, &mesh)) {
    label = path.substr(path.find_last_of('/') + 1);
  } else {
    if (require) {
      std::fprintf(stderr, "mesh %s not readable: skipped\n", path.c_str());
      return 77;
    }
    if (!path.empty())
      std::fprintf(stderr, "mesh %s not readable: using the terrain\n",
                   path.c_str());
    mesh = example::pyramidTerrain();
  }
  std::printf("mesh: %s, %zu triangles (%s)\n", label.c_str(),
              mesh.triangles.size(),
              stock ? "fcl::collide" : "tricyl::collide");

  // Placements relative to the mesh's bounding box, so any mesh works.
  fcl::Vector3d lo = mesh.vertices[0], hi = mesh.vertices[0];
  for (const auto& v : mesh.vertices) {
    lo = lo.cwiseMin(v);
    hi = hi.cwiseMax(v);
  }
  const fcl::Vector3d mid = (lo + hi) / 2;
  const double size = (hi - lo).maxCoeff();
  const double r = size / 16, lz = size / 4;

  const fcl::CollisionObjectd mesh_obj(example::toBVH(mesh),
                                       fcl::Transform3d::Identity());
  auto cylinder = std::make_shared<fcl::Cylinderd>(r, lz);

  struct Placement {
    const char* what;
    fcl::Transform3d tf;
  };
  auto at = [](double x, double y, double z) {
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.translation() = fcl::Vector3d(x, y, z);
    return tf;
  };
  fcl::Transform3d lying = at(mid.x(), mid.y(), mid.z());
  lying.linear() << 1, 0, 0, 0, 0, -1, 0, 1, 0;  // axis along world y
  const double cx = lo.x() + 2 * r, cy = lo.y() + 2 * r;
  const Placement placements[] = {
      {"above the box", at(mid.x(), mid.y(), hi.z() + lz)},
      {"vertical through the middle", at(mid.x(), mid.y(), mid.z())},
      {"lying through the middle", lying},
      {"standing on the box floor (touching z = min)",
       at(cx, cy, lo.z() + lz / 2)},
      {"1e-9 above the box floor", at(cx, cy, lo.z() + lz / 2 + 1e-9)},
      {"1e-9 below the box floor", at(cx, cy, lo.z() + lz / 2 - 1e-9)},
  };

  fcl::CollisionRequestd request;  // defaults: Boolean, first contact
  for (const auto& p : placements) {
    const fcl::CollisionObjectd cyl_obj(cylinder, p.tf);
    fcl::CollisionResultd result;
    // THE SWITCH: same arguments, same result type; one name differs.
    const std::size_t n =
        stock ? fcl::collide(&cyl_obj, &mesh_obj, request, result)
              : tricyl::collide(&cyl_obj, &mesh_obj, request, result);
    std::printf("%-46s %s\n", p.what, n > 0 ? "collision" : "free");
  }
  return 0;
}
