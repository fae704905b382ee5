// SPDX-License-Identifier: BSD-3-Clause
// tricyl::Solver<S>'s members, for any S (fcl_solver.h). Included by the two
// files that instantiate them: fcl_solver.cpp (double) and
// fcl_solver_float.cpp (float), each with FCL's collision and distance
// matrices for its Solver (see fcl_solver.h, COMPILE TIME).
#pragma once

#include "tricyl/fcl_adapters.h"
#include "tricyl/fcl_contact.h"
#include "tricyl/fcl_solver.h"
#include "tricyl/sphere_cylinder.h"
#include "tricyl/triangle_cylinder.h"

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

/// Puts TriangleP/Cylinder (both orders) into Solver<S>'s own table. FCL's
/// generic ShapeShapeCollide calls Solver::shapeIntersect above.
template <class S>
bool registerTrianglePairs() {
  auto& table = fcl::getCollisionFunctionLookTable<Solver<S>>();
  table.collision_matrix[fcl::GEOM_TRIANGLE][fcl::GEOM_CYLINDER] =
      &fcl::detail::ShapeShapeCollide<fcl::TriangleP<S>, fcl::Cylinder<S>,
                                      Solver<S>>;
  table.collision_matrix[fcl::GEOM_CYLINDER][fcl::GEOM_TRIANGLE] =
      &fcl::detail::ShapeShapeCollide<fcl::Cylinder<S>, fcl::TriangleP<S>,
                                      Solver<S>>;
  return true;
}

}  // namespace solver_detail

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
