// Dispatch for the triangle-cylinder test: validate, filter, fall back.
#include "tricyl/triangle_cylinder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "filter.h"
#include "triangle_cylinder_impl.h"

namespace tricyl {
namespace {

using detail::ExactKernel;
using detail::ExtendedKernel;
using detail::FilterKernel;
using detail::NaiveKernel;
using detail::Tri;

struct Inputs {
  Cylinder<double> cyl;
  Pose<double> pose;
  Triangle<double> tri;
};

template <class S>
Vec3<double> widen(const Vec3<S>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

// float -> double is exact, so the double kernel is exact for float inputs.
template <class S>
Inputs widen(const Cylinder<S>& cyl, const Pose<S>& pose,
             const Triangle<S>& tri) {
  Inputs in;
  in.cyl = {double(cyl.radius), double(cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) in.pose.R[i][j] = double(pose.R[i][j]);
  in.pose.t = widen(pose.t);
  in.tri = {widen(tri.a), widen(tri.b), widen(tri.c)};
  return in;
}

// One pass over the input bits: a double is finite iff its exponent field
// is not all ones, and for non-negative doubles the bit pattern orders like
// the value, so the maxima of |x| are maxima of (bits & ~sign). Returns
// false for NaN/Inf anywhere or a negative radius or length (-0 is fine);
// otherwise the largest magnitudes for the filter's range gate.
bool validate(const Inputs& in, double* max_len, double* max_unitless) {
  constexpr std::uint64_t kAbs = ~(std::uint64_t(1) << 63);
  constexpr std::uint64_t kInf = 0x7ff0000000000000ULL;
  auto bits = [](double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, sizeof b);
    return b;
  };
  const double len[] = {in.cyl.radius, in.cyl.lz,  in.pose.t.x, in.pose.t.y,
                        in.pose.t.z,   in.tri.a.x, in.tri.a.y,  in.tri.a.z,
                        in.tri.b.x,    in.tri.b.y, in.tri.b.z,  in.tri.c.x,
                        in.tri.c.y,    in.tri.c.z};
  std::uint64_t ml = 0, mu = 0;
  for (double v : len) ml = std::max(ml, bits(v) & kAbs);
  for (const auto& row : in.pose.R)
    for (double v : row) mu = std::max(mu, bits(v) & kAbs);
  if (ml >= kInf || mu >= kInf) return false;
  std::memcpy(max_len, &ml, sizeof ml);
  std::memcpy(max_unitless, &mu, sizeof mu);
  return in.cyl.radius >= 0 && in.cyl.lz >= 0;  // -0 passes
}

Decision decide(const Inputs& in) {
  double max_len = 0, max_unitless = 0;
  if (!validate(in, &max_len, &max_unitless))
    return {Answer::kInvalidInput, Stage::kInvalid};
  bool early = false;
  if (detail::rangeGateOk(max_len, max_unitless)) {
    const auto q =
        detail::makeLocal<FilterKernel>(in.cyl, in.pose, in.tri, max_unitless);
    const Tri t = detail::triangleCylinder<FilterKernel>(q, &early);
    if (t != Tri::kUnknown)
      return {t == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint,
              early ? Stage::kEarlyOut : Stage::kFastPath};
  }
  if (detail::rangeGateOk(max_len, max_unitless)) {
    const auto q = detail::makeLocal<ExtendedKernel>(in.cyl, in.pose, in.tri,
                                                     max_unitless);
    const Tri t = detail::triangleCylinder<ExtendedKernel>(q, &early);
    if (t != Tri::kUnknown)
      return {t == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint,
              Stage::kExtended};
  }
  const auto q =
      detail::makeLocal<ExactKernel>(in.cyl, in.pose, in.tri, max_unitless);
  const Tri t = detail::triangleCylinder<ExactKernel>(q, &early);
  return {t == Tri::kTrue ? Answer::kIntersect : Answer::kDisjoint,
          Stage::kExact};
}

bool checked(const Inputs& in) {
  const Decision d = decide(in);
  if (d.answer == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::intersect(cylinder, triangle): NaN or infinite input, or a "
        "negative radius or length");
  return d.answer == Answer::kIntersect;
}

}  // namespace

template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Triangle<S>& triangle) noexcept {
  return decide(widen(cylinder, pose, triangle));
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle) noexcept {
  return decide(widen(cylinder, pose, triangle)).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Triangle<S>& triangle) {
  return checked(widen(cylinder, pose, triangle));
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Triangle<S>& triangle) {
  return checked(widen(cylinder, identityPose<S>(), triangle));
}

namespace diagnostic {
template <class S>
bool intersectUncertified(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const Triangle<S>& triangle) noexcept {
  const Inputs in = widen(cylinder, pose, triangle);
  const auto q = detail::makeLocal<NaiveKernel>(in.cyl, in.pose, in.tri, 1.0);
  bool early = false;
  return detail::triangleCylinder<NaiveKernel>(q, &early) == Tri::kTrue;
}
template bool intersectUncertified(const Cylinder<float>&, const Pose<float>&,
                                   const Triangle<float>&) noexcept;
template bool intersectUncertified(const Cylinder<double>&, const Pose<double>&,
                                   const Triangle<double>&) noexcept;
}  // namespace diagnostic

template bool intersect(const Cylinder<float>&, const Pose<float>&,
                        const Triangle<float>&);
template bool intersect(const Cylinder<double>&, const Pose<double>&,
                        const Triangle<double>&);
template bool intersect(const Cylinder<float>&, const Triangle<float>&);
template bool intersect(const Cylinder<double>&, const Triangle<double>&);
template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                             const Triangle<float>&) noexcept;
template Answer tryIntersect(const Cylinder<double>&, const Pose<double>&,
                             const Triangle<double>&) noexcept;
template Decision decideIntersect(const Cylinder<float>&, const Pose<float>&,
                                  const Triangle<float>&) noexcept;
template Decision decideIntersect(const Cylinder<double>&, const Pose<double>&,
                                  const Triangle<double>&) noexcept;

}  // namespace tricyl
