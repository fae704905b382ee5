// Shared test support: seeded randomness (TRICYL_SEED), FP traps, helpers.
#pragma once

#include <fenv.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <string>

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
/// the acceptance figures uses 10).
inline long scaled(long n) {
  if (const char* s = std::getenv("TRICYL_CASES_SCALE"))
    return n * std::atol(s);
  return n;
}

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
