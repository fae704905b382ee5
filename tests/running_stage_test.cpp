// The extended stage's running error bounds (src/filter.h: Rd in double,
// Fl in long double; docs/exactness.md, section 4): the folded bound of the
// local frame (toLocalRunning, src/triangle_cylinder_impl.h) encloses the
// exact local coordinates, computed by the oracle's independent rational
// transform, in general position, under heavy cancellation, with mixed
// exponents and (double) with products that underflow; and each stage on
// its own, run on every case of the scene families, never decides against
// the exact oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>

#include "filter.h"
#include "oracle.h"
#include "scenes.h"
#include "test_support.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using detail::ExtendedKernel;
using detail::RunningDoubleKernel;
using detail::Tri;
using oracle::Q;

// Exact rational value of a long double (or double): its significand, at
// most 64 bits, as an integer times a power of two (frexp and ldexp are
// exact; the integer is built from two 32-bit halves, since mpz_class
// takes no unsigned 64-bit value portably).
Q exactly(long double v) {
  if (v == 0) return Q(0);
  int k = 0;
  const long double f = std::frexp(v < 0 ? -v : v, &k);   // 0.5 <= f < 1
  const long double top = std::floor(std::ldexp(f, 32));  // f 2^32, high
  const long double low = std::ldexp(f, 64) - std::ldexp(top, 32);
  mpz_class m = mpz_class(static_cast<unsigned long>(top));
  m <<= 32;
  m += mpz_class(static_cast<unsigned long>(low));
  Q q(m);
  if (k - 64 >= 0)
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(k - 64));
  else
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(64 - k));
  return v < 0 ? Q(-q) : q;
}

template <class K>
struct RunningFrameTest : ::testing::Test {};
using RunningKernels = ::testing::Types<RunningDoubleKernel, ExtendedKernel>;
TYPED_TEST_SUITE(RunningFrameTest, RunningKernels);

TYPED_TEST(RunningFrameTest, BoundEnclosesTheExactLocalCoordinates) {
  using K = TypeParam;
  const std::uint64_t seed = test::baseSeed() + 71;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const long n = test::scaled(3000);
  double worst = 0;  // max |v - exact| / e over all coordinates
  long failures = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    const int regime = int(i % 4);
    Pose<double> pose;
    Vec3<double> p;
    if (regime == 0) {  // general position
      pose = test::randomPose(g, 100);
      p = {100 * U(g), 100 * U(g), 100 * U(g)};
    } else if (regime == 1) {  // p = t + R y with tiny y: cancellation
      pose = test::randomPose(g, 1e3);
      const double y[3] = {1e-9 * U(g), 1e-9 * U(g), 1e-9 * U(g)};
      const auto& R = pose.R;
      p = {pose.t.x + (R[0][0] * y[0] + R[0][1] * y[1] + R[0][2] * y[2]),
           pose.t.y + (R[1][0] * y[0] + R[1][1] * y[1] + R[1][2] * y[2]),
           pose.t.z + (R[2][0] * y[0] + R[2][1] * y[1] + R[2][2] * y[2])};
    } else if (regime == 2) {  // mixed exponents
      pose = test::randomPose(g, 1e-10);
      p = {1e10 * U(g), 1e-10 * U(g), U(g)};
    } else {  // tiny: in double, products fall below 2^-1022
      pose = test::randomPose(g, 1e-305);
      for (auto& row : pose.R)
        for (double& r : row) r *= 1e-12;
      p = {1e-305 * U(g), 1e-305 * U(g), 1e-305 * U(g)};
    }
    typename K::Num x, y, Z;
    detail::toLocal<K>(pose, p, 1.0, x, y, Z);
    const oracle::Q3 ex = oracle::toLocal(pose, p);
    const Q exact[3] = {ex.x, ex.y, 2 * ex.z};
    const typename K::Num* got[3] = {&x, &y, &Z};
    for (int c = 0; c < 3; ++c) {
      const Q err = abs(exactly(got[c]->v) - exact[c]);
      const Q e = exactly(got[c]->e);
      if (err > e) {
        ++failures;
        ADD_FAILURE() << "case " << i << " (regime " << regime
                      << "), coordinate " << c << ": error " << err.get_d()
                      << " > bound " << e.get_d();
      }
      if (e > 0) worst = std::max(worst, Q(err / e).get_d());
    }
  }
  std::printf("[ stats    ] %ld points: worst error / bound %.3f\n", n, worst);
  EXPECT_EQ(failures, 0);
  // Not vacuous: some coordinate's error comes within a factor 16 of its
  // bound (a bound inflated by that much would cost the stage decisions).
  EXPECT_GT(worst, 1.0 / 16);
}

// Each running kernel alone, through the whole triangle kernel (the
// largest predicate set in tricyl), on every case of the families (not only
// those the double filter leaves): whatever it decides is the oracle's
// answer. The double one decides the cylinder queries' extended stage;
// its sign() is tested here on far more predicates than those use.
template <class K>
void agreesWithOracle(scenes::Family family, long n, std::uint64_t seed) {
  long decided = 0, failures = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    const scenes::TriCase k = scenes::generate(family, seed, std::uint64_t(i));
    double rho = 0, len = std::max(k.cyl.radius, k.cyl.lz);
    for (const auto& row : k.pose.R)
      for (double v : row) rho = std::max(rho, std::fabs(v));
    for (const Vec3<double>& v : {k.pose.t, k.tri.a, k.tri.b, k.tri.c})
      len = std::max({len, std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
    if (!detail::rangeGateOk(len, rho)) continue;  // the stages' precondition
    bool early = false;
    const auto q = detail::makeLocal<K>(k.cyl, k.pose, k.tri, rho);
    const Tri t = detail::triangleCylinder<K>(q, &early);
    if (t == Tri::kUnknown) continue;
    ++decided;
    const bool truth = oracle::triangleCylinder(k.cyl, k.pose, k.tri);
    if ((t == Tri::kTrue) != truth) {
      ++failures;
      ADD_FAILURE() << scenes::familyName(family) << " case " << i
                    << ": oracle " << truth;
    }
  }
  std::printf("[ stats    ] %s: %ld of %ld decided\n",
              scenes::familyName(family), decided, n);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(decided, n / 2);
}

TYPED_TEST(RunningFrameTest, TriangleKernelAgreesWithTheOracle) {
  const std::uint64_t seed = test::baseSeed() + 72;
  SCOPED_TRACE(test::seedTrace(seed));
  for (scenes::Family f :
       {scenes::Family::kNear, scenes::Family::kThin, scenes::Family::kFar,
        scenes::Family::kAligned, scenes::Family::kSliver})
    agreesWithOracle<TypeParam>(f, test::scaled(1500), seed);
}

}  // namespace
}  // namespace tricyl
