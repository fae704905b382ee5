// SPDX-License-Identifier: BSD-3-Clause
// The explicit instantiations behind tricyl::Solver<S> and tricyl::collide
// (fcl_solver.h, Compile time), written once for both uses:
//   TRICYL_FCL_SOLVER_INSTANCES(extern template, S)  in fcl_solver.h, and
//   TRICYL_FCL_SOLVER_INSTANCES(template, S)         in the one .cpp per S.
// They instantiate FCL templates for tricyl's own solver type; nothing of
// FCL's is specialised. Not part of the documented interface.
#pragma once

#define TRICYL_FCL_SOLVER_INSTANCES(KIND, S)                                  \
  namespace tricyl {                                                          \
  KIND class Solver<S>;                                                       \
  KIND std::size_t collide(const fcl::CollisionObject<S>*,                    \
                           const fcl::CollisionObject<S>*,                    \
                           const fcl::CollisionRequest<S>&,                   \
                           fcl::CollisionResult<S>&);                         \
  KIND std::size_t collide(const fcl::CollisionGeometry<S>*,                  \
                           const fcl::Transform3<S>&,                         \
                           const fcl::CollisionGeometry<S>*,                  \
                           const fcl::Transform3<S>&,                         \
                           const fcl::CollisionRequest<S>&,                   \
                           fcl::CollisionResult<S>&);                         \
  KIND bool DefaultCollisionFunction(fcl::CollisionObject<S>*,                \
                                     fcl::CollisionObject<S>*, void*);        \
  namespace detail {                                                          \
  KIND S distanceImpl(const fcl::CollisionGeometry<S>*,                       \
                      const fcl::Transform3<S>&,                              \
                      const fcl::CollisionGeometry<S>*,                       \
                      const fcl::Transform3<S>&,                              \
                      const fcl::DistanceRequest<S>&,                         \
                      fcl::DistanceResult<S>&);                               \
  KIND std::size_t collideWithinImpl(const fcl::CollisionGeometry<S>*,        \
                                     const fcl::Transform3<S>&,               \
                                     const fcl::CollisionGeometry<S>*,        \
                                     const fcl::Transform3<S>&,               \
                                     const fcl::CollisionRequest<S>&,         \
                                     fcl::CollisionResult<S>&, S);            \
  }                                                                           \
  }                                                                           \
  namespace fcl {                                                             \
  KIND detail::CollisionFunctionMatrix<tricyl::Solver<S>>&                    \
  getCollisionFunctionLookTable<tricyl::Solver<S>>();                         \
  KIND detail::DistanceFunctionMatrix<tricyl::Solver<S>>&                     \
  getDistanceFunctionLookTable<tricyl::Solver<S>>();                          \
  KIND std::size_t collide(const CollisionObject<S>*,                         \
                           const CollisionObject<S>*,                         \
                           const tricyl::Solver<S>*,                          \
                           const CollisionRequest<S>&, CollisionResult<S>&);  \
  KIND std::size_t collide(const CollisionGeometry<S>*, const Transform3<S>&, \
                           const CollisionGeometry<S>*, const Transform3<S>&, \
                           const tricyl::Solver<S>*,                          \
                           const CollisionRequest<S>&, CollisionResult<S>&);  \
  KIND S distance(const CollisionObject<S>*, const CollisionObject<S>*,       \
                  const tricyl::Solver<S>*, const DistanceRequest<S>&,        \
                  DistanceResult<S>&);                                        \
  KIND S distance(const CollisionGeometry<S>*, const Transform3<S>&,          \
                  const CollisionGeometry<S>*, const Transform3<S>&,          \
                  const tricyl::Solver<S>*, const DistanceRequest<S>&,        \
                  DistanceResult<S>&);                                        \
  namespace detail {                                                          \
  KIND struct CollisionFunctionMatrix<tricyl::Solver<S>>;                     \
  KIND struct DistanceFunctionMatrix<tricyl::Solver<S>>;                      \
  }                                                                           \
  }

// FCL's own fcl::collide(..., request, result) for float, which
// tricyl::collide<float> calls for the pairs it does not answer (libfcl.so
// instantiates only double, and declares those extern itself). Instantiated
// once, in src/fcl/fcl_stock_float.cpp, so that no including file compiles
// FCL's float libccd and GJKSolver_indep matrices again.
#define TRICYL_FCL_FLOAT_STOCK_COLLIDE(KIND)                                   \
  namespace fcl {                                                              \
  KIND float distance(const CollisionObject<float>*,                           \
                      const CollisionObject<float>*,                           \
                      const DistanceRequest<float>&, DistanceResult<float>&);  \
  KIND float distance(const CollisionGeometry<float>*,                         \
                      const Transform3<float>&,                                \
                      const CollisionGeometry<float>*,                         \
                      const Transform3<float>&, const DistanceRequest<float>&, \
                      DistanceResult<float>&);                                 \
  KIND std::size_t collide(const CollisionObject<float>*,                      \
                           const CollisionObject<float>*,                      \
                           const CollisionRequest<float>&,                     \
                           CollisionResult<float>&);                           \
  KIND std::size_t collide(const CollisionGeometry<float>*,                    \
                           const Transform3<float>&,                           \
                           const CollisionGeometry<float>*,                    \
                           const Transform3<float>&,                           \
                           const CollisionRequest<float>&,                     \
                           CollisionResult<float>&);                           \
  }
