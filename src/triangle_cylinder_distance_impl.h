// SPDX-License-Identifier: BSD-3-Clause
// The triangle-cylinder distance, written once for any number type T with
// + - * / sqrt abs and exact comparisons: double (the first pass), the
// double-word DD of src/dd.h (the refinement) and a 256+-bit MPFR float
// (support/distance_oracle.cpp). Everything is in the cylinder's frame:
// C = { y : y0^2 + y1^2 <= r^2, |y2| <= h }, h = lz / 2, and the triangle
// (v0, v1, v2) is the pulled-back one. Derivations: docs/distance.md.
//
// 1. phi(p) = dist(p, C)^2 / 2 is convex and C^1 with gradient p - P(p),
//    P the projection onto C, and that gradient is 1-Lipschitz (projections
//    onto convex sets are firmly non-expansive). So along an edge
//    p(s) = a + s d the function phi(s) is convex with the continuous,
//    non-decreasing derivative phi'(s) = (p - P(p)) . d, Lipschitz with
//    constant |d|^2: its minimiser on [0, 1] is an end or the root of
//    phi', found by Newton's method safeguarded by bisection of a bracket
//    (edgeSolve), with a fixed cap on the iterations.
// 2. The minimum over the triangle is on an edge unless it is in the
//    relative interior, where the gradient p - P(p) is normal to the
//    plane H of the triangle: p is then a point of H nearest to C, the
//    projection onto H of a support point of C in the direction of H
//    (faceCandidate). If H meets C there is no such interior point with a
//    positive distance.
// 3. Certificate (certify): for any direction w != 0,
//      d(T, C) >= ( min_i w . v_i - h_C(w) ) / |w|,
//    h_C(w) = r |w_xy| + h |w_z| the support function of C (separating
//    planes; weak duality). With w = p - P(p) at the computed nearest pair,
//    made exactly orthogonal to the edge for an edge point (or w = the
//    face normal for a face point), this lower bound meets the upper bound
//    |p - P(p)| to second order in the error of p.
#pragma once

namespace tricyl::detail::dist {

/// Denominators below this (squared lengths, normals) are treated as 0:
/// a quotient by them could overflow. After the scaling of
/// src/triangle_cylinder_distance.cpp every length of a query is within
/// 2^-80 .. 2^82, so only exactly or nearly degenerate features (whose
/// distance the other candidates then give) fall below it.
inline constexpr double kTinyDen = 0x1p-900;

/// The edges as (first, second) vertex: edge k runs from v[kEdgeA[k]] to
/// v[kEdgeB[k]]. With the vertices sorted by increasing magnitude (the
/// kernel sorts them), every edge starts at its smaller end, so the points
/// a + s d near the small end (usually the near ones) are accurate even
/// when the other end is far away.
inline constexpr int kEdgeA[3] = {0, 1, 0};
inline constexpr int kEdgeB[3] = {1, 2, 2};

template <class T>
struct P3 {
  T x, y, z;
};

template <class T>
inline P3<T> operator+(const P3<T>& a, const P3<T>& b) {
  return {a.x + b.x, a.y + b.y, a.z + b.z};
}
template <class T>
inline P3<T> operator-(const P3<T>& a, const P3<T>& b) {
  return {a.x - b.x, a.y - b.y, a.z - b.z};
}
template <class T>
inline P3<T> operator*(const P3<T>& a, const T& s) {
  return {a.x * s, a.y * s, a.z * s};
}
template <class T>
inline T dot(const P3<T>& a, const P3<T>& b) {
  return a.x * b.x + a.y * b.y + a.z * b.z;
}
template <class T>
inline P3<T> cross(const P3<T>& a, const P3<T>& b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
template <class T>
inline T absT(const T& x) {
  return x < T(0) ? -x : x;
}

/// The pulled-back triangle and the cylinder (h = lz / 2).
template <class T>
struct Problem {
  P3<T> v[3];
  T r, h;
};

/// P(p): the point of C nearest to p.
template <class T>
inline P3<T> project(const P3<T>& p, const T& r, const T& h) {
  using std::sqrt;
  P3<T> q = p;
  const T rho2 = p.x * p.x + p.y * p.y;
  if (rho2 > r * r) {
    const T k = r / sqrt(rho2);
    q.x = p.x * k;
    q.y = p.y * k;
  }
  if (q.z > h) q.z = h;
  if (q.z < -h) q.z = -h;
  return q;
}

template <class T>
inline T norm(const P3<T>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}

/// phi'(s) and phi''(s) (where it exists; the one-sided value at the
/// boundaries of the regions) of phi(s) = dist(a + s d, C)^2 / 2.
///   outside the slab:  + (z - clamp(z)) d_z,        + d_z^2
///   outside the barrel: + (1 - r/rho) (p_xy . d_xy),
///                       + r (p_xy . d_xy)^2 / rho^3 + (1 - r/rho) |d_xy|^2
template <class T>
struct Dphi {
  T g, g2;
};
template <class T>
inline Dphi<T> edgeDphi(const P3<T>& a, const P3<T>& d, const T& s, const T& r,
                        const T& h) {
  using std::sqrt;
  const P3<T> p = a + d * s;
  Dphi<T> out{T(0), T(0)};
  if (p.z > h) {
    out.g = (p.z - h) * d.z;
    out.g2 = d.z * d.z;
  } else if (p.z < -h) {
    out.g = (p.z + h) * d.z;
    out.g2 = d.z * d.z;
  }
  const T rho2 = p.x * p.x + p.y * p.y;
  if (rho2 > r * r) {
    const T rho = sqrt(rho2);
    const T rr = r / rho;  // in [0, 1)
    const T k = T(1) - rr;
    const T pd = p.x * d.x + p.y * d.y;
    const T pr = pd / rho;  // |pr| <= |d_xy|: no overflow, no 0 / 0
    out.g = out.g + k * pd;
    out.g2 = out.g2 + rr * pr * pr + k * (d.x * d.x + d.y * d.y);
  }
  return out;
}

template <class T>
inline T pointDist(const P3<T>& p, const T& r, const T& h) {
  return norm(p - project(p, r, h));
}

/// The root of phi' in a bracket [lo, hi] with phi'(lo) < 0 < phi'(hi),
/// starting at s inside it: Newton's iteration kept inside the shrinking
/// bracket (a bisection whenever the bracket did not halve in two steps,
/// and whenever the Newton point leaves it, unless the end it overshot is an
/// earlier iterate: then the regula falsi point between s and that end,
/// strictly inside, replaces it). At most `max_iter` evaluations.
/// It stops when the bracket is narrower than `tol`, or after a Newton step
/// shorter than `step_tol` (the iterate is then within about step_tol^2 of
/// a smooth root; at a kink of phi' the bracket criterion decides).
template <class T>
inline T edgeSolveIn(const P3<T>& a, const P3<T>& d, const T& r, const T& h,
                     T lo, T hi, T s, int max_iter, const T& tol,
                     const T& step_tol) {
  T width_before = hi - lo;
  // phi' at the bracket's ends once they are iterates (g_lo < 0 < g_hi).
  T g_lo = T(0), g_hi = T(0);
  bool have_lo = false, have_hi = false;
  for (int it = 0; it < max_iter; ++it) {
    const Dphi<T> e = edgeDphi(a, d, s, r, h);
    if (e.g == T(0)) return s;
    if (e.g < T(0)) {
      lo = s;
      g_lo = e.g;
      have_lo = true;
    } else {
      hi = s;
      g_hi = e.g;
      have_hi = true;
    }
    if (!(hi - lo > tol)) return (lo + hi) * T(0.5);
    T next = T(0.5) * (lo + hi);
    if (e.g2 > T(kTinyDen) && absT(e.g) < e.g2 * T(2)) {
      const T step = e.g / e.g2;
      const T newton = s - step;
      if (newton > lo && newton < hi) {
        next = newton;
        if (!(absT(step) > step_tol)) return next;
      } else if (newton == s) {
        // A step that rounds away: s is the root to its last bit (phi'(s)
        // is a rounding error; s is an end of the bracket, just moved
        // there). Bisecting from there would shrink the bracket by halves
        // down to `tol`, about 50 evaluations for nothing.
        return s;
      } else if (e.g < T(0) ? have_hi : have_lo) {
        // The Newton point overshot an end that is an earlier iterate on
        // the other side of the root (phi' is steeper between s and the
        // root than at s: a root next to that end, where the iterates
        // would otherwise approach it by bisections): the regula falsi
        // point between s and that end, inside (s, end) as the signs
        // differ.
        const T far = e.g < T(0) ? hi : lo;
        const T gf = e.g < T(0) ? g_hi : g_lo;
        const T secant = s + (far - s) * (e.g / (e.g - gf));
        if (secant > lo && secant < hi) next = secant;
      }
    }
    if ((it & 1) != 0) {
      if (hi - lo > T(0.5) * width_before) next = T(0.5) * (lo + hi);
      width_before = hi - lo;
    }
    s = next;
  }
  return s;
}

/// The minimiser of phi on [0, 1]: an end where phi' does not change sign
/// there, else the root of phi' (edgeSolveIn from the regula falsi point,
/// which is exact for a quadratic phi).
template <class T>
inline T edgeSolve(const P3<T>& a, const P3<T>& d, const T& r, const T& h,
                   int max_iter, const T& tol) {
  const Dphi<T> e0 = edgeDphi(a, d, T(0), r, h);
  if (!(e0.g < T(0))) return T(0);
  const Dphi<T> e1 = edgeDphi(a, d, T(1), r, h);
  if (!(e1.g > T(0))) return T(1);
  T s = e0.g / (e0.g - e1.g);
  if (!(s > T(0) && s < T(1))) s = T(0.5);
  return edgeSolveIn(a, d, r, h, T(0), T(1), s, max_iter, tol, tol);
}

/// The minimiser of phi on [0, 1] in a stronger arithmetic T, from s0, the
/// minimiser found in a weaker one: the ends are re-checked; then the root
/// of phi' is solved in the bracket [s0 - delta, s0 + delta] when phi'
/// changes sign there (Newton converges from s0 in a few steps), else in
/// [0, 1]. Bounded by `max_iter` evaluations.
///
/// With `kinks` (the edge's `nk` kinks, edgeKinks), the bracket is first
/// cut at those inside it by the sign of phi' there: phi'' then has no jump
/// inside it, and Newton's steps are not thrown back into bisections by a
/// kink next to the root (an edge hovering over a cap and leaving it over
/// the rim, whose root lies just past the rim's kink: from the cap's side
/// phi'' = d_z^2 is tiny and the Newton point leaves the bracket).
template <class T>
inline T edgeRefine(const P3<T>& a, const P3<T>& d, const T& r, const T& h,
                    const T& s0, const T& delta, int max_iter, const T& tol,
                    const T* kinks = nullptr, int nk = 0) {
  if (!(edgeDphi(a, d, T(0), r, h).g < T(0))) return T(0);
  if (!(edgeDphi(a, d, T(1), r, h).g > T(0))) return T(1);
  T lo = s0 - delta, hi = s0 + delta;
  if (lo < T(0)) lo = T(0);
  if (hi > T(1)) hi = T(1);
  if (!(lo == T(0) || edgeDphi(a, d, lo, r, h).g < T(0)) ||
      !(hi == T(1) || edgeDphi(a, d, hi, r, h).g > T(0))) {
    lo = T(0);
    hi = T(1);
  }
  bool lo_kink = false, hi_kink = false;
  for (int k = 0; k < nk; ++k) {
    const T& x = kinks[k];
    if (!(x > lo && x < hi)) continue;
    const T g = edgeDphi(a, d, x, r, h).g;
    if (g < T(0)) {
      lo = x;
      lo_kink = true;
    } else if (g > T(0)) {
      hi = x;
      hi_kink = true;
    } else {
      return x;
    }
  }
  // A root within `tol` of a kink at an end of the bracket (the edge
  // nearly parallel to a cap and leaving it over the rim: phi' jumps from
  // the cap's side within the rounding of the kink's parameter, phi'' =
  // d_z^2 is tiny there, every Newton point leaves the bracket and the
  // bisection would run down to `tol`): one probe at `tol` from the kink
  // settles it.
  if (lo_kink && hi - lo > tol) {
    const T x = lo + tol;
    if (edgeDphi(a, d, x, r, h).g > T(0)) return (lo + x) * T(0.5);
  }
  if (hi_kink && hi - lo > tol) {
    const T x = hi - tol;
    if (edgeDphi(a, d, x, r, h).g < T(0)) return (x + hi) * T(0.5);
  }
  T s = s0;
  if (!(s > lo && s < hi)) s = (lo + hi) * T(0.5);
  return edgeSolveIn(a, d, r, h, lo, hi, s, max_iter, tol, tol);
}

/// The parameters in [0, 1] where the edge a + s d crosses the planes
/// z = +-h and the barrel rho = r (the kinks of phi''): up to 4, written to
/// `out`; returns their number. Where phi' is too small to resolve in T
/// (an edge nearly parallel to a cap, hovering at a distance near T's
/// rounding), the minimum is at an end or at such a kink, and f is still
/// evaluated accurately there.
template <class T>
inline int edgeKinks(const P3<T>& a, const P3<T>& d, const T& r, const T& h,
                     T out[4]) {
  using std::sqrt;
  int n = 0;
  auto keep = [&](const T& s) {
    if (s > T(0) && s < T(1)) out[n++] = s;
  };
  // A quotient is computed only when it lies in (-1, 1): no overflow.
  if (absT(h - a.z) < absT(d.z)) keep((h - a.z) / d.z);
  if (absT(h + a.z) < absT(d.z)) keep((T(0) - h - a.z) / d.z);
  // |a_xy + s d_xy|^2 = r^2: A s^2 + 2 B s + C = 0.
  const T A = d.x * d.x + d.y * d.y;
  if (A > T(0)) {
    const T B = a.x * d.x + a.y * d.y;
    const T C = a.x * a.x + a.y * a.y - r * r;
    const T disc = B * B - A * C;
    if (disc >= T(0)) {
      const T sq = sqrt(disc);
      // Cancellation-free pair of roots.
      const T q = B < T(0) ? sq - B : T(0) - B - sq;
      if (absT(q) < A) keep(q / A);
      if (absT(C) < absT(q)) keep(C / q);
    }
  }
  return n;
}

/// A nearest pair candidate: p on the triangle, q = P(p), f = |p - q|,
/// and the direction w whose separating plane certifies it.
template <class T>
struct Candidate {
  /// Tag of the constructor that leaves the numbers unset (the double
  /// pass's slots, each written whole before it is read, or invalid).
  struct Unset {};
  bool valid;
  int kind;  // 0, 1, 2: edge kind (kEdgeA, kEdgeB); 3: face
  T s;       // edge parameter
  P3<T> p, q, w;
  T f;
  Candidate() : valid(false), kind(-1), s(), p(), q(), w(), f() {}
  explicit Candidate(Unset) : valid(false), kind(-1) {}
};

/// The candidate of edge k (kEdgeA, kEdgeB) at parameter s; w made
/// orthogonal to the edge when s is inside (0, 1).
template <class T>
inline Candidate<T> edgeCandidate(const Problem<T>& P, int k, const T& s) {
  const P3<T>& a = P.v[kEdgeA[k]];
  const P3<T> d = P.v[kEdgeB[k]] - a;
  Candidate<T> c;
  c.valid = true;
  c.kind = k;
  c.s = s;
  c.p = s == T(1) ? P.v[kEdgeB[k]] : a + d * s;
  c.q = project(c.p, P.r, P.h);
  c.w = c.p - c.q;
  c.f = norm(c.w);
  const T dd = dot(d, d);
  if (s > T(0) && s < T(1) && dd > T(kTinyDen))
    c.w = c.w - d * (dot(c.w, d) / dd);
  return c;
}

/// The face's candidate (see 2. above). `cut` reports that the plane meets
/// C; then, for the zero case, p is the plane's point on the segment
/// between C's two support points in the directions -n and +n (a point of
/// the plane in C), valid when it lies in the triangle.
template <class T>
inline Candidate<T> faceCandidate(const Problem<T>& P, bool* cut) {
  using std::sqrt;
  Candidate<T> c;
  c.kind = 3;
  *cut = false;
  // n = e_k x e_(k+1) for the cyclic edges e_k = v_(k+1) - v_k (all three
  // products are the same vector), from the two shorter edges: with one
  // vertex far away the two long edges are nearly parallel and their
  // product cancels; c0 from the vertex of least magnitude (the vertices
  // are sorted by magnitude, see kEdge).
  const P3<T> e[3] = {P.v[1] - P.v[0], P.v[2] - P.v[1], P.v[0] - P.v[2]};
  int longest = 0;
  T len[3];
  for (int k = 0; k < 3; ++k) len[k] = dot(e[k], e[k]);
  if (len[1] > len[longest]) longest = 1;
  if (len[2] > len[longest]) longest = 2;
  const P3<T> n = cross(e[(longest + 1) % 3], e[(longest + 2) % 3]);
  const T nxy2 = n.x * n.x + n.y * n.y;
  const T nn = nxy2 + n.z * n.z;
  if (!(nn > T(kTinyDen))) return c;
  const T nxy = sqrt(nxy2);
  const T c0 = dot(n, P.v[0]);
  const T ext = P.r * nxy + P.h * absT(n.z);
  auto support = [&](int sg) {
    P3<T> q{T(0), T(0), T(0)};
    if (nxy > T(0)) {
      q.x = P.r * (n.x / nxy);  // |n.x / nxy| <= 1
      q.y = P.r * (n.y / nxy);
    }
    if (n.z > T(0)) q.z = P.h;
    if (n.z < T(0)) q.z = -P.h;
    if (sg < 0) q = q * T(-1);
    return q;
  };
  // p on the inner side of each edge; p - (the nearer end) keeps the
  // product small when one end is far away.
  auto inside = [&](const P3<T>& p) {
    for (int k = 0; k < 3; ++k) {
      const P3<T>& a = P.v[k];
      const P3<T>& b = P.v[(k + 1) % 3];
      const P3<T> pa = p - a, pb = p - b;
      const P3<T>& near = dot(pa, pa) <= dot(pb, pb) ? pa : pb;
      if (dot(cross(e[k], near), n) < T(0)) return false;
    }
    return true;
  };
  if (c0 > ext || c0 < -ext) {
    const int sg = c0 > ext ? 1 : -1;
    c.q = support(sg);
    c.p = c.q + n * ((c0 - dot(n, c.q)) / nn);
    c.w = sg > 0 ? n : n * T(-1);
    c.f = (absT(c0) - ext) / sqrt(nn);
    c.valid = inside(c.p);
    return c;
  }
  *cut = true;
  const P3<T> qp = support(1), qm = support(-1);
  const T den = dot(n, qp - qm);
  if (den > T(kTinyDen)) {
    c.p = qm + (qp - qm) * ((c0 - dot(n, qm)) / den);
    c.q = project(c.p, P.r, P.h);
    c.f = norm(c.p - c.q);
    c.valid = inside(c.p);
  }
  return c;
}

/// The separating-plane lower bound of d(T, C) for the direction w (see 3.
/// above); -1 (no bound) for w = 0.
template <class T>
inline T certify(const Problem<T>& P, const P3<T>& w) {
  using std::sqrt;
  const T ww = dot(w, w);
  if (!(ww > T(kTinyDen))) return T(-1);
  T m = dot(w, P.v[0]);
  for (int k = 1; k < 3; ++k) {
    const T x = dot(w, P.v[k]);
    if (x < m) m = x;
  }
  const T hc = P.r * sqrt(w.x * w.x + w.y * w.y) + P.h * absT(w.z);
  return (m - hc) / sqrt(ww);
}

}  // namespace tricyl::detail::dist
