// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Line vs finite solid cylinder: exact Boolean, and the entry/exit interval
/// along the unbounded line.
///
/// ## Contract
/// - Cylinder and Pose: as for the triangle kernel (types.h); R used exactly
///   as given.
/// - Line<S>{p, q}: the points p (1 - s) + q s for every real s (s = 0 at p,
///   s = 1 at q). p == q is valid: the line is then the single point p.
///   More generally, if the local direction R^T (q - p) is zero (p == q, or
///   a singular R), every s maps to the same local point.
/// - intersect: true iff the line meets the closed cylinder. Touching counts
///   (a line tangent to the side, through a rim point, or lying in a cap
///   plane and meeting the cap disk). Exact (no epsilon): (V) p inside;
///   (X) the line's crossing with a cap plane (if it is not parallel to it)
///   inside the cap disk; (E) the closest approach of the projected line to
///   the axis within r at a height inside the slab; the segment's tests
///   without the segment's interior conditions, certified in double or long
///   double or decided exactly with GMP (src/cylinder_queries_impl.h,
///   lineCylinder). For p == q it is exactly "p is inside".
/// - clip: the set { s real : p(s) in cylinder } is a closed interval (the
///   cylinder is convex) or empty. For R^T (q - p) != 0 it is bounded (the
///   cylinder is bounded); for R^T (q - p) == 0 with p inside it is the whole
///   real line, returned as [-inf, +inf] (the only case with an infinite end
///   other than overflow, below). It is computed as the intersection of the
///   slab interval {|z(s)| <= lz/2} and the infinite-cylinder interval
///   {x(s)^2 + y(s)^2 <= r^2} (Freesteel's "intersection of two volumes": no
///   separate side/cap surfaces, hence no crack at the rims), by the same
///   code as the segment's clip (a segment is this line restricted to
///   [0, 1]): src/line_cylinder_interval.cpp.
///   * Emptiness is decided EXACTLY by the same decision as `intersect`:
///     clip(...).has_value() == intersect(...) always.
///   * Endpoints: lo <= hi. For double, |lo - lo*| <= 1e-14 max(1, |lo*|)
///     and |hi - hi*| <= 1e-14 max(1, |hi*|), where lo*, hi* are the exact
///     endpoints for the inputs as given (the implementation guarantees
///     1.9e-15 max(1, |s*|); a RELATIVE bound because the parameter is
///     unbounded: |s*| grows as |q - p| shrinks or as p moves away along the
///     line). For float the double result is rounded to the nearest float:
///     error <= (2^-24 + 1e-14) max(1, |s*|); rounding is monotone, so
///     lo <= hi still holds.
///   * Overflow: |s*| may exceed the largest finite S (p and q very close
///     together, e.g. a subnormal |q - p| against a cylinder of size 1). An
///     end beyond the finite range of S is returned as the infinity of its
///     sign (an end within the bound of that limit may come back either as
///     the infinity or as a finite value within the bound): no undefined
///     behaviour, no NaN, no exception, lo <= hi still holds. The bound above
///     applies to the finite ends. Every stage tests its quotients before
///     use (values beyond max/4 go to the exact stage) and converts to S
///     explicitly.
///   * Grazing lines (the discriminant r^2 |d|^2 - (p x d)^2 cancels) and
///     lines through the rim are computed with a running error bound in
///     double, then long double; when that bound exceeds
///     2^-49 max(1, |s|) the endpoints are recomputed from the exact (GMP)
///     coordinates with a multi-precision square root.
///   * A tangent line (touching the side along one point) or a line touching
///     only a rim gives lo == hi (up to the bound).
///   * Consistency with the segment: clip(Segment{p, q}) equals
///     clip(Line{p, q}) intersected with [0, 1] up to the bounds, and
///     intersect(Segment{p, q}) implies intersect(Line{p, q}).
///
/// INVALID INPUT: `intersect` and `clip` throw InvalidInput on NaN/Inf
/// anywhere or a negative radius or length; `tryIntersect` and `tryClip`
/// return Answer::kInvalidInput instead.
#pragma once

#include <optional>

#include "tricyl/types.h"

namespace tricyl {

/// True iff the line meets the closed posed cylinder (see the file
/// contract). Throws InvalidInput on NaN/Inf or a negative size.
template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Line<S>& line);

/// Non-throwing form: kIntersect, kDisjoint or kInvalidInput.
template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Line<S>& line) noexcept;

/// As tryIntersect, and also reports which stage decided (statistics).
template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Line<S>& line) noexcept;

/// The entry/exit interval { s : p(s) in cylinder }, or nullopt when the
/// line misses. Throws InvalidInput.
template <class S>
std::optional<Interval<S>> clip(const Cylinder<S>& cylinder,
                                const Pose<S>& pose, const Line<S>& line);

/// Non-throwing form: kIntersect (and `*out` set), kDisjoint (`*out`
/// untouched) or kInvalidInput.
template <class S>
Answer tryClip(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Line<S>& line, Interval<S>* out) noexcept;

extern template bool intersect(const Cylinder<float>&, const Pose<float>&,
                               const Line<float>&);
extern template bool intersect(const Cylinder<double>&, const Pose<double>&,
                               const Line<double>&);
extern template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                                    const Line<float>&) noexcept;
extern template Answer tryIntersect(const Cylinder<double>&,
                                    const Pose<double>&,
                                    const Line<double>&) noexcept;
extern template Decision decideIntersect(const Cylinder<float>&,
                                         const Pose<float>&,
                                         const Line<float>&) noexcept;
extern template Decision decideIntersect(const Cylinder<double>&,
                                         const Pose<double>&,
                                         const Line<double>&) noexcept;
extern template std::optional<Interval<float>> clip(const Cylinder<float>&,
                                                    const Pose<float>&,
                                                    const Line<float>&);
extern template std::optional<Interval<double>> clip(const Cylinder<double>&,
                                                     const Pose<double>&,
                                                     const Line<double>&);
extern template Answer tryClip(const Cylinder<float>&, const Pose<float>&,
                               const Line<float>&, Interval<float>*) noexcept;
extern template Answer tryClip(const Cylinder<double>&, const Pose<double>&,
                               const Line<double>&, Interval<double>*) noexcept;

}  // namespace tricyl
