// SPDX-License-Identifier: BSD-3-Clause
// The tightening step for tiny distances (docs/distance.md, section 6.1):
// internal, behind tricyl::tightenDistance.
#pragma once

#include "tricyl/triangle_cylinder_distance.h"

namespace tricyl::detail::dist {

/// The work of tricyl::tightenDistance (its contract): replaces *out by
/// the narrowest certified enclosure of the candidates with a closed form
/// (the nearest vertex, an edge beside the barrel, an edge or the face
/// parallel to a cap, the face in a vertical plane beside the barrel) when
/// that is narrower than out->error_bound; leaves it otherwise. Inputs
/// finite with r, lz >= 0 (anything beyond 2^120 is left alone).
void tightenTiny(const Cylinder<double>& cyl, const Pose<double>& pose,
                 const Triangle<double>& tri, DistanceResult<double>* out);

}  // namespace tricyl::detail::dist
