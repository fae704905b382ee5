// SPDX-License-Identifier: BSD-3-Clause
// The evaluation loop of tricyl-compare: forked workers, a per-query time
// limit, and the aggregation of every answer into statistics.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "harness.h"

namespace tricyl::compare {

struct RunOptions {
  std::vector<Method> methods;  ///< in evaluation order
  int workers = 2;              ///< worker processes evaluating in parallel
  double timeout_s = 1.0;       ///< per FCL query
  std::uint64_t unit = 256;     ///< cases per work unit handed to a worker
  bool progress = true;         ///< progress bar on stderr (runs > 1 s)
};

/// Statistics of one method on one case set.
struct MethodStats {
  std::uint64_t cases = 0;
  std::uint64_t false_positives = 0;
  std::uint64_t false_negatives = 0;
  std::uint64_t hangs = 0;
  /// Largest error size (see errorSize) among false positives (a clearance)
  /// and among false negatives (a penetration); 0 if none.
  double max_fp_size = 0;
  double max_fn_size = 0;
  /// The case index attaining max_fp_size / max_fn_size (the smallest index
  /// on ties, so independent of scheduling); kNoCase if none.
  static constexpr std::uint64_t kNoCase = ~std::uint64_t(0);
  std::uint64_t worst_fp_index = kNoCase;
  std::uint64_t worst_fn_index = kNoCase;
  /// ns per query for every answered (not hung) query.
  std::vector<float> ns;
  /// mesh_bvh (exhaustive requests): oracle colliding triangles over the
  /// answered cases, those the method missed, and those it reported that do
  /// not collide. A hung case counts its oracle triangles as missed.
  std::uint64_t tri_oracle = 0, tri_missed = 0, tri_extra = 0;
  /// Agreement with tricyl's exact answer: [tricyl][this], index 1 = hit.
  std::uint64_t agree[2][2] = {{0, 0}, {0, 0}};
  std::uint64_t wrong() const {
    return false_positives + false_negatives + hangs;
  }
};

/// Errors per generator feature (scenes::TriCase::feature) of a set.
struct FeatureStats {
  std::uint64_t cases = 0;
  std::array<std::uint64_t, kMethodCount> wrong{};  ///< fp + fn + hangs
};

struct SetStats {
  std::uint64_t cases = 0;
  std::uint64_t hits = 0;  ///< oracle says "intersect"
  /// Cases whose pose has det R < 0: the FCL methods get fclPose of them.
  std::uint64_t improper = 0;
  /// tricyl's deciding stage, counted by int(tricyl::Stage) (triangle sets).
  std::array<std::uint64_t, 8> stage{};
  std::array<MethodStats, kMethodCount> method;
  std::map<std::string, FeatureStats> features;
};

struct HangRecord {
  std::size_t set;
  std::uint64_t index;
  Method method;
};

struct RunResult {
  std::vector<SetStats> sets;  ///< parallel to the input sets
  std::vector<HangRecord> hangs;
  double wall_seconds = 0;
  std::uint64_t worker_restarts = 0;
};

/// Evaluates every case of every set with every method. Throws
/// std::runtime_error if a worker dies or stalls outside an FCL call.
RunResult runAll(const std::vector<CaseSet>& sets, const RunOptions& options);

/// Percentile (0..100) of a sample, nearest rank; NaN if empty. Sorts.
double percentile(std::vector<float>& v, double p);
/// Arithmetic mean of a sample (in double); NaN if empty.
double mean(const std::vector<float>& v);

}  // namespace tricyl::compare
