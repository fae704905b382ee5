// SPDX-License-Identifier: BSD-3-Clause
// The adaptive kernel: escalate the PREDICATE, not the query.
//
// Every query of tricyl is written once over a kernel K (src/filter.h) and
// first run with FilterKernel, whose signs are certified by an a-priori
// error bound or come back kUnknown. Where one comes back kUnknown, the
// driver (runStages, src/stages.h) runs the query once more with
// AdaptiveKernel below, and that run never meets kUnknown: each sign is
// tried in double first, with a RUNNING error bound (RunningDoubleKernel's
// rules, src/filter.h: the same double values as FilterKernel's, a bound
// that follows the values instead of the magnitudes, so it also certifies
// what cancellation made the magnitude bound give up on), and only a sign
// that bound cannot certify is re-decided, by itself, in stronger
// arithmetic:
//   1. double-word arithmetic (about 106 bits, src/eft.h) with a running
//      error bound (src/adaptive.cpp);
//   2. exact floating-point expansions on the stack (src/expansion.h);
//   3. GMP dyadic rationals (ExactKernel), only where the expansions give
//      up (products near underflow, capacity).
// All of it runs only for inputs inside the range gate (rangeGateOk:
// lengths <= 2^40, rotation entries <= 2), where the double bounds hold
// and nothing overflows; the driver decides other inputs with GMP
// alone (src/stages.h).
// The control flow of the query continues in double with the certified
// sign. This is the shape of CGAL's Filtered_predicate and of Shewchuk's
// adaptive predicates (only the expression that failed is evaluated more
// exactly), applied to every sign of a query rather than to a whole
// predicate function.
//
// How one sign is re-decided without re-running the query: every value of
// the adaptive run carries, besides its double value and running error
// bound, the index of a node in a Tape, the record of how it was
// computed (an input, a difference of two inputs, +, -, negation, *). The
// record costs one small store per operation; a stronger arithmetic
// evaluates only the sub-DAG below the sign that failed, and the
// double-word values are memoised per node, so the local frame of a query
// (the leaves' sub-DAGs) is computed in double-word at most once, and only
// when first needed.
#pragma once

#include <cstdint>
#include <cstring>

#include "dw_kernel.h"
#include "eft.h"
#include "expansion.h"
#include "filter.h"
#include "tricyl/types.h"

#if defined(__GNUC__) || defined(__clang__)
#define TRICYL_ADAPTIVE_NOINLINE __attribute__((noinline, cold))
#else
#define TRICYL_ADAPTIVE_NOINLINE
#endif

namespace tricyl::detail {

class Tape;

/// A value of the adaptive run: the double value v (computed by the same
/// operations as FilterKernel's), a running bound m >= |v - E| (the rules of
/// RunningDoubleKernel, src/filter.h), and the node that records how it was
/// computed.
struct An {
  double v;
  double m;  // the running error bound e of Rd
  Tape* tape;
  std::uint32_t id;
};

/// The running bound of a local coordinate's double value v from the
/// fast path's per-vertex magnitude M (derived in src/adaptive.cpp, at
/// Tape::coordinates); for Z = 2 z, call it with v = z and double it.
inline double coordinateBound(double M, double v) {
  constexpr double c = 0x1p-53 + 0x1p-53 * 0x1p-40;
  return (3 * M + std::fabs(v)) * c + 4 * 0x1p-1074;
}
/// Whether coordinate j of p is an exact 0 with nothing rounded: every term
/// R_kj (p_k - t_k) has a zero factor (then its bound may be 0).
inline bool exactZeroCoordinate(const Pose<double>& pose, const Vec3<double>& p,
                                int j) {
  const double d[3] = {p.x - pose.t.x, p.y - pose.t.y, p.z - pose.t.z};
  bool zero = true;
  for (int k = 0; k < 3; ++k) zero = zero && (pose.R[k][j] == 0 || d[k] == 0);
  return zero;
}

class Tape {
 public:
  /// Nodes of one query's run. The largest query, the triangle kernel,
  /// records fewer than 500 (tests/adaptive_stage_test.cpp measures the
  /// maximum over every family); a run that would need more is flagged and
  /// the driver decides the query with ExactKernel alone.
  static constexpr int kMaxNodes = 1024;
  static constexpr int kMaxLeaves = 512;
  /// Points mapped to the local frame (the triangle: 3; a segment: 3).
  static constexpr int kMaxPoints = 8;

  /// For inputs that passed rangeGateOk only: the double bounds and the
  /// double-word stage's absolute slack rest on it, and under it nothing
  /// overflows (magnitudes <= 2^380, docs/exactness.md).
  Tape() {
    // Fixed-size clears (a few vector stores; a loop here became two
    // `rep stos`, a third of the cost of setting up a run).
    std::memset(memo_, 0, sizeof memo_);
    std::memset(xmemo_, 0, sizeof xmemo_);
    std::memset(edone_, 0, sizeof edone_);
  }
  Tape(const Tape&) = delete;
  Tape& operator=(const Tape&) = delete;

  /// Whether the driver must decide the query otherwise (with ExactKernel):
  /// the tape overflowed, or a sign needed GMP (escalate).
  bool overflowed() const { return overflow_ || abandoned_; }
  int size() const { return n_; }
  /// The strongest arithmetic any sign needed: 0 filter, 1 double-word,
  /// 2 expansions, 3 GMP.
  int level() const { return level_; }

  std::uint32_t op(std::uint16_t code, std::uint32_t a, std::uint32_t b) {
    if (n_ == kMaxNodes) {
      overflow_ = true;
      return 0;
    }
    nodes_[n_] = {code, std::uint16_t(a), std::uint16_t(b)};
    return std::uint32_t(n_++);
  }
  std::uint32_t leaf(std::uint16_t code, double a, double b) {
    if (leaves_ == kMaxLeaves) {
      overflow_ = true;
      return 0;
    }
    la_[leaves_] = a;
    lb_[leaves_] = b;
    return op(code, std::uint32_t(leaves_++), 0);
  }

  /// The local coordinates of p (y = R^T (p - t), z doubled: Z = 2 z), as
  /// three leaves whose stronger values are computed only when a sign
  /// needs them (one straight-line evaluation each, not a sub-DAG of 11
  /// nodes); `x`, `y`, `Z` get the double values and magnitudes exactly as
  /// the generic toLocal<K> computes them, and the running bound of
  /// toLocalRunning (src/triangle_cylinder_impl.h) for each.
  void toLocal(const Pose<double>& pose, const Vec3<double>& p, An& x, An& y,
               An& Z);

  /// As toLocal, from double values the caller already computed exactly as
  /// toLocal does (x, y and Z = 2 z: the scalar fast path's), with `M` >=
  /// rho (|d_0| + |d_1| + |d_2|) rounded as that path rounds it (rho >=
  /// every |R_jk|, d_k = fl(p_k - t_k)). The running bound is then derived
  /// from M (src/adaptive.cpp) instead of per-coordinate sums.
  void coordinates(const Pose<double>& pose, const Vec3<double>& p, double x,
                   double y, double Z, double M, An& ax, An& ay, An& aZ);

  /// The sign of node `id`, which the running double bound could not
  /// certify.
  /// `v`: its double value.
  TRICYL_ADAPTIVE_NOINLINE Sign escalate(std::uint32_t id, double v);

  enum Code : std::uint16_t { kLift, kDiff, kAdd, kSub, kNeg, kMul, kCoord };

  /// For tests: node `id`'s double-word value and error bound, and its
  /// exact value.
  void doubleWord(std::uint32_t id, DW* v, double* e) {
    const DwRun d = dw(id);
    *v = d.v;
    *e = d.e;
  }
  Dyadic exact(std::uint32_t id) const { return dyadic(id); }
  /// For tests: double-word values from here on with the coordinates to
  /// their own precision (dwCoordAccurate), as escalate switches to.
  void useAccurateCoordinates() {
    accurate_ = true;
    std::memset(memo_, 0, sizeof memo_);
  }

 private:
  // No member of a character type: a store through one may alias anything,
  // and would make every recorded operation reload the tape's counters.
  struct Node {
    std::uint16_t code;
    std::uint16_t a, b;  // operands; a leaf's index; a coordinate's point
                         // and axis (b: 0 x, 1 y, 2 Z)
  };
  /// A point's data for its coordinate leaves: p, t and R (the pose's own
  /// rotation: the pose outlives the run, which is one call of the query).
  struct Point {
    double p[3], t[3];
    const double (*R)[3];
  };
  // Double-word values: dw dispatches once per escalation to dwFma (x86-64
  // CPUs with FMA, in builds that do not assume it) or dwPlain; both run
  // dwNode, whose TwoProducts are exact either way: the same bits.
  /// Records a point for coordinate leaves (its index; overflow flagged).
  std::uint32_t addPoint(const Pose<double>& pose, const Vec3<double>& p);
  DwRun dw(std::uint32_t id);
  void dwPlain(std::uint32_t id);
  void dwFma(std::uint32_t id);
  template <bool kFma>
  void dwNode(std::uint32_t id);
  template <bool kFma>
  DwRun dwCoord(const Node& nd) const;
  DwRun dwCoordAccurate(const Node& nd) const;
  Expansion expansionCoord(const Node& nd) const;
  Dyadic dyadicCoord(const Node& nd) const;
  Expansion expansion(std::uint32_t id);
  bool exactInDouble(std::uint32_t id, double* value);
  bool exactInDoubleNode(std::uint32_t id, double* value);
  Dyadic dyadic(std::uint32_t id) const;

  bool overflow_ = false;
  bool abandoned_ = false;
  // Coordinates to their own precision (dwCoordAccurate): set by the first
  // sign that the plain double-word values could not decide.
  bool accurate_ = false;
  int level_ = 0;
  int n_ = 0;
  int leaves_ = 0;
  Node nodes_[kMaxNodes];
  double la_[kMaxLeaves], lb_[kMaxLeaves];
  int points_ = 0;
  Point pts_[kMaxPoints];
  std::uint64_t memo_[kMaxNodes / 64];
  DwRun dw_[kMaxNodes];
  // exactInDouble's memo: checked (edone_), and if so whether the double
  // value was exact (eok_) and that value (ev_).
  std::uint64_t edone_[kMaxNodes / 64], eok_[kMaxNodes / 64];
  double ev_[kMaxNodes];
  // The exact stage's memo: node -> its expansion's components in arena_
  // (a true tie usually needs several signs of the same coordinates and
  // sub-expressions). Nodes whose expansion does not fit are not memoised.
  static constexpr int kArena = 2048;
  std::uint64_t xmemo_[kMaxNodes / 64];
  std::uint16_t xoff_[kMaxNodes], xlen_[kMaxNodes];
  int arena_used_ = 0;
  double arena_[kArena];
};

/// The tape of the adaptive run in progress on this thread (set by the
/// driver for the duration of one run; nested runs restore it).
inline thread_local Tape* tls_tape = nullptr;

class TapeScope {
 public:
  explicit TapeScope(Tape* t) : prev_(tls_tape) { tls_tape = t; }
  ~TapeScope() { tls_tape = prev_; }
  TapeScope(const TapeScope&) = delete;
  TapeScope& operator=(const TapeScope&) = delete;

 private:
  Tape* prev_;
};

inline An operator+(const An& a, const An& b) {
  const double v = a.v + b.v;
  return {v, a.m + b.m + kU1d * std::fabs(v), a.tape,
          a.tape->op(Tape::kAdd, a.id, b.id)};
}
inline An operator-(const An& a, const An& b) {
  const double v = a.v - b.v;
  return {v, a.m + b.m + kU1d * std::fabs(v), a.tape,
          a.tape->op(Tape::kSub, a.id, b.id)};
}
inline An operator-(const An& a) {
  return {-a.v, a.m, a.tape, a.tape->op(Tape::kNeg, a.id, 0)};
}
inline An operator*(const An& a, const An& b) {
  const double v = a.v * b.v;
  return {v,
          std::fabs(a.v) * b.m + std::fabs(b.v) * a.m + a.m * b.m +
              kU1d * std::fabs(v) + 0x1p-1074,
          a.tape, a.tape->op(Tape::kMul, a.id, b.id)};
}

struct AdaptiveKernel {
  using Num = An;
  static constexpr bool kExact = false;
  static Num lift(double x) {
    Tape* t = tls_tape;
    return {x, 0.0, t, t->leaf(Tape::kLift, x, 0)};
  }
  /// The input difference: value fl(a - b) with bound u' |fl(a - b)|,
  /// recorded as one exact leaf.
  static Num inputDiff(double a, double b) {
    Tape* t = tls_tape;
    const double d = a - b;
    return {d, kU1d * std::fabs(d), t, t->leaf(Tape::kDiff, a, b)};
  }
  static Sign sign(const Num& a) {
    const Sign s = RunningDoubleKernel::sign(Rd{a.v, a.m});
    if (s != Sign::kUnknown) return s;
    return a.tape->escalate(a.id, a.v);
  }
};

/// The stage a run of the adaptive kernel reached, as reported in Decision.
inline Stage stageOfLevel(int level) {
  switch (level) {
    case 0:
      return Stage::kFastPath;
    case 1:
      return Stage::kExtended;
    case 2:
      return Stage::kExact;
    default:
      return Stage::kExactGmp;
  }
}

}  // namespace tricyl::detail
