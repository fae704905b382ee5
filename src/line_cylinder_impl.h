// SPDX-License-Identifier: BSD-3-Clause
// Shared by the segment and the line queries (src/segment_cylinder.cpp,
// src/line_cylinder.cpp): widened and validated inputs, and the entry/exit
// interval (src/line_cylinder_interval.cpp). A segment is the line through
// p and q restricted to s in [0, 1]; the interval code is written once for
// both, the restriction being two extra candidates 0 and 1.
#pragma once

#include <limits>
#include <type_traits>

#include "cylinder_queries_impl.h"
#include "tricyl/types.h"

namespace tricyl::detail {

/// The inputs of a segment or line query, widened to double (exact for
/// float), and the magnitudes for the range gate.
struct LinearInputs {
  Cylinder<double> cyl;
  Pose<double> pose;
  Vec3<double> p, q;
  double max_len = 0, max_unitless = 0;
  bool float_bits_ok = true;  ///< false: a float input NaN or Inf (not widened)
};

template <class S>
inline LinearInputs widenLinear(const Cylinder<S>& cyl, const Pose<S>& pose,
                                const Vec3<S>& p, const Vec3<S>& q) {
  LinearInputs in;
  if constexpr (std::is_same_v<S, float>) {
    // Validated in float before widening (floatBitsFinite); the inputs stay
    // zero and validateLinear rejects them.
    if (!floatBitsFinite(cyl, pose, p, q)) {
      in.float_bits_ok = false;
      return in;
    }
  }
  in.cyl = {double(cyl.radius), double(cyl.lz)};
  in.pose = widen(pose);
  in.p = widen(p);
  in.q = widen(q);
  return in;
}

/// False on NaN/Inf anywhere or a negative size; sets the magnitudes.
inline bool validateLinear(LinearInputs& in) {
  const auto& p = in.p;
  const auto& q = in.q;
  return in.float_bits_ok &&
         scanFinite({in.cyl.radius, in.cyl.lz, p.x, p.y, p.z, q.x, q.y, q.z},
                    in.pose, &in.max_len, &in.max_unitless) &&
         in.cyl.radius >= 0 && in.cyl.lz >= 0;
}

/// The segment query with one kernel K of src/filter.h, for runStages (the
/// triangle's degenerate hand-off, src/triangle_cylinder.cpp).
template <class K>
struct SegmentPred {
  static Tri run(const LinearInputs& in, bool* early) {
    const SegmentQuery q{in.cyl, in.pose, in.p, in.q, in.max_unitless};
    KernelCtx<K, SegmentQuery> c(q);
    return segmentCylinder(c, early);
  }
};

/// The exact Boolean of the segment (kSegment) or the line in double:
/// validation, then the per-sign stages (src/per_sign.h). No copy of the
/// inputs (decideIntersect in double calls it directly).
template <bool kSegment>
Decision decideLinear(const Cylinder<double>& cyl, const Pose<double>& pose,
                      const Vec3<double>& p, const Vec3<double>& q) {
  double max_len = 0, max_unitless = 0;
  bool gate = quickGate(cyl, pose, p, q, 0.0, &max_unitless);
  if (!gate) {
    if (!scanFinite({cyl.radius, cyl.lz, p.x, p.y, p.z, q.x, q.y, q.z}, pose,
                    &max_len, &max_unitless) ||
        !(cyl.radius >= 0 && cyl.lz >= 0))
      return {Answer::kInvalidInput, Stage::kInvalid};
    gate = rangeGateOk(max_len, max_unitless);
  }
  const LinearQuery<kSegment> lq{cyl, pose, p, q, max_unitless};
  return runPerSign(lq, gate, [](auto& c, bool* early) {
    if constexpr (kSegment)
      return segmentCylinder(c, early);
    else
      return lineCylinder(c, early);
  });
}

/// The same on widened inputs (float, and the interval queries, which keep
/// them for linearInterval); sets in's magnitudes.
template <bool kSegment>
Decision decideLinear(LinearInputs& in) {
  if (!validateLinear(in)) return {Answer::kInvalidInput, Stage::kInvalid};
  return decideLinear<kSegment>(in.cyl, in.pose, in.p, in.q);
}

/// decideIntersect for a segment or line {p, q} of S (float: validated by
/// its bits, then widened).
template <bool kSegment, class S>
Decision decideLinearAs(const Cylinder<S>& cyl, const Pose<S>& pose,
                        const Vec3<S>& p, const Vec3<S>& q) {
  if constexpr (std::is_same_v<S, double>) {
    return decideLinear<kSegment>(cyl, pose, p, q);
  } else {
    LinearInputs in = widenLinear(cyl, pose, p, q);
    return decideLinear<kSegment>(in);
  }
}

/// The entry/exit interval of a query whose exact Boolean said "intersect"
/// (its emptiness is never read from these numbers). `segment`: the
/// interval of { s in [0, 1] : p(s) in cylinder }, clamped to [0, 1], each
/// end within 1.9e-15 of the exact one. Otherwise the line's
/// { s real : p(s) in cylinder }: each end within 1.9e-15 max(1, |s*|) of
/// the exact s*; [-inf, +inf] when the local direction R^T (q - p) is zero
/// (the line is a point, inside); an end whose exact value exceeds the
/// largest double in magnitude is returned as the infinity of its sign.
/// Derivation in src/line_cylinder_interval.cpp.
Interval<double> linearInterval(const LinearInputs& in, bool segment);

/// double -> S for an interval end: round to nearest, except that a value
/// beyond the largest finite S becomes the infinity of its sign (no
/// out-of-range conversion). Monotone, so lo <= hi is kept.
template <class S>
inline S narrowEnd(double x) {
  constexpr double kMax = double(std::numeric_limits<S>::max());
  if (x > kMax) return std::numeric_limits<S>::infinity();
  if (x < -kMax) return -std::numeric_limits<S>::infinity();
  return S(x);
}

}  // namespace tricyl::detail
