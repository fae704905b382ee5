// SPDX-License-Identifier: BSD-3-Clause
// tricyl's BVHModel/Cylinder traversal (fcl_mesh_cylinder.h): a certified
// node test over the model's own tree, then the scalar kernel on the leaves;
// with a margin, the same walk for the margin-neighbourhood of the cylinder
// and tryWithinDistance on the leaves.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/cylinder.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <type_traits>
#include <vector>

#include "margin_contact.h"
#include "mesh_traversal.h"
#include "tricyl/fcl_contact.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"
#include "tricyl/triangle_cylinder_margin.h"

namespace tricyl {
namespace {

using namespace traversal;  // NOLINT: this file's own internal helpers

// (THE NODE TEST AND ITS MARGIN: mesh_traversal.h.)

// A node that passes the test with at most this many triangles below it
// sends them all to the kernel without testing the nodes in between (the
// kernel's own early-outs against a node test). Measured in instructions
// per call (callgrind) on bench_fcl_collide's grazing scenes, first hit and
// exhaustive, over 0, 2, 4, 8 and 16: 2 is the least on all six (env,
// bunny, rob) but env exhaustive (4: 2 % fewer), 8 costs 4-17 % more than
// 2 (rob first hit the most: its large triangles leave the kernel's early
// outs more often than a leaf's box test does). A leaf's box is in the node
// the walk reads for the triangle's index anyway. Only speed depends on it.
// Measured again with the first block of one leaf and the AVX2 node test
// (bench/results/2026-11-26-mesh-walks-c.md), 0 against 2: first hit env
// 10,913 -> 10,276, bunny 6,874 -> 6,724, rob 5,913 -> 5,596 instructions a
// call (every leaf tested: a query about to stop reaches its hit through
// fewer kernel calls), exhaustive 55,953 -> 58,504, 18,448 -> 18,934,
// 19,694 -> 19,716; 4: more on all but env exhaustive (56,200). So a query
// that can stop early (ORDER, below) tests every node (first hit 10,202 /
// 6,683 / 5,574), the others send subtrees of at most 2 triangles untested.
constexpr int kUntestedSubtree = 2;
constexpr int kUntestedSubtreeEarlyStop = 0;
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
            fcl::CollisionResult<double>& result, double margin,
            TraversalStats* stats)
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
        margin_(margin),
        stats_(stats) {}

  bool full() const { return n_ == capacity_; }

  /// Queues triangle `id`; its vertices are read at the flush, all in one
  /// loop, so that the cache misses of different leaves overlap.
  void add(int id) { id_[n_++] = id; }

  /// Decides the waiting leaves and records the hits in order. Returns true
  /// when the request is satisfied (the traversal stops).
  bool flush() {
    if (n_ == 0) return satisfied();
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
      // A margin collide asks the exact margin test instead (margin 0 is
      // never routed here: it is the plain collide).
      Answer a;
      if (margin_ > 0) {
        // A triangle proved farther than the margin by its cheap bound
        // (mesh_traversal.h, triangleLowerBound) is not within it.
        const Triangle<double>& w = tri_[i];
        const double x[3][3] = {{w.a.x, w.a.y, w.a.z},
                                {w.b.x, w.b.y, w.b.z},
                                {w.c.x, w.c.y, w.c.z}};
        const double tc[3] = {pose_.t.x, pose_.t.y, pose_.t.z};
        if (gt(triangleLowerBound(x, pose_.R, tc, cyl_.radius, 0.5 * cyl_.lz),
               margin_))
          continue;
        a = tryWithinDistance(cyl_, pose_, tri_[i], margin_);
      } else {
        a = tryIntersect(cyl_, pose_, tri_[i]);
      }
      if (a == Answer::kDisjoint) continue;
      if (stats_ != nullptr) ++stats_->hits;
      record(i);
      if (satisfied()) {
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

  /// request_.isSatisfied(result_) (FCL 0.7's definition: no cost asked,
  /// which the caller checked, and at least one and at least
  /// num_max_contacts contacts), from the count kept here: FCL's is a call
  /// into libfcl for every triangle decided.
  bool satisfied() const {
    return contacts_ > 0 && request_.num_max_contacts <= contacts_;
  }

  void record(std::size_t i) {
    if (!request_.enable_contact) {
      result_.addContact(fcl::Contact<double>(mesh_, cyl_geom_, id_[i],
                                              fcl::Contact<double>::NONE));
      ++contacts_;
      return;
    }
    // The Solver's contact path (fcl_solver.cpp), and FCL's storage of it:
    // the solver's normal points from the cylinder to the triangle, the
    // Contact's from the mesh (o1) to the cylinder (o2).
    ContactEstimate<double> est;
    if (estimateContact(cyl_, pose_, tri_[i], &est) == Answer::kDisjoint) {
      if (margin_ > 0) recordWithinMargin(i);
      return;
    }
    result_.addContact(fcl::Contact<double>(
        mesh_, cyl_geom_, id_[i], fcl::Contact<double>::NONE,
        V3(est.point.x, est.point.y, est.point.z),
        -V3(est.normal.x, est.normal.y, est.normal.z), est.depth));
    ++contacts_;
  }

  /// A triangle within the margin that does not touch the cylinder: the
  /// contact of a margin collide (fcl_solver.h, MARGIN COLLIDE).
  void recordWithinMargin(std::size_t i) {
    const margin_detail::MarginContact<double> c =
        margin_detail::marginContact(cyl_, pose_, tri_[i]);
    result_.addContact(fcl::Contact<double>(mesh_, cyl_geom_, id_[i],
                                            fcl::Contact<double>::NONE, c.pos,
                                            c.normal, c.depth));
    ++contacts_;
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
  double margin_;
  TraversalStats* stats_;
  std::size_t n_ = 0;
  std::size_t contacts_ = result_.numContacts();  // (record() counts)
  // First hits: small blocks first, so that a traversal that is about to
  // stop does not walk to and decide leaves past the hit; doubled at every
  // flush. The first block holds as many leaves as contacts are still
  // wanted (one for a first-hit query: decided as soon as the walk reaches
  // it; the nearer-child ORDER makes it a hit more often than not). On the
  // grazing scenes of bench_fcl_collide, first hit, against a first block
  // of at least 4 (bench/results/2026-11-26-mesh-walks-c.md): node tests
  // per call env 46.4 -> 41.1, bunny 24.8 -> 21.3, rob 17.9 -> 15.5,
  // instructions 7-10 % fewer; a first block of 2 read 2-4 % more nodes.
  std::size_t capacity_ = std::clamp<std::size_t>(
      request_.num_max_contacts -
          std::min(request_.num_max_contacts, result_.numContacts()),
      1, kSize);
  int id_[kSize];
  Triangle<double> tri_[kSize];
};

// ORDER. Of a node's two children that both may hold a colliding triangle,
// the walk takes first the one whose box centre is nearer the cylinder's
// centre (squared distance, in the mesh frame; the left child first on a tie),
// not FCL's left child first. The walk stops at num_max_contacts, so the
// order decides which colliding triangles fill a small num_max_contacts and
// how much of the tree a first-hit query reads before its first hit: on the
// grazing scenes of bench_fcl_collide (most poses in contact), first hit,
// node tests per call env 56.4 -> 46.4, bunny 35.0 -> 24.8, rob 22.6 -> 17.9,
// triangles decided 7.11 -> 6.14, 5.76 -> 4.89, 4.29 -> 3.92, instructions
// 13-20 % fewer (bench/results/2026-11-26-mesh-walks-b.md). Other orders
// measured the same way: the distance to the axis segment instead of the
// centre, and either less the box's squared circumradius, 5-60 % more than
// the centres (a large box near the cylinder is not likelier to hold the
// contact); testing both children as soon as the parent passes and taking
// the one whose test leaves more room first, more instructions than FCL's
// order (the second child's test is wasted when the first subtree hits).
// The choice reads only the children's box centres (the nodes' lines that
// the prefetch below asks for anyway). An exhaustive query reads the same
// nodes in any order: a query that cannot stop early (num_max_contacts,
// less the contacts already in the result, at least the model's triangle
// count) keeps FCL's order, left child first, and its contact sequence is
// FCL's; choosing the nearer child cost it 3-5 % more instructions on the
// grazing scenes for nothing. FCL's contract bounds how many contacts a
// query returns, not which: its own choice already differs between BV
// types (other trees) and, for AABB/KDOP meshes moved by a transform,
// between calls (the tree is rebuilt).
template <class Boxer, class BV>
double centreDistance2(const BV& bv, const Local& k) {
  Box x;
  Boxer::get(bv, &x);
  const double d0 = x.b[0] - k.c[0], d1 = x.b[1] - k.c[1], d2 = x.b[2] - k.c[2];
  return d0 * d0 + d1 * d1 + d2 * d2;
}

template <class BV>
#if defined(__GNUC__) || defined(__clang__)
__attribute__((always_inline))
#endif
inline bool
traverseBody(const fcl::CollisionGeometry<double>* geom, const Tf& tf_mesh,
             const fcl::Cylinderd* cyl_geom, const Tf& tf_cyl,
             const fcl::CollisionRequest<double>& request,
             fcl::CollisionResult<double>& result, double margin,
             TraversalStats* stats) {
  using Boxer = BoxOf<BV>;
  const auto& model = static_cast<const fcl::BVHModel<BV>&>(*geom);
  Setup setup;
  if (!prepare<BV, Boxer>(model, tf_mesh, *cyl_geom, tf_cyl, margin, &setup))
    return false;
  const Local& k = setup.k;
  const bool raw = setup.raw;
  const double r = cyl_geom->radius, lz = cyl_geom->lz;
  const Cylinder<double> cyl{r, lz};
  const Pose<double> pose = toPose(tf_cyl);
  LeafBlock block(geom, model.vertices, model.tri_indices, tf_mesh, raw,
                  cyl_geom, cyl, pose, request, result, margin, stats);
  // ORDER: only a walk that can stop early orders its children.
  const bool nearer_first = request.num_max_contacts - result.numContacts() <
                            std::size_t(std::max(model.num_tris, 0));
  const int untested_subtree =
      nearer_first ? kUntestedSubtreeEarlyStop : kUntestedSubtree;
  NodeStack stack;
  // SCALE (mesh_traversal.h): beyond kMaxScale the root goes in untested,
  // and with it every node: each triangle reaches the kernel.
  stack.push(setup.bounded ? 0 : ~0);
  Box box;
  std::size_t tested = 0, skipped = 0;
  bool done = false;
  // Stack entries >= 0 are nodes to test; ~n (< 0) are nodes inside a
  // small subtree that passed: their leaves go to the kernel untested.
  while (!stack.empty() && !done) {
    const int entry = stack.pop();
    const bool untested = entry < 0;
    const fcl::BVNode<BV>& node = model.getBV(untested ? ~entry : entry);
    // (The children are asked for once the node passes. Asking before the
    // test, and for a leaf's vertex indices, made the fastest first-hit
    // calls of bench_fcl_collide's grazing rows 5-8 % slower.)
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
      if (untested || node.num_primitives <= untested_subtree) {
        stack.push(~right);
        stack.push(~left);
        continue;
      }
      // ORDER: the child whose box centre is nearer the cylinder's centre
      // first (left first on a tie or a NaN).
      const bool right_first =
          nearer_first &&
          std::isless(centreDistance2<Boxer>(model.getBV(right).bv, k),
                      centreDistance2<Boxer>(model.getBV(left).bv, k));
      stack.push(right_first ? left : right);
      stack.push(right_first ? right : left);
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

// The walk compiled twice on x86-64: for the baseline (SSE2) and for AVX2,
// chosen once per process. The same operations in the same order either way
// (-ffp-contract=off, no FMA: AVX2's three-operand, VEX-encoded forms of
// the same instructions, correctly rounded alike), so the same nodes are
// skipped and the same triangles reported; the AVX2 build saves the register
// copies and two-instruction broadcasts of the baseline's node test (5-8 %
// fewer instructions a call on bench_fcl_collide's grazing scenes). As for
// the kernel's prologues, TRICYL_SCALAR_BASELINE=1 in the environment keeps
// the baseline (to test it on AVX2 machines).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__)) && \
    !defined(__AVX2__)
#define TRICYL_WALK_AVX2 1
const bool kWalkAvx2 = __builtin_cpu_supports("avx2") != 0 &&
                       std::getenv("TRICYL_SCALAR_BASELINE") == nullptr;
#else
#define TRICYL_WALK_AVX2 0
#endif

template <class BV>
bool traverseBaseline(const fcl::CollisionGeometry<double>* geom,
                      const Tf& tf_mesh, const fcl::Cylinderd* cyl_geom,
                      const Tf& tf_cyl,
                      const fcl::CollisionRequest<double>& request,
                      fcl::CollisionResult<double>& result, double margin,
                      TraversalStats* stats) {
  return traverseBody<BV>(geom, tf_mesh, cyl_geom, tf_cyl, request, result,
                          margin, stats);
}

#if TRICYL_WALK_AVX2
template <class BV>
__attribute__((target("avx2"))) bool traverseAvx2(
    const fcl::CollisionGeometry<double>* geom, const Tf& tf_mesh,
    const fcl::Cylinderd* cyl_geom, const Tf& tf_cyl,
    const fcl::CollisionRequest<double>& request,
    fcl::CollisionResult<double>& result, double margin,
    TraversalStats* stats) {
  return traverseBody<BV>(geom, tf_mesh, cyl_geom, tf_cyl, request, result,
                          margin, stats);
}
#endif

template <class BV>
bool traverse(const fcl::CollisionGeometry<double>* geom, const Tf& tf_mesh,
              const fcl::Cylinderd* cyl_geom, const Tf& tf_cyl,
              const fcl::CollisionRequest<double>& request,
              fcl::CollisionResult<double>& result, double margin,
              TraversalStats* stats) {
#if TRICYL_WALK_AVX2
  if (kWalkAvx2)
    return traverseAvx2<BV>(geom, tf_mesh, cyl_geom, tf_cyl, request, result,
                            margin, stats);
#endif
  return traverseBaseline<BV>(geom, tf_mesh, cyl_geom, tf_cyl, request, result,
                              margin, stats);
}

}  // namespace

bool collideMeshCylinderWithin(const fcl::CollisionGeometry<double>* g1,
                               const fcl::Transform3<double>& tf1,
                               const fcl::CollisionGeometry<double>* g2,
                               const fcl::Transform3<double>& tf2,
                               const fcl::CollisionRequest<double>& request,
                               fcl::CollisionResult<double>& result,
                               double margin, std::size_t* num_contacts,
                               TraversalStats* stats) {
  if (g1 == nullptr || g2 == nullptr) return false;
  // FCL always runs the mesh as o1 (collide swaps a shape/BVH pair).
  if (g2->getObjectType() == fcl::OT_BVH &&
      g1->getNodeType() == fcl::GEOM_CYLINDER)
    return collideMeshCylinderWithin(g2, tf2, g1, tf1, request, result, margin,
                                     num_contacts, stats);
  if (g1->getObjectType() != fcl::OT_BVH ||
      g2->getNodeType() != fcl::GEOM_CYLINDER)
    return false;
  if (request.enable_cost || request.num_max_contacts == 0 ||
      !g1->isOccupied() || !g2->isOccupied() ||
      !(std::isfinite(margin) && margin >= 0))
    return false;
  if (request.isSatisfied(result)) {  // as FCL's collider does first
    *num_contacts = result.numContacts();
    return true;
  }
  const auto* cyl = static_cast<const fcl::Cylinderd*>(g2);
  const bool handled = dispatchBv(g1->getNodeType(), [&](auto tag) {
    using BV = typename decltype(tag)::type;
    return traverse<BV>(g1, tf1, cyl, tf2, request, result, margin, stats);
  });
  if (handled) *num_contacts = result.numContacts();
  return handled;
}

bool collideMeshCylinder(const fcl::CollisionGeometry<double>* g1,
                         const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* g2,
                         const fcl::Transform3<double>& tf2,
                         const fcl::CollisionRequest<double>& request,
                         fcl::CollisionResult<double>& result,
                         std::size_t* num_contacts, TraversalStats* stats) {
  return collideMeshCylinderWithin(g1, tf1, g2, tf2, request, result, 0.0,
                                   num_contacts, stats);
}

}  // namespace tricyl
