// SPDX-License-Identifier: BSD-3-Clause
// Example: tricyl on FCL's own objects, converting nothing by hand
// (include/tricyl/fcl_adapters.h).
//   1. An fcl::Cylinder at an fcl::Transform3 against an fcl::TriangleP:
//      toCylinder, toPose, toTriangle, then the exact kernel.
//   2. The batch scan straight from an fcl::BVHModel: BvhMeshView borrows
//      the model's vertices and takes its fcl::Triangle indices, and is
//      passed wherever a MeshView goes (intersectMask, intersectIndices,
//      intersectAny). Its answers are the kernel's; tricyl::collide on the
//      same model (identity pose) finds the same triangles.
#include <tricyl/fcl_adapters.h>
#include <tricyl/fcl_solver.h>
#include <tricyl/mesh_cylinder.h>
#include <tricyl/triangle_cylinder.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <vector>

int main() {
  // 1. Shapes. A cylinder (r 0.5, length 2) lying along x, centred at
  // (0, 0, 1): its lowest line is z = 0.5.
  const fcl::Cylinderd fcl_cyl(0.5, 2.0);
  fcl::Transform3d cyl_tf = fcl::Transform3d::Identity();
  cyl_tf.linear() << 0, 0, 1,  //
      0, 1, 0,                 //
      -1, 0, 0;                // local z -> world x (a proper rotation)
  cyl_tf.translation() = fcl::Vector3d(0, 0, 1);
  const tricyl::Cylinder<double> cyl = tricyl::toCylinder(fcl_cyl);
  const tricyl::Pose<double> pose = tricyl::toPose(cyl_tf);
  const fcl::TrianglePd tri(fcl::Vector3d(-1, -1, 0), fcl::Vector3d(1, -1, 0),
                            fcl::Vector3d(0, 1, 0));
  // The triangle touching the cylinder's lowest line, 1e-12 below it, and
  // through the axis.
  const struct {
    double z;
    const char* label;
  } tri_cases[] = {{0.5, "0.5 (touching)"},
                   {0.5 - 1e-12, "0.5 - 1e-12"},
                   {1.0, "1 (the axis)"}};
  for (const auto& c : tri_cases) {
    fcl::Transform3d tri_tf = fcl::Transform3d::Identity();
    tri_tf.translation() = fcl::Vector3d(0, 0, c.z);
    const bool hit =
        tricyl::intersect(cyl, pose, tricyl::toTriangle(tri, tri_tf));
    std::printf("TriangleP at z = %-15s %s\n", c.label,
                hit ? "intersects" : "disjoint");
  }

  // 2. A 16 x 16 grid of squares (512 triangles) on [-2, 2]^2, z = 0, as an
  // FCL mesh; the cylinder stands on it at a few places.
  const int n = 16;
  std::vector<fcl::Vector3d> v;
  std::vector<fcl::Triangle> t;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j)
      v.emplace_back(-2 + 4.0 * i / n, -2 + 4.0 * j / n, 0);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const std::size_t a = i * (n + 1) + j, b = a + 1, c = a + n + 1,
                        d = c + 1;
      t.emplace_back(a, c, b);
      t.emplace_back(b, c, d);
    }
  auto model = std::make_shared<fcl::BVHModel<fcl::OBBRSSd>>();
  model->beginModel();
  model->addSubModel(v, t);
  model->endModel();

  const tricyl::BvhMeshView<double> mesh(*model);  // once per model
  std::vector<std::uint64_t> mask((mesh.num_triangles + 63) / 64);
  const auto fcl_cyl_ptr = std::make_shared<fcl::Cylinderd>(fcl_cyl);
  for (const double z : {0.5, 0.4, 0.5 + 1e-12}) {
    fcl::Transform3d tf = cyl_tf;
    tf.translation() = fcl::Vector3d(0.1, 0.3, z);
    const std::size_t hits =
        tricyl::intersectMask(cyl, tricyl::toPose(tf), mesh, mask.data());
    const std::optional<std::size_t> first =
        tricyl::intersectAny(cyl, tricyl::toPose(tf), mesh);
    fcl::CollisionRequestd request(1000, false);
    fcl::CollisionResultd result;
    tricyl::collide(model.get(), fcl::Transform3d::Identity(),
                    fcl_cyl_ptr.get(), tf, request, result);
    std::printf(
        "cylinder axis at z = %-9s batch scan %3zu triangles (first %s), "
        "tricyl::collide %3zu contacts\n",
        z == 0.5   ? "0.5:"
        : z == 0.4 ? "0.4:"
                   : "0.5+1e-12:",
        hits, first ? std::to_string(*first).c_str() : "none",
        result.numContacts());
  }
  return 0;
}
