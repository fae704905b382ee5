// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Triangle vs the margin-neighbourhood of a finite solid cylinder: an exact
/// safety-margin test ("is the triangle within distance m of the cylinder?").
///
/// ## Contract
/// - Cylinder, Pose, Triangle: exactly as for `intersect` (types.h,
///   triangle_cylinder.h). The triangle is pulled back exactly,
///   y = R^T (x - t), and the test is made in the cylinder's frame.
/// - margin m >= 0: the tested solid is the closed m-neighbourhood of the
///   cylinder C, the Minkowski sum with the closed ball B_m,
///       C + B_m = { y : dist(y, C) <= m }.
///   This is NOT the cylinder with r and lz grown by m: its rims are rounded
///   (it is Cyl(r + m, lz/2) u Cyl(r, lz/2 + m) u two solid tori of tube
///   radius m around the rim circles).
/// - Answer: true iff the closed triangle meets C + B_m, i.e. iff the
///   Euclidean distance between the triangle (as pulled back) and C is <= m.
///   Exact for the float or double inputs as given: r + m, lz/2 + m and the
///   quartic distance from an edge to a rim circle are never rounded; ties
///   (distance exactly m) answer true. margin = 0 answers exactly as
///   `intersect`.
/// - For an orthonormal R this is the world distance; for a rounded rotation
///   it is the distance of the pulled-back triangle, the one definition
///   consistent with the exact Boolean (as for `tricyl::distance`).
/// - Bounded time: no iteration whose count depends on the data beyond fixed
///   bounds (docs/margin.md).
///
/// ## Invalid input
/// - `withinDistance` throws tricyl::InvalidInput if any coordinate, pose
///   entry, radius, length or the margin is NaN or infinite, or if radius, lz
///   or margin is negative. `tryWithinDistance` is noexcept and returns
///   Answer::kInvalidInput instead. Validation reads bit patterns before any
///   arithmetic: no input raises FE_INVALID or FE_DIVBYZERO.
///
/// ## Method
/// docs/margin.md: the decomposition above, each part decided by the exact
/// triangle kernel or by sign conditions on polynomials with dyadic
/// coefficients, with a certified floating-point filter in front.
#pragma once

#include "tricyl/types.h"

namespace tricyl {

/// World-frame triangle vs the margin-neighbourhood of a posed cylinder.
/// Throws InvalidInput (see above).
template <class S>
bool withinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle, S margin);

/// Triangle already in the cylinder's frame. Throws InvalidInput.
template <class S>
bool withinDistance(const Cylinder<S>& cylinder, const Triangle<S>& triangle,
                    S margin);

/// Non-throwing form: kIntersect (within the margin), kDisjoint or
/// kInvalidInput.
template <class S>
Answer tryWithinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Triangle<S>& triangle, S margin) noexcept;

/// As tryWithinDistance, and also reports which stage decided (statistics):
/// kEarlyOut (outside the grown cylinder Cyl(r + m, lz/2 + m)), kFastPath
/// (the exact triangle kernel on the parts and the double torus filter),
/// kExactGmp (some part needed GMP), or what the adaptive kernel reports.
template <class S>
Decision decideWithinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                              const Triangle<S>& triangle, S margin) noexcept;

extern template bool withinDistance(const Cylinder<float>&, const Pose<float>&,
                                    const Triangle<float>&, float);
extern template bool withinDistance(const Cylinder<double>&,
                                    const Pose<double>&,
                                    const Triangle<double>&, double);
extern template bool withinDistance(const Cylinder<float>&,
                                    const Triangle<float>&, float);
extern template bool withinDistance(const Cylinder<double>&,
                                    const Triangle<double>&, double);
extern template Answer tryWithinDistance(const Cylinder<float>&,
                                         const Pose<float>&,
                                         const Triangle<float>&,
                                         float) noexcept;
extern template Answer tryWithinDistance(const Cylinder<double>&,
                                         const Pose<double>&,
                                         const Triangle<double>&,
                                         double) noexcept;
extern template Decision decideWithinDistance(const Cylinder<float>&,
                                              const Pose<float>&,
                                              const Triangle<float>&,
                                              float) noexcept;
extern template Decision decideWithinDistance(const Cylinder<double>&,
                                              const Pose<double>&,
                                              const Triangle<double>&,
                                              double) noexcept;

}  // namespace tricyl
