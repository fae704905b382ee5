// SPDX-License-Identifier: BSD-3-Clause
// Point in cone: validate, then the three stages of src/filter.h.
#include "tricyl/point_cone.h"

#include <type_traits>

#include "cylinder_queries_impl.h"

namespace tricyl {
namespace {

Decision decide(const Cone<double>& cone, const Pose<double>& pose,
                const Vec3<double>& p) {
  double max_len = 0, max_unitless = 0;
  if (!detail::scanFinite({cone.radius, cone.lz, p.x, p.y, p.z}, pose, &max_len,
                          &max_unitless) ||
      !(cone.radius >= 0 && cone.lz >= 0))
    return {Answer::kInvalidInput, Stage::kInvalid};
  return detail::runStages(
      [&](auto tag, bool*) {
        using K = typename decltype(tag)::type;
        const auto q = detail::localPoint<K>(pose, p, max_unitless);
        return detail::pointInCone<K>(q, K::lift(cone.lz),
                                      K::lift(cone.radius));
      },
      max_len, max_unitless);
}

template <class S>
Decision decideAs(const Cone<S>& cone, const Pose<S>& pose, const Vec3<S>& p) {
  if constexpr (std::is_same_v<S, float>)
    if (!detail::floatBitsFinite(cone, pose, p))  // before widening (issue 20)
      return {Answer::kInvalidInput, Stage::kInvalid};
  return decide({double(cone.radius), double(cone.lz)}, detail::widen(pose),
                detail::widen(p));
}

}  // namespace

template <class S>
Decision decideContains(const Cone<S>& cone, const Pose<S>& pose,
                        const Vec3<S>& point) noexcept {
  return decideAs(cone, pose, point);
}

template <class S>
Answer tryContains(const Cone<S>& cone, const Pose<S>& pose,
                   const Vec3<S>& point) noexcept {
  return decideAs(cone, pose, point).answer;
}

template <class S>
bool contains(const Cone<S>& cone, const Pose<S>& pose, const Vec3<S>& point) {
  const Answer a = decideAs(cone, pose, point).answer;
  if (a == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::contains(cone, point): NaN or infinite input, or a "
        "negative radius or length");
  return a == Answer::kIntersect;
}

template bool contains(const Cone<float>&, const Pose<float>&,
                       const Vec3<float>&);
template bool contains(const Cone<double>&, const Pose<double>&,
                       const Vec3<double>&);
template Answer tryContains(const Cone<float>&, const Pose<float>&,
                            const Vec3<float>&) noexcept;
template Answer tryContains(const Cone<double>&, const Pose<double>&,
                            const Vec3<double>&) noexcept;
template Decision decideContains(const Cone<float>&, const Pose<float>&,
                                 const Vec3<float>&) noexcept;
template Decision decideContains(const Cone<double>&, const Pose<double>&,
                                 const Vec3<double>&) noexcept;

}  // namespace tricyl
