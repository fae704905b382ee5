// SPDX-License-Identifier: BSD-3-Clause
// The core alone (tricyl::tricyl: GMP, no FCL) through the installed
// package: the kernel on a few triangles, then contact data for the
// intersecting ones (estimateContact, fcl_contact.h, which needs no FCL).
#include <tricyl/fcl_contact.h>
#include <tricyl/tricyl.h>

#include <cstdio>

int main() {
  const tricyl::Cylinder<double> cyl{0.5, 4.0};
  const tricyl::Pose<double> pose{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 0, 0}};
  const tricyl::Triangle<double> cases[] = {
      {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}},      // through the axis
      {{1, 0, -1}, {2, 0, -1}, {1.5, 0, 1}},  // plane contains the axis, misses
      {{0.5, 0, 2}, {1, 0, 3}, {1, 1, 3}},    // touches the rim at one point
      {{0.5, 0.5, 0}, {1, 0.5, 0}, {1, 1, 0}},  // just outside the side
  };
  for (const auto& tri : cases)
    std::printf("%s\n",
                tricyl::intersect(cyl, pose, tri) ? "intersect" : "disjoint");
  // Contact data: a triangle 0.1 deep in the top cap, and the rim touch.
  const tricyl::Triangle<double> in_cap{
      {-1, -1, 1.9}, {1, -1, 1.9}, {0, 2, 1.9}};
  for (const auto& tri : {in_cap, cases[2]}) {
    tricyl::ContactEstimate<double> c;
    const tricyl::Answer a = tricyl::estimateContact(cyl, pose, tri, &c);
    std::printf("contact: %s, normal (%g, %g, %g), depth %s\n",
                a == tricyl::Answer::kIntersect ? "yes" : "no", c.normal.x,
                c.normal.y, c.normal.z,
                c.depth == tricyl::kMinDepth<double>   ? "kMinDepth (touching)"
                : c.depth > 0.0999 && c.depth < 0.1001 ? "0.1"
                                                       : "other");
  }
  return 0;
}
