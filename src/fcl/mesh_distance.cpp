// SPDX-License-Identifier: BSD-3-Clause
// tricyl's BVHModel/Cylinder distance traversal (fcl_mesh_cylinder.h,
// distanceMeshCylinder): best-first over the model's own tree, each node
// and each triangle pruned by a certified lower bound of its distance to the
// cylinder (mesh_traversal.h, lowerBound and triangleLowerBound),
// tricyl::tryDistance on the triangles that survive.
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

#include "mesh_traversal.h"
#include "tricyl/fcl_adapters.h"
#include "tricyl/fcl_contact.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"

namespace tricyl {
namespace {

using namespace traversal;  // NOLINT: this file's own internal helpers

// PRUNING. Each triangle i measured gets d_i and a certified e_i
// (error_bound): its true distance is in [d_i - e_i, d_i + e_i]. best is
// the smallest d_i so far (triangle c) and cut = (d_c + e_c) (1 + 2^-40),
// rounded (two roundings of 2^-53 each: cut > d_c + e_c still). A node
// whose certified lower bound lb (lowerBoundLocal, triangleLowerBound,
// triangleSupportBound) exceeds cut is skipped: every triangle below it is
// certainly farther than c (true >= lb > d_c + e_c >= c's true distance),
// so it is not the nearest triangle, and the nearest one (every triangle
// attaining the true minimum) is always measured. The traversal returns
// the smallest d_i over the triangles it measured; hence, with b the
// brute-force minimum over ALL the triangles (triangle j): b <= returned
// <= b + e_j, the returned triangle is never certainly farther than
// another (returned - e <= min (d_i + e_i)), and returned = b exactly
// whenever a pruned triangle's own error cannot take its d below best,
// in particular whenever the minimum is certified unique and whenever the
// pruned triangles' e_i are within 2^-40 of their distance (the usual case:
// a few ulps above about 2^-45 of the problem's size, docs/distance.md,
// section 4). Below that size the kernel's e_i is its double-word
// allowance, about 2^-95 of the size, wider than 2^-40 of the distance
// (an earlier rule, lb > best (1 + 2^-40), assumed e <= 2^-40 best and
// could then prune the nearest triangle, one within e_c of best): ties
// among triangles whose intervals overlap may then be broken differently
// from brute force, the value staying within the bounds above
// (tests/fcl_distance_test.cpp, TinyDistancesAgreeWithBruteForceWithinBounds;
// docs/distance.md, section 6.2). Distances in the subnormal range, where
// error_bound is absolute, are covered the same way (the node bound's own
// absolute term, 2^-500 and up, prunes nothing that near anyway).
// DistanceRequest::rel_err and abs_err, when set, loosen the test exactly as
// FCL's traversal does (canStop: lb >= best - abs_err and lb (1 + rel_err) >=
// best): the answer is then within those tolerances of the minimum.
constexpr double kLeafRel = 0x1p-40;

/// A node still to visit, or (leaf) a triangle still to measure, with a
/// lower bound of its distance.
enum Kind : unsigned char {
  kInner,         // an inner node, its box bound
  kLeafBoxBound,  // a leaf, its box bound only
  kLeaf,          // a leaf, the larger of its box and triangle bounds
  kLeafSupport,   // a leaf, with its support bound too
};

struct Entry {
  double lb;
  int node;
  Kind kind;
};

// ORDER. Entries whose bound is positive wait in a heap, smallest bound
// first (best-first: a triangle is measured only if no open entry could hold
// a nearer one). Entries whose bound proves nothing (<= 0 or NaN: the box
// may meet the cylinder) cannot be ordered by it: every bound of a box that
// the cylinder enters is <= 0, and the larger the box the more negative, so
// a heap would expand the whole overlapping part of the tree breadth-first,
// largest boxes first, before its first leaf (about 110 bounds for one
// triangle measured on the colliding poses of bench_fcl_distance's env.obj
// scene). They go on a stack instead and are taken first, depth-first, the
// child with the more negative bound first (it holds the deeper part of
// the overlap), as tricyl::collide's walk: a pose in collision stops at the
// first colliding triangle that walk meets. A pose clear of the mesh must
// visit every such entry whatever the order (none can be pruned while the
// best distance is positive), so the order changes nothing for it: its
// answer is the brute-force minimum whatever the order (PRUNING). A pose in
// collision reports the first colliding triangle the walk meets (any
// colliding triangle, as FCL's traversal).
class EntryQueue {
 public:
  void push(double lb, int node, Kind kind) {
    if (!gt(lb, 0)) {
      stack_.push({lb, node, kind});
      return;
    }
    // Binary min-heap on lb, sifted up in place (a hole moved up to where
    // the new entry belongs).
    std::size_t hole = heap_.size();
    heap_.push({lb, node, kind});
    Entry* h = heap_.data();
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 2;
      if (!(h[parent].lb > lb)) break;
      h[hole] = h[parent];
      hole = parent;
    }
    h[hole] = {lb, node, kind};
  }
  bool empty() const { return stack_.size() == 0 && heap_.size() == 0; }
  /// A lower bound of every open entry's bound (-Inf while the stack holds
  /// any; the queue is not empty).
  double floor() const {
    return stack_.size() == 0 ? heap_.data()[0].lb
                              : -std::numeric_limits<double>::infinity();
  }
  /// The next entry: the top of the stack, else the smallest bound.
  Entry pop() {
    if (stack_.size() != 0) return stack_.pop();
    const Entry top = heap_.data()[0];
    const Entry last = heap_.pop();
    Entry* h = heap_.data();  // (after the pop: it may move the entries)
    const std::size_t n = heap_.size();
    if (n == 0) return top;
    // The root's hole moved down to the bottom along the smaller children
    // (the choice as an add, not a branch: which child is smaller is data),
    // then the last entry sifted up from there (Floyd's bottom-up pop: it
    // rarely climbs, the last entry being among the largest). The bounds
    // in the heap are positive, never NaN.
    std::size_t hole = 0, child = 1;
    while (child + 1 < n) {
      child += std::size_t(h[child + 1].lb < h[child].lb);
      h[hole] = h[child];
      hole = child;
      child = 2 * hole + 1;
    }
    if (child < n) {
      h[hole] = h[child];
      hole = child;
    }
    while (hole > 0) {
      const std::size_t parent = (hole - 1) / 2;
      if (!(h[parent].lb > last.lb)) break;
      h[hole] = h[parent];
      hole = parent;
    }
    h[hole] = last;
    return top;
  }

 private:
  // In place up to 256 entries each (no allocation on a typical call: about
  // 90 bounds a call on bunny.obj).
  InlineStack<Entry, 256> heap_;
  InlineStack<Entry, 256> stack_;
};

class Pruner {
 public:
  explicit Pruner(const fcl::DistanceRequest<double>& request)
      : rel_err_(request.rel_err),
        abs_err_(request.abs_err),
        loose_(request.rel_err > 0 || request.abs_err > 0) {}
  /// The best triangle so far changed: its distance and error bound (the
  /// cut of PRUNING).
  void setBest(double best, double error_bound) {
    best_ = best;
    cut_ = (best + error_bound) * (1 + kLeafRel);
  }
  /// True when a node of lower bound lb cannot hold the nearest triangle.
  bool prune(double lb) const {
    if (gt(lb, cut_)) return true;
    return loose_ && std::isgreaterequal(lb, best_ - abs_err_) &&
           std::isgreaterequal(lb * (1 + rel_err_), best_);
  }

 private:
  double rel_err_, abs_err_;
  bool loose_;
  double best_ = std::numeric_limits<double>::infinity();
  double cut_ = std::numeric_limits<double>::infinity();
};

template <class BV>
bool traverse(const fcl::CollisionGeometry<double>* geom, const Tf& tf_mesh,
              const fcl::CollisionGeometry<double>* cyl_geom_base,
              const Tf& tf_cyl, const fcl::DistanceRequest<double>& request,
              fcl::DistanceResult<double>& result, TraversalStats* stats) {
  using Boxer = BoxOf<BV>;
  const auto& model = static_cast<const fcl::BVHModel<BV>&>(*geom);
  const auto& cyl_geom = static_cast<const fcl::Cylinderd&>(*cyl_geom_base);
  Setup setup;
  if (!prepare<BV, Boxer>(model, tf_mesh, cyl_geom, tf_cyl, 0.0, &setup))
    return false;
  const Local& k = setup.k;
  const Cylinder<double> cyl{cyl_geom.radius, cyl_geom.lz};
  const Pose<double> pose = toPose(tf_cyl);
  Pruner pruner(request);

  // A node's bound. Its children (or its triangle's vertex indices) are
  // asked for at the same time: about half the nodes bounded are expanded
  // later, and their children's fetch has then long been under way.
  const auto bound = [&](int n) {
    const fcl::BVNode<BV>& node = model.getBV(n);
    if (!isLeaf(node)) {
      prefetchNode(model.getBV(leftChild(node)));
      prefetchNode(model.getBV(rightChild(node)));
    } else {
      prefetchTriangle(model.tri_indices[primitiveId(node)]);
    }
    Box box;
    Boxer::get(node.bv, &box);
    return lowerBoundLocal(lowerBound<Boxer::kAligned>(box, k), k);
  };
  const double t_cyl[3] = {pose.t.x, pose.t.y, pose.t.z};
  // A leaf's triangle, in the world frame the Solver sees.
  const auto triangleOf = [&](const fcl::BVNode<BV>& node, V3 p[3]) {
    worldTriangle(model.vertices, model.tri_indices[primitiveId(node)], tf_mesh,
                  setup.raw, p);
  };
  std::size_t tested = 0, skipped = 0, leaves = 0, hits = 0;
  double best = result.min_distance;
  // (A result passed in carries no error bound: its distance is taken as
  // it is.)
  pruner.setBest(best, 0);
  EntryQueue queue;
  // A node's entry carries its box bound; a leaf's triangle gets its own
  // cheap bound (mesh_traversal.h, triangleLowerBound) only when it comes
  // to the top of the queue (most leaves never do), and goes back in with
  // the larger bound if another entry is now first.
  const auto entryOf = [&](int n, double lb) {
    return Entry{lb, n, isLeaf(model.getBV(n)) ? kLeafBoxBound : kInner};
  };
  const auto survives = [&](double lb) {
    ++tested;
    if (!pruner.prune(lb)) return true;
    ++skipped;
    return false;
  };
  // A triangle (world vertices p, lower bound lt of its distance) measured
  // against best; true when it meets the cylinder (the walk then stops).
  const auto measure = [&](int id, const V3 p[3], double lt) {
    const Triangle<double> tri{toVec3(p[0]), toVec3(p[1]), toVec3(p[2])};
    ++leaves;
    // A triangle whose bound proves nothing may meet the cylinder: the
    // Boolean first (tryIntersect: not kDisjoint exactly when tryDistance
    // is not, and several times cheaper), then the distance only if they
    // are apart. A pose in collision stops at such a triangle.
    DistanceResult<double> d;
    if ((gt(lt, 0) || tryIntersect(cyl, pose, tri) == Answer::kDisjoint) &&
        tryDistance(cyl, pose, tri, &d) == Answer::kDisjoint) {
      if (d.distance < best) {
        ++hits;
        best = d.distance;
        pruner.setBest(best, d.error_bound);
        result.update(d.distance, geom, cyl_geom_base, id,
                      fcl::DistanceResult<double>::NONE,
                      V3(d.point_on_triangle.x, d.point_on_triangle.y,
                         d.point_on_triangle.z),
                      V3(d.point_on_cylinder.x, d.point_on_cylinder.y,
                         d.point_on_cylinder.z));
      }
      return false;
    }
    // In collision (or a non-finite world vertex, reported "in collision"
    // as the Solver answers it): minus the contact depth, and both nearest
    // points at the contact point, as Solver::shapeTriangleDistance gives
    // them; the request is then satisfied (FCL stops at min_distance <= 0).
    ContactEstimate<double> est;
    estimateContact(cyl, pose, tri, &est);
    ++hits;
    const V3 pos(est.point.x, est.point.y, est.point.z);
    result.update(-est.depth, geom, cyl_geom_base, id,
                  fcl::DistanceResult<double>::NONE, pos, pos);
    return true;
  };
  const auto report = [&] {
    if (stats == nullptr) return;
    stats->nodes_tested += tested;
    stats->nodes_skipped += skipped;
    stats->leaves += leaves;
    stats->hits += hits;
  };
  // SCALE (mesh_traversal.h): beyond kMaxScale no bound is computed; every
  // triangle is measured, in index order (the brute-force minimum, the
  // first triangle reaching it; the first colliding one stops).
  if (!setup.bounded) {
    for (int id = 0; id < model.num_tris; ++id) {
      V3 p[3];
      worldTriangle(model.vertices, model.tri_indices[id], tf_mesh, setup.raw,
                    p);
      if (measure(id, p, 0.0)) break;
    }
    report();
    return true;
  }
  // `next`: the entry the queue would give next, taken without the round
  // trip through it (the nearer child of the node just expanded, below).
  Entry next{};
  bool have_next = false;
  {
    const double lb = bound(0);
    if (survives(lb)) {
      next = entryOf(0, lb);
      have_next = true;
    }
  }
  while (have_next || !queue.empty()) {
    const Entry e = have_next ? next : queue.pop();
    have_next = false;
    // Taken from the heap, every open entry is at least e.lb: once that
    // cannot improve on best, nothing can. (From the stack, e.lb is <= 0 or
    // NaN and prunes nothing while best > 0; the loop ends at best <= 0.)
    if (pruner.prune(e.lb)) {
      ++skipped;
      if (gt(e.lb, 0)) break;
      continue;
    }
    const fcl::BVNode<BV>& node = model.getBV(e.node);
    // A leaf's world triangle (read once) and the best bound known for it.
    V3 p[3];
    if (e.kind != kInner) triangleOf(node, p);
    double lt = e.lb;
    if (e.kind == kLeafBoxBound || e.kind == kLeaf) {
      const double x[3][3] = {{p[0][0], p[0][1], p[0][2]},
                              {p[1][0], p[1][1], p[1][2]},
                              {p[2][0], p[2][1], p[2][2]}};
      const LocalTriangle local =
          toCylinderFrame(x, pose.R, t_cyl, cyl.radius, k.h);
      // A leaf's bounds, cheapest first, each only when the ones before
      // leave it first in line (best-first: most leaves never are): the
      // triangle's cheap bound, then its support bound (mesh_traversal.h)
      // just before the distance itself, which costs far more (and
      // measures, more often than not, a triangle that does not improve
      // on best: the neighbours of the nearest one).
      const bool support = e.kind == kLeaf;
      const double lb = support ? triangleSupportBound(local, cyl.radius, k.h)
                                : triangleLowerBound(local, cyl.radius, k.h);
      if (gt(lb, lt)) lt = lb;
      if (pruner.prune(lt)) {
        ++skipped;
        continue;
      }
      // Back in line when another entry is now first. (Not when lt proves
      // nothing: it would come straight back.)
      if (gt(lt, 0) && gt(lt, e.lb) && !queue.empty() &&
          gt(lt, queue.floor())) {
        queue.push(lt, e.node, support ? kLeafSupport : kLeaf);
        continue;
      }
      if (!support && gt(lt, 0)) {
        const double ls = triangleSupportBound(local, cyl.radius, k.h);
        if (gt(ls, lt)) {
          if (pruner.prune(ls)) {
            ++skipped;
            continue;
          }
          if (!queue.empty() && gt(ls, queue.floor())) {
            queue.push(ls, e.node, kLeafSupport);
            continue;
          }
          lt = ls;
        }
      }
    }
    if (e.kind == kInner) {
      const int left = leftChild(node), right = rightChild(node);
      const double lb_left = bound(left), lb_right = bound(right);
      // ORDER: the child with the smaller bound (more negative: deeper in
      // the overlap) first. It is what the queue would give next when its
      // bound proves nothing (the top of the stack) or is at most every
      // open bound (the top of the heap, the stack empty): then it is taken
      // directly, else queued.
      const bool left_first = std::isless(lb_left, lb_right);
      const int first = left_first ? left : right,
                second = left_first ? right : left;
      const double lb_first = left_first ? lb_left : lb_right;
      const double lb_second = left_first ? lb_right : lb_left;
      if (survives(lb_second)) {
        const Entry f = entryOf(second, lb_second);
        queue.push(f.lb, f.node, f.kind);
      }
      if (survives(lb_first)) {
        next = entryOf(first, lb_first);
        if (!gt(lb_first, 0) || queue.empty() || !gt(lb_first, queue.floor()))
          have_next = true;
        else
          queue.push(next.lb, next.node, next.kind);
      }
      continue;
    }
    if (measure(primitiveId(node), p, lt)) break;
  }
  report();
  return true;
}

}  // namespace

bool distanceMeshCylinder(const fcl::CollisionGeometry<double>* g1,
                          const fcl::Transform3<double>& tf1,
                          const fcl::CollisionGeometry<double>* g2,
                          const fcl::Transform3<double>& tf2,
                          const fcl::DistanceRequest<double>& request,
                          fcl::DistanceResult<double>& result,
                          TraversalStats* stats) {
  if (g1 == nullptr || g2 == nullptr) return false;
  // FCL runs the mesh as o1 whatever the argument order (fcl::distance
  // swaps a shape/BVH pair): so does this.
  if (g2->getObjectType() == fcl::OT_BVH &&
      g1->getNodeType() == fcl::GEOM_CYLINDER)
    return distanceMeshCylinder(g2, tf2, g1, tf1, request, result, stats);
  if (g1->getObjectType() != fcl::OT_BVH ||
      g2->getNodeType() != fcl::GEOM_CYLINDER)
    return false;
  if (request.isSatisfied(result)) return true;  // as FCL's distancers
  return dispatchBv(g1->getNodeType(), [&](auto tag) {
    using BV = typename decltype(tag)::type;
    return traverse<BV>(g1, tf1, g2, tf2, request, result, stats);
  });
}

}  // namespace tricyl
