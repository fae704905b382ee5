// SPDX-License-Identifier: BSD-3-Clause
// The order in which a benchmark visits its cases (shared by the suites).
#pragma once

#include <cstddef>

namespace tricyl::bench {

// Every pass over n cases (n a power of two) is a permutation, an odd stride
// modulo n, with a new stride on each pass. Visited in the same order on
// every pass, a few thousand cases are a sequence that a modern branch
// predictor learns: the kernel's branches on the outcome are then predicted
// from the history of the previous queries' branches, and the kernel looks
// about twice as fast as it is, while FCL barely moves (the measurement is in
// bench/results/README.md). Real queries never replay one sequence, so the
// figures are taken in an order the predictor cannot learn, for tricyl and
// FCL alike.
class Walk {
 public:
  explicit Walk(std::size_t n) : mask_(n - 1), left_(n) {}
  static constexpr bool valid(std::size_t n) {
    return n > 0 && (n & (n - 1)) == 0;
  }
  std::size_t next() {
    const std::size_t k = i_;
    i_ = (i_ + stride_) & mask_;
    if (--left_ == 0) {
      left_ = mask_ + 1;
      stride_ += 2 * 7919;  // stays odd: the next pass is a new permutation
    }
    return k;
  }

 private:
  std::size_t mask_, left_, i_ = 0, stride_ = 1;
};

}  // namespace tricyl::bench
