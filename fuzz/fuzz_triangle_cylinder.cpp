// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::intersect / tryIntersect / decideIntersect
// (include/tricyl/triangle_cylinder.h) on inputs decoded from raw bytes
// (fuzz_input.h: full double or float bit patterns mixed with structured
// values). Built with -fsanitize=fuzzer,address,undefined (TRICYL_BUILD_FUZZ).
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no floating-point
//   invalid operation or division by zero (trapped around the kernel calls:
//   the README promises no NaN is ever produced on valid input);
// - valid input (all finite, radius and lz >= 0): tryIntersect equals the
//   exact oracle (compare/oracle.h), and so does every reordering of the
//   triangle's vertices and the point reflection of the whole scene
//   (t, a, b, c negated: exact, and the cylinder is symmetric);
// - invalid input (NaN or Inf anywhere, negative radius or lz): tryIntersect
//   and decideIntersect return kInvalidInput (stage kInvalid) and intersect
//   throws tricyl::InvalidInput;
// - intersect, tryIntersect and decideIntersect agree; the local-frame
//   overload agrees with the posed one when the pose is the identity.
#include <cstddef>
#include <cstdint>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "oracle.h"
#include "tricyl/triangle_cylinder.h"

namespace {

using tricyl::Answer;
using tricyl::Stage;
using tricyl::fuzz::Case;
using tricyl::fuzz::check;
using tricyl::fuzz::FpTraps;
using tricyl::fuzz::widen;

template <class S>
void run(const Case<S>& c) {
  const bool valid = tricyl::fuzz::valid(c);
  tricyl::fuzz::maybePrint(c);

  if (!valid) {
    check(tricyl::tryIntersect(c.cyl, c.pose, c.tri) == Answer::kInvalidInput,
          "tryIntersect != kInvalidInput on invalid input", c);
    const tricyl::Decision d = tricyl::decideIntersect(c.cyl, c.pose, c.tri);
    check(d.answer == Answer::kInvalidInput && d.stage == Stage::kInvalid,
          "decideIntersect != {kInvalidInput, kInvalid} on invalid input", c);
    bool threw = false;
    try {
      (void)tricyl::intersect(c.cyl, c.pose, c.tri);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "intersect did not throw InvalidInput on invalid input", c);
    if (c.identity_pose) {
      threw = false;
      try {
        (void)tricyl::intersect(c.cyl, c.tri);
      } catch (const tricyl::InvalidInput&) {
        threw = true;
      }
      check(threw, "local intersect did not throw on invalid input", c);
    }
    return;
  }

  Answer a;
  tricyl::Decision d;
  bool b = false, threw = false;
  Answer perm[5], reflected;
  {
    FpTraps traps;
    a = tricyl::tryIntersect(c.cyl, c.pose, c.tri);
    d = tricyl::decideIntersect(c.cyl, c.pose, c.tri);
    try {
      b = tricyl::intersect(c.cyl, c.pose, c.tri);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    const auto orders = tricyl::fuzz::otherVertexOrders(c.tri);
    for (int i = 0; i < 5; ++i)
      perm[i] = tricyl::tryIntersect(c.cyl, c.pose, orders[i]);
    reflected = tricyl::tryIntersect(c.cyl, tricyl::fuzz::reflectedPose(c.pose),
                                     tricyl::fuzz::reflectedTriangle(c.tri));
  }
  check(!threw, "intersect threw on valid input", c);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", c);
  check(d.answer == a, "decideIntersect != tryIntersect", c);
  check(d.stage != Stage::kInvalid, "stage kInvalid on valid input", c);
  check(b == (a == Answer::kIntersect), "intersect != tryIntersect", c);
  if (c.identity_pose) {
    bool local = false;
    {
      FpTraps traps;
      local = tricyl::intersect(c.cyl, c.tri);
    }
    check(local == b, "local-frame intersect != posed intersect", c);
  }

  const bool truth = tricyl::oracle::triangleCylinder(
      {double(c.cyl.radius), double(c.cyl.lz)}, widen(c.pose),
      {widen(c.tri.a), widen(c.tri.b), widen(c.tri.c)});
  check(b == truth, "kernel disagrees with the exact oracle", c);
  for (Answer p : perm) check(p == a, "answer depends on the vertex order", c);
  check(reflected == a, "answer changes under the point reflection", c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data,
                                      std::size_t size) {
  tricyl::fuzz::withTriangleCase(data, size, [](const auto& c) { run(c); });
  return 0;
}
