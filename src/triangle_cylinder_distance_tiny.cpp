// SPDX-License-Identifier: BSD-3-Clause
// tricyl::tightenDistance: certified bounds of a few ulps for tiny
// distances (include/tricyl/triangle_cylinder_distance.h; derivation:
// docs/distance.md, section 6.1).
//
// The double-word refinement certifies its result to about 2^-95 of the
// problem's size M (the pulled-back vertices and every operation carry an
// absolute error of that order), which is wider than 8 ulps of the distance
// d below d of about 2^-45 M. When the nearest point is a vertex v of the
// triangle, both bounds of a certificate can be made relative to d itself
// (the other closed-form candidates below, an edge beside the barrel, an
// edge or the face parallel to a cap and the face in a vertical plane
// beside the barrel, the same way):
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

/// Certified bounds lo <= d <= hi of the distance, the estimate est (the
/// upper bound's candidate, rounded to nearest) and its local pair (p on
/// T, q = P_C(p)); merged over the candidates: the largest lower bound,
/// the smallest upper bound with its estimate and pair.
struct Enclosure {
  bool ok = false;
  double lo = 0, hi = 0, est = 0;
  double p[3] = {0, 0, 0}, q[3] = {0, 0, 0};
  int vertex = -1;  // p is this vertex (its world point is exact)
  void addLower(double l) {
    if (!ok || l > lo) lo = l;
  }
  /// An upper bound U (within 2^-96 relative) with its pair; true if it
  /// is the smallest so far.
  bool addUpper(const DD& U) {
    const double u = double(U), u_hi = upTwo(u);
    if (ok && !(u_hi < hi)) return false;
    hi = u_hi;
    est = u;
    return true;
  }
};

/// The nearest vertex: U its distance, L its separating plane (see the
/// top of this file).
void atVertex(const E (&v)[3][3], const bool (&near)[3], const E& r, const E& h,
              double rd, double hd, Enclosure* enc) {
  int best = -1;
  VertexDistance vd;
  for (int k = 0; k < 3; ++k) {
    if (!near[k]) continue;
    const VertexDistance o = vertexDistance(v[k], r, h, rd);
    if (!o.ok) return;
    if (best < 0 || o.dist < vd.dist) {
      best = k;
      vd = o;
    }
  }
  if (best < 0) return;
  const E(&vb)[3] = v[best];
  // W = v - P_C(v), as double-words: (0, 0, side ez) over a cap, (v_x,
  // v_y, 0) beside the barrel, (er v_x / rho, er v_y / rho, side ez)
  // beyond a rim (any positive multiple of the direction will do).
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
  const bool lower = B.ok() && B.sign() > 0;
  const DD wz2 = w[2] * w[2];
  if (lower && !vd.beside) {
    enc->addLower(downTwo(double(toDD(B) / sqrt(wz2))));  // |W| = |W_z|
  } else if (lower) {
    const E Q = sq(W[0]) + sq(W[1]);
    const E num = sq(B) - sq(r) * Q;
    if (Q.ok() && num.ok() && num.sign() > 0) {
      const DD q = toDD(Q);
      const DD n = toDD(num) / (toDD(B) + DD(rd) * sqrt(q));
      enc->addLower(downTwo(double(n / sqrt(q + wz2))));
    }
  }
  if (!enc->addUpper(vd.dist)) return;
  enc->ok = true;
  enc->vertex = best;
  for (int i = 0; i < 3; ++i) enc->p[i] = enc->q[i] = double(toDD(vb[i]));
  if (vd.beside) {
    const double s = rd / double(vd.rho);
    enc->q[0] *= s;
    enc->q[1] *= s;
  }
  if (vd.beyond) enc->q[2] = vd.side * hd;
}

/// Edge k beside the barrel: its line's closest approach to the axis in
/// the xy-projection, at s* = -(a_xy . d_xy) / |d_xy|^2 (d = b - a), is
/// rho* = |a_x d_y - a_y d_x| / |d_xy|. If s* is in [0, 1] and p(s*) in
/// the slab |z| <= h, p(s*) is a point of T at distance rho* - r = U from
/// C (beside the barrel: rho* > r). The horizontal W = sign (d_y, -d_x, 0)
/// is exactly orthogonal to the edge, and W.a = W.b = |a_x d_y - a_y
/// d_x|: its separating plane gives L = (min_i W.v_i - r |d_xy|) / |d_xy|,
/// equal to U when the third vertex is not nearer along W (the edge is
/// then the nearest feature). Both as exact numerators over positive
/// denominators: U = (c^2 - r^2 |d_xy|^2) / (|d_xy| (|c| + r |d_xy|)), c
/// = a_x d_y - a_y d_x; L the same with min_i W.v_i for |c|.
void besideBarrel(const E (&v)[3][3], int k, const E& r, const E& h, double rd,
                  Enclosure* enc) {
  static constexpr int kA[3] = {0, 1, 0}, kB[3] = {1, 2, 2}, kC[3] = {2, 0, 1};
  const E(&a)[3] = v[kA[k]];
  const E(&b)[3] = v[kB[k]];
  const E(&c)[3] = v[kC[k]];
  const E d[3] = {(b[0] - a[0]).compressed(), (b[1] - a[1]).compressed(),
                  (b[2] - a[2]).compressed()};
  const E dxy2 = (sq(d[0]) + sq(d[1])).compressed();
  if (!dxy2.ok() || dxy2.sign() <= 0) return;
  const E dot = (a[0] * d[0] + a[1] * d[1]).compressed();
  // s* in [0, 1]: -dot in [0, |d_xy|^2].
  if (!dot.ok() || dot.sign() > 0 || (dxy2 + dot).sign() < 0) return;
  // |z(s*)| <= h: |a_z |d_xy|^2 - dot d_z| <= h |d_xy|^2.
  const E zn = (a[2] * dxy2 - dot * d[2]).compressed();
  const E hd2 = (h * dxy2).compressed();
  if (!zn.ok() || !hd2.ok() || (hd2 - zn).sign() < 0 || (hd2 + zn).sign() < 0)
    return;
  const E cr = (a[0] * d[1] - a[1] * d[0]).compressed();
  const E r2d = (sq(r) * dxy2).compressed();
  const E num = (sq(cr) - r2d).compressed();
  if (!cr.ok() || !r2d.ok() || !num.ok() || num.sign() <= 0) return;
  const DD len = sqrt(toDD(dxy2));
  const DD rlen = DD(rd) * len;
  // L: W = sign(c) (d_y, -d_x, 0); the third vertex's W.c_v.
  const E cc = (c[0] * d[1] - c[1] * d[0]).compressed();
  const E acr = absE(cr);
  const E wc = cr.sign() < 0 ? -cc : cc;
  const E m = (wc - acr).sign() < 0 ? wc : acr;
  if (m.ok() && m.sign() > 0) {
    const E lnum = (sq(m) - r2d).compressed();
    if (lnum.ok() && lnum.sign() > 0)
      enc->addLower(downTwo(double(toDD(lnum) / (len * (toDD(m) + rlen)))));
  }
  const DD U = toDD(num) / (len * (toDD(acr) + rlen));
  if (!enc->addUpper(U)) return;
  enc->ok = true;
  enc->vertex = -1;
  // p = a + s* d, q = its projection onto the barrel (in double).
  const DD s = -toDD(dot) / toDD(dxy2);
  double rho2 = 0;
  for (int i = 0; i < 3; ++i) {
    enc->p[i] = double(toDD(a[i]) + s * toDD(d[i]));
    if (i < 2) rho2 += enc->p[i] * enc->p[i];
  }
  const double f = rho2 > 0 ? rd / std::sqrt(rho2) : 1.0;
  enc->q[0] = enc->p[0] * f;
  enc->q[1] = enc->p[1] * f;
  enc->q[2] = enc->p[2];
}

/// Whether the xy-projection of the segment (a, b) meets the disk of
/// radius r (exact), and then its point nearest to the axis (in double,
/// *p_xy).
bool segmentMeetsDisk(const E (&a)[3], const E (&b)[3], const E& r2,
                      double p_xy[2]) {
  const E d[2] = {(b[0] - a[0]).compressed(), (b[1] - a[1]).compressed()};
  const E dd = (sq(d[0]) + sq(d[1])).compressed();
  const E dot = (a[0] * d[0] + a[1] * d[1]).compressed();
  if (!dd.ok() || !dot.ok()) return false;
  double s = 0;
  bool meets;
  if (dd.sign() > 0 && dot.sign() < 0 && (dd + dot).sign() > 0) {
    // The closest approach inside: rho*^2 = c^2 / |d|^2 <= r^2.
    const E c = (a[0] * d[1] - a[1] * d[0]).compressed();
    const E g = (r2 * dd - sq(c)).compressed();
    meets = g.ok() && g.sign() >= 0;
    s = double(-toDD(dot) / toDD(dd));
  } else {  // an end: a (s = 0) unless b is nearer
    const E ga = (r2 - sq(a[0]) - sq(a[1])).compressed();
    const E gb = (r2 - sq(b[0]) - sq(b[1])).compressed();
    if (!ga.ok() || !gb.ok()) return false;
    meets = ga.sign() >= 0 || gb.sign() >= 0;
    s = ga.sign() >= 0 ? 0 : 1;
  }
  for (int i = 0; i < 2; ++i)
    p_xy[i] = double(toDD(a[i]) + DD(s) * toDD(b[i] - a[i]));
  return meets;
}

/// The triangle's lowest points over a cap: W = side e_z gives L = min_i
/// side z_i - h (exact). When two or three vertices attain that minimum
/// exactly (an edge or the face parallel to the cap) and their segment or
/// triangle reaches over the cap's disk in the xy-projection (exact
/// tests), a point at that height over the disk is at distance L: U = L.
/// (One vertex alone over the disk is atVertex's case.)
void overCap(const E (&v)[3][3], const E& r, const E& h, double hd,
             Enclosure* enc) {
  for (const int side : {1, -1}) {
    const E z[3] = {side > 0 ? v[0][2] : -v[0][2],
                    side > 0 ? v[1][2] : -v[1][2],
                    side > 0 ? v[2][2] : -v[2][2]};
    int lo = 0;
    for (int k = 1; k < 3; ++k)
      if ((z[k] - z[lo]).sign() < 0) lo = k;
    const E m = (z[lo] - h).compressed();
    if (!m.ok() || m.sign() <= 0) continue;
    const DD md = toDD(m);
    enc->addLower(downTwo(double(md)));
    int at[3], n = 0;
    for (int k = 0; k < 3; ++k)
      if ((z[k] - z[lo]).sign() == 0) at[n++] = k;
    if (n < 2) return;
    const E r2 = sq(r);
    double p_xy[2];
    bool meets = false;
    if (n == 3) {
      // The origin inside the projected triangle: the three orientations
      // (v_i x v_j)_z of one sign (or zero).
      int pos = 0, neg = 0;
      for (int k = 0; k < 3; ++k) {
        const E(&a)[3] = v[k];
        const E(&b)[3] = v[(k + 1) % 3];
        const int sg = (a[0] * b[1] - a[1] * b[0]).sign();
        pos += sg > 0;
        neg += sg < 0;
      }
      if (pos == 0 || neg == 0) {
        meets = true;
        p_xy[0] = p_xy[1] = 0;
      }
      for (int k = 0; k < 3 && !meets; ++k)
        meets = segmentMeetsDisk(v[k], v[(k + 1) % 3], r2, p_xy);
    } else {
      meets = segmentMeetsDisk(v[at[0]], v[at[1]], r2, p_xy);
    }
    if (!meets || !enc->addUpper(md)) return;
    enc->ok = true;
    enc->vertex = -1;
    enc->p[0] = enc->q[0] = p_xy[0];
    enc->p[1] = enc->q[1] = p_xy[1];
    enc->p[2] = double(toDD(v[lo][2]));
    enc->q[2] = side * hd;
    return;
  }
}

/// The face in a vertical plane (normal n = e1 x e2 with n_z = 0 exactly)
/// beside the barrel: W = sign(n.v_0) n is exactly orthogonal to the face,
/// W.v_i = |n.v_0| = B for every vertex, and L = (B - r |n|) / |n| as the
/// edge's (exact numerator B^2 - r^2 |n|^2). The foot f = (n.v_0) n /
/// |n|^2 of the axis on the plane, at any height, is at distance |f| - r
/// = L from the barrel; the vertical line through it lies in the plane and
/// crosses T where u = (-n_y, n_x, 0).y vanishes (u(f) = 0): if T meets
/// that line at a height within [-h, h] (exact tests on the crossings of
/// the edges, z = (u_j z_i - u_i z_j) / (u_j - u_i)), U = L.
void faceBesideBarrel(const E (&v)[3][3], const E& r, const E& h, double rd,
                      double hd, Enclosure* enc) {
  E e1[3], e2[3];
  for (int i = 0; i < 3; ++i) {
    e1[i] = (v[1][i] - v[0][i]).compressed();
    e2[i] = (v[2][i] - v[0][i]).compressed();
  }
  const E nz = e1[0] * e2[1] - e1[1] * e2[0];
  if (!nz.ok() || nz.sign() != 0) return;
  const E nx = (e1[1] * e2[2] - e1[2] * e2[1]).compressed();
  const E ny = (e1[2] * e2[0] - e1[0] * e2[2]).compressed();
  const E n2 = (sq(nx) + sq(ny)).compressed();
  const E b0 = (nx * v[0][0] + ny * v[0][1]).compressed();
  if (!n2.ok() || n2.sign() <= 0 || !b0.ok()) return;
  const E B = absE(b0);
  const E num = (sq(B) - sq(r) * n2).compressed();
  if (!num.ok() || num.sign() <= 0) return;
  const DD len = sqrt(toDD(n2));
  const DD L = toDD(num) / (len * (toDD(B) + DD(rd) * len));
  enc->addLower(downTwo(double(L)));
  // The crossings of the line u = 0 by T's edges: below / above [-h, h].
  E u[3];
  for (int k = 0; k < 3; ++k) {
    u[k] = (ny * v[k][0] - nx * v[k][1]).compressed();
    if (!u[k].ok()) return;
  }
  bool any = false, le_h = false, ge_mh = false;
  double zmin = 0, zmax = 0;
  auto crossing = [&](double z) {
    zmin = any ? std::fmin(zmin, z) : z;
    zmax = any ? std::fmax(zmax, z) : z;
    any = true;
  };
  for (int k = 0; k < 3; ++k) {
    const int i = k, j = (k + 1) % 3;
    const int si = u[i].sign(), sj = u[j].sign();
    if (si == 0) {  // the vertex is on the line
      le_h |= (v[i][2] - h).sign() <= 0;
      ge_mh |= (v[i][2] + h).sign() >= 0;
      crossing(double(toDD(v[i][2])));
    }
    if (si * sj >= 0) continue;
    // z = (u_j z_i - u_i z_j) / (u_j - u_i), the denominator of sign sj.
    const E zn = (u[j] * v[i][2] - u[i] * v[j][2]).compressed();
    const E den = (u[j] - u[i]).compressed();
    const E hd_ = (h * den).compressed();
    if (!zn.ok() || !hd_.ok()) return;
    le_h |= (zn - hd_).sign() * sj <= 0;
    ge_mh |= (zn + hd_).sign() * sj >= 0;
    crossing(double(toDD(zn) / toDD(den)));
  }
  if (!any || !le_h || !ge_mh || !enc->addUpper(L)) return;
  enc->ok = true;
  enc->vertex = -1;
  const DD f = toDD(b0) / toDD(n2);
  const double fx = double(f * toDD(nx)), fy = double(f * toDD(ny));
  const double z =
      std::fmin(std::fmax(0.0, std::fmax(zmin, -hd)), std::fmin(zmax, hd));
  const double rho = std::sqrt(fx * fx + fy * fy);
  const double sc = rho > 0 ? rd / rho : 1.0;
  enc->p[0] = fx;
  enc->p[1] = fy;
  enc->p[2] = z;
  enc->q[0] = fx * sc;
  enc->q[1] = fy * sc;
  enc->q[2] = z;
}

/// The screen in double that keeps the exact step cheap: a candidate is
/// re-evaluated only if its distance, computed in double from the rounded
/// pulled-back vertices y (each within a few ulps of M, the problem's
/// magnitude, of the exact one), can be within the kernel's interval, up to
/// tol = d0 + error_bound + 2^-40 M (far more than those roundings: a
/// screened-out candidate cannot be the nearest, and the screen only ever
/// skips work, never certifies anything).
struct Screen {
  bool vertex[3] = {false, false, false};
  bool edge[3] = {false, false, false};
  bool cap = false, face = false;
  bool any() const {
    return vertex[0] || vertex[1] || vertex[2] || edge[0] || edge[1] ||
           edge[2] || cap || face;
  }
};

Screen screen(const double (&y)[3][3], double r, double h, double d_hi) {
  Screen sc;
  double M = r + h;
  for (const auto& p : y)
    M = std::fmax(M, std::fabs(p[0]) + std::fabs(p[1]) + std::fabs(p[2]));
  const double slack = 0x1p-40 * M;
  const double tol = d_hi + slack;
  for (int k = 0; k < 3; ++k) {
    const double rho = std::sqrt(y[k][0] * y[k][0] + y[k][1] * y[k][1]);
    const double er = std::fmax(rho - r, 0.0);
    const double ez = std::fmax(std::fabs(y[k][2]) - h, 0.0);
    sc.vertex[k] = std::sqrt(er * er + ez * ez) <= tol;
  }
  static constexpr int kA[3] = {0, 1, 0}, kB[3] = {1, 2, 2};
  for (int k = 0; k < 3; ++k) {
    const double* a = y[kA[k]];
    const double* b = y[kB[k]];
    const double d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    const double dd = d[0] * d[0] + d[1] * d[1];
    if (!(dd > 0x1p-200 * M * M)) continue;
    const double len = std::sqrt(dd);
    const double s = -(a[0] * d[0] + a[1] * d[1]) / dd;
    const double ds = slack / len;  // the parameter's slack
    if (s < -ds || s > 1 + ds) continue;
    if (std::fabs(a[2] + s * d[2]) > h + slack) continue;
    sc.edge[k] = std::fabs(a[0] * d[1] - a[1] * d[0]) / len - r <= tol;
  }
  // Two or three vertices at the same lowest height over a cap.
  for (const double side : {1.0, -1.0}) {
    double z[3];
    for (int k = 0; k < 3; ++k) z[k] = side * y[k][2];
    const double lo = std::fmin(z[0], std::fmin(z[1], z[2]));
    int at = 0;
    for (int k = 0; k < 3; ++k) at += z[k] - lo <= slack;
    sc.cap = sc.cap || (at >= 2 && lo - h <= tol && lo - h >= -slack);
  }
  // A face in a vertical plane at about the distance from the axis.
  double n[3];
  for (int i = 0; i < 3; ++i) {  // (y1 - y0) x (y2 - y0), component i
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    n[i] = (y[1][j] - y[0][j]) * (y[2][k] - y[0][k]) -
           (y[1][k] - y[0][k]) * (y[2][j] - y[0][j]);
  }
  const double nxy = std::sqrt(n[0] * n[0] + n[1] * n[1]);
  if (nxy > 0 && std::fabs(n[2]) <= 0x1p-40 * nxy) {
    const double plane = std::fabs(n[0] * y[0][0] + n[1] * y[0][1]) / nxy;
    sc.face = plane - r <= tol;
  }
  return sc;
}

}  // namespace

void tightenTiny(const Cylinder<double>& cyl, const Pose<double>& pose,
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

  const double t[3] = {pose.t.x, pose.t.y, pose.t.z};
  // The screen (in double): which candidates can be the nearest.
  double y[3][3];
  for (int k = 0; k < 3; ++k) {
    const double dx[3] = {x[k]->x - t[0], x[k]->y - t[1], x[k]->z - t[2]};
    for (int i = 0; i < 3; ++i)
      y[k][i] =
          pose.R[0][i] * dx[0] + pose.R[1][i] * dx[1] + pose.R[2][i] * dx[2];
  }
  const Screen sc = screen(y, cyl.radius, hd, d0 + out->error_bound);
  if (!sc.any()) return;

  // The pulled-back vertices, exactly.
  E v[3][3];
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
  Enclosure best;
  atVertex(v, sc.vertex, r, h, cyl.radius, hd, &best);
  for (int k = 0; k < 3; ++k)
    if (sc.edge[k]) besideBarrel(v, k, r, h, cyl.radius, &best);
  if (sc.cap) overCap(v, r, h, hd, &best);
  if (sc.face) faceBesideBarrel(v, r, h, cyl.radius, hd, &best);
  if (!best.ok) return;
  const double dbl_min = std::numeric_limits<double>::min();
  if (!(best.lo >= dbl_min && best.lo <= best.hi)) return;
  const double d = best.est;
  const double eb = std::fmax(best.hi - d, d - best.lo) * (1 + 0x1p-50);
  if (!(eb < out->error_bound)) return;
  // The nearest pair, mapped back as x = R y + t (a vertex: the world
  // vertex itself).
  auto toWorld = [&](const double(&yl)[3]) {
    double w[3];
    for (int i = 0; i < 3; ++i)
      w[i] = pose.R[i][0] * yl[0] + pose.R[i][1] * yl[1] +
             pose.R[i][2] * yl[2] + t[i];
    return Vec3<double>{w[0], w[1], w[2]};
  };
  out->distance = d;
  out->error_bound = eb;
  out->point_on_triangle = best.vertex >= 0 ? *x[best.vertex] : toWorld(best.p);
  out->point_on_cylinder = toWorld(best.q);
}

}  // namespace tricyl::detail::dist

namespace tricyl {

bool tightenDistance(const Cylinder<double>& cylinder, const Pose<double>& pose,
                     const Triangle<double>& triangle,
                     DistanceResult<double>* result) noexcept {
  if (result == nullptr || !(result->distance > 0) ||
      !(result->error_bound > 0x1p-50 * result->distance) ||
      !(cylinder.radius >= 0 && cylinder.lz >= 0))
    return false;  // (NaN and Inf fail the range checks of tightenTiny)
  const double before = result->error_bound;
  detail::dist::tightenTiny(cylinder, pose, triangle, result);
  return result->error_bound < before;
}

}  // namespace tricyl
