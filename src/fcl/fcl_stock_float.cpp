// SPDX-License-Identifier: BSD-3-Clause
// FCL's own fcl::collide(..., request, result) for float, which
// tricyl::collide<float> calls for the pairs it does not answer (libfcl.so
// instantiates only double). It instantiates FCL's libccd and
// GJKSolver_indep collision matrices for float: a file of its own, so that
// no compiler process holds them together with Solver<float>'s
// (fcl_solver_float.cpp; fcl_solver.h, Compile time).
//
// FCL's own float code (convexHalfspaceIntersect, halfspace-inl.h) trips
// GCC 12's -Wmaybe-uninitialized when instantiated; libfcl.so compiles only
// double, so the double build never meets it. FCL's code, not ours.
#if defined(__GNUC__) && !defined(__clang__)  // a GCC-only warning
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif

#include "tricyl/fcl_solver.h"

TRICYL_FCL_FLOAT_STOCK_COLLIDE(template)
