// SPDX-License-Identifier: BSD-3-Clause
// The triangle-cylinder test, written once over a kernel K (src/filter.h).
//
// Frame: the cylinder frame, with every z coordinate DOUBLED (Z = 2 z, an
// exact operation) so that the slab |z| <= lz/2 reads |Z| <= H with H = lz
// and no halving (which could round a subnormal lz) is ever needed.
//
// Eberly's clip-and-project, evaluated implicitly. The slab-clipped triangle
// projects to a convex piece P' of the xy-plane; P' meets the disk of
// radius r iff one of the following holds (Eberly, Section 2, last three
// paragraphs):
//   (V) a vertex of P' that is a triangle vertex lies in the disk;
//   (X) a vertex of P' that is an edge/plane crossing lies in the disk;
//   (E) the closest point to the origin of a slab-clipped triangle edge is
//       interior to it and within r;
//   (B) the closest point of a chord {Z = +-H} of the triangle (the clipped
//       polygon's edges that Eberly's clip creates) is interior and within r;
//   (A) the origin lies in P', i.e. the axis segment meets the triangle.
// Correspondence with Eberly's Figure 1: 0a/0b are the slab early-outs;
// 1a/1b/2a/2b (one vertex or one edge touching a clip plane from outside)
// are decided by (V) or by (E)/(X) on the touching edge; 3a (all inside) by
// (V),(E),(A); 3b-3e and 4a-4f (one plane clips) add (X) and one chord (B);
// 5 (both planes clip, a pentagon) adds both chords. The chord and crossing
// tests are evaluated for each plane separately, with that plane's own sign
// (the "clip against -h/2 instead of +h/2" bug cannot arise).
//
// Why (A) needs a non-zero projected area: when the triangle's plane
// contains the axis direction, the projection is a segment through or near
// the origin, and "origin inside the polygon" is meaningless (the published
// bug answers "intersect" for r = 0.5, lz = 4, triangle (1,0,-1), (2,0,-1),
// (1.5,0,1)). In that case every point the cylinder shares with the
// triangle's plane forms a rectangle with corners on the rims, so (V),(X),
// (E),(B) alone are complete; the proof is in docs/exactness.md.
#pragma once

#include <limits>

#include "adaptive.h"
#include "dw_kernel.h"
#include "filter.h"
#include "tricyl/types.h"

namespace tricyl::detail {

template <class K>
struct TriCylLocal {
  using N = typename K::Num;
  N x[3], y[3], Z[3];  // local coordinates, Z = 2 z
  N H;                 // lz: the slab is |Z| <= H
  N r;                 // radius
};

/// y = R^T (p - t), with z doubled, in kernel K. `rho` >= max |R_ij| (used
/// by the filter only).
template <class K>
inline void toLocal(const Pose<double>& pose, const Vec3<double>& p,
                    double /*rho*/, typename K::Num& x, typename K::Num& y,
                    typename K::Num& Z) {
  using N = typename K::Num;
  const N d0 = K::inputDiff(p.x, pose.t.x);
  const N d1 = K::inputDiff(p.y, pose.t.y);
  const N d2 = K::inputDiff(p.z, pose.t.z);
  const auto& R = pose.R;
  x = K::lift(R[0][0]) * d0 + K::lift(R[1][0]) * d1 + K::lift(R[2][0]) * d2;
  y = K::lift(R[0][1]) * d0 + K::lift(R[1][1]) * d1 + K::lift(R[2][1]) * d2;
  const N z =
      K::lift(R[0][2]) * d0 + K::lift(R[1][2]) * d1 + K::lift(R[2][2]) * d2;
  Z = z + z;
}

/// The filter's version: the same rounded values, with ONE magnitude per
/// vertex, m = rho (|d0| + |d1| + |d2|), for x, y and z alike. It bounds
/// every coordinate's own magnitude sum |R_0k||d0| + |R_1k||d1| + |R_2k||d2|
/// from above (rho >= |R_jk|), and a larger m only loosens the bound of
/// FilterKernel::sign (every later m is a monotone function of it). Its
/// rounding, three operations on non-negative values, stays within the
/// (1 - u)^D allowance of that bound. Cost: 4 operations per vertex instead
/// of 15 per coordinate.
template <>
inline void toLocal<FilterKernel>(const Pose<double>& pose,
                                  const Vec3<double>& p, double rho, Fd& x,
                                  Fd& y, Fd& Z) {
  const double d0 = p.x - pose.t.x;
  const double d1 = p.y - pose.t.y;
  const double d2 = p.z - pose.t.z;
  const auto& R = pose.R;
  const double m = rho * (std::fabs(d0) + std::fabs(d1) + std::fabs(d2));
  x = {R[0][0] * d0 + R[1][0] * d1 + R[2][0] * d2, m};
  y = {R[0][1] * d0 + R[1][1] * d1 + R[2][1] * d2, m};
  const double z = R[0][2] * d0 + R[1][2] * d1 + R[2][2] * d2;
  Z = {z + z, m + m};
}

/// The running kernel's version (RunningDoubleKernel; value
/// type T with unit roundoff u and smallest subnormal eta): the values
/// computed exactly as the generic toLocal computes them, in T, and the
/// per-operation rules folded into one bound per coordinate (a third of the
/// operations, the same bound to first order). Derivation, for
///   x = R_00 (p_0 - t_0) + R_10 (p_1 - t_1) + R_20 (p_2 - t_2)
/// computed as d_k = fl(p_k - t_k), P_k = fl(R_k0 d_k), s1 = fl(P_0 + P_1),
/// x^ = fl(s1 + P_2). With u' = u (1 + 2 u) (an operation's error relative
/// to its rounded result) and an underflow loss of at most eta / 2 per
/// product:
///   |x^ - x| <= u' |x^| + u' |s1| + sum_k (u' |P_k| + eta / 2)
///               + sum_k |R_k0| u' |d_k|,
/// and |P_k| <= (1 + u) |R_k0| |d_k| + eta / 2. With S = sum_k |R_k0| |d_k|
/// and S^ its computed value (non-negative terms: S <= (S^ + 2 eta) /
/// (1 - u)^3),
///   |x^ - x| <= u (1 + 8.5 u) (2 S^ + |s1| + |x^|) + 2 eta
///            <= e = fl(fl(fl(2 S^ + |s1|) + |x^|) * c) + 4 eta,
/// c = u (1 + 2^-40): the three roundings of e lose at most a factor
/// (1 - u)^3, and 2^-40 >> 12 u. Where every term has a zero factor the
/// value is an exact 0 and e = 0. Z = z + z is exact (no overflow under the
/// range gate), and so is e_Z = 2 e_z.
template <class K>
inline void toLocalRunning(const Pose<double>& pose, const Vec3<double>& p,
                           typename K::Num& x, typename K::Num& y,
                           typename K::Num& Z) {
  using T = decltype(x.v);
  constexpr T u = std::numeric_limits<T>::epsilon() / 2;
  constexpr T c = u + u * T(0x1p-40);
  constexpr T eta = std::numeric_limits<T>::denorm_min();
  auto abs = [](T v) { return v < 0 ? -v : v; };
  const T d[3] = {T(p.x) - T(pose.t.x), T(p.y) - T(pose.t.y),
                  T(p.z) - T(pose.t.z)};
  const T a[3] = {abs(d[0]), abs(d[1]), abs(d[2])};
  const auto& R = pose.R;
  auto coord = [&](int j, typename K::Num& out) {
    const T r0 = T(R[0][j]), r1 = T(R[1][j]), r2 = T(R[2][j]);
    const T s1 = r0 * d[0] + r1 * d[1];
    out.v = s1 + r2 * d[2];
    const T S = abs(r0) * a[0] + abs(r1) * a[1] + abs(r2) * a[2];
    // Every term an exact zero (a zero factor: fl(p - t) = 0 iff p == t
    // under gradual underflow): then x^ = x = 0 and nothing underflowed,
    // and e = 0 keeps that zero certified (the per-operation rules gave it
    // too; the line interval tests A = 0 and DZ = 0 that way).
    const bool zero = (r0 == 0 || d[0] == 0) && (r1 == 0 || d[1] == 0) &&
                      (r2 == 0 || d[2] == 0);
    out.e = (((S + S) + abs(s1)) + abs(out.v)) * c + (zero ? T(0) : 4 * eta);
  };
  coord(0, x);
  coord(1, y);
  coord(2, Z);
  Z.v = Z.v + Z.v;
  Z.e = Z.e + Z.e;
}
template <>
inline void toLocal<RunningDoubleKernel>(const Pose<double>& pose,
                                         const Vec3<double>& p, double /*rho*/,
                                         Rd& x, Rd& y, Rd& Z) {
  toLocalRunning<RunningDoubleKernel>(pose, p, x, y, Z);
}
/// The adaptive run's version: the same double values and magnitudes as
/// the generic toLocal<FilterKernel>, and one leaf per coordinate whose
/// stronger values the tape computes only when a sign needs them.
template <>
inline void toLocal<AdaptiveKernel>(const Pose<double>& pose,
                                    const Vec3<double>& p, double /*rho*/,
                                    An& x, An& y, An& Z) {
  tls_tape->toLocal(pose, p, x, y, Z);
}

template <class K>
inline TriCylLocal<K> makeLocal(const Cylinder<double>& cyl,
                                const Pose<double>& pose,
                                const Triangle<double>& tri, double rho) {
  TriCylLocal<K> q;
  toLocal<K>(pose, tri.a, rho, q.x[0], q.y[0], q.Z[0]);
  toLocal<K>(pose, tri.b, rho, q.x[1], q.y[1], q.Z[1]);
  toLocal<K>(pose, tri.c, rho, q.x[2], q.y[2], q.Z[2]);
  q.H = K::lift(cyl.lz);
  q.r = K::lift(cyl.radius);
  return q;
}

/// Accumulates a disjunction: returns true as soon as a term is certainly
/// true; remembers whether any term was undecided.
class AnyOf {
 public:
  bool add(Tri t) {
    if (t == Tri::kUnknown) unknown_ = true;
    return t == Tri::kTrue;
  }
  Tri result() const { return unknown_ ? Tri::kUnknown : Tri::kFalse; }

 private:
  bool unknown_ = false;
};

/// The 15 tests of triangleCylinderTests, one bit each: (V) vertex i,
/// (X) cap s and edge e, (E) edge e, (A), (B) cap s.
/// The triangle's edges (i, j), in the order of the tests' bits.
constexpr int kEdge[3][2] = {{0, 1}, {1, 2}, {2, 0}};

constexpr int kTestV = 0, kTestX = 3, kTestE = 9, kTestA = 12, kTestB = 13;
constexpr std::uint32_t kAllTests = (std::uint32_t(1) << 15) - 1;

/// Which tests to run (`run`), and which of them the kernel left undecided
/// (`unknown`, filled in). The query's answer is the disjunction of the
/// tests, so after a run that decided no test true, the tests it decided
/// false (certified) can be dropped: a second run in stronger arithmetic
/// needs only the undecided ones (triangleCylinderUndecided below).
///   `stop_at_unknown`: the run ends at its first undecided test, which
/// with every later test in `run` is reported undecided (the tests run in
/// the order of their bits). For a stage whose undecided tests go on to a
/// stronger one (the running stage): a test it cannot decide is usually a
/// near tie that the later tests share, and the stronger stage re-runs
/// them anyway (bench/results/2026-11-26-triangle-stages-f.md).
struct TestMask {
  std::uint32_t run = kAllTests;
  std::uint32_t unknown = 0;
  bool stop_at_unknown = false;
};

/// Closest point of the 2D segment between the homogeneous points
/// (X1, Y1)/W1 and (X2, Y2)/W2 (W1, W2 > 0) to the origin is interior to the
/// segment and within r of the origin. Endpoints are tested elsewhere.
/// Derivation: with E_k = (X_k, Y_k)/W_k and D = E2 - E1, the foot of the
/// perpendicular is interior iff E1.(E1 - E2) >= 0 and E2.(E2 - E1) >= 0;
/// multiplying by W1^2 W2 > 0 (resp. W2^2 W1):
///   dot1 = (X1,Y1).(W2 (X1,Y1) - W1 (X2,Y2)) >= 0,  dot2 symmetric.
/// Its distance is |E1 x E2| / |D|; multiplying by W1 W2 > 0 (twice):
///   (X1 Y2 - Y1 X2)^2 <= r^2 |W1 (X2,Y2) - W2 (X1,Y1)|^2,  with |.| > 0.
/// Degree 8 in the inputs when X, Y have degree 2 and W degree 1.
template <class K>
inline Tri chordWithinR(const typename K::Num& X1, const typename K::Num& Y1,
                        const typename K::Num& W1, const typename K::Num& X2,
                        const typename K::Num& Y2, const typename K::Num& W2,
                        const typename K::Num& r2) {
  using N = typename K::Num;
  const N Dx = W1 * X2 - W2 * X1;  // W1 W2 (E2 - E1)
  const N Dy = W1 * Y2 - W2 * Y1;
  const N D2 = Dx * Dx + Dy * Dy;
  Tri t = isPos(K::sign(D2));  // a chord that is a single point: no interior
  if (t == Tri::kFalse) return t;
  t = kAnd(t, isNonPos(K::sign(X1 * Dx + Y1 * Dy)));  // dot1 = -(E1n . D)
  if (t == Tri::kFalse) return t;
  t = kAnd(t, isNonNeg(K::sign(X2 * Dx + Y2 * Dy)));  // dot2 = E2n . D
  if (t == Tri::kFalse) return t;
  const N c = X1 * Y2 - Y1 * X2;
  return kAnd(t, isNonNeg(K::sign(r2 * D2 - c * c)));
}

template <class K>
Tri triangleCylinderTests(const TriCylLocal<K>& q, const Sign* top,
                          const Sign* bot, TestMask* mask = nullptr);

/// The early-outs: cases 0a/0b (the triangle strictly below or above the
/// slab, from the slab signs top[i] = sign(Z_i - H), bot[i] = sign(Z_i + H)),
/// then the disk's bounding square (the projection strictly beyond x > r,
/// x < -r, y > r or y < -r). An undecided sign simply skips an early-out.
template <class K>
bool certainlyBeyond(const TriCylLocal<K>& q, const Sign* top,
                     const Sign* bot) {
  using N = typename K::Num;
  if ((top[0] == Sign::kPos && top[1] == Sign::kPos && top[2] == Sign::kPos) ||
      (bot[0] == Sign::kNeg && bot[1] == Sign::kNeg && bot[2] == Sign::kNeg))
    return true;
  const N& r = q.r;
  auto allPos = [&](const N* c, bool negate) {
    for (int i = 0; i < 3; ++i) {
      const N v = negate ? N(-c[i] - r) : N(c[i] - r);
      if (K::sign(v) != Sign::kPos) return false;
    }
    return true;
  };
  return allPos(q.x, false) || allPos(q.x, true) || allPos(q.y, false) ||
         allPos(q.y, true);
}

/// The test itself. `early` is set when a certified early-out decided.
/// `mask` (optional): which tests were left undecided (TestMask).
template <class K>
Tri triangleCylinder(const TriCylLocal<K>& q, bool* early,
                     TestMask* mask = nullptr) {
  using N = typename K::Num;
  const N* Z = q.Z;
  const N& H = q.H;
  *early = false;

  // Slab signs, shared by the early-out, (V), (X) and (B):
  // top[i] = sign(Z_i - H), bot[i] = sign(Z_i + H).
  Sign top[3], bot[3];
  for (int i = 0; i < 3; ++i) {
    top[i] = K::sign(Z[i] - H);
    bot[i] = K::sign(Z[i] + H);
  }
  if (certainlyBeyond<K>(q, top, bot)) {
    *early = true;
    return Tri::kFalse;
  }
  return triangleCylinderTests<K>(q, top, bot, mask);
}

/// The disjunction of the tests in `tests` alone (the ones an earlier run
/// left undecided, TestMask), with only the slab signs they read: (V) i
/// reads top[i] and bot[i], (X) on cap s the two ends' signs on that cap,
/// (B) on cap s all three; (E) and (A) none. The early-outs first: a
/// certified rejection is the answer whatever the tests say. `left`
/// (optional): the tests this run left undecided, when it returns kUnknown
/// (the double-word kernel, src/dw_kernel.h, can). `stop_at_unknown`:
/// TestMask's.
/// Whether the six early-outs are settled: each failed at a certified sign,
/// so that a stronger kernel would fail them too.
struct EarlyOuts {
  bool settled = false;
};

template <class K>
Tri triangleCylinderUndecided(const TriCylLocal<K>& q, std::uint32_t tests,
                              std::uint32_t* left = nullptr,
                              EarlyOuts* early = nullptr,
                              bool stop_at_unknown = false) {
  // The early-outs again (the slab, then the disk's bounding square): in
  // the adaptive kernel they often decide what the filter could not, at the
  // cost of a few signs (fewer instructions in every family than going
  // straight to the undecided tests). Each fails at its first sign that is
  // not positive; if that sign is certified (not kUnknown) the early-out
  // fails in every arithmetic, and when all six do, a later stage skips
  // them (EarlyOuts).
  if (early == nullptr || !early->settled) {
    using N = typename K::Num;
    bool settled = true;
    auto allPos = [&](const N* c, bool negate, const N& d) {
      for (int i = 0; i < 3; ++i) {
        const Sign s = K::sign(negate ? N(-c[i] - d) : N(c[i] - d));
        if (s != Sign::kPos) {
          settled &= s != Sign::kUnknown;
          return false;
        }
      }
      return true;
    };
    if (allPos(q.Z, false, q.H) || allPos(q.Z, true, q.H) ||
        allPos(q.x, false, q.r) || allPos(q.x, true, q.r) ||
        allPos(q.y, false, q.r) || allPos(q.y, true, q.r))
      return Tri::kFalse;
    if (early) early->settled = settled;
  }
  std::uint32_t need[2] = {0, 0};  // per cap: bit i = vertex i's sign
  for (int i = 0; i < 3; ++i)
    if (tests >> (kTestV + i) & 1) need[0] |= 1u << i, need[1] |= 1u << i;
  for (int c = 0; c < 2; ++c) {
    if (tests >> (kTestB + c) & 1) need[c] |= 7u;
    for (int e = 0; e < 3; ++e)
      if (tests >> (kTestX + 3 * c + e) & 1)
        need[c] |= (1u << kEdge[e][0]) | (1u << kEdge[e][1]);
  }
  Sign top[3], bot[3];
  for (int i = 0; i < 3; ++i) {
    top[i] = need[0] >> i & 1 ? K::sign(q.Z[i] - q.H) : Sign::kUnknown;
    bot[i] = need[1] >> i & 1 ? K::sign(q.Z[i] + q.H) : Sign::kUnknown;
  }
  TestMask mask;
  mask.run = tests;
  mask.stop_at_unknown = stop_at_unknown;
  const Tri t = triangleCylinderTests<K>(q, top, bot, &mask);
  if (left) *left = mask.unknown;
  return t;
}

/// Everything after the early-outs: (V), (X), (E), (A), (B). `top` and
/// `bot` are the slab signs sign(Z_i - H) and sign(Z_i + H) in kernel K
/// (the caller computed them; the scalar fast path of
/// src/triangle_cylinder.cpp computes them itself, branch-free).
template <class K>
Tri triangleCylinderTests(const TriCylLocal<K>& q, const Sign* top,
                          const Sign* bot, TestMask* mask) {
  using N = typename K::Num;
  const N* x = q.x;
  const N* y = q.y;
  const N* Z = q.Z;
  const N& H = q.H;
  const N r2 = q.r * q.r;
  AnyOf any;
  const std::uint32_t run = mask ? mask->run : kAllTests;
  auto skip = [run](int bit) { return (run >> bit & 1) == 0; };
  // any.add, and the test's bit in mask->unknown when it is undecided.
  // With stop_at_unknown, an undecided test ends the run: add returns true
  // and `done` then answers kUnknown.
  bool stopped = false;
  auto add = [&any, mask, &stopped](Tri t, int bit) {
    if (t == Tri::kUnknown && mask) {
      mask->unknown |= std::uint32_t(1) << bit;
      if (mask->stop_at_unknown) {
        mask->unknown |= mask->run & (~std::uint32_t(0) << bit);
        stopped = true;
        return true;
      }
    }
    return any.add(t);
  };
  auto done = [&stopped] { return stopped ? Tri::kUnknown : Tri::kTrue; };

  // (V) A triangle vertex inside the solid: |Z| <= H and x^2 + y^2 <= r^2.
  for (int i = 0; i < 3; ++i) {
    if (skip(kTestV + i)) continue;
    const Tri in_slab = kAnd(isNonPos(top[i]), isNonNeg(bot[i]));
    if (in_slab == Tri::kFalse) continue;
    if (add(kAnd(in_slab, isNonNeg(K::sign(r2 - x[i] * x[i] - y[i] * y[i]))),
            kTestV + i))
      return done();
  }

  // (X) An edge crossing a cap plane Z = s H strictly (a_i a_j < 0, with
  // a = Z - s H) at a point inside the cap disk. The crossing point is
  //   (x_i a_j - x_j a_i, y_i a_j - y_j a_i) / (a_j - a_i),
  // so "inside" is X^2 + Y^2 <= r^2 W^2 with W = a_j - a_i (sign-free).
  for (int s = 0; s < 2; ++s) {
    const Sign* sa = s == 0 ? top : bot;
    for (int ei = 0; ei < 3; ++ei) {
      if (skip(kTestX + 3 * s + ei)) continue;
      const int i = kEdge[ei][0], j = kEdge[ei][1];
      const Tri crossing = kOr(kAnd(isNeg(sa[i]), isPos(sa[j])),
                               kAnd(isPos(sa[i]), isNeg(sa[j])));
      if (crossing == Tri::kFalse) continue;
      const N ai = s == 0 ? N(Z[i] - H) : N(Z[i] + H);
      const N aj = s == 0 ? N(Z[j] - H) : N(Z[j] + H);
      const N X = x[i] * aj - x[j] * ai;
      const N Y = y[i] * aj - y[j] * ai;
      const N W = aj - ai;
      if (add(kAnd(crossing, isNonNeg(K::sign(r2 * (W * W) - X * X - Y * Y))),
              kTestX + 3 * s + ei))
        return done();
    }
  }

  // (E) The closest point of edge (i, j)'s projection to the origin, at
  // parameter mu = g / L with L = |e|^2, g = -A.e (A = (x_i, y_i),
  // e = B - A), is interior (0 <= g <= L), at squared distance
  // c^2 / L <= r^2 (c = A x B, by Lagrange's identity), and inside the slab:
  // |Z_i + mu (Z_j - Z_i)| <= H, i.e. |Z_i L + g (Z_j - Z_i)| <= H L,
  // evaluated as (H -+ Z_i) L -+ g (Z_j - Z_i) >= 0: the same polynomials,
  // grouped so that an edge lying in a cap plane (Z_i = Z_j = +-H) gives
  // products of exact zeros, an exact 0 that the exact stage certifies cheaply
  // (a wall standing on the floor plane of a cylinder's cap), where
  // H L - Z_i L would cancel two rounded products.
  // L = 0 (an edge parallel to the axis) is covered by (V) and (X).
  for (int ei = 0; ei < 3; ++ei) {
    if (skip(kTestE + ei)) continue;
    const int i = kEdge[ei][0], j = kEdge[ei][1];
    const N ex = x[j] - x[i];
    const N ey = y[j] - y[i];
    const N L = ex * ex + ey * ey;
    Tri t = isPos(K::sign(L));
    if (t == Tri::kFalse) continue;
    const N c = x[i] * y[j] - x[j] * y[i];
    t = kAnd(t, isNonNeg(K::sign(r2 * L - c * c)));
    if (t == Tri::kFalse) continue;
    const N g = -(x[i] * ex + y[i] * ey);
    t = kAnd(t, isNonNeg(K::sign(g)));
    if (t == Tri::kFalse) continue;
    t = kAnd(t, isNonNeg(K::sign(L - g)));
    if (t == Tri::kFalse) continue;
    const N gz = g * (Z[j] - Z[i]);
    t = kAnd(t, isNonNeg(K::sign((H - Z[i]) * L - gz)));
    if (t == Tri::kFalse) continue;
    t = kAnd(t, isNonNeg(K::sign((H + Z[i]) * L + gz)));
    if (add(t, kTestE + ei)) return done();
  }

  // (A) The axis segment meets the triangle. With o_ij = x_i y_j - x_j y_i
  // (the orientation of origin, P_i, P_j) and A2 = o01 + o12 + o20 (twice
  // the signed projected area), the origin is in the projected triangle iff
  // every o_ij has the sign of A2 or is zero; its barycentric coordinates
  // are (o12, o20, o01) / A2, so the axis meets the triangle's plane at
  // Z* = (o12 Z0 + o20 Z1 + o01 Z2) / A2 = Z0 + (o20 (Z1 - Z0) +
  // o01 (Z2 - Z0)) / A2 (o12 = A2 - o20 - o01), and |Z*| <= H is, with A2
  // oriented positive and w = o20 (Z1 - Z0) + o01 (Z2 - Z0),
  //   (H - Z0) A2 - w >= 0  and  (H + Z0) A2 + w >= 0.
  // This grouping makes a triangle lying in a cap plane (the floor under a
  // standing cylinder) an exact 0 from exact zeros, which the exact stage
  // certifies; H A2 - (o12 Z0 + ...) would cancel rounded products.
  // A2 = 0: see the header comment.
  if (!skip(kTestA)) {
    const N o01 = x[0] * y[1] - x[1] * y[0];
    const N o12 = x[1] * y[2] - x[2] * y[1];
    const N o20 = x[2] * y[0] - x[0] * y[2];
    const N A2 = o01 + o12 + o20;
    const Sign sA = K::sign(A2);
    if (sA == Sign::kUnknown) {
      if (add(Tri::kUnknown, kTestA)) return done();
    } else if (sA != Sign::kZero) {
      const bool flip = sA == Sign::kNeg;
      auto oriented = [flip](const N& v) { return flip ? N(-v) : v; };
      Tri t = isNonNeg(K::sign(oriented(o01)));
      if (t != Tri::kFalse) t = kAnd(t, isNonNeg(K::sign(oriented(o12))));
      if (t != Tri::kFalse) t = kAnd(t, isNonNeg(K::sign(oriented(o20))));
      if (t != Tri::kFalse) {
        const N w = oriented(o20 * (Z[1] - Z[0]) + o01 * (Z[2] - Z[0]));
        const N A = oriented(A2);
        t = kAnd(t, isNonNeg(K::sign((H - Z[0]) * A - w)));
        if (t != Tri::kFalse)
          t = kAnd(t, isNonNeg(K::sign((H + Z[0]) * A + w)));
      }
      if (add(t, kTestA)) return done();
    }
  }

  // (B) The chord of the triangle in each cap plane Z = s H, tested against
  // the cap disk through its interior closest point (its endpoints are (V)
  // or (X) points). Chord endpoints, homogeneous with W > 0: a vertex with
  // a_k = 0 gives (x_k, y_k, 1); an edge with a_i < 0 < a_j gives
  // (x_i a_j - x_j a_i, y_i a_j - y_j a_i, a_j - a_i). With all three a_k = 0
  // the triangle lies in the plane and (V), (E), (A) are complete.
  for (int s = 0; s < 2; ++s) {
    if (skip(kTestB + s)) continue;
    const Sign* sa = s == 0 ? top : bot;
    if (sa[0] == Sign::kUnknown || sa[1] == Sign::kUnknown ||
        sa[2] == Sign::kUnknown) {
      // The chord's shape is undecided.
      if (add(Tri::kUnknown, kTestB + s)) return done();
      continue;
    }
    N X[3], Y[3], W[3];
    int n = 0;
    for (int k = 0; k < 3; ++k) {
      if (sa[k] == Sign::kZero) {
        X[n] = x[k];
        Y[n] = y[k];
        W[n] = K::lift(1.0);
        ++n;
      }
    }
    if (n == 3) continue;  // triangle in the cap plane
    for (const auto& e : kEdge) {
      int i = e[0], j = e[1];
      const bool cross = (sa[i] == Sign::kNeg && sa[j] == Sign::kPos) ||
                         (sa[i] == Sign::kPos && sa[j] == Sign::kNeg);
      if (!cross) continue;
      if (sa[i] == Sign::kPos) std::swap(i, j);  // now a_i < 0 < a_j
      const N ai = s == 0 ? N(Z[i] - H) : N(Z[i] + H);
      const N aj = s == 0 ? N(Z[j] - H) : N(Z[j] + H);
      X[n] = x[i] * aj - x[j] * ai;
      Y[n] = y[i] * aj - y[j] * ai;
      W[n] = aj - ai;
      ++n;
    }
    if (n != 2) continue;  // no chord, or a single touching vertex
    if (add(chordWithinR<K>(X[0], Y[0], W[0], X[1], Y[1], W[1], r2),
            kTestB + s))
      return done();
  }

  return any.result();
}

}  // namespace tricyl::detail
