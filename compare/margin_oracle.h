// SPDX-License-Identifier: BSD-3-Clause
// The exact reference oracle for tricyl::withinDistance: GMP rationals,
// written for clarity, not speed, and not sharing code or formulation with
// the kernel (src/triangle_cylinder_margin.cpp) beyond the decomposition
//   C + B_m = Cyl(r + m, h) u Cyl(r, h + m) u Tor(+h) u Tor(-h)
// (h = lz/2; Tor(c) the solid torus of tube radius m about the rim circle at
// height c), which docs/margin.md proves. Each part is decided here by other
// means than in the kernel:
//   - the two cylinders: the triangle oracle's explicit clipping and hull
//     test (oracle.h) with the exact rational sizes r + m and h + m;
//   - an edge vs a torus: on the edge p(s), s in [0, 1], with
//     L = rho^2 + (z - c)^2 + r^2 - m^2 and Q = L^2 - 4 r^2 rho^2, a point
//     is inside iff L <= 0 or Q <= 0; "some s with P(s) <= 0" is decided for
//     P = L, Q by the ends and by exact root isolation of the square-free
//     part of P on (0, 1) (Descartes' rule of signs on Bernstein
//     coefficients with bisection; the kernel uses a Sturm sequence);
//   - the face vs a torus: the two rim points whose meridian plane holds the
//     plane's normal, and their feet on the plane, constructed explicitly in
//     Q(sqrt(D)), D = n_x^2 + n_y^2, tested by barycentric signs (the kernel
//     uses premultiplied edge functions).
// Used by the tests (tests/triangle_cylinder_margin_test.cpp) and available
// to tricyl-compare.
#pragma once

#include <gmpxx.h>

#include <array>
#include <utility>
#include <vector>

#include "oracle.h"
#include "tricyl/types.h"

namespace tricyl::margin_oracle {

using Q = mpq_class;
using oracle::Q2;
using oracle::Q3;
using Poly = std::vector<Q>;  // lowest degree first

inline void trim(Poly& p) {
  while (!p.empty() && p.back() == 0) p.pop_back();
}

inline Q eval(const Poly& p, const Q& x) {
  Q v = 0;
  for (size_t i = p.size(); i-- > 0;) v = v * x + p[i];
  return v;
}

/// Quotient and remainder of a by b (b trimmed, non-empty).
inline std::pair<Poly, Poly> divmod(Poly a, const Poly& b) {
  trim(a);
  Poly quo(a.size() >= b.size() ? a.size() - b.size() + 1 : 0);
  while (!a.empty() && a.size() >= b.size()) {
    const size_t k = a.size() - b.size();
    const Q f = a.back() / b.back();
    quo[k] = f;
    for (size_t i = 0; i < b.size(); ++i) a[k + i] -= f * b[i];
    trim(a);
  }
  return {quo, a};
}

inline Poly gcd(Poly a, Poly b) {
  trim(a);
  trim(b);
  while (!b.empty()) {
    Poly r = divmod(a, b).second;
    a = std::move(b);
    b = std::move(r);
  }
  return a;
}

inline Poly derivative(const Poly& p) {
  Poly d;
  for (size_t i = 1; i < p.size(); ++i) d.push_back(p[i] * long(i));
  trim(d);
  return d;
}

/// Bernstein coefficients on [0, 1] of p (degree n = size - 1).
inline Poly bernstein(const Poly& p) {
  const size_t n = p.size() - 1;
  auto binom = [](size_t a, size_t b) {
    mpz_class c;
    mpz_bin_uiui(c.get_mpz_t(), a, b);
    return Q(c);
  };
  Poly b(n + 1);
  for (size_t k = 0; k <= n; ++k) {
    Q s = 0;
    for (size_t i = 0; i <= k; ++i) s += binom(k, i) / binom(n, i) * p[i];
    b[k] = s;
  }
  return b;
}

inline int signVariations(const Poly& b) {
  int v = 0, last = 0;
  for (const Q& c : b) {
    const int s = sgn(c);
    if (s == 0) continue;
    if (last != 0 && s != last) ++v;
    last = s;
  }
  return v;
}

/// Does the square-free polynomial with Bernstein coefficients b on an
/// interval, non-zero at both ends, have a root inside? Descartes' rule on
/// Bernstein coefficients: 0 variations, none; 1, exactly one; otherwise
/// bisect at the midpoint (de Casteljau), which terminates for a
/// square-free polynomial (Vincent's theorem).
inline bool rootInOpen(const Poly& b) {
  const int v = signVariations(b);
  if (v <= 1) return v == 1;
  const size_t n = b.size() - 1;
  Poly left(n + 1), right(n + 1), w = b;
  for (size_t k = 0; k <= n; ++k) {
    left[k] = w[0];
    right[n - k] = w[n - k];
    for (size_t i = 0; i + k < n; ++i) w[i] = (w[i] + w[i + 1]) / 2;
  }
  if (left[n] == 0) return true;  // the midpoint is a root
  return rootInOpen(left) || rootInOpen(right);
}

/// Is P(s) <= 0 for some s in [0, 1]?
inline bool someNonPosOnUnit(Poly p) {
  trim(p);
  if (p.empty()) return true;  // P == 0
  if (eval(p, 0) <= 0 || eval(p, 1) <= 0) return true;
  if (p.size() == 1) return false;
  // Both ends > 0: a point with P <= 0 exists iff P has a root in (0, 1).
  const Poly g = gcd(p, derivative(p));
  Poly sf = g.size() > 1 ? divmod(p, g).first : p;
  trim(sf);
  if (sf.size() <= 1) return false;
  return rootInOpen(bernstein(sf));
}

/// Numbers a + b sqrt(D) with a fixed D >= 0.
struct QS {
  Q a, b;
};
inline QS operator+(const QS& x, const QS& y) { return {x.a + y.a, x.b + y.b}; }
inline QS operator-(const QS& x, const QS& y) { return {x.a - y.a, x.b - y.b}; }
inline QS mul(const QS& x, const QS& y, const Q& D) {
  return {x.a * y.a + x.b * y.b * D, x.a * y.b + x.b * y.a};
}
inline QS scale(const QS& x, const Q& k) { return {x.a * k, x.b * k}; }
inline int sign(const QS& x, const Q& D) {
  const int sa = sgn(x.a), sb = D == 0 ? 0 : sgn(x.b);
  if (sb == 0) return sa;
  if (sa == 0 || sa == sb) return sb;
  const int c = sgn(x.a * x.a - x.b * x.b * D);
  return c == 0 ? 0 : (c > 0 ? sa : sb);
}

/// Is the triangle v (local, undoubled) within m of the rim circle of
/// radius r at height c?
inline bool torus(const Q3* v, const Q& r, const Q& m, const Q& c) {
  // Edges (and so vertices).
  for (int i = 0; i < 3; ++i) {
    const Q3& a = v[i];
    const Q3& b = v[(i + 1) % 3];
    const Q ex = b.x - a.x, ey = b.y - a.y, ez = b.z - a.z, za = a.z - c;
    const Poly rho2 = {a.x * a.x + a.y * a.y, 2 * (a.x * ex + a.y * ey),
                       ex * ex + ey * ey};
    const Poly L = {rho2[0] + za * za + r * r - m * m, rho2[1] + 2 * za * ez,
                    rho2[2] + ez * ez};
    Poly Qp(5, Q(0));
    for (int p = 0; p < 3; ++p)
      for (int q = 0; q < 3; ++q) Qp[p + q] += L[p] * L[q];
    for (int p = 0; p < 3; ++p) Qp[p] -= 4 * r * r * rho2[p];
    if (someNonPosOnUnit(L) || someNonPosOnUnit(Qp)) return true;
  }
  // Face: n = (b - a) x (c - a).
  const Q3 &A = v[0], &B = v[1], &C = v[2];
  const Q ux = B.x - A.x, uy = B.y - A.y, uz = B.z - A.z;
  const Q wx = C.x - A.x, wy = C.y - A.y, wz = C.z - A.z;
  const Q nx = uy * wz - uz * wy, ny = uz * wx - ux * wz,
          nz = ux * wy - uy * wx;
  const Q nn = nx * nx + ny * ny + nz * nz;
  if (nn == 0) return false;
  const Q D = nx * nx + ny * ny;
  for (int sg = -1; sg <= 1; sg += 2) {
    // The rim point g: r (n_x, n_y) / sqrt(D) = r (n_x, n_y) sqrt(D) / D, or
    // (r, 0) for a horizontal plane; height c.
    QS g[3];
    if (D == 0) {
      g[0] = {sg * r, 0};
      g[1] = {0, 0};
    } else {
      g[0] = {0, sg * r * nx / D};
      g[1] = {0, sg * r * ny / D};
    }
    g[2] = {c, 0};
    // Foot f = g - ((g - A) . n / |n|^2) n.
    const QS gA[3] = {g[0] - QS{A.x, 0}, g[1] - QS{A.y, 0}, g[2] - QS{A.z, 0}};
    const QS dn = scale(gA[0], nx) + scale(gA[1], ny) + scale(gA[2], nz);
    // Within m: dn^2 <= m^2 |n|^2.
    const QS dn2 = mul(dn, dn, D);
    if (sign(dn2 - QS{m * m * nn, 0}, D) > 0) continue;
    const QS t = scale(dn, 1 / nn);
    const QS f[3] = {g[0] - scale(t, nx), g[1] - scale(t, ny),
                     g[2] - scale(t, nz)};
    // Barycentric signs: ((V_{i+1} - V_i) x (f - V_i)) . n >= 0 for all i.
    bool inside = true;
    for (int i = 0; i < 3 && inside; ++i) {
      const Q3& p = v[i];
      const Q3& q = v[(i + 1) % 3];
      const Q dx = q.x - p.x, dy = q.y - p.y, dz = q.z - p.z;
      const QS fx = f[0] - QS{p.x, 0}, fy = f[1] - QS{p.y, 0},
               fz = f[2] - QS{p.z, 0};
      const QS cx = scale(fz, dy) - scale(fy, dz);
      const QS cy = scale(fx, dz) - scale(fz, dx);
      const QS cz = scale(fy, dx) - scale(fx, dy);
      const QS s = scale(cx, nx) + scale(cy, ny) + scale(cz, nz);
      if (sign(s, D) < 0) inside = false;
    }
    if (inside) return true;
  }
  return false;
}

/// Does the triangle meet the cylinder of rational radius r and half-length
/// h (both >= 0)? The triangle oracle's clip-and-hull test.
inline bool cylinder(const Q3* v, const Q& r, const Q& h) {
  std::vector<Q3> poly = {v[0], v[1], v[2]};
  poly = oracle::clipHalfSpace(poly, +1, h);
  poly = oracle::clipHalfSpace(poly, -1, h);
  if (poly.empty()) return false;
  std::vector<Q2> pts;
  for (const Q3& p : poly) pts.push_back({p.x, p.y});
  return oracle::hullMeetsDisk(pts, r * r);
}

/// The triangle's vertices pulled back exactly into the cylinder frame.
inline std::array<Q3, 3> localVertices(const Pose<double>& pose,
                                       const Triangle<double>& tri) {
  return {oracle::toLocal(pose, tri.a), oracle::toLocal(pose, tri.b),
          oracle::toLocal(pose, tri.c)};
}

/// Does the triangle v meet one of the two sized parts of the
/// neighbourhood, Cyl(r + m, h) or Cyl(r, h + m)?
inline bool sizedCylinders(const Q3* v, const Q& r, const Q& h, const Q& m) {
  return cylinder(v, r + m, h) || cylinder(v, r, h + m);
}

/// The same for the posed triangle (tests use it to tell the margins
/// decided by a rim torus).
inline bool sizedCylinders(const Cylinder<double>& cyl,
                           const Pose<double>& pose,
                           const Triangle<double>& tri, double margin) {
  return sizedCylinders(localVertices(pose, tri).data(), Q(cyl.radius),
                        Q(cyl.lz) / 2, Q(margin));
}

/// Exact: is the closed triangle within distance m (>= 0) of the closed
/// posed cylinder (the triangle pulled back exactly, as in intersect)?
/// Inputs must be finite with radius, lz, m >= 0.
inline bool withinDistance(const Cylinder<double>& cyl,
                           const Pose<double>& pose,
                           const Triangle<double>& tri, double margin) {
  const std::array<Q3, 3> v = localVertices(pose, tri);
  const Q r(cyl.radius), h = Q(cyl.lz) / 2, m(margin);
  if (sizedCylinders(v.data(), r, h, m)) return true;
  if (m == 0) return false;
  if (torus(v.data(), r, m, h)) return true;
  const Q3 w[3] = {{v[0].x, v[0].y, -v[0].z},
                   {v[1].x, v[1].y, -v[1].z},
                   {v[2].x, v[2].y, -v[2].z}};
  return torus(w, r, m, h);
}

}  // namespace tricyl::margin_oracle
