// SPDX-License-Identifier: BSD-3-Clause
// Example 4: contacts on request. The Boolean never depends on whether
// contacts are asked for; with request.enable_contact, tricyl::collide fills
// fcl::Contact the way FCL does, with tricyl::estimateContact's point,
// normal and depth (bounded time, no libccd) for cylinder/triangle pairs.
//
// Conventions (FCL 0.7's own, kept unchanged; the stock solver prints the
// same normals and depths for these scenes):
// - Mesh vs cylinder: Contact::normal is a unit vector pointing from the
//   MESH toward the CYLINDER, whichever of the two is o1 (FCL routes the
//   shape-first order through its mesh-first code). So it is "from o1 to
//   o2" only when the mesh is o1.
// - Shape vs shape (TriangleP vs Cylinder): from o1 toward o2.
// - Contact::penetration_depth > 0; a pair that only touches reports
//   tricyl::kMinDepth<double> (a tiny positive number), never 0.
// - Contact::pos is a world-frame point of triangle ∩ cylinder.
// - One contact per intersecting mesh triangle, up to
//   request.num_max_contacts.
#include <tricyl/fcl_solver.h>

#include <cstdio>

#include "example_mesh.h"

namespace {

fcl::Transform3d translation(double x, double y, double z) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.translation() = fcl::Vector3d(x, y, z);
  return tf;
}

double r6(double v) {  // print-stable: no "-0.000000"
  return v == 0 ? 0.0 : v;
}

void report(const char* what, const fcl::CollisionObjectd& o1,
            const fcl::CollisionObjectd& o2, bool enable_contact) {
  fcl::CollisionRequestd request;
  request.enable_contact = enable_contact;
  request.num_max_contacts = 100;
  fcl::CollisionResultd result;
  tricyl::collide(&o1, &o2, request, result);
  std::printf("%s (enable_contact=%s): %s, %zu contact(s)\n", what,
              enable_contact ? "true" : "false",
              result.isCollision() ? "collision" : "free",
              result.numContacts());
  if (!enable_contact) return;
  const fcl::Vector3d c1 = o1.getTranslation(), c2 = o2.getTranslation();
  for (std::size_t i = 0; i < result.numContacts(); ++i) {
    const fcl::Contactd& c = result.getContact(i);
    const double d = c.penetration_depth;
    std::printf("  #%zu depth %s%.6f  normal (%.6f, %.6f, %.6f)", i,
                d > 0 ? "+" : "", r6(d), r6(c.normal.x()), r6(c.normal.y()),
                r6(c.normal.z()));
    std::printf("  points from %s",
                c.normal.dot(c2 - c1) > 0 ? "o1 to o2" : "o2 to o1");
    if (d == tricyl::kMinDepth<double>) std::printf("  [touching: kMinDepth]");
    std::printf("\n");
  }
}

}  // namespace

int main() {
  // A flat floor (two triangles at z = 0) and a cylinder r = 0.5, lz = 2.
  example::Mesh floor;
  floor.vertices = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  const fcl::CollisionObjectd floor_obj(example::toBVH(floor),
                                        translation(0, 0, 0));
  auto cylinder = std::make_shared<fcl::Cylinderd>(0.5, 2.0);

  // Pressed 0.125 into the floor, standing on the diagonal shared by both
  // triangles: both triangles intersect, two contacts.
  const fcl::CollisionObjectd pressed(cylinder, translation(0, 0, 0.875));
  report("cylinder pressed 0.125 into the floor, mesh first", floor_obj,
         pressed, false);
  report("cylinder pressed 0.125 into the floor, mesh first", floor_obj,
         pressed, true);
  report("the same, cylinder first", pressed, floor_obj, true);

  // Standing exactly on the floor: touching counts, depth is kMinDepth.
  const fcl::CollisionObjectd standing(cylinder, translation(1, 1, 1));
  report("cylinder standing on the floor", floor_obj, standing, true);

  // 1e-12 above the floor: free, no contact.
  const fcl::CollisionObjectd hovering(cylinder, translation(1, 1, 1 + 1e-12));
  report("cylinder 1e-12 above the floor", floor_obj, hovering, true);

  // A single triangle as an fcl::TriangleP shape: FCL 0.7 itself has no
  // TriangleP/Cylinder entry; tricyl::Solver registers one.
  auto tri = std::make_shared<fcl::TrianglePd>(fcl::Vector3d(-1, -1, 0),
                                               fcl::Vector3d(1, -1, 0),
                                               fcl::Vector3d(0, 1, 0));
  const fcl::CollisionObjectd tri_obj(tri, translation(0, 0, 0));
  report("TriangleP shape vs the pressed cylinder", tri_obj, pressed, true);
  report("the pressed cylinder vs the TriangleP shape", pressed, tri_obj, true);
  return 0;
}
