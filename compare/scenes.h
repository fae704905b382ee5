// SPDX-License-Identifier: BSD-3-Clause
// Seeded triangle/cylinder scene generators, shared by the tests, the
// benchmarks and tricyl-compare. Header-only, no FCL.
//
// generate(family, seed, index) is a pure function of its arguments, so a
// run's cases do not depend on the number of threads and any case can be
// replayed from (seed, index) alone.
//
// Families:
//   uniform  random sizes, random rotation and translation, random triangles
//            of random size around the cylinder: a mix of hits and misses.
//   near     a touching configuration (vertex on the side, vertex on a cap,
//            vertex on the rim, edge tangent to the side, edge on a cap,
//            edge tangent to the rim, face on a cap) built in the cylinder
//            frame, pushed out (delta > 0) or in (delta < 0) by a relative
//            offset in 1e-1 .. 1e-15 or by 1..4 ulps, then posed.
//   far      uniform and near configurations translated by 1e3 .. 1e9.
//   thin     needles (r = 1e-6 .. 1e-3, lz up to 1e3) and discs (r = 1e3,
//            lz = 1e-6) with triangles at their scale.
//   sliver   near-degenerate and exactly degenerate triangles (collinear,
//            repeated vertices, a point) near the cylinder.
//   aligned  triangles in the cap planes, parallel to or containing the
//            axis, edges through the rim; exactly representable poses.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <optional>
#include <string_view>

#include "enum_names.h"
#include "tricyl/types.h"

namespace tricyl::scenes {

enum class Family { kUniform, kNear, kFar, kThin, kSliver, kAligned };
inline constexpr Family kAllFamilies[] = {Family::kUniform, Family::kNear,
                                          Family::kFar,     Family::kThin,
                                          Family::kSliver,  Family::kAligned};

/// In the order of Family's enumerators.
inline constexpr const char* kFamilyNames[] = {"uniform", "near",   "far",
                                               "thin",    "sliver", "aligned"};
static_assert(std::size(kFamilyNames) == std::size(kAllFamilies));

inline const char* familyName(Family f) {
  return enum_names::nameOf(f, kFamilyNames);
}

inline std::optional<Family> parseFamily(std::string_view s) {
  for (Family f : kAllFamilies)
    if (s == familyName(f)) return f;
  return std::nullopt;
}

struct TriCase {
  Cylinder<double> cyl;
  Pose<double> pose;
  Triangle<double> tri;
  /// near cases: the intended signed relative offset of the touching
  /// feature (> 0 pushed outside, < 0 inside; for ulp offsets, k * 2^-52);
  /// NaN for other families. The world mapping rounds, so the exact
  /// clearance differs from delta by a few ulps of the coordinates.
  double delta = std::numeric_limits<double>::quiet_NaN();
  const char* feature = "";
};

/// SplitMix64 seeding a xoshiro256** generator: small, fast, reproducible.
class Rng {
 public:
  explicit Rng(std::uint64_t seed) {
    for (auto& w : s_) w = splitmix(seed);
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
    const std::uint64_t t = s_[1] << 17;
    s_[2] ^= s_[0];
    s_[3] ^= s_[1];
    s_[1] ^= s_[2];
    s_[0] ^= s_[3];
    s_[2] ^= t;
    s_[3] = rotl(s_[3], 45);
    return result;
  }
  /// Uniform in [0, 1).
  double uniform() { return double(next() >> 11) * 0x1p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// Log-uniform in [lo, hi], lo > 0.
  double logUniform(double lo, double hi) {
    return std::exp(uniform(std::log(lo), std::log(hi)));
  }
  int integer(int n) { return int(next() % std::uint64_t(n)); }
  bool coin() { return (next() >> 63) != 0; }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) {
    return (x << k) | (x >> (64 - k));
  }
  static std::uint64_t splitmix(std::uint64_t& x) {
    std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  std::uint64_t s_[4];
};

namespace internal {

using V = Vec3<double>;
inline V add(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
inline V scale(V a, double s) { return {a.x * s, a.y * s, a.z * s}; }

/// A uniformly random rotation (unit quaternion to matrix, rounded).
inline Pose<double> randomPose(Rng& g, double tmax) {
  double q[4], n2;
  do {
    for (double& c : q) c = g.uniform(-1, 1);
    n2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3];
  } while (n2 > 1 || n2 < 1e-6);
  const double n = std::sqrt(n2);
  const double w = q[0] / n, x = q[1] / n, y = q[2] / n, z = q[3] / n;
  Pose<double> p;
  p.R[0][0] = 1 - 2 * (y * y + z * z);
  p.R[0][1] = 2 * (x * y - w * z);
  p.R[0][2] = 2 * (x * z + w * y);
  p.R[1][0] = 2 * (x * y + w * z);
  p.R[1][1] = 1 - 2 * (x * x + z * z);
  p.R[1][2] = 2 * (y * z - w * x);
  p.R[2][0] = 2 * (x * z - w * y);
  p.R[2][1] = 2 * (y * z + w * x);
  p.R[2][2] = 1 - 2 * (x * x + y * y);
  p.t = {g.uniform(-tmax, tmax), g.uniform(-tmax, tmax),
         g.uniform(-tmax, tmax)};
  return p;
}

/// A signed axis permutation with a small dyadic translation: exact.
inline Pose<double> exactPose(Rng& g) {
  static constexpr int kPerm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                      {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const auto& p = kPerm[g.integer(6)];
  Pose<double> pose{};
  for (int i = 0; i < 3; ++i) pose.R[i][p[i]] = g.coin() ? 1.0 : -1.0;
  pose.t = {double(g.integer(17) - 8) * 0.5, double(g.integer(17) - 8) * 0.5,
            double(g.integer(17) - 8) * 0.5};
  return pose;
}

inline V toWorld(const Pose<double>& p, V l) {
  return {p.R[0][0] * l.x + p.R[0][1] * l.y + p.R[0][2] * l.z + p.t.x,
          p.R[1][0] * l.x + p.R[1][1] * l.y + p.R[1][2] * l.z + p.t.y,
          p.R[2][0] * l.x + p.R[2][1] * l.y + p.R[2][2] * l.z + p.t.z};
}

inline TriCase posed(Cylinder<double> cyl, const Pose<double>& pose, V a, V b,
                     V c) {
  TriCase k;
  k.cyl = cyl;
  k.pose = pose;
  k.tri = {toWorld(pose, a), toWorld(pose, b), toWorld(pose, c)};
  return k;
}

inline V randomUnit(Rng& g) {
  V v;
  double n2;
  do {
    v = {g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)};
    n2 = v.x * v.x + v.y * v.y + v.z * v.z;
  } while (n2 > 1 || n2 < 1e-6);
  return scale(v, 1 / std::sqrt(n2));
}

inline TriCase uniformCase(Rng& g) {
  // Centres within 1 unit of the cylinder's centre per axis, sizes
  // 0.05 .. 2, cylinder sizes 0.1 .. 2 and 0.1 .. 4: a mix of hits and
  // misses, most misses separable by the bounding box.
  const Cylinder<double> cyl{g.logUniform(0.1, 2), g.logUniform(0.1, 4)};
  const V c = {g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)};
  const double size = g.logUniform(0.05, 2);
  // Every draw in its own statement: the arguments of one call are
  // evaluated in an unspecified order (GCC right to left, clang left to
  // right), so draws inside a call's arguments made the families depend on
  // the compiler (issue 20). The order kept is the one GCC used.
  const V uc = randomUnit(g);
  const V ub = randomUnit(g);
  const V ua = randomUnit(g);
  const Pose<double> pose = randomPose(g, 1);
  return posed(cyl, pose, add(c, scale(ua, size)), add(c, scale(ub, size)),
               add(c, scale(uc, size)));
}

/// Relative offsets for the near family: 1e-1 .. 1e-15, or 1..4 ulps.
inline double nearDelta(Rng& g) {
  double d;
  if (g.integer(4) == 0) {
    d = double(1 + g.integer(4)) * 0x1p-52;
  } else {
    d = std::pow(10.0, -double(1 + g.integer(15)));
  }
  return g.coin() ? d : -d;
}

/// A touching configuration in the cylinder frame, pushed by delta.
inline TriCase nearCase(Rng& g, double r, double lz, const Pose<double>& pose,
                        double delta) {
  const double h = lz / 2;
  const double th = g.uniform(0, 2 * M_PI);
  const V rad = {std::cos(th), std::sin(th), 0};   // outward radial
  const V tan = {-std::sin(th), std::cos(th), 0};  // tangential
  const V up = {0, 0, g.coin() ? 1.0 : -1.0};      // towards one cap
  const double s = 1 + delta;
  const double zin = g.uniform(-0.9, 0.9) * h;
  const double len = g.logUniform(0.05, 3) * (r + h);
  auto out = [&](V base, double a, double b, double c) {
    return add(base, add(scale(rad, a * len),
                         add(scale(tan, b * len), scale(up, c * len))));
  };
  const Cylinder<double> cyl{r, lz};
  TriCase k;
  // Every draw in its own statement: the arguments of one call are
  // evaluated in an unspecified order (GCC right to left, clang left to
  // right), so draws inside a call's arguments made the families depend on
  // the compiler (issue 20). The order kept is the one GCC used: c2, c1, b2, b1
  // for out(v, .., b1, b2) and out(v, .., c1, c2).
  auto draw = [&g](double lo, double hi) { return g.uniform(lo, hi); };
  switch (g.integer(7)) {
    case 0: {  // vertex on the side
      const V v = add(scale(rad, r * s), {0, 0, zin});
      const double c2 = draw(-1, 1), c1 = draw(-1, 1), b2 = draw(-1, 1),
                   b1 = draw(-1, 1);
      k = posed(cyl, pose, v, out(v, 1, b1, b2), out(v, 1, c1, c2));
      k.feature = "vertex_side";
      break;
    }
    case 1: {  // vertex on a cap
      const V v = add(scale(rad, r * g.uniform(0, 0.9)), scale(up, h * s));
      const double c2 = draw(-1, 1), c1 = draw(-1, 1), b2 = draw(-1, 1),
                   b1 = draw(-1, 1);
      k = posed(cyl, pose, v, out(v, b1, b2, 1), out(v, c1, c2, 1));
      k.feature = "vertex_cap";
      break;
    }
    case 2: {  // vertex on the rim
      const V v = add(scale(rad, r * s), scale(up, h * s));
      const double c2 = draw(-1, 1), c1 = draw(0, 1), b2 = draw(0, 1),
                   b1 = draw(-1, 1);
      k = posed(cyl, pose, v, out(v, 1, b1, b2), out(v, c1, c2, 1));
      k.feature = "vertex_rim";
      break;
    }
    case 3: {  // edge tangent to the side
      const V m = add(scale(rad, r * s), {0, 0, zin});
      const double a = g.uniform(0.1, 1) * len, b = g.uniform(0.1, 1) * len;
      const double tilt = g.uniform(-0.5, 0.5);
      const V e = {tan.x, tan.y, tilt};
      const double c2 = draw(-1, 1), c1 = draw(-1, 1);
      k = posed(cyl, pose, add(m, scale(e, a)), add(m, scale(e, -b)),
                out(m, 1, c1, c2));
      k.feature = "edge_side";
      break;
    }
    case 4: {  // edge lying on a cap plane, across the disk
      const V m = add(scale(rad, r * g.uniform(0, 0.9)), scale(up, h * s));
      const double a = g.uniform(0.1, 1) * len, b = g.uniform(0.1, 1) * len;
      const double c2 = draw(-1, 1), c1 = draw(-1, 1);
      k = posed(cyl, pose, add(m, scale(tan, a)), add(m, scale(tan, -b)),
                out(m, c1, c2, 1));
      k.feature = "edge_cap";
      break;
    }
    case 5: {  // edge tangent to the rim circle, in the cap plane
      const V m = add(scale(rad, r * s), scale(up, h * s));
      const double a = g.uniform(0.1, 1) * len, b = g.uniform(0.1, 1) * len;
      const double c2 = draw(-1, 1), c1 = draw(0, 1);
      k = posed(cyl, pose, add(m, scale(tan, a)), add(m, scale(tan, -b)),
                out(m, c1, c2, 1));
      k.feature = "edge_rim";
      break;
    }
    default: {  // face parallel to a cap, over the disk
      const V c = add(scale(rad, r * g.uniform(0, 0.9)), scale(up, h * s));
      const double a = len;
      k = posed(cyl, pose, add(c, {a, 0, 0}), add(c, {-a / 2, a, 0}),
                add(c, {-a / 2, -a, 0}));
      k.feature = "face_cap";
      break;
    }
  }
  k.delta = delta;
  return k;
}

inline TriCase thinCase(Rng& g) {
  const bool needle = g.coin();
  const double r = needle ? g.logUniform(1e-6, 1e-3) : 1e3;
  const double lz = needle ? g.logUniform(1, 1e3) : 1e-6;
  const Pose<double> pose = randomPose(g, 1);
  if (g.coin()) return nearCase(g, r, lz, pose, nearDelta(g));
  // Triangles at the scale of the thin dimension, near the thin part.
  const double scale_thin = needle ? r : lz;
  const double scale_long = needle ? lz : r;
  const V c = needle ? V{g.uniform(-3, 3) * r, g.uniform(-3, 3) * r,
                         g.uniform(-0.6, 0.6) * lz}
                     : V{g.uniform(-1.2, 1.2) * r, g.uniform(-1.2, 1.2) * r,
                         g.uniform(-3, 3) * lz};
  const double size = g.coin() ? scale_thin * g.logUniform(0.5, 20)
                               : scale_long * g.logUniform(1e-3, 1);
  // One draw per statement (see uniformCase), in GCC's order.
  const V uc = randomUnit(g);
  const V ub = randomUnit(g);
  const V ua = randomUnit(g);
  TriCase k = posed({r, lz}, pose, add(c, scale(ua, size)),
                    add(c, scale(ub, size)), add(c, scale(uc, size)));
  k.feature = needle ? "needle" : "disc";
  return k;
}

inline TriCase sliverCase(Rng& g) {
  TriCase k = uniformCase(g);
  V& a = k.tri.a;
  V& b = k.tri.b;
  V& c = k.tri.c;
  switch (g.integer(5)) {
    case 0: {  // c very close to the segment ab
      const double t = g.uniform(-0.5, 1.5);
      const double eps = std::pow(10.0, -double(g.integer(16)));
      c = add(add(a, scale({b.x - a.x, b.y - a.y, b.z - a.z}, t)),
              scale(randomUnit(g), eps));
      k.feature = "near_collinear";
      break;
    }
    case 1: {  // exactly collinear: c = a + (b - a) * 2^-k, computed exactly
      const double t = std::ldexp(1.0, -g.integer(4));
      // Snap a and b to a coarse dyadic grid so the affine point is exact.
      auto snap = [](double v) {
        return std::ldexp(std::round(std::ldexp(v, 20)), -20);
      };
      a = {snap(a.x), snap(a.y), snap(a.z)};
      b = {snap(b.x), snap(b.y), snap(b.z)};
      c = {a.x + (b.x - a.x) * t, a.y + (b.y - a.y) * t, a.z + (b.z - a.z) * t};
      k.feature = "collinear";
      break;
    }
    case 2:  // a repeated vertex
      c = b;
      k.feature = "repeated_vertex";
      break;
    case 3:  // a point
      b = a;
      c = a;
      k.feature = "point";
      break;
    default: {  // a needle triangle: very short edge
      const double eps = std::pow(10.0, -double(g.integer(16)));
      b = add(a, scale(randomUnit(g), eps));
      k.feature = "short_edge";
      break;
    }
  }
  return k;
}

inline TriCase alignedCase(Rng& g) {
  // Small dyadic numbers, exactly representable poses: many exact ties.
  const double r = double(1 + g.integer(8)) * 0.25;
  const double lz = double(1 + g.integer(8)) * 0.5;
  const double h = lz / 2;
  const Pose<double> pose = g.coin() ? exactPose(g) : randomPose(g, 1);
  auto d = [&g](int n) { return double(g.integer(2 * n + 1) - n) * 0.125; };
  const Cylinder<double> cyl{r, lz};
  TriCase k;
  // One draw per statement (see uniformCase), in GCC's order: the third
  // vertex first, each vertex's coordinates in order.
  switch (g.integer(5)) {
    case 0: {  // in a cap plane (or just off it)
      const double z = (g.coin() ? h : -h) + (g.integer(3) - 1) * 0.0625;
      const V c = {d(16), d(16), z};
      const V b = {d(16), d(16), z};
      const V a = {d(16), d(16), z};
      k = posed(cyl, pose, a, b, c);
      k.feature = "cap_plane";
      break;
    }
    case 1: {  // parallel to the axis: a vertical triangle x = const
      const double x = (g.integer(3) - 1) * 0.0625 + (g.coin() ? r : -r);
      const V c = {x, d(16), d(24)};
      const V b = {x, d(16), d(24)};
      const V a = {x, d(16), d(24)};
      k = posed(cyl, pose, a, b, c);
      k.feature = "parallel_axis";
      break;
    }
    case 2: {  // plane containing the axis: y = m x
      const double m = d(8);
      const double x0 = d(16), x1 = d(16), x2 = d(16);
      const V c = {x2, m * x2, d(24)};
      const V b = {x1, m * x1, d(24)};
      const V a = {x0, m * x0, d(24)};
      k = posed(cyl, pose, a, b, c);
      k.feature = "contains_axis";
      break;
    }
    case 3: {  // an edge through a rim point (r, 0, +-h)
      const double z = g.coin() ? h : -h;
      const V p = {r, 0, z};
      const V q = {r + d(8), d(8), z + d(8)};
      const V mirror = {2 * p.x - q.x, 2 * p.y - q.y, 2 * p.z - q.z};
      k = posed(cyl, pose, q, mirror, {d(16), d(16), d(24)});
      k.feature = "edge_through_rim";
      break;
    }
    default: {  // axis-aligned box-like triangles on the grid
      const V c = {d(16), d(16), d(24)};
      const V b = {d(16), d(16), d(24)};
      const V a = {d(16), d(16), d(24)};
      k = posed(cyl, pose, a, b, c);
      k.feature = "grid";
      break;
    }
  }
  return k;
}

}  // namespace internal

/// The case `index` of `family` for `seed`.
inline TriCase generate(Family family, std::uint64_t seed,
                        std::uint64_t index) {
  Rng g(seed * 0x9e3779b97f4a7c15ULL ^ (std::uint64_t(family) << 56) ^ index);
  switch (family) {
    case Family::kUniform: {
      TriCase k = internal::uniformCase(g);
      k.feature = "uniform";
      return k;
    }
    case Family::kNear: {
      const double r = g.logUniform(0.1, 2), lz = g.logUniform(0.1, 4);
      const Pose<double> pose =
          g.coin() ? internal::exactPose(g) : internal::randomPose(g, 1);
      return internal::nearCase(g, r, lz, pose, internal::nearDelta(g));
    }
    case Family::kFar: {
      TriCase k;
      if (g.coin()) {
        k = internal::uniformCase(g);
      } else {  // one draw per statement (see uniformCase), GCC's order
        const double delta = internal::nearDelta(g);
        const Pose<double> pose = internal::randomPose(g, 1);
        const double lz = g.logUniform(0.1, 4);
        const double r = g.logUniform(0.1, 2);
        k = internal::nearCase(g, r, lz, pose, delta);
      }
      const double mag = g.logUniform(1e3, 1e9);
      const internal::V T = internal::scale(internal::randomUnit(g), mag);
      k.pose.t = internal::add(k.pose.t, T);
      k.tri.a = internal::add(k.tri.a, T);
      k.tri.b = internal::add(k.tri.b, T);
      k.tri.c = internal::add(k.tri.c, T);
      k.feature = "far";
      return k;
    }
    case Family::kThin:
      return internal::thinCase(g);
    case Family::kSliver:
      return internal::sliverCase(g);
    case Family::kAligned:
      return internal::alignedCase(g);
  }
  return {};
}

/// The case `i` of a distance family (tricyl-compare's distance and margin
/// families, tricyl-margin-stage-costs): the family's scene, for 3 in 4 of
/// them moved apart along a random direction by 10^-15 .. 10^3 (log-
/// uniform) of the cylinder's size max(r, lz).
inline TriCase distanceCase(Family f, std::uint64_t seed, std::uint64_t i) {
  TriCase k = generate(f, seed ^ 0x64697374616e6365ULL, i);
  if (i % 4 == 0) return k;
  Rng g(seed * 0x2545f4914f6cdd1dULL ^ (std::uint64_t(f) << 48) ^ i);
  const double size = std::max(k.cyl.radius, k.cyl.lz);
  const double s = g.logUniform(1e-15, 1e3) * size;
  const internal::V u = internal::randomUnit(g);
  const internal::V T = internal::scale(u, s);
  k.tri.a = internal::add(k.tri.a, T);
  k.tri.b = internal::add(k.tri.b, T);
  k.tri.c = internal::add(k.tri.c, T);
  return k;
}

/// Hostile input with random exponents (tricyl-margin-stage-costs and the
/// margin tests; the Boolean's set of tricyl-stage-costs is drawn the same
/// way): every length (sizes, translation, vertices) sign * (1 + f) *
/// 2^e with e uniform in [-1070, len_hi], every rotation entry with e in
/// [-1070, rot_hi] (not a rotation), from the 64-bit draws of `next`:
/// mantissa, exponent, sign, in that order. The sizes are made
/// non-negative.
template <class Next>
double randomExponent(Next& next, int lo, int hi) {
  const double f = 1.0 + double(next() >> 12) * 0x1p-52;
  const int e = lo + int(next() % std::uint64_t(hi - lo + 1));
  return ((next() & 1) ? -1.0 : 1.0) * std::ldexp(f, e);
}
template <class Next>
TriCase randomExponentCase(Next& next, int len_hi, int rot_hi) {
  auto len = [&] { return randomExponent(next, -1070, len_hi); };
  TriCase k;
  k.cyl.radius = std::fabs(len());
  k.cyl.lz = std::fabs(len());
  for (auto& row : k.pose.R)
    for (double& r : row) r = randomExponent(next, -1070, rot_hi);
  k.pose.t.x = len();
  k.pose.t.y = len();
  k.pose.t.z = len();
  for (Vec3<double>* v : {&k.tri.a, &k.tri.b, &k.tri.c}) {
    v->x = len();
    v->y = len();
    v->z = len();
  }
  return k;
}

}  // namespace tricyl::scenes
