// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::intersect / tryIntersect / decideIntersect for
// an unbounded line and a cylinder and the entry/exit interval tricyl::clip
// / tryClip along the line (include/tricyl/line_cylinder.h), with the
// cylinder given directly or built by cylinderFromAxis /
// cylinderFromEndpoints (include/tricyl/endpoint_form.h), on inputs decoded
// from raw bytes (fuzz_input.h: decodeSegment, the line through p and q).
// Built with -fsanitize=fuzzer,address,undefined.
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no FE_INVALID or
//   FE_DIVBYZERO inside the library calls (trapped);
// - valid input (all finite, radius and lz >= 0): intersect equals the
//   exact oracle (compare/query_oracles.h: lineInterval non-empty), and so
//   does the quarter turn of the pose about the axis, with and without
//   flipping it; p contained (tryContains of point_cylinder.h) means a hit;
//   the segment [p, q] (segment_cylinder.h) hits exactly when the oracle's
//   line interval meets [0, 1] (lineMeetsUnit), and a segment hit implies a
//   line hit;
// - the interval: tryClip answers as tryIntersect (and leaves *out
//   untouched unless kIntersect), clip(...).has_value() == intersect, clip
//   and tryClip give the same interval, lo <= hi, no NaN, and each end
//   against the oracle's reference (within 2^-200 of the exact end):
//   * an unbounded reference end (local direction zero, p inside) is the
//     infinity of its side;
//   * a finite returned end is within the header's bound,
//     1e-14 max(1, |s*|) for double, (2^-24 + 1e-14) max(1, |s*|) for float;
//   * an infinite returned end has the sign of s*, and s* is beyond the
//     largest finite S or within the bound of it (the header's overflow
//     rule);
//   the same for the reversed line (q, p) against [1 - hi*, 1 - lo*] and
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
#include <cstdio>
#include <limits>
#include <optional>

#include "fuzz_check.h"
#include "fuzz_endpoint_form.h"
#include "fuzz_input.h"
#include "query_oracles.h"
#include "tricyl/line_cylinder.h"
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

/// A reference end: unbounded (the infinity of its side) or a value within
/// 2^-200 of the exact end.
struct End {
  bool unbounded = false;
  Q value;
};

/// The header's relative bound factor b: |s - s*| <= b max(1, |s*|).
template <class S>
Q relativeBound() {
  Q b(1e-14);
  if (sizeof(S) == 4) b += Q(0x1p-24);
  return b;
}

/// One returned end against its reference; side -1 for lo, +1 for hi.
template <class S>
bool endOk(S v, const End& ref, int side) {
  if (std::isnan(v)) return false;
  if (ref.unbounded) return std::isinf(v) && (v > 0) == (side > 0);
  const Q mag = abs(ref.value);
  const Q scale = mag > 1 ? mag : Q(1);
  const Q allowed = relativeBound<S>() * scale + Q(0x1p-190);
  if (std::isinf(v)) {
    // Overflow: the sign of s*, and |s*| beyond or within the bound of the
    // largest finite S.
    const bool sign_ok = (v > 0) ? ref.value > 0 : ref.value < 0;
    return sign_ok && mag + allowed >= Q(double(std::numeric_limits<S>::max()));
  }
  return abs(Q(double(v)) - ref.value) <= allowed;
}

template <class S>
void checkInterval(const Interval<S>& iv, const End& lo, const End& hi,
                   const char* what, const SegmentCase<S>& c) {
  const bool ok = iv.lo <= iv.hi && endOk(iv.lo, lo, -1) && endOk(iv.hi, hi, 1);
  if (ok) return;
  std::fprintf(stderr, "interval [%a, %a], reference [%s%.17g, %s%.17g]\n",
               double(iv.lo), double(iv.hi), lo.unbounded ? "unbounded " : "",
               lo.unbounded ? 0.0 : lo.value.get_d(),
               hi.unbounded ? "unbounded " : "",
               hi.unbounded ? 0.0 : hi.value.get_d());
  check(false, what, c);
}

template <class S>
void run(const SegmentCase<S>& c) {
  namespace fz = tricyl::fuzz;
  fz::maybePrint(c);
  fz::checkEndpointForm(c);
  const tricyl::Cylinder<S> cyl{c.shape.radius, c.shape.lz};
  const tricyl::Pose<S>& pose = c.shape.pose;
  const tricyl::Line<S> line{c.seg.p, c.seg.q};
  const Interval<S> sentinel{S(7), S(-7)};

  if (!fz::valid(c)) {
    check(tricyl::tryIntersect(cyl, pose, line) == Answer::kInvalidInput,
          "tryIntersect != kInvalidInput on invalid input", c);
    const tricyl::Decision d = tricyl::decideIntersect(cyl, pose, line);
    check(d.answer == Answer::kInvalidInput && d.stage == Stage::kInvalid,
          "decideIntersect != {kInvalidInput, kInvalid} on invalid input", c);
    Interval<S> out = sentinel;
    check(tricyl::tryClip(cyl, pose, line, &out) == Answer::kInvalidInput,
          "tryClip != kInvalidInput on invalid input", c);
    check(sameInterval(out, sentinel), "tryClip wrote *out on invalid input",
          c);
    bool threw = false;
    try {
      (void)tricyl::intersect(cyl, pose, line);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "intersect did not throw InvalidInput on invalid input", c);
    threw = false;
    try {
      (void)tricyl::clip(cyl, pose, line);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "clip did not throw InvalidInput on invalid input", c);
    return;
  }

  const tricyl::Line<S> rev_line{line.q, line.p};
  const tricyl::Line<S> refl_line{fz::neg(line.p), fz::neg(line.q)};
  Answer a, turned, flipped, ac, p_in, seg;
  tricyl::Decision d;
  Interval<S> out = sentinel;
  std::optional<Interval<S>> iv, rev, refl;
  bool b = false, threw = false;
  {
    fz::FpTraps traps;
    a = tricyl::tryIntersect(cyl, pose, line);
    d = tricyl::decideIntersect(cyl, pose, line);
    ac = tricyl::tryClip(cyl, pose, line, &out);
    try {
      b = tricyl::intersect(cyl, pose, line);
      iv = tricyl::clip(cyl, pose, line);
      rev = tricyl::clip(cyl, pose, rev_line);
      refl = tricyl::clip(cyl, fz::reflectedPose(pose), refl_line);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    turned = tricyl::tryIntersect(cyl, fz::quarterTurnPose(pose, false), line);
    flipped = tricyl::tryIntersect(cyl, fz::quarterTurnPose(pose, true), line);
    p_in = tricyl::tryContains(cyl, pose, line.p);
    seg = tricyl::tryIntersect(cyl, pose, c.seg);
  }
  check(!threw, "intersect or clip threw on valid input", c);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", c);
  check(d.answer == a, "decideIntersect != tryIntersect", c);
  check(d.stage != Stage::kInvalid, "stage kInvalid on valid input", c);
  check(b == (a == Answer::kIntersect), "intersect != tryIntersect", c);

  const auto ref = tricyl::oracle::lineInterval(
      {double(cyl.radius), double(cyl.lz)}, fz::widen(pose),
      {fz::widen(line.p), fz::widen(line.q)});
  check(b == !ref.empty, "intersect disagrees with the exact oracle", c);
  check(turned == a, "answer changes under a quarter turn about the axis", c);
  check(flipped == a, "answer changes when the axis is flipped", c);
  check(p_in != Answer::kIntersect || b, "p contained but no hit", c);
  check((seg == Answer::kIntersect) == tricyl::oracle::lineMeetsUnit(ref),
        "segment answer != the oracle's line interval meeting [0, 1]", c);
  check(seg != Answer::kIntersect || b, "segment hit but line miss", c);

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
  End lo, hi;
  lo.unbounded = ref.lower.empty();
  hi.unbounded = ref.upper.empty();
  for (std::size_t i = 0; i < ref.lower.size(); ++i) {
    const Q v = tricyl::oracle::approx(ref.lower[i]);
    if (i == 0 || v > lo.value) lo.value = v;
  }
  for (std::size_t i = 0; i < ref.upper.size(); ++i) {
    const Q v = tricyl::oracle::approx(ref.upper[i]);
    if (i == 0 || v < hi.value) hi.value = v;
  }
  checkInterval(*iv, lo, hi, "clip: end beyond the documented bound", c);
  End rlo, rhi;  // s -> 1 - s
  rlo.unbounded = hi.unbounded;
  rhi.unbounded = lo.unbounded;
  if (!hi.unbounded) rlo.value = 1 - hi.value;
  if (!lo.unbounded) rhi.value = 1 - lo.value;
  checkInterval(*rev, rlo, rhi,
                "clip(q, p): end beyond the bound of [1 - hi*, 1 - lo*]", c);
  checkInterval(*refl, lo, hi,
                "reflected clip: end beyond the documented bound", c);
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
