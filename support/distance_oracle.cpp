// SPDX-License-Identifier: BSD-3-Clause
// The distance oracle (distance_oracle.h): the generic algorithm of
// src/triangle_cylinder_distance_impl.h at 333 bits, certified by its
// upper and lower bounds.
#include "distance_oracle.h"

#include <boost/multiprecision/mpfr.hpp>
#include <cmath>
#include <limits>

#include "triangle_cylinder_distance_impl.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl::oracle {
namespace {

namespace bmp = boost::multiprecision;
using R = bmp::number<bmp::mpfr_float_backend<100>, bmp::et_off>;
using detail::dist::Candidate;
using detail::dist::P3;
using detail::dist::Problem;

// Every MPFR operation rounds with a relative error <= 2^-332; the short
// straight-line formulas of the algorithm (and the pulled-back triangle)
// stay within 64 such roundings of the problem's magnitude.
const R& unitRoundoff() {
  static const R u = bmp::ldexp(R(1), -326);
  return u;
}

double down(const R& x) {
  double d = static_cast<double>(x);
  if (R(d) > x) d = std::nextafter(d, -std::numeric_limits<double>::infinity());
  return d;
}
double up(const R& x) {
  double d = static_cast<double>(x);
  if (R(d) < x) d = std::nextafter(d, std::numeric_limits<double>::infinity());
  return d;
}

P3<R> toR(const Vec3<double>& v) { return {R(v.x), R(v.y), R(v.z)}; }

P3<R> pullBack(const Pose<double>& pose, const Vec3<double>& x) {
  const R d[3] = {R(x.x) - R(pose.t.x), R(x.y) - R(pose.t.y),
                  R(x.z) - R(pose.t.z)};
  R y[3];
  for (int i = 0; i < 3; ++i)
    y[i] = R(pose.R[0][i]) * d[0] + R(pose.R[1][i]) * d[1] +
           R(pose.R[2][i]) * d[2];
  return {y[0], y[1], y[2]};
}

R magnitude(const Problem<R>& P) {
  R m = P.r + P.h;
  for (const auto& v : P.v) m += bmp::abs(v.x) + bmp::abs(v.y) + bmp::abs(v.z);
  return m;
}

// The minimiser of phi on edge k at 333 bits: a narrow bracket around the
// double solution when phi' brackets there, else all of [0, 1].
R solveEdge(const Problem<R>& P, int k) {
  const P3<R>& a = P.v[detail::dist::kEdgeA[k]];
  const P3<R> d = P.v[detail::dist::kEdgeB[k]] - a;
  const P3<double> ad{double(a.x), double(a.y), double(a.z)};
  const P3<double> dd{double(d.x), double(d.y), double(d.z)};
  const double s0 =
      detail::dist::edgeSolve(ad, dd, double(P.r), double(P.h), 200, 0x1p-60);
  return detail::dist::edgeRefine(a, d, P.r, P.h, R(s0), R(0x1p-30), 4000,
                                  R(bmp::ldexp(R(1), -320)));
}

R pointSegment(const P3<R>& x, const P3<R>& a, const P3<R>& b) {
  const P3<R> d = b - a;
  const R dd = detail::dist::dot(d, d);
  R s = 0;
  if (dd > 0) {
    s = detail::dist::dot(x - a, d) / dd;
    if (s < 0) s = 0;
    if (s > 1) s = 1;
  }
  return detail::dist::norm(x - (a + d * s));
}

}  // namespace

DistanceEnclosure distanceEnclosure(const Cylinder<double>& cylinder,
                                    const Pose<double>& pose,
                                    const Triangle<double>& triangle) {
  DistanceEnclosure out;
  if (intersect(cylinder, pose, triangle)) {
    out.intersect = true;
    out.tight = true;
    return out;
  }
  Problem<R> P;
  P.r = R(cylinder.radius);
  P.h = R(cylinder.lz) / 2;
  P.v[0] = pullBack(pose, triangle.a);
  P.v[1] = pullBack(pose, triangle.b);
  P.v[2] = pullBack(pose, triangle.c);
  R U = std::numeric_limits<double>::infinity();
  R L = -1;
  bool cut = false;
  const Candidate<R> face = detail::dist::faceCandidate(P, &cut);
  if (!cut) L = detail::dist::certify(P, face.w);
  if (face.valid) U = face.f;
  for (int k = 0; k < 3; ++k) {
    const Candidate<R> c = detail::dist::edgeCandidate(P, k, solveEdge(P, k));
    const R l = detail::dist::certify(P, c.w);
    if (l > L) L = l;
    if (c.f < U) U = c.f;
  }
  // 64 roundings of the magnitude, and the 2^-332 rounding of each
  // pulled-back coordinate (sums of three products of doubles).
  const R slack = 64 * unitRoundoff() * magnitude(P);
  const R lo = L - slack, hi = U + slack;
  out.lo = lo > 0 ? down(lo) : 0.0;
  out.hi = up(hi);
  const R mid = (U + (L > 0 ? L : R(0))) / 2;
  out.mid_hi = static_cast<double>(mid);
  out.mid_lo = static_cast<double>(mid - R(out.mid_hi));
  out.rel_width = up((hi - lo) / (mid > 0 ? mid : hi));
  out.tight = mid > 0 && (hi - lo) <= bmp::ldexp(mid, -200);
  return out;
}

double ulpsError(const DistanceEnclosure& e, double d) {
  const double truth = e.mid_hi;
  if (truth == 0) return d == 0 ? 0 : std::numeric_limits<double>::infinity();
  if (d == 0) return std::numeric_limits<double>::infinity();
  int ex = 0;
  (void)std::frexp(truth, &ex);  // truth in [2^(ex-1), 2^ex)
  const double ulp = std::ldexp(1.0, (ex - 1 < -1022 ? -1022 : ex - 1) - 52);
  const R diff = bmp::abs(R(d) - R(e.mid_hi) - R(e.mid_lo));
  return up(diff / R(ulp));
}

double relativeError(const DistanceEnclosure& e, double d) {
  if (e.mid_hi == 0)
    return d == 0 ? 0 : std::numeric_limits<double>::infinity();
  const R truth = R(e.mid_hi) + R(e.mid_lo);
  return up(bmp::abs(R(d) - truth) / truth);
}

double pointCylinderDistance(const Cylinder<double>& cylinder,
                             const Pose<double>& pose, const Vec3<double>& x) {
  const P3<R> y = pullBack(pose, x);
  const R r(cylinder.radius), h = R(cylinder.lz) / 2;
  return up(detail::dist::pointDist(y, r, h));
}

double pointTriangleDistance(const Triangle<double>& t, const Vec3<double>& x) {
  const P3<R> a = toR(t.a), b = toR(t.b), c = toR(t.c), p = toR(x);
  const P3<R> n = detail::dist::cross(b - a, c - a);
  const R nn = detail::dist::dot(n, n);
  if (nn > 0) {
    const R off = detail::dist::dot(n, p - a) / nn;
    const P3<R> f = p - n * off;  // the foot on the plane
    const P3<R>* v[3] = {&a, &b, &c};
    bool in = true;
    for (int k = 0; k < 3 && in; ++k)
      in = detail::dist::dot(
               detail::dist::cross(*v[(k + 1) % 3] - *v[k], f - *v[k]), n) >= 0;
    if (in) return up(bmp::abs(off) * bmp::sqrt(nn));
  }
  R m = pointSegment(p, a, b);
  const R m2 = pointSegment(p, b, c), m3 = pointSegment(p, c, a);
  if (m2 < m) m = m2;
  if (m3 < m) m = m3;
  return up(m);
}

}  // namespace tricyl::oracle
