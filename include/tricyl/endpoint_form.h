// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// The endpoint form of the sources, converted to tricyl's Pose + shape.
///
/// The sources describe a cylinder by an axis from O along a direction N for
/// a length L (or from a to b) and a radius R, and a cone by its apex O, the
/// axis direction N into the cone, the height L and the base radius R.
/// tricyl's shapes are FCL's: centred in their own frame, axis +z (types.h).
/// These helpers build that pose. The queries are then exact FOR THE
/// RETURNED POSE AND SHAPE; the conversion itself rounds as stated below, so
/// the returned solid can differ from the ideal endpoint-form solid by a few
/// ulps of the inputs' magnitude.
///
/// What is exact and what rounds (round to nearest, double or float):
/// - radius: copied, exact.
/// - lz: cylinderFromAxis / coneFromApex copy L exactly. cylinderFromEndpoints
///   computes d = b - a (one rounding per coordinate) and L = |d| (a few
///   ulps, also scaled first: +Inf only if |d| exceeds the largest finite
///   value).
/// - axis column R[.][2] = n = N / |N| (N need not be unit; |N| and the
///   division round: a few ulps; n has unit length to a few ulps). This holds
///   for every finite non-zero N, however huge or tiny: N is scaled by a power
///   of two before it is squared (detail::scaledLength), so no square
///   overflows or underflows (found by fuzz_point_cylinder: unscaled, |N| >
///   1.3e154 gave a zero axis and |N| < 2e-162 silently gave +z). For
///   coneFromApex the column is -n (the apex is at +lz/2), negation exact.
/// - the two other columns: Duff et al., "Building an Orthonormal Basis,
///   Revisited" (JCGT 2017), branch-free from n: orthonormal to a few ulps.
///   Their choice is irrelevant to every query here (all are symmetric about
///   the axis) except through those ulps.
/// - centre t: cylinderFromAxis t = O + n (L/2): L/2 is exact except for a
///   subnormal L; the product and the sum round (two roundings per
///   coordinate). cylinderFromEndpoints t = a/2 + b/2 (one rounding per
///   coordinate; halving exact except for subnormals). coneFromApex
///   t = O + n (L/2) like cylinderFromAxis.
/// Degenerate directions: N = 0 (or a == b) has no axis; the helpers then use
/// n = +z, so cylinderFromEndpoints(a, a, R) is the disk of radius R about a
/// in the plane z = a.z (lz = 0). A NaN or infinite N (or a, b) gives a NaN
/// axis. Inputs are not validated here; the queries validate what they are
/// given, so non-finite inputs end as InvalidInput there.
#pragma once

#include <cmath>
#include <limits>

#include "tricyl/types.h"

namespace tricyl {

/// A cylinder and its pose, as the endpoint and axis forms build them.
template <class S>
struct PosedCylinder {
  Cylinder<S> cylinder;  ///< FCL's cylinder (centred, axis +z)
  Pose<S> pose;          ///< its placement: world = R local + t
};

/// A cone and its pose, as coneFromApex builds them.
template <class S>
struct PosedCone {
  Cone<S> cone;  ///< FCL's cone (centred, apex at z = +lz/2)
  Pose<S> pose;  ///< its placement: world = R local + t
};

namespace detail {
/// Rotation whose third column is the unit vector n (Duff et al. 2017).
template <class S>
Pose<S> frameFromAxis(const Vec3<S>& n, const Vec3<S>& t) {
  const S sign = std::copysign(S(1), n.z);
  const S a = S(-1) / (sign + n.z);
  const S b = n.x * n.y * a;
  const Vec3<S> b1{S(1) + sign * n.x * n.x * a, sign * b, -sign * n.x};
  const Vec3<S> b2{b, sign + n.y * n.y * a, -n.y};
  Pose<S> p;
  p.R[0][0] = b1.x, p.R[1][0] = b1.y, p.R[2][0] = b1.z;
  p.R[0][1] = b2.x, p.R[1][1] = b2.y, p.R[2][1] = b2.z;
  p.R[0][2] = n.x, p.R[1][2] = n.y, p.R[2][2] = n.z;
  p.t = t;
  return p;
}

/// |N| without overflow or underflow in the squares: N is scaled by the
/// power of two 2^-e that brings its largest component into [1, 2) (exact,
/// except for components below 2^-1074 of the largest, far under the
/// result's rounding), so the sum of squares lies in [1, 12). `*scaled`
/// receives N 2^-e; returns the length of the scaled vector (in [1, 3.5))
/// and sets *e. Requires N finite and non-zero.
template <class S>
S scaledLength(const Vec3<S>& N, Vec3<S>* scaled, int* e) {
  const S m =
      std::fmax(std::fabs(N.x), std::fmax(std::fabs(N.y), std::fabs(N.z)));
  *e = std::ilogb(m);
  *scaled = {std::ldexp(N.x, -*e), std::ldexp(N.y, -*e), std::ldexp(N.z, -*e)};
  return std::sqrt(scaled->x * scaled->x + scaled->y * scaled->y +
                   scaled->z * scaled->z);
}

template <class S>
bool finiteVec(const Vec3<S>& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

/// N / |N|; +z for N = 0; a NaN vector for a non-finite N (so that the
/// queries report invalid input). Accurate to a few ulps for every finite
/// non-zero N, huge or tiny (scaledLength).
template <class S>
Vec3<S> unitOrZ(const Vec3<S>& N) {
  if (!finiteVec(N)) {
    const S nan = std::numeric_limits<S>::quiet_NaN();
    return {nan, nan, nan};
  }
  if (N.x == S(0) && N.y == S(0) && N.z == S(0)) return {S(0), S(0), S(1)};
  Vec3<S> s;
  int e = 0;
  const S len = scaledLength(N, &s, &e);
  return {s.x / len, s.y / len, s.z / len};
}

/// |d| without spurious overflow or underflow; +Inf only when |d| itself
/// exceeds the largest finite S; NaN for a non-finite d.
template <class S>
S lengthOf(const Vec3<S>& d) {
  if (!finiteVec(d)) return std::numeric_limits<S>::quiet_NaN();
  if (d.x == S(0) && d.y == S(0) && d.z == S(0)) return S(0);
  Vec3<S> s;
  int e = 0;
  const S len = scaledLength(d, &s, &e);  // sets e: read it only after
  return std::ldexp(len, e);
}
}  // namespace detail

/// Axis from O along N (any non-zero length; normalised) for the length L,
/// radius R: the solid { O + u n + w : 0 <= u <= L, w . n = 0, |w| <= R }.
template <class S>
PosedCylinder<S> cylinderFromAxis(const Vec3<S>& O, const Vec3<S>& N, S L,
                                  S R) {
  const Vec3<S> n = detail::unitOrZ(N);
  const S h = L / S(2);
  const Vec3<S> t{O.x + n.x * h, O.y + n.y * h, O.z + n.z * h};
  return {Cylinder<S>{R, L}, detail::frameFromAxis(n, t)};
}

/// Axis from a to b, radius R.
template <class S>
PosedCylinder<S> cylinderFromEndpoints(const Vec3<S>& a, const Vec3<S>& b,
                                       S R) {
  const Vec3<S> d{b.x - a.x, b.y - a.y, b.z - a.z};
  const S L = detail::lengthOf(d);
  const Vec3<S> n = detail::unitOrZ(d);
  const Vec3<S> t{a.x / S(2) + b.x / S(2), a.y / S(2) + b.y / S(2),
                  a.z / S(2) + b.z / S(2)};
  return {Cylinder<S>{R, L}, detail::frameFromAxis(n, t)};
}

/// The sources' cone: apex O, axis direction N pointing from the apex into
/// the cone (normalised), height L, base radius R. FCL's cone has its apex
/// at local +lz/2, so the local z axis is -n and the centre is O + n L/2.
template <class S>
PosedCone<S> coneFromApex(const Vec3<S>& O, const Vec3<S>& N, S L, S R) {
  const Vec3<S> n = detail::unitOrZ(N);
  const S h = L / S(2);
  const Vec3<S> t{O.x + n.x * h, O.y + n.y * h, O.z + n.z * h};
  return {Cone<S>{R, L}, detail::frameFromAxis(Vec3<S>{-n.x, -n.y, -n.z}, t)};
}

}  // namespace tricyl
