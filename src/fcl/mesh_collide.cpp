// SPDX-License-Identifier: BSD-3-Clause
// tricyl's BVHModel/Cylinder traversal (fcl_mesh_cylinder.h): a certified
// node test over the model's own tree, then the scalar kernel on the leaves.
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
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "tricyl/fcl_contact.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

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
// |a_i x u| is computed as the square root of the sum of the squared
// components of the cross product: the components' rounding is absolute
// (a few ulps of |a_i| |u|), not amplified.
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

// A node that passes the test with at most this many triangles below it
// sends them all to the kernel without testing the nodes in between: on the
// env.obj and bunny.obj scenes of bench_fcl_collide, 5 in 6 tested nodes
// pass, and the kernel's own early-outs are cheaper than a node test. Only
// speed depends on it.
constexpr int kUntestedSubtree = 8;

/// The cylinder in the mesh frame and the per-call constants.
struct Local {
  double c[3];
  double u[3];
  double r;
  double h;
  double rel;     // 2^-36 + 16 delta
  double global;  // rel * (|c|_1 + |t_m|_1 + |t_c|_1 + r + h) + 2^-500
  // Axis-aligned boxes: the cylinder's support along the world axes of the
  // mesh frame, h |u_i| + r |e_i x u|, and |u_i|.
  double au[3];
  double support[3];
};

/// A node's box. Axis-aligned boxes (AABB, KDOP) leave `a` unset.
struct Box {
  double b[3];
  double a[3][3];  // a[i] = axis i
  double e[3];
};

/// a > b without raising FE_INVALID on a NaN (a quiet comparison): false
/// then, so a NaN never skips a node.
inline bool gt(double a, double b) { return std::isgreater(a, b); }

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

template <bool kAligned>
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline bool
overlaps(const Box& x, const Local& k) {
  const double d[3] = {x.b[0] - k.c[0], x.b[1] - k.c[1], x.b[2] - k.c[2]};
  const double m =
      k.global + k.rel * (std::fabs(x.b[0]) + std::fabs(x.b[1]) +
                          std::fabs(x.b[2]) + x.e[0] + x.e[1] + x.e[2]);
  const double ud = k.u[0] * d[0] + k.u[1] * d[1] + k.u[2] * d[2];
  double ua[3];
  if constexpr (kAligned) {
    for (int i = 0; i < 3; ++i) ua[i] = k.au[i];
  } else {
    for (int i = 0; i < 3; ++i)
      ua[i] = std::fabs(k.u[0] * x.a[i][0] + k.u[1] * x.a[i][1] +
                        k.u[2] * x.a[i][2]);
  }
  // (A): the cylinder's axis.
  if (gt(std::fabs(ud),
         k.h + x.e[0] * ua[0] + x.e[1] * ua[1] + x.e[2] * ua[2] + m))
    return false;
  // (B): the box's axes. The radial part r |a_i x u| >= 0 is only computed
  // when the rest does not already pass.
  for (int i = 0; i < 3; ++i) {
    if constexpr (kAligned) {
      if (gt(std::fabs(d[i]), x.e[i] + k.support[i] + m)) return false;
    } else {
      const double ad = x.a[i][0] * d[0] + x.a[i][1] * d[1] + x.a[i][2] * d[2];
      const double excess = std::fabs(ad) - (x.e[i] + k.h * ua[i] + m);
      if (!gt(excess, 0)) continue;
      // r |a_i x u| (see THE NODE TEST AND ITS MARGIN).
      const double* a = x.a[i];
      const double c0 = a[1] * k.u[2] - a[2] * k.u[1],
                   c1 = a[2] * k.u[0] - a[0] * k.u[2],
                   c2 = a[0] * k.u[1] - a[1] * k.u[0];
      if (gt(excess, k.r * sqrtNonNegative(c0 * c0 + c1 * c1 + c2 * c2)))
        return false;
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
  const double e01 = gt(x.e[1], x.e[0]) ? x.e[1] : x.e[0];
  const double near = k.r + (gt(x.e[2], e01) ? x.e[2] : e01) + m;
  if (!gt(q2, near * near)) return true;
  const double reach =
      k.r +
      sqrtNonNegative(x.e[0] * x.e[0] + x.e[1] * x.e[1] + x.e[2] * x.e[2]) + m;
  return !gt(q2, reach * reach);
}

// Box conversions, one per BV type. Each gives a box containing the BV.
void fromObb(const fcl::OBB<double>& o, Box* x) {
  for (int i = 0; i < 3; ++i) {
    x->b[i] = o.To[i];
    x->e[i] = o.extent[i];
    for (int j = 0; j < 3; ++j) x->a[i][j] = o.axis(j, i);
  }
}

void fromMinMax(const double* lo, const double* hi, Box* x) {
  for (int i = 0; i < 3; ++i) {
    x->b[i] = 0.5 * (lo[i] + hi[i]);
    x->e[i] = 0.5 * (hi[i] - lo[i]);
  }
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
    for (int i = 0; i < 3; ++i) {
      x->b[i] = v.To[i] + h0 * v.axis(i, 0) + h1 * v.axis(i, 1);
      for (int j = 0; j < 3; ++j) x->a[i][j] = v.axis(j, i);
    }
    x->e[0] = h0 + v.r;
    x->e[1] = h1 + v.r;
    x->e[2] = v.r;
  }
};

/// sum |R^T R - I| over the nine entries; NaN for a non-finite R.
double nonOrthogonality(const fcl::Matrix3d& R) {
  double s = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const double g = R(0, i) * R(0, j) + R(1, i) * R(1, j) +
                       R(2, i) * R(2, j) - (i == j ? 1.0 : 0.0);
      s += std::fabs(g);
    }
  return s;
}

bool finiteTransform(const Tf& tf) {
  const auto& M = tf.matrix();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      if (!std::isfinite(M(i, j))) return false;
  return true;
}

bool exactIdentity(const Tf& tf) {
  const auto& M = tf.matrix();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j)
      if (!(M(i, j) == (i == j ? 1.0 : 0.0))) return false;
  return true;
}

double norm1(const V3& v) {
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

/// A small explicit stack (FCL's trees are rarely deeper than 64; deeper
/// ones spill to the heap).
class NodeStack {
 public:
  void push(int n) {
    if (size_ < kInline)
      inline_[size_] = n;
    else
      spill_.push_back(n);
    ++size_;
  }
  bool empty() const { return size_ == 0; }
  int pop() {
    --size_;
    if (size_ < kInline) return inline_[size_];
    const int n = spill_.back();
    spill_.pop_back();
    return n;
  }

 private:
  static constexpr std::size_t kInline = 128;
  int inline_[kInline];
  std::size_t size_ = 0;
  std::vector<int> spill_;
};

/// Leaves waiting for the kernel, in traversal order.
///
/// Each is decided by the scalar kernel (tryIntersect), not by the batch
/// kernel (tryIntersectMask) that decided them until 2026-11: the leaves
/// reaching a block have passed the node test, so the batch's vertex-code
/// cull rejected few of them and its setup and code pass (three calls over
/// at most 64 vertices, about 4 ns a vertex at these sizes) cost more than
/// the scalar kernel's own early-outs. Medians of six interleaved runs of
/// bench_fcl_collide's scenes, exhaustive, per call: bunny.obj 3.76 -> 3.35
/// us, env.obj 10.38 -> 9.17 us. With the node test's inline square roots
/// (below), the paired ratio to stock fcl::collide went from 5.1x to 6.1x
/// (bunny.obj) and 6.1x to 7.0x (env.obj) between the recordings of
/// bench/results (2026-11-23 21:34 and 2026-11-24 00:06 UTC). The answers are
/// the same (the batch is bit-identical to the scalar kernel).
class LeafBlock {
 public:
  static constexpr std::size_t kSize = 64;

  LeafBlock(const fcl::CollisionGeometry<double>* mesh, const V3* vertices,
            const fcl::Triangle* tris, const Tf& tf_mesh, bool raw,
            const fcl::CollisionGeometry<double>* cyl_geom,
            const Cylinder<double>& cyl, const Pose<double>& pose,
            const fcl::CollisionRequest<double>& request,
            fcl::CollisionResult<double>& result, TraversalStats* stats)
      : mesh_(mesh),
        vertices_(vertices),
        tris_(tris),
        tf_mesh_(tf_mesh),
        raw_(raw),
        cyl_geom_(cyl_geom),
        cyl_(cyl),
        pose_(pose),
        request_(request),
        result_(result),
        stats_(stats) {}

  bool full() const { return n_ == capacity_; }

  /// Queues triangle `id`; its vertices are read at the flush, all in one
  /// loop, so that the cache misses of different leaves overlap.
  void add(int id) { id_[n_++] = id; }

  /// Decides the waiting leaves and records the hits in order. Returns true
  /// when the request is satisfied (the traversal stops).
  bool flush() {
    if (n_ == 0) return request_.isSatisfied(result_);
    // World vertices exactly as the Solver sees them (fcl_solver.h, FRAMES).
    const fcl::Triangle* t[kSize];
    for (std::size_t i = 0; i < n_; ++i) t[i] = &tris_[id_[i]];
    for (std::size_t i = 0; i < n_; ++i) {
      std::size_t v[3];
      vertexIds(*t[i], v);
      const V3& p0 = vertices_[v[0]];
      const V3& p1 = vertices_[v[1]];
      const V3& p2 = vertices_[v[2]];
      if (raw_) {
        tri_[i] = {vec(p0), vec(p1), vec(p2)};
      } else {
        tri_[i] = {vec(tf_mesh_ * p0), vec(tf_mesh_ * p1), vec(tf_mesh_ * p2)};
      }
    }
    if (stats_ != nullptr) stats_->leaves += n_;
    bool done = false;
    for (std::size_t i = 0; i < n_; ++i) {
      // Cylinder and pose were validated: kInvalidInput means a non-finite
      // world coordinate, reported "in collision" (as the Solver answers).
      if (tryIntersect(cyl_, pose_, tri_[i]) == Answer::kDisjoint) continue;
      if (stats_ != nullptr) ++stats_->hits;
      record(i);
      if (request_.isSatisfied(result_)) {
        done = true;
        break;
      }
    }
    n_ = 0;
    capacity_ = std::min(kSize, 2 * capacity_);
    return done;
  }

 private:
  static Vec3<double> vec(const V3& p) { return {p[0], p[1], p[2]}; }

  void record(std::size_t i) {
    if (!request_.enable_contact) {
      result_.addContact(fcl::Contact<double>(mesh_, cyl_geom_, id_[i],
                                              fcl::Contact<double>::NONE));
      return;
    }
    // The Solver's contact path (fcl_solver.cpp), and FCL's storage of it:
    // the solver's normal points from the cylinder to the triangle, the
    // Contact's from the mesh (o1) to the cylinder (o2).
    ContactEstimate<double> est;
    if (estimateContact(cyl_, pose_, tri_[i], &est) == Answer::kDisjoint)
      return;
    result_.addContact(fcl::Contact<double>(
        mesh_, cyl_geom_, id_[i], fcl::Contact<double>::NONE,
        V3(est.point.x, est.point.y, est.point.z),
        -V3(est.normal.x, est.normal.y, est.normal.z), est.depth));
  }

  const fcl::CollisionGeometry<double>* mesh_;
  const V3* vertices_;
  const fcl::Triangle* tris_;
  const Tf& tf_mesh_;
  bool raw_;
  const fcl::CollisionGeometry<double>* cyl_geom_;
  const Cylinder<double>& cyl_;
  const Pose<double>& pose_;
  const fcl::CollisionRequest<double>& request_;
  fcl::CollisionResult<double>& result_;
  TraversalStats* stats_;
  std::size_t n_ = 0;
  // First hits: small blocks first, so that a traversal that is about to
  // stop does not decide 64 leaves past the hit; doubled at every flush.
  std::size_t capacity_ = std::clamp<std::size_t>(
      2 * (request_.num_max_contacts -
           std::min(request_.num_max_contacts, result_.numContacts())),
      4, kSize);
  int id_[kSize];
  Triangle<double> tri_[kSize];
};

template <class BV>
bool traverse(const fcl::CollisionGeometry<double>* geom, const Tf& tf_mesh,
              const fcl::Cylinderd* cyl_geom, const Tf& tf_cyl,
              const fcl::CollisionRequest<double>& request,
              fcl::CollisionResult<double>& result, TraversalStats* stats) {
  using Boxer = BoxOf<BV>;
  const auto& model = static_cast<const fcl::BVHModel<BV>&>(*geom);
  if (model.getModelType() != fcl::BVH_MODEL_TRIANGLES ||
      (model.build_state != fcl::BVH_BUILD_STATE_PROCESSED &&
       model.build_state != fcl::BVH_BUILD_STATE_UPDATED) ||
      model.getNumBVs() <= 0 || model.vertices == nullptr ||
      model.tri_indices == nullptr)
    return false;

  // Validation: anything the margins do not cover goes to FCL's traversal.
  const double r = cyl_geom->radius, lz = cyl_geom->lz;
  if (!(std::isfinite(r) && std::isfinite(lz) && r >= 0 && lz >= 0) ||
      !finiteTransform(tf_mesh) || !finiteTransform(tf_cyl))
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
  {
    Box root;
    Boxer::get(model.getBV(0).bv, &root);
    for (int i = 0; i < 3; ++i) {
      if (!std::isfinite(root.b[i]) || !std::isfinite(root.e[i])) return false;
      if constexpr (!Boxer::kAligned)
        for (int j = 0; j < 3; ++j)
          box_delta += std::fabs(
              root.a[i][0] * root.a[j][0] + root.a[i][1] * root.a[j][1] +
              root.a[i][2] * root.a[j][2] - (i == j ? 1.0 : 0.0));
    }
  }
  const double delta =
      std::max({nonOrthogonality(Rm), nonOrthogonality(Rc), box_delta});
  if (!std::islessequal(delta, kMaxNonOrthogonality)) return false;

  Local k;
  const V3 c = Rm.transpose() * (tf_cyl.translation() - tf_mesh.translation());
  const V3 u = Rm.transpose() * Rc.col(2);
  for (int i = 0; i < 3; ++i) {
    k.c[i] = c[i];
    k.u[i] = u[i];
  }
  k.r = r;
  k.h = 0.5 * lz;
  k.rel = kRelMargin + 16 * delta;
  k.global = k.rel * (norm1(c) + norm1(tf_mesh.translation()) +
                      norm1(tf_cyl.translation()) + k.r + k.h) +
             kAbsMargin;
  for (int i = 0; i < 3; ++i) {
    k.au[i] = std::fabs(u[i]);
    // h |u_i| + r |e_i x u| (see THE NODE TEST AND ITS MARGIN): |e_i x u|
    // is the length of u's other two components.
    const double uj = u[(i + 1) % 3], uk = u[(i + 2) % 3];
    k.support[i] = k.h * k.au[i] + k.r * std::sqrt(uj * uj + uk * uk);
  }

  // World vertices exactly as the Solver sees them (fcl_solver.h, FRAMES):
  // AABB and KDOP meshes are moved by FCL's initialize() unless it takes the
  // transform for the identity (Eigen's isIdentity, as FCL calls it). The
  // other meshes are moved by tf_mesh at every leaf; when tf_mesh is exactly
  // the identity that gives each finite coordinate's own value (1 x + 0 y +
  // 0 z + 0 = x, up to the sign of a zero), so the vertices are read as they
  // are. (A non-finite vertex stays non-finite and is reported "in
  // collision" either way.)
  const bool raw =
      Boxer::kAligned ? tf_mesh.matrix().isIdentity() : exactIdentity(tf_mesh);
  const Cylinder<double> cyl{r, lz};
  const Pose<double> pose = toPose(tf_cyl);
  LeafBlock block(geom, model.vertices, model.tri_indices, tf_mesh, raw,
                  cyl_geom, cyl, pose, request, result, stats);
  NodeStack stack;
  stack.push(0);
  Box box;
  std::size_t tested = 0, skipped = 0;
  bool done = false;
  // Stack entries >= 0 are nodes to test; ~n (< 0) are nodes inside a
  // small subtree that passed: their leaves go to the kernel untested.
  while (!stack.empty() && !done) {
    const int entry = stack.pop();
    const bool untested = entry < 0;
    const fcl::BVNode<BV>& node = model.getBV(untested ? ~entry : entry);
    if (!untested) {
      Boxer::get(node.bv, &box);
      ++tested;
      if (!overlaps<Boxer::kAligned>(box, k)) {
        ++skipped;
        continue;
      }
    }
    if (!isLeaf(node)) {
      const int left = leftChild(node), right = rightChild(node);
      prefetchNode(model.getBV(left));
      prefetchNode(model.getBV(right));
      if (untested || node.num_primitives <= kUntestedSubtree) {
        stack.push(~right);
        stack.push(~left);
        continue;
      }
      stack.push(right);  // left child first, as FCL
      stack.push(left);
      continue;
    }
    block.add(primitiveId(node));
    if (block.full()) done = block.flush();
  }
  if (!done) block.flush();
  if (stats != nullptr) {
    stats->nodes_tested += tested;
    stats->nodes_skipped += skipped;
  }
  return true;
}

}  // namespace

bool collideMeshCylinder(const fcl::CollisionGeometry<double>* g1,
                         const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* g2,
                         const fcl::Transform3<double>& tf2,
                         const fcl::CollisionRequest<double>& request,
                         fcl::CollisionResult<double>& result,
                         std::size_t* num_contacts, TraversalStats* stats) {
  if (g1 == nullptr || g2 == nullptr) return false;
  // FCL always runs the mesh as o1 (collide swaps a shape/BVH pair).
  if (g2->getObjectType() == fcl::OT_BVH &&
      g1->getNodeType() == fcl::GEOM_CYLINDER)
    return collideMeshCylinder(g2, tf2, g1, tf1, request, result, num_contacts,
                               stats);
  if (g1->getObjectType() != fcl::OT_BVH ||
      g2->getNodeType() != fcl::GEOM_CYLINDER)
    return false;
  if (request.enable_cost || request.num_max_contacts == 0 ||
      !g1->isOccupied() || !g2->isOccupied())
    return false;
  if (request.isSatisfied(result)) {  // as FCL's collider does first
    *num_contacts = result.numContacts();
    return true;
  }
  const auto* cyl = static_cast<const fcl::Cylinderd*>(g2);
  bool handled = false;
  switch (g1->getNodeType()) {
    case fcl::BV_AABB:
      handled = traverse<fcl::AABB<double>>(g1, tf1, cyl, tf2, request, result,
                                            stats);
      break;
    case fcl::BV_OBB:
      handled =
          traverse<fcl::OBB<double>>(g1, tf1, cyl, tf2, request, result, stats);
      break;
    case fcl::BV_RSS:
      handled =
          traverse<fcl::RSS<double>>(g1, tf1, cyl, tf2, request, result, stats);
      break;
    case fcl::BV_kIOS:
      handled = traverse<fcl::kIOS<double>>(g1, tf1, cyl, tf2, request, result,
                                            stats);
      break;
    case fcl::BV_OBBRSS:
      handled = traverse<fcl::OBBRSS<double>>(g1, tf1, cyl, tf2, request,
                                              result, stats);
      break;
    case fcl::BV_KDOP16:
      handled = traverse<fcl::KDOP<double, 16>>(g1, tf1, cyl, tf2, request,
                                                result, stats);
      break;
    case fcl::BV_KDOP18:
      handled = traverse<fcl::KDOP<double, 18>>(g1, tf1, cyl, tf2, request,
                                                result, stats);
      break;
    case fcl::BV_KDOP24:
      handled = traverse<fcl::KDOP<double, 24>>(g1, tf1, cyl, tf2, request,
                                                result, stats);
      break;
    default:
      break;
  }
  if (handled) *num_contacts = result.numContacts();
  return handled;
}

}  // namespace tricyl
