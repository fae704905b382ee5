// SPDX-License-Identifier: BSD-3-Clause
// The running error bounds of the local frame: the double running bound
// (src/filter.h's Rd, the line interval's first stage; toLocalRunning,
// src/triangle_cylinder_impl.h) and the double-word coordinates of the
// adaptive stage (Tape::dwCoord, src/adaptive.cpp) enclose the exact local
// coordinates, computed by the oracle's independent rational transform, in
// general position, under heavy cancellation, with mixed exponents and
// with products that underflow; and the running kernel on its own, run on
// every case of the scene families, never decides against the exact
// oracle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <random>

#include "adaptive.h"
#include "filter.h"
#include "oracle.h"
#include "scenes.h"
#include "test_support.h"
#include "triangle_cylinder_impl.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

using detail::RunningDoubleKernel;
using detail::Tri;
using oracle::Q;

// Exact rational value of a long double (or double), read from its bits:
// no libm call (a test built with -mlong-double-64 must not call libm's
// long double functions, whose ABI is the 80-bit one) and every significand
// width: 53 (long double = double), 64 (x87 extended, explicit leading bit)
// and 113 (IEEE binary128, AArch64 Linux). Issue 20: the frexp/ldexp
// version kept only 64 significand bits and failed on AArch64.
Q exactly(long double v) {
  constexpr int kMant = LDBL_MANT_DIG;
  static_assert(kMant == 53 || kMant == 64 || kMant == 113,
                "long double: binary64, x87 extended or binary128");
  static_assert(std::numeric_limits<long double>::is_iec559 || kMant == 64);
  unsigned char b[sizeof(long double)];
  std::memcpy(b, &v, sizeof v);
  // Little-endian byte k of the encoding (x86-64, AArch64).
  auto bit = [&](int k) { return (b[k / 8] >> (k % 8)) & 1; };
  const int frac_bits = kMant == 64 ? 63 : kMant - 1;  // stored fraction
  const int exp_bits = kMant == 53 ? 11 : 15;
  const int exp_at = kMant == 64 ? 64 : frac_bits;  // x87: explicit bit 63
  int biased = 0;
  for (int k = exp_bits - 1; k >= 0; --k) biased = 2 * biased + bit(exp_at + k);
  const bool negative = bit(exp_at + exp_bits) != 0;
  mpz_class m = 0;
  for (int k = frac_bits - 1; k >= 0; --k) m = 2 * m + bit(k);
  const int bias = (1 << (exp_bits - 1)) - 1;
  int e = 0;  // v = m 2^(e - frac_bits)
  if (kMant == 64) {
    if (bit(63)) m += mpz_class(1) << 63;  // the explicit leading bit
    e = (biased == 0 ? 1 : biased) - bias;
  } else if (biased == 0) {
    e = 1 - bias;  // subnormal
  } else {
    m += mpz_class(1) << frac_bits;  // the hidden bit
    e = biased - bias;
  }
  Q q(m);
  const int shift = e - frac_bits;
  if (shift >= 0)
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(shift));
  else
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-shift));
  q.canonicalize();
  return negative ? Q(-q) : q;
}

// exactly() on values that use every significand bit of the type, the
// smallest subnormal and the largest finite value, against their values
// built independently in Q.
TEST(RunningFrameExactly, ConvertsEverySignificandBit) {
  using L = std::numeric_limits<long double>;
  const int p = LDBL_MANT_DIG;
  auto pow2 = [](int k) {  // 2^k in Q
    Q q(1);
    if (k >= 0)
      mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(k));
    else
      mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-k));
    return q;
  };
  const long double all_ones = 1 - L::epsilon() / 2;  // 1 - 2^-p
  EXPECT_EQ(exactly(all_ones), Q(1 - pow2(-p)));
  EXPECT_EQ(exactly(-all_ones * 8), Q(-8 * (1 - pow2(-p))));
  EXPECT_EQ(exactly(1 + L::epsilon()), Q(1 + pow2(1 - p)));
  EXPECT_EQ(exactly(L::denorm_min()), pow2(L::min_exponent - 1 - (p - 1)));
  EXPECT_EQ(exactly(L::min()), pow2(L::min_exponent - 1));
  EXPECT_EQ(exactly(L::max()), Q((1 - pow2(-p)) * pow2(L::max_exponent)));
  EXPECT_EQ(exactly(0.0L), Q(0));
  EXPECT_EQ(exactly(-0.0L), Q(0));
  EXPECT_EQ(exactly(0.375L), Q(3, 8));
}

// A point and a pose for case i: four regimes in turn (general position;
// p = t + R y with tiny y, heavy cancellation; mixed exponents; tiny
// values whose products underflow).
void framePoint(std::mt19937_64& g, long i, Pose<double>& pose,
                Vec3<double>& p) {
  std::uniform_real_distribution<double> U(-1, 1);
  const int regime = int(i % 4);
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
}

template <class K>
struct RunningFrameTest : ::testing::Test {};
using RunningKernels = ::testing::Types<RunningDoubleKernel>;
TYPED_TEST_SUITE(RunningFrameTest, RunningKernels);

TYPED_TEST(RunningFrameTest, BoundEnclosesTheExactLocalCoordinates) {
  using K = TypeParam;
  const std::uint64_t seed = test::baseSeed() + 71;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  const long n = test::scaled(3000);
  double worst = 0;  // max |v - exact| / e over all coordinates
  long failures = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    const int regime = int(i % 4);
    Pose<double> pose;
    Vec3<double> p;
    framePoint(g, i, pose, p);
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

// The double-word stage's retry frame (dwCoordinateAccurate): the bound
// encloses the exact coordinate, in every regime of framePoint, and it is
// relative to the coordinate's own size (2^-100 |x|), where dwCoordinate's
// is relative to the terms' magnitude: the point of the retry.
TEST(DwFrame, AccurateCoordinatesEncloseTheExactAndAreRelative) {
  const std::uint64_t seed = test::baseSeed() + 77;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  const long n = test::scaled(3000);
  long failures = 0, formed = 0, tighter = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    Pose<double> pose;
    Vec3<double> p;
    framePoint(g, i, pose, p);
    const oracle::Q3 ex = oracle::toLocal(pose, p);
    const Q exact[3] = {ex.x, ex.y, 2 * ex.z};
    detail::DwKernel<false>::Num c[3];
    detail::DwKernel<false>::toLocal(pose, p, c[0], c[1], c[2]);
    for (int j = 0; j < 3; ++j) {
      detail::DwRun r;
      if (!detail::dwCoordinateAccurate(pose, p, j, &r)) continue;
      ++formed;
      const Q v = exactly(r.v.hi) + exactly(r.v.lo);
      const Q err = abs(v - exact[j]);
      if (err > exactly(r.e) || (r.e == 0 && r.v.lo != 0)) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << j << ": error "
                      << err.get_d() << " > bound " << r.e;
      }
      if (r.e > 0x1p-100 * std::fabs(r.v.hi) + detail::kNotDouble) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << j << ": bound "
                      << r.e << " not relative to " << r.v.hi;
      }
      tighter += r.e + std::fabs(r.v.lo) < c[j].e + std::fabs(c[j].v.lo);
    }
  }
  std::printf("[ stats    ] %ld coordinates formed, %ld tighter\n", formed,
              tighter);
  EXPECT_EQ(failures, 0);
  // Not vacuous: most coordinates form, and the cancelling regime makes
  // the retry's bound tighter than the frame's.
  EXPECT_GT(formed, n);
  EXPECT_GT(tighter, n / 8);
}

// The adaptive run's coordinates from the fast path's values
// (Tape::coordinates): the double values of toLocal and the per-vertex
// magnitude M = rho (|d0| + |d1| + |d2|) as the prologues round it; the
// bound derived from M encloses the exact coordinate, in every regime of
// framePoint (general position, cancellation, mixed exponents, underflow).
TEST(AdaptiveFrame, BoundFromTheFastPathMagnitudeEnclosesTheExact) {
  const std::uint64_t seed = test::baseSeed() + 73;
  SCOPED_TRACE(test::seedTrace(seed));
  std::mt19937_64 g(seed);
  const long n = test::scaled(3000);
  double worst = 0;
  long failures = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    Pose<double> pose;
    Vec3<double> p;
    framePoint(g, i, pose, p);
    detail::Tape tape;
    detail::TapeScope scope(&tape);
    // toLocal's values (its leaves' v), and the prologue's M.
    detail::An t[3];
    tape.toLocal(pose, p, t[0], t[1], t[2]);
    double rho = 0;
    for (const auto& row : pose.R)
      for (double r : row) rho = std::max(rho, std::fabs(r));
    const double d0 = p.x - pose.t.x, d1 = p.y - pose.t.y, d2 = p.z - pose.t.z;
    const double M = rho * ((std::fabs(d0) + std::fabs(d1)) + std::fabs(d2));
    detail::An c[3];
    tape.coordinates(pose, p, t[0].v, t[1].v, t[2].v, M, c[0], c[1], c[2]);
    const oracle::Q3 ex = oracle::toLocal(pose, p);
    const Q exact[3] = {ex.x, ex.y, 2 * ex.z};
    for (int k = 0; k < 3; ++k) {
      const Q err = abs(exactly(c[k].v) - exact[k]);
      if (err > exactly(c[k].m)) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << k << ": error "
                      << err.get_d() << " > bound " << c[k].m;
      }
      if (c[k].m > 0) worst = std::max(worst, Q(err / exactly(c[k].m)).get_d());
      // The same leaf for the stronger stages: its double-word value.
      detail::DW v;
      double e;
      tape.doubleWord(c[k].id, &v, &e);
      if (abs(exactly(v.hi) + exactly(v.lo) - exact[k]) > exactly(e)) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << k
                      << ": double-word value outside its bound";
      }
    }
  }
  std::printf("[ stats    ] %ld points: worst error / bound %.3g\n", n, worst);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(worst, 1.0 / 64);  // not vacuous
}

// The tape's double-word local coordinates enclose the exact value, for the
// same points: Tape::dwCoord's a-priori bound 2^-100 M + kDwTiny, and (with
// `accurate`) Tape::dwCoordAccurate, which escalate switches to when double
// word cannot decide a sign, whose bound is relative to the coordinate
// itself (far below dwCoord's where the coordinate cancels: regime 1).
void tapeCoordinatesEnclose(std::uint64_t seed, bool accurate) {
  std::mt19937_64 g(seed);
  const long n = test::scaled(3000);
  double worst = 0;
  long failures = 0, tight = 0, eligible = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    Pose<double> pose;
    Vec3<double> p;
    framePoint(g, i, pose, p);
    detail::Tape tape;
    detail::TapeScope scope(&tape);
    detail::An c[3];
    tape.toLocal(pose, p, c[0], c[1], c[2]);
    if (accurate) tape.useAccurateCoordinates();
    const oracle::Q3 ex = oracle::toLocal(pose, p);
    const Q exact[3] = {ex.x, ex.y, 2 * ex.z};
    for (int k = 0; k < 3; ++k) {
      detail::DW v;
      double e;
      tape.doubleWord(c[k].id, &v, &e);
      const Q err = abs(exactly(v.hi) + exactly(v.lo) - exact[k]);
      if (err > exactly(e)) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << k << ": error "
                      << err.get_d() << " > bound " << e;
      }
      if (e > 0) worst = std::max(worst, Q(err / exactly(e)).get_d());
      // Regime 3's products underflow: no expansion, dwCoord's bound kept.
      if (i % 4 != 3) {
        ++eligible;
        tight += e <= std::fabs(v.hi) * 0x1p-100;
      }
    }
  }
  std::printf("[ stats    ] %ld points: worst error / bound %.3g\n", n, worst);
  EXPECT_EQ(failures, 0);
  if (accurate) {
    EXPECT_EQ(tight, eligible);  // every bound relative
  }
}
TEST(DoubleWordFrame, BoundEnclosesTheExactLocalCoordinates) {
  const std::uint64_t seed = test::baseSeed() + 71;
  SCOPED_TRACE(test::seedTrace(seed));
  tapeCoordinatesEnclose(seed, false);
}
TEST(DoubleWordFrame, AccurateCoordinatesEncloseTheExact) {
  const std::uint64_t seed = test::baseSeed() + 77;
  SCOPED_TRACE(test::seedTrace(seed));
  tapeCoordinatesEnclose(seed, true);
}

// Each running kernel alone, through the whole triangle kernel (the
// largest predicate set in tricyl), on every case of the families (not only
// those the double filter leaves): whatever it decides is the oracle's
// answer. Its rules are the adaptive run's first check of every sign
// (src/adaptive.h) and the line interval's first stage; its sign() is
// tested here on the whole triangle kernel.
// `make(k, rho)`: the kernel's local frame for case k (rho = max |R_jk|).
template <class K, class MakeLocal>
void agreesWithOracleOn(scenes::Family family, long n, std::uint64_t seed,
                        MakeLocal make) {
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
    const detail::TriCylLocal<K> q = make(k, rho);
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

template <class K>
void agreesWithOracle(scenes::Family family, long n, std::uint64_t seed) {
  agreesWithOracleOn<K>(
      family, n, seed, [](const scenes::TriCase& k, double rho) {
        return detail::makeLocal<K>(k.cyl, k.pose, k.tri, rho);
      });
}

TYPED_TEST(RunningFrameTest, TriangleKernelAgreesWithTheOracle) {
  const std::uint64_t seed = test::baseSeed() + 72;
  SCOPED_TRACE(test::seedTrace(seed));
  for (scenes::Family f :
       {scenes::Family::kNear, scenes::Family::kThin, scenes::Family::kFar,
        scenes::Family::kAligned, scenes::Family::kSliver})
    agreesWithOracle<TypeParam>(f, test::scaled(1500), seed);
}

// The double-word filter (DwFilterKernel: values in double word, a
// magnitude bound of 2^-94) through the whole triangle kernel, on the
// double-word frame's coordinates as the driver gives them (leaf): whatever
// it decides is the oracle's answer, and it decides nearly every case of
// families whose ties are near ties, not exact ones.
TEST(DwFilterTriangle, AgreesWithTheOracle) {
  using K = detail::DwFilterKernel<false>;
  const std::uint64_t seed = test::baseSeed() + 78;
  SCOPED_TRACE(test::seedTrace(seed));
  auto frame = [](const scenes::TriCase& k, double) {
    detail::TriCylLocal<K> q;
    const Vec3<double>* P[3] = {&k.tri.a, &k.tri.b, &k.tri.c};
    for (int v = 0; v < 3; ++v) {
      detail::DwKernel<false>::Num c[3];
      detail::DwKernel<false>::toLocal(k.pose, *P[v], c[0], c[1], c[2]);
      q.x[v] = K::leaf({c[0].v, c[0].e});
      q.y[v] = K::leaf({c[1].v, c[1].e});
      q.Z[v] = K::leaf({c[2].v, c[2].e});
    }
    q.H = K::lift(k.cyl.lz);
    q.r = K::lift(k.cyl.radius);
    return q;
  };
  for (scenes::Family f :
       {scenes::Family::kNear, scenes::Family::kThin, scenes::Family::kFar,
        scenes::Family::kAligned, scenes::Family::kSliver})
    agreesWithOracleOn<K>(f, test::scaled(1500), seed, frame);
}

// The double-word kernel's coordinates (DwKernel::toLocal, src/dw_kernel.h)
// enclose the exact local coordinates in every regime of framePoint, and in
// exact poses on dyadic points (signed permutations) they are certified
// exact (bound 0, low part 0) and equal to the exact value.
template <bool kFma>
void dwFrameEncloses(std::uint64_t seed) {
  std::mt19937_64 g(seed);
  const long n = test::scaled(3000);
  long failures = 0, exact_count = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    Pose<double> pose;
    Vec3<double> p;
    const bool exact_pose = i % 5 == 4;
    if (exact_pose) {  // a signed permutation, dyadic data: exact
      pose = Pose<double>{};
      const int perm = int(g() % 3);
      for (int k = 0; k < 3; ++k)
        pose.R[k][(k + perm) % 3] = (g() & 1) ? 1.0 : -1.0;
      auto small = [&g] { return double(long(g() % 257) - 128) * 0.0625; };
      pose.t = {small(), small(), small()};
      p = {small(), small(), small()};
    } else {
      framePoint(g, i, pose, p);
    }
    detail::Dwe<kFma> c[3];
    detail::DwKernel<kFma>::toLocal(pose, p, c[0], c[1], c[2]);
    const oracle::Q3 ex = oracle::toLocal(pose, p);
    const Q exact[3] = {ex.x, ex.y, 2 * ex.z};
    for (int k = 0; k < 3; ++k) {
      const Q v = exactly(c[k].v.hi) + exactly(c[k].v.lo);
      if (abs(v - exact[k]) > exactly(c[k].e) ||
          (c[k].e == 0 && c[k].v.lo != 0)) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << k << ": error "
                      << Q(abs(v - exact[k])).get_d() << " > bound " << c[k].e;
      }
      exact_count += c[k].e == 0;
      if (exact_pose && c[k].e != 0) {
        ++failures;
        ADD_FAILURE() << "case " << i << ", coordinate " << k
                      << ": an exact pose's coordinate not certified exact";
      }
    }
  }
  EXPECT_EQ(failures, 0);
  EXPECT_GE(exact_count, 3 * (n / 5));
}
TEST(DwKernelFrame, BoundEnclosesTheExactLocalCoordinates) {
  const std::uint64_t seed = test::baseSeed() + 74;
  SCOPED_TRACE(test::seedTrace(seed));
  dwFrameEncloses<false>(seed);
  dwFrameEncloses<true>(seed);  // std::fma: correctly rounded everywhere
}

// The vectorised double-word frame (AVX2 with FMA, src/triangle_cylinder.cpp
// dwFrameAvx2Fma) is the scalar one, value for value: on every scene family
// and on inputs that stress each exact-value rule of dwCoordinate (zero
// rotation entries, vertices equal to the translation in some axis, short
// dyadics whose products are exact, subnormal and mixed-exponent values
// inside the fast path's gate).
TEST(DwFramePaths, VectorisedEqualsScalar) {
  const std::uint64_t seed = test::baseSeed() + 75;
  SCOPED_TRACE(test::seedTrace(seed));
  const Pose<double> I = identityPose<double>();
  if (diagnostic::dwFramePathsAgree(I, Triangle<double>{}) < 0)
    GTEST_SKIP() << "no AVX2+FMA frame in this build or on this CPU";
  long failures = 0;
  const long n = test::scaled(3000);
  for (auto fam : scenes::kAllFamilies)
    for (long i = 0; i < n && failures < 10; ++i) {
      const auto k = scenes::generate(fam, seed, std::uint64_t(i));
      if (diagnostic::fastPathGate(k.cyl, k.pose, k.tri) != 1) continue;
      if (diagnostic::dwFramePathsAgree(k.pose, k.tri) != 1) {
        ++failures;
        ADD_FAILURE() << scenes::kFamilyNames[int(fam)] << " case " << i;
      }
    }
  std::mt19937_64 g(seed);
  auto pick = [&](int regime) {
    const double u = std::ldexp(double(g() >> 11), -53) * 2 - 1;
    switch (regime) {
      case 0:
        return double(long(g() % 17) - 8) * 0.25;  // short dyadics
      case 1:
        return std::ldexp(u, int(g() % 200) - 100);  // mixed exponents
      case 2:
        return std::ldexp(u, -1060);  // subnormal
      default:
        return u;
    }
  };
  for (long i = 0; i < test::scaled(20000) && failures < 10; ++i) {
    const int regime = int(i % 4);
    Pose<double> p;
    for (auto& row : p.R)
      for (double& r : row) r = g() % 3 == 0 ? 0.0 : pick(regime) * 0.99;
    p.t = {pick(regime), pick(regime), pick(regime)};
    Triangle<double> t{{pick(regime), pick(regime), pick(regime)},
                       {pick(regime), pick(regime), pick(regime)},
                       {pick(regime), pick(regime), pick(regime)}};
    if (g() % 4 == 0) t.b.y = p.t.y;  // d = 0 in one axis
    if (diagnostic::dwFramePathsAgree(p, t) != 1) {
      ++failures;
      ADD_FAILURE() << "regime " << regime << " case " << i;
    }
  }
  EXPECT_EQ(failures, 0);
}

// The arithmetic of the tracking kernels on polynomials of the triangle's
// shape (a b - c d, (a b - c d) (e + f) - g h, squares), with inputs that
// make exact ties, cancellations and mixed exponents: the bound of every
// result encloses the exact value (GMP dyadics), a bound of 0 means the
// value is exact, and every certified sign is the exact sign.
Q dyadicQ(const detail::Dyadic& x) {
  Q q(x.m);
  if (x.e >= 0)
    mpq_mul_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(x.e));
  else
    mpq_div_2exp(q.get_mpq_t(), q.get_mpq_t(), mp_bitcnt_t(-x.e));
  return q;
}

template <class K, class Value>
void trackingArithmetic(std::uint64_t seed, Value value) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  const long n = test::scaled(20000);
  long failures = 0, zeros = 0, decided = 0;
  for (long i = 0; i < n && failures < 10; ++i) {
    double in[8];
    const int regime = int(i % 4);
    for (double& x : in) {
      if (regime == 0)  // small dyadics: exact ties
        x = double(long(g() % 33) - 16) * 0.125;
      else if (regime == 1)  // general
        x = U(g);
      else if (regime == 2)  // mixed exponents
        x = std::ldexp(U(g), int(g() % 120) - 60);
      else  // near-cancelling pairs
        x = 1 + std::ldexp(U(g), -50);
    }
    if (regime == 3) in[2] = in[0], in[3] = in[1];  // a b - a b
    using N = typename K::Num;
    using detail::Dyadic;
    using detail::ExactKernel;
    N a[8];
    Dyadic d[8];
    for (int k = 0; k < 8; ++k) {
      a[k] = K::lift(in[k]);
      d[k] = ExactKernel::lift(in[k]);
    }
    const N r1 = a[0] * a[1] - a[2] * a[3];
    const Dyadic x1 = d[0] * d[1] - d[2] * d[3];
    const N r2 = r1 * (a[4] + a[5]) - a[6] * a[7];
    const Dyadic x2 = x1 * (d[4] + d[5]) - d[6] * d[7];
    const N r3 = r1 * r1 - (a[4] - a[5]) * (a[4] - a[5]);
    const Dyadic x3 = x1 * x1 - (d[4] - d[5]) * (d[4] - d[5]);
    const std::pair<const N*, const Dyadic*> checks[3] = {
        {&r1, &x1}, {&r2, &x2}, {&r3, &x3}};
    for (const auto& [r, x] : checks) {
      const Q exact = dyadicQ(*x);
      Q v;
      double e;
      value(*r, &v, &e);
      if (abs(v - exact) > exactly(e)) {
        ++failures;
        ADD_FAILURE() << "case " << i << " (regime " << regime
                      << "): outside the bound";
      }
      const detail::Sign s = K::sign(*r);
      const int truth = sgn(exact);
      if (s != detail::Sign::kUnknown) {
        ++decided;
        zeros += s == detail::Sign::kZero;
        if (int(s) != truth) {
          ++failures;
          ADD_FAILURE() << "case " << i << " (regime " << regime << "): sign "
                        << int(s) << ", exact " << truth;
        }
      }
    }
  }
  std::printf(
      "[ stats    ] %ld polynomials: %ld signs decided, %ld exact zeros\n",
      3 * n, decided, zeros);
  EXPECT_EQ(failures, 0);
  EXPECT_GT(zeros, n / 20);  // exact ties certified (regimes 0 and 3)
}
TEST(TrackingKernels, BoundsEncloseAndSignsAreExact) {
  const std::uint64_t seed = test::baseSeed() + 75;
  SCOPED_TRACE(test::seedTrace(seed));
  auto dw = [](const auto& r, Q* v, double* e) {
    *v = exactly(r.v.hi) + exactly(r.v.lo);
    *e = r.e;
  };
  trackingArithmetic<detail::DwKernel<false>>(seed, dw);
  trackingArithmetic<detail::DwKernel<true>>(seed, dw);
}

// The double-word kernel through the whole triangle kernel on every case of
// the families: whatever it decides is the oracle's answer.
TEST(DwKernelTriangle, AgreesWithTheOracle) {
  const std::uint64_t seed = test::baseSeed() + 76;
  SCOPED_TRACE(test::seedTrace(seed));
  for (scenes::Family f :
       {scenes::Family::kNear, scenes::Family::kThin, scenes::Family::kFar,
        scenes::Family::kAligned, scenes::Family::kSliver})
    agreesWithOracle<detail::DwKernel<false>>(f, test::scaled(1500), seed);
}

// diagnostic::filterOnly (the stage report's "filter's part") stops where
// the fast path stops: what it decides is what decideIntersect reports as
// decided by the early-outs or the filter; what it leaves open goes to a
// later stage; invalid input and gate misses are not its to time; and it
// leaves no trace on the next query.
TEST(FilterOnly, StopsWhereTheFastPathStops) {
  const std::uint64_t seed = test::baseSeed() + 76;
  SCOPED_TRACE(test::seedTrace(seed));
  long open = 0, failures = 0;
  const long n = test::scaled(2000);
  for (auto fam : scenes::kAllFamilies)
    for (long i = 0; i < n && failures < 10; ++i) {
      const auto k = scenes::generate(fam, seed, std::uint64_t(i));
      const int f = diagnostic::filterOnly(k.cyl, k.pose, k.tri);
      const Decision d = decideIntersect(k.cyl, k.pose, k.tri);
      const bool by_fast =
          d.stage == Stage::kEarlyOut || d.stage == Stage::kFastPath;
      const bool ok = f == 1 ? by_fast
                      : f == 0
                          ? d.stage != Stage::kEarlyOut
                          : diagnostic::fastPathGate(k.cyl, k.pose, k.tri) != 1;
      open += f == 0;
      if (!ok) {
        ++failures;
        ADD_FAILURE() << scenes::kFamilyNames[int(fam)] << " case " << i
                      << ": filterOnly " << f << ", stage " << int(d.stage);
      }
    }
  EXPECT_EQ(failures, 0);
  EXPECT_GT(open, 0) << "no query left open: the check above proved nothing";
  const Cylinder<double> cyl{1, 2};
  const Triangle<double> tri{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  Pose<double> bad = identityPose<double>();
  bad.t.x = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(diagnostic::filterOnly(cyl, bad, tri), -1);
  Pose<double> far = identityPose<double>();
  far.t.x = 0x1p41;  // outside the fast path's gate
  EXPECT_EQ(diagnostic::filterOnly(cyl, far, tri), -1);
  EXPECT_EQ(decideIntersect(cyl, identityPose<double>(), tri).answer,
            Answer::kIntersect);
  EXPECT_EQ(decideIntersect(cyl, far, tri).answer, Answer::kDisjoint);
}

}  // namespace
}  // namespace tricyl
