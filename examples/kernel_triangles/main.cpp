// SPDX-License-Identifier: BSD-3-Clause
// Example 1: the exact kernel alone (tricyl::tricyl, no FCL).
//
// A cylinder of radius 0.5 and length 4 (FCL's convention: centred, axis
// +z), turned 90 degrees about x and moved to (1, 2, 3), against a few
// triangles given in the WORLD frame. Prints the answer and which stage of
// the kernel decided it; then shows the checked and unchecked error paths.
#include <tricyl/tricyl.h>

#include <cstdio>
#include <limits>

namespace {

const char* name(tricyl::Answer a) {
  switch (a) {
    case tricyl::Answer::kDisjoint:
      return "disjoint";
    case tricyl::Answer::kIntersect:
      return "intersect";
    case tricyl::Answer::kInvalidInput:
      return "invalid input";
  }
  return "?";
}

const char* name(tricyl::Stage s) {
  switch (s) {
    case tricyl::Stage::kEarlyOut:
      return "early-out";
    case tricyl::Stage::kFastPath:
      return "double filter";
    case tricyl::Stage::kRunning:
      return "double, running bound (a sign re-decided)";
    case tricyl::Stage::kExtended:
      return "double-word (a sign re-decided)";
    case tricyl::Stage::kExact:
      return "exact (a tie certified exactly)";
    case tricyl::Stage::kExactGmp:
      return "exact (GMP)";
    case tricyl::Stage::kInvalid:
      return "rejected";
  }
  return "?";
}

}  // namespace

int main() {
  using T = tricyl::Triangle<double>;
  const tricyl::Cylinder<double> cyl{0.5, 4.0};
  // world = R * local + t. R turns the local axis +z into world -y
  // (rotation by +90 degrees about x), so the cylinder spans y in [0, 4].
  const tricyl::Pose<double> pose{{{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
                                  {1, 2, 3}};
  struct Case {
    const char* what;
    T tri;
  };
  const Case cases[] = {
      {"crosses the axis", {{0, 2, 2}, {2, 2, 2}, {1, 2, 5}}},
      {"far away", {{10, 10, 10}, {11, 10, 10}, {10, 11, 10}}},
      {"touches the side at one point (x = 1.5)",
       {{1.5, 2, 3}, {2.5, 1, 3}, {2.5, 3, 3}}},
      {"one ulp beyond the side",
       {{1.5000000000000002, 2, 3}, {2.5, 1, 3}, {2.5, 3, 3}}},
      {"touches the cap plane y = 4 inside the disk",
       {{1, 4, 3}, {1, 5, 3}, {1, 5, 4}}},
      // README's trap case, local (1,0,-1) (2,0,-1) (1.5,0,1), in the world.
      {"plane contains the axis, beside it",
       {{2, 3, 3}, {3, 3, 3}, {2.5, 1, 3}}},
      {"degenerate: a segment through the cylinder",
       {{1, -1, 3}, {1, 5, 3}, {1, 2, 3}}},
      {"degenerate: a single point on the rim",
       {{1.5, 0, 3}, {1.5, 0, 3}, {1.5, 0, 3}}},
  };
  for (const auto& c : cases) {
    const tricyl::Decision d = tricyl::decideIntersect(cyl, pose, c.tri);
    std::printf("%-44s %-9s  (%s)\n", c.what, name(d.answer), name(d.stage));
  }

  // Invalid input: the checked entry point throws, tryIntersect says so.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const T bad{{nan, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  std::printf("NaN vertex, tryIntersect: %s\n",
              name(tricyl::tryIntersect(cyl, pose, bad)));
  try {
    tricyl::intersect(cyl, pose, bad);
    std::printf("NaN vertex, intersect: no exception (unexpected)\n");
  } catch (const tricyl::InvalidInput&) {
    std::printf("NaN vertex, intersect: throws tricyl::InvalidInput\n");
  }
  return 0;
}
