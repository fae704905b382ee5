// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::intersect / tryIntersect / decideIntersect for
// a segment and a cylinder and the entry/exit interval tricyl::clip /
// tryClip (include/tricyl/segment_cylinder.h), with the cylinder given
// directly or built by cylinderFromAxis / cylinderFromEndpoints
// (include/tricyl/endpoint_form.h), on inputs decoded from raw bytes
// (fuzz_input.h: decodeSegment). Built with
// -fsanitize=fuzzer,address,undefined.
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no FE_INVALID or
//   FE_DIVBYZERO inside the library calls (trapped);
// - valid input (all finite, radius and lz >= 0): intersect equals the
//   exact oracle (compare/query_oracles.h: segmentInterval non-empty), and
//   so does the quarter turn of the pose about the axis, with and without
//   flipping it; an endpoint contained (tryContains of point_cylinder.h)
//   means a hit, and a point segment (p == q) is point containment;
// - the interval: tryClip answers as tryIntersect (and leaves *out
//   untouched unless kIntersect), clip(...).has_value() == intersect, clip
//   and tryClip give the same interval; lo <= hi, both in [0, 1], and each
//   endpoint within the header's bound of the exact one (1e-14 for double,
//   2^-25 + 1e-14 for float), measured against the oracle's reference
//   endpoints (referenceEndpoints, within 2^-200 of the exact ones);
//   the same for the reversed segment (q, p) against [1 - hi*, 1 - lo*] and
//   for the point reflection of the scene against [lo*, hi*];
// - invalid input (NaN or Inf anywhere, negative radius or lz):
//   tryIntersect, decideIntersect and tryClip return kInvalidInput (stage
//   kInvalid; *out untouched), intersect and clip throw
//   tricyl::InvalidInput;
// - intersect, tryIntersect and decideIntersect agree;
// - endpoint form: the helper properties of fuzz_endpoint_form.h.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "fuzz_check.h"
#include "fuzz_endpoint_form.h"
#include "fuzz_input.h"
#include "query_oracles.h"
#include "tricyl/point_cylinder.h"
#include "tricyl/segment_cylinder.h"

namespace {

using tricyl::Answer;
using tricyl::Interval;
using tricyl::Stage;
using tricyl::fuzz::check;
using tricyl::fuzz::SegmentCase;
using tricyl::oracle::Q;

template <class S>
bool sameInterval(const Interval<S>& x, const Interval<S>& y) {
  return tricyl::fuzz::sameBits(x.lo, y.lo) &&
         tricyl::fuzz::sameBits(x.hi, y.hi);
}

/// The header's bound on |lo - lo*| and |hi - hi*|, plus the reference's
/// 2^-200 (so the check cannot fail spuriously).
template <class S>
Q endpointBound() {
  Q bound(1e-14);
  if (sizeof(S) == 4) bound += Q(0x1p-25);
  return bound + Q(0x1p-190);
}

/// lo <= hi in [0, 1], and both within the bound of the references.
template <class S>
void checkInterval(const Interval<S>& iv, const Q& lo_ref, const Q& hi_ref,
                   const char* what_range, const char* what_bound,
                   const SegmentCase<S>& c) {
  check(iv.lo >= 0 && iv.hi <= 1 && iv.lo <= iv.hi, what_range, c);
  const Q e_lo = abs(Q(double(iv.lo)) - lo_ref);
  const Q e_hi = abs(Q(double(iv.hi)) - hi_ref);
  if (e_lo <= endpointBound<S>() && e_hi <= endpointBound<S>()) return;
  std::fprintf(stderr, "interval [%a, %a], reference [%.17g, %.17g]\n",
               double(iv.lo), double(iv.hi), lo_ref.get_d(), hi_ref.get_d());
  std::fprintf(stderr, "errors %.3g, %.3g\n", e_lo.get_d(), e_hi.get_d());
  check(false, what_bound, c);
}

template <class S>
void run(const SegmentCase<S>& c) {
  namespace fz = tricyl::fuzz;
  fz::maybePrint(c);
  fz::checkEndpointForm(c);
  const tricyl::Cylinder<S> cyl{c.shape.radius, c.shape.lz};
  const tricyl::Pose<S>& pose = c.shape.pose;
  const tricyl::Segment<S>& seg = c.seg;
  const Interval<S> sentinel{S(7), S(-7)};

  if (!fz::valid(c)) {
    check(tricyl::tryIntersect(cyl, pose, seg) == Answer::kInvalidInput,
          "tryIntersect != kInvalidInput on invalid input", c);
    const tricyl::Decision d = tricyl::decideIntersect(cyl, pose, seg);
    check(d.answer == Answer::kInvalidInput && d.stage == Stage::kInvalid,
          "decideIntersect != {kInvalidInput, kInvalid} on invalid input", c);
    Interval<S> out = sentinel;
    check(tricyl::tryClip(cyl, pose, seg, &out) == Answer::kInvalidInput,
          "tryClip != kInvalidInput on invalid input", c);
    check(sameInterval(out, sentinel), "tryClip wrote *out on invalid input",
          c);
    bool threw = false;
    try {
      (void)tricyl::intersect(cyl, pose, seg);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "intersect did not throw InvalidInput on invalid input", c);
    threw = false;
    try {
      (void)tricyl::clip(cyl, pose, seg);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "clip did not throw InvalidInput on invalid input", c);
    return;
  }

  const tricyl::Segment<S> rev_seg{seg.q, seg.p};
  const tricyl::Segment<S> refl_seg{fz::neg(seg.p), fz::neg(seg.q)};
  Answer a, turned, flipped, ac, p_in, q_in;
  tricyl::Decision d;
  Interval<S> out = sentinel;
  std::optional<Interval<S>> iv, rev, refl;
  bool b = false, threw = false;
  {
    fz::FpTraps traps;
    a = tricyl::tryIntersect(cyl, pose, seg);
    d = tricyl::decideIntersect(cyl, pose, seg);
    ac = tricyl::tryClip(cyl, pose, seg, &out);
    try {
      b = tricyl::intersect(cyl, pose, seg);
      iv = tricyl::clip(cyl, pose, seg);
      rev = tricyl::clip(cyl, pose, rev_seg);
      refl = tricyl::clip(cyl, fz::reflectedPose(pose), refl_seg);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    turned = tricyl::tryIntersect(cyl, fz::quarterTurnPose(pose, false), seg);
    flipped = tricyl::tryIntersect(cyl, fz::quarterTurnPose(pose, true), seg);
    p_in = tricyl::tryContains(cyl, pose, seg.p);
    q_in = tricyl::tryContains(cyl, pose, seg.q);
  }
  check(!threw, "intersect or clip threw on valid input", c);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", c);
  check(d.answer == a, "decideIntersect != tryIntersect", c);
  check(d.stage != Stage::kInvalid, "stage kInvalid on valid input", c);
  check(b == (a == Answer::kIntersect), "intersect != tryIntersect", c);

  const auto ref = tricyl::oracle::segmentInterval(
      {double(cyl.radius), double(cyl.lz)}, fz::widen(pose),
      {fz::widen(seg.p), fz::widen(seg.q)});
  check(b == !ref.empty, "intersect disagrees with the exact oracle", c);
  check(turned == a, "answer changes under a quarter turn about the axis", c);
  check(flipped == a, "answer changes when the axis is flipped", c);
  check(p_in != Answer::kIntersect || b, "p contained but no hit", c);
  check(q_in != Answer::kIntersect || b, "q contained but no hit", c);
  if (seg.p.x == seg.q.x && seg.p.y == seg.q.y && seg.p.z == seg.q.z)
    check(a == p_in, "a point segment differs from point containment", c);

  // The interval.
  check(ac == a, "tryClip != tryIntersect", c);
  if (ac != Answer::kIntersect)
    check(sameInterval(out, sentinel), "tryClip wrote *out on a miss", c);
  check(iv.has_value() == b, "clip().has_value() != intersect", c);
  check(rev.has_value() == b, "clip(q, p).has_value() != intersect", c);
  check(refl.has_value() == b,
        "clip().has_value() changes under the point reflection", c);
  if (!b) return;
  check(sameInterval(*iv, out), "clip and tryClip give different intervals", c);
  Q lo, hi;
  tricyl::oracle::referenceEndpoints(ref, &lo, &hi);
  checkInterval(*iv, lo, hi, "clip: not lo <= hi in [0, 1]",
                "clip: endpoint beyond the documented bound", c);
  checkInterval(
      *rev, Q(1 - hi), Q(1 - lo), "clip(q, p): not lo <= hi in [0, 1]",
      "clip(q, p): endpoint beyond the bound of [1 - hi*, 1 - lo*]", c);
  checkInterval(*refl, lo, hi, "reflected clip: not lo <= hi in [0, 1]",
                "reflected clip: endpoint beyond the documented bound", c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data,
                                      std::size_t size) {
  if (size == 0) return 0;
  using tricyl::fuzz::decodeSegment;
  // Bit 3 of the flags byte selects float inputs (4-byte patterns).
  if (data[0] & 8)
    run(decodeSegment<float>(data, size));
  else
    run(decodeSegment<double>(data, size));
  return 0;
}
