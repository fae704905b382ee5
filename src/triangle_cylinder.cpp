// Dispatch for the triangle-cylinder test: validate, filter, fall back.
#include "tricyl/triangle_cylinder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <type_traits>

#include "filter.h"
#include "triangle_cylinder_impl.h"

namespace tricyl {
namespace {

using detail::ExactKernel;
using detail::ExtendedKernel;
using detail::FilterKernel;
using detail::NaiveKernel;
using detail::Tri;

// The double kernel works on references to the caller's values; float
// inputs are widened first (float -> double is exact, so the double kernel
// is exact for float inputs).
struct Inputs {
  const Cylinder<double>& cyl;
  const Pose<double>& pose;
  const Triangle<double>& tri;
};

struct Widened {
  Cylinder<double> cyl;
  Pose<double> pose;
  Triangle<double> tri;
};

template <class S>
Vec3<double> widen(const Vec3<S>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

Widened widen(const Cylinder<float>& cyl, const Pose<float>& pose,
              const Triangle<float>& tri) {
  Widened w;
  w.cyl = {double(cyl.radius), double(cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.pose.R[i][j] = double(pose.R[i][j]);
  w.pose.t = widen(pose.t);
  w.tri = {widen(tri.a), widen(tri.b), widen(tri.c)};
  return w;
}

static_assert(sizeof(Pose<double>) == 12 * sizeof(double) &&
                  sizeof(Triangle<double>) == 9 * sizeof(double) &&
                  sizeof(Cylinder<double>) == 2 * sizeof(double),
              "the aggregates are arrays of doubles without padding");

// |x| as bits. For non-negative doubles the bit pattern orders like the
// value, and a double is finite iff (bits & ~sign) < 0x7ff0...0.
template <size_t N>
std::uint64_t maxAbsBits(const void* p) {
  std::uint64_t b[N];
  std::memcpy(b, p, sizeof b);
  std::uint64_t m = 0;
  for (size_t i = 0; i < N; ++i) {
    const std::uint64_t a = b[i] & ~(std::uint64_t(1) << 63);
    m = a > m ? a : m;
  }
  return m;
}

// One pass over the input bits. Returns false for NaN/Inf anywhere or a
// negative radius or length (-0 is fine); otherwise the largest magnitudes
// of the lengths and of the rotation entries, for the filter's range gate.
bool validate(const Inputs& in, double* max_len, double* max_unitless) {
  constexpr std::uint64_t kInf = 0x7ff0000000000000ULL;
  const std::uint64_t mu = maxAbsBits<9>(&in.pose.R[0][0]);
  std::uint64_t ml = maxAbsBits<9>(&in.tri);
  const std::uint64_t mt = maxAbsBits<3>(&in.pose.t);
  const std::uint64_t mc = maxAbsBits<2>(&in.cyl);
  ml = ml > mt ? ml : mt;
  ml = ml > mc ? ml : mc;
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

Decision decideAny(const Cylinder<double>& cylinder, const Pose<double>& pose,
                   const Triangle<double>& triangle) {
  return decide(Inputs{cylinder, pose, triangle});
}
Decision decideAny(const Cylinder<float>& cylinder, const Pose<float>& pose,
                   const Triangle<float>& triangle) {
  const Widened w = widen(cylinder, pose, triangle);
  return decide(Inputs{w.cyl, w.pose, w.tri});
}

bool checked(Decision d) {
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
  return decideAny(cylinder, pose, triangle);
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle) noexcept {
  return decideAny(cylinder, pose, triangle).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Triangle<S>& triangle) {
  return checked(decideAny(cylinder, pose, triangle));
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Triangle<S>& triangle) {
  return checked(decideAny(cylinder, identityPose<S>(), triangle));
}

namespace diagnostic {
template <class S>
bool intersectUncertified(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const Triangle<S>& triangle) noexcept {
  Widened in;
  if constexpr (std::is_same_v<S, float>) {
    in = widen(cylinder, pose, triangle);
  } else {
    in = {cylinder, pose, triangle};
  }
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
