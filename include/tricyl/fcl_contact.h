// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Contact data for an intersecting triangle/cylinder pair, in bounded time,
/// in the convention FCL's libccd solver uses for shape/triangle queries.
/// Part of tricyl::fcl (the FCL adapter), but does not include FCL.
///
/// ## Contract
/// - Inputs as in triangle_cylinder.h (world-frame triangle, posed cylinder,
///   FCL's cylinder convention). The Boolean is tryIntersect's, exactly:
///   estimateContact returns the same Answer for the same inputs.
/// - kDisjoint: `*out` is not touched.
/// - kIntersect: `*out` holds, all in the WORLD frame,
///     point:  a point of (triangle ∩ cylinder), up to rounding (see ACCURACY);
///     normal: unit, pointing from the cylinder toward the triangle (libccd's
///             convention; FCL's mesh traversal stores -normal in
///             Contact::normal, which then points from the mesh to the shape);
///     depth:  > 0, see METHOD; a touching pair reports kMinDepth.
/// - kInvalidInput: `*out` holds finite placeholders (point = pose
///   translation if finite, else the origin; normal = +z; depth = kMinDepth).
/// - Bounded time, no iteration: a fixed number of floating-point operations
///   after the kernel's answer (about 40 candidate directions, a 5-vertex
///   clip). Nothing here calls libccd; see issue 9.
///
/// ## Method (all in the cylinder frame, y = R^T (x - t), h = lz / 2)
/// - normal and depth: the separating-axis overlap
///       d(n) = sup_{c in C} c.n - min_{v in T} v.n
///            = r sqrt(n_x^2 + n_y^2) + h |n_z| - min_i (y_i . n)
///   minimised over a FIXED finite set of unit directions n (both signs of
///   each): the triangle normal; the axis; per edge e, e x z (edge vs barrel)
///   and e x N (in-plane edge normal); per vertex, the radial direction and
///   the directions from the nearest point of each rim circle; per edge, e x
///   the rim tangent at the edge's angular position. Translating the triangle
///   by s n with any s > d(n) separates the pair (exactly, in real
///   arithmetic): the reported (normal, depth) is a separation certificate.
///   depth >= the true penetration depth (minimum translation distance);
///   they are EQUAL whenever the minimising direction of the true one is in
///   the set: face vs cap, face vs barrel, edge vs barrel, vertex vs barrel,
///   vertex or edge vs cap. For contacts at the rim with an oblique edge the
///   depth may exceed the true one (it is still a valid separating
///   translation). Measured on 264 random small triangles at the rims of an
///   r = 1, lz = 2 cylinder (tests/fcl_contact_test.cpp): depth minus a
///   dense-sampled minimum (20000 directions + local refinement) is at the
///   median 0, at the 95th percentile 0.7%, at most 3.4% of lz. The first
///   minimum wins ties, in the order listed.
/// - point: the triangle is clipped to the slab |z| <= h (Sutherland-Hodgman,
///   at most 5 vertices); the point of that polygon whose projection on the
///   xy-plane is nearest the axis is taken (the axis/plane crossing when the
///   projection surrounds the axis). That point is in the cylinder iff the
///   pair intersects (Eberly's reduction), so it is a point of T ∩ C. It is
///   then clamped into the closed cylinder, which moves it only by rounding.
///
/// ## Accuracy (double; float inputs are widened to double, computed, rounded)
/// - point: within a few ulps of max(|y_i|, r, h) of the triangle (it is
///   built from the triangle by convex combinations) and inside the closed
///   cylinder up to the rounding of the final clamp and the map back to the
///   world frame. When rounding empties the clipped polygon (the triangle only
///   touches a cap plane) the clip is repeated once with the slab widened by
///   16 ulps of max |y_i.z|.
/// - normal: |normal| = 1 to a few ulps; depth: the rounding of d(n), a few
///   ulps of max(|y_i|, r, h). tests/fcl_contact_test.cpp pins the
///   certificate property with a slack of 1e-9 of the scene size.
#pragma once

#include <limits>

#include "tricyl/types.h"

namespace tricyl {

/// Contact data of an intersecting triangle/cylinder pair (see the file
/// contract), all in the world frame.
template <class S>
struct ContactEstimate {
  Vec3<S> point;   ///< world frame, a point of triangle ∩ cylinder
  Vec3<S> normal;  ///< world frame, unit, from the cylinder toward the triangle
  S depth;         ///< > 0
};

/// The smallest depth reported: a touching pair reports this instead of 0
/// so that code which selects "the deepest contact" with a strict
/// `numeric_limits<S>::min() < depth` (FCL's signed-distance path in
/// distance-inl.h) always finds one.
template <class S>
constexpr S kMinDepth = S(4) * std::numeric_limits<S>::min();

/// Decides the pair exactly (same answer as tryIntersect) and, if it
/// intersects or the input is invalid, fills `*out` (see the contract).
/// `out` may be null: then this is tryIntersect.
template <class S>
Answer estimateContact(const Cylinder<S>& cylinder, const Pose<S>& pose,
                       const Triangle<S>& triangle,
                       ContactEstimate<S>* out) noexcept;

extern template Answer estimateContact(const Cylinder<float>&,
                                       const Pose<float>&,
                                       const Triangle<float>&,
                                       ContactEstimate<float>*) noexcept;
extern template Answer estimateContact(const Cylinder<double>&,
                                       const Pose<double>&,
                                       const Triangle<double>&,
                                       ContactEstimate<double>*) noexcept;

}  // namespace tricyl
