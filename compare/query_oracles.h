// SPDX-License-Identifier: BSD-3-Clause
// Exact GMP oracles for the cylinder query family: point in
// cylinder, point in cone, sphere vs cylinder, segment and line vs cylinder
// and their entry/exit intervals. Written for clarity, with mpq_class, and
// deliberately formulated DIFFERENTLY from the library's predicates
// (src/cylinder_queries_impl.h):
//   - true z with h = lz / 2 (the library doubles z);
//   - the cone's radius at height z by division, r (h - z) / lz;
//   - the sphere test isolates sqrt(s) (the library isolates the slice
//     radius f);
//   - the segment test is the emptiness of the interval
//     [max(0, slab_lo, root_lo), min(1, slab_hi, root_hi)], decided by exact
//     comparisons of quadratic surds with rationals (the library tests
//     endpoints, cap crossings and closest approach); the line's is the
//     same without 0 and 1 (the library's line test is (V), (X), (E)
//     without the segment's interior conditions);
//   - interval reference values come from integer square roots (mpz_sqrt)
//     with an error below 2^-200, not from floating point.
// Inputs must be finite with non-negative sizes.
#pragma once

#include <gmpxx.h>

#include <algorithm>
#include <vector>

#include "oracle.h"
#include "tricyl/types.h"

namespace tricyl::oracle {

inline bool pointInCylinder(const Cylinder<double>& cyl,
                            const Pose<double>& pose, const Vec3<double>& p) {
  const Q3 y = toLocal(pose, p);
  const Q h = Q(cyl.lz) / 2, r(cyl.radius);
  return y.x * y.x + y.y * y.y <= r * r && y.z <= h && y.z >= -h;
}

/// FCL's cone (apex +lz/2, base disk of radius r at -lz/2) as the convex
/// hull of apex and base disk.
inline bool pointInCone(const Cone<double>& cone, const Pose<double>& pose,
                        const Vec3<double>& p) {
  const Q3 y = toLocal(pose, p);
  const Q lz(cone.lz), r(cone.radius), h = Q(cone.lz) / 2;
  const Q s = y.x * y.x + y.y * y.y;
  if (lz == 0) return y.z == 0 && s <= r * r;
  if (y.z > h || y.z < -h) return false;
  const Q rad = r * (h - y.z) / lz;  // >= 0 on the slab
  return s <= rad * rad;
}

/// The local ball of radius rho about R^T (center - t).
inline bool sphereCylinder(const Cylinder<double>& cyl,
                           const Pose<double>& pose,
                           const Sphere<double>& sph) {
  const Q3 c = toLocal(pose, sph.center);
  const Q h = Q(cyl.lz) / 2, r(cyl.radius), rho(sph.radius);
  Q az = c.z < 0 ? Q(-c.z) : c.z;
  const Q dz = az > h ? Q(az - h) : Q(0);
  if (dz > rho) return false;
  const Q g = rho * rho - dz * dz;  // squared radial allowance beyond r
  const Q s = c.x * c.x + c.y * c.y;
  if (s <= r * r) return true;
  // sqrt(s) - r <= sqrt(g), sqrt(s) > r >= 0:
  // s + r^2 - g <= 2 r sqrt(s).
  const Q k = s + r * r - g;
  return k <= 0 || k * k <= 4 * r * r * s;
}

/// (base + sgn sqrt(disc)) / den with den > 0, disc >= 0; sgn in {-1,0,1}.
struct Surd {
  Q base, disc, den;
  int sgn = 0;
};

inline Surd rational(const Q& v) { return {v, Q(0), Q(1), 0}; }

/// Sign of a - x for a surd a and a rational x, exactly.
inline int cmp(const Surd& a, const Q& x) {
  // a - x has the sign of sgn sqrt(disc) - w, w = x den - base.
  const Q w = x * a.den - a.base;
  if (a.sgn == 0) return -sgn(w);
  auto cmpSqrt = [&](const Q& v) {  // sign of sqrt(disc) - v
    if (v < 0) return 1;
    return sgn(a.disc - v * v);
  };
  return a.sgn > 0 ? cmpSqrt(w) : -cmpSqrt(-w);
}

/// Sign of a - b when at least one is rational, or both are the two roots
/// of the same quadratic (then sgn decides).
inline int cmp(const Surd& a, const Surd& b) {
  if (b.sgn == 0) return cmp(a, b.base / b.den);
  if (a.sgn == 0) return -cmp(b, a.base / a.den);
  if (a.disc == 0) return 0;
  return a.sgn < b.sgn ? -1 : (a.sgn > b.sgn ? 1 : 0);
}

/// An approximation of the surd within 2^-200 (integer square root).
inline Q approx(const Surd& a) {
  if (a.sgn == 0 || a.disc == 0) return a.base / a.den;
  // Scale so that 2^-k / den <= 2^-200.
  const long dbits = long(mpz_sizeinbase(a.den.get_den_mpz_t(), 2)) -
                     long(mpz_sizeinbase(a.den.get_num_mpz_t(), 2)) + 1;
  const unsigned long k = (unsigned long)(204 + std::max(0L, dbits));
  // sqrt(n/d) = sqrt(n d) / d; isqrt(n d 4^k) / (d 2^k), error < 2^-k / d.
  mpz_class nd = a.disc.get_num() * a.disc.get_den();
  mpz_mul_2exp(nd.get_mpz_t(), nd.get_mpz_t(), 2 * k);
  mpz_class root;
  mpz_sqrt(root.get_mpz_t(), nd.get_mpz_t());
  mpz_class den = a.disc.get_den();
  mpz_mul_2exp(den.get_mpz_t(), den.get_mpz_t(), k);
  const Q sq(root, den);
  return (a.base + a.sgn * sq) / a.den;
}

/// The exact entry/exit interval of the segment p (1 - s) + q s, s in
/// [0, 1], or of the line (every real s), as candidate lists: the interval
/// is [max(lower), min(upper)], empty iff `empty`. For a line a list may be
/// empty: that end is unbounded (only when the local direction is zero).
struct SegmentInterval {
  bool empty = true;
  std::vector<Surd> lower, upper;
};
using LineInterval = SegmentInterval;

/// `bounded`: the segment (candidates 0 and 1); otherwise the line.
inline SegmentInterval linearInterval(const Cylinder<double>& cyl,
                                      const Pose<double>& pose,
                                      const Vec3<double>& p,
                                      const Vec3<double>& q, bool bounded) {
  const Q3 a = toLocal(pose, p);
  const Q3 b = toLocal(pose, q);
  const Q h = Q(cyl.lz) / 2, r(cyl.radius);
  const Q dx = b.x - a.x, dy = b.y - a.y, dz = b.z - a.z;
  SegmentInterval out;
  if (bounded) {
    out.lower.push_back(rational(0));
    out.upper.push_back(rational(1));
  }
  // Slab: -h <= a.z + s dz <= h.
  if (dz == 0) {
    if (a.z > h || a.z < -h) return out;
  } else {
    Q s1 = (-h - a.z) / dz, s2 = (h - a.z) / dz;
    if (s1 > s2) std::swap(s1, s2);
    out.lower.push_back(rational(s1));
    out.upper.push_back(rational(s2));
  }
  // Infinite cylinder: A s^2 + B s + C <= 0.
  const Q A = dx * dx + dy * dy;
  const Q B = 2 * (a.x * dx + a.y * dy);
  const Q C = a.x * a.x + a.y * a.y - r * r;
  if (A == 0) {
    if (C > 0) return out;
  } else {
    const Q disc = B * B - 4 * A * C;
    if (disc < 0) return out;
    out.lower.push_back({-B, disc, 2 * A, -1});
    out.upper.push_back({-B, disc, 2 * A, +1});
  }
  out.empty = false;
  for (const Surd& l : out.lower)
    for (const Surd& u : out.upper)
      if (cmp(l, u) > 0) out.empty = true;
  return out;
}

inline SegmentInterval segmentInterval(const Cylinder<double>& cyl,
                                       const Pose<double>& pose,
                                       const Segment<double>& seg) {
  return linearInterval(cyl, pose, seg.p, seg.q, true);
}

/// The line's interval { s real : p(s) in cylinder }.
inline LineInterval lineInterval(const Cylinder<double>& cyl,
                                 const Pose<double>& pose,
                                 const Line<double>& line) {
  return linearInterval(cyl, pose, line.p, line.q, false);
}

inline bool lineCylinder(const Cylinder<double>& cyl, const Pose<double>& pose,
                         const Line<double>& line) {
  return !lineInterval(cyl, pose, line).empty;
}

/// Does the non-empty line interval meet [0, 1]? Exactly (the segment's
/// answer, derived from the line's candidates instead of the segment's).
inline bool lineMeetsUnit(const LineInterval& iv) {
  if (iv.empty) return false;
  for (const Surd& l : iv.lower)
    if (cmp(l, Q(1)) > 0) return false;
  for (const Surd& u : iv.upper)
    if (cmp(u, Q(0)) < 0) return false;
  return true;
}

inline bool segmentCylinder(const Cylinder<double>& cyl,
                            const Pose<double>& pose,
                            const Segment<double>& seg) {
  return !segmentInterval(cyl, pose, seg).empty;
}

/// Reference endpoints within 2^-200 of the exact ones (non-empty, both
/// ends bounded only).
inline void referenceEndpoints(const SegmentInterval& iv, Q* lo, Q* hi) {
  *lo = approx(iv.lower[0]);
  for (const Surd& l : iv.lower) *lo = std::max(*lo, approx(l));
  *hi = approx(iv.upper[0]);
  for (const Surd& u : iv.upper) *hi = std::min(*hi, approx(u));
}

}  // namespace tricyl::oracle
