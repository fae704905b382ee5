// SPDX-License-Identifier: BSD-3-Clause
// Stability sweeps of tricyl-compare: near-touching configurations from the
// `near` generator (scenes.h) with one quantity swept and the rest drawn as
// in that family. Header-only, no FCL. Each sweep point is a CaseSet.
//
//   delta        the relative offset |delta| = 1e-1 .. 1e-15 and 4, 2, 1 ulp
//                (2^-52 units), half the cases pushed out, half pushed in;
//   translation  |delta| = 1e-3, both shapes moved by |t| = 1 .. 1e9 in a
//                random direction (the `far` construction at a fixed |t|);
//   aspect       |delta| = 1e-3, lz / (2 r) = 1e-6 .. 1e6 with the larger
//                of 2r and lz equal to 1 (discs to needles).
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "harness.h"
#include "scenes.h"

namespace tricyl::compare::sweeps {

inline std::uint64_t mix(std::uint64_t seed, std::uint64_t sweep,
                         std::uint64_t point, std::uint64_t index) {
  return seed * 0x9e3779b97f4a7c15ULL ^ (sweep << 56) ^ (point << 40) ^
         (index * 0xbf58476d1ce4e5b9ULL);
}

/// Near case with the given |delta| (sign from the index's parity), sizes
/// and pose drawn as in the near family unless r, lz are given.
inline scenes::TriCase nearAt(scenes::Rng& g, double abs_delta,
                              std::uint64_t index, double r = -1,
                              double lz = -1) {
  if (r < 0) {
    r = g.logUniform(0.1, 2);
    lz = g.logUniform(0.1, 4);
  }
  const Pose<double> pose = g.coin() ? scenes::internal::exactPose(g)
                                     : scenes::internal::randomPose(g, 1);
  const double delta = (index % 2 == 0) ? abs_delta : -abs_delta;
  return scenes::internal::nearCase(g, r, lz, pose, delta);
}

inline std::vector<CaseSet> deltaSweep(std::uint64_t seed, std::uint64_t n) {
  std::vector<double> ds;
  for (int e = 1; e <= 15; ++e) ds.push_back(std::pow(10.0, -e));
  for (int u : {4, 2, 1}) ds.push_back(u * 0x1p-52);
  std::vector<CaseSet> out;
  for (std::uint64_t p = 0; p < ds.size(); ++p) {
    const double d = ds[p];
    out.push_back({"sweep", "delta", d, n, [=](std::uint64_t i) {
                     scenes::Rng g(mix(seed, 1, p, i));
                     return Case{nearAt(g, d, i), nullptr};
                   }});
  }
  return out;
}

inline std::vector<CaseSet> translationSweep(std::uint64_t seed,
                                             std::uint64_t n) {
  std::vector<CaseSet> out;
  for (std::uint64_t p = 0; p <= 9; ++p) {
    const double mag = std::pow(10.0, double(p));
    out.push_back({"sweep", "translation", mag, n, [=](std::uint64_t i) {
                     scenes::Rng g(mix(seed, 2, p, i));
                     scenes::TriCase k = nearAt(g, 1e-3, i);
                     const auto u = scenes::internal::randomUnit(g);
                     const Vec3<double> T = {u.x * mag, u.y * mag, u.z * mag};
                     auto add = [&T](Vec3<double>& v) {
                       v = {v.x + T.x, v.y + T.y, v.z + T.z};
                     };
                     add(k.pose.t);
                     add(k.tri.a);
                     add(k.tri.b);
                     add(k.tri.c);
                     return Case{k, nullptr};
                   }});
  }
  return out;
}

inline std::vector<CaseSet> aspectSweep(std::uint64_t seed, std::uint64_t n) {
  std::vector<CaseSet> out;
  for (std::uint64_t p = 0; p <= 12; ++p) {
    const double aspect = std::pow(10.0, double(p) - 6);  // lz / (2 r)
    const double r = aspect >= 1 ? 0.5 / aspect : 0.5;
    const double lz = aspect >= 1 ? 1.0 : aspect;
    out.push_back({"sweep", "aspect", aspect, n, [=](std::uint64_t i) {
                     scenes::Rng g(mix(seed, 3, p, i));
                     return Case{nearAt(g, 1e-3, i, r, lz), nullptr};
                   }});
  }
  return out;
}

}  // namespace tricyl::compare::sweeps
