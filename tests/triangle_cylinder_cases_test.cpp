// SPDX-License-Identifier: BSD-3-Clause
// Hand-built triangle/cylinder cases with known answers, one or more per
// case of Eberly's Figure 1 (0a .. 5), both sides of each, the published
// bugs, and the degenerate inputs. Each case is run for float and double,
// through the local entry point and under several exactly representable
// world frames, and its expectation is also confirmed by the exact oracle.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "oracle.h"
#include "test_support.h"
#include "tricyl/tricyl.h"

namespace tricyl {
namespace {

constexpr double kNudge = 0x1p-20;  // exact in float and double

struct Case {
  const char* name;
  double r, lz;
  double v[3][3];  // local vertices
  bool expected;
};

// r = 1, lz = 2 (slab |z| <= 1) unless stated otherwise.
const std::vector<Case>& cases() {
  static const std::vector<Case> k = {
      // 0a / 0b: strictly below / above the slab.
      {"0a_below", 1, 2, {{0, 0, -3}, {1, 0, -2}, {0, 1, -1.5}}, false},
      {"0b_above", 1, 2, {{0, 0, 3}, {1, 0, 2}, {0, 1, 1.5}}, false},
      // 1a / 1b: one vertex exactly on a cap plane, the rest outside.
      {"1a_vertex_on_bottom_cap",
       1,
       2,
       {{0, 0, -1}, {1, 0, -2}, {0, 1, -3}},
       true},
      {"1a_vertex_on_bottom_plane_outside_disk",
       1,
       2,
       {{2, 0, -1}, {3, 0, -2}, {2, 1, -3}},
       false},
      {"1b_vertex_on_top_cap",
       1,
       2,
       {{0.5, 0.5, 1}, {1, 0, 2}, {0, 1, 3}},
       true},
      {"1b_vertex_on_top_plane_outside_disk",
       1,
       2,
       {{1, 1, 1}, {1, 0, 2}, {0, 1, 3}},
       false},
      // 2a / 2b: an edge lying in a cap plane, the third vertex outside.
      {"2a_edge_tangent_to_bottom_rim",
       1,
       2,
       {{1, -1, -1}, {1, 1, -1}, {0, 0, -3}},
       true},
      {"2a_edge_in_bottom_plane_outside",
       1,
       2,
       {{1 + kNudge, -1, -1}, {1 + kNudge, 1, -1}, {3, 0, -3}},
       false},
      {"2b_edge_through_top_cap",
       1,
       2,
       {{-2, 0, 1}, {2, 0, 1}, {0, 0, 4}},
       true},
      {"2b_edge_in_top_plane_outside",
       1,
       2,
       {{-2, 1.5, 1}, {2, 1.5, 1}, {0, 0, 4}},
       false},
      // 3a: entirely inside the slab.
      {"3a_small_inside",
       1,
       2,
       {{0, 0, 0}, {0.5, 0, 0.5}, {0, 0.5, -0.5}},
       true},
      {"3a_outside_disk", 1, 2, {{2, 0, 0}, {3, 0, 0}, {2, 1, 0.5}}, false},
      {"3a_surrounds_axis",
       1,
       2,
       {{5, 0, 0}, {-3, 4, 0.5}, {-3, -4, -0.5}},
       true},
      {"3a_edge_tangent_to_side",
       1,
       2,
       {{1, -1, 0}, {1, 1, 0}, {3, 0, 0}},
       true},
      {"3a_edge_just_off_side",
       1,
       2,
       {{1 + kNudge, -1, 0}, {1 + kNudge, 1, 0}, {3, 0, 0}},
       false},
      // 3b/3c: two vertices below, one inside the slab.
      {"3bc_vertex_in_slab_in_disk",
       1,
       2,
       {{0, 0, 0.5}, {0.5, 0, -3}, {-0.5, 0.25, -3}},
       true},
      {"3bc_vertex_in_slab_outside",
       1,
       2,
       {{3, 0, 0.5}, {3, 1, -3}, {4, 0, -3}},
       false},
      // 3d/3e: two vertices above, one inside the slab.
      {"3de_vertex_in_slab_in_disk",
       1,
       2,
       {{0, 0, -0.5}, {0.5, 0, 3}, {-0.5, 0.25, 3}},
       true},
      {"3de_vertex_in_slab_outside",
       1,
       2,
       {{0, 3, -0.5}, {1, 3, 3}, {0, 4, 3}},
       false},
      // 4a/4b: one vertex below, two above (quadrilateral).
      {"4ab_crosses_near_axis",
       1,
       2,
       {{0, -0.5, -3}, {1, 1, 3}, {-1, 1, 3}},
       true},
      {"4ab_crosses_outside",
       1,
       2,
       {{2, -0.5, -3}, {3, 1, 3}, {2, 1, 3}},
       false},
      // 4c/4d: two below, one above.
      {"4cd_crosses_near_axis",
       1,
       2,
       {{1, 1, -3}, {-1, 1, -3}, {0, -0.5, 3}},
       true},
      {"4cd_crosses_outside",
       1,
       2,
       {{-3, 1, -3}, {-2, 1, -3}, {-2, -0.5, 3}},
       false},
      // 4e: one below, two inside.
      {"4e_inside_part_hits",
       1,
       2,
       {{0, 0, -3}, {0.5, 0, 0}, {0, 0.5, 0.5}},
       true},
      {"4e_inside_part_misses",
       1,
       2,
       {{3, 0, -3}, {3, 1, 0}, {4, 0, 0.5}},
       false},
      // 4f: two inside, one above. The second is the regression for the
      // published version that clipped this case against -h/2 instead of
      // +h/2: inside the slab the triangle stays at x >= 2.4 (z <= 1 forces
      // the weight of the apex pair below 0.2), while above the slab it
      // passes over the axis. The wrong plane keeps the part above the slab.
      {"4f_inside_part_hits",
       1,
       2,
       {{0, 0, 0}, {0.5, 0, 0.5}, {0, 0, 3}},
       true},
      {"4f_bug_wrong_clip_plane",
       1,
       2,
       {{3, 0, 0}, {0, 0, 5}, {0, 0.2, 5}},
       false},
      // 5: one below, one inside, one above (pentagon).
      {"5_pentagon_hits",
       1,
       2,
       {{0.5, 0, -3}, {-0.25, 0.25, 0}, {0, -0.5, 3}},
       true},
      {"5_pentagon_misses", 1, 2, {{5, 0, -3}, {4, 1, 0}, {4, -1, 3}}, false},
      {"5_pentagon_axis_through_interior",
       1,
       2,
       {{4, -4, -3}, {-4, -4, 0}, {0, 8, 3}},
       true},
      // The published bug: the plane contains the axis (y = 0), the
      // projection is the segment [1, 2] x {0}, and "origin inside the
      // polygon" must not fire.
      {"bug_plane_contains_axis_miss",
       0.5,
       4,
       {{1, 0, -1}, {2, 0, -1}, {1.5, 0, 1}},
       false},
      {"plane_contains_axis_hit",
       0.5,
       4,
       {{0.5, 0, -1}, {2, 0, -1}, {1.5, 0, 1}},
       true},
      {"plane_contains_axis_straddles_axis",
       0.5,
       4,
       {{-1, 0, -1}, {2, 0, -1}, {1.5, 0, 1}},
       true},
      // Rim contacts.
      {"cap_plane_vertex_on_rim",
       1,
       2,
       {{1, 0, 1}, {2, -1, 1}, {2, 1, 1}},
       true},
      {"cap_plane_vertex_off_rim",
       1,
       2,
       {{1 + kNudge, 0, 1}, {2, -1, 1}, {2, 1, 1}},
       false},
      {"cap_plane_edge_tangent_to_rim",
       1,
       2,
       {{1, -1, 1}, {1, 1, 1}, {2, 0, 1}},
       true},
      {"vertex_on_rim_rest_above",
       1,
       2,
       {{1, 0, 1}, {3, 0, 3}, {1, 2, 3}},
       true},
      {"vertex_off_rim_rest_above",
       1,
       2,
       {{1 + kNudge, 0, 1}, {3, 0, 3}, {1, 2, 3}},
       false},
      {"vertex_above_rim_rest_above",
       1,
       2,
       {{1, 0, 1 + kNudge}, {3, 0, 3}, {1, 2, 3}},
       false},
      // Parallel to the axis at distance exactly r.
      {"parallel_to_axis_at_r",
       1,
       2,
       {{1, -1, -3}, {1, 1, -3}, {1, 0, 3}},
       true},
      {"parallel_to_axis_beyond_r",
       1,
       2,
       {{1 + kNudge, -1, -3}, {1 + kNudge, 1, -3}, {1 + kNudge, 0, 3}},
       false},
      // Zero radius: the cylinder is the axis segment.
      {"r0_triangle_crosses_axis",
       0,
       2,
       {{1, -1, 0.5}, {-1, -1, 0}, {0, 1, 0}},
       true},
      {"r0_triangle_beside_axis",
       0,
       2,
       {{kNudge, -1, 0.5}, {1, -1, 0}, {1, 1, 0}},
       false},
      {"r0_vertex_at_axis_end", 0, 2, {{0, 0, 1}, {1, 0, 2}, {0, 1, 2}}, true},
      // Zero length: the cylinder is a disk in z = 0.
      {"lz0_crosses_disk",
       1,
       0,
       {{0.5, 0, -1}, {0.5, 0.5, 1}, {0, 0.5, 1}},
       true},
      {"lz0_just_above",
       1,
       0,
       {{0, 0, kNudge}, {0.5, 0, 1}, {0, 0.5, 1}},
       false},
      {"lz0_chord_tangent_to_rim",
       1,
       0,
       {{1, -1, -1}, {1, 1, -1}, {1, 0, 1}},
       true},
      {"r0_lz0_point_in_triangle",
       0,
       0,
       {{1, -1, -1}, {-1, -1, 1}, {0, 1, 0}},
       true},
      {"r0_lz0_point_beside_triangle",
       0,
       0,
       {{1, 1, -1}, {2, 1, 1}, {1, 2, 0}},
       false},
      // Degenerate triangles.
      {"collinear_through_cylinder",
       1,
       2,
       {{-5, 0, 0}, {5, 0, 0}, {0, 0, 0}},
       true},
      {"collinear_beside_cylinder",
       1,
       2,
       {{-5, 1 + kNudge, 0}, {5, 1 + kNudge, 0}, {0, 1 + kNudge, 0}},
       false},
      {"collinear_tangent_to_side",
       1,
       2,
       {{-5, 1, 0}, {5, 1, 0}, {1, 1, 0}},
       true},
      {"collinear_along_axis_above",
       1,
       2,
       {{0, 0, 2}, {0, 0, 4}, {0, 0, 3}},
       false},
      {"collinear_along_axis_touching_cap",
       1,
       2,
       {{0, 0, 1}, {0, 0, 4}, {0, 0, 3}},
       true},
      {"repeated_vertex_segment_hits",
       1,
       2,
       {{0.5, 0.5, -3}, {0.5, 0.5, -3}, {0.5, 0.5, 3}},
       true},
      {"all_equal_inside",
       1,
       2,
       {{0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}, {0.5, 0.5, 0.5}},
       true},
      {"all_equal_on_boundary", 1, 2, {{0, 1, 1}, {0, 1, 1}, {0, 1, 1}}, true},
      {"all_equal_outside",
       1,
       2,
       {{0, 1, 1 + kNudge}, {0, 1, 1 + kNudge}, {0, 1, 1 + kNudge}},
       false},
  };
  return k;
}

// Exactly representable rigid motions: signed axis permutations and small
// dyadic translations (every sum below is exact in float and double).
struct Frame {
  const char* name;
  double R[3][3];
  double t[3];
};
const std::vector<Frame>& frames() {
  static const std::vector<Frame> k = {
      {"identity", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0, 0, 0}},
      {"translated", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, {0.5, -2, 4}},
      {"cyclic", {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}}, {0, 0, 0}},
      {"flip_xz", {{0, 0, -1}, {0, 1, 0}, {1, 0, 0}}, {-4, 0.25, 2}},
      {"reflect_y", {{1, 0, 0}, {0, -1, 0}, {0, 0, 1}}, {1, 1, -1}},
      {"upside_down", {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}, {-0.5, 8, 0}},
  };
  return k;
}

template <class S>
Vec3<S> apply(const Frame& f, const double v[3]) {
  double w[3];
  for (int i = 0; i < 3; ++i)
    w[i] = f.R[i][0] * v[0] + f.R[i][1] * v[1] + f.R[i][2] * v[2] + f.t[i];
  return {S(w[0]), S(w[1]), S(w[2])};
}

template <class S>
Pose<S> pose(const Frame& f) {
  Pose<S> p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.R[i][j] = S(f.R[i][j]);
  p.t = {S(f.t[0]), S(f.t[1]), S(f.t[2])};
  return p;
}

template <class S>
class TriangleCylinderCases : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(TriangleCylinderCases, Scalars);

TEST(TriangleCylinderOracle, AgreesWithEveryHandCase) {
  for (const Case& c : cases()) {
    const Triangle<double> tri{{c.v[0][0], c.v[0][1], c.v[0][2]},
                               {c.v[1][0], c.v[1][1], c.v[1][2]},
                               {c.v[2][0], c.v[2][1], c.v[2][2]}};
    EXPECT_EQ(
        oracle::triangleCylinder({c.r, c.lz}, identityPose<double>(), tri),
        c.expected)
        << c.name;
  }
}

TYPED_TEST(TriangleCylinderCases, LocalEntryPoint) {
  using S = TypeParam;
  for (const Case& c : cases()) {
    const Triangle<S> tri{{S(c.v[0][0]), S(c.v[0][1]), S(c.v[0][2])},
                          {S(c.v[1][0]), S(c.v[1][1]), S(c.v[1][2])},
                          {S(c.v[2][0]), S(c.v[2][1]), S(c.v[2][2])}};
    EXPECT_EQ(intersect(Cylinder<S>{S(c.r), S(c.lz)}, tri), c.expected)
        << c.name;
  }
}

TYPED_TEST(TriangleCylinderCases, EveryWorldFrameEveryVertexOrder) {
  using S = TypeParam;
  static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                      {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (const Case& c : cases()) {
    for (const Frame& f : frames()) {
      const Vec3<S> w[3] = {apply<S>(f, c.v[0]), apply<S>(f, c.v[1]),
                            apply<S>(f, c.v[2])};
      for (const auto& p : kPerm) {
        const Triangle<S> tri{w[p[0]], w[p[1]], w[p[2]]};
        EXPECT_EQ(intersect(Cylinder<S>{S(c.r), S(c.lz)}, pose<S>(f), tri),
                  c.expected)
            << c.name << " frame=" << f.name << " order=" << p[0] << p[1]
            << p[2];
      }
    }
  }
}

TYPED_TEST(TriangleCylinderCases, PowerOfTwoScalingKeepsTheAnswer) {
  using S = TypeParam;
  // 2^k for k in a range that keeps every case exact in float.
  for (int k : {-60, -20, -3, 3, 20, 60}) {
    const double s = std::ldexp(1.0, k);
    for (const Case& c : cases()) {
      const Triangle<S> tri{
          {S(s * c.v[0][0]), S(s * c.v[0][1]), S(s * c.v[0][2])},
          {S(s * c.v[1][0]), S(s * c.v[1][1]), S(s * c.v[1][2])},
          {S(s * c.v[2][0]), S(s * c.v[2][1]), S(s * c.v[2][2])}};
      EXPECT_EQ(intersect(Cylinder<S>{S(s * c.r), S(s * c.lz)}, tri),
                c.expected)
          << c.name << " scale=2^" << k;
    }
  }
}

}  // namespace
}  // namespace tricyl
