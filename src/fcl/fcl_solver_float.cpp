// tricyl::Solver<float>'s members (fcl_solver_impl.h) and the ONE place
// where FCL's collision and distance matrices are instantiated for it, with
// tricyl::collide<float> and FCL's own float fcl::collide(..., request,
// result), which tricyl::collide<float> calls for the pairs it does not
// answer. A file of its own so that the two heavy instantiations
// compile in parallel and each within about 1 GB (fcl_solver.h, Compile
// time).
//
// FCL's own float code (convexHalfspaceIntersect, halfspace-inl.h) trips
// GCC 12's -Wmaybe-uninitialized when instantiated here; libfcl.so compiles
// only double, so the double build never meets it. FCL's code, not ours.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"

#include "fcl_solver_impl.h"

TRICYL_FCL_FLOAT_STOCK_COLLIDE(template)
TRICYL_FCL_SOLVER_INSTANCES(template, float)
