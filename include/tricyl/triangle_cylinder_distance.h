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
///   It is 0 when distance is 0. It is within 8 ulps of the distance when
///   the distance is above about 2^-45 of the problem's magnitude (the
///   local coordinates, r, lz/2); below, it is the double-word arithmetic's
///   allowance, about 2^-95 of that magnitude (docs/distance.md, sections 4
///   and 6, derive it and give the measured errors); `tightenDistance`
///   (below) brings it to a few ulps there for the nearest features that
///   have a closed form, at a cost paid only by its caller. distance is
///   positive whenever intersect is false (the smallest subnormal if it would
///   round to 0) and +inf only if the true distance exceeds the double range.
/// - `point_on_triangle` and `point_on_cylinder` are p and q = P_C(p), the
///   computed local nearest pair (p in the pulled-back triangle, q its
///   projection onto C), mapped by x = R y + t in double (world overload)
///   or as they are (local overload): each on its set to a few ulps of the
///   coordinates' and the problem's magnitude (docs/distance.md, section
///   5), so not to ulps of a distance much smaller than the coordinates.
///   When R is not orthonormal the world points are the images of the
///   local pair under that map: a point of the world triangle and a point
///   of the posed solid, whose world distance is then NOT the returned
///   distance (which is measured in the cylinder's frame).
/// - When the distance is 0, p is a common point of the two sets (to a few
///   ulps of the problem's magnitude) and q = P_C(p).
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
/// The zero test is the exact Boolean, run whenever a certified lower bound
/// (below) does not already prove the pair disjoint. Otherwise the distance
/// is the minimum over the triangle of the convex function dist(., C): per
/// edge, an end or the root of its monotone derivative (in closed form in
/// the barrel's region, else Newton's method in a shrinking bracket, a
/// fixed cap on the iterations; the hard case, an edge against a rim
/// circle, is a root of a quartic found this way); for the face, the
/// projection of C's support point. A double pass finds the nearest pair;
/// its best candidate is re-evaluated with double-word vertices (the
/// cancelling differences in double-word, the rest in double), and
/// re-solved in double-word only when that does not certify the result.
/// The result is certified by an upper bound (a point of each set) and a
/// lower bound (a separating plane: weak duality), whatever the search
/// found.
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

namespace diagnostic {
/// tryDistance on the portable path: the double-word TwoProduct by
/// Dekker's split even where the CPU has a fused multiply-add (the default
/// path dispatches to it at run time). Both are exact, so the results are
/// the same bits; this exists so that the tests can check that.
template <class S>
Answer tryDistancePortable(const Cylinder<S>& cylinder, const Pose<S>& pose,
                           const Triangle<S>& triangle,
                           DistanceResult<S>* out) noexcept;
extern template Answer tryDistancePortable(const Cylinder<double>&,
                                           const Pose<double>&,
                                           const Triangle<double>&,
                                           DistanceResult<double>*) noexcept;
}  // namespace diagnostic

/// Tightens the certified bound of a tiny distance (opt-in: tryDistance
/// and distance never call it). For a result `*result` of a disjoint pair
/// whose error_bound exceeds 2^-50 of its distance (distances below about
/// 2^-45 of the problem's magnitude, where the double-word allowance
/// dominates), re-evaluates from the exactly pulled-back vertices (floating-
/// point expansions) the candidates whose distance has a closed form — the
/// nearest vertex, an edge beside the barrel, an edge or the face parallel
/// to a cap over its disk, the face in a vertical plane beside the barrel —
/// each with a separating-plane lower bound exactly orthogonal to it, both
/// bounds free of cancellation (docs/distance.md, section 6.1). Where one
/// of them is the nearest feature, replaces the result (distance within
/// 0.5 ulp, error_bound 2 ulps, that feature's nearest pair) and returns
/// true; otherwise (an edge against a rim circle, a tilted face, lengths
/// above 2^120, a distance below 2^-300, invalid input, or no narrower
/// bound) leaves it and returns false. The new bound is certified on its
/// own (it does not rely on *result). Costs some 5-40 µs (expansion
/// arithmetic), hence not part of tryDistance: on the bench_distance
/// families it would run on up to a fifth of the queries (near).
bool tightenDistance(const Cylinder<double>& cylinder, const Pose<double>& pose,
                     const Triangle<double>& triangle,
                     DistanceResult<double>* result) noexcept;

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
extern template Answer tryDistance(const Cylinder<double>&, const Pose<double>&,
                                   const Triangle<double>&,
                                   DistanceResult<double>*) noexcept;

}  // namespace tricyl
