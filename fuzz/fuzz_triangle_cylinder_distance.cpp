// SPDX-License-Identifier: BSD-3-Clause
// libFuzzer target: tricyl::distance / tryDistance (and tightenDistance)
// (include/tricyl/triangle_cylinder_distance.h) on the triangle target's
// input layout (fuzz_input.h, decode()). Built with
// -fsanitize=fuzzer,address,undefined (TRICYL_BUILD_FUZZ).
//
// Properties (any violation prints the case in hex floats and aborts):
// - no crash, no sanitizer report, and on valid input no floating-point
//   invalid operation or division by zero (trapped around the calls);
// - valid input: tryDistance is kIntersect exactly when the exact Boolean
//   tryIntersect is, with distance 0 and error_bound 0, and kDisjoint
//   otherwise with a positive distance and an error_bound >= 0, both
//   finite and with finite nearest points when |R_ij| <= 2 and the lengths
//   are below max/16 (else the distance may be beyond the range: +inf);
//   distance (throwing form) returns the same;
//   every reordering of the vertices and the point reflection of the
//   scene (t, a, b, c negated, exact) give distances within the sum of
//   the two error bounds; the float result is the double result for the
//   widened inputs, rounded;
// - invalid input (NaN or Inf anywhere, negative radius or lz):
//   tryDistance returns kInvalidInput and leaves its output alone, and
//   distance throws tricyl::InvalidInput.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>
#include <type_traits>

#include "fuzz_check.h"
#include "fuzz_input.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"

namespace {

using tricyl::Answer;
using tricyl::DistanceResult;
using tricyl::fuzz::Case;
using tricyl::fuzz::check;
using tricyl::fuzz::FpTraps;

template <class S>
bool finite(const tricyl::Vec3<S>& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

template <class S>
void run(const Case<S>& c) {
  const bool valid = tricyl::fuzz::valid(c);
  tricyl::fuzz::maybePrint(c);
  if (!valid) {
    DistanceResult<S> out{};
    out.distance = S(42);
    check(tricyl::tryDistance(c.cyl, c.pose, c.tri, &out) ==
                  Answer::kInvalidInput &&
              out.distance == S(42),
          "tryDistance on invalid input: not kInvalidInput, or output written",
          c);
    bool threw = false;
    try {
      (void)tricyl::distance(c.cyl, c.pose, c.tri);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    check(threw, "distance did not throw InvalidInput on invalid input", c);
    return;
  }
  DistanceResult<S> r{}, thrown{};
  Answer a, boolean;
  Answer perm_answer[5];
  DistanceResult<S> perm[5], refl{};
  Answer refl_answer;
  bool threw = false;
  {
    FpTraps traps;
    a = tricyl::tryDistance(c.cyl, c.pose, c.tri, &r);
    boolean = tricyl::tryIntersect(c.cyl, c.pose, c.tri);
    try {
      thrown = tricyl::distance(c.cyl, c.pose, c.tri);
    } catch (const tricyl::InvalidInput&) {
      threw = true;
    }
    const auto orders = tricyl::fuzz::otherVertexOrders(c.tri);
    for (int i = 0; i < 5; ++i)
      perm_answer[i] = tricyl::tryDistance(c.cyl, c.pose, orders[i], &perm[i]);
    refl_answer =
        tricyl::tryDistance(c.cyl, tricyl::fuzz::reflectedPose(c.pose),
                            tricyl::fuzz::reflectedTriangle(c.tri), &refl);
  }
  check(!threw, "distance threw on valid input", c);
  check(a != Answer::kInvalidInput, "kInvalidInput on valid input", c);
  check(a == boolean, "tryDistance's answer differs from tryIntersect", c);
  check(std::memcmp(&r.distance, &thrown.distance, sizeof(S)) == 0,
        "distance differs from tryDistance", c);
  // A huge R, or lengths near the top of the range, may put the distance
  // beyond the double range: it is then +inf (overflow), never NaN.
  double mr = 0;
  for (const auto& row : c.pose.R)
    for (S x : row) mr = std::max(mr, std::fabs(double(x)));
  double ml =
      std::max(std::fabs(double(c.cyl.radius)), std::fabs(double(c.cyl.lz)));
  for (const auto* v : {&c.tri.a, &c.tri.b, &c.tri.c, &c.pose.t})
    ml = std::max({ml, std::fabs(double(v->x)), std::fabs(double(v->y)),
                   std::fabs(double(v->z))});
  if (ml > double(std::numeric_limits<S>::max()) / 16) mr = 4;
  if (a == Answer::kIntersect) {
    check(r.distance == 0 && r.error_bound == 0,
          "intersecting, but distance or error_bound not 0", c);
  } else {
    check(r.distance > 0 && (mr > 2 || std::isfinite(r.distance)),
          "disjoint, but distance not positive and finite", c);
    check(r.error_bound >= 0 && (mr > 2 || std::isfinite(r.error_bound)),
          "error_bound negative, NaN or not finite", c);
  }
  // World points are R y + t: finite whenever R is a rotation-sized matrix.
  if (mr <= 2)
    check(finite(r.point_on_cylinder) && finite(r.point_on_triangle),
          "nearest point not finite", c);
  auto close = [&](const DistanceResult<S>& q) {
    const double gap = std::fabs(double(q.distance) - double(r.distance));
    if (!std::isfinite(double(r.distance))) return q.distance == r.distance;
    return gap <= (double(q.error_bound) + double(r.error_bound)) * 1.000001;
  };
  for (int i = 0; i < 5; ++i)
    check(perm_answer[i] == a && close(perm[i]),
          "distance depends on the vertex order beyond its error bounds", c);
  check(refl_answer == a && close(refl),
        "distance changes under the point reflection beyond its bounds", c);
  // tightenDistance (double): its interval is certified on its own, so it
  // must overlap tryDistance's, and it replaces the result only with a
  // narrower one; no FP exception.
  if constexpr (std::is_same_v<S, double>) {
    if (a == Answer::kDisjoint) {
      DistanceResult<double> t = r;
      bool tightened = false;
      {
        FpTraps traps;
        tightened = tricyl::tightenDistance(c.cyl, c.pose, c.tri, &t);
      }
      if (tightened) {
        check(t.error_bound < r.error_bound && t.distance > 0 &&
                  std::isfinite(t.distance),
              "tightenDistance: bound not narrower, or distance not positive",
              c);
        check(close(t), "tightenDistance's interval misses tryDistance's", c);
      }
    }
  }
  if constexpr (std::is_same_v<S, float>) {
    DistanceResult<double> w{};
    {
      FpTraps traps;
      (void)tricyl::tryDistance(
          tricyl::Cylinder<double>{c.cyl.radius, c.cyl.lz},
          tricyl::fuzz::widen(c.pose),
          tricyl::Triangle<double>{tricyl::fuzz::widen(c.tri.a),
                                   tricyl::fuzz::widen(c.tri.b),
                                   tricyl::fuzz::widen(c.tri.c)},
          &w);
    }
    const float f = float(w.distance);
    check(r.distance == f || (f == 0 && w.distance > 0),
          "float distance is not the double one rounded", c);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data,
                                      std::size_t size) {
  tricyl::fuzz::withTriangleCase(data, size, [](const auto& c) { run(c); });
  return 0;
}
