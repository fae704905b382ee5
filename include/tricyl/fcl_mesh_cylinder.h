// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// tricyl's own traversal of an FCL BVHModel against a Cylinder: what
/// tricyl::collide runs for a mesh/cylinder pair instead of FCL's traversal
/// (fcl_solver.h). CMake target tricyl::fcl.
///
/// ## Contract
/// - Same answer as fcl::collide(mesh, cylinder, &tricyl::Solver, ...): a
///   triangle collides iff tricyl::tryIntersect says so for the world-frame
///   triangle FCL would hand the solver (fcl_solver.h, FRAMES: tf_mesh * v,
///   or v itself for AABB/KDOP meshes whose transform FCL takes for the
///   identity), so the Boolean is exact for those points. Touching counts.
/// - Contacts: one per colliding triangle, Contact(mesh, cylinder,
///   triangle index, Contact::NONE), at most request.num_max_contacts in
///   total (counting the contacts already in `result`), in the order of a
///   depth-first walk of the model's own tree. A query that can stop early
///   (num_max_contacts, less the contacts already in `result`, below the
///   model's triangle count) takes first, of two children that may both
///   hold a hit, the one whose box centre is nearer the cylinder's centre
///   (ties: the left one); any other query takes the left child first, as
///   FCL's traversal, and its contacts come in FCL's order. So when more
///   triangles collide than num_max_contacts allows, the ones reported may
///   not be FCL's (FCL's contract bounds the number of contacts, not which;
///   its own choice depends on the BV type's tree). With
///   request.enable_contact, pos/normal/penetration_depth are
///   tricyl::estimateContact's, exactly as the Solver stores them (normal from
///   the mesh toward the cylinder). Either argument order: like FCL, the
///   mesh is always o1 of the contacts.
/// - Where the two can differ besides the order: (a) FCL's floating-point BV
///   tests may prune a node holding a triangle that touches the cylinder
///   (rounding); the node test here is certified, so such triangles ARE
///   reported. (b) For AABB and KDOP meshes with a non-identity transform
///   FCL rebuilds the tree around the moved vertices on every call; the set
///   of colliding triangles is the same.
///
/// ## Method
/// 1. The cylinder is moved into the mesh frame once (centre, unit axis).
/// 2. Depth-first over the model's BVH with an explicit stack, the child
///    nearer the cylinder first when the walk can stop early (above;
///    src/fcl/mesh_collide.cpp, ORDER: 13-20 % fewer instructions a
///    first-hit call on grazing poses than the left child first). A node is
///    skipped only when a separating axis proves its box (the OBB of an OBB,
///    kIOS or OBBRSS node, the box around an RSS, the axis-aligned slabs of
///    an AABB or KDOP) disjoint from the cylinder: the cylinder's axis, the
///    three box axes (with the cylinder's exact support along them) and the
///    distance from the box centre to the axis line. Every comparison
///    carries a margin that covers all rounding and the departure of both
///    rotations from orthonormal (derivation in src/fcl/mesh_traversal.h),
///    so the test never skips a node with a colliding triangle.
///    A node that passes with at most 2 triangles below it sends them to
///    the next step untested (src/fcl/mesh_collide.cpp, kUntestedSubtree).
/// 3. The surviving leaves' triangles are queued in blocks of up to 64,
///    moved to the world frame together and decided one by one by
///    tryIntersect (the batch kernel's vertex-code cull rejects few leaves
///    that passed the node test, and cost more than it saved). Blocks are
///    flushed in traversal order, and the walk stops as soon as
///    num_max_contacts is reached.
///
/// ASSUMED: each node's BV contains its triangles up to rounding, as FCL's
/// builders (fit, refit) make it for finite vertices; FCL's own traversal
/// relies on the same. A model whose root box is not finite or has axes
/// that are not orthonormal (what a NaN or Inf vertex does to FCL's fit) is
/// not handled (below).
///
/// NOT HANDLED HERE (collideMeshCylinder returns false and touches nothing;
/// tricyl::collide then runs fcl::collide with tricyl::Solver, whose answers
/// are the same): request.enable_cost, num_max_contacts == 0, a model that
/// is not a built triangle mesh or whose root box is spoilt (above), a
/// geometry that is not occupied, NaN/Inf or negative cylinder sizes,
/// non-finite transforms, rotations far from orthonormal
/// (sum |R^T R - I| > 2^-20). A triangle the traversal reaches whose world
/// coordinates are not finite (tf * v overflowed) is reported in collision,
/// as the Solver answers it. No floating-point exception is raised by the
/// traversal itself (quiet comparisons), whatever the input.
///
/// THREADS: reentrant; no state outside the call.
#pragma once

#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/collision_request.h>
#include <fcl/narrowphase/collision_result.h>
#include <fcl/narrowphase/distance_request.h>
#include <fcl/narrowphase/distance_result.h>

#include <cstddef>

namespace tricyl {

/// What one collideMeshCylinder call did (statistics; never changes an
/// answer).
struct TraversalStats {
  std::size_t nodes_tested = 0;   ///< BV nodes given to the node test
  std::size_t nodes_skipped = 0;  ///< nodes the node test proved disjoint
  std::size_t leaves = 0;         ///< triangles given to the kernel
  std::size_t hits = 0;           ///< triangles found colliding
};

/// Runs the traversal above when (g1, g2) is a BVHModel/Cylinder pair (either
/// order) it handles; then returns true with *num_contacts =
/// result.numContacts(). Otherwise returns false and touches nothing.
bool collideMeshCylinder(const fcl::CollisionGeometry<double>* g1,
                         const fcl::Transform3<double>& tf1,
                         const fcl::CollisionGeometry<double>* g2,
                         const fcl::Transform3<double>& tf2,
                         const fcl::CollisionRequest<double>& request,
                         fcl::CollisionResult<double>& result,
                         std::size_t* num_contacts,
                         TraversalStats* stats = nullptr);

/// The same traversal for the margin collide (fcl_solver.h, MARGIN
/// COLLIDE): a triangle counts iff tricyl::tryWithinDistance(cylinder, pose,
/// triangle, margin) is not kDisjoint (the closed margin-neighbourhood of the
/// cylinder meets it: exact), the node test is run for that neighbourhood
/// (margin added to every support: certified, see src/fcl/mesh_traversal.h),
/// contacts as above, except that a triangle within the margin that does not
/// touch the cylinder gets, with request.enable_contact, the midpoint of the
/// nearest points, the unit normal from the triangle's nearest point toward
/// the cylinder's, and penetration_depth = -distance (in [-margin, 0)).
/// margin = 0 is collideMeshCylinder. Also returns false (touching nothing)
/// for a margin that is negative, NaN or infinite.
bool collideMeshCylinderWithin(const fcl::CollisionGeometry<double>* g1,
                               const fcl::Transform3<double>& tf1,
                               const fcl::CollisionGeometry<double>* g2,
                               const fcl::Transform3<double>& tf2,
                               const fcl::CollisionRequest<double>& request,
                               fcl::CollisionResult<double>& result,
                               double margin, std::size_t* num_contacts,
                               TraversalStats* stats = nullptr);

/// tricyl's own distance traversal of a BVHModel/Cylinder pair (either
/// order), what tricyl::distance (fcl_solver.h) runs for it in double.
///
/// Contract: result.min_distance becomes the smallest, over the triangles,
/// of what Solver::shapeTriangleDistance gives for the world triangle FCL
/// would hand it (tf_mesh * v, or v for AABB/KDOP meshes whose transform FCL
/// takes for the identity, as in collideMeshCylinder), if smaller than the
/// value already in `result` (DistanceResult::update): tricyl::distance's
/// certified distance for a disjoint triangle, and for a colliding one minus
/// estimateContact's depth, where the walk stops (FCL stops at
/// min_distance <= 0 too). Without rel_err/abs_err in the request the
/// nearest triangle is always measured (a triangle is skipped only when
/// certainly farther than the best one: src/fcl/mesh_distance.cpp,
/// PRUNING) and the value is the brute-force minimum over all the
/// triangles, except that ties within tricyl::distance's error bounds may
/// be broken differently (then within the brute-force triangle's bound of
/// it; docs/distance.md, section 6.2); with them, within those tolerances
/// as in FCL. result.o1 is the mesh, b1 the triangle,
/// nearest_points[0] on the triangle and [1] on the cylinder, world frame
/// (FCL's convention in either argument order). Signed distance is the
/// caller's (tricyl::distance): this never reads enable_signed_distance.
/// Returns false, touching nothing, for what collideMeshCylinder does not
/// handle (its NOT HANDLED list, except the collide-only request fields).
/// stats: nodes_tested = lower bounds computed, nodes_skipped = nodes
/// pruned, leaves = triangles measured, hits = improvements of the minimum.
bool distanceMeshCylinder(const fcl::CollisionGeometry<double>* g1,
                          const fcl::Transform3<double>& tf1,
                          const fcl::CollisionGeometry<double>* g2,
                          const fcl::Transform3<double>& tf2,
                          const fcl::DistanceRequest<double>& request,
                          fcl::DistanceResult<double>& result,
                          TraversalStats* stats = nullptr);

}  // namespace tricyl
