// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// tricyl::Solver: FCL 0.7's libccd narrow phase with the exact
/// triangle/cylinder test in place of libccd's MPR for that pair, and
/// tricyl::collide, the one-name replacement for fcl::collide. CMake target
/// tricyl::fcl (`find_package(tricyl REQUIRED COMPONENTS fcl)`). For `float`
/// and `double`. Change one name in user code:
///
/// - `fcl::collide(o1, o2, request, result)` becomes
///   `tricyl::collide(o1, o2, request, result)` (also the geometry form);
/// - `fcl::DefaultCollisionFunction<S>` becomes
///   `tricyl::DefaultCollisionFunction<S>`;
/// - `fcl::DefaultCollisionData<S>` becomes `tricyl::DefaultCollisionData<S>`;
/// - `fcl::distance(o1, o2, request, result)` becomes
///   `tricyl::distance(o1, o2, request, result)`, and
///   `fcl::DefaultDistanceFunction<S>` / `DefaultDistanceData<S>` become
///   `tricyl::DefaultDistanceFunction<S>` / `tricyl::DefaultDistanceData<S>`;
/// - `fcl::collide(o1, o2, &solver, ...)` takes a `tricyl::Solver<S> solver`.
///
/// ## What changes (and nothing else does)
/// - Cylinder vs a BVHModel<BV> triangle (every BV: AABB, KDOP16/18/24 use
///   the world-frame overload, OBB, RSS, kIOS, OBBRSS the one with the mesh
///   transform), in either argument order of collide: the Boolean is
///   tricyl::tryIntersect's, exact for the triangle FCL hands the solver
///   (see Frames). Touching counts as colliding.
/// - TriangleP vs Cylinder and Cylinder vs TriangleP: FCL 0.7 has no entry
///   for them (collide prints a warning and returns 0); Solver registers one
///   in its own collision table, with the same exact Boolean.
/// - Contact data for those pairs (request.enable_contact) comes from
///   tricyl::estimateContact (fcl_contact.h): bounded time, no libccd, point
///   in triangle ∩ cylinder, unit normal, depth > 0 with a separation
///   certificate. The Boolean never depends on whether contact data is
///   requested. libccd's MPR, which has no iteration cap and can hang on
///   thin cylinders, is never reached for these pairs.
/// - Sphere vs Cylinder and Cylinder vs Sphere (shape pairs), Boolean
///   requests (no contact vector): tricyl::tryIntersect(Cylinder, Pose,
///   Sphere), exact (sphere_cylinder.h; the sphere's centre is its
///   Transform3's translation, its radius taken in the cylinder frame). With
///   request.enable_contact the pair keeps FCL's own path
///   (detail::sphereCylinderIntersect), contact data included, so the
///   Boolean can differ from the stock one only where FCL's is wrong.
///   Invalid input (NaN/Inf, negative sizes): "in collision".
/// - tricyl::collide (not fcl::collide with a Solver) walks a BVHModel vs
///   Cylinder pair itself for `double` (fcl_mesh_cylinder.h): same contacts,
///   cheaper traversal; requests it does not handle, and `float` models, run
///   FCL's traversal with Solver.
/// - Distance (DISTANCE below): Cylinder vs a BVHModel triangle (every BV
///   type) and TriangleP vs Cylinder, either order: tricyl::distance's
///   certified distance, or minus the contact depth when they meet.
/// - Every other pair (Box, Capsule, Cone, Convex, ... vs meshes and shapes,
///   Sphere vs meshes, and their distance queries) runs GJKSolver_libccd<S>'s
///   own code, inherited unchanged; through tricyl::collide and
///   tricyl::distance, the solver the request names (see The request).
///
/// ## DISTANCE (docs/fcl_solver.md, Distance and margins through FCL)
/// - shapeTriangleDistance (both of FCL's overloads, the same world
///   triangles as the Boolean): disjoint -> tricyl::distance's distance and
///   nearest points (world frame), returns true; meeting (the exact
///   Boolean; invalid input counts as meeting) -> minus estimateContact's
///   depth (< 0), both points at its contact point, returns false (libccd's
///   convention). FCL then stores nearest_points[0] on the mesh and [1] on
///   the cylinder in either argument order, world frame.
/// - FCL 0.7 registers mesh/cylinder distance for RSS, kIOS and OBBRSS only;
///   Solver's own distance table adds AABB, OBB and KDOP16/18/24 (double:
///   tricyl's own traversal; float: every triangle) and TriangleP/Cylinder
///   (both orders).
/// - enable_signed_distance: FCL's own signed step (collide with contacts,
///   minus the deepest contact's depth) runs with this solver's contacts.
/// - tricyl::distance(o1, o2, request, result): fcl::distance's
///   replacement; a mesh/cylinder pair in double is walked by tricyl's own
///   traversal (fcl_mesh_cylinder.h, distanceMeshCylinder): certified lower
///   bounds per node and per triangle, best-first, the brute-force minimum
///   of the per-triangle distances (ties within their certified error
///   bounds aside: docs/distance.md, section 6.2).
///
/// ## MARGIN COLLIDE (docs/fcl_solver.md)
/// tricyl::collide(o1, o2, request, result, CollideOptions<S>{margin}):
/// FCL 0.7's CollisionRequest has no margin field. A triangle collides when
/// the closed margin-neighbourhood of the cylinder (Minkowski sum with a
/// ball of radius margin) meets it: tricyl::withinDistance, exact. Mesh
/// (every BV type, either order) and TriangleP against a cylinder; the mesh
/// traversal prunes with the node test run for the neighbourhood
/// (certified). Contacts as tricyl::collide's; with enable_contact, a
/// triangle within the margin that does not meet the cylinder gets the
/// midpoint of the nearest points, the unit normal from o1 toward o2 and
/// penetration_depth = -distance. margin = 0 is tricyl::collide; a
/// negative, NaN or infinite margin throws InvalidInput. Every other pair:
/// tricyl::collide, then fcl::distance with Solver (libccd's GJK, not
/// exact) <= margin.
///
/// ## The request (tricyl::collide)
/// - The pairs tricyl answers itself (cylinder vs mesh or TriangleP in
///   either order, with or without contacts; sphere vs cylinder without
///   contacts): request.gjk_solver_type and request.gjk_tolerance are not
///   used, since the answer is exact and needs neither a solver nor a
///   tolerance. num_max_contacts, enable_contact and enable_cost are
///   honoured as fcl::collide honours them.
/// - Every other pair: exactly what fcl::collide(o1, o2, request, result)
///   does. GST_LIBCCD: Solver<S> (which is GJKSolver_libccd<S> for those
///   pairs) with collision_tolerance = request.gjk_tolerance; GST_INDEP:
///   fcl::collide itself, i.e. FCL's GJKSolver_indep<S> with gjk_tolerance
///   and epa_tolerance = request.gjk_tolerance; any other value: FCL's answer
///   to it (a warning and `std::size_t(-1)`).
///
/// ## Conventions (FCL's, for the overloads FCL calls)
/// - shapeTriangleIntersect: `normal` points from the cylinder toward the
///   triangle (libccd's convention; FCL's traversal stores -normal in
///   Contact::normal, which then points from o1 = mesh to o2 = cylinder),
///   `contact_points` is a world-frame point, `penetration_depth` > 0.
/// - shapeIntersect (TriangleP/Cylinder): ContactPoint::normal points from
///   the first shape to the second, as for FCL's other shape pairs.
/// - No intersection: no output is written.
/// - Invalid input (NaN/Inf anywhere, negative radius or length): the answer
///   is "in collision" (the safe answer for a collision query), and contact
///   outputs, if requested, get finite placeholders (fcl_contact.h).
///
/// ## Frames
/// - World-frame overload (AABB, KDOP meshes): FCL has already moved the
///   mesh vertices to the world frame (tf * v, rounded, in FCL's
///   initialize); the cylinder's Transform3 is converted to tricyl::Pose
///   exactly (toPose, fcl_adapters.h), so the answer is exact for those
///   world points.
/// - Mesh-frame overload (OBB, RSS, kIOS, OBBRSS): the vertices are moved to
///   the world frame with the same Eigen expression, tf_mesh * v, so that
///   every BV type sees bit-identical triangles; the answer is exact for
///   those points. (libccd's own path rounds the same way.)
/// - `float`: the same, in float: the answer is exact for the float
///   world-frame triangle and the float pose.
///
/// ## Threads and state
/// - Solver holds only GJKSolver_libccd's tolerances and iteration caps; the
///   overloads added here are const and read no member. One Solver can be
///   shared across threads as far as this code is concerned.
/// - The first Solver<S> constructed registers TriangleP/Cylinder in
///   fcl::getCollisionFunctionLookTable<Solver<S>>() (a thread-safe static).
///   Nothing else is ever written to FCL's tables; no FCL template is
///   specialised (libfcl.so has its own instantiations: that would be an ODR
///   violation).
///
/// ## Compile time
/// The collision and distance matrices for Solver<double> and Solver<float>
/// (FCL's whole traversal code, 30 to 60 s and 0.8 to 1.4 GB of compiler
/// memory each) are instantiated once in src/fcl/fcl_solver.cpp and
/// src/fcl/fcl_solver_float.cpp, and FCL's own float fcl::collide (which
/// libfcl.so does not provide) in src/fcl/fcl_stock_float.cpp; the extern
/// template declarations at the end of this header keep every including
/// file from instantiating them again. Solver is provided for S = float and
/// S = double only.
#pragma once

#include <fcl/broadphase/default_broadphase_callbacks.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/sphere.h>
#include <fcl/geometry/shape/triangle_p.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/collision_object.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>
#include <fcl/narrowphase/distance.h>

#include <cmath>
#include <cstddef>
#include <type_traits>
#include <vector>

#include "tricyl/fcl_adapters.h"
#include "tricyl/fcl_contact.h"
#include "tricyl/fcl_mesh_cylinder.h"
#include "tricyl/types.h"

namespace tricyl {

/// FCL narrow-phase solver: GJKSolver_libccd<S> plus the exact
/// triangle/cylinder and sphere/cylinder tests (this file's description).
/// Use wherever FCL takes a NarrowPhaseSolver. S is float or double.
template <class S>
class Solver : public fcl::detail::GJKSolver_libccd<S> {
  // The members and FCL's matrices are compiled once per type, in
  // src/fcl/fcl_solver.cpp (double) and src/fcl/fcl_solver_float.cpp.
  static_assert(std::is_same_v<S, double> || std::is_same_v<S, float>,
                "tricyl::Solver is built for float and double");

 public:
  /// The libccd solver this one extends.
  using Base = fcl::detail::GJKSolver_libccd<S>;

  /// Same defaults as GJKSolver_libccd; also registers the TriangleP /
  /// Cylinder pairs in this solver type's collision table (once).
  Solver();

  using Base::shapeDistance;
  using Base::shapeIntersect;
  using Base::shapeSignedDistance;
  using Base::shapeTriangleDistance;
  using Base::shapeTriangleIntersect;

  /// Cylinder `s` at `tf` vs the world-frame triangle (P1, P2, P3): the
  /// form FCL's AABB and KDOP mesh traversals call. Exact Boolean.
  /// [out] contact_points, penetration_depth, normal: see the header comment.
  bool shapeTriangleIntersect(
      const fcl::Cylinder<S>& s, const fcl::Transform3<S>& tf,
      const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2,
      const fcl::Vector3<S>& P3, fcl::Vector3<S>* contact_points = nullptr,
      S* penetration_depth = nullptr, fcl::Vector3<S>* normal = nullptr) const;

  /// Cylinder `s` at `tf1` vs the triangle (P1, P2, P3) given in the mesh
  /// frame `tf2`: the form FCL's OBB, RSS, kIOS and OBBRSS traversals call.
  bool shapeTriangleIntersect(
      const fcl::Cylinder<S>& s, const fcl::Transform3<S>& tf1,
      const fcl::Vector3<S>& P1, const fcl::Vector3<S>& P2,
      const fcl::Vector3<S>& P3, const fcl::Transform3<S>& tf2,
      fcl::Vector3<S>* contact_points = nullptr, S* penetration_depth = nullptr,
      fcl::Vector3<S>* normal = nullptr) const;

  /// TriangleP vs Cylinder (and the reverse): at most one contact, whose
  /// normal points from the first shape to the second.
  bool shapeIntersect(
      const fcl::TriangleP<S>& s1, const fcl::Transform3<S>& tf1,
      const fcl::Cylinder<S>& s2, const fcl::Transform3<S>& tf2,
      std::vector<fcl::ContactPoint<S>>* contacts = nullptr) const;
  /// Cylinder vs TriangleP: as above, normal from the cylinder to the
  /// triangle.
  bool shapeIntersect(
      const fcl::Cylinder<S>& s1, const fcl::Transform3<S>& tf1,
      const fcl::TriangleP<S>& s2, const fcl::Transform3<S>& tf2,
      std::vector<fcl::ContactPoint<S>>* contacts = nullptr) const;

  /// Sphere vs Cylinder (and the reverse): without `contacts`, the exact
  /// Boolean; with `contacts`, FCL's own sphere/cylinder code (header
  /// comment).
  bool shapeIntersect(
      const fcl::Sphere<S>& s1, const fcl::Transform3<S>& tf1,
      const fcl::Cylinder<S>& s2, const fcl::Transform3<S>& tf2,
      std::vector<fcl::ContactPoint<S>>* contacts = nullptr) const;
  /// Cylinder vs Sphere: as above.
  bool shapeIntersect(
      const fcl::Cylinder<S>& s1, const fcl::Transform3<S>& tf1,
      const fcl::Sphere<S>& s2, const fcl::Transform3<S>& tf2,
      std::vector<fcl::ContactPoint<S>>* contacts = nullptr) const;

  /// Cylinder `s` at `tf` vs the world-frame triangle (P1, P2, P3): the form
  /// FCL's AABB (and generic) mesh distance traversal calls (DISTANCE).
  /// [out] dist: tricyl::distance's certified distance when disjoint (then
  /// returns true); minus tricyl::estimateContact's depth (< 0) when they
  /// meet (then returns false, libccd's convention). p1: nearest point on
  /// the cylinder, p2: on the triangle, world frame (both the contact point
  /// when they meet).
  bool shapeTriangleDistance(const fcl::Cylinder<S>& s,
                             const fcl::Transform3<S>& tf,
                             const fcl::Vector3<S>& P1,
                             const fcl::Vector3<S>& P2,
                             const fcl::Vector3<S>& P3, S* dist = nullptr,
                             fcl::Vector3<S>* p1 = nullptr,
                             fcl::Vector3<S>* p2 = nullptr) const;

  /// The same for a triangle in the mesh frame `tf2` (FCL's RSS, kIOS and
  /// OBBRSS distance traversals): moved to the world frame as tf2 * P, the
  /// points are world-frame.
  bool shapeTriangleDistance(const fcl::Cylinder<S>& s,
                             const fcl::Transform3<S>& tf1,
                             const fcl::Vector3<S>& P1,
                             const fcl::Vector3<S>& P2,
                             const fcl::Vector3<S>& P3,
                             const fcl::Transform3<S>& tf2, S* dist = nullptr,
                             fcl::Vector3<S>* p1 = nullptr,
                             fcl::Vector3<S>* p2 = nullptr) const;

  /// TriangleP vs Cylinder distance (and the reverse, below), registered in
  /// this solver's distance table: as shapeTriangleDistance, p1 on the first
  /// shape, p2 on the second, world frame.
  bool shapeDistance(const fcl::TriangleP<S>& s1, const fcl::Transform3<S>& tf1,
                     const fcl::Cylinder<S>& s2, const fcl::Transform3<S>& tf2,
                     S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                     fcl::Vector3<S>* p2 = nullptr) const;
  /// Cylinder vs TriangleP distance.
  bool shapeDistance(const fcl::Cylinder<S>& s1, const fcl::Transform3<S>& tf1,
                     const fcl::TriangleP<S>& s2, const fcl::Transform3<S>& tf2,
                     S* dist = nullptr, fcl::Vector3<S>* p1 = nullptr,
                     fcl::Vector3<S>* p2 = nullptr) const;
  /// Signed forms (request.enable_signed_distance): the same values (minus
  /// the contact depth when they meet).
  bool shapeSignedDistance(const fcl::TriangleP<S>& s1,
                           const fcl::Transform3<S>& tf1,
                           const fcl::Cylinder<S>& s2,
                           const fcl::Transform3<S>& tf2, S* dist = nullptr,
                           fcl::Vector3<S>* p1 = nullptr,
                           fcl::Vector3<S>* p2 = nullptr) const;
  /// Cylinder vs TriangleP, signed.
  bool shapeSignedDistance(const fcl::Cylinder<S>& s1,
                           const fcl::Transform3<S>& tf1,
                           const fcl::TriangleP<S>& s2,
                           const fcl::Transform3<S>& tf2, S* dist = nullptr,
                           fcl::Vector3<S>* p1 = nullptr,
                           fcl::Vector3<S>* p2 = nullptr) const;

  /// The same pairs in the pointer form (deprecated in FCL, kept so that no
  /// route reaches libccd for them). Normal from the first shape to the
  /// second.
  bool shapeIntersect(const fcl::TriangleP<S>& s1,
                      const fcl::Transform3<S>& tf1, const fcl::Cylinder<S>& s2,
                      const fcl::Transform3<S>& tf2,
                      fcl::Vector3<S>* contact_points, S* penetration_depth,
                      fcl::Vector3<S>* normal) const;
  /// Cylinder vs TriangleP in the pointer form: as above.
  bool shapeIntersect(const fcl::Cylinder<S>& s1, const fcl::Transform3<S>& tf1,
                      const fcl::TriangleP<S>& s2,
                      const fcl::Transform3<S>& tf2,
                      fcl::Vector3<S>* contact_points, S* penetration_depth,
                      fcl::Vector3<S>* normal) const;
};

namespace detail {

/// True when tricyl answers the pair itself (The request, in this file's
/// description): a cylinder against a BVHModel or a TriangleP, either
/// order; a sphere against a cylinder, either order, without contacts.
template <class S>
bool answersPair(const fcl::CollisionGeometry<S>* g1,
                 const fcl::CollisionGeometry<S>* g2,
                 const fcl::CollisionRequest<S>& request) {
  const auto meshOrTriangle = [](const fcl::CollisionGeometry<S>* g) {
    return g->getObjectType() == fcl::OT_BVH ||
           g->getNodeType() == fcl::GEOM_TRIANGLE;
  };
  const fcl::NODE_TYPE t1 = g1->getNodeType(), t2 = g2->getNodeType();
  if (t1 == fcl::GEOM_CYLINDER && meshOrTriangle(g2)) return true;
  if (t2 == fcl::GEOM_CYLINDER && meshOrTriangle(g1)) return true;
  return !request.enable_contact &&
         ((t1 == fcl::GEOM_SPHERE && t2 == fcl::GEOM_CYLINDER) ||
          (t1 == fcl::GEOM_CYLINDER && t2 == fcl::GEOM_SPHERE));
}

}  // namespace detail

/// fcl::collide(g1, tf1, g2, tf2, request, result) with the exact tests:
/// the pairs tricyl answers go to Solver<S> (a BVHModel/Cylinder pair in
/// double to tricyl's own traversal, fcl_mesh_cylinder.h: same answers,
/// certified node test, batched leaves); every other pair is run as
/// fcl::collide runs it for request.gjk_solver_type (The request, in this
/// file's description). Returns the number of contacts.
template <class S>
std::size_t collide(const fcl::CollisionGeometry<S>* g1,
                    const fcl::Transform3<S>& tf1,
                    const fcl::CollisionGeometry<S>* g2,
                    const fcl::Transform3<S>& tf2,
                    const fcl::CollisionRequest<S>& request,
                    fcl::CollisionResult<S>& result) {
  if (request.gjk_solver_type != fcl::GST_LIBCCD &&
      !detail::answersPair(g1, g2, request))
    return fcl::collide(g1, tf1, g2, tf2, request, result);
  if constexpr (std::is_same_v<S, double>) {  // mesh/cylinder: own traversal
    std::size_t n = 0;
    if (collideMeshCylinder(g1, tf1, g2, tf2, request, result, &n)) return n;
  }
  Solver<S> solver;
  solver.collision_tolerance = request.gjk_tolerance;
  return fcl::collide(g1, tf1, g2, tf2, &solver, request, result);
}

/// fcl::collide(o1, o2, request, result) with the exact tests: the same as
/// the geometry form on the objects' geometries and transforms.
template <class S>
std::size_t collide(const fcl::CollisionObject<S>* o1,
                    const fcl::CollisionObject<S>* o2,
                    const fcl::CollisionRequest<S>& request,
                    fcl::CollisionResult<S>& result) {
  const fcl::CollisionGeometry<S>* g1 = o1->collisionGeometry().get();
  const fcl::CollisionGeometry<S>* g2 = o2->collisionGeometry().get();
  if (request.gjk_solver_type != fcl::GST_LIBCCD &&
      !detail::answersPair(g1, g2, request))
    return fcl::collide(o1, o2, request, result);
  if constexpr (std::is_same_v<S, double>) {  // mesh/cylinder: own traversal
    std::size_t n = 0;
    if (collideMeshCylinder(g1, o1->getTransform(), g2, o2->getTransform(),
                            request, result, &n))
      return n;
  }
  Solver<S> solver;
  solver.collision_tolerance = request.gjk_tolerance;
  return fcl::collide(o1, o2, &solver, request, result);
}

namespace detail {

/// True when tricyl answers a distance query itself (DISTANCE): a cylinder
/// against a BVHModel or a TriangleP, either order.
template <class S>
bool answersDistancePair(const fcl::CollisionGeometry<S>* g1,
                         const fcl::CollisionGeometry<S>* g2) {
  const auto meshOrTriangle = [](const fcl::CollisionGeometry<S>* g) {
    return g->getObjectType() == fcl::OT_BVH ||
           g->getNodeType() == fcl::GEOM_TRIANGLE;
  };
  const fcl::NODE_TYPE t1 = g1->getNodeType(), t2 = g2->getNodeType();
  return (t1 == fcl::GEOM_CYLINDER && meshOrTriangle(g2)) ||
         (t2 == fcl::GEOM_CYLINDER && meshOrTriangle(g1));
}

/// The rest of tricyl::distance (below), compiled once per S in
/// src/fcl/fcl_solver*.cpp.
template <class S>
S distanceImpl(const fcl::CollisionGeometry<S>* g1,
               const fcl::Transform3<S>& tf1,
               const fcl::CollisionGeometry<S>* g2,
               const fcl::Transform3<S>& tf2,
               const fcl::DistanceRequest<S>& request,
               fcl::DistanceResult<S>& result);

/// The margin collide (MARGIN COLLIDE), compiled once per S.
template <class S>
std::size_t collideWithinImpl(const fcl::CollisionGeometry<S>* g1,
                              const fcl::Transform3<S>& tf1,
                              const fcl::CollisionGeometry<S>* g2,
                              const fcl::Transform3<S>& tf2,
                              const fcl::CollisionRequest<S>& request,
                              fcl::CollisionResult<S>& result, S margin);

}  // namespace detail

/// fcl::distance(g1, tf1, g2, tf2, request, result) with tricyl's distance
/// (DISTANCE in this file's description): a cylinder against a BVHModel
/// (double: tricyl's own traversal, fcl_mesh_cylinder.h, distanceMeshCylinder;
/// float, or models it does not handle: FCL's traversal with Solver<S>) or a
/// TriangleP, either order, is measured by tricyl::distance per triangle;
/// every other pair is run as fcl::distance runs it for
/// request.gjk_solver_type. Returns result.min_distance (after the signed
/// distance step, unlike fcl::distance, which returns the value before it).
template <class S>
S distance(const fcl::CollisionGeometry<S>* g1, const fcl::Transform3<S>& tf1,
           const fcl::CollisionGeometry<S>* g2, const fcl::Transform3<S>& tf2,
           const fcl::DistanceRequest<S>& request,
           fcl::DistanceResult<S>& result) {
  return detail::distanceImpl(g1, tf1, g2, tf2, request, result);
}

/// fcl::distance(o1, o2, request, result) with tricyl's distance: the
/// geometry form on the objects' geometries and transforms.
template <class S>
S distance(const fcl::CollisionObject<S>* o1, const fcl::CollisionObject<S>* o2,
           const fcl::DistanceRequest<S>& request,
           fcl::DistanceResult<S>& result) {
  return detail::distanceImpl(o1->collisionGeometry().get(), o1->getTransform(),
                              o2->collisionGeometry().get(), o2->getTransform(),
                              request, result);
}

/// What tricyl::collide takes beyond FCL 0.7's CollisionRequest (which has
/// no margin field): see MARGIN COLLIDE in this file's description.
template <class S>
struct CollideOptions {
  /// Safety margin, >= 0 and finite: a pair collides when the closed
  /// margin-neighbourhood of one meets the other (distance <= margin).
  /// 0 is the plain collide.
  S margin = S(0);
};

/// tricyl::collide with options (MARGIN COLLIDE). Throws tricyl::InvalidInput
/// for a negative, NaN or infinite margin. Returns the number of contacts.
template <class S>
std::size_t collide(const fcl::CollisionGeometry<S>* g1,
                    const fcl::Transform3<S>& tf1,
                    const fcl::CollisionGeometry<S>* g2,
                    const fcl::Transform3<S>& tf2,
                    const fcl::CollisionRequest<S>& request,
                    fcl::CollisionResult<S>& result,
                    const CollideOptions<S>& options) {
  if (!(std::isfinite(options.margin) && options.margin >= 0))
    throw InvalidInput("tricyl::collide: the margin must be finite and >= 0");
  if (options.margin == 0)
    return tricyl::collide(g1, tf1, g2, tf2, request, result);
  return detail::collideWithinImpl(g1, tf1, g2, tf2, request, result,
                                   options.margin);
}

/// tricyl::collide with options, on collision objects.
template <class S>
std::size_t collide(const fcl::CollisionObject<S>* o1,
                    const fcl::CollisionObject<S>* o2,
                    const fcl::CollisionRequest<S>& request,
                    fcl::CollisionResult<S>& result,
                    const CollideOptions<S>& options) {
  return tricyl::collide(o1->collisionGeometry().get(), o1->getTransform(),
                         o2->collisionGeometry().get(), o2->getTransform(),
                         request, result, options);
}

/// The broadphase callback data: FCL's own struct (request, result, done).
template <class S>
using DefaultCollisionData = fcl::DefaultCollisionData<S>;

/// fcl::DefaultCollisionFunction with tricyl::collide: pass it with a
/// DefaultCollisionData<S>* to BroadPhaseCollisionManager::collide.
template <class S>
bool DefaultCollisionFunction(fcl::CollisionObject<S>* o1,
                              fcl::CollisionObject<S>* o2, void* data) {
  auto* collision_data = static_cast<DefaultCollisionData<S>*>(data);
  const fcl::CollisionRequest<S>& request = collision_data->request;
  fcl::CollisionResult<S>& result = collision_data->result;
  if (collision_data->done) return true;
  tricyl::collide(o1, o2, request, result);
  // Same stopping rule as FCL's: enough contacts and no cost wanted.
  if (!request.enable_cost && result.isCollision() &&
      result.numContacts() >= request.num_max_contacts) {
    collision_data->done = true;
  }
  return collision_data->done;
}

/// The broadphase distance callback data: FCL's own struct (request,
/// result, done).
template <class S>
using DefaultDistanceData = fcl::DefaultDistanceData<S>;

/// fcl::DefaultDistanceFunction with tricyl::distance: pass it with a
/// DefaultDistanceData<S>* to BroadPhaseCollisionManager::distance.
template <class S>
bool DefaultDistanceFunction(fcl::CollisionObject<S>* o1,
                             fcl::CollisionObject<S>* o2, void* data, S& dist) {
  auto* distance_data = static_cast<DefaultDistanceData<S>*>(data);
  const fcl::DistanceRequest<S>& request = distance_data->request;
  fcl::DistanceResult<S>& result = distance_data->result;
  if (distance_data->done) {
    dist = result.min_distance;
    return true;
  }
  tricyl::distance(o1, o2, request, result);
  dist = result.min_distance;
  // Same stopping rule as FCL's: in collision or touching.
  if (dist <= 0) return true;
  return distance_data->done;
}

}  // namespace tricyl

#include "tricyl/detail/fcl_solver_instances.h"

// Instantiated once per type, in src/fcl/fcl_solver.cpp and
// src/fcl/fcl_solver_float.cpp (see Compile time). These are explicit
// instantiations of FCL templates for OUR solver type, never
// specialisations.
TRICYL_FCL_SOLVER_INSTANCES(extern template, double)
TRICYL_FCL_SOLVER_INSTANCES(extern template, float)
TRICYL_FCL_FLOAT_STOCK_COLLIDE(extern template)
