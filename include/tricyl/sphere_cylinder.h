// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Sphere vs finite solid cylinder: exact Boolean.
///
/// ## Contract
/// - Cylinder and Pose: as for the triangle kernel (types.h).
/// - Sphere<S>{center, radius rho}: the centre is a world point; it is mapped
///   exactly to the cylinder frame, c = R^T (center - t). The radius is taken
///   IN THE CYLINDER FRAME: the tested solid is the local ball
///       B = { y : |y - c| <= rho }.
///   "R treated as a rotation" means exactly this. For an orthonormal R, B is
///   the world sphere of radius rho about `center`. For a non-orthonormal R
///   (a rotation rounded to floating point, or anything else), the world
///   solid is the preimage of B under x -> R^T (x - t), the ellipsoid
///       { x : |R^T (x - center)| <= rho },
///   whose semi-axes are rho / sigma_i (sigma_i the singular values of R);
///   for a rotation a few ulps off orthonormal that is rho (1 + O(ulp)). The
///   answer is exact for that solid; nothing is re-orthonormalised.
/// - Touching counts as intersecting. rho = 0 is point containment; r = 0
///   and lz = 0 are valid.
/// - METHOD: the source's case split on the centre's height (beyond the top
///   cap, within the slab, beyond the bottom cap) with the radial test
///   against R + f, f = sqrt(rho^2 - e^2) the radius of the sphere's slice at
///   the cap plane, e the height above it. Both sides are squared only where
///   both are non-negative, so the decision is the sign of polynomials of
///   degree <= 8, with no sqrt and no division, certified in double or long
///   double or decided exactly (src/cylinder_queries_impl.h).
///
/// INVALID INPUT: `intersect` throws InvalidInput on NaN/Inf anywhere or a
/// negative radius, length or sphere radius; `tryIntersect` returns
/// Answer::kInvalidInput instead.
#pragma once

#include "tricyl/types.h"

namespace tricyl {

/// True iff the closed ball meets the closed posed cylinder (see the file
/// contract). Throws InvalidInput on NaN/Inf or a negative size.
template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Sphere<S>& sphere);

/// Non-throwing form: kIntersect, kDisjoint or kInvalidInput.
template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Sphere<S>& sphere) noexcept;

/// As tryIntersect, and also reports which stage decided (statistics).
template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Sphere<S>& sphere) noexcept;

extern template bool intersect(const Cylinder<float>&, const Pose<float>&,
                               const Sphere<float>&);
extern template bool intersect(const Cylinder<double>&, const Pose<double>&,
                               const Sphere<double>&);
extern template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                                    const Sphere<float>&) noexcept;
extern template Answer tryIntersect(const Cylinder<double>&,
                                    const Pose<double>&,
                                    const Sphere<double>&) noexcept;
extern template Decision decideIntersect(const Cylinder<float>&,
                                         const Pose<float>&,
                                         const Sphere<float>&) noexcept;
extern template Decision decideIntersect(const Cylinder<double>&,
                                         const Pose<double>&,
                                         const Sphere<double>&) noexcept;

}  // namespace tricyl
