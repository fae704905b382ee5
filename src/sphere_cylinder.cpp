// SPDX-License-Identifier: BSD-3-Clause
// Sphere vs cylinder: validate, then sphereCylinder
// (src/cylinder_queries_impl.h), decided sign by sign (src/per_sign.h).
#include "tricyl/sphere_cylinder.h"

#include <type_traits>

#include "cylinder_queries_impl.h"

namespace tricyl {
namespace {

Decision decide(const Cylinder<double>& cyl, const Pose<double>& pose,
                const Sphere<double>& sph) {
  double max_len = 0, max_unitless = 0;
  const Vec3<double>& c = sph.center;
  bool gate = detail::quickGate(cyl, pose, c, c, sph.radius, &max_unitless);
  if (!gate) {
    if (!detail::scanFinite({cyl.radius, cyl.lz, sph.radius, c.x, c.y, c.z},
                            pose, &max_len, &max_unitless) ||
        !(cyl.radius >= 0 && cyl.lz >= 0 && sph.radius >= 0))
      return {Answer::kInvalidInput, Stage::kInvalid};
    gate = detail::rangeGateOk(max_len, max_unitless);
  }
  const detail::SphereQuery q{cyl, pose, sph, max_unitless};
  return detail::runPerSign(q, gate, [](auto& ctx, bool* early) {
    return detail::sphereCylinder(ctx, early);
  });
}

template <class S>
Decision decideAs(const Cylinder<S>& cyl, const Pose<S>& pose,
                  const Sphere<S>& sph) {
  if constexpr (std::is_same_v<S, double>) {
    return decide(cyl, pose, sph);  // no copy
  } else {
    if (!detail::floatBitsFinite(cyl, pose, sph))  // before widening (issue 20)
      return {Answer::kInvalidInput, Stage::kInvalid};
    return decide({double(cyl.radius), double(cyl.lz)}, detail::widen(pose),
                  {detail::widen(sph.center), double(sph.radius)});
  }
}

}  // namespace

template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Sphere<S>& sphere) noexcept {
  return decideAs(cylinder, pose, sphere);
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Sphere<S>& sphere) noexcept {
  return decideAs(cylinder, pose, sphere).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Sphere<S>& sphere) {
  const Answer a = decideAs(cylinder, pose, sphere).answer;
  if (a == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::intersect(cylinder, sphere): NaN or infinite input, or a "
        "negative radius or length");
  return a == Answer::kIntersect;
}

template bool intersect(const Cylinder<float>&, const Pose<float>&,
                        const Sphere<float>&);
template bool intersect(const Cylinder<double>&, const Pose<double>&,
                        const Sphere<double>&);
template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                             const Sphere<float>&) noexcept;
template Answer tryIntersect(const Cylinder<double>&, const Pose<double>&,
                             const Sphere<double>&) noexcept;
template Decision decideIntersect(const Cylinder<float>&, const Pose<float>&,
                                  const Sphere<float>&) noexcept;
template Decision decideIntersect(const Cylinder<double>&, const Pose<double>&,
                                  const Sphere<double>&) noexcept;

}  // namespace tricyl
