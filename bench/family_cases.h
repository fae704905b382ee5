// SPDX-License-Identifier: BSD-3-Clause
// The benchmarks' cases of each triangle family (shared by
// bench_triangle_cylinder and bench_distance): 4096 per family, seed 7,
// generated once.
#pragma once

#include <cstdint>
#include <vector>

#include "scenes.h"
#include "walk.h"

namespace tricyl::bench {

inline constexpr int kFamilyCases = 4096;  // a power of two (Walk)
static_assert(Walk::valid(kFamilyCases));

inline const std::vector<scenes::TriCase>& familyCases(scenes::Family f) {
  static std::vector<scenes::TriCase> store[6];
  auto& v = store[int(f)];
  if (v.empty())
    for (int i = 0; i < kFamilyCases; ++i)
      v.push_back(scenes::generate(f, 7, std::uint64_t(i)));
  return v;
}

}  // namespace tricyl::bench
