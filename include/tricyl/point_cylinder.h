// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Point in finite solid cylinder: exact.
///
/// ## Contract
/// - Cylinder and Pose: as for the triangle kernel (types.h): the point x is
///   inside iff y = R^T (x - t), evaluated exactly, satisfies
///   y0^2 + y1^2 <= r^2 and |y2| <= lz/2. R is used exactly as given.
/// - The boundary counts as inside. r = 0 (the axis segment) and lz = 0 (a
///   flat disk) are valid.
/// - Exact for the float or double inputs as given: no epsilon. Decided by
///   the certified double filter, the certified extended filter or the exact
///   GMP fallback of src/filter.h (the triangle kernel's mechanism).
/// - The source's formula 0 <= (P-O).N <= L, |(P-O) - ((P-O).N) N| <= R is
///   this test for the endpoint form; see endpoint_form.h for the conversion.
///
/// ## Invalid input
/// - `contains` throws InvalidInput on NaN/Inf anywhere or a negative radius
///   or length; `tryContains` returns Answer::kInvalidInput instead.
///   Answer::kIntersect means "inside or on the boundary".
#pragma once

#include "tricyl/types.h"

namespace tricyl {

/// True iff the world point lies in the closed posed cylinder (see the
/// file contract). Throws InvalidInput on NaN/Inf or a negative size.
template <class S>
bool contains(const Cylinder<S>& cylinder, const Pose<S>& pose,
              const Vec3<S>& point);

/// Non-throwing form: kIntersect (inside), kDisjoint (outside) or
/// kInvalidInput.
template <class S>
Answer tryContains(const Cylinder<S>& cylinder, const Pose<S>& pose,
                   const Vec3<S>& point) noexcept;

/// As tryContains, and also reports which stage decided (statistics).
template <class S>
Decision decideContains(const Cylinder<S>& cylinder, const Pose<S>& pose,
                        const Vec3<S>& point) noexcept;

extern template bool contains(const Cylinder<float>&, const Pose<float>&,
                              const Vec3<float>&);
extern template bool contains(const Cylinder<double>&, const Pose<double>&,
                              const Vec3<double>&);
extern template Answer tryContains(const Cylinder<float>&, const Pose<float>&,
                                   const Vec3<float>&) noexcept;
extern template Answer tryContains(const Cylinder<double>&, const Pose<double>&,
                                   const Vec3<double>&) noexcept;
extern template Decision decideContains(const Cylinder<float>&,
                                        const Pose<float>&,
                                        const Vec3<float>&) noexcept;
extern template Decision decideContains(const Cylinder<double>&,
                                        const Pose<double>&,
                                        const Vec3<double>&) noexcept;

}  // namespace tricyl
