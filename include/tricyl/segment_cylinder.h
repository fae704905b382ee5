// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Segment vs finite solid cylinder: exact Boolean, and the entry/exit
/// interval.
///
/// ## Contract
/// - Cylinder and Pose: as for the triangle kernel (types.h); R used exactly
///   as given.
/// - Segment<S>{p, q}: the points p (1 - s) + q s, s in [0, 1]; p == q (a
///   point) is valid.
/// - intersect: true iff the closed segment meets the closed cylinder.
///   Touching counts. Exact (no epsilon): the segment case of the triangle
///   kernel's tests (V) endpoint inside, (X) cap-plane crossing inside the cap
///   disk, (E) closest approach to the axis interior, within r and between the
///   caps, certified in double or long double or decided exactly with GMP.
///   The source's pseudo-code (accept iff a root of the infinite-cylinder
///   quadratic lies in [0, 1]) is wrong for a segment entirely inside, for a
///   root beyond the caps and for a segment through a cap disk; those cases
///   are regression tests (tests/segment_cylinder_test.cpp).
/// - clip: the set { s in [0, 1] : p(s) in cylinder } is a closed interval
///   (the cylinder is convex) or empty. It is computed as the intersection of
///   [0, 1], the slab interval {|z(s)| <= lz/2} and the infinite-cylinder
///   interval {x(s)^2 + y(s)^2 <= r^2} (Freesteel's "intersection of two
///   volumes": no separate side/cap surfaces, hence no crack at the rims).
///   * Emptiness is decided EXACTLY by the same decision as `intersect`:
///     clip(...).has_value() == intersect(...) always.
///   * Endpoints: lo <= hi, both in [0, 1]. For double, |lo - lo*| and
///     |hi - hi*| <= 1e-14 where lo*, hi* are the exact endpoints for the
///     inputs as given (the implementation guarantees about 2e-15, see
///     src/segment_cylinder.cpp). For float the double result is rounded to
///     the nearest float (error <= 2^-25 + 1e-14); rounding to nearest is
///     monotone, so lo <= hi still holds.
///   * Grazing lines (the discriminant r^2 |d|^2 - (p x d)^2 cancels) and
///     lines through the rim are computed with a running error bound in long
///     double; when that bound exceeds 2^-49 the endpoints are recomputed from
///     the exact (GMP) coordinates with a multi-precision square root.
///   * A tangent segment (touching the side along one point) or a segment
///     touching only a rim gives lo == hi (up to the bound).
///
/// INVALID INPUT: `intersect` and `clip` throw InvalidInput on NaN/Inf
/// anywhere or a negative radius or length; `tryIntersect` and `tryClip`
/// return Answer::kInvalidInput instead.
#pragma once

#include <optional>

#include "tricyl/types.h"

namespace tricyl {

/// True iff the closed segment meets the closed posed cylinder (see the
/// file contract). Throws InvalidInput on NaN/Inf or a negative size.
template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Segment<S>& segment);

/// Non-throwing form: kIntersect, kDisjoint or kInvalidInput.
template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Segment<S>& segment) noexcept;

/// As tryIntersect, and also reports which stage decided (statistics).
template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Segment<S>& segment) noexcept;

/// The entry/exit interval, or nullopt when the segment misses. Throws
/// InvalidInput.
template <class S>
std::optional<Interval<S>> clip(const Cylinder<S>& cylinder,
                                const Pose<S>& pose, const Segment<S>& segment);

/// Non-throwing form: kIntersect (and `*out` set), kDisjoint (`*out`
/// untouched) or kInvalidInput.
template <class S>
Answer tryClip(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Segment<S>& segment, Interval<S>* out) noexcept;

extern template bool intersect(const Cylinder<float>&, const Pose<float>&,
                               const Segment<float>&);
extern template bool intersect(const Cylinder<double>&, const Pose<double>&,
                               const Segment<double>&);
extern template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                                    const Segment<float>&) noexcept;
extern template Answer tryIntersect(const Cylinder<double>&,
                                    const Pose<double>&,
                                    const Segment<double>&) noexcept;
extern template Decision decideIntersect(const Cylinder<float>&,
                                         const Pose<float>&,
                                         const Segment<float>&) noexcept;
extern template Decision decideIntersect(const Cylinder<double>&,
                                         const Pose<double>&,
                                         const Segment<double>&) noexcept;
extern template std::optional<Interval<float>> clip(const Cylinder<float>&,
                                                    const Pose<float>&,
                                                    const Segment<float>&);
extern template std::optional<Interval<double>> clip(const Cylinder<double>&,
                                                     const Pose<double>&,
                                                     const Segment<double>&);
extern template Answer tryClip(const Cylinder<float>&, const Pose<float>&,
                               const Segment<float>&,
                               Interval<float>*) noexcept;
extern template Answer tryClip(const Cylinder<double>&, const Pose<double>&,
                               const Segment<double>&,
                               Interval<double>*) noexcept;

}  // namespace tricyl
