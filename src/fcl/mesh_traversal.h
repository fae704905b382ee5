// SPDX-License-Identifier: BSD-3-Clause
// The pieces shared by tricyl's own BVHModel/Cylinder traversals
// (fcl_mesh_cylinder.h): tricyl::collide's (mesh_collide.cpp, with or without
// a margin) and tricyl::distance's (mesh_distance.cpp). A certified node test
// and a certified lower bound of a node's distance to the cylinder, the box
// of every FCL BV type, the validation and set-up common to both. Internal:
// not installed, not part of the interface.
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/math/bv/AABB.h>
#include <fcl/math/bv/OBB.h>
#include <fcl/math/bv/OBBRSS.h>
#include <fcl/math/bv/RSS.h>
#include <fcl/math/bv/kDOP.h>
#include <fcl/math/bv/kIOS.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace tricyl {
namespace traversal {

using V3 = fcl::Vector3d;
using Tf = fcl::Transform3d;

// ---------------------------------------------------------------------------
// THE NODE TEST AND ITS MARGIN
//
// A node is skipped when one of these separating tests holds for its box
// (centre b, axes a_i, half extents e_i) and the cylinder moved into the mesh
// frame (centre c, unit axis u, radius r, half length h), with d = b - c:
//   (A) |u.d|   > h + sum_i e_i |u.a_i|                       (cylinder axis)
//   (B) |a_i.d| > e_i + h |a_i.u| + r |a_i x u|               (box axis i)
//   (C) |d - (u.d) u| > r + |e|                               (axis line)
// In exact arithmetic with orthonormal rotations and boxes that contain
// their triangles, each right-hand side is the sum of the two supports along
// that direction (for (C): the cylinder lies within r of its axis line and
// the box within |e| of b), so a skipped node holds no point of the
// cylinder. What the computed test departs from that by, and the margin m
// added to every right-hand side:
// 1. Rounding in c, u (R_m^T (t_c - t_m), R_m^T R_c e_z), in the tests
//    themselves, in FCL's box fit (centres, extents, unit axes), in the
//    world vertices tf_m * v the leaf test sees, and in the box
//    conversions below: each a few units in the last place (u = 2^-53) of
//    the magnitudes involved, all bounded by
//      L = |b|_1 + sum e + |c|_1 + |t_m|_1 + |t_c|_1 + r + h.
//    2^-36 L is more than 10^5 times the largest of them.
// 2. Rotations a hair off orthonormal, delta = max over R_m, R_c (and the
//    root box's axes, see traverse) of sum |R^T R - I| (required <= 2^-20,
//    else FCL's own traversal runs):
//    the contract's cylinder {x : R_c^T (x - t_c) in C} is then
//    {t_c + R_c^-T y : y in C}, and the mesh frame is R_m^-1 (x - t_m);
//    R^-T and R^-1 differ from R and R^T by at most 2 delta (delta <= 2^-20)
//    in norm, which moves every point of the sets compared by at most
//    2 delta (|x - t_m| + r + h) <= 4 delta L; u is unit to within 2 delta.
//    16 delta L covers both.
// Every right-hand side is a 1-Lipschitz function of u and of the box axes
// (times the lengths it multiplies), which is what lets errors of a few ulps
// (item 1) or of 2 delta (item 2) in them move it by as little. The radial
// term of (B) is written r |a_i x u| for that reason: for unit vectors it
// equals r sqrt(1 - (a_i.u)^2), but that form is not Lipschitz in a_i.u
// near 1, and an error epsilon there (a.u rounded to 1, or u a hair longer
// than unit) became an error r sqrt(2 epsilon): a node holding a triangle
// the tilted rim touches was skipped when a box axis lay within ~2^-26 of
// the cylinder's axis (before 2026-11, on all eight BV types;
// tests/fcl_mesh_collide_test.cpp, BoxAxisNearlyParallelToTheCylinderAxis).
// |a_i x u| is computed as sqrt(w_j^2 + w_k^2), w = (a_0.u, a_1.u, a_2.u)
// the axis in the box's frame and {i, j, k} = {0, 1, 2}: for an orthonormal
// box frame that is the length of a_i x u exactly (a_i x u = w_j (a_i x a_j)
// + w_k (a_i x a_k), two orthogonal unit vectors), and each w_j is
// computed with an absolute rounding of a few ulps of |a_j| |u|, not
// amplified. For box axes A a hair off orthonormal (A = Q (I + F), Q
// orthogonal, |F| <= delta: item 2), a_i x u and the w_j move by at most
// delta |u| against those of Q, so the two lengths differ by at most
// (1 + sqrt 2) delta |u| <= 3 delta (times r: inside item 2's 16 delta L,
// of which the moved points and the non-unit u take 6 delta L). The box
// test needs w anyway (the supports h |w_i| along a_i), so this costs two
// products and a square root, and only when the rest of (B) does not
// already decide (the cross products it replaced cost nine products).
// 3. Underflow, where "a few ulps" fails: a product or square below 2^-1022
//    is off by up to 2^-1074 absolutely, whatever its size. In the squared
//    comparisons ((C), and the sum of squares under (B)'s root) that is an
//    error of at most 2^-536 in the lengths compared (sqrt(a^2 - eps) >=
//    a - sqrt(eps)); elsewhere less. An absolute 2^-500 covers it; it is
//    nothing next to any length a mesh has (tests: ExactTouchingIsFound at
//    scales 2^-540 and 2^-560).
// So m = (2^-36 + 16 delta) L + 2^-500, evaluated per node (the |b|_1 +
// sum e part changes from node to node). NaN or Inf in a box makes m NaN or
// Inf, and no test with a NaN or an infinite right-hand side skips: such nodes
// are always visited (and their triangles reported "in collision", below).
constexpr double kRelMargin = 0x1p-36;
constexpr double kAbsMargin = 0x1p-500;
constexpr double kMaxNonOrthogonality = 0x1p-20;

/// The cylinder in the mesh frame and the per-call constants.
struct Local {
  double c[3];
  double u[3];
  double r;
  double h;
  double rel;  // 2^-36 + 16 delta
  // rel * (|c|_1 + |t_m|_1 + |t_c|_1 + r + h) + 2^-500, plus the margin
  // of a margin collide ((1 + rel) margin: see MARGIN COLLIDE below).
  double global;
  double delta;  // the departure from orthonormal (item 2), for lowerBound
  // Axis-aligned boxes: the cylinder's support along the world axes of the
  // mesh frame, h |u_i| + r |e_i x u|, and |u_i|.
  double au[3];
  double support[3];
};

/// A node's box, read in place where the BV stores it (no copy of an OBB:
/// centre, half extents and the three axes are pointers into the node).
/// Boxes that are computed (AABB, KDOP, RSS) are stored in `own`; `a` is
/// null for the axis-aligned ones. Not copyable (the pointers may point
/// into `own`).
struct Box {
  const double* b;  // centre
  const double* e;  // half extents
  const double* a;  // axis i at a + 3 i (an FCL Matrix3d's column i)
  double own[6];
  Box() = default;
  Box(const Box&) = delete;
  Box& operator=(const Box&) = delete;
  const double* axis(int i) const { return a + 3 * i; }
};

/// a > b without raising FE_INVALID on a NaN (a quiet comparison): false
/// then, so a NaN never skips a node.
inline bool gt(double a, double b) { return std::isgreater(a, b); }

/// cand when cand > g, else g (a NaN cand leaves g; a NaN g stays): the
/// larger of two gaps without a branch. Written as the ordered comparison
/// it is, which compilers turn into one maxsd on x86 (maxsd keeps its
/// second operand unless the first is greater: exactly this). Unlike gt,
/// a NaN operand raises FE_INVALID here: the bounds that use it get a NaN
/// only from arithmetic that raised it already (Inf - Inf; the traversals
/// never see non-finite boxes, prepare() hands such models to FCL).
inline double keepLarger(double g, double cand) { return cand > g ? cand : g; }

/// t clamped to [0, 1] without a branch (maxsd and minsd), for t not NaN.
inline double clampUnit(double t) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(
      _mm_min_sd(_mm_max_sd(_mm_set_sd(t), _mm_setzero_pd()), _mm_set_sd(1)));
#else
  const double lo = t > 0 ? t : 0;
  return lo < 1 ? lo : 1;
#endif
}

/// The correctly rounded square root of x >= 0 (or a quiet NaN, or +Inf:
/// then NaN or +Inf, with no FP exception). Not std::sqrt: GCC treats the node
/// test's rarely taken branches as cold and compiles std::sqrt there as a call
/// into libm (errno handling) that also spills the live registers; in the
/// bunny.obj scene of bench_fcl_collide those calls took about 4% of
/// tricyl::collide's time.
inline double sqrtNonNegative(double x) {
#if defined(__SSE2__)
  return _mm_cvtsd_f64(_mm_sqrt_sd(_mm_setzero_pd(), _mm_set_sd(x)));
#else
  return std::sqrt(x);
#endif
}

/// The terms every test of a node reads: d = b - c, the margin m of THE NODE
/// TEST AND ITS MARGIN for this box, u.d, |w_i| = |a_i.u| (the axis in the
/// box's frame; for axis-aligned boxes |u_i|) and, for oriented boxes, the
/// signed w_i and p_i = a_i.d (d in the box's frame).
struct NodeTerms {
  double d[3];
  double m;
  double ud;
  double ua[3];
  double w[3];
  double p[3];
};

template <bool kAligned, bool kMargin = true>
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline NodeTerms
nodeTerms(const Box& x, const Local& k) {
  NodeTerms n;
  const double* b = x.b;
  const double* e = x.e;
  for (int i = 0; i < 3; ++i) n.d[i] = b[i] - k.c[i];
  if constexpr (kMargin) {
    n.m = k.global + k.rel * (std::fabs(b[0]) + std::fabs(b[1]) +
                              std::fabs(b[2]) + e[0] + e[1] + e[2]);
  } else {
    n.m = 0;  // (computed by the caller only where needed: nodeMargin)
  }
  n.ud = k.u[0] * n.d[0] + k.u[1] * n.d[1] + k.u[2] * n.d[2];
  if constexpr (kAligned) {
    for (int i = 0; i < 3; ++i) n.ua[i] = k.au[i];
  } else {
#if defined(__SSE2__)
    // w_i and p_i side by side in one register: a_i0 (u_0, d_0) + a_i1
    // (u_1, d_1) + a_i2 (u_2, d_2), the same products summed in the same
    // order as the scalar form below, so the same values bit for bit (the
    // margin's item 1 is unchanged); half the multiplications and additions.
    const __m128d ud0 = _mm_set_pd(n.d[0], k.u[0]);
    const __m128d ud1 = _mm_set_pd(n.d[1], k.u[1]);
    const __m128d ud2 = _mm_set_pd(n.d[2], k.u[2]);
    for (int i = 0; i < 3; ++i) {
      const double* a = x.axis(i);
      const __m128d s =
          _mm_add_pd(_mm_add_pd(_mm_mul_pd(_mm_set1_pd(a[0]), ud0),
                                _mm_mul_pd(_mm_set1_pd(a[1]), ud1)),
                     _mm_mul_pd(_mm_set1_pd(a[2]), ud2));
      n.w[i] = _mm_cvtsd_f64(s);
      n.p[i] = _mm_cvtsd_f64(_mm_unpackhi_pd(s, s));
      n.ua[i] = std::fabs(n.w[i]);
    }
#else
    for (int i = 0; i < 3; ++i) {
      const double* a = x.axis(i);
      n.w[i] = k.u[0] * a[0] + k.u[1] * a[1] + k.u[2] * a[2];
      n.ua[i] = std::fabs(n.w[i]);
      n.p[i] = a[0] * n.d[0] + a[1] * n.d[1] + a[2] * n.d[2];
    }
#endif
  }
  return n;
}

/// |a_i x u| for an oriented box, from the axis in the box's frame (THE
/// NODE TEST AND ITS MARGIN).
inline double radialFactor(const NodeTerms& n, int i) {
  const double wj = n.w[(i + 1) % 3], wk = n.w[(i + 2) % 3];
  return sqrtNonNegative(wj * wj + wk * wk);
}

// The margin m is added last to each right-hand side (the sums are
// evaluated left to right), so each test is first made without it: rounding
// is monotone and m >= 0 (or NaN), so a right-hand side without m is at most
// the one with it, and a node the test without m does not skip, the test
// with m does not skip either. Only a test that would skip without m
// computes m and decides with the right-hand side it always had: the
// same decisions, bit for bit, without m's eight operations on the nodes
// that pass (most of a grazing walk's nodes).
inline double nodeMargin(const Box& x, const Local& k) {
  const double* b = x.b;
  const double* e = x.e;
  return k.global + k.rel * (std::fabs(b[0]) + std::fabs(b[1]) +
                             std::fabs(b[2]) + e[0] + e[1] + e[2]);
}

template <bool kAligned>
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline bool
overlaps(const Box& x, const Local& k) {
  const NodeTerms n = nodeTerms<kAligned, false>(x, k);
  const double* d = n.d;
  const double* e = x.e;
  const double ud = n.ud;
  const double* ua = n.ua;
  // (A): the cylinder's axis.
  const double sa = k.h + e[0] * ua[0] + e[1] * ua[1] + e[2] * ua[2];
  if (gt(std::fabs(ud), sa) && gt(std::fabs(ud), sa + nodeMargin(x, k)))
    return false;
  // (B): the box's axes. The radial part r |a_i x u| >= 0 is only computed
  // when the rest does not already pass.
  for (int i = 0; i < 3; ++i) {
    if constexpr (kAligned) {
      const double sb = e[i] + k.support[i];
      if (gt(std::fabs(d[i]), sb) && gt(std::fabs(d[i]), sb + nodeMargin(x, k)))
        return false;
    } else {
      const double sb = e[i] + k.h * ua[i];
      if (!gt(std::fabs(n.p[i]) - sb, 0)) continue;
      const double excess = std::fabs(n.p[i]) - (sb + nodeMargin(x, k));
      if (!gt(excess, 0)) continue;
      if (gt(excess, k.r * radialFactor(n, i))) return false;
    }
  }
  // (C): the axis line, squared on both sides (both non-negative; the
  // relative rounding of the squares is covered by m as in 1.). |e| >=
  // max e_i, so a node within r + max e_i + m passes without the root.
  const double q[3] = {d[0] - ud * k.u[0], d[1] - ud * k.u[1],
                       d[2] - ud * k.u[2]};
  const double q2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  // (max by quiet comparisons, not std::fmax, a libm call: a NaN extent
  // makes m NaN, and the node is visited either way.)
  const double e01 = gt(e[1], e[0]) ? e[1] : e[0];
  const double re = k.r + (gt(e[2], e01) ? e[2] : e01);
  // (re >= 0 for every box FCL fits: then re + m >= re >= 0.)
  if (!gt(q2, re * re) && std::isgreaterequal(re, 0)) return true;
  const double m = nodeMargin(x, k);
  const double inner = re + m;
  if (!gt(q2, inner * inner)) return true;
  const double reach =
      k.r + sqrtNonNegative(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) + m;
  return !gt(q2, reach * reach);
}

// Box conversions, one per BV type. Each gives a box containing the BV.
static_assert(!fcl::Matrix3d::IsRowMajor &&
                  sizeof(fcl::Matrix3d) == 9 * sizeof(double),
              "an FCL axis matrix is three contiguous columns");

inline void fromObb(const fcl::OBB<double>& o, Box* x) {
  x->b = o.To.data();
  x->e = o.extent.data();
  x->a = o.axis.data();  // column i, axis i, at 3 i
}

inline void fromMinMax(const double* lo, const double* hi, Box* x) {
  for (int i = 0; i < 3; ++i) {
    x->own[i] = 0.5 * (lo[i] + hi[i]);
    x->own[3 + i] = 0.5 * (hi[i] - lo[i]);
  }
  x->b = x->own;
  x->e = x->own + 3;
  x->a = nullptr;
}

template <class BV>
struct BoxOf;

template <>
struct BoxOf<fcl::AABB<double>> {
  static constexpr bool kAligned = true;
  static void get(const fcl::AABB<double>& v, Box* x) {
    fromMinMax(v.min_.data(), v.max_.data(), x);
  }
};

template <std::size_t N>
struct BoxOf<fcl::KDOP<double, N>> {
  static constexpr bool kAligned = true;
  // The first three of the N/2 directions are the coordinate axes; the
  // minima are dist(0..2), the maxima dist(N/2 + 0..2) (FCL's kDOP.h).
  static void get(const fcl::KDOP<double, N>& v, Box* x) {
    const double lo[3] = {v.dist(0), v.dist(1), v.dist(2)};
    const double hi[3] = {v.dist(N / 2), v.dist(N / 2 + 1), v.dist(N / 2 + 2)};
    fromMinMax(lo, hi, x);
  }
};

template <>
struct BoxOf<fcl::OBB<double>> {
  static constexpr bool kAligned = false;
  static void get(const fcl::OBB<double>& v, Box* x) { fromObb(v, x); }
};

template <>
struct BoxOf<fcl::OBBRSS<double>> {
  static constexpr bool kAligned = false;
  static void get(const fcl::OBBRSS<double>& v, Box* x) { fromObb(v.obb, x); }
};

template <>
struct BoxOf<fcl::kIOS<double>> {
  static constexpr bool kAligned = false;
  static void get(const fcl::kIOS<double>& v, Box* x) { fromObb(v.obb, x); }
};

template <>
struct BoxOf<fcl::RSS<double>> {
  static constexpr bool kAligned = false;
  // FCL's RSS: a rectangle with one corner at To, sides l[0] along axis
  // column 0 and l[1] along column 1, swept by a sphere of radius r. Its box:
  // centre To + (l0/2) a0 + (l1/2) a1, half extents (l0/2 + r, l1/2 + r, r).
  static void get(const fcl::RSS<double>& v, Box* x) {
    const double h0 = 0.5 * v.l[0], h1 = 0.5 * v.l[1];
    for (int i = 0; i < 3; ++i)
      x->own[i] = v.To[i] + h0 * v.axis(i, 0) + h1 * v.axis(i, 1);
    x->own[3] = h0 + v.r;
    x->own[4] = h1 + v.r;
    x->own[5] = v.r;
    x->b = x->own;
    x->e = x->own + 3;
    x->a = v.axis.data();
  }
};

/// sum |A^T A - I| over the nine entries, for the 3x3 matrix whose column i
/// is a + 3 i (an FCL Matrix3d's storage); NaN for a non-finite A. A^T A is
/// symmetric, its entries computed the same way either side of the diagonal
/// (the same products, summed in the same order): the three off-diagonal
/// ones are computed once and counted twice.
inline double gramDeparture(const double* a) {
  const auto dot = [a](int i, int j) {
    const double* x = a + 3 * i;
    const double* y = a + 3 * j;
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
  };
  const double diag = std::fabs(dot(0, 0) - 1) + std::fabs(dot(1, 1) - 1) +
                      std::fabs(dot(2, 2) - 1);
  const double off =
      std::fabs(dot(0, 1)) + std::fabs(dot(0, 2)) + std::fabs(dot(1, 2));
  return diag + 2 * off;
}

/// sum |R^T R - I| over the nine entries; NaN for a non-finite R.
inline double nonOrthogonality(const fcl::Matrix3d& R) {
  return gramDeparture(R.data());
}

inline bool finiteVector(const V3& v) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

inline bool exactIdentity(const Tf& tf) {
  const auto& M = tf.matrix();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      if (!(M(i, j) == (i == j ? 1.0 : 0.0))) return false;
  return true;
}

inline double norm1(const V3& v) {
  return std::fabs(v[0]) + std::fabs(v[1]) + std::fabs(v[2]);
}

// FCL 0.7's BVNodeBase accessors and fcl::Triangle::operator[] are
// out-of-line functions of libfcl: a call through the PLT for every node and
// vertex index (about 6 % of tricyl::collide on bunny.obj). These read the
// same data directly: BV_node_base.h documents first_child (>= 0: the first
// of the two adjacent children, < 0: -(primitive index + 1)), and an
// fcl::Triangle is its three vertex indices, read through its object
// representation (trivially copyable). MeshCollideTest checks the contacts
// against FCL's own traversal for every BV type.
inline bool isLeaf(const fcl::BVNodeBase& n) { return n.first_child < 0; }
inline int leftChild(const fcl::BVNodeBase& n) { return n.first_child; }
inline int rightChild(const fcl::BVNodeBase& n) { return n.first_child + 1; }
inline int primitiveId(const fcl::BVNodeBase& n) {
  return -(n.first_child + 1);
}

static_assert(std::is_trivially_copyable_v<fcl::Triangle> &&
              sizeof(fcl::Triangle) == 3 * sizeof(std::size_t));
inline void vertexIds(const fcl::Triangle& t, std::size_t ids[3]) {
  std::memcpy(ids, &t, sizeof(fcl::Triangle));
}

/// Asks for the part of a node the node test reads (the traversal is a
/// chain of dependent loads through a tree far larger than the cache).
template <class BV>
void prefetchNode(const fcl::BVNode<BV>& node) {
#if defined(__GNUC__) || defined(__clang__)
  const char* p = reinterpret_cast<const char*>(&node);
  constexpr std::size_t kBytes = std::min<std::size_t>(sizeof(node), 192);
  for (std::size_t off = 0; off < kBytes; off += 64)
    __builtin_prefetch(p + off);
#else
  (void)node;
#endif
}

/// Asks for a triangle's vertex indices (the vertices themselves depend on
/// them).
inline void prefetchTriangle(const fcl::Triangle& t) {
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(&t);
#else
  (void)t;
#endif
}

/// A stack of T held in place up to N entries, then in a vector (moved back
/// in place when it shrinks to N): no allocation on a typical call. Its
/// entries are contiguous (data(), size()), so the distance walk keeps its
/// binary heap in one too.
template <class T, std::size_t N>
class InlineStack {
 public:
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* data() { return size_ <= N ? inline_ : spill_.data(); }
  const T* data() const { return size_ <= N ? inline_ : spill_.data(); }
  void push(const T& x) {
    if (size_ < N) {
      inline_[size_++] = x;
      return;
    }
    if (size_ == N) spill_.assign(inline_, inline_ + N);
    spill_.push_back(x);
    ++size_;
  }
  T pop() {
    --size_;
    if (size_ < N) return inline_[size_];
    const T x = spill_.back();
    spill_.pop_back();
    if (size_ == N) std::copy(spill_.begin(), spill_.end(), inline_);
    return x;
  }

 private:
  T inline_[N];
  std::size_t size_ = 0;
  std::vector<T> spill_;
};

/// The collide walk's stack (FCL's trees are rarely deeper than 64).
using NodeStack = InlineStack<int, 128>;

/// A certified lower bound of the distance between the node's box and the
/// cylinder (in the mesh frame), or a value <= 0 (or NaN) when none is
/// proved. Each separating test of `overlaps` gives one: the gap between the
/// two supports along a unit direction (tests (A), (B)), or the distance
/// from the box centre to the axis line less r and the box's circumradius
/// |e| (test (C)), is at most the distance between the sets (projection on a
/// unit direction, and distance to a line, are 1-Lipschitz). The computed
/// gaps are within m of the exact ones (THE NODE TEST AND ITS MARGIN: the
/// margin bounds the error of each computed side, not only its sign), so
/// max(gaps) - m is a lower bound. The caller converts it to the cylinder's
/// frame (lowerBoundLocal). Used with k.global holding no collide margin.
template <bool kAligned>
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline double
lowerBound(const Box& x, const Local& k) {
  const NodeTerms n = nodeTerms<kAligned>(x, k);
  const double* d = n.d;
  const double* e = x.e;
  const double m = n.m;
  const double ud = n.ud;
  const double* ua = n.ua;
  // (A)
  const double g_axis =
      std::fabs(ud) - (k.h + e[0] * ua[0] + e[1] * ua[1] + e[2] * ua[2]);
  double g = g_axis;
  // (B). Every gap computed and the largest kept without a branch (which
  // of them wins is data, and a branch on it was mispredicted about once a
  // bound); the three square roots are independent and overlap.
  for (int i = 0; i < 3; ++i) {
    if constexpr (kAligned) {
      g = keepLarger(g, std::fabs(d[i]) - (e[i] + k.support[i]));
    } else {
      const double gi = std::fabs(n.p[i]) - (e[i] + k.h * ua[i]);
      g = keepLarger(g, gi - k.r * radialFactor(n, i));
    }
  }
  // (C), with its two square roots (taken always, as (B)'s: a pre-test
  // that skipped them when they could not beat g was mispredicted as
  // often).
  //
  // (A) and (C) at once: in the cylinder's frame the cylinder is a disc
  // times an interval, so a point's distance to it is sqrt(dz^2 + dxy^2)
  // (to the slab along u, and to the infinite solid cylinder), and every
  // point of the box has dz >= the gap of (A) and dxy >= the gap of (C)
  // (its distance to the axis line is at least |q| - |e|). With each gap
  // less m (a lower bound of the exact gap, above) and both positive, the
  // root of the sum of squares is a lower bound; its rounding (relative, a
  // few ulps) is covered by the factor 1 - 2^-50 and the underflow of the
  // squares by 2^-500 (m >= 2^-500 too).
  const double q[3] = {d[0] - ud * k.u[0], d[1] - ud * k.u[1],
                       d[2] - ud * k.u[2]};
  const double q2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2];
  const double ga = g_axis - m;
  const double gcm = sqrtNonNegative(q2) - k.r -
                     sqrtNonNegative(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) -
                     m;
  const double lb = keepLarger(g - m, gcm);
  if (gt(ga, 0) && gt(gcm, 0)) {
    const double both =
        sqrtNonNegative(ga * ga + gcm * gcm) * (1 - 0x1p-50) - 0x1p-500;
    return keepLarger(lb, both);
  }
  return lb;
}

/// The mesh-frame lower bound `lb` of lowerBound as a lower bound of the
/// distance the contract measures (in the cylinder's frame, y = R_c^T (x -
/// t_c), of the world triangles tf_m * v): both maps are within delta of
/// isometries (item 2; delta <= 2^-20), so lengths shrink by at most a
/// factor (1 - delta) each; (1 - 4 delta) covers both and the rounding of
/// this product. Not positive (or NaN) stays so: nothing is pruned then.
inline double lowerBoundLocal(double lb, const Local& k) {
  return lb * (1 - 4 * k.delta - 0x1p-50);
}

// SCALE. The node test, lowerBound and the leaves' bounds compute squares
// and sums of the coordinates: beyond some size they overflow, and the
// margin's analysis (relative rounding) no longer holds. An overflowed
// square made lowerBound +Inf for a node about 1.4e154 from the axis line
// (sqrt(q2) = Inf), a bound above the true distance that pruned the
// nearest triangle; nearer 1e308, b - c or t_c - t_m overflowed and
// Inf - Inf or 0 * Inf raised FE_INVALID (tests/fcl_distance_test.cpp,
// HugeCoordinates). Let S = |b_root|_1 + sum e_root + |t_m|_1 + |t_c|_1 + r
// + h, the root's box and the poses (tf_mesh's translation counts even for
// the identity: it is then 0). Every box FCL fits lies within a few times
// S: the AABB/KDOP boxes nest in the root's; an oriented box is fitted to a
// subset of the vertices, all inside the root's box, so its centre and
// extents are at most about 2 S in norm. The cylinder's centre in the mesh
// frame is at most |t_c - t_m| (1 + delta) <= 2 S. So every d = b - c is
// within 5 S, u.d too, q = d - (u.d) u within 10 S, and q2 (the largest
// quantity computed: three squares) below 300 S^2 < 2^9 S^2, finite for S <
// 2^507; the leaves' bounds check their own range (triangleLowerBound and
// triangleSupportBound: 2^240). Below kMaxScale = 2^480 nothing overflows
// with 2^27 to spare. Above it (or when S itself overflows) the walks fall
// back to testing every triangle: prepare() sets Setup::bounded false and
// leaves Local zero; the collide walk then takes every node as untested
// (no node test) and the distance walk measures every triangle
// (mesh_distance.cpp, measureAll), in index order. A model that large is
// rare (1e144 and up); the kernel itself covers the whole range.
constexpr double kMaxScale = 0x1p480;

/// What prepare() found: the model, the cylinder in the mesh frame, and how
/// the Solver forms the world vertices.
struct Setup {
  Local k;
  bool raw;      // vertices used as stored (no tf_mesh * v), see prepare()
  bool bounded;  // false: the scale is beyond kMaxScale (SCALE), no node
                 // test or bound may be computed, k is zero
};

/// The validation and set-up common to the traversals. Returns false (the
/// caller then hands the query to FCL's own traversal) for anything the
/// margins do not cover: a model that is not a built triangle mesh, a
/// cylinder with NaN/Inf or negative sizes, non-finite transforms, rotations
/// or a root box far from orthonormal, a root box that is not finite.
/// `margin` (>= 0, finite) is a collide margin added to every support (0 for
/// plain collide and for distance). A scene beyond kMaxScale is accepted
/// with Setup::bounded false (SCALE): the caller then tests every triangle.
template <class BV, class Boxer>
bool prepare(const fcl::BVHModel<BV>& model, const Tf& tf_mesh,
             const fcl::Cylinderd& cyl_geom, const Tf& tf_cyl, double margin,
             Setup* out) {
  if (model.getModelType() != fcl::BVH_MODEL_TRIANGLES ||
      (model.build_state != fcl::BVH_BUILD_STATE_PROCESSED &&
       model.build_state != fcl::BVH_BUILD_STATE_UPDATED) ||
      model.getNumBVs() <= 0 || model.vertices == nullptr ||
      model.tri_indices == nullptr)
    return false;

  const double r = cyl_geom.radius, lz = cyl_geom.lz;
  if (!(std::isfinite(r) && std::isfinite(lz) && r >= 0 && lz >= 0) ||
      !(std::isfinite(margin) && margin >= 0))
    return false;
  // A mesh placed by the identity (the common case: a static environment)
  // needs neither its checks nor its products. The rotations' entries need
  // no finiteness test of their own: a NaN or an infinite entry makes
  // nonOrthogonality NaN or infinite, which the delta test below rejects;
  // the translations are tested here.
  const bool identity = exactIdentity(tf_mesh);
  if (!(identity || finiteVector(tf_mesh.translation())) ||
      !finiteVector(tf_cyl.translation()))
    return false;
  const fcl::Matrix3d& Rm = tf_mesh.linear();
  const fcl::Matrix3d& Rc = tf_cyl.linear();
  // The root's box must be finite with near-orthonormal axes. FCL's fit
  // gives that for finite vertices (Jacobi eigenvectors: orthonormal to
  // rounding); a NaN or Inf vertex spoils the root's fit (its covariance)
  // and can leave boxes that hold nothing: such models go to FCL's
  // traversal. The root's departure from orthonormal enters delta like the
  // rotations' (a box fitted along axes A misses its points by at most
  // |A A^T - I| |v - b|, item 2 of the margin); the other boxes come from
  // the same fit.
  double box_delta = 0;
  double scale =
      norm1(tf_mesh.translation()) + norm1(tf_cyl.translation()) + r + 0.5 * lz;
  {
    Box root;
    Boxer::get(model.getBV(0).bv, &root);
    for (int i = 0; i < 3; ++i)
      if (!std::isfinite(root.b[i]) || !std::isfinite(root.e[i])) return false;
    if constexpr (!Boxer::kAligned) box_delta = gramDeparture(root.a);
    for (int i = 0; i < 3; ++i) scale += std::fabs(root.b[i]) + root.e[i];
  }
  // (The identity's departure is exactly 0.)
  const double delta = std::max(
      {identity ? 0.0 : nonOrthogonality(Rm), nonOrthogonality(Rc), box_delta});
  if (!std::islessequal(delta, kMaxNonOrthogonality)) return false;

  // World vertices exactly as the Solver sees them (fcl_solver.h, FRAMES):
  // AABB and KDOP meshes are moved by FCL's initialize() unless it takes the
  // transform for the identity (Eigen's isIdentity, as FCL calls it). The
  // other meshes are moved by tf_mesh at every leaf; when tf_mesh is exactly
  // the identity that gives each finite coordinate's own value (1 x + 0 y +
  // 0 z + 0 = x, up to the sign of a zero), so the vertices are read as they
  // are. (A non-finite vertex stays non-finite and is reported "in
  // collision" either way.)
  out->raw = Boxer::kAligned ? tf_mesh.matrix().isIdentity() : identity;
  Local& k = out->k;
  // SCALE: beyond kMaxScale (or overflowed), every triangle is tested.
  out->bounded = std::isless(scale, kMaxScale);
  if (!out->bounded) {
    k = Local{};
    return true;
  }
  // (For the identity, R_m^T x computes x exactly, up to the sign of a zero.)
  const V3 c =
      identity
          ? V3(tf_cyl.translation())
          : V3(Rm.transpose() * (tf_cyl.translation() - tf_mesh.translation()));
  const V3 u = identity ? V3(Rc.col(2)) : V3(Rm.transpose() * Rc.col(2));
  for (int i = 0; i < 3; ++i) {
    k.c[i] = c[i];
    k.u[i] = u[i];
  }
  k.r = r;
  k.h = 0.5 * lz;
  k.delta = delta;
  k.rel = kRelMargin + 16 * delta;
  // MARGIN COLLIDE: the margin-neighbourhood of the cylinder (its Minkowski
  // sum with a closed ball of radius `margin`) has, along every unit
  // direction, the cylinder's support plus `margin`, and lies within r +
  // margin of the axis line: adding `margin` to every right-hand side of
  // (A), (B), (C) makes them separating tests for it. The sums it enters are
  // rounded relatively, as the other lengths: rel * margin more covers that.
  k.global = k.rel * (norm1(c) + norm1(tf_mesh.translation()) +
                      norm1(tf_cyl.translation()) + k.r + k.h + margin) +
             kAbsMargin + margin;
  // (Read by the axis-aligned boxes' tests only.)
  if constexpr (Boxer::kAligned) {
    for (int i = 0; i < 3; ++i) {
      k.au[i] = std::fabs(u[i]);
      // h |u_i| + r |e_i x u| (see THE NODE TEST AND ITS MARGIN): |e_i x u|
      // is the length of u's other two components.
      const double uj = u[(i + 1) % 3], uk = u[(i + 2) % 3];
      k.support[i] = k.h * k.au[i] + k.r * sqrtNonNegative(uj * uj + uk * uk);
    }
  }
  return true;
}

/// The world vertices of triangle `id` as the Solver sees them.
inline void worldTriangle(const V3* vertices, const fcl::Triangle& t,
                          const Tf& tf_mesh, bool raw, V3 out[3]) {
  std::size_t v[3];
  vertexIds(t, v);
  for (int j = 0; j < 3; ++j)
    out[j] = raw ? vertices[v[j]] : V3(tf_mesh * vertices[v[j]]);
}

/// The 2D distance from the origin to the triangle (p0, p1, p2) of the
/// plane (0 when the triangle, or the segment or point it degenerates to,
/// holds the origin). 1-Lipschitz in the vertices.
inline double originToTriangle2d(const double p[3][2]) {
  // Inside: the origin on the same side of the three edges (or on one).
  double s[3];
  for (int i = 0; i < 3; ++i) {
    const double* a = p[i];
    const double* b = p[(i + 1) % 3];
    s[i] = a[0] * b[1] - a[1] * b[0];  // (a - o) x (b - o)
  }
  // (Quiet comparisons throughout: a NaN raises no FP exception and proves
  // nothing.)
  const bool nonneg = std::isgreaterequal(s[0], 0) &&
                      std::isgreaterequal(s[1], 0) &&
                      std::isgreaterequal(s[2], 0);
  const bool nonpos = std::islessequal(s[0], 0) && std::islessequal(s[1], 0) &&
                      std::islessequal(s[2], 0);
  if (nonneg || nonpos) {
    // A proper triangle holds the origin. (A degenerate one, all s = 0,
    // is a segment through the origin's line: fall through to the edges,
    // which measure it correctly.)
    if (s[0] != 0 || s[1] != 0 || s[2] != 0) return 0;
  }
  double best2 = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 3; ++i) {
    const double* a = p[i];
    const double* b = p[(i + 1) % 3];
    const double e0 = b[0] - a[0], e1 = b[1] - a[1];
    const double ee = e0 * e0 + e1 * e1;
    double t = 0;
    if (gt(ee, 0)) {
      t = -(a[0] * e0 + a[1] * e1) / ee;
      t = clampUnit(t);
    }
    const double q0 = a[0] + t * e0, q1 = a[1] + t * e1;
    const double d2 = q0 * q0 + q1 * q1;
    if (std::isless(d2, best2)) best2 = d2;
  }
  return sqrtNonNegative(best2);
}

/// A certified lower bound of the distance the contract of
/// tricyl::distance measures (the pulled-back triangle y = R^T (x - t), R
/// and t as given, to the solid cylinder of radius r and half length h), or
/// a value <= 0 (or NaN) when none is proved; cheap (about 60 flops) next to
/// the distance itself. The largest of three gaps, each at most the
/// distance: along the axis (projection on z), in the plane of the caps
/// (projection on xy: the 2D distance from the axis to the projected
/// triangle, less r), and across the triangle's plane (the distance from
/// the centre to the plane, less the cylinder's support h |n_z| + r |n_xy|
/// along its unit normal n). Rounding: the computed y are within
/// E = 2^-44 L (L = the largest |x| + |t| + r + h; the true error is a few
/// ulps of L, 2^-50 L at most) of the exact ones; the first two gaps are
/// 1-Lipschitz in y, and their own rounding is a few ulps of L: 4 E covers
/// both. The plane gap is not Lipschitz for slivers: the unit normal is off
/// by at most eps_n = 4 (E (|e1| + |e2|) + 2^-50 |e1| |e2|) / |n|; it is used
/// only when eps_n < 2^-20, with (|y0| + r + h) eps_n + 4 E taken off.
///
/// The triangle in the cylinder's frame and E are computed once
/// (toCylinderFrame) and shared with triangleSupportBound below.
struct LocalTriangle {
  double y[3][3];  // vertex k at y[k]
  double E;        // 2^-44 L: each y[k] is within E of the exact one
};

inline LocalTriangle toCylinderFrame(const double x[3][3], const double R[3][3],
                                     const double t[3], double r, double h) {
  LocalTriangle lt;
  double L = 0;
  for (int k = 0; k < 3; ++k) {
    const double d[3] = {x[k][0] - t[0], x[k][1] - t[1], x[k][2] - t[2]};
    for (int i = 0; i < 3; ++i) {
      lt.y[k][i] = R[0][i] * d[0] + R[1][i] * d[1] + R[2][i] * d[2];
      const double a = std::fabs(x[k][i]);
      if (gt(a, L)) L = a;
    }
  }
  L += std::fabs(t[0]) + std::fabs(t[1]) + std::fabs(t[2]) + r + h;
  lt.E = 0x1p-44 * L;
  return lt;
}

inline double triangleLowerBound(const LocalTriangle& lt, double r, double h) {
  const double(&y)[3][3] = lt.y;
  const double E = lt.E;
  // Coordinates up to L < 2^240: the products below (of up to three
  // coordinates, and the squares of two) stay finite. Beyond, or for a NaN
  // coordinate, nothing is proved (the squares overflowed from about 2^256
  // and the face gap became Inf / Inf).
  if (!std::isless(E, 0x1p196)) return 0;
  // Along the axis.
  // (min and max by quiet comparisons, not std::fmin/fmax, libm calls: a
  // NaN coordinate makes the bound NaN or leaves it unproved either way.)
  double zmin = y[0][2], zmax = y[0][2];
  for (int k = 1; k < 3; ++k) {
    if (std::isless(y[k][2], zmin)) zmin = y[k][2];
    if (gt(y[k][2], zmax)) zmax = y[k][2];
  }
  double axial = zmin - h;
  if (gt(-h - zmax, axial)) axial = -h - zmax;
  // In the caps' plane.
  const double p[3][2] = {
      {y[0][0], y[0][1]}, {y[1][0], y[1][1]}, {y[2][0], y[2][1]}};
  // (Its squares may underflow: the root of a sum off by 2^-1073 at most
  // is off by 2^-536 at most, inside the 2^-530 taken off.)
  const double radial = originToTriangle2d(p) - r - 0x1p-530;
  double g = gt(radial, axial) ? radial : axial;
  g -= 4 * E;
  // Both at once: the cylinder is a disc times an interval, so a point's
  // distance to it is sqrt(dz^2 + dxy^2) (its distances to the slab and to
  // the infinite solid cylinder), and every point of the triangle has dz >=
  // the axial gap and dxy >= the radial gap. With each gap less its 4 E,
  // both positive, the root of the sum of squares is a lower bound; its own
  // rounding (three operations, relative) is covered by the factor 1 -
  // 2^-50, the underflow of the squares (< 2^-1073 each) by 2^-530.
  const double ga = axial - 4 * E, gr = radial - 4 * E;
  if (gt(ga, 0) && gt(gr, 0)) {
    const double both =
        sqrtNonNegative(ga * ga + gr * gr) * (1 - 0x1p-50) - 0x1p-530;
    if (gt(both, g)) g = both;
  }
  // Across the triangle's plane.
  const double e1[3] = {y[1][0] - y[0][0], y[1][1] - y[0][1],
                        y[1][2] - y[0][2]};
  const double e2[3] = {y[2][0] - y[0][0], y[2][1] - y[0][1],
                        y[2][2] - y[0][2]};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                       e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double nn = sqrtNonNegative(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  const double l1 =
      sqrtNonNegative(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
  const double l2 =
      sqrtNonNegative(e2[0] * e2[0] + e2[1] * e2[1] + e2[2] * e2[2]);
  const double eps_n = 4 * (E * (l1 + l2) + 0x1p-50 * l1 * l2);
  // (nn >= 2^-480: a component of n whose square underflows is below
  // 2^-511, so the roots nn and |n_xy| are off by 2^-536 at most, 2^-56 of
  // nn, and the products' own underflow (2^-1074 each) is 2^-594 of nn: a
  // relative error far inside 4 E over the lengths it scales.)
  if (std::isgreaterequal(nn, 0x1p-480) && std::isless(eps_n, 0x1p-20 * nn)) {
    const double en = eps_n / nn;
    const double s =
        std::fabs(n[0] * y[0][0] + n[1] * y[0][1] + n[2] * y[0][2]) / nn;
    const double support =
        (h * std::fabs(n[2]) + r * sqrtNonNegative(n[0] * n[0] + n[1] * n[1])) /
        nn;
    const double y0 =
        std::fabs(y[0][0]) + std::fabs(y[0][1]) + std::fabs(y[0][2]);
    const double face = s - support - (y0 + r + h) * en - 4 * E - 0x1p-530;
    if (gt(face, g)) g = face;
  }
  return g;
}

inline double triangleLowerBound(const double x[3][3], const double R[3][3],
                                 const double t[3], double r, double h) {
  return triangleLowerBound(toCylinderFrame(x, R, t, r, h), r, h);
}

/// The point of the triangle (a, b, c) nearest to p, by the region of the
/// triangle's Voronoi diagram p falls in (a vertex, an edge or the face),
/// read from the dot products of p - vertex with the two edge vectors (the
/// method of Ericson, Real-Time Collision Detection, 2005, 5.1.5).
/// Not certified: a heuristic for triangleSupportBound, whose bound holds
/// for any direction. Inputs finite and below 2^240 in magnitude (no
/// product overflows); a degenerate triangle gets a point of itself (each
/// division only by a positive denominator: no FP exception).
inline void nearestOnTriangle(const double p[3], const double a[3],
                              const double b[3], const double c[3],
                              double out[3]) {
  const auto dot = [](const double* u, const double* v) {
    return u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
  };
  // u + (num / den) (v - u), or u when den is not positive.
  const auto onEdge = [out](const double* u, const double* v, double num,
                            double den) {
    const double s = gt(den, 0) ? num / den : 0.0;
    for (int i = 0; i < 3; ++i) out[i] = u[i] + s * (v[i] - u[i]);
  };
  const double ab[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const double ac[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  const double ap[3] = {p[0] - a[0], p[1] - a[1], p[2] - a[2]};
  const double d1 = dot(ab, ap), d2 = dot(ac, ap);
  if (d1 <= 0 && d2 <= 0) return onEdge(a, b, 0, 0);  // vertex a
  const double bp[3] = {p[0] - b[0], p[1] - b[1], p[2] - b[2]};
  const double d3 = dot(ab, bp), d4 = dot(ac, bp);
  if (d3 >= 0 && d4 <= d3) return onEdge(b, c, 0, 0);  // vertex b
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return onEdge(a, b, d1, d1 - d3);
  const double cp[3] = {p[0] - c[0], p[1] - c[1], p[2] - c[2]};
  const double d5 = dot(ab, cp), d6 = dot(ac, cp);
  if (d6 >= 0 && d5 <= d6) return onEdge(c, a, 0, 0);  // vertex c
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return onEdge(a, c, d2, d2 - d6);
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 >= d3 && d5 >= d6)
    return onEdge(b, c, d4 - d3, (d4 - d3) + (d5 - d6));
  const double sum = va + vb + vc;
  if (!gt(sum, 0)) return onEdge(a, b, 0, 0);
  const double v = vb / sum, w = vc / sum;
  for (int i = 0; i < 3; ++i) out[i] = a[i] + v * ab[i] + w * ac[i];
}

/// The point of the solid cylinder (radius r, half length h, axis z,
/// centred at the origin) nearest to q (finite). Not certified (a
/// heuristic, as nearestOnTriangle).
inline void nearestOnCylinder(const double q[3], double r, double h,
                              double out[3]) {
  out[2] = q[2] < -h ? -h : (q[2] > h ? h : q[2]);
  const double rho2 = q[0] * q[0] + q[1] * q[1];
  const double s = rho2 > r * r ? r / sqrtNonNegative(rho2) : 1.0;
  out[0] = q[0] * s;
  out[1] = q[1] * s;
}

/// A certified lower bound of the same distance as triangleLowerBound's
/// (the pulled-back triangle to the solid cylinder of radius r and half
/// length h), or 0 when none is proved; tighter where that one is loose:
/// when the nearest points lie on an edge or a vertex of the triangle, or
/// on the cylinder's rim (then neither the axis, the caps' plane nor the
/// triangle's normal separates by the distance). About four times the cost
/// of triangleLowerBound: the distance walk asks for it only for a
/// triangle about to be measured.
///
/// Any direction v with |v| <= 1 gives one: every point of the triangle
/// has v.y >= min_k v.y_k (a linear function's minimum over a triangle is
/// at a vertex), every point of the cylinder has v.y <= h |v_z| + r |v_xy|
/// (its support along v), so the gap between the two is at most the
/// distance (times |v|). The direction comes from alternating projections
/// (the triangle's point nearest to a point of the cylinder, then the
/// cylinder's point nearest to that; for two convex sets these pairs
/// approach a nearest pair), started from the triangle's point nearest to
/// the cylinder's centre, three rounds. How good the direction is does not
/// matter to the bound's validity, only to its strength.
///
/// Rounding. v = w / |w| (computed) has |v| <= 1 + 2^-50 and is used as an
/// exact vector: the computed gap is that of v up to (i) the error of the
/// local coordinates (|v| 2^-49 L, see triangleLowerBound), (ii) the
/// rounding of the three dot products (3 ulps of |v| |y| <= 2^-50.6 L
/// each, |y| <= sqrt(3) L), of the support (4 ulps of r + h) and of the
/// differences: less than 2^-47 L in all, inside 4 E = 2^-42 L. The gap of
/// the unit v / |v| is the gap of v over |v|, so (gap - 4 E) (1 - 2^-49)
/// is a lower bound when positive (the factor also covers its own
/// rounding). |w| >= 2^-500 is required, so its largest component's square
/// does not underflow and |v| is as stated; the underflow of the other
/// products (2^-1074 each) is covered by 2^-530. Inputs: the local
/// coordinates must sum to less than 2^240 in magnitude (no overflow in
/// the heuristic's products), else nothing is proved; a NaN coordinate
/// fails that test too.
constexpr int kSupportRounds = 2;

inline double triangleSupportBound(const LocalTriangle& lt, double r,
                                   double h) {
  const double(&y)[3][3] = lt.y;
  double size = 0;
  for (int k = 0; k < 3; ++k)
    size += std::fabs(y[k][0]) + std::fabs(y[k][1]) + std::fabs(y[k][2]);
  if (!std::isless(size, 0x1p240)) return 0;
  const double origin[3] = {0, 0, 0};
  double q[3], p[3];
  nearestOnTriangle(origin, y[0], y[1], y[2], q);
  for (int round = 0; round < kSupportRounds; ++round) {
    nearestOnCylinder(q, r, h, p);
    nearestOnTriangle(p, y[0], y[1], y[2], q);
  }
  nearestOnCylinder(q, r, h, p);
  const double w[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]};
  const double len = sqrtNonNegative(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  if (!gt(len, 0x1p-500)) return 0;
  const double v[3] = {w[0] / len, w[1] / len, w[2] / len};
  double smin = v[0] * y[0][0] + v[1] * y[0][1] + v[2] * y[0][2];
  for (int k = 1; k < 3; ++k) {
    const double s = v[0] * y[k][0] + v[1] * y[k][1] + v[2] * y[k][2];
    if (s < smin) smin = s;
  }
  const double support =
      h * std::fabs(v[2]) + r * sqrtNonNegative(v[0] * v[0] + v[1] * v[1]);
  return (smin - support - 4 * lt.E) * (1 - 0x1p-49) - 0x1p-530;
}

/// Calls f(BvTag<BV>{}) for the BV type of a BVHModel<BV> of node type `t`
/// (FCL 0.7's eight BV types, for scalar S) and returns its result; false
/// for any other node type. Shared by the traversals and the Solver.
template <class BV>
struct BvTag {
  using type = BV;
};

template <class S = double, class F>
bool dispatchBv(fcl::NODE_TYPE t, F&& f) {
  switch (t) {
    case fcl::BV_AABB:
      return f(BvTag<fcl::AABB<S>>{});
    case fcl::BV_OBB:
      return f(BvTag<fcl::OBB<S>>{});
    case fcl::BV_RSS:
      return f(BvTag<fcl::RSS<S>>{});
    case fcl::BV_kIOS:
      return f(BvTag<fcl::kIOS<S>>{});
    case fcl::BV_OBBRSS:
      return f(BvTag<fcl::OBBRSS<S>>{});
    case fcl::BV_KDOP16:
      return f(BvTag<fcl::KDOP<S, 16>>{});
    case fcl::BV_KDOP18:
      return f(BvTag<fcl::KDOP<S, 18>>{});
    case fcl::BV_KDOP24:
      return f(BvTag<fcl::KDOP<S, 24>>{});
    default:
      return false;
  }
}

}  // namespace traversal
}  // namespace tricyl
