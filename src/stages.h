// SPDX-License-Identifier: BSD-3-Clause
// The one stage driver of every exact query in tricyl (the triangle, the
// cylinder queries, the degenerate-triangle hand-off): a query is a
// callable pred(KernelTag<K>{}, &early) -> Tri written once over a kernel
// K of src/filter.h, and runStages decides it
//   1. with FilterKernel (certified double), inside the range gate;
//   2. where that left a sign open: once more with AdaptiveKernel
//      (src/adaptive.h), in which each sign the double bound cannot certify
//      is re-decided by itself in double-word, then exactly (stack
//      expansions, then GMP), while the query's control flow goes on in
//      double. That run always decides.
// docs/exactness.md describes the stages and their bounds.
#pragma once

#include "adaptive.h"
#include "filter.h"
#include "tricyl/types.h"

namespace tricyl::detail {

/// A decided Tri (kTrue or kFalse) as the query's answer.
inline Answer toAnswer(Tri t) {
  return t == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint;
}

template <class K>
struct KernelTag {
  using type = K;
};

/// Step 2 alone (out of line: most queries never get here). Outside the
/// range gate (a length beyond 2^40 or a rotation entry beyond 2 in
/// magnitude) no bound of the double or double-word stages holds and double
/// arithmetic may overflow, so the query is decided in GMP dyadics alone,
/// with no floating-point operation on the inputs.
template <class Pred>
TRICYL_ADAPTIVE_NOINLINE Decision runAdaptive(const Pred& pred, bool gate) {
  bool early = false;
  if (!gate)
    return {toAnswer(pred(KernelTag<ExactKernel>{}, &early)), Stage::kExactGmp};
  Tape tape;
  Tri t;
  {
    TapeScope scope(&tape);
    t = pred(KernelTag<AdaptiveKernel>{}, &early);
  }
  if (!tape.overflowed() && t != Tri::kUnknown)
    return {toAnswer(t), stageOfLevel(tape.level())};
  // A sign needed GMP (Tape::escalate: the whole query is decided in GMP
  // once), or the tape overflowed (not reached by any query of tricyl:
  // their tapes stay far below Tape::kMaxNodes,
  // tests/adaptive_stage_test.cpp; kept so that the answer is exact even
  // then).
  return {toAnswer(pred(KernelTag<ExactKernel>{}, &early)), Stage::kExactGmp};
}

/// The whole sequence. `filter_done`: the caller already ran step 1 (the
/// triangle's scalar fast path) and it could not decide.
template <class Pred>
Decision runStages(const Pred& pred, double max_len, double max_unitless,
                   bool filter_done = false) {
  const bool gate = rangeGateOk(max_len, max_unitless);
  if (gate && !filter_done) {
    bool early = false;
    const Tri t = pred(KernelTag<FilterKernel>{}, &early);
    if (t != Tri::kUnknown)
      return {toAnswer(t), early ? Stage::kEarlyOut : Stage::kFastPath};
  }
  return runAdaptive(pred, gate);
}

}  // namespace tricyl::detail
