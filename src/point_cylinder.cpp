// SPDX-License-Identifier: BSD-3-Clause
// Point in cylinder: validate, then the three stages of src/filter.h.
#include "tricyl/point_cylinder.h"

#include <type_traits>

#include "cylinder_queries_impl.h"

namespace tricyl {
namespace {

Decision decide(const Cylinder<double>& cyl, const Pose<double>& pose,
                const Vec3<double>& p) {
  double max_len = 0, max_unitless = 0;
  if (!detail::scanFinite({cyl.radius, cyl.lz, p.x, p.y, p.z}, pose, &max_len,
                          &max_unitless) ||
      !(cyl.radius >= 0 && cyl.lz >= 0))
    return {Answer::kInvalidInput, Stage::kInvalid};
  return detail::runStages(
      [&](auto tag, bool*) {
        using K = typename decltype(tag)::type;
        const auto q = detail::localPoint<K>(pose, p, max_unitless);
        return detail::pointInCylinder<K>(q, K::lift(cyl.lz),
                                          K::lift(cyl.radius));
      },
      max_len, max_unitless);
}

template <class S>
Decision decideAs(const Cylinder<S>& cyl, const Pose<S>& pose,
                  const Vec3<S>& p) {
  if constexpr (std::is_same_v<S, float>)
    if (!detail::floatBitsFinite(cyl, pose, p))  // before widening (issue 20)
      return {Answer::kInvalidInput, Stage::kInvalid};
  return decide({double(cyl.radius), double(cyl.lz)}, detail::widen(pose),
                detail::widen(p));
}

}  // namespace

template <class S>
Decision decideContains(const Cylinder<S>& cylinder, const Pose<S>& pose,
                        const Vec3<S>& point) noexcept {
  return decideAs(cylinder, pose, point);
}

template <class S>
Answer tryContains(const Cylinder<S>& cylinder, const Pose<S>& pose,
                   const Vec3<S>& point) noexcept {
  return decideAs(cylinder, pose, point).answer;
}

template <class S>
bool contains(const Cylinder<S>& cylinder, const Pose<S>& pose,
              const Vec3<S>& point) {
  const Answer a = decideAs(cylinder, pose, point).answer;
  if (a == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::contains(cylinder, point): NaN or infinite input, or a "
        "negative radius or length");
  return a == Answer::kIntersect;
}

template bool contains(const Cylinder<float>&, const Pose<float>&,
                       const Vec3<float>&);
template bool contains(const Cylinder<double>&, const Pose<double>&,
                       const Vec3<double>&);
template Answer tryContains(const Cylinder<float>&, const Pose<float>&,
                            const Vec3<float>&) noexcept;
template Answer tryContains(const Cylinder<double>&, const Pose<double>&,
                            const Vec3<double>&) noexcept;
template Decision decideContains(const Cylinder<float>&, const Pose<float>&,
                                 const Vec3<float>&) noexcept;
template Decision decideContains(const Cylinder<double>&, const Pose<double>&,
                                 const Vec3<double>&) noexcept;

}  // namespace tricyl
