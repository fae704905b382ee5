// SPDX-License-Identifier: BSD-3-Clause
// tricyl::Solver<S>'s members, for any S (fcl_solver.h). Included by the two
// files that instantiate them: fcl_solver.cpp (double) and
// fcl_solver_float.cpp (float), each with FCL's collision and distance
// matrices for its Solver (see fcl_solver.h, COMPILE TIME).
#pragma once

#include <fcl/geometry/bvh/BVH_model.h>

#include <limits>

#include "margin_contact.h"
#include "mesh_traversal.h"
#include "tricyl/fcl_adapters.h"
#include "tricyl/fcl_contact.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/sphere_cylinder.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"
#include "tricyl/triangle_cylinder_margin.h"

namespace tricyl {
namespace solver_detail {

template <class S>
fcl::Vector3<S> toFcl(const Vec3<S>& v) {
  return fcl::Vector3<S>(v.x, v.y, v.z);
}

/// The one body behind every overload: world-frame triangle vs posed
/// cylinder. The Boolean is the kernel's (kInvalidInput counts as "in
/// collision", fcl_solver.h); contact data only on request and only when
/// the answer is not "disjoint".
template <class S>
bool cylinderVsWorldTriangle(const fcl::Cylinder<S>& s,
                             const fcl::Transform3<S>& tf,
                             const fcl::Vector3<S>& p1,
                             const fcl::Vector3<S>& p2,
                             const fcl::Vector3<S>& p3,
                             fcl::Vector3<S>* contact_point, S* depth,
                             fcl::Vector3<S>* normal) {
  const Cylinder<S> cyl = toCylinder(s);
  const Pose<S> pose = toPose(tf);
  const Triangle<S> tri{toVec3(p1), toVec3(p2), toVec3(p3)};
  if (contact_point == nullptr && depth == nullptr && normal == nullptr)
    return tryIntersect(cyl, pose, tri) != Answer::kDisjoint;
  ContactEstimate<S> est;
  if (estimateContact(cyl, pose, tri, &est) == Answer::kDisjoint) return false;
  if (contact_point != nullptr) *contact_point = toFcl(est.point);
  if (depth != nullptr) *depth = est.depth;
  if (normal != nullptr) *normal = toFcl(est.normal);
  return true;
}

/// TriangleP at tf_tri vs Cylinder at tf_cyl. `tri_first` says which shape
/// is the first argument of the caller, so the normal points from the first
/// to the second (libccd gives cylinder -> triangle).
template <class S>
bool cylinderVsTriangleP(const fcl::Cylinder<S>& cyl,
                         const fcl::Transform3<S>& tf_cyl,
                         const fcl::TriangleP<S>& tri,
                         const fcl::Transform3<S>& tf_tri, bool tri_first,
                         fcl::Vector3<S>* contact_point, S* depth,
                         fcl::Vector3<S>* normal) {
  // Same expression as FCL uses for mesh vertices (fcl_solver.h, FRAMES).
  const fcl::Vector3<S> a = tf_tri * tri.a;
  const fcl::Vector3<S> b = tf_tri * tri.b;
  const fcl::Vector3<S> c = tf_tri * tri.c;
  const bool hit = cylinderVsWorldTriangle(cyl, tf_cyl, a, b, c, contact_point,
                                           depth, normal);
  if (hit && tri_first && normal != nullptr) *normal = -*normal;
  return hit;
}

template <class S>
bool cylinderVsTrianglePContacts(const fcl::Cylinder<S>& cyl,
                                 const fcl::Transform3<S>& tf_cyl,
                                 const fcl::TriangleP<S>& tri,
                                 const fcl::Transform3<S>& tf_tri,
                                 bool tri_first,
                                 std::vector<fcl::ContactPoint<S>>* contacts) {
  if (contacts == nullptr)
    return cylinderVsTriangleP(cyl, tf_cyl, tri, tf_tri, tri_first,
                               static_cast<fcl::Vector3<S>*>(nullptr),
                               static_cast<S*>(nullptr),
                               static_cast<fcl::Vector3<S>*>(nullptr));
  fcl::Vector3<S> point, normal;
  S depth;
  if (!cylinderVsTriangleP(cyl, tf_cyl, tri, tf_tri, tri_first, &point, &depth,
                           &normal))
    return false;
  contacts->emplace_back(normal, point, depth);
  return true;
}

/// Sphere at tf_sphere vs Cylinder at tf_cyl, exact (sphere_cylinder.h):
/// the centre is the sphere's translation, as FCL uses it; invalid input
/// counts as a collision (fcl_solver.h).
template <class S>
bool sphereVsCylinder(const fcl::Sphere<S>& sphere,
                      const fcl::Transform3<S>& tf_sphere,
                      const fcl::Cylinder<S>& cyl,
                      const fcl::Transform3<S>& tf_cyl) {
  const Sphere<S> ball{toVec3<S>(tf_sphere.translation()), sphere.radius};
  return tryIntersect(toCylinder(cyl), toPose(tf_cyl), ball) !=
         Answer::kDisjoint;
}

/// The one body behind every distance overload: world-frame triangle vs
/// posed cylinder (fcl_solver.h, DISTANCE). Returns true (disjoint) with
/// tricyl::distance's distance and points, or false (they meet, or invalid
/// input: "in collision") with minus estimateContact's depth and its point
/// as both points.
template <class S>
bool cylinderVsWorldTriangleDistance(const fcl::Cylinder<S>& s,
                                     const fcl::Transform3<S>& tf,
                                     const fcl::Vector3<S>& p1,
                                     const fcl::Vector3<S>& p2,
                                     const fcl::Vector3<S>& p3, S* dist,
                                     fcl::Vector3<S>* on_cylinder,
                                     fcl::Vector3<S>* on_triangle) {
  const Cylinder<S> cyl = toCylinder(s);
  const Pose<S> pose = toPose(tf);
  const Triangle<S> tri{toVec3(p1), toVec3(p2), toVec3(p3)};
  DistanceResult<S> d;
  if (tryDistance(cyl, pose, tri, &d) == Answer::kDisjoint) {
    if (dist != nullptr) *dist = d.distance;
    if (on_cylinder != nullptr) *on_cylinder = toFcl(d.point_on_cylinder);
    if (on_triangle != nullptr) *on_triangle = toFcl(d.point_on_triangle);
    return true;
  }
  ContactEstimate<S> est;
  if (estimateContact(cyl, pose, tri, &est) == Answer::kDisjoint) {
    // Not reached: the zero test of tryDistance is the exact Boolean that
    // estimateContact asks too. A finite "touching" answer all the same.
    est.point = d.point_on_cylinder;
    est.depth = kMinDepth<S>;
  }
  if (dist != nullptr) *dist = -est.depth;
  if (on_cylinder != nullptr) *on_cylinder = toFcl(est.point);
  if (on_triangle != nullptr) *on_triangle = toFcl(est.point);
  return false;
}

/// TriangleP at tf_tri vs Cylinder at tf_cyl, distance; p_first / p_second
/// on the caller's first and second shapes.
template <class S>
bool cylinderVsTrianglePDistance(const fcl::Cylinder<S>& cyl,
                                 const fcl::Transform3<S>& tf_cyl,
                                 const fcl::TriangleP<S>& tri,
                                 const fcl::Transform3<S>& tf_tri,
                                 bool tri_first, S* dist,
                                 fcl::Vector3<S>* p_first,
                                 fcl::Vector3<S>* p_second) {
  const fcl::Vector3<S> a = tf_tri * tri.a;
  const fcl::Vector3<S> b = tf_tri * tri.b;
  const fcl::Vector3<S> c = tf_tri * tri.c;
  fcl::Vector3<S> on_cyl, on_tri;
  const bool apart = cylinderVsWorldTriangleDistance(cyl, tf_cyl, a, b, c, dist,
                                                     &on_cyl, &on_tri);
  if (p_first != nullptr) *p_first = tri_first ? on_tri : on_cyl;
  if (p_second != nullptr) *p_second = tri_first ? on_cyl : on_tri;
  return apart;
}

/// fcl::distance for a BVHModel<BV> (o1) and a Cylinder (o2) where FCL 0.7
/// has no usable traversal: OBB and KDOP, whose BV distance prints "not
/// implemented" and returns 0, and AABB, whose generic traversal does not
/// compile (FCL leaves these entries empty). In double,
/// tricyl's own traversal (distanceMeshCylinder); otherwise, and for models
/// it does not handle, every triangle through Solver::shapeTriangleDistance
/// (the world vertices as FCL forms them: tf * v, or v for a KDOP mesh whose
/// transform is the identity), stopping at min_distance <= 0.
template <class BV>
typename BV::S meshCylinderDistance(
    const fcl::CollisionGeometry<typename BV::S>* o1,
    const fcl::Transform3<typename BV::S>& tf1,
    const fcl::CollisionGeometry<typename BV::S>* o2,
    const fcl::Transform3<typename BV::S>& tf2,
    const Solver<typename BV::S>* nsolver,
    const fcl::DistanceRequest<typename BV::S>& request,
    fcl::DistanceResult<typename BV::S>& result) {
  using S = typename BV::S;
  if (request.isSatisfied(result)) return result.min_distance;
  if constexpr (std::is_same_v<S, double>) {
    if (distanceMeshCylinder(o1, tf1, o2, tf2, request, result))
      return result.min_distance;
  }
  const auto& model = static_cast<const fcl::BVHModel<BV>&>(*o1);
  const auto& cyl = static_cast<const fcl::Cylinder<S>&>(*o2);
  if (model.getModelType() != fcl::BVH_MODEL_TRIANGLES)
    return result.min_distance;
  // FCL moves AABB/KDOP vertices unless the transform is the identity
  // (fcl_solver.h, FRAMES); an OBB mesh's triangles go through tf1 * v.
  const bool raw =
      !std::is_same_v<BV, fcl::OBB<S>> && tf1.matrix().isIdentity();
  for (int i = 0; i < model.num_tris && !request.isSatisfied(result); ++i) {
    const fcl::Triangle& t = model.tri_indices[i];
    fcl::Vector3<S> p[3];
    for (int j = 0; j < 3; ++j)
      p[j] = raw ? model.vertices[t[j]]
                 : fcl::Vector3<S>(tf1 * model.vertices[t[j]]);
    S d;
    fcl::Vector3<S> on_cyl, on_tri;
    nsolver->shapeTriangleDistance(cyl, tf2, p[0], p[1], p[2], &d, &on_cyl,
                                   &on_tri);
    result.update(d, o1, o2, i, fcl::DistanceResult<S>::NONE, on_tri, on_cyl);
  }
  return result.min_distance;
}

/// Puts TriangleP/Cylinder (both orders) into Solver<S>'s own collision and
/// distance tables, and the mesh/Cylinder distance entries FCL 0.7 leaves
/// empty (AABB, OBB, KDOP: meshCylinderDistance; FCL's generic
/// BVHShapeDistancer, commented out of its table, does not compile). FCL's
/// generic ShapeShapeCollide and ShapeShapeDistance call Solver's overloads
/// above.
template <class S>
bool registerTrianglePairs() {
  auto& table = fcl::getCollisionFunctionLookTable<Solver<S>>();
  table.collision_matrix[fcl::GEOM_TRIANGLE][fcl::GEOM_CYLINDER] =
      &fcl::detail::ShapeShapeCollide<fcl::TriangleP<S>, fcl::Cylinder<S>,
                                      Solver<S>>;
  table.collision_matrix[fcl::GEOM_CYLINDER][fcl::GEOM_TRIANGLE] =
      &fcl::detail::ShapeShapeCollide<fcl::Cylinder<S>, fcl::TriangleP<S>,
                                      Solver<S>>;
  auto& dist = fcl::getDistanceFunctionLookTable<Solver<S>>();
  dist.distance_matrix[fcl::GEOM_TRIANGLE][fcl::GEOM_CYLINDER] =
      &fcl::detail::ShapeShapeDistance<fcl::TriangleP<S>, fcl::Cylinder<S>,
                                       Solver<S>>;
  dist.distance_matrix[fcl::GEOM_CYLINDER][fcl::GEOM_TRIANGLE] =
      &fcl::detail::ShapeShapeDistance<fcl::Cylinder<S>, fcl::TriangleP<S>,
                                       Solver<S>>;
  dist.distance_matrix[fcl::BV_AABB][fcl::GEOM_CYLINDER] =
      &meshCylinderDistance<fcl::AABB<S>>;
  dist.distance_matrix[fcl::BV_OBB][fcl::GEOM_CYLINDER] =
      &meshCylinderDistance<fcl::OBB<S>>;
  dist.distance_matrix[fcl::BV_KDOP16][fcl::GEOM_CYLINDER] =
      &meshCylinderDistance<fcl::KDOP<S, 16>>;
  dist.distance_matrix[fcl::BV_KDOP18][fcl::GEOM_CYLINDER] =
      &meshCylinderDistance<fcl::KDOP<S, 18>>;
  dist.distance_matrix[fcl::BV_KDOP24][fcl::GEOM_CYLINDER] =
      &meshCylinderDistance<fcl::KDOP<S, 24>>;
  return true;
}

/// FCL's signed-distance step (fcl::distance, distance-inl.h) for a pair
/// found in collision: collide with contacts (tricyl::collide, the same
/// contacts as fcl::collide with Solver) and minus the largest depth, both
/// nearest points at that contact.
template <class S>
void signedFromContacts(const fcl::CollisionGeometry<S>* g1,
                        const fcl::Transform3<S>& tf1,
                        const fcl::CollisionGeometry<S>* g2,
                        const fcl::Transform3<S>& tf2,
                        const fcl::DistanceRequest<S>& request,
                        fcl::DistanceResult<S>& result) {
  fcl::CollisionRequest<S> creq;
  creq.enable_contact = true;
  fcl::CollisionResult<S> cres;
  tricyl::collide(g1, tf1, g2, tf2, creq, cres);
  if (cres.numContacts() == 0) return;  // not reached: the leaf collided
  std::size_t index = 0;
  for (std::size_t i = 1; i < cres.numContacts(); ++i)
    if (cres.getContact(i).penetration_depth >
        cres.getContact(index).penetration_depth)
      index = i;
  result.min_distance = -cres.getContact(index).penetration_depth;
  if (request.enable_nearest_points) {
    result.nearest_points[0] = cres.getContact(index).pos;
    result.nearest_points[1] = cres.getContact(index).pos;
  }
}

/// Contact data of a margin collide for a world triangle (fcl_solver.h,
/// MARGIN COLLIDE): the collide contact when they meet, else the nearest
/// points' midpoint, the normal from the triangle toward the cylinder,
/// depth = -distance. `cyl_first` flips the normal to point from the first
/// object to the second.
template <class S>
fcl::Contact<S> marginContactFor(const fcl::CollisionGeometry<S>* o1,
                                 const fcl::CollisionGeometry<S>* o2, int b1,
                                 int b2, const Cylinder<S>& cyl,
                                 const Pose<S>& pose, const Triangle<S>& tri,
                                 bool cyl_first, bool with_data) {
  if (!with_data) return fcl::Contact<S>(o1, o2, b1, b2);
  ContactEstimate<S> est;
  if (estimateContact(cyl, pose, tri, &est) != Answer::kDisjoint) {
    // estimateContact's normal points from the cylinder to the triangle.
    const fcl::Vector3<S> n = toFcl(est.normal);
    return fcl::Contact<S>(o1, o2, b1, b2, toFcl(est.point),
                           cyl_first ? n : fcl::Vector3<S>(-n), est.depth);
  }
  const margin_detail::MarginContact<S> c =
      margin_detail::marginContact(cyl, pose, tri);
  return fcl::Contact<S>(o1, o2, b1, b2, c.pos,
                         cyl_first ? fcl::Vector3<S>(-c.normal) : c.normal,
                         c.depth);
}

/// Margin collide of a BVHModel<BV> (g1) and a Cylinder (g2) triangle by
/// triangle (float models, and double models the traversal does not
/// handle): exact per triangle, no pruning.
template <class BV>
void collideWithinEveryTriangle(
    const fcl::CollisionGeometry<typename BV::S>* g1,
    const fcl::Transform3<typename BV::S>& tf1,
    const fcl::CollisionGeometry<typename BV::S>* g2,
    const fcl::Transform3<typename BV::S>& tf2,
    const fcl::CollisionRequest<typename BV::S>& request,
    fcl::CollisionResult<typename BV::S>& result, typename BV::S margin) {
  using S = typename BV::S;
  const auto& model = static_cast<const fcl::BVHModel<BV>&>(*g1);
  const auto& fcyl = static_cast<const fcl::Cylinder<S>&>(*g2);
  const Cylinder<S> cyl = toCylinder(fcyl);
  const Pose<S> pose = toPose(tf2);
  constexpr bool kAligned = std::is_same_v<BV, fcl::AABB<S>> ||
                            std::is_same_v<BV, fcl::KDOP<S, 16>> ||
                            std::is_same_v<BV, fcl::KDOP<S, 18>> ||
                            std::is_same_v<BV, fcl::KDOP<S, 24>>;
  const bool raw = kAligned && tf1.matrix().isIdentity();
  for (int i = 0; i < model.num_tris && !request.isSatisfied(result); ++i) {
    const fcl::Triangle& t = model.tri_indices[i];
    Vec3<S> p[3];
    for (int j = 0; j < 3; ++j)
      p[j] = toVec3<S>(raw ? model.vertices[t[j]]
                           : fcl::Vector3<S>(tf1 * model.vertices[t[j]]));
    const Triangle<S> tri{p[0], p[1], p[2]};
    if (tryWithinDistance(cyl, pose, tri, margin) == Answer::kDisjoint)
      continue;
    result.addContact(marginContactFor<S>(g1, g2, i, fcl::Contact<S>::NONE, cyl,
                                          pose, tri, false,
                                          request.enable_contact));
  }
}

}  // namespace solver_detail

namespace detail {

template <class S>
S distanceImpl(const fcl::CollisionGeometry<S>* g1,
               const fcl::Transform3<S>& tf1,
               const fcl::CollisionGeometry<S>* g2,
               const fcl::Transform3<S>& tf2,
               const fcl::DistanceRequest<S>& request,
               fcl::DistanceResult<S>& result) {
  if (request.gjk_solver_type != fcl::GST_LIBCCD &&
      !answersDistancePair(g1, g2))
    return fcl::distance(g1, tf1, g2, tf2, request, result);
  if constexpr (std::is_same_v<S, double>) {  // mesh/cylinder: own traversal
    if (distanceMeshCylinder(g1, tf1, g2, tf2, request, result)) {
      if (request.enable_signed_distance && result.min_distance < 0)
        solver_detail::signedFromContacts(g1, tf1, g2, tf2, request, result);
      return result.min_distance;
    }
  }
  Solver<S> solver;
  solver.distance_tolerance = request.distance_tolerance;
  fcl::distance(g1, tf1, g2, tf2, &solver, request, result);
  return result.min_distance;
}

template <class S>
std::size_t collideWithinImpl(const fcl::CollisionGeometry<S>* g1,
                              const fcl::Transform3<S>& tf1,
                              const fcl::CollisionGeometry<S>* g2,
                              const fcl::Transform3<S>& tf2,
                              const fcl::CollisionRequest<S>& request,
                              fcl::CollisionResult<S>& result, S margin) {
  if (request.isSatisfied(result)) return result.numContacts();
  if constexpr (std::is_same_v<S, double>) {  // mesh/cylinder: own traversal
    std::size_t n = 0;
    if (collideMeshCylinderWithin(g1, tf1, g2, tf2, request, result, margin,
                                  &n))
      return n;
  }
  const fcl::NODE_TYPE t1 = g1->getNodeType(), t2 = g2->getNodeType();
  // Mesh/cylinder, either order (the mesh is o1 of the contacts, as FCL).
  if ((g1->getObjectType() == fcl::OT_BVH && t2 == fcl::GEOM_CYLINDER) ||
      (g2->getObjectType() == fcl::OT_BVH && t1 == fcl::GEOM_CYLINDER)) {
    const bool mesh_first = g1->getObjectType() == fcl::OT_BVH;
    const auto* mesh = mesh_first ? g1 : g2;
    const auto* cyl = mesh_first ? g2 : g1;
    const auto& tf_mesh = mesh_first ? tf1 : tf2;
    const auto& tf_cyl = mesh_first ? tf2 : tf1;
    traversal::dispatchBv<S>(mesh->getNodeType(), [&](auto tag) {
      using BV = typename decltype(tag)::type;
      solver_detail::collideWithinEveryTriangle<BV>(mesh, tf_mesh, cyl, tf_cyl,
                                                    request, result, margin);
      return true;
    });
    return result.numContacts();
  }
  // TriangleP/cylinder, either order.
  if ((t1 == fcl::GEOM_TRIANGLE && t2 == fcl::GEOM_CYLINDER) ||
      (t2 == fcl::GEOM_TRIANGLE && t1 == fcl::GEOM_CYLINDER)) {
    const bool tri_first = t1 == fcl::GEOM_TRIANGLE;
    const auto& tp =
        static_cast<const fcl::TriangleP<S>&>(tri_first ? *g1 : *g2);
    const auto& fc =
        static_cast<const fcl::Cylinder<S>&>(tri_first ? *g2 : *g1);
    const auto& tf_tri = tri_first ? tf1 : tf2;
    const auto& tf_cyl = tri_first ? tf2 : tf1;
    const Triangle<S> tri{toVec3<S>(tf_tri * tp.a), toVec3<S>(tf_tri * tp.b),
                          toVec3<S>(tf_tri * tp.c)};
    const Cylinder<S> cyl = toCylinder(fc);
    const Pose<S> pose = toPose(tf_cyl);
    if (tryWithinDistance(cyl, pose, tri, margin) != Answer::kDisjoint)
      result.addContact(solver_detail::marginContactFor<S>(
          g1, g2, fcl::Contact<S>::NONE, fcl::Contact<S>::NONE, cyl, pose, tri,
          !tri_first, request.enable_contact));
    return result.numContacts();
  }
  // Every other pair: the plain collide, then FCL's distance with Solver
  // (libccd GJK for these pairs: not exact) against the margin.
  const std::size_t before = result.numContacts();
  tricyl::collide(g1, tf1, g2, tf2, request, result);
  if (result.numContacts() > before || request.isSatisfied(result))
    return result.numContacts();
  Solver<S> solver;
  solver.distance_tolerance = request.gjk_tolerance;
  fcl::DistanceRequest<S> dreq(true);
  fcl::DistanceResult<S> dres;
  fcl::distance(g1, tf1, g2, tf2, &solver, dreq, dres);
  if (dres.min_distance >= 0 && dres.min_distance <= margin) {
    if (!request.enable_contact) {
      result.addContact(fcl::Contact<S>(g1, g2, dres.b1, dres.b2));
    } else {
      const fcl::Vector3<S> n = dres.nearest_points[1] - dres.nearest_points[0];
      const S len = n.norm();
      result.addContact(fcl::Contact<S>(
          g1, g2, dres.b1, dres.b2,
          S(0.5) * (dres.nearest_points[0] + dres.nearest_points[1]),
          len > 0 ? fcl::Vector3<S>(n / len) : fcl::Vector3<S>(0, 0, 1),
          -dres.min_distance));
    }
  }
  return result.numContacts();
}

}  // namespace detail

template <class S>
Solver<S>::Solver() : Base() {
  // Thread-safe once (a function-local static); every path into the table
  // goes through a constructed Solver, so it is always registered in time.
  static const bool registered = solver_detail::registerTrianglePairs<S>();
  (void)registered;
}

template <class S>
bool Solver<S>::shapeTriangleIntersect(
    const fcl::Cylinder<S>& s, const fcl::Transform3<S>& tf,
    const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2,
    const fcl::Vector3<S>& P3, fcl::Vector3<S>* contact_points,
    S* penetration_depth, fcl::Vector3<S>* normal) const {
  return solver_detail::cylinderVsWorldTriangle(
      s, tf, P1, P2, P3, contact_points, penetration_depth, normal);
}

template <class S>
bool Solver<S>::shapeTriangleIntersect(
    const fcl::Cylinder<S>& s, const fcl::Transform3<S>& tf1,
    const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2,
    const fcl::Vector3<S>& P3, const fcl::Transform3<S>& tf2,
    fcl::Vector3<S>* contact_points, S* penetration_depth,
    fcl::Vector3<S>* normal) const {
  // Mesh frame -> world, as FCL's initialize() does for AABB meshes.
  const fcl::Vector3<S> a = tf2 * P1;
  const fcl::Vector3<S> b = tf2 * P2;
  const fcl::Vector3<S> c = tf2 * P3;
  return solver_detail::cylinderVsWorldTriangle(s, tf1, a, b, c, contact_points,
                                                penetration_depth, normal);
}

template <class S>
bool Solver<S>::shapeTriangleDistance(const fcl::Cylinder<S>& s,
                                      const fcl::Transform3<S>& tf,
                                      const fcl::Vector3<S>& P1,
                                      const fcl::Vector3<S>& P2,
                                      const fcl::Vector3<S>& P3, S* dist,
                                      fcl::Vector3<S>* p1,
                                      fcl::Vector3<S>* p2) const {
  return solver_detail::cylinderVsWorldTriangleDistance(s, tf, P1, P2, P3, dist,
                                                        p1, p2);
}

template <class S>
bool Solver<S>::shapeTriangleDistance(
    const fcl::Cylinder<S>& s, const fcl::Transform3<S>& tf1,
    const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2,
    const fcl::Vector3<S>& P3, const fcl::Transform3<S>& tf2, S* dist,
    fcl::Vector3<S>* p1, fcl::Vector3<S>* p2) const {
  // Mesh frame -> world, as for the Boolean (fcl_solver.h, FRAMES).
  const fcl::Vector3<S> a = tf2 * P1;
  const fcl::Vector3<S> b = tf2 * P2;
  const fcl::Vector3<S> c = tf2 * P3;
  return solver_detail::cylinderVsWorldTriangleDistance(s, tf1, a, b, c, dist,
                                                        p1, p2);
}

template <class S>
bool Solver<S>::shapeDistance(const fcl::TriangleP<S>& s1,
                              const fcl::Transform3<S>& tf1,
                              const fcl::Cylinder<S>& s2,
                              const fcl::Transform3<S>& tf2, S* dist,
                              fcl::Vector3<S>* p1, fcl::Vector3<S>* p2) const {
  return solver_detail::cylinderVsTrianglePDistance(s2, tf2, s1, tf1, true,
                                                    dist, p1, p2);
}

template <class S>
bool Solver<S>::shapeDistance(const fcl::Cylinder<S>& s1,
                              const fcl::Transform3<S>& tf1,
                              const fcl::TriangleP<S>& s2,
                              const fcl::Transform3<S>& tf2, S* dist,
                              fcl::Vector3<S>* p1, fcl::Vector3<S>* p2) const {
  return solver_detail::cylinderVsTrianglePDistance(s1, tf1, s2, tf2, false,
                                                    dist, p1, p2);
}

template <class S>
bool Solver<S>::shapeSignedDistance(const fcl::TriangleP<S>& s1,
                                    const fcl::Transform3<S>& tf1,
                                    const fcl::Cylinder<S>& s2,
                                    const fcl::Transform3<S>& tf2, S* dist,
                                    fcl::Vector3<S>* p1,
                                    fcl::Vector3<S>* p2) const {
  return shapeDistance(s1, tf1, s2, tf2, dist, p1, p2);
}

template <class S>
bool Solver<S>::shapeSignedDistance(const fcl::Cylinder<S>& s1,
                                    const fcl::Transform3<S>& tf1,
                                    const fcl::TriangleP<S>& s2,
                                    const fcl::Transform3<S>& tf2, S* dist,
                                    fcl::Vector3<S>* p1,
                                    fcl::Vector3<S>* p2) const {
  return shapeDistance(s1, tf1, s2, tf2, dist, p1, p2);
}

template <class S>
bool Solver<S>::shapeIntersect(
    const fcl::TriangleP<S>& s1, const fcl::Transform3<S>& tf1,
    const fcl::Cylinder<S>& s2, const fcl::Transform3<S>& tf2,
    std::vector<fcl::ContactPoint<S>>* contacts) const {
  return solver_detail::cylinderVsTrianglePContacts(s2, tf2, s1, tf1, true,
                                                    contacts);
}

template <class S>
bool Solver<S>::shapeIntersect(
    const fcl::Cylinder<S>& s1, const fcl::Transform3<S>& tf1,
    const fcl::TriangleP<S>& s2, const fcl::Transform3<S>& tf2,
    std::vector<fcl::ContactPoint<S>>* contacts) const {
  return solver_detail::cylinderVsTrianglePContacts(s1, tf1, s2, tf2, false,
                                                    contacts);
}

template <class S>
bool Solver<S>::shapeIntersect(const fcl::TriangleP<S>& s1,
                               const fcl::Transform3<S>& tf1,
                               const fcl::Cylinder<S>& s2,
                               const fcl::Transform3<S>& tf2,
                               fcl::Vector3<S>* contact_points,
                               S* penetration_depth,
                               fcl::Vector3<S>* normal) const {
  return solver_detail::cylinderVsTriangleP(
      s2, tf2, s1, tf1, true, contact_points, penetration_depth, normal);
}

template <class S>
bool Solver<S>::shapeIntersect(const fcl::Cylinder<S>& s1,
                               const fcl::Transform3<S>& tf1,
                               const fcl::TriangleP<S>& s2,
                               const fcl::Transform3<S>& tf2,
                               fcl::Vector3<S>* contact_points,
                               S* penetration_depth,
                               fcl::Vector3<S>* normal) const {
  return solver_detail::cylinderVsTriangleP(
      s1, tf1, s2, tf2, false, contact_points, penetration_depth, normal);
}

template <class S>
bool Solver<S>::shapeIntersect(
    const fcl::Sphere<S>& s1, const fcl::Transform3<S>& tf1,
    const fcl::Cylinder<S>& s2, const fcl::Transform3<S>& tf2,
    std::vector<fcl::ContactPoint<S>>* contacts) const {
  if (contacts != nullptr)  // FCL's own contact path, unchanged
    return Base::shapeIntersect(s1, tf1, s2, tf2, contacts);
  return solver_detail::sphereVsCylinder(s1, tf1, s2, tf2);
}

template <class S>
bool Solver<S>::shapeIntersect(
    const fcl::Cylinder<S>& s1, const fcl::Transform3<S>& tf1,
    const fcl::Sphere<S>& s2, const fcl::Transform3<S>& tf2,
    std::vector<fcl::ContactPoint<S>>* contacts) const {
  if (contacts != nullptr)
    return Base::shapeIntersect(s1, tf1, s2, tf2, contacts);
  return solver_detail::sphereVsCylinder(s2, tf2, s1, tf1);
}

}  // namespace tricyl
