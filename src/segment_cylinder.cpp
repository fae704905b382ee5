// SPDX-License-Identifier: BSD-3-Clause
// Segment vs cylinder: the exact Boolean (segmentCylinder in
// src/cylinder_queries_impl.h, decided sign by sign, src/per_sign.h) and the
// entry/exit interval. The interval is the line's (a segment is the line
// through p and q restricted to [0, 1]): src/line_cylinder_interval.cpp,
// written once for both, with the derivation of the 1.9e-15 guarantee
// (stage 1, running error bounds in double then long double, accepted at
// 2^-49) and of the exact stage 2 (GMP coefficients, mpf candidates).
#include "tricyl/segment_cylinder.h"

#include <string>

#include "line_cylinder_impl.h"

namespace tricyl {
namespace {

using detail::LinearInputs;

Decision decide(LinearInputs& in) { return detail::decideLinear<true>(in); }

template <class S>
Answer clipAs(const Cylinder<S>& cyl, const Pose<S>& pose,
              const Segment<S>& seg, Interval<S>* out) {
  LinearInputs in = detail::widenLinear(cyl, pose, seg.p, seg.q);
  const Decision d = decide(in);
  if (d.answer != Answer::kIntersect) return d.answer;
  const Interval<double> iv = detail::linearInterval(in, true);
  *out = {S(iv.lo), S(iv.hi)};  // in [0, 1]; nearest: monotone, lo <= hi
  return d.answer;
}

[[noreturn]] void throwInvalid(const char* what) {
  throw InvalidInput(std::string("tricyl::") + what +
                     "(cylinder, segment): NaN or infinite input, or a "
                     "negative radius or length");
}

}  // namespace

template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Segment<S>& segment) noexcept {
  return detail::decideLinearAs<true>(cylinder, pose, segment.p, segment.q);
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Segment<S>& segment) noexcept {
  return decideIntersect(cylinder, pose, segment).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Segment<S>& segment) {
  const Answer a = tryIntersect(cylinder, pose, segment);
  if (a == Answer::kInvalidInput) throwInvalid("intersect");
  return a == Answer::kIntersect;
}

template <class S>
Answer tryClip(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Segment<S>& segment, Interval<S>* out) noexcept {
  return clipAs(cylinder, pose, segment, out);
}

template <class S>
std::optional<Interval<S>> clip(const Cylinder<S>& cylinder,
                                const Pose<S>& pose,
                                const Segment<S>& segment) {
  Interval<S> iv{};
  const Answer a = clipAs(cylinder, pose, segment, &iv);
  if (a == Answer::kInvalidInput) throwInvalid("clip");
  if (a == Answer::kDisjoint) return std::nullopt;
  return iv;
}

template bool intersect(const Cylinder<float>&, const Pose<float>&,
                        const Segment<float>&);
template bool intersect(const Cylinder<double>&, const Pose<double>&,
                        const Segment<double>&);
template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                             const Segment<float>&) noexcept;
template Answer tryIntersect(const Cylinder<double>&, const Pose<double>&,
                             const Segment<double>&) noexcept;
template Decision decideIntersect(const Cylinder<float>&, const Pose<float>&,
                                  const Segment<float>&) noexcept;
template Decision decideIntersect(const Cylinder<double>&, const Pose<double>&,
                                  const Segment<double>&) noexcept;
template std::optional<Interval<float>> clip(const Cylinder<float>&,
                                             const Pose<float>&,
                                             const Segment<float>&);
template std::optional<Interval<double>> clip(const Cylinder<double>&,
                                              const Pose<double>&,
                                              const Segment<double>&);
template Answer tryClip(const Cylinder<float>&, const Pose<float>&,
                        const Segment<float>&, Interval<float>*) noexcept;
template Answer tryClip(const Cylinder<double>&, const Pose<double>&,
                        const Segment<double>&, Interval<double>*) noexcept;

}  // namespace tricyl
