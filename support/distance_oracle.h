// SPDX-License-Identifier: BSD-3-Clause
// A high-precision, self-certifying oracle for the triangle-cylinder
// distance (tests, fuzz checks, benchmarks and tricyl-compare judge
// tricyl::distance and FCL against it). Needs MPFR (Debian: libmpfr-dev),
// used through Boost.Multiprecision at 100 decimal digits (333 bits).
//
// Method (docs/distance.md, section 7): the zero test is tricyl::intersect
// (exact). Otherwise the pulled-back triangle is formed in 333-bit
// arithmetic, each edge's convex distance function is minimised by a
// bracketed Newton/bisection to 2^-320 in the parameter, the face by the
// support-point projection, and the result is CERTIFIED by two bounds that
// hold whatever the search found: the distance between a point of the
// triangle and a point of the cylinder (upper) and a separating plane
// (lower, weak duality). The enclosure [lo, hi] adds a rounding allowance
// of 2^-320 times the problem's magnitude to each side; `tight` says that
// the two bounds met (relative width <= 2^-200), which is what every use
// of the oracle checks before it judges anything.
#pragma once

#include "tricyl/types.h"

namespace tricyl::oracle {

/// The oracle's answer for one query.
struct DistanceEnclosure {
  bool intersect = false;  ///< exact: the sets meet (distance 0)
  double lo = 0;           ///< lo <= true distance (rounded down)
  double hi = 0;           ///< true distance <= hi (rounded up)
  double mid_hi = 0;       ///< the distance ~ mid_hi + mid_lo: a
  double mid_lo = 0;       ///< double-word value inside [lo, hi]
  double rel_width = 0;    ///< (hi - lo) / distance, computed at 333 bits
  bool tight = false;      ///< rel_width <= 2^-200 (or intersect)
};

/// The certified distance of the pulled-back triangle R^T (x - t) to the
/// solid cylinder (the contract of tricyl::distance). Valid, finite
/// inputs only (the caller checks).
DistanceEnclosure distanceEnclosure(const Cylinder<double>& cylinder,
                                    const Pose<double>& pose,
                                    const Triangle<double>& triangle);

/// |d - true distance| in units of ulp(true distance) = 2^(e - 52) for a
/// true distance in [2^e, 2^(e+1)) (the ulp of the smallest normal double
/// below 2^-1022). 0 when both are 0, +inf when exactly one is 0.
double ulpsError(const DistanceEnclosure& e, double d);

/// |d - true distance| / true distance (0 or +inf as ulpsError).
double relativeError(const DistanceEnclosure& e, double d);

/// The distance of the world point x, pulled back to y = R^T (x - t), to
/// the solid cylinder, at 333 bits, rounded up.
double pointCylinderDistance(const Cylinder<double>& cylinder,
                             const Pose<double>& pose, const Vec3<double>& x);

/// The distance of the world point x to the world triangle (its closed
/// convex hull), at 333 bits, rounded up.
double pointTriangleDistance(const Triangle<double>& triangle,
                             const Vec3<double>& x);

}  // namespace tricyl::oracle
