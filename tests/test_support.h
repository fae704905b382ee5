// SPDX-License-Identifier: BSD-3-Clause
// Shared test support: seeded randomness (TRICYL_SEED), FP traps, helpers.
#pragma once

#include <fenv.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>

#include "tricyl/types.h"

namespace tricyl::test {

/// The run's base seed: TRICYL_SEED from the environment, else a fixed
/// default. Every randomized test puts it in a SCOPED_TRACE so a failure
/// prints the seed to replay with.
inline std::uint64_t baseSeed() {
  if (const char* s = std::getenv("TRICYL_SEED"))
    return std::strtoull(s, nullptr, 10);
  return 20261122u;
}

/// Case counts scale with TRICYL_CASES_SCALE (default 1; the local run of
/// the acceptance figures uses 10; the emulated AArch64 run in CI a
/// fraction, e.g. 0.25, of the slowest suites), at least one case.
inline long scaled(long n) {
  if (const char* s = std::getenv("TRICYL_CASES_SCALE")) {
    const double f = std::strtod(s, nullptr);
    const double m = double(n) * f;
    return m < 1 ? 1 : static_cast<long>(m + 0.5);
  }
  return n;
}

/// An exact rigid motion of the world, x -> P x with P a signed axis
/// permutation: (P x)_i = sign_i x_{perm_i}. On a pose R' = P R, t' = P t,
/// so the local frame, and every answer, is unchanged bit for bit.
struct SignedPermutation {
  int perm[3];
  double sign[3];

  /// The motion number k of 48: the 6 permutations times the 8 signs.
  static SignedPermutation nth(long k) {
    static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                        {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
    const int p = int(k % 6);
    return {{kPerm[p][0], kPerm[p][1], kPerm[p][2]},
            {k & 1 ? -1.0 : 1.0, k & 2 ? -1.0 : 1.0, k & 4 ? -1.0 : 1.0}};
  }
  Vec3<double> operator()(const Vec3<double>& x) const {
    const double c[3] = {x.x, x.y, x.z};
    return {sign[0] * c[perm[0]], sign[1] * c[perm[1]], sign[2] * c[perm[2]]};
  }
  Pose<double> operator()(const Pose<double>& p) const {
    Pose<double> q;
    for (int r = 0; r < 3; ++r)
      for (int col = 0; col < 3; ++col)
        q.R[r][col] = sign[r] * p.R[perm[r]][col];
    q.t = (*this)(p.t);
    return q;
  }
};

/// A pose with the rotation of a random unit quaternion, rounded to double
/// (so a general pose: its local frame rounds, and R is orthonormal only to
/// about 1e-16, which the kernels use exactly as given), and a translation
/// with normal coordinates of standard deviation `spread`.
inline Pose<double> randomPose(std::mt19937_64& rng, double spread) {
  std::normal_distribution<double> g;
  double q[4] = {g(rng), g(rng), g(rng), g(rng)};
  const double n =
      std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (double& x : q) x /= n;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  const double R[3][3] = {
      {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)},
      {2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)},
      {2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)}};
  Pose<double> p;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.R[i][j] = R[i][j];
  p.t = {spread * g(rng), spread * g(rng), spread * g(rng)};
  return p;
}

/// How many queries each stage (tricyl::Stage) decided, for the [ stats ]
/// lines of the family tests.
struct StageCounts {
  std::array<long, 8> n{};
  void add(Stage s) { ++n[std::size_t(s)]; }
  long exact() const {
    return n[std::size_t(Stage::kExact)] + n[std::size_t(Stage::kExactGmp)];
  }
  std::string summary(long total) const {
    char buf[256];
    std::snprintf(
        buf, sizeof buf,
        "early-out %ld, fast %ld, running %ld, double-word %ld, exact %ld "
        "(stack %ld, GMP %ld: %.3f%%)",
        n[std::size_t(Stage::kEarlyOut)], n[std::size_t(Stage::kFastPath)],
        n[std::size_t(Stage::kRunning)], n[std::size_t(Stage::kExtended)],
        exact(), n[std::size_t(Stage::kExact)],
        n[std::size_t(Stage::kExactGmp)],
        100.0 * double(exact()) / double(total ? total : 1));
    return buf;
  }
};

inline std::string seedTrace(std::uint64_t seed) {
  return "seed=" + std::to_string(seed) +
         " (replay: TRICYL_SEED=" + std::to_string(seed) + ")";
}

/// Traps invalid operations and division by zero in every test: the kernel
/// must never produce a NaN or divide by zero on valid input. Tests that feed
/// NaN or Inf on purpose use NoFpTraps for their scope.
class FpTrapEnvironment : public ::testing::Environment {
 public:
  void SetUp() override { feenableexcept(FE_INVALID | FE_DIVBYZERO); }
  void TearDown() override { fedisableexcept(FE_ALL_EXCEPT); }
};

struct NoFpTraps {
  int saved = fegetexcept();
  NoFpTraps() { fedisableexcept(FE_ALL_EXCEPT); }
  ~NoFpTraps() {
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(saved);
  }
};

}  // namespace tricyl::test
