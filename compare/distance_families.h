// SPDX-License-Identifier: BSD-3-Clause
// tricyl-compare's distance and margin families (issue 23): tricyl::distance
// and FCL's GJK distances on the six kinds of scene moved 10^-15 .. 10^3 of
// the cylinder's size apart, settled by the 333-bit MPFR distance oracle
// (support/distance_oracle.h); margin Booleans (tricyl::withinDistance and
// "FCL distance <= m") settled by the exact GMP margin oracle
// (compare/margin_oracle.h). Compiled when the distance oracle is built
// (MPFR found): TRICYL_COMPARE_HAVE_DISTANCE.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scenes.h"

namespace tricyl::distance_families {

struct Options {
  std::string out;                       // output folder (exists)
  std::uint64_t seed = 1;                // cases are a function of (seed, i)
  long cases = 2000;                     // distance cases per family
  long margin_cases = 200;               // margin scenes per family
  std::vector<scenes::Family> families;  // which families
  bool plots = true;                     // run gnuplot on the figure
};

/// Runs both parts and writes, in options.out: distance.md (the tables),
/// distance.csv (one row per family x method), margin.csv, and
/// distance_error_vs_time.gp (+ .png when gnuplot runs). Returns a short
/// summary for stdout.
std::string run(const Options& options);

}  // namespace tricyl::distance_families
