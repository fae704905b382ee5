// SPDX-License-Identifier: BSD-3-Clause
// Shared by the stage-cost reports (tricyl-stage-costs for the triangle,
// tricyl-query-stage-costs for the cylinder queries): the clock, quantiles
// and the stage names.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

#include "tricyl/types.h"
#include "walk.h"

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
    case Stage::kRunning:
      return "running double";
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

/// One family's costs as decideIntersect sees them: the mean per query of
/// whole passes (no clock inside the loop), and every query timed one by
/// one (the clock's cost subtracted), overall and by the deciding stage.
struct FamilyCosts {
  double mean = 0;
  std::vector<double> all;
  std::vector<double> by[8];  // by Stage
  long hits = 0;              // keeps the answers alive
};

/// `decide(case) -> Decision` over `cases` (a power-of-two count), visited
/// in an order the branch predictor cannot learn (walk.h).
template <class Case, class Decide>
FamilyCosts measureFamily(const std::vector<Case>& cases, int passes,
                          double clock_ns, const Decide& decide) {
  FamilyCosts fc;
  Walk walk(cases.size());
  const auto t0 = Clock::now();
  for (int p = 0; p < passes; ++p)
    for (std::size_t n = 0; n < cases.size(); ++n)
      fc.hits += decide(cases[walk.next()]).answer == Answer::kIntersect;
  fc.mean = ns(Clock::now() - t0) / double(passes * cases.size());
  Walk w1(cases.size());
  for (int p = 0; p < passes; ++p)
    for (std::size_t n = 0; n < cases.size(); ++n) {
      const Case& c = cases[w1.next()];
      const auto a = Clock::now();
      const Decision d = decide(c);
      const double t = std::max(0.0, ns(Clock::now() - a) - clock_ns);
      fc.hits += d.answer == Answer::kIntersect;
      fc.all.push_back(t);
      fc.by[int(d.stage)].push_back(t);
    }
  return fc;
}

/// The markdown rows "| <prefix> | stage | share | mean | p99 | max |" of
/// the stages that decided some query.
inline std::vector<std::string> stageRows(const std::string& prefix,
                                          const FamilyCosts& fc) {
  std::vector<std::string> rows;
  for (Stage s : {Stage::kEarlyOut, Stage::kFastPath, Stage::kRunning,
                  Stage::kExtended, Stage::kExact, Stage::kExactGmp}) {
    const auto& b = fc.by[int(s)];
    if (b.empty()) continue;
    double sum = 0;
    for (double t : b) sum += t;
    char row[256];
    std::snprintf(row, sizeof row,
                  "| %s | %s | %.3f %% | %.0f ns | %.0f ns | %.0f ns |\n",
                  prefix.c_str(), stageName(s),
                  100.0 * double(b.size()) / double(fc.all.size()),
                  sum / double(b.size()), quantile(b, 0.99),
                  *std::max_element(b.begin(), b.end()));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace tricyl::bench
