// SPDX-License-Identifier: BSD-3-Clause
// The distance's tightening step for tiny distances at a vertex
// (triangle_cylinder_distance_tiny.h; derivation: docs/distance.md,
// section 6, "Tiny distances at a vertex").
//
// The double-word refinement certifies its result to about 2^-95 of the
// problem's size M (the pulled-back vertices and every operation carry an
// absolute error of that order), which is wider than 8 ulps of the distance
// d below d of about 2^-45 M. When the nearest point is a vertex v of the
// triangle, both bounds of a certificate can be made relative to d itself:
//
// * v is formed exactly: each coordinate sum_j R_ji (x_j - t_j) is a
//   floating-point expansion (x_j - t_j by TwoSum, the products by
//   TwoProduct; src/expansion.h), so is everything polynomial in it;
// * U = dist(v, C) >= d: with A = v_x^2 + v_y^2 - r^2 and Z = |v_z| - h
//   exact (their signs place v beside the barrel, over a cap or beyond a
//   rim), dist = A / (rho + r), Z, or the root of the sum of their squares
//   (rho - r written as A / (rho + r): no cancellation);
// * L <= d from the separating plane along W = v - P_C(v) (weak duality,
//   docs/distance.md section 2, step 4): L = (min_i W.v_i - h|W_z| -
//   r|W_xy|) / |W|. With B = min_i W.v_i - h|W_z| exact (W's components
//   double-words: each W.v_i is an exact expansion), the numerator is
//   B - r|W_xy| = (B^2 - r^2 |W_xy|^2) / (B + r|W_xy|) for B > 0, whose
//   numerator is exact again: no cancellation either.
// The remaining operations (the exact values' leading two components as a
// double-word, then a square root, sums of positive terms, products and
// quotients) are each within 2^-100 relative (src/dd.h; 2^-102 for the
// leading pair of a compressed expansion), ten at most: U and L are known
// to 2^-96 relative, and rounded outwards by two ulps each. W is the
// direction of v - P_C(v) to about 2^-100, so L falls short of d by a
// second-order term (about M 2^-200): the interval [L, U] is a few ulps of
// d wide whenever the vertex is the nearest point; when it is not (an
// edge or the face is nearer), L falls short by more and nothing changes.
#include "triangle_cylinder_distance_tiny.h"

#include <cmath>
#include <limits>

#include "dd.h"
#include "expansion.h"

namespace tricyl::detail::dist {
namespace {

using E = Expansion;

/// The value of an exact expansion as a double-word (its two leading
/// components after Compress, renormalised): within 2^-102 relative.
DD toDD(const E& e) {
  const E c = e.compressed();
  const int n = c.size();
  const double* p = c.data();
  double hi = 0, lo = 0;
  if (n >= 1) hi = p[n - 1];
  if (n >= 2) lo = p[n - 2];
  double s, t;
  fastTwoSum(hi, lo, s, t);
  return DD(s, t);
}

E fromDD(const DD& x) { return E(x.hi) + E(x.lo); }

E sq(const E& a) {
  const E c = a.compressed();
  return c * c;
}

E absE(const E& a) { return a.sign() < 0 ? -a : a; }

/// Two ulps outwards: x rounded from a value within 2^-96 relative of the
/// exact one, so the exact one is within u + 2^-96 of x, less than two
/// ulps of x (each at least 2^-53 of it). Normal x only (checked).
double upTwo(double x) {
  const double inf = std::numeric_limits<double>::infinity();
  return std::nextafter(std::nextafter(x, inf), inf);
}
double downTwo(double x) { return std::nextafter(std::nextafter(x, 0.0), 0.0); }

struct VertexDistance {
  bool ok = false;
  bool beside = false;  // outside the barrel (A > 0)
  bool beyond = false;  // outside the slab (Z > 0)
  int side = 1;         // the sign of v_z
  DD rho, er, ez, dist;
};

VertexDistance vertexDistance(const E (&v)[3], const E& r, const E& h,
                              double rd) {
  VertexDistance o;
  const E rho2 = sq(v[0]) + sq(v[1]);
  const E A = rho2 - sq(r);
  o.side = v[2].sign() < 0 ? -1 : 1;
  const E Z = absE(v[2]) - h;
  if (!rho2.ok() || !A.ok() || !Z.ok()) return o;
  o.beside = A.sign() > 0;
  o.beyond = Z.sign() > 0;
  if (!o.beside && !o.beyond) return o;  // in C: not a disjoint pair
  o.rho = sqrt(toDD(rho2));
  if (o.beside) o.er = toDD(A) / (o.rho + DD(rd));
  if (o.beyond) o.ez = toDD(Z);
  o.dist = o.beside && o.beyond ? sqrt(o.er * o.er + o.ez * o.ez)
                                : (o.beside ? o.er : o.ez);
  o.ok = true;
  return o;
}

}  // namespace

void tightenAtVertex(const Cylinder<double>& cyl, const Pose<double>& pose,
                     const Triangle<double>& tri, DistanceResult<double>* out) {
  // The range in which every expansion below stays exact and every
  // double-word operation relative (squares of squares of lengths up to
  // 2^120, distances far above the underflow threshold): outside it the
  // result stays as it is.
  const double d0 = out->distance;
  if (!(d0 >= 0x1p-300)) return;
  const Vec3<double>* x[3] = {&tri.a, &tri.b, &tri.c};
  const double lim = 0x1p120;
  if (!(cyl.radius <= lim && cyl.lz <= lim)) return;
  for (const Vec3<double>* p : {x[0], x[1], x[2], &pose.t})
    if (!(std::fabs(p->x) <= lim && std::fabs(p->y) <= lim &&
          std::fabs(p->z) <= lim))
      return;
  for (const auto& row : pose.R)
    for (double a : row)
      if (!(std::fabs(a) <= 4)) return;
  const double hd = 0.5 * cyl.lz;
  if (hd * 2 != cyl.lz) return;  // (a subnormal lz: h not exact)

  // The pulled-back vertices, exactly.
  E v[3][3];
  const double t[3] = {pose.t.x, pose.t.y, pose.t.z};
  for (int k = 0; k < 3; ++k) {
    const double xk[3] = {x[k]->x, x[k]->y, x[k]->z};
    for (int i = 0; i < 3; ++i) {
      E s;
      for (int j = 0; j < 3; ++j)
        s = s + E::difference(xk[j], t[j]) * E(pose.R[j][i]);
      if (!s.ok()) return;
      v[k][i] = s.compressed();
    }
  }
  const E r(cyl.radius), h(hd);

  // The vertex nearest to C (by its double-word distance).
  int best = -1;
  VertexDistance vd;
  for (int k = 0; k < 3; ++k) {
    const VertexDistance o = vertexDistance(v[k], r, h, cyl.radius);
    if (!o.ok) return;
    if (best < 0 || o.dist < vd.dist) {
      best = k;
      vd = o;
    }
  }
  const E(&vb)[3] = v[best];

  // W = v - P_C(v), as double-words: (0, 0, side) over a cap, (v_x, v_y,
  // 0) beside the barrel, (er v_x / rho, er v_y / rho, side ez) beyond a
  // rim (any positive multiple of the direction will do).
  DD w[3] = {DD(0), DD(0), DD(0)};
  if (vd.beside) {
    const DD k = vd.beyond ? vd.er / vd.rho : DD(1);
    w[0] = toDD(vb[0]) * k;
    w[1] = toDD(vb[1]) * k;
  }
  if (vd.beyond) w[2] = vd.side < 0 ? -vd.ez : vd.ez;
  const E W[3] = {fromDD(w[0]), fromDD(w[1]), fromDD(w[2])};

  // B = min_i W.v_i - h |W_z|, exact.
  E B;
  for (int k = 0; k < 3; ++k) {
    const E p = (W[0] * v[k][0] + W[1] * v[k][1] + W[2] * v[k][2]).compressed();
    if (!p.ok()) return;
    if (k == 0 || (p - B).sign() < 0) B = p;
  }
  B = (B - h * absE(W[2])).compressed();
  if (!B.ok() || B.sign() <= 0) return;
  const DD wz2 = w[2] * w[2];
  DD L;
  if (!vd.beside) {
    L = toDD(B) / sqrt(wz2);  // W = (0, 0, +-ez): |W| = |W_z|
  } else {
    const E Q = sq(W[0]) + sq(W[1]);
    const E num = sq(B) - sq(r) * Q;
    if (!Q.ok() || !num.ok() || num.sign() <= 0) return;
    const DD q = toDD(Q);
    const DD n = toDD(num) / (toDD(B) + DD(cyl.radius) * sqrt(q));
    L = n / sqrt(q + wz2);
  }
  // The vertex's distance U is the answer when the vertex is the nearest
  // point (then L meets it to a second-order term): U rounded, with the
  // certified interval [L, U] around it.
  const double U = double(vd.dist);
  const double U_hi = upTwo(U);
  const double L_lo = downTwo(double(L));
  const double dbl_min = std::numeric_limits<double>::min();
  if (!(L_lo >= dbl_min && L_lo <= U_hi)) return;
  const double d = U;
  const double eb = std::fmax(U_hi - d, d - L_lo) * (1 + 0x1p-50);
  if (!(eb < out->error_bound)) return;

  // The nearest pair: the vertex (the world vertex itself) and its
  // projection onto C, mapped back as x = R q + t.
  const double yv[3] = {double(toDD(vb[0])), double(toDD(vb[1])),
                        double(toDD(vb[2]))};
  double q[3] = {yv[0], yv[1], yv[2]};
  if (vd.beside) {
    const double s = cyl.radius / double(vd.rho);
    q[0] *= s;
    q[1] *= s;
  }
  if (vd.beyond) q[2] = vd.side * hd;
  double qw[3];
  for (int i = 0; i < 3; ++i)
    qw[i] =
        pose.R[i][0] * q[0] + pose.R[i][1] * q[1] + pose.R[i][2] * q[2] + t[i];
  out->distance = d;
  out->error_bound = eb;
  out->point_on_triangle = *x[best];
  out->point_on_cylinder = {qw[0], qw[1], qw[2]};
}

}  // namespace tricyl::detail::dist
