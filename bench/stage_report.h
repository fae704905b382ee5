// SPDX-License-Identifier: BSD-3-Clause
// Shared by the stage-cost reports (tricyl-stage-costs for the triangle,
// tricyl-query-stage-costs for the cylinder queries): the clock, quantiles
// and the stage names.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <vector>

#include "tricyl/types.h"

namespace tricyl::bench {

using Clock = std::chrono::steady_clock;

inline double ns(Clock::duration d) {
  return std::chrono::duration<double, std::nano>(d).count();
}

/// The q-quantile of v (nearest rank; 0 for an empty v).
inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return 0;
  const std::size_t k =
      std::min(v.size() - 1, std::size_t(q * double(v.size())));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(k), v.end());
  return v[k];
}

/// The cost of reading the clock, to subtract from single-query times.
inline double clockOverheadNs() {
  double best = 1e300;
  for (int i = 0; i < 20000; ++i) {
    const auto a = Clock::now();
    const auto b = Clock::now();
    best = std::min(best, ns(b - a));
  }
  return best;
}

inline const char* stageName(Stage s) {
  switch (s) {
    case Stage::kEarlyOut:
      return "early-out";
    case Stage::kFastPath:
      return "double filter";
    case Stage::kExtended:
      return "double-word";
    case Stage::kExact:
      return "exact (stack)";
    case Stage::kExactGmp:
      return "exact (GMP)";
    case Stage::kInvalid:
      return "invalid";
  }
  return "?";
}

}  // namespace tricyl::bench
