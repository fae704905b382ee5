// SPDX-License-Identifier: BSD-3-Clause
// The exact reference oracle for triangle vs cylinder: GMP rationals,
// written for clarity, not speed, and deliberately NOT sharing any code or
// formulation with the kernel (src/triangle_cylinder_impl.h):
//
//   1. map the vertices to the cylinder frame exactly: y = R^T (x - t);
//   2. clip the triangle explicitly (Sutherland-Hodgman) against z <= h and
//      then against z >= -h, each with its own plane, h = lz / 2;
//   3. project the resulting points onto the xy-plane;
//   4. the hull of those points meets the disk iff some segment between two
//      of them (a point when i == j) is within r of the origin, or some
//      NON-DEGENERATE triangle of three of them contains the origin
//      (Caratheodory; a degenerate triple is already covered by its
//      segments, and testing it as a triangle is exactly the published bug).
//
// Used by the tests and by tricyl-compare to settle every answer.
#pragma once

#include <gmpxx.h>

#include <vector>

#include "tricyl/types.h"

namespace tricyl::oracle {

using Q = mpq_class;

struct Q3 {
  Q x, y, z;
};
struct Q2 {
  Q x, y;
};

inline Q3 toLocal(const Pose<double>& pose, const Vec3<double>& p) {
  const Q d[3] = {Q(p.x) - Q(pose.t.x), Q(p.y) - Q(pose.t.y),
                  Q(p.z) - Q(pose.t.z)};
  Q3 out;
  Q* o[3] = {&out.x, &out.y, &out.z};
  for (int i = 0; i < 3; ++i) {
    *o[i] = 0;
    for (int j = 0; j < 3; ++j) *o[i] += Q(pose.R[j][i]) * d[j];  // R^T
  }
  return out;
}

/// Keeps the part of a convex polygon (possibly degenerate) with s z <= h.
inline std::vector<Q3> clipHalfSpace(const std::vector<Q3>& poly, int s,
                                     const Q& h) {
  std::vector<Q3> out;
  const size_t n = poly.size();
  for (size_t k = 0; k < n; ++k) {
    const Q3& a = poly[k];
    const Q3& b = poly[(k + 1) % n];
    const Q fa = s * a.z - h;  // <= 0: inside
    const Q fb = s * b.z - h;
    if (fa <= 0) out.push_back(a);
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
      const Q t = fa / (fa - fb);
      out.push_back({a.x + t * (b.x - a.x), a.y + t * (b.y - a.y),
                     a.z + t * (b.z - a.z)});
    }
  }
  return out;
}

/// Squared distance from the origin to the segment [p, q] (a point if p == q).
inline Q dist2PointSegment(const Q2& p, const Q2& q) {
  const Q dx = q.x - p.x, dy = q.y - p.y;
  const Q len2 = dx * dx + dy * dy;
  Q t = 0;
  if (len2 > 0) {
    t = -(p.x * dx + p.y * dy) / len2;
    if (t < 0) t = 0;
    if (t > 1) t = 1;
  }
  const Q cx = p.x + t * dx, cy = p.y + t * dy;
  return cx * cx + cy * cy;
}

inline Q orient(const Q2& a, const Q2& b) { return a.x * b.y - a.y * b.x; }

/// Does the convex hull of `pts` come within r (r2 = r^2) of the origin?
inline bool hullMeetsDisk(const std::vector<Q2>& pts, const Q& r2) {
  const size_t n = pts.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i; j < n; ++j)
      if (dist2PointSegment(pts[i], pts[j]) <= r2) return true;
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        const Q2 &a = pts[i], &b = pts[j], &c = pts[k];
        const Q area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
        if (area == 0) continue;
        const Q o1 = orient(a, b), o2 = orient(b, c), o3 = orient(c, a);
        if (area > 0 && o1 >= 0 && o2 >= 0 && o3 >= 0) return true;
        if (area < 0 && o1 <= 0 && o2 <= 0 && o3 <= 0) return true;
      }
  return false;
}

/// Exact: does the closed triangle meet the closed posed cylinder?
/// Inputs must be finite with radius, lz >= 0.
inline bool triangleCylinder(const Cylinder<double>& cyl,
                             const Pose<double>& pose,
                             const Triangle<double>& tri) {
  std::vector<Q3> poly = {toLocal(pose, tri.a), toLocal(pose, tri.b),
                          toLocal(pose, tri.c)};
  const Q h = Q(cyl.lz) / 2;
  poly = clipHalfSpace(poly, +1, h);
  poly = clipHalfSpace(poly, -1, h);
  if (poly.empty()) return false;
  std::vector<Q2> pts;
  for (const Q3& p : poly) pts.push_back({p.x, p.y});
  const Q r(cyl.radius);
  return hullMeetsDisk(pts, r * r);
}

}  // namespace tricyl::oracle
