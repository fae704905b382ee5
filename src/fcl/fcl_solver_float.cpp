// SPDX-License-Identifier: BSD-3-Clause
// tricyl::Solver<float>'s members (fcl_solver_impl.h) and the ONE place
// where FCL's collision and distance matrices are instantiated for it, with
// tricyl::collide<float> (FCL's own float collide, which that calls for the
// pairs it does not answer, is in fcl_stock_float.cpp). Files of their own
// so that the heavy instantiations compile in parallel, each in one
// compiler process of about 1 GB (fcl_solver.h, Compile time).
//
// FCL's own float code (convexHalfspaceIntersect, halfspace-inl.h) trips
// GCC 12's -Wmaybe-uninitialized when instantiated here; libfcl.so compiles
// only double, so the double build never meets it. FCL's code, not ours.
#if defined(__GNUC__) && !defined(__clang__)  // a GCC-only warning
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "fcl_solver_impl.h"

TRICYL_FCL_SOLVER_INSTANCES(template, float)
