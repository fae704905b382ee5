// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Point in finite solid cone: exact.
///
/// ## Contract
/// - Cone<S>{radius r, lz}: FCL's cone, centred in its own frame, axis +z,
///   apex at (0, 0, +lz/2), base disk of radius r at z = -lz/2.
///   DEFINITION, for every size including the degenerate ones: the closed
///   convex hull of the apex and the base disk. So
///     lz > 0:          |z| <= lz/2 and sqrt(x^2 + y^2) <= r (lz/2 - z) / lz;
///     lz = 0:          the base disk {z = 0, x^2 + y^2 <= r^2} (not the
///                      whole plane z = 0, which the formula would give);
///     r = 0:           the axis segment {x = y = 0, |z| <= lz/2};
///     r = 0, lz = 0:   the single point at the origin.
/// - Pose: y = R^T (x - t) evaluated exactly (types.h); R used as given.
/// - The boundary counts as inside. Exact (no epsilon, no division): the
///   test is the sign of r^2 (lz - 2z)^2 - 4 lz^2 (x^2 + y^2) and of the slab
///   and disk conditions, certified or exact (src/cylinder_queries_impl.h).
/// - The source's form (apex O, axis N into the cone, height L, base radius
///   R: 0 <= (P-O).N <= L, dist to axis <= ((P-O).N) R / L) converts with
///   coneFromApex() of endpoint_form.h.
///
/// INVALID INPUT: as point_cylinder.h (throwing `contains`, non-throwing
/// `tryContains`).
#pragma once

#include "tricyl/types.h"

namespace tricyl {

/// True iff the world point lies in the closed posed cone (see the file
/// contract). Throws InvalidInput on NaN/Inf or a negative size.
template <class S>
bool contains(const Cone<S>& cone, const Pose<S>& pose, const Vec3<S>& point);

/// Non-throwing form: kIntersect (inside), kDisjoint (outside) or
/// kInvalidInput.
template <class S>
Answer tryContains(const Cone<S>& cone, const Pose<S>& pose,
                   const Vec3<S>& point) noexcept;

/// As tryContains, and also reports which stage decided (statistics).
template <class S>
Decision decideContains(const Cone<S>& cone, const Pose<S>& pose,
                        const Vec3<S>& point) noexcept;

extern template bool contains(const Cone<float>&, const Pose<float>&,
                              const Vec3<float>&);
extern template bool contains(const Cone<double>&, const Pose<double>&,
                              const Vec3<double>&);
extern template Answer tryContains(const Cone<float>&, const Pose<float>&,
                                   const Vec3<float>&) noexcept;
extern template Answer tryContains(const Cone<double>&, const Pose<double>&,
                                   const Vec3<double>&) noexcept;
extern template Decision decideContains(const Cone<float>&, const Pose<float>&,
                                        const Vec3<float>&) noexcept;
extern template Decision decideContains(const Cone<double>&,
                                        const Pose<double>&,
                                        const Vec3<double>&) noexcept;

}  // namespace tricyl
