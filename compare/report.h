// SPDX-License-Identifier: BSD-3-Clause
// Writing the results of a tricyl-compare run: report.md, results.csv,
// stability.csv, results.json, hangs.txt and the gnuplot figures.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "harness.h"
#include "runner.h"

namespace tricyl::compare {

struct ReportInfo {
  std::string command_line;
  std::uint64_t seed = 0;
  std::uint64_t cases = 0;        ///< per triangle family
  std::uint64_t mesh_cases = 0;   ///< each mesh family
  std::uint64_t sweep_cases = 0;  ///< per sweep point
  std::uint64_t query_cases = 0;  ///< per query x family
  std::vector<std::string> meshes;
  RunOptions options;
  bool plots = true;  ///< run gnuplot (the .gp scripts are written anyway)
};

/// Writes every output file into `dir` (created if needed). Returns the
/// paths of the figures that gnuplot actually produced.
std::vector<std::string> writeReport(const std::string& dir,
                                     const std::vector<CaseSet>& sets,
                                     RunResult& result, const ReportInfo& info);

}  // namespace tricyl::compare
