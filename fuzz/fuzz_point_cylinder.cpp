// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::contains / tryContains / decideContains for a
// point in a cylinder (include/tricyl/point_cylinder.h), with the cylinder
// given directly or built by cylinderFromAxis / cylinderFromEndpoints
// (include/tricyl/endpoint_form.h), on inputs decoded from raw bytes
// (fuzz_input.h: decodePoint). Built with -fsanitize=fuzzer,address,undefined.
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no FE_INVALID or
//   FE_DIVBYZERO inside the library calls (trapped);
// - valid input (all finite, radius and lz >= 0): contains equals the exact
//   oracle (compare/query_oracles.h: pointInCylinder), and so do the point
//   reflection of the scene (t and x negated) and the quarter turn of the
//   pose about the axis, with and without flipping the axis (exact
//   symmetries of the cylinder);
// - invalid input (NaN or Inf anywhere, negative radius or lz):
//   tryContains and decideContains return kInvalidInput (stage kInvalid)
//   and contains throws tricyl::InvalidInput;
// - contains, tryContains and decideContains agree;
// - endpoint form: the helper properties of fuzz_endpoint_form.h.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.h"
#include "fuzz_endpoint_form.h"
#include "fuzz_input.h"
#include "query_oracles.h"
#include "tricyl/point_cylinder.h"

namespace {

using tricyl::Answer;
using tricyl::Stage;
using tricyl::fuzz::check;
using tricyl::fuzz::PointCase;

template <class S>
void run(const PointCase<S>& c) {
  namespace fz = tricyl::fuzz;
  fz::maybePrint(c);
  fz::checkEndpointForm(c);
  const tricyl::Cylinder<S> cyl{c.shape.radius, c.shape.lz};
  const tricyl::Pose<S>& pose = c.shape.pose;

  if (!fz::valid(c)) {
    check(tricyl::tryContains(cyl, pose, c.x) == Answer::kInvalidInput,
          "tryContains != kInvalidInput on invalid input", c);
    const tricyl::Decision d = tricyl::decideContains(cyl, pose, c.x);
    check(d.answer == Answer::kInvalidInput && d.stage == Stage::kInvalid,
          "decideContains != {kInvalidInput, kInvalid} on invalid input", c);
    bool threw = false;
    try {
      (void)tricyl::contains(cyl, pose, c.x);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "contains did not throw InvalidInput on invalid input", c);
    return;
  }

  Answer a, reflected, turned, flipped;
  tricyl::Decision d;
  bool b = false, threw = false;
  {
    fz::FpTraps traps;
    a = tricyl::tryContains(cyl, pose, c.x);
    d = tricyl::decideContains(cyl, pose, c.x);
    try {
      b = tricyl::contains(cyl, pose, c.x);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    reflected = tricyl::tryContains(cyl, fz::reflectedPose(pose), fz::neg(c.x));
    turned = tricyl::tryContains(cyl, fz::quarterTurnPose(pose, false), c.x);
    flipped = tricyl::tryContains(cyl, fz::quarterTurnPose(pose, true), c.x);
  }
  check(!threw, "contains threw on valid input", c);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", c);
  check(d.answer == a, "decideContains != tryContains", c);
  check(d.stage != Stage::kInvalid, "stage kInvalid on valid input", c);
  check(b == (a == Answer::kIntersect), "contains != tryContains", c);

  const bool truth = tricyl::oracle::pointInCylinder(
      {double(cyl.radius), double(cyl.lz)}, fz::widen(pose), fz::widen(c.x));
  check(b == truth, "contains disagrees with the exact oracle", c);
  check(reflected == a, "answer changes under the point reflection", c);
  check(turned == a, "answer changes under a quarter turn about the axis", c);
  check(flipped == a, "answer changes when the axis is flipped", c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data,
                                      std::size_t size) {
  if (size == 0) return 0;
  using tricyl::fuzz::decodePoint;
  using tricyl::fuzz::ShapeKind;
  // Bit 3 of the flags byte selects float inputs (4-byte patterns).
  if (data[0] & 8)
    run(decodePoint<float>(data, size, ShapeKind::kCylinder));
  else
    run(decodePoint<double>(data, size, ShapeKind::kCylinder));
  return 0;
}
