// SPDX-License-Identifier: BSD-3-Clause
// The distance's rare tightening step for tiny distances (docs/distance.md,
// section 6): internal, called by src/triangle_cylinder_distance.cpp only.
#pragma once

#include "tricyl/triangle_cylinder_distance.h"

namespace tricyl::detail::dist {

/// For a disjoint pair whose certified error_bound is wider than 2^-50 of
/// the distance (the double-word allowance, about 2^-95 of the problem's
/// size, dominates below distances of about 2^-45 of it): re-evaluates
/// the distance of the triangle's vertex nearest to the cylinder from the
/// exactly pulled-back vertices (floating-point expansions), with a
/// separating plane along that vertex's gradient, and when that proves
/// the vertex is the nearest point to within the new bound, replaces the
/// result (distance, error_bound, points: the vertex and its projection)
/// if the bound is narrower. Leaves *out alone otherwise (the nearest
/// point is on an edge or the face, an expansion fell outside the exact
/// range, or the new bound is not narrower). Inputs: valid and finite,
/// as tricyl::tryDistance has already checked.
void tightenTiny(const Cylinder<double>& cyl, const Pose<double>& pose,
                     const Triangle<double>& tri, DistanceResult<double>* out);

}  // namespace tricyl::detail::dist
