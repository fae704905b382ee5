// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::withinDistance / tryWithinDistance /
// decideWithinDistance (include/tricyl/triangle_cylinder_margin.h) on inputs
// decoded from raw bytes: the triangle query's layout (fuzz_input.h: decode)
// followed by one more scalar, the margin. Built with
// -fsanitize=fuzzer,address,undefined (TRICYL_BUILD_FUZZ).
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no FE_INVALID or
//   FE_DIVBYZERO inside the library calls (trapped);
// - valid input (all finite, radius, lz and margin >= 0): the answer equals
//   the exact margin oracle (compare/margin_oracle.h), and so does every
//   reordering of the vertices and the point reflection of the scene;
// - margin 0 is tryIntersect; a hit stays a hit when the margin grows by
//   one ulp; a triangle that meets the cylinder is within any margin;
// - invalid input (NaN or Inf anywhere, a negative radius, lz or margin):
//   kInvalidInput (stage kInvalid) and withinDistance throws InvalidInput;
// - withinDistance, tryWithinDistance and decideWithinDistance agree; the
//   local-frame overload agrees with the posed one for the identity pose.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "margin_oracle.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_margin.h"

namespace tricyl::fuzz {

/// The triangle case and a margin.
template <class S>
struct MarginCase {
  using Scalar = S;
  Case<S> c;
  S margin;
};

template <class S>
void print(const MarginCase<S>& m) {
  print(m.c);
  printScalar("m ", double(m.margin));
}

/// decode()'s layout, then the margin (the same scalar encodings).
template <class S>
MarginCase<S> decodeMargin(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  ScalarDecoder<S> dec(&in);
  MarginCase<S> m;
  m.c = decodeCase(&in, &dec);
  m.margin = dec.next();
  return m;
}

}  // namespace tricyl::fuzz

namespace {

using tricyl::Answer;
using tricyl::Stage;
using tricyl::fuzz::check;
using tricyl::fuzz::FpTraps;
using tricyl::fuzz::MarginCase;
using tricyl::fuzz::neg;
using tricyl::fuzz::widen;

template <class S>
void run(const MarginCase<S>& mc) {
  const auto& c = mc.c;
  const S m = mc.margin;
  tricyl::fuzz::maybePrint(mc);
  const bool valid = tricyl::fuzz::valid(c) && std::isfinite(m) && !(m < 0);

  if (!valid) {
    check(tricyl::tryWithinDistance(c.cyl, c.pose, c.tri, m) ==
              Answer::kInvalidInput,
          "tryWithinDistance != kInvalidInput on invalid input", mc);
    const tricyl::Decision d =
        tricyl::decideWithinDistance(c.cyl, c.pose, c.tri, m);
    check(d.answer == Answer::kInvalidInput && d.stage == Stage::kInvalid,
          "decideWithinDistance != {kInvalidInput, kInvalid}", mc);
    bool threw = false;
    try {
      (void)tricyl::withinDistance(c.cyl, c.pose, c.tri, m);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "withinDistance did not throw InvalidInput", mc);
    return;
  }

  const S grown = std::nextafter(m, std::numeric_limits<S>::infinity());
  const bool can_grow = std::isfinite(grown);
  Answer a, zero, hit, grown_a = Answer::kIntersect, perm[5], reflected;
  tricyl::Decision d;
  bool b = false, threw = false;
  {
    FpTraps traps;
    a = tricyl::tryWithinDistance(c.cyl, c.pose, c.tri, m);
    d = tricyl::decideWithinDistance(c.cyl, c.pose, c.tri, m);
    try {
      b = tricyl::withinDistance(c.cyl, c.pose, c.tri, m);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    zero = tricyl::tryWithinDistance(c.cyl, c.pose, c.tri, S(0));
    hit = tricyl::tryIntersect(c.cyl, c.pose, c.tri);
    if (can_grow)
      grown_a = tricyl::tryWithinDistance(c.cyl, c.pose, c.tri, grown);
    const auto& t = c.tri;
    const auto orders = tricyl::fuzz::otherVertexOrders(t);
    for (int i = 0; i < 5; ++i)
      perm[i] = tricyl::tryWithinDistance(c.cyl, c.pose, orders[i], m);
    tricyl::Pose<S> p = c.pose;
    p.t = neg(p.t);
    reflected =
        tricyl::tryWithinDistance(c.cyl, p, {neg(t.a), neg(t.b), neg(t.c)}, m);
  }
  check(!threw, "withinDistance threw on valid input", mc);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", mc);
  check(d.answer == a, "decideWithinDistance != tryWithinDistance", mc);
  check(d.stage != Stage::kInvalid, "stage kInvalid on valid input", mc);
  check(b == (a == Answer::kIntersect), "withinDistance != try...", mc);
  check(zero == hit, "margin 0 differs from intersect", mc);
  check(hit != Answer::kIntersect || b, "a hit is not within the margin", mc);
  check(!b || grown_a == Answer::kIntersect,
        "within becomes outside when the margin grows by one ulp", mc);
  for (Answer q : perm) check(q == a, "answer depends on the vertex order", mc);
  check(reflected == a, "answer changes under the point reflection", mc);
  if (c.identity_pose) {
    bool local = false;
    {
      FpTraps traps;
      local = tricyl::withinDistance(c.cyl, c.tri, m);
    }
    check(local == b, "local-frame withinDistance != posed", mc);
  }

  const bool truth = tricyl::margin_oracle::withinDistance(
      {double(c.cyl.radius), double(c.cyl.lz)}, widen(c.pose),
      {widen(c.tri.a), widen(c.tri.b), widen(c.tri.c)}, double(m));
  check(b == truth, "withinDistance disagrees with the exact oracle", mc);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data,
                                      std::size_t size) {
  if (size == 0) return 0;
  // Bit 3 of the flags byte selects float inputs (4-byte patterns).
  if (data[0] & 8)
    run(tricyl::fuzz::decodeMargin<float>(data, size));
  else
    run(tricyl::fuzz::decodeMargin<double>(data, size));
  return 0;
}
