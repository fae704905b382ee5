// The kernel alone on a few triangles, through the installed package.
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
  return 0;
}
