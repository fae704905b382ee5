// SPDX-License-Identifier: BSD-3-Clause
// Triangle vs the margin-neighbourhood of a cylinder: exact (docs/margin.md).
//
// With C the closed cylinder (radius r, half-length h = lz/2) and B_m the
// closed ball of radius m, the nearest point of C to any point p is on the
// barrel, on a cap's interior or on a rim circle, so
//   C + B_m = Cyl(r + m, h)  u  Cyl(r, h + m)  u  Tor(+h)  u  Tor(-h),
// Tor(c) the solid torus of tube radius m around the rim circle at z = c.
// The triangle meets C + B_m iff it meets one of the four parts.
//
// The cylinders: the exact triangle kernel (src/triangle_cylinder_impl.h)
// with r + m (resp. lz + 2m) as the SUM of its two inputs: first bracketed
// by the public intersect on the two neighbouring doubles of the rounded sum
// (a subset and a superset, both exact tests), and only where the bracket
// disagrees, i.e. where the true radius lies in one ulp of the triangle's
// radial reach, re-decided with the sum as a node of the adaptive kernel's
// tape (double-word, then exact expansions or GMP).
//
// The tori: a point (rho, z) is within m of the rim circle (radius r, height
// c) iff (rho - r)^2 + (z - c)^2 <= m^2. With
//   L = rho^2 + (z - c)^2 + r^2 - m^2,   Q = L^2 - 4 r^2 rho^2
// that is L <= 2 r rho, i.e. L <= 0 or Q <= 0 (both sides squared only where
// both are non-negative): no square root. Along an edge p(s) = a + s (b - a),
// L is a quadratic and Q a quartic in s; the edge meets the torus iff one of
// them is <= 0 somewhere on [0, 1]. The face interior is needed only when no
// edge meets the torus and the triangle misses C (so it misses the rim
// circle): then a component of torus-cap-plane lies inside the triangle and
// holds a local minimum of dist(., circle) on the plane, which (off the axis
// and off the circle) is the foot of a rim point where the plane's normal n
// lies in the meridian plane: the rim points r (n_x, n_y)/|n_xy| (+-), or any
// rim point when n_xy = 0 (docs/margin.md has the proof). Testing these two
// feet (inside the triangle, and within m of their rim point) is exact in
// Q(sqrt(n_x^2 + n_y^2)): sign(a + b sqrt(D)) from the signs of a, b and
// a^2 - b^2 D.
//
// Stages of the tori: a double filter with running error bounds (the rules
// of RunningDoubleKernel, src/filter.h) on inputs scaled by a power of two to
// unit size, in which the edge polynomials are decided by their Bernstein
// coefficients on [0, 1] with de Casteljau subdivision to a fixed depth (all
// coefficients > 0: no point of the edge is inside; an end value < 0: a
// point is); then, for what it leaves open, GMP rationals, where the quartic
// is decided by its Sturm sequence on (0, 1) (its ends are tested first) and
// the quadratic by its vertex. Every stage does a fixed amount of work.
#include "tricyl/triangle_cylinder_margin.h"

#include <gmpxx.h>

#include <cmath>
#include <limits>
#include <type_traits>
#include <utility>
#include <vector>

#include "cylinder_queries_impl.h"
#include "filter.h"
#include "stages.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using detail::kAnd;
using detail::kOr;
using detail::Sign;
using detail::Tri;

// ---------------------------------------------------------------------------
// Exact sums of two doubles: the rounded sum and its error (Knuth's TwoSum),
// and the neighbouring doubles below and above the exact sum.

struct TwoSum {
  double s;       // fl(a + b), finite
  double e;       // a + b - s exactly
  bool finite;    // false: the rounded sum overflowed (e is then 0)
  double down() const {
    return e < 0 ? std::nextafter(s, -std::numeric_limits<double>::infinity())
                 : s;
  }
  double up() const {
    return e > 0 ? std::nextafter(s, std::numeric_limits<double>::infinity())
                 : s;
  }
};

TwoSum twoSum(double a, double b) {
  const double s = a + b;
  if (!std::isfinite(s)) return {s, 0, false};  // no inf - inf below
  const double bb = s - a;
  const double e = (a - (s - bb)) + (b - bb);
  return {s, e, true};
}

// ---------------------------------------------------------------------------
// Kernels for the torus parts: the running-bound double filter of
// src/filter.h, and GMP rationals (exact; the Sturm sequence divides).

using Rk = detail::RunningDoubleKernel;

struct QKernel {
  using Num = mpq_class;
  static Num lift(double x) { return Num(x); }
  static Sign sign(const Num& a) {
    const int s = sgn(a);
    return s < 0 ? Sign::kNeg : (s > 0 ? Sign::kPos : Sign::kZero);
  }
};

/// One torus in doubled local coordinates (X = 2x, Y = 2y, Z = 2z: the
/// doubled rim height c = +-lz stays a double): the triangle's vertices,
/// the doubled radius R = 2r, tube M = 2m, rim height C.
template <class K>
struct TorusInput {
  using N = typename K::Num;
  N X[3], Y[3], Z[3];
  N R, M, C;
};

/// sign(a + b sqrt(D)) for D > 0 (kUnknown where a needed sign is open).
template <class K>
Sign signWithRoot(const typename K::Num& a, const typename K::Num& b,
                  const typename K::Num& D) {
  const Sign sa = K::sign(a), sb = K::sign(b);
  if (sa == Sign::kUnknown || sb == Sign::kUnknown) return Sign::kUnknown;
  if (sb == Sign::kZero) return sa;
  if (sa == Sign::kZero || sa == sb) return sb;
  const Sign s2 = K::sign(a * a - b * b * D);  // |a| vs |b| sqrt(D)
  if (s2 == Sign::kUnknown || s2 == Sign::kZero) return s2;
  return s2 == Sign::kPos ? sa : sb;
}

/// The face part (see the file comment): does the foot on the triangle's
/// plane of one of the rim points +-r (n_x, n_y)/|n_xy| lie in the triangle
/// within m of that rim point? Only called for a triangle that misses the
/// rim circle and whose edges miss the torus.
template <class K>
Tri faceFeet(const TorusInput<K>& t) {
  using N = typename K::Num;
  const N ex0 = t.X[1] - t.X[0], ey0 = t.Y[1] - t.Y[0], ez0 = t.Z[1] - t.Z[0];
  const N ex1 = t.X[2] - t.X[0], ey1 = t.Y[2] - t.Y[0], ez1 = t.Z[2] - t.Z[0];
  const N n[3] = {ey0 * ez1 - ez0 * ey1, ez0 * ex1 - ex0 * ez1,
                  ex0 * ey1 - ey0 * ex1};
  const Sign sn[3] = {K::sign(n[0]), K::sign(n[1]), K::sign(n[2])};
  bool any_unknown = false, nonzero = false;
  for (Sign s : sn) {
    if (s == Sign::kUnknown) any_unknown = true;
    if (s == Sign::kPos || s == Sign::kNeg) nonzero = true;
  }
  if (!nonzero) return any_unknown ? Tri::kUnknown : Tri::kFalse;  // segment
  const N D = n[0] * n[0] + n[1] * n[1];
  const Sign sD = K::sign(D);
  if (sD == Sign::kUnknown) return Tri::kUnknown;
  const N n2 = D + n[2] * n[2];
  const N R2 = t.R * t.R, M2 = t.M * t.M;
  // Edge normals in the plane, c_i = n x E_i, E_i = V_{i+1} - V_i.
  N c[3][3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3;
    const N ex = t.X[j] - t.X[i], ey = t.Y[j] - t.Y[i], ez = t.Z[j] - t.Z[i];
    c[i][0] = n[1] * ez - n[2] * ey;
    c[i][1] = n[2] * ex - n[0] * ez;
    c[i][2] = n[0] * ey - n[1] * ex;
  }
  // beta_i = c_i . ((0, 0, C) - V_i), beta_d = n . ((0, 0, C) - V_0).
  N beta[3];
  for (int i = 0; i < 3; ++i)
    beta[i] = c[i][2] * (t.C - t.Z[i]) - c[i][0] * t.X[i] - c[i][1] * t.Y[i];
  const N bd = n[2] * (t.C - t.Z[0]) - n[0] * t.X[0] - n[1] * t.Y[0];
  detail::AnyOf any;
  for (int sg = 0; sg < 2; ++sg) {
    Tri ok = Tri::kTrue;
    if (sD == Sign::kZero) {
      // Horizontal plane: every rim point is critical; take (+-R, 0, C).
      const N gx = sg == 0 ? t.R : N(-t.R);
      for (int i = 0; i < 3 && ok != Tri::kFalse; ++i) {
        // (E_i x (g - V_i)) . n = (g - V_i) . c_i
        const N s = c[i][0] * (gx - t.X[i]) - c[i][1] * t.Y[i] +
                    c[i][2] * (t.C - t.Z[i]);
        ok = kAnd(ok, detail::isNonNeg(K::sign(s)));
      }
      if (ok == Tri::kFalse) continue;
      const N dn = n[0] * (gx - t.X[0]) - n[1] * t.Y[0] +
                   n[2] * (t.C - t.Z[0]);
      ok = kAnd(ok, detail::isNonPos(K::sign(dn * dn - M2 * n2)));
    } else {
      for (int i = 0; i < 3 && ok != Tri::kFalse; ++i) {
        N alpha = t.R * (c[i][0] * n[0] + c[i][1] * n[1]);
        if (sg == 1) alpha = -alpha;
        ok = kAnd(ok, detail::isNonNeg(signWithRoot<K>(alpha, beta[i], D)));
      }
      if (ok == Tri::kFalse) continue;
      // (s R w + beta_d)^2 <= M^2 |n|^2, w = sqrt(D), s = +-1:
      // R^2 D + beta_d^2 - M^2 |n|^2 + 2 s R beta_d w <= 0.
      const N a0 = R2 * D + bd * bd - M2 * n2;
      N a1 = (t.R + t.R) * bd;
      if (sg == 1) a1 = -a1;
      ok = kAnd(ok, detail::isNonPos(signWithRoot<K>(a0, a1, D)));
    }
    if (any.add(ok)) return Tri::kTrue;
  }
  return any.result();
}

/// The coefficients (power basis in s) of L and Q along the edge a -> b.
template <class K>
void edgePolys(const TorusInput<K>& t, int a, int b, typename K::Num* l,
               typename K::Num* q) {
  using N = typename K::Num;
  const N ex = t.X[b] - t.X[a], ey = t.Y[b] - t.Y[a], ez = t.Z[b] - t.Z[a];
  const N za = t.Z[a] - t.C;
  const N p0 = t.X[a] * t.X[a] + t.Y[a] * t.Y[a];
  const N p1 = (t.X[a] * ex + t.Y[a] * ey) + (t.X[a] * ex + t.Y[a] * ey);
  const N p2 = ex * ex + ey * ey;
  const N R2 = t.R * t.R;
  const N R4 = (R2 + R2) + (R2 + R2);
  l[0] = p0 + za * za + (R2 - t.M * t.M);
  l[1] = p1 + (za * ez + za * ez);
  l[2] = p2 + ez * ez;
  q[0] = l[0] * l[0] - R4 * p0;
  q[1] = (l[0] * l[1] + l[0] * l[1]) - R4 * p1;
  q[2] = l[1] * l[1] + (l[0] * l[2] + l[0] * l[2]) - R4 * p2;
  q[3] = l[1] * l[2] + l[1] * l[2];
  q[4] = l[2] * l[2];
}

// ---- The filter: Bernstein coefficients with subdivision ------------------

using Rd = detail::Rd;

/// Is some value of the polynomial with Bernstein coefficients b[0..n] on
/// an interval <= 0? kTrue if an end value is certainly < 0, kFalse if every
/// coefficient is certainly > 0 (convex-hull property), else subdivides at
/// the midpoint (de Casteljau; halving is exact but for underflow, which the
/// running bound's product rule covers), to `depth` more levels.
Tri bernsteinAnyNonPos(const Rd* b, int n, int depth) {
  const Sign s0 = Rk::sign(b[0]), sn = Rk::sign(b[n]);
  if (s0 == Sign::kNeg || sn == Sign::kNeg) return Tri::kTrue;
  bool all_pos = true;
  for (int i = 0; i <= n; ++i)
    if (Rk::sign(b[i]) != Sign::kPos) all_pos = false;
  if (all_pos) return Tri::kFalse;
  if (depth == 0) return Tri::kUnknown;
  Rd left[5], right[5], w[5];
  for (int i = 0; i <= n; ++i) w[i] = b[i];
  const Rd half = Rk::lift(0.5);
  for (int k = 0; k <= n; ++k) {
    left[k] = w[0];
    right[n - k] = w[n - k];
    for (int i = 0; i < n - k; ++i) w[i] = (w[i] + w[i + 1]) * half;
  }
  const Tri l = bernsteinAnyNonPos(left, n, depth - 1);
  if (l == Tri::kTrue) return l;
  return kOr(l, bernsteinAnyNonPos(right, n, depth - 1));
}

constexpr int kBernsteinDepth = 6;

Tri edgeFilter(const TorusInput<Rk>& t, int a, int b) {
  Rd l[3], q[5];
  edgePolys<Rk>(t, a, b, l, q);
  auto k = [](double v) { return Rk::lift(v); };
  // Bernstein coefficients times 2 (L) and 12 (Q): power -> Bernstein.
  const Rd lb[3] = {k(2) * l[0], k(2) * l[0] + l[1],
                    k(2) * (l[0] + l[1] + l[2])};
  const Rd q0 = k(12) * q[0];
  const Rd qb[5] = {q0, q0 + k(3) * q[1], q0 + k(6) * q[1] + k(2) * q[2],
                    q0 + k(9) * q[1] + k(6) * q[2] + k(3) * q[3],
                    k(12) * ((q[0] + q[1]) + (q[2] + q[3]) + q[4])};
  const Tri tq = bernsteinAnyNonPos(qb, 4, kBernsteinDepth);
  if (tq == Tri::kTrue) return tq;
  return kOr(tq, bernsteinAnyNonPos(lb, 2, kBernsteinDepth));
}

// ---- The exact stage: GMP rationals, Sturm sequence ------------------------

using Poly = std::vector<mpq_class>;  // coefficients, lowest degree first

void trim(Poly& p) {
  while (!p.empty() && sgn(p.back()) == 0) p.pop_back();
}

mpq_class evalAt(const Poly& p, const mpq_class& x) {
  mpq_class v = 0;
  for (auto it = p.rbegin(); it != p.rend(); ++it) v = v * x + *it;
  return v;
}

/// The remainder of a by b (b non-zero, trimmed).
Poly remainder(Poly a, const Poly& b) {
  trim(a);
  const size_t nb = b.size();
  while (a.size() >= nb) {
    const mpq_class f = a.back() / b.back();
    const size_t shift = a.size() - nb;
    for (size_t i = 0; i < nb; ++i) a[shift + i] -= f * b[i];
    a.pop_back();  // its leading coefficient is now exactly 0
    trim(a);
  }
  return a;
}

/// Number of distinct real roots of p in (0, 1), for p(0) != 0, p(1) != 0
/// (Sturm's theorem: variations at 0 minus variations at 1).
int sturmRootsInUnit(Poly p) {
  trim(p);
  if (p.size() <= 1) return 0;
  std::vector<Poly> chain;
  chain.push_back(p);
  Poly d;
  for (size_t i = 1; i < p.size(); ++i) d.push_back(p[i] * int(i));
  trim(d);
  while (!d.empty()) {
    chain.push_back(d);
    Poly r = remainder(chain[chain.size() - 2], d);
    for (auto& c : r) c = -c;
    d = std::move(r);
  }
  auto variations = [&](const mpq_class& x) {
    int v = 0, last = 0;
    for (const Poly& q : chain) {
      const int s = sgn(evalAt(q, x));
      if (s == 0) continue;
      if (last != 0 && s != last) ++v;
      last = s;
    }
    return v;
  };
  return variations(0) - variations(1);
}

bool edgeExact(const TorusInput<QKernel>& t, int a, int b) {
  mpq_class l[3], q[5];
  edgePolys<QKernel>(t, a, b, l, q);
  // L <= 0 somewhere on [0, 1]: at an end, or at the interior vertex of the
  // parabola (l2 > 0, -l1 / (2 l2) in (0, 1), 4 l0 l2 - l1^2 <= 0).
  const mpq_class l_end = l[0] + l[1] + l[2];
  if (sgn(l[0]) <= 0 || sgn(l_end) <= 0) return true;
  if (sgn(l[2]) > 0 && sgn(l[1]) < 0 && l[1] + 2 * l[2] > 0 &&
      4 * l[0] * l[2] - l[1] * l[1] <= 0)
    return true;
  // Q <= 0 somewhere: at an end, or (both ends > 0) at a root in (0, 1).
  const mpq_class q_end = q[0] + q[1] + q[2] + q[3] + q[4];
  if (sgn(q[0]) <= 0 || sgn(q_end) <= 0) return true;
  return sturmRootsInUnit(Poly(q, q + 5)) > 0;
}

/// One torus, exactly.
bool torusExact(const TorusInput<QKernel>& t) {
  static constexpr int kEdge[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  for (const auto& e : kEdge)
    if (edgeExact(t, e[0], e[1])) return true;
  return faceFeet<QKernel>(t) == Tri::kTrue;
}

/// One torus in the filter.
Tri torusFilter(const TorusInput<Rk>& t) {
  static constexpr int kEdge[3][2] = {{0, 1}, {1, 2}, {2, 0}};
  detail::AnyOf any;
  for (const auto& e : kEdge)
    if (any.add(edgeFilter(t, e[0], e[1]))) return Tri::kTrue;
  if (any.add(faceFeet<Rk>(t))) return Tri::kTrue;
  return any.result();
}

// ---------------------------------------------------------------------------
// The query.

struct Query {
  Cylinder<double> cyl;
  Pose<double> pose;
  Triangle<double> tri;
  double m;
  double max_len;
  double max_unitless;
};

/// The doubled local coordinates and sizes of the torus at height sgn * h,
/// exactly, mirrored in z for the bottom one (sgn = -1) so that its rim is
/// at +lz.
TorusInput<QKernel> torusExactInput(const Query& q, int sgn) {
  TorusInput<QKernel> t;
  const Vec3<double>* v[3] = {&q.tri.a, &q.tri.b, &q.tri.c};
  for (int i = 0; i < 3; ++i) {
    const mpq_class d[3] = {mpq_class(v[i]->x) - q.pose.t.x,
                            mpq_class(v[i]->y) - q.pose.t.y,
                            mpq_class(v[i]->z) - q.pose.t.z};
    mpq_class o[3];
    for (int k = 0; k < 3; ++k)
      o[k] = 2 * (mpq_class(q.pose.R[0][k]) * d[0] +
                  mpq_class(q.pose.R[1][k]) * d[1] +
                  mpq_class(q.pose.R[2][k]) * d[2]);
    t.X[i] = o[0];
    t.Y[i] = o[1];
    t.Z[i] = sgn > 0 ? o[2] : mpq_class(-o[2]);
  }
  t.R = 2 * mpq_class(q.cyl.radius);
  t.M = 2 * mpq_class(q.m);
  t.C = mpq_class(q.cyl.lz);
  return t;
}

/// The same in the filter, on the inputs scaled by 2^-k (k = the exponent of
/// the largest length), which keeps every magnitude of the torus tests
/// below 2^60 so that the bound computations' own underflow stays far below
/// the filter's absolute slack. False if the scaling is not exact (a
/// length would become subnormal) or the inputs are outside the range gate.
bool torusFilterInputs(const Query& q, TorusInput<Rk>* top,
                       TorusInput<Rk>* bot) {
  if (!detail::rangeGateOk(q.max_len, q.max_unitless) || q.max_len == 0)
    return false;
  const int k = std::ilogb(q.max_len);
  bool exact = true;
  auto sc = [&](double v) {
    const double w = std::ldexp(v, -k);
    if (std::ldexp(w, k) != v) exact = false;  // w became subnormal
    return w;
  };
  const Vec3<double>* v[3] = {&q.tri.a, &q.tri.b, &q.tri.c};
  const double tx = sc(q.pose.t.x), ty = sc(q.pose.t.y), tz = sc(q.pose.t.z);
  const Rd two = Rk::lift(2.0);
  for (int i = 0; i < 3; ++i) {
    const Rd d0 = Rk::inputDiff(sc(v[i]->x), tx);
    const Rd d1 = Rk::inputDiff(sc(v[i]->y), ty);
    const Rd d2 = Rk::inputDiff(sc(v[i]->z), tz);
    Rd o[3];
    for (int c = 0; c < 3; ++c)
      o[c] = two * (Rk::lift(q.pose.R[0][c]) * d0 +
                    Rk::lift(q.pose.R[1][c]) * d1 +
                    Rk::lift(q.pose.R[2][c]) * d2);
    top->X[i] = bot->X[i] = o[0];
    top->Y[i] = bot->Y[i] = o[1];
    top->Z[i] = o[2];
    bot->Z[i] = -o[2];
  }
  top->R = bot->R = Rk::lift(2 * sc(q.cyl.radius));
  top->M = bot->M = Rk::lift(2 * sc(q.m));
  top->C = bot->C = Rk::lift(sc(q.cyl.lz));
  return exact;
}

/// Cylinder part with the exact sum r + m (grow_radius) or lz + 2m as the
/// size, on the adaptive tape (or in GMP dyadics outside the range gate).
/// Reached only when the bracket of the two neighbouring doubles disagrees.
Decision cylinderPartExact(const Query& q, bool grow_radius) {
  auto pred = [&](auto tag, bool* early) {
    using K = typename decltype(tag)::type;
    auto loc = detail::makeLocal<K>(q.cyl, q.pose, q.tri, q.max_unitless);
    if (grow_radius)
      loc.r = loc.r + K::lift(q.m);
    else
      loc.H = loc.H + (K::lift(q.m) + K::lift(q.m));
    return detail::triangleCylinder<K>(loc, early);
  };
  // r + m and lz + 2m are at most 3 times the largest length: the gate is
  // taken on that, so the bounds behind the adaptive run hold for them.
  const bool gate = detail::rangeGateOk(4 * q.max_len, q.max_unitless);
  return detail::runAdaptive(pred, gate);
}

bool intersects(double r, double lz, const Query& q) {
  return tryIntersect(Cylinder<double>{r, lz}, q.pose, q.tri) ==
         Answer::kIntersect;
}

Stage stronger(Stage a, Stage b) {
  auto rank = [](Stage s) {
    switch (s) {
      case Stage::kEarlyOut: return 0;
      case Stage::kFastPath: return 1;
      case Stage::kExtended: return 2;
      case Stage::kExact: return 3;
      case Stage::kExactGmp: return 4;
      default: return 5;
    }
  };
  return rank(a) >= rank(b) ? a : b;
}

Decision yes(Stage s) { return {Answer::kIntersect, s}; }
Decision no(Stage s) { return {Answer::kDisjoint, s}; }

/// A sized part (grow_radius: Cyl(r + m, h), else Cyl(r, h + m)).
/// `stage` accumulates the strongest stage used.
bool cylinderPart(const Query& q, bool grow_radius, Stage* stage) {
  const TwoSum s = grow_radius ? twoSum(q.cyl.radius, q.m)
                               : twoSum(q.cyl.lz, 2 * q.m);
  if (s.finite && std::isfinite(2 * q.m)) {
    const double r = grow_radius ? s.down() : q.cyl.radius;
    const double lz = grow_radius ? q.cyl.lz : s.down();
    if (intersects(r, lz, q)) return true;  // a subset: exact yes
    if (s.e == 0) return false;             // the sum itself: exact no
    const double r_up = grow_radius ? s.up() : q.cyl.radius;
    const double lz_up = grow_radius ? q.cyl.lz : s.up();
    if (std::isfinite(r_up) && std::isfinite(lz_up) &&
        !intersects(r_up, lz_up, q))
      return false;  // a superset: exact no
  }
  const Decision d = cylinderPartExact(q, grow_radius);
  *stage = stronger(*stage, d.stage);
  return d.answer == Answer::kIntersect;
}

Decision decide(const Query& q) {
  if (q.m == 0) return decideIntersect(q.cyl, q.pose, q.tri);
  // A superset of C + B_m: Cyl(r + m, h + m), sizes rounded up.
  const TwoSum rs = twoSum(q.cyl.radius, q.m);
  const TwoSum ls = twoSum(q.cyl.lz, 2 * q.m);
  if (rs.finite && ls.finite && std::isfinite(2 * q.m)) {
    const double r_up = rs.up(), lz_up = ls.up();
    if (std::isfinite(r_up) && std::isfinite(lz_up) &&
        !intersects(r_up, lz_up, q))
      return no(Stage::kEarlyOut);
  }
  Stage stage = Stage::kFastPath;
  if (cylinderPart(q, true, &stage)) return yes(stage);
  if (cylinderPart(q, false, &stage)) return yes(stage);
  // The tori. The triangle misses C here, hence the rim circles.
  Tri t[2] = {Tri::kUnknown, Tri::kUnknown};
  TorusInput<Rk> ft[2];
  if (torusFilterInputs(q, &ft[0], &ft[1])) {
    for (int i = 0; i < 2; ++i) {
      t[i] = torusFilter(ft[i]);
      if (t[i] == Tri::kTrue) return yes(stage);
    }
    if (t[0] == Tri::kFalse && t[1] == Tri::kFalse) return no(stage);
  }
  for (int i = 0; i < 2; ++i) {
    if (t[i] != Tri::kUnknown) continue;
    if (torusExact(torusExactInput(q, i == 0 ? 1 : -1)))
      return yes(Stage::kExactGmp);
  }
  return no(Stage::kExactGmp);
}

Decision validateAndDecide(const Cylinder<double>& cyl,
                           const Pose<double>& pose,
                           const Triangle<double>& tri, double m) {
  Query q{cyl, pose, tri, m, 0, 0};
  if (!detail::scanFinite({cyl.radius, cyl.lz, m, tri.a.x, tri.a.y, tri.a.z,
                           tri.b.x, tri.b.y, tri.b.z, tri.c.x, tri.c.y,
                           tri.c.z},
                          pose, &q.max_len, &q.max_unitless) ||
      !(cyl.radius >= 0 && cyl.lz >= 0 && m >= 0))
    return {Answer::kInvalidInput, Stage::kInvalid};
  // -0 is 0 for every size (the bits of -0 would break nothing, but the
  // exact sums are clearer on +0).
  q.cyl.radius = cyl.radius + 0.0;
  q.cyl.lz = cyl.lz + 0.0;
  q.m = m + 0.0;
  return decide(q);
}

template <class S>
Decision decideAs(const Cylinder<S>& cyl, const Pose<S>& pose,
                  const Triangle<S>& tri, S m) noexcept {
  if constexpr (std::is_same_v<S, float>) {
    const Cylinder<float> mm{m, m};
    if (!detail::floatBitsFinite(cyl, pose, tri, mm))  // before widening
      return {Answer::kInvalidInput, Stage::kInvalid};
  }
  try {
    return validateAndDecide(
        {double(cyl.radius), double(cyl.lz)}, detail::widen(pose),
        {detail::widen(tri.a), detail::widen(tri.b), detail::widen(tri.c)},
        double(m));
  } catch (...) {  // std::bad_alloc from GMP or a vector: nothing else throws
    std::terminate();
  }
}

}  // namespace

template <class S>
Decision decideWithinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                              const Triangle<S>& triangle, S margin) noexcept {
  return decideAs(cylinder, pose, triangle, margin);
}

template <class S>
Answer tryWithinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Triangle<S>& triangle, S margin) noexcept {
  return decideAs(cylinder, pose, triangle, margin).answer;
}

template <class S>
bool withinDistance(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle, S margin) {
  const Answer a = decideAs(cylinder, pose, triangle, margin).answer;
  if (a == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::withinDistance: NaN or infinite input, or a negative "
        "radius, length or margin");
  return a == Answer::kIntersect;
}

template <class S>
bool withinDistance(const Cylinder<S>& cylinder, const Triangle<S>& triangle,
                    S margin) {
  return withinDistance(cylinder, identityPose<S>(), triangle, margin);
}

template bool withinDistance(const Cylinder<float>&, const Pose<float>&,
                             const Triangle<float>&, float);
template bool withinDistance(const Cylinder<double>&, const Pose<double>&,
                             const Triangle<double>&, double);
template bool withinDistance(const Cylinder<float>&, const Triangle<float>&,
                             float);
template bool withinDistance(const Cylinder<double>&, const Triangle<double>&,
                             double);
template Answer tryWithinDistance(const Cylinder<float>&, const Pose<float>&,
                                  const Triangle<float>&, float) noexcept;
template Answer tryWithinDistance(const Cylinder<double>&, const Pose<double>&,
                                  const Triangle<double>&, double) noexcept;
template Decision decideWithinDistance(const Cylinder<float>&,
                                       const Pose<float>&,
                                       const Triangle<float>&, float) noexcept;
template Decision decideWithinDistance(const Cylinder<double>&,
                                       const Pose<double>&,
                                       const Triangle<double>&,
                                       double) noexcept;

}  // namespace tricyl
