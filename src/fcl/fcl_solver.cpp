// SPDX-License-Identifier: BSD-3-Clause
// tricyl::Solver<double>'s members (fcl_solver_impl.h) and the ONE place
// where FCL's collision and distance matrices are instantiated for it (see
// fcl_solver.h, Compile time). Explicit instantiations only: no FCL template
// is specialised.
#include "fcl_solver_impl.h"

TRICYL_FCL_SOLVER_INSTANCES(template, double)
