// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Triangle vs finite solid cylinder: certified Euclidean distance and a pair
/// of nearest points.
///
/// ## Contract
/// - Cylinder, Pose and Triangle: exactly as for `intersect`
///   (triangle_cylinder.h, types.h). The distance is that of the
///   pulled-back triangle T' = { R^T (x - t) : x in T } (R and t used as
///   given, never re-orthonormalised) to the closed solid
///       C = { y : y0^2 + y1^2 <= r^2, |y2| <= lz/2 }
///   in the cylinder's frame. When R is orthonormal this is the world
///   Euclidean distance; when R is a rounded rotation it is the only
///   definition that stays consistent with the exact Boolean.
///   r = 0 (the axis segment), lz = 0 (a flat disk) and degenerate
///   triangles (segments, points) are valid.
/// - `distance` is >= 0 and is exactly 0 iff `intersect` is true for the
///   same inputs: the zero test IS the exact Boolean, so the two never
///   disagree.
/// - `error_bound` is certified: |distance - true distance| <= error_bound.
///   It is 0 when distance is 0. For a positive distance it is a few ulps of
///   the distance (docs/distance.md derives the bound: relative error
///   <= 8 ulps of the true distance for double, except for distances in or
///   near the subnormal range, where error_bound states the absolute
///   accuracy actually reached).
/// - `point_on_cylinder` lies in C and `point_on_triangle` in T' (each up to
///   the rounding stated in docs/distance.md) and their distance is the
///   returned distance up to error_bound. The world overload reports both
///   points in the world frame: the local points y mapped by x = R y + t
///   (rounded once more). When R is not orthonormal the world points are the
///   images of the local nearest points under that map: a point on the world
///   triangle and a point on the posed solid, whose world distance is then
///   NOT the returned distance (which is measured in the cylinder's frame).
///   The local overload reports local points.
/// - When the distance is 0 both points are one common point of the two
///   sets (rounded to S).
/// - Bounded time: no unbounded iteration anywhere.
///
/// ## Invalid input
/// - `distance` throws tricyl::InvalidInput on NaN or Inf anywhere, or a
///   negative radius or length (the policy of `intersect`).
/// - `tryDistance` is noexcept and returns Answer::kInvalidInput instead
///   (leaving *out unchanged); otherwise kIntersect (distance 0) or
///   kDisjoint (distance > 0), with the result in *out (when out != null).
///
/// ## Method (docs/distance.md)
/// The zero test is the exact Boolean. Otherwise the distance is the
/// minimum over feature pairs of the triangle (face, edges, vertices) and of
/// the cylinder (barrel, cap disks, rim circles); each pair is a closed-form
/// or a bounded one-dimensional root-finding problem (segment vs rim circle:
/// a quartic stationarity condition solved by safeguarded Newton on a
/// bracketing interval with a fixed iteration cap), evaluated in double with
/// a compensated (double-word) refinement where the double result cannot be
/// certified to the target accuracy.
#pragma once

#include "tricyl/types.h"

namespace tricyl {

/// The result of `distance`: the distance, a pair of nearest points and a
/// certified bound on the distance's error.
template <class S>
struct DistanceResult {
  S distance;                 ///< >= 0; exactly 0 iff intersect(...) is true
  Vec3<S> point_on_cylinder;  ///< world frame (local frame for the local
                              ///< overload)
  Vec3<S> point_on_triangle;  ///< world frame (local frame for the local
                              ///< overload)
  S error_bound;  ///< certified: |distance - true distance| <= error_bound
};

/// World-frame triangle vs posed cylinder. Throws InvalidInput (see above).
template <class S>
DistanceResult<S> distance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                           const Triangle<S>& triangle);

/// Triangle already in the cylinder's frame; the points are local.
/// Throws InvalidInput.
template <class S>
DistanceResult<S> distance(const Cylinder<S>& cylinder,
                           const Triangle<S>& triangle);

/// Non-throwing form: kIntersect (distance 0), kDisjoint (distance > 0) or
/// kInvalidInput (then *out is left unchanged). `out` may be null.
template <class S>
Answer tryDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                   const Triangle<S>& triangle,
                   DistanceResult<S>* out) noexcept;

extern template DistanceResult<float> distance(const Cylinder<float>&,
                                               const Pose<float>&,
                                               const Triangle<float>&);
extern template DistanceResult<double> distance(const Cylinder<double>&,
                                                const Pose<double>&,
                                                const Triangle<double>&);
extern template DistanceResult<float> distance(const Cylinder<float>&,
                                               const Triangle<float>&);
extern template DistanceResult<double> distance(const Cylinder<double>&,
                                                const Triangle<double>&);
extern template Answer tryDistance(const Cylinder<float>&, const Pose<float>&,
                                   const Triangle<float>&,
                                   DistanceResult<float>*) noexcept;
extern template Answer tryDistance(const Cylinder<double>&,
                                   const Pose<double>&,
                                   const Triangle<double>&,
                                   DistanceResult<double>*) noexcept;

}  // namespace tricyl
