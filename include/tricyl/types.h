// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// tricyl: plain aggregate types shared by every query.
///
/// Conventions (the same for every header in include/tricyl/):
/// - Cylinder<S>{radius, lz}: FCL's convention. Centred at the origin of its
///   own frame, axis +z, full length lz: the closed solid
///       { y : y0^2 + y1^2 <= radius^2, |y2| <= lz/2 }.
/// - Pose<S>{R, t}: world = R * local + t, R row-major, exactly as FCL's
///   Transform3 holds linear() and translation(). A world point x maps to the
///   local point y = R^T (x - t), and every query evaluates that map EXACTLY:
///   R is used as given, never re-orthonormalised. A rotation a hair off
///   orthonormal is fine; the solid is then the exact preimage under that map.
/// - Triangle<S>{a, b, c}: the closed convex hull of three points. Collinear or
///   coincident vertices are valid: the hull is a segment or a point.
/// - Answers are exact for the inputs as given (no epsilon, no tolerance
///   parameter). Touching counts as intersecting.
#pragma once

#include <stdexcept>

namespace tricyl {

/// A point or vector, three coordinates.
template <class S>
struct Vec3 {
  S x;  ///< first coordinate
  S y;  ///< second coordinate
  S z;  ///< third coordinate
};

/// FCL's cylinder: centred at the origin of its frame, axis +z, the closed
/// solid { y : y0^2 + y1^2 <= radius^2, |y2| <= lz/2 }.
template <class S>
struct Cylinder {
  S radius;  ///< r >= 0
  S lz;      ///< full length, >= 0; the solid spans |z| <= lz/2
};

/// FCL's cone: centred, apex at z = +lz/2, base disk of radius `radius` at
/// z = -lz/2.
template <class S>
struct Cone {
  S radius;  ///< base radius, >= 0
  S lz;      ///< full length (apex to base), >= 0
};

/// A rigid placement as FCL's Transform3 holds it: world = R * local + t.
/// Every query maps a world point x to y = R^T (x - t) exactly; R is used as
/// given, never re-orthonormalised.
template <class S>
struct Pose {
  S R[3][3];  ///< row-major; world = R * local + t
  Vec3<S> t;  ///< translation
};

/// The closed convex hull of three points (collinear or coincident points
/// are valid: a segment or a point).
template <class S>
struct Triangle {
  Vec3<S> a;  ///< first vertex
  Vec3<S> b;  ///< second vertex
  Vec3<S> c;  ///< third vertex
};

/// The points p (1 - s) + q s for s in [0, 1].
template <class S>
struct Segment {
  Vec3<S> p;  ///< the point at s = 0
  Vec3<S> q;  ///< the point at s = 1
};

/// The unbounded line: the points p (1 - s) + q s for every real s (so
/// s = 0 at p, s = 1 at q). p == q is valid and is the single point p; the
/// queries of line_cylinder.h then answer for that point, and `clip`
/// returns the whole real line [-inf, +inf] when it is inside.
template <class S>
struct Line {
  Vec3<S> p;  ///< the point at s = 0
  Vec3<S> q;  ///< the point at s = 1
};

/// The closed ball of `radius` around `center`.
template <class S>
struct Sphere {
  Vec3<S> center;  ///< centre
  S radius;        ///< >= 0
};

/// A closed parameter interval [lo, hi] (for a Line, an end may be
/// infinite; see line_cylinder.h).
template <class S>
struct Interval {
  S lo;  ///< lower end
  S hi;  ///< upper end
};

/// The identity pose: local coordinates are world coordinates.
template <class S>
constexpr Pose<S> identityPose() {
  return Pose<S>{{{S(1), S(0), S(0)}, {S(0), S(1), S(0)}, {S(0), S(0), S(1)}},
                 {S(0), S(0), S(0)}};
}

/// Outcome of a non-throwing query.
enum class Answer : unsigned char {
  kDisjoint = 0,      ///< the closed sets share no point
  kIntersect = 1,     ///< the closed sets share at least one point
  kInvalidInput = 2,  ///< NaN or Inf somewhere, or a negative size
};

/// Which stage of the kernel decided a query (for statistics only; it never
/// changes the answer). A query is first run in double with a certified
/// error bound; where a sign stays open, the query runs once more and only
/// the open signs are re-decided in stronger arithmetic (docs/exactness.md):
/// the stage is the strongest arithmetic any sign of the query needed.
enum class Stage : unsigned char {
  kEarlyOut = 0,  ///< a cheap certified rejection (slab or bounding box)
  kFastPath = 1,  ///< double predicates with a certified error bound
  kExact = 2,     ///< some sign decided exactly: an exact tie certified
                  ///< by exact double or double-word values, or stack
                  ///< floating-point expansions (no heap allocation)
  kInvalid = 3,   ///< input rejected before any arithmetic
  kExtended = 4,  ///< some sign decided in double-word arithmetic (about
                  ///< 106 bits) with a running error bound, none exactly
  kRunning = 5,   ///< some sign the double filter left open decided in
                  ///< double with a running error bound (which follows the
                  ///< values, where the filter's follows their magnitudes),
                  ///< none in double word or exactly (the triangle)
  kExactGmp = 6,  ///< some sign decided exactly with GMP (inputs outside
                  ///< the expansions' exponent window)
};

/// The answer of a query and the kernel stage that decided it.
struct Decision {
  Answer answer;  ///< the answer, exactly as tryIntersect gives it
  Stage stage;    ///< which stage decided (statistics only)
};

/// Thrown by the checked entry points (`intersect`, `contains`, `clip`) when
/// an input is NaN or infinite, or a radius or length is negative.
class InvalidInput : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

}  // namespace tricyl
