// SPDX-License-Identifier: BSD-3-Clause
// The cases of the cylinder-query benchmarks (bench_queries,
// tricyl-query-stage-costs): 4096 per query and family of
// compare/query_scenes.h, seed 20261122.
#pragma once

#include <cstdint>
#include <vector>

#include "query_scenes.h"

namespace tricyl::bench {

inline constexpr int kQueryCases = 4096;

inline std::vector<qscenes::QueryCase> queryCases(qscenes::Query q,
                                                  qscenes::Family f) {
  std::vector<qscenes::QueryCase> v;
  for (int i = 0; i < kQueryCases; ++i)
    v.push_back(qscenes::generate(q, f, 20261122u, std::uint64_t(i)));
  return v;
}

}  // namespace tricyl::bench
