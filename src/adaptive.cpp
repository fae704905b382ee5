// SPDX-License-Identifier: BSD-3-Clause
// The escalation of one sign (src/adaptive.h): double-word with a running
// error bound, then stack expansions, then GMP.
#include "adaptive.h"

#include <cmath>

#if defined(__GNUC__) || defined(__clang__)
#define TRICYL_EFT_INLINE inline __attribute__((always_inline))
#else
#define TRICYL_EFT_INLINE inline
#endif

namespace tricyl::detail {

// ---------------------------------------------------------------------------
// Stage 1: double-word values with a running error bound (DwRun).
//
// Each node carries a double-word value v (normalised: |v.lo| <=
// ulp(v.hi) / 2) and a bound e >= |v - E| on its distance to the exact
// value E of the node's expression. Rules (src/eft.h for the constants):
//   input x:               v = x, e = 0.
//   input difference a-b:  v = TwoSum(a, -b), exact: e = 0 (no overflow
//                          under the range gate).
//   a +- b:  v = dwAdd(a, +-b),
//            e = e_a + e_b + kDwAddRel (|a.hi| + |b.hi|);
//   a * b:   v = dwMul(a, b),
//            e = |a| e_b + |b| e_a + e_a e_b + kDwRel |v.hi| + kDwTiny,
//            with |a| = |a.hi| + |a.lo|,
//   since |v_a v_b - A B| <= |v_a| |v_b - B| + |B| |v_a - A| and
//   |B| <= |v_b| + e_b; kDwAddRel (...) and kDwRel |v.hi| bound the
//   double-word operations' own errors (src/eft.h) and kDwTiny the
//   product's losses to underflow.
//   local coordinate sum_k R_kj (p_k - t_k): one straight-line
//   evaluation with an a-priori bound (dwCoord below).
// e itself is computed with rounding to nearest from non-negative terms, at
// most 5 roundings per operation: over the deepest chain (depth <= 56 as
// for FilterKernel) it falls short of the exact bound by at most a factor
// (1 - u)^280 > 1 - 2^-44, and by absolute underflow losses of at most
// 2^-1075 per rounding, which the products of later operations multiply by
// at most the a-priori magnitudes (<= 2^380 under the range gate,
// docs/exactness.md "Underflow"): below 2^-680 in all. The sign test covers
// both: with b = (e + |v.lo|) (1 + 2^-40) + 2^-600, hi > b gives
// E >= hi - |lo| - e_true > 0, and symmetrically.

// A local coordinate: dwCoordinate (src/dw_kernel.h) on the point's
// exact differences; Z = 2 z: the same, doubled.
template <bool kFma>
DwRun Tape::dwCoord(const Node& nd) const {
  const Point& P = pts_[nd.a];
  const int j = nd.b;
  double D[3], l[3];
  for (int k = 0; k < 3; ++k) twoSum(P.p[k], -P.t[k], D[k], l[k]);
  const double R[3] = {P.R[0][j], P.R[1][j], P.R[2][j]};
  DwRun r = dwCoordinate<kFma>(R, D, l);
  if (j == 2) {  // Z = 2 z: exact scaling, bound doubled
    r.v.hi *= 2;
    r.v.lo *= 2;
    r.e *= 2;
  }
  return r;
}

// Node `id`'s double-word value, into dw_[id] (not memoised yet). Its
// operands are looked up in the memo first, so that a memoised operand
// (about half of them) costs no call; the recursion returns nothing and
// the values are read from dw_ in place.
template <bool kFma>
TRICYL_EFT_INLINE void Tape::dwNode(std::uint32_t id) {
  auto get = [this](std::uint32_t c) -> const DwRun& {
    if ((memo_[c >> 6] >> (c & 63) & 1) == 0) {
      if constexpr (kFma)
        dwFma(c);
      else
        dwPlain(c);
    }
    return dw_[c];
  };
  const Node nd = nodes_[id];
  DwRun r;
  switch (nd.code) {
    case kLift:
      r = {{la_[nd.a], 0.0}, 0.0};
      break;
    case kDiff:
      twoSum(la_[nd.a], -lb_[nd.a], r.v.hi, r.v.lo);
      r.e = 0;
      break;
    case kCoord:
      r = accurate_ ? dwCoordAccurate(nd) : dwCoord<kFma>(nd);
      break;
    case kNeg: {
      const DwRun& a = get(nd.a);
      r = {dwNeg(a.v), a.e};
      break;
    }
    case kAdd: {
      const DwRun& a = get(nd.a);
      const DwRun& b = get(nd.b);
      r = dwRunAdd(a, b);
      break;
    }
    case kSub: {
      const DwRun& a = get(nd.a);
      DwRun b = get(nd.b);
      b.v = dwNeg(b.v);
      r = dwRunAdd(a, b);
      break;
    }
    default: {  // kMul
      const DwRun& a = get(nd.a);
      const DwRun& b = get(nd.b);
      r = dwRunMul<kFma>(a, b);
      break;
    }
  }
  dw_[id] = r;
  memo_[id >> 6] |= std::uint64_t(1) << (id & 63);
}

void Tape::dwPlain(std::uint32_t id) { dwNode<TRICYL_HAVE_FMA != 0>(id); }

#if TRICYL_FMA_DISPATCH
// The same evaluation compiled for FMA (dwNode, dwCoord, dwRunMul and the
// double-word operations inline into it), for CPUs that have it
// (fmaAtRunTime, src/eft.h): the same bits.
__attribute__((target("fma"))) void Tape::dwFma(std::uint32_t id) {
  dwNode<true>(id);
}
#else
void Tape::dwFma(std::uint32_t id) { dwPlain(id); }
#endif

DwRun Tape::dw(std::uint32_t id) {
  if ((memo_[id >> 6] >> (id & 63) & 1) == 0) {
#if TRICYL_FMA_DISPATCH
    if (fmaAtRunTime())
      dwFma(id);
    else
#endif
      dwPlain(id);
  }
  return dw_[id];
}

// A local coordinate to within 2^-104 or so of ITS OWN magnitude, where
// dwCoord's bound is 2^-100 of the terms' magnitude M: its exact value as
// an expansion (expansionCoord, below), compressed, rounded to a double
// word with a bound (dwFromExpansion, src/dw_kernel.h). For needles and
// discs, whose local coordinates are far smaller than the terms they cancel
// from, this is what decides a near tie that dwCoord's absolute bound leaves
// to the expansions. An expansion that cannot be formed (src/expansion.h)
// keeps dwCoord's value.
DwRun Tape::dwCoordAccurate(const Node& nd) const {
  const Expansion x = expansionCoord(nd).compressed();
  if (!x.ok()) return dwCoord<false>(nd);
  return dwFromExpansion(x);
}

// ---------------------------------------------------------------------------
// Stage 2: the exact value as a stack expansion (src/expansion.h), which
// flags the cases it cannot compute exactly. It runs only for signs that
// are zero or within about 2^-100 of zero relative to their magnitudes,
// i.e. (almost) only for true ties, which usually come several to a query
// (a triangle in a cap plane: every slab sign, chord and area term) and
// share coordinates and sub-expressions: memoised per node in the tape's
// arena.
Expansion Tape::expansionCoord(const Node& nd) const {
  const Point& P = pts_[nd.a];
  const int j = nd.b;
  Expansion x;
  for (int k = 0; k < 3; ++k)
    x = x + Expansion(P.R[k][j]) * Expansion::difference(P.p[k], P.t[k]);
  return j == 2 ? x + x : x;
}

Expansion Tape::expansion(std::uint32_t id) {
  std::uint64_t& word = xmemo_[id >> 6];
  const std::uint64_t bit = std::uint64_t(1) << (id & 63);
  if (word & bit)
    return Expansion::fromComponents(arena_ + xoff_[id], xlen_[id]);
  const Node nd = nodes_[id];
  Expansion r;
  switch (nd.code) {
    case kLift:
      return Expansion(la_[nd.a]);
    case kDiff:
      return Expansion::difference(la_[nd.a], lb_[nd.a]);
    case kCoord:
      r = expansionCoord(nd);
      break;
    case kNeg:
      r = -expansion(nd.a);
      break;
    case kAdd:
      r = expansion(nd.a) + expansion(nd.b);
      break;
    case kSub:
      r = expansion(nd.a) - expansion(nd.b);
      break;
    default: {
      const Expansion a = expansion(nd.a);
      if (!a.ok()) return a;
      r = nd.b == nd.a ? a * a : a * expansion(nd.b);
      break;
    }
  }
  if (r.ok() && arena_used_ + r.size() <= kArena) {
    for (int i = 0; i < r.size(); ++i) arena_[arena_used_ + i] = r.data()[i];
    xoff_[id] = std::uint16_t(arena_used_);
    xlen_[id] = std::uint16_t(r.size());
    arena_used_ += r.size();
    word |= bit;
  }
  return r;
}

// Before the expansions, for a sign whose double value is exactly 0: was
// the double evaluation itself exact? In exact poses with exact data (signed
// permutations, dyadic or decimal coordinates that cancel exactly) it often
// is, and then the value is the exact value. Each operation is re-done in
// double and checked: a sum by its TwoSum error being 0 (and finite), a
// product by its TwoProduct error being 0 with the product at least
// kProdExactMin (so that the error term is itself exact), or by an exact 0
// factor (then the product is an exact 0 whatever the other factor is). The
// operations and their order are those of the adaptive run, so the value
// found is that run's value.
bool Tape::exactInDouble(std::uint32_t id, double* value) {
  // Memoised per node: the signs of one tie share their sub-DAGs.
  const std::uint64_t bit = std::uint64_t(1) << (id & 63);
  std::uint64_t& done = edone_[id >> 6];
  std::uint64_t& ok = eok_[id >> 6];
  if (done & bit) {
    *value = ev_[id];
    return (ok & bit) != 0;
  }
  const bool exact = exactInDoubleNode(id, value);
  done |= bit;
  if (exact) {
    ok |= bit;
    ev_[id] = *value;
  } else {
    ok &= ~bit;
  }
  return exact;
}

bool Tape::exactInDoubleNode(std::uint32_t id, double* value) {
  const Node nd = nodes_[id];
  auto sumOk = [](double a, double b, double* out) {
    double s, e;
    twoSum(a, b, s, e);
    *out = s;
    return e == 0 && std::isfinite(s);
  };
  auto prodOk = [](double a, double b, double* out) {
    if (a == 0 || b == 0) {
      *out = a * b;
      return true;
    }
    double p, e;
    twoProd(a, b, p, e);
    *out = p;
    return e == 0 && std::fabs(p) >= kProdExactMin && std::isfinite(p);
  };
  switch (nd.code) {
    case kLift:
      *value = la_[nd.a];
      return true;
    case kDiff:
      return sumOk(la_[nd.a], -lb_[nd.a], value);
    case kCoord: {
      const Point& P = pts_[nd.a];
      const int j = nd.b;
      double t[3];
      for (int k = 0; k < 3; ++k) {
        double d;
        if (P.R[k][j] == 0) {
          t[k] = 0;  // an exact zero factor
          continue;
        }
        if (!sumOk(P.p[k], -P.t[k], &d) || !prodOk(P.R[k][j], d, &t[k]))
          return false;
      }
      double s1, v;
      if (!sumOk(t[0], t[1], &s1) || !sumOk(s1, t[2], &v)) return false;
      *value = j == 2 ? v + v : v;
      return std::isfinite(*value);
    }
    case kNeg: {
      if (!exactInDouble(nd.a, value)) return false;
      *value = -*value;
      return true;
    }
    case kAdd:
    case kSub: {
      double a, b;
      if (!exactInDouble(nd.a, &a) || !exactInDouble(nd.b, &b)) return false;
      return sumOk(a, nd.code == kSub ? -b : b, value);
    }
    default: {  // kMul
      double a, b;
      const bool ea = exactInDouble(nd.a, &a);
      if (ea && a == 0) {
        *value = 0;
        return true;
      }
      if (!exactInDouble(nd.b, &b)) return false;
      if (b == 0) {
        *value = 0;
        return true;
      }
      return ea && prodOk(a, b, value);
    }
  }
}

// Stage 3: GMP dyadic rationals (ExactKernel), exact for every finite input.
Dyadic Tape::dyadicCoord(const Node& nd) const {
  const Point& P = pts_[nd.a];
  const int j = nd.b;
  Dyadic x;
  for (int k = 0; k < 3; ++k)
    x = x +
        ExactKernel::lift(P.R[k][j]) * ExactKernel::inputDiff(P.p[k], P.t[k]);
  return j == 2 ? x + x : x;
}

Dyadic Tape::dyadic(std::uint32_t id) const {
  const Node nd = nodes_[id];
  switch (nd.code) {
    case kLift:
      return ExactKernel::lift(la_[nd.a]);
    case kDiff:
      return ExactKernel::inputDiff(la_[nd.a], lb_[nd.a]);
    case kCoord:
      return dyadicCoord(nd);
    case kNeg:
      return -dyadic(nd.a);
    case kAdd:
      return dyadic(nd.a) + dyadic(nd.b);
    case kSub:
      return dyadic(nd.a) - dyadic(nd.b);
    default:
      return dyadic(nd.a) * dyadic(nd.b);
  }
}

// ---------------------------------------------------------------------------

std::uint32_t Tape::addPoint(const Pose<double>& pose, const Vec3<double>& p) {
  if (points_ == kMaxPoints) {
    overflow_ = true;
    return 0;
  }
  Point& P = pts_[points_];
  P.p[0] = p.x;
  P.p[1] = p.y;
  P.p[2] = p.z;
  P.t[0] = pose.t.x;
  P.t[1] = pose.t.y;
  P.t[2] = pose.t.z;
  P.R = pose.R;
  return std::uint32_t(points_++);
}

void Tape::toLocal(const Pose<double>& pose, const Vec3<double>& p, An& x,
                   An& y, An& Z) {
  // The double values of the generic toLocal: d_k = fl(p_k - t_k), then
  // ((R_0j d_0 + R_1j d_1) + R_2j d_2), and the folded running bound of
  // toLocalRunning (src/triangle_cylinder_impl.h, derived there) from
  // S = sum_k |R_kj| |d_k|.
  const double d0 = p.x - pose.t.x, d1 = p.y - pose.t.y, d2 = p.z - pose.t.z;
  const double a0 = std::fabs(d0), a1 = std::fabs(d1), a2 = std::fabs(d2);
  const std::uint32_t point = addPoint(pose, p);
  auto coord = [&](int j) {
    const double r0 = pose.R[0][j], r1 = pose.R[1][j], r2 = pose.R[2][j];
    const double s1 = r0 * d0 + r1 * d1;
    const double v = s1 + r2 * d2;
    const double S =
        (std::fabs(r0) * a0 + std::fabs(r1) * a1) + std::fabs(r2) * a2;
    constexpr double c = 0x1p-53 + 0x1p-53 * 0x1p-40;
    const bool zero =
        (r0 == 0 || d0 == 0) & (r1 == 0 || d1 == 0) & (r2 == 0 || d2 == 0);
    const double m = (((S + S) + std::fabs(s1)) + std::fabs(v)) * c +
                     (zero ? 0.0 : 4 * 0x1p-1074);
    return An{v, m, this, op(kCoord, point, std::uint32_t(j))};
  };
  x = coord(0);
  y = coord(1);
  Z = coord(2);
  Z.v = Z.v + Z.v;
  Z.m = Z.m + Z.m;
}

// The bound from M. With S_j = sum_k |R_kj| |d_k| (the exact sum of the
// computed differences' terms), toLocal's derivation (toLocalRunning,
// src/triangle_cylinder_impl.h) gives
//   |x^ - x| <= u (1 + 8.5 u) (2 S_j + |s1| + |x^|) + 2 eta,
// and |s1| <= (1 + u)^2 S_j. M = fl(rho fl(fl(|d_0| + |d_1|) + |d_2|))
// >= (1 - u)^3 rho sum_k |d_k| >= (1 - u)^3 S_j, so 2 S_j + |s1| <=
// 3 (1 + 2u) S_j <= 3 (1 + 6u) M, and
//   e = fl(fl(fl(3 M) + |x^|) c) + 4 eta,   c = u (1 + 2^-40),
// covers it: the three roundings of e and every (1 + k u) factor above
// stay far inside the 2^-40 slack (coordinateBound, src/adaptive.h). An
// exact zero (every term with a zero factor) keeps e = 0, as in toLocal; it
// is checked only when x^ = 0.
void Tape::coordinates(const Pose<double>& pose, const Vec3<double>& p,
                       double x, double y, double Z, double M, An& ax, An& ay,
                       An& aZ) {
  const std::uint32_t point = addPoint(pose, p);
  auto leaf = [&](int j, double v) {
    double m = coordinateBound(M, v);
    // An exact zero? (rare: the check only then)
    if (v == 0 && exactZeroCoordinate(pose, p, j)) m = 0;
    return An{v, m, this, op(kCoord, point, std::uint32_t(j))};
  };
  ax = leaf(0, x);
  ay = leaf(1, y);
  aZ = leaf(2, Z * 0.5);
  aZ.v = Z;
  aZ.m = aZ.m + aZ.m;
}

Sign Tape::escalate(std::uint32_t id, double v) {
  if (overflow_ || abandoned_) return Sign::kZero;  // the driver discards
  // A double value that is exactly 0 may be a true tie that the double
  // arithmetic computed without rounding (an exact pose and exact data),
  // which no bound certifies: checked first, at the cost of a pass over
  // the sign's sub-DAG in double. Otherwise (and when that check fails:
  // in the aligned family most zeros are cancellations that rounded to 0,
  // with a non-zero exact value) double-word, and the exact stage only
  // for what double-word cannot decide. Any order gives the same sign.
  if (v == 0) {
    double exact = 0;
    if (exactInDouble(id, &exact)) {
      if (level_ < 2) level_ = 2;
      return exact > 0 ? Sign::kPos : (exact < 0 ? Sign::kNeg : Sign::kZero);
    }
  }
  DwRun d = dw(id);
  double b = (d.e + std::fabs(d.v.lo)) * (1 + 0x1p-40) + 0x1p-600;
  if (level_ < 1) level_ = 1;
  if (d.v.hi > b) return Sign::kPos;
  if (d.v.hi < -b) return Sign::kNeg;
  if (!accurate_) {
    // Once more with the coordinates to their own precision
    // (dwCoordAccurate), for this sign and every later one of the run:
    // the memo is cleared and refilled, and its values keep valid bounds.
    accurate_ = true;
    std::memset(memo_, 0, sizeof memo_);
    d = dw(id);
    b = (d.e + std::fabs(d.v.lo)) * (1 + 0x1p-40) + 0x1p-600;
    if (d.v.hi > b) return Sign::kPos;
    if (d.v.hi < -b) return Sign::kNeg;
  }
  const Expansion x = expansion(id);
  if (x.ok()) {
    if (level_ < 2) level_ = 2;
    const int s = x.sign();
    return s > 0 ? Sign::kPos : (s < 0 ? Sign::kNeg : Sign::kZero);
  }
  // The expansions cannot hold it (products near underflow, capacity:
  // inputs whose exponents spread over most of the double range). GMP
  // then, but for the whole query at once: the driver re-runs it with
  // ExactKernel (runAdaptive), which computes every value once, where GMP
  // per sign would re-evaluate the shared sub-DAGs of every later sign
  // (measured on random-exponent inputs inside the range gate: a worst
  // case of 0.85 ms per query that way).
  level_ = 3;
  abandoned_ = true;
  return Sign::kZero;  // the driver discards this run
}

}  // namespace tricyl::detail
