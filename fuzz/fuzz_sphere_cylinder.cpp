// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::intersect / tryIntersect / decideIntersect for
// a sphere and a cylinder (include/tricyl/sphere_cylinder.h), with the
// cylinder given directly or built by cylinderFromAxis /
// cylinderFromEndpoints (include/tricyl/endpoint_form.h), on inputs decoded
// from raw bytes (fuzz_input.h: decodeSphere). Built with
// -fsanitize=fuzzer,address,undefined.
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no FE_INVALID or
//   FE_DIVBYZERO inside the library calls (trapped);
// - valid input (all finite, radius, lz and rho >= 0): intersect equals the
//   exact oracle (compare/query_oracles.h: sphereCylinder, the local ball
//   of radius rho), and so do the point reflection of the scene and the
//   quarter turn of the pose about the axis, with and without flipping it;
// - cross-query: the sphere of radius 0 is point containment (tryContains
//   of point_cylinder.h on the centre), a contained centre means a hit, and
//   a hit stays a hit when rho grows by one ulp;
// - invalid input (NaN or Inf anywhere, negative radius, lz or rho):
//   tryIntersect and decideIntersect return kInvalidInput (stage kInvalid)
//   and intersect throws tricyl::InvalidInput;
// - intersect, tryIntersect and decideIntersect agree;
// - endpoint form: the helper properties of fuzz_endpoint_form.h.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "fuzz_check.h"
#include "fuzz_endpoint_form.h"
#include "fuzz_input.h"
#include "query_oracles.h"
#include "tricyl/point_cylinder.h"
#include "tricyl/sphere_cylinder.h"

namespace {

using tricyl::Answer;
using tricyl::Stage;
using tricyl::fuzz::check;
using tricyl::fuzz::SphereCase;

template <class S>
void run(const SphereCase<S>& c) {
  namespace fz = tricyl::fuzz;
  fz::maybePrint(c);
  fz::checkEndpointForm(c);
  const tricyl::Cylinder<S> cyl{c.shape.radius, c.shape.lz};
  const tricyl::Pose<S>& pose = c.shape.pose;
  const tricyl::Sphere<S>& sph = c.sphere;

  if (!fz::valid(c)) {
    check(tricyl::tryIntersect(cyl, pose, sph) == Answer::kInvalidInput,
          "tryIntersect != kInvalidInput on invalid input", c);
    const tricyl::Decision d = tricyl::decideIntersect(cyl, pose, sph);
    check(d.answer == Answer::kInvalidInput && d.stage == Stage::kInvalid,
          "decideIntersect != {kInvalidInput, kInvalid} on invalid input", c);
    bool threw = false;
    try {
      (void)tricyl::intersect(cyl, pose, sph);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "intersect did not throw InvalidInput on invalid input", c);
    return;
  }

  const S grown_rho =
      std::nextafter(sph.radius, std::numeric_limits<S>::infinity());
  const bool can_grow = std::isfinite(grown_rho);
  Answer a, reflected, turned, flipped, point, zero, grown = Answer::kDisjoint;
  tricyl::Decision d;
  bool b = false, threw = false;
  {
    fz::FpTraps traps;
    a = tricyl::tryIntersect(cyl, pose, sph);
    d = tricyl::decideIntersect(cyl, pose, sph);
    try {
      b = tricyl::intersect(cyl, pose, sph);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    reflected = tricyl::tryIntersect(
        cyl, fz::reflectedPose(pose),
        tricyl::Sphere<S>{fz::neg(sph.center), sph.radius});
    turned = tricyl::tryIntersect(cyl, fz::quarterTurnPose(pose, false), sph);
    flipped = tricyl::tryIntersect(cyl, fz::quarterTurnPose(pose, true), sph);
    point = tricyl::tryContains(cyl, pose, sph.center);
    zero = tricyl::tryIntersect(cyl, pose, tricyl::Sphere<S>{sph.center, S(0)});
    if (can_grow)
      grown = tricyl::tryIntersect(cyl, pose,
                                   tricyl::Sphere<S>{sph.center, grown_rho});
  }
  check(!threw, "intersect threw on valid input", c);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", c);
  check(d.answer == a, "decideIntersect != tryIntersect", c);
  check(d.stage != Stage::kInvalid, "stage kInvalid on valid input", c);
  check(b == (a == Answer::kIntersect), "intersect != tryIntersect", c);

  const bool truth = tricyl::oracle::sphereCylinder(
      {double(cyl.radius), double(cyl.lz)}, fz::widen(pose),
      {fz::widen(sph.center), double(sph.radius)});
  check(b == truth, "intersect disagrees with the exact oracle", c);
  check(reflected == a, "answer changes under the point reflection", c);
  check(turned == a, "answer changes under a quarter turn about the axis", c);
  check(flipped == a, "answer changes when the axis is flipped", c);
  check(zero == point, "rho = 0 differs from point containment", c);
  check(point != Answer::kIntersect || b,
        "centre contained but the sphere misses", c);
  check(!can_grow || !b || grown == Answer::kIntersect,
        "a hit becomes a miss when rho grows by one ulp", c);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data,
                                      std::size_t size) {
  if (size == 0) return 0;
  using tricyl::fuzz::decodeSphere;
  // Bit 3 of the flags byte selects float inputs (4-byte patterns).
  if (data[0] & 8)
    run(decodeSphere<float>(data, size));
  else
    run(decodeSphere<double>(data, size));
  return 0;
}
