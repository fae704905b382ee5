// SPDX-License-Identifier: BSD-3-Clause
// Bounded-time contact data for an intersecting triangle/cylinder pair.
// The contract, method and accuracy are in include/tricyl/fcl_contact.h.
#include <algorithm>
#include <cmath>
#include <limits>

#include "tricyl/fcl_contact.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

struct V {
  double x, y, z;
};

V operator+(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V operator-(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
V operator*(double s, V a) { return {s * a.x, s * a.y, s * a.z}; }
V operator-(V a) { return {-a.x, -a.y, -a.z}; }
double dot(V a, V b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
V cross(V a, V b) {
  return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
double maxAbs(V a) {
  return std::max({std::fabs(a.x), std::fabs(a.y), std::fabs(a.z)});
}

/// Unit vector along `v`; false if v is zero or not finite. Scales by the
/// largest component first so that neither tiny nor huge inputs under- or
/// overflow in the squared norm.
bool normalize(V v, V* out) {
  const double m = maxAbs(v);
  if (!(m > 0) || !std::isfinite(m)) return false;
  const V s = (1 / m) * v;
  const double len = std::sqrt(dot(s, s));  // in [1, sqrt(3)]
  *out = (1 / len) * s;
  return true;
}

template <class S>
V widen(const Vec3<S>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

template <class S>
Vec3<S> narrow(V v) {
  return {S(v.x), S(v.y), S(v.z)};
}

/// The finite placeholders of the kInvalidInput contract.
template <class S>
void fillInvalid(const Pose<S>& pose, ContactEstimate<S>* out) {
  const V t = widen(pose.t);
  const bool finite =
      std::isfinite(t.x) && std::isfinite(t.y) && std::isfinite(t.z);
  out->point = finite ? pose.t : Vec3<S>{S(0), S(0), S(0)};
  out->normal = {S(0), S(0), S(1)};
  out->depth = kMinDepth<S>;
}

// ---------------------------------------------------------------- depth ---

/// Picks the direction of least separating-axis overlap among a fixed set.
/// Directions are offered unnormalised, in +/- pairs that share the work:
/// for n = v / |v|,
///   d(+n) = (r |v_xy| + h |v_z| - min_i y_i.v) / |v|,
///   d(-n) = (r |v_xy| + h |v_z| + max_i y_i.v) / |v|,
/// and only the winner is normalised (a third of the cost of normalising
/// every candidate first).
class DirectionSearch {
 public:
  DirectionSearch(const V (&y)[3], double r, double h) : y_(y), r_(r), h_(h) {}

  /// Offers +v and -v (in that order); a zero or non-finite v is skipped.
  void offerBoth(V v) {
    const double m = maxAbs(v);
    if (!(m > 0) || !std::isfinite(m)) return;
    // Keep the squares below in range (|v|^2 neither under- nor overflows).
    if (m < 0x1p-400 || m > 0x1p400) v = (1 / m) * v;
    const double inv_len = 1 / std::sqrt(dot(v, v));
    const double sup_c =
        r_ * std::sqrt(v.x * v.x + v.y * v.y) + h_ * std::fabs(v.z);
    const double p0 = dot(y_[0], v), p1 = dot(y_[1], v), p2 = dot(y_[2], v);
    const double lo = std::min(p0, std::min(p1, p2));
    const double hi = std::max(p0, std::max(p1, p2));
    consider((sup_c - lo) * inv_len, v, inv_len);
    consider((sup_c + hi) * inv_len, -v, inv_len);
  }

  bool found() const { return found_; }
  /// The winning direction, unit.
  V normal() const { return best_inv_len_ * best_v_; }
  double depth() const { return best_d_; }

 private:
  void consider(double d, V v, double inv_len) {
    if (!found_ || d < best_d_) {  // strict: the first minimum wins ties
      found_ = true;
      best_d_ = d;
      best_v_ = v;
      best_inv_len_ = inv_len;
    }
  }

  const V (&y_)[3];
  double r_, h_;
  bool found_ = false;
  double best_d_ = 0;
  V best_v_{0, 0, 1};
  double best_inv_len_ = 1;
};

/// Point of segment [a, b] whose xy-projection is nearest the axis, and the
/// squared xy-distance of that point.
V nearestToAxisOnSegment(V a, V b, double* dist2) {
  const double ex = b.x - a.x, ey = b.y - a.y;
  const double len2 = ex * ex + ey * ey;
  double s = 0;
  if (len2 > 0) {
    // s = -(a_xy . e_xy) / |e_xy|^2, clamped to [0, 1].
    s = -(a.x * ex + a.y * ey) / len2;
    s = std::min(1.0, std::max(0.0, s));
  }
  const V p = a + s * (b - a);
  *dist2 = p.x * p.x + p.y * p.y;
  return p;
}

void searchDirections(const V (&y)[3], V tri_normal, double r, double h,
                      DirectionSearch* search) {
  const V z{0, 0, 1};
  // 1. Face: the triangle normal (skipped when the triangle is degenerate).
  search->offerBoth(tri_normal);
  // 2. Caps: the axis.
  search->offerBoth(z);
  for (int i = 0; i < 3; ++i) {
    const V e = y[(i + 1) % 3] - y[i];
    // 3. Edge vs barrel: the common perpendicular of the edge and the axis.
    search->offerBoth(cross(e, z));
    // 4. In-plane edge normal.
    search->offerBoth(cross(e, tri_normal));
    // 5. Edge vs rim: e x (rim tangent at the edge's angular position).
    double d2;
    const V q = nearestToAxisOnSegment(y[i], y[(i + 1) % 3], &d2);
    if (d2 > 0) search->offerBoth(cross(e, V{-q.y, q.x, 0}));
  }
  for (int i = 0; i < 3; ++i) {
    const double rho = std::sqrt(y[i].x * y[i].x + y[i].y * y[i].y);
    if (!(rho > 0)) continue;  // vertex on the axis: no radial direction
    // 6. Vertex vs barrel: radial.
    search->offerBoth(V{y[i].x, y[i].y, 0});
    // 7. Vertex vs rim: from the nearest point of each rim circle.
    for (double side : {1.0, -1.0}) {
      const V rim{r * y[i].x / rho, r * y[i].y / rho, side * h};
      search->offerBoth(y[i] - rim);
    }
  }
}

// ---------------------------------------------------------------- point ---

constexpr int kMaxPoly = 8;  // 3 vertices, +1 per half-space clip

struct Poly {
  V p[kMaxPoly];
  int n = 0;
};

/// Sutherland-Hodgman against side*z <= h.
Poly clipHalfSpace(const Poly& in, double side, double h) {
  Poly out;
  for (int k = 0; k < in.n; ++k) {
    const V a = in.p[k];
    const V b = in.p[(k + 1) % in.n];
    const double fa = side * a.z - h;  // <= 0: kept
    const double fb = side * b.z - h;
    if (fa <= 0) out.p[out.n++] = a;
    if ((fa < 0 && fb > 0) || (fa > 0 && fb < 0)) {
      // Crossing of the plane: t = fa / (fa - fb), |fa - fb| >= |fa| > 0.
      const double t = fa / (fa - fb);
      V c = a + t * (b - a);
      c.z = side * h;  // on the plane by construction
      out.p[out.n++] = c;
    }
  }
  return out;
}

Poly clipSlab(const V (&y)[3], double h) {
  Poly tri;
  tri.n = 3;
  for (int i = 0; i < 3; ++i) tri.p[i] = y[i];
  return clipHalfSpace(clipHalfSpace(tri, 1, h), -1, h);
}

/// The point of a (possibly degenerate) convex polygon lying in the plane
/// with normal `plane_n` through `plane_p` whose xy-projection is nearest
/// the axis.
V nearestToAxis(const Poly& poly, V plane_n, V plane_p) {
  if (poly.n >= 3 && plane_n.z != 0) {
    // Does the projection contain the origin? Every edge must see it on the
    // same side (cross_i = p_i x p_{i+1}, z component).
    bool pos = true, neg = true;
    for (int k = 0; k < poly.n; ++k) {
      const V a = poly.p[k];
      const V b = poly.p[(k + 1) % poly.n];
      const double c = a.x * b.y - a.y * b.x;
      pos = pos && c >= 0;
      neg = neg && c <= 0;
    }
    if (pos != neg) {  // exactly one of them: inside, non-degenerate
      // The plane N.(p - p0) = 0 at p = (0, 0, z): z = N.p0 / N_z.
      return V{0, 0, dot(plane_n, plane_p) / plane_n.z};
    }
  }
  V best = poly.p[0];
  double best_d2 = best.x * best.x + best.y * best.y;
  for (int k = 0; k < poly.n; ++k) {
    double d2;
    const V p =
        nearestToAxisOnSegment(poly.p[k], poly.p[(k + 1) % poly.n], &d2);
    if (d2 < best_d2) {
      best_d2 = d2;
      best = p;
    }
  }
  return best;
}

/// Moves p into the closed cylinder (radial scale, then z clamp).
V clampIntoCylinder(V p, double r, double h) {
  const double rho2 = p.x * p.x + p.y * p.y;
  if (rho2 > r * r) {
    const double s = r / std::sqrt(rho2);
    p.x *= s;
    p.y *= s;
  }
  p.z = std::min(h, std::max(-h, p.z));
  return p;
}

V contactPoint(const V (&y)[3], V tri_normal, double r, double h) {
  Poly poly = clipSlab(y, h);
  if (poly.n == 0) {
    // Rounding put a touching triangle just outside a cap plane: widen the
    // slab once by 16 ulps of the local scale (fcl_contact.h, ACCURACY).
    double scale = h;
    for (const V& v : y) scale = std::max(scale, maxAbs(v));
    poly = clipSlab(y, h + 16 * std::numeric_limits<double>::epsilon() * scale);
  }
  if (poly.n == 0) {  // still nothing: the whole triangle, then the clamp
    poly.n = 3;
    for (int i = 0; i < 3; ++i) poly.p[i] = y[i];
  }
  return clampIntoCylinder(nearestToAxis(poly, tri_normal, y[0]), r, h);
}

}  // namespace

template <class S>
Answer estimateContact(const Cylinder<S>& cylinder, const Pose<S>& pose,
                       const Triangle<S>& triangle,
                       ContactEstimate<S>* out) noexcept {
  const Answer answer = tryIntersect(cylinder, pose, triangle);
  if (out == nullptr || answer == Answer::kDisjoint) return answer;
  if (answer == Answer::kInvalidInput) {
    fillInvalid(pose, out);
    return answer;
  }

  // Cylinder frame: y = R^T (x - t).
  double R[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R[i][j] = double(pose.R[i][j]);
  V t = widen(pose.t);
  V world[3] = {widen(triangle.a), widen(triangle.b), widen(triangle.c)};
  double r = double(cylinder.radius);
  double h = double(cylinder.lz) / 2;
  // Lengths above 2^300: the search's cross products (an edge times the
  // normal, cubic in the lengths) and squares, and x - t itself near 1e308,
  // overflow, and Inf / Inf or 0 * Inf raised FE_INVALID (from about 2^341).
  // Everything is then computed on the scene scaled by
  // 2^-e (exact: a power of two; lengths below 2^(e - 1074) lose their
  // last bits or flush to zero, far below the estimate's accuracy), which
  // brings the largest length near 1; the point and depth are scaled back.
  double big = std::max({maxAbs(t), r, h});
  for (const V& w : world) big = std::max(big, maxAbs(w));
  const int e = big > 0x1p300 ? std::ilogb(big) : 0;
  if (e != 0) {
    t = std::ldexp(1.0, -e) * t;
    for (V& w : world) w = std::ldexp(1.0, -e) * w;
    r = std::ldexp(r, -e);
    h = std::ldexp(h, -e);
  }
  V y[3];
  for (int k = 0; k < 3; ++k) {
    const V d = world[k] - t;
    y[k] = {R[0][0] * d.x + R[1][0] * d.y + R[2][0] * d.z,
            R[0][1] * d.x + R[1][1] * d.y + R[2][1] * d.z,
            R[0][2] * d.x + R[1][2] * d.y + R[2][2] * d.z};
  }
  const V tri_normal = cross(y[1] - y[0], y[2] - y[0]);

  DirectionSearch search(y, r, h);
  searchDirections(y, tri_normal, r, h, &search);
  // The axis is always offered, so `found()` holds; n is unit.
  const V n = search.normal();

  const V p = contactPoint(y, tri_normal, r, h);

  // Back to the world frame: x = R y + t; the normal is R n, renormalised
  // (R may be a hair off orthonormal).
  V p_world{R[0][0] * p.x + R[0][1] * p.y + R[0][2] * p.z + t.x,
            R[1][0] * p.x + R[1][1] * p.y + R[1][2] * p.z + t.y,
            R[2][0] * p.x + R[2][1] * p.y + R[2][2] * p.z + t.z};
  double depth = search.depth();
  if (e != 0) {  // back to the scene's scale (may overflow: guarded below)
    p_world = std::ldexp(1.0, e) * p_world;
    depth = std::ldexp(depth, e);
  }
  V n_world{R[0][0] * n.x + R[0][1] * n.y + R[0][2] * n.z,
            R[1][0] * n.x + R[1][1] * n.y + R[1][2] * n.z,
            R[2][0] * n.x + R[2][1] * n.y + R[2][2] * n.z};
  if (!normalize(n_world, &n_world)) n_world = {0, 0, 1};  // singular R

  // Overflow guards for inputs near the top of the double range (finite by
  // validation, but sums of them need not be).
  const bool point_ok = std::isfinite(p_world.x) && std::isfinite(p_world.y) &&
                        std::isfinite(p_world.z);
  out->point = point_ok ? narrow<S>(p_world) : pose.t;
  out->normal = narrow<S>(n_world);
  const S depth_s =
      std::isfinite(S(depth)) ? S(depth) : std::numeric_limits<S>::max();
  out->depth = depth_s > kMinDepth<S> ? depth_s : kMinDepth<S>;
  return answer;
}

template Answer estimateContact(const Cylinder<float>&, const Pose<float>&,
                                const Triangle<float>&,
                                ContactEstimate<float>*) noexcept;
template Answer estimateContact(const Cylinder<double>&, const Pose<double>&,
                                const Triangle<double>&,
                                ContactEstimate<double>*) noexcept;

}  // namespace tricyl
