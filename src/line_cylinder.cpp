// SPDX-License-Identifier: BSD-3-Clause
// Line vs cylinder: the exact Boolean (lineCylinder in
// src/cylinder_queries_impl.h, decided sign by sign, src/per_sign.h) and the
// entry/exit interval along the unbounded line (the segment's interval
// code without the [0, 1] restriction: src/line_cylinder_interval.cpp).
#include "tricyl/line_cylinder.h"

#include <string>

#include "line_cylinder_impl.h"

namespace tricyl {
namespace {

using detail::LinearInputs;

Decision decide(LinearInputs& in) { return detail::decideLinear<false>(in); }

template <class S>
Answer clipAs(const Cylinder<S>& cyl, const Pose<S>& pose, const Line<S>& line,
              Interval<S>* out) {
  LinearInputs in = detail::widenLinear(cyl, pose, line.p, line.q);
  const Decision d = decide(in);
  if (d.answer != Answer::kIntersect) return d.answer;
  const Interval<double> iv = detail::linearInterval(in, false);
  *out = {detail::narrowEnd<S>(iv.lo), detail::narrowEnd<S>(iv.hi)};
  return d.answer;
}

[[noreturn]] void throwInvalid(const char* what) {
  throw InvalidInput(std::string("tricyl::") + what +
                     "(cylinder, line): NaN or infinite input, or a "
                     "negative radius or length");
}

}  // namespace

template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Line<S>& line) noexcept {
  return detail::decideLinearAs<false>(cylinder, pose, line.p, line.q);
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Line<S>& line) noexcept {
  return decideIntersect(cylinder, pose, line).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Line<S>& line) {
  const Answer a = tryIntersect(cylinder, pose, line);
  if (a == Answer::kInvalidInput) throwInvalid("intersect");
  return a == Answer::kIntersect;
}

template <class S>
Answer tryClip(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Line<S>& line, Interval<S>* out) noexcept {
  return clipAs(cylinder, pose, line, out);
}

template <class S>
std::optional<Interval<S>> clip(const Cylinder<S>& cylinder,
                                const Pose<S>& pose, const Line<S>& line) {
  Interval<S> iv{};
  const Answer a = clipAs(cylinder, pose, line, &iv);
  if (a == Answer::kInvalidInput) throwInvalid("clip");
  if (a == Answer::kDisjoint) return std::nullopt;
  return iv;
}

template bool intersect(const Cylinder<float>&, const Pose<float>&,
                        const Line<float>&);
template bool intersect(const Cylinder<double>&, const Pose<double>&,
                        const Line<double>&);
template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                             const Line<float>&) noexcept;
template Answer tryIntersect(const Cylinder<double>&, const Pose<double>&,
                             const Line<double>&) noexcept;
template Decision decideIntersect(const Cylinder<float>&, const Pose<float>&,
                                  const Line<float>&) noexcept;
template Decision decideIntersect(const Cylinder<double>&, const Pose<double>&,
                                  const Line<double>&) noexcept;
template std::optional<Interval<float>> clip(const Cylinder<float>&,
                                             const Pose<float>&,
                                             const Line<float>&);
template std::optional<Interval<double>> clip(const Cylinder<double>&,
                                              const Pose<double>&,
                                              const Line<double>&);
template Answer tryClip(const Cylinder<float>&, const Pose<float>&,
                        const Line<float>&, Interval<float>*) noexcept;
template Answer tryClip(const Cylinder<double>&, const Pose<double>&,
                        const Line<double>&, Interval<double>*) noexcept;

}  // namespace tricyl
