// SPDX-License-Identifier: BSD-3-Clause
// Seeded case generators for the cylinder query family: point in
// cylinder, point in cone, sphere vs cylinder, segment and line vs cylinder.
// Shared
// by the tests and the benchmarks (and available to tricyl-compare).
// Header-only; reuses the Rng and pose helpers of scenes.h.
//
// generate(query, family, seed, index) is a pure function of its arguments.
// Families:
//   uniform     random sizes, random rotation and translation, query objects
//               around the solid: a mix of inside/outside, hit/miss.
//   near        a touching configuration built in the solid's frame (a
//               point on the side, a cap, the rim, the cone's slant or apex;
//               a sphere touching side, cap or rim; a segment tangent to the
//               side, through or grazing the rim, ending on the surface, in
//               a cap plane, parallel to the axis on the side), pushed by a
//               relative offset 1e-1 .. 1e-15 or 1..4 ulps, posed (random or
//               exact pose), and half the time nudged by -3..3 ulps per world
//               coordinate.
//   far         uniform and near cases translated by 1e3 .. 1e9.
//   degenerate  r = 0, lz = 0, rho = 0, p == q, axis-parallel and
//               axis-crossing segments, exactly touching configurations with
//               exact poses (Pythagorean triples on dyadic sizes), tiny and
//               huge sizes (outside the filter's range gate).
// Lines (Query::kLine) are built as the segments, then re-parametrised:
// the two defining points are moved along the line (lineParams), so that
// the touching or crossing feature sits anywhere in s (inside or outside
// [0, 1], up to |s| ~ 1e7) and p, q are sometimes very close together (a
// relative separation down to 1e-9); the degenerate family does it with
// exact dyadic factors (exact touching stays exact), p == q included.
#pragma once

#include <cmath>
#include <cstdint>
#include <iterator>

#include "enum_names.h"
#include "scenes.h"
#include "tricyl/types.h"

namespace tricyl::qscenes {

enum class Query { kPointCylinder, kPointCone, kSphere, kSegment, kLine };
enum class Family { kUniform, kNear, kFar, kDegenerate };
inline constexpr Family kAllFamilies[] = {Family::kUniform, Family::kNear,
                                          Family::kFar, Family::kDegenerate};

/// In the order of Family's enumerators.
inline constexpr const char* kFamilyNames[] = {"uniform", "near", "far",
                                               "degenerate"};
static_assert(std::size(kFamilyNames) == std::size(kAllFamilies));

inline const char* familyName(Family f) {
  return enum_names::nameOf(f, kFamilyNames);
}

/// One case. Point queries use p; the cone query reads cyl as Cone{radius,
/// lz}; the sphere is {p, rho}; the segment and the line are {p, q}.
struct QueryCase {
  Cylinder<double> cyl{0, 0};
  Pose<double> pose = identityPose<double>();
  Vec3<double> p{0, 0, 0}, q{0, 0, 0};
  double rho = 0;
  const char* feature = "";
};

namespace internal {

using scenes::Rng;
using V = Vec3<double>;
using scenes::internal::add;
using scenes::internal::scale;

inline V sub(V a, V b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }

inline V nudge(Rng& g, V v) {
  auto n = [&](double x) {
    const int k = g.integer(7) - 3;
    for (int i = 0; i < (k < 0 ? -k : k); ++i)
      x = std::nextafter(x, k < 0 ? -INFINITY : INFINITY);
    return x;
  };
  return {n(v.x), n(v.y), n(v.z)};
}

/// Local -> world with a random (rounded) or exact pose; world ulp nudges.
inline QueryCase pose(Rng& g, QueryCase k, bool exact_ok, bool nudge_ok) {
  k.pose = (exact_ok && g.coin()) ? scenes::internal::exactPose(g)
                                  : scenes::internal::randomPose(g, 1);
  k.p = scenes::internal::toWorld(k.pose, k.p);
  k.q = scenes::internal::toWorld(k.pose, k.q);
  if (nudge_ok && g.coin()) {
    k.p = nudge(g, k.p);
    k.q = nudge(g, k.q);
  }
  return k;
}

inline double angle(Rng& g) { return g.uniform(0, 2 * M_PI); }

/// A line's defining points at at + a dir and at + b dir (a != b), where
/// the feature of interest is at `at`, given the segment's choice
/// (a, b) = (-t0 len, (1 - t0) len): kept (feature inside [p, q]), both
/// within 4 len of the feature, both far on one side (|s| of the feature up
/// to ~1e7), or very close together (relative separation 1e-9 .. 1e-2).
inline void lineParams(Rng& g, double len, double t0, double* a, double* b) {
  const double sa = g.coin() ? 1.0 : -1.0, sb = g.coin() ? 1.0 : -1.0;
  switch (g.integer(4)) {
    case 0:
      *a = -t0 * len;
      *b = (1 - t0) * len;
      break;
    case 1:
      *a = g.uniform(-4, 4) * len;
      *b = g.uniform(-4, 4) * len;
      break;
    case 2:
      *a = sa * g.logUniform(1, 1e6) * len;
      *b = *a + sb * g.logUniform(0.1, 10) * len;
      break;
    default:
      *a = g.uniform(-2, 2) * len;
      *b = *a + sb * g.logUniform(1e-9, 1e-2) * len;
  }
  if (*a == *b) *b = *a + len;
}

/// Moves p and q along their line (uniform family).
inline void reparamLine(Rng& g, QueryCase& k) {
  const V d = sub(k.q, k.p);
  double a = 0, b = 1;
  lineParams(g, 1, 0, &a, &b);
  const V p = k.p;
  k.p = add(p, scale(d, a));
  k.q = add(p, scale(d, b));
}

/// Uniform: everything within ~1.5x of the solid.
inline QueryCase uniformLocal(Query qy, Rng& g) {
  QueryCase k;
  k.cyl = {g.logUniform(0.1, 2), g.logUniform(0.1, 4)};
  const double ext = 1.5 * std::max(k.cyl.radius, k.cyl.lz / 2);
  auto pt = [&] {
    return V{g.uniform(-ext, ext), g.uniform(-ext, ext), g.uniform(-ext, ext)};
  };
  k.p = pt();
  k.q = pt();
  if (qy == Query::kSphere) k.rho = g.logUniform(0.01, ext);
  if (qy == Query::kLine) reparamLine(g, k);
  k.feature = "uniform";
  return k;
}

/// A touching configuration pushed by the relative offset d.
inline QueryCase nearLocal(Query qy, Rng& g, double d) {
  QueryCase k;
  const double r = g.logUniform(0.1, 2), lz = g.logUniform(0.1, 4);
  const double h = lz / 2;
  k.cyl = {r, lz};
  const double th = angle(g), c = std::cos(th), s = std::sin(th);
  const double zs = g.coin() ? 1.0 : -1.0;
  switch (qy) {
    case Query::kPointCylinder:
      switch (g.integer(3)) {
        case 0:
          k.p = {r * (1 + d) * c, r * (1 + d) * s, g.uniform(-h, h)};
          k.feature = "side";
          break;
        case 1: {
          const double rr = r * std::sqrt(g.uniform());
          k.p = {rr * c, rr * s, zs * h * (1 + d)};
          k.feature = "cap";
          break;
        }
        default:
          k.p = {r * (1 + d) * c, r * (1 + d) * s, zs * h * (1 + d)};
          k.feature = "rim";
      }
      break;
    case Query::kPointCone:
      switch (g.integer(4)) {
        case 0: {  // slant: radius r (h - z) / lz, pushed outward
          const double z = g.uniform(-h, h);
          const double rad = r * (h - z) / lz * (1 + d);
          k.p = {rad * c, rad * s, z};
          k.feature = "slant";
          break;
        }
        case 1: {
          const double rr = r * std::sqrt(g.uniform());
          k.p = {rr * c, rr * s, -h * (1 + d)};
          k.feature = "base";
          break;
        }
        case 2:
          k.p = {r * (1 + d) * c, r * (1 + d) * s, -h * (1 + d)};
          k.feature = "rim";
          break;
        default:
          k.p = {d * r * c, d * r * s, h * (1 + d * (g.coin() ? 1 : -1))};
          k.feature = "apex";
      }
      break;
    case Query::kSphere: {
      const double rho = g.logUniform(0.01, 2);
      k.rho = rho;
      const double push = rho * (1 + d);
      switch (g.integer(3)) {
        case 0:
          k.p = {(r + push) * c, (r + push) * s, g.uniform(-h, h)};
          k.feature = "side";
          break;
        case 1: {
          const double rr = r * std::sqrt(g.uniform());
          k.p = {rr * c, rr * s, zs * (h + push)};
          k.feature = "cap";
          break;
        }
        default: {  // rim: a direction in the rim's normal cone
          const double phi = g.uniform(0, M_PI / 2);
          const double rad = r + push * std::cos(phi);
          k.p = {rad * c, rad * s, zs * (h + push * std::sin(phi))};
          k.feature = "rim";
        }
      }
      break;
    }
    case Query::kSegment:
    case Query::kLine: {
      const double len = g.logUniform(0.01, 4);
      const double t0 = g.uniform(0, 1);  // where the touching point sits
      auto around = [&](V at, V dir) {
        if (qy == Query::kLine) {
          double a = 0, b = 0;
          lineParams(g, len, t0, &a, &b);
          k.p = add(at, scale(dir, a));
          k.q = add(at, scale(dir, b));
          return;
        }
        k.p = sub(at, scale(dir, t0 * len));
        k.q = add(at, scale(dir, (1 - t0) * len));
      };
      switch (g.integer(7)) {
        case 0: {  // tangent to the side: horizontal or slanted tangent
          const V at{r * (1 + d) * c, r * (1 + d) * s, g.uniform(-h, h)};
          const double tz = g.coin() ? 0.0 : g.uniform(-1, 1);
          around(at, V{-s, c, tz});
          k.feature = "side tangent";
          break;
        }
        case 1: {  // through the rim, random direction (often crossing)
          const V at{r * (1 + d) * c, r * (1 + d) * s, zs * h * (1 + d)};
          around(at, scenes::internal::randomUnit(g));
          k.feature = "through rim";
          break;
        }
        case 2: {  // grazing the rim: tangent to both side and cap
          const V at{r * (1 + d) * c, r * (1 + d) * s, zs * h * (1 + d)};
          around(at, V{-s, c, 0});
          k.feature = "grazing rim";
          break;
        }
        case 3: {  // ends on the surface, going away
          const V at{r * (1 + d) * c, r * (1 + d) * s, g.uniform(-h, h)};
          V dir = scenes::internal::randomUnit(g);
          if (dir.x * c + dir.y * s < 0) dir = scale(dir, -1);
          if (qy == Query::kLine) {  // through a side point, outward
            around(at, dir);
            k.feature = "through a side point";
            break;
          }
          k.p = at;
          k.q = add(at, scale(dir, len));
          if (g.coin()) std::swap(k.p, k.q);
          k.feature = "endpoint on side";
          break;
        }
        case 4: {  // in a cap plane
          const double rr = r * g.uniform(0, 1.5);
          const V at{rr * c, rr * s, zs * h * (1 + d)};
          const double ph = angle(g);
          around(at, V{std::cos(ph), std::sin(ph), 0});
          k.feature = "in cap plane";
          break;
        }
        case 5: {  // parallel to the axis, on the side
          const V at{r * (1 + d) * c, r * (1 + d) * s, g.uniform(-h, h)};
          around(at, V{0, 0, 1});
          k.feature = "axis-parallel on side";
          break;
        }
        default: {  // crossing a cap disk near its edge, from outside
          const double rr = r * (1 + d);
          const V at{rr * c, rr * s, zs * h};
          V dir = scenes::internal::randomUnit(g);
          around(at, dir);
          k.feature = "cap edge crossing";
        }
      }
      break;
    }
  }
  return k;
}

inline double nearDelta(Rng& g) { return scenes::internal::nearDelta(g); }

/// Exactly representable, often exactly touching configurations.
inline QueryCase degenerateLocal(Query qy, Rng& g) {
  QueryCase k;
  // Dyadic sizes with Pythagorean points: r = 5 u, (3u, 4u) on the side.
  const double u = std::ldexp(1.0, g.integer(9) - 6);
  const double r = 5 * u, h = double(1 + g.integer(6)) * u;
  k.cyl = {r, 2 * h};
  const int sx = g.coin() ? 1 : -1, sy = g.coin() ? 1 : -1;
  const double zs = g.coin() ? 1.0 : -1.0;
  const V side{sx * 3 * u, sy * 4 * u, 0};
  switch (g.integer(8)) {
    case 0:
      k.cyl.radius = 0;
      k.feature = "r = 0";
      break;
    case 1:
      k.cyl.lz = 0;
      k.feature = "lz = 0";
      break;
    case 2:
      k.cyl = {0, 0};
      k.feature = "r = lz = 0";
      break;
    case 3: {
      const double sc = std::ldexp(1.0, g.coin() ? -1040 : 60);  // gate
      k.cyl = {r * sc, 2 * h * sc};
      k.feature = "huge or subnormal scale";
      break;
    }
    default:
      k.feature = "exact touching";
  }
  const double hz = k.cyl.lz / 2, rr = k.cyl.radius;
  const double sc = k.cyl.radius > 0 ? k.cyl.radius / r : (hz > 0 ? hz / h : u);
  const V side_s = scale(side, sc);
  switch (qy) {
    case Query::kPointCylinder:
    case Query::kPointCone:
      switch (g.integer(5)) {
        case 0:
          k.p = {side_s.x, side_s.y, zs * hz};  // rim
          break;
        case 1:
          k.p = {side_s.x, side_s.y, qy == Query::kPointCone ? -hz : 0};
          break;
        case 2:
          k.p = {0, 0, zs * hz};  // axis end / apex
          break;
        case 3:  // cone slant at mid-height: radius r / 2 at z = 0
          k.p = {side_s.x / 2, side_s.y / 2, 0};
          break;
        default:
          k.p = {0, 0, 0};
      }
      if (g.integer(3) == 0) k.p = nudge(g, k.p);
      break;
    case Query::kSphere: {
      const double rho = g.integer(4) == 0 ? 0.0 : 5 * sc * u;
      k.rho = rho;
      switch (g.integer(4)) {
        case 0:  // touching the rim: centre (r + 3k, h + 4k), rho = 5k
          k.p = {sx * (rr + 3 * sc * u), 0, zs * (hz + 4 * sc * u)};
          k.rho = 5 * sc * u;
          break;
        case 1:  // touching a cap
          k.p = {side_s.x / 5, side_s.y / 5, zs * (hz + rho)};
          break;
        case 2:  // touching the side
          k.p = {sx * (rr + rho), 0, zs * hz / 2};
          break;
        default:  // centre on the axis
          k.p = {0, 0, zs * (hz + rho * g.integer(3))};
      }
      if (g.integer(3) == 0) k.p = nudge(g, k.p);
      break;
    }
    case Query::kSegment:
    case Query::kLine:
      switch (g.integer(7)) {
        case 0:  // a point
          k.p = k.q = {side_s.x, side_s.y, zs * hz};
          break;
        case 1:  // along the side line, crossing both caps
          k.p = {side_s.x, side_s.y, -3 * hz - sc * u};
          k.q = {side_s.x, side_s.y, 3 * hz + sc * u};
          break;
        case 2:  // through the axis, perpendicular
          k.p = {-2 * rr - sc * u, 0, zs * hz};
          k.q = {2 * rr + sc * u, 0, zs * hz};
          break;
        case 3:  // tangent to the side at (r, 0)
          k.p = {sx * rr, -rr - sc * u, 0};
          k.q = {sx * rr, rr + sc * u, zs * hz};
          break;
        case 4:  // through the rim diagonally: (r, 0, h) +- (a, 0, a)
          k.p = {rr - 2 * sc * u, 0, zs * (hz - 2 * sc * u)};
          k.q = {rr + 2 * sc * u, 0, zs * (hz + 2 * sc * u)};
          break;
        case 5:  // along the axis
          k.p = {0, 0, -hz - sc * u * g.integer(3)};
          k.q = {0, 0, hz + sc * u * g.integer(3)};
          break;
        default:  // entirely inside
          k.p = {side_s.x / 2, side_s.y / 2, hz / 2};
          k.q = {-side_s.x / 2, 0, -hz / 2};
      }
      if (qy == Query::kLine && g.coin()) {
        // Move p and q along the line by dyadic factors (exact for these
        // few-bit coordinates, except in the subnormal scale): the feature
        // then sits outside [0, 1], or p and q are 2^-30 apart.
        static constexpr double kF[] = {-3, -1,  0,       1,      2,
                                        4,  0.5, -0x1p20, 0x1p20, 1 + 0x1p-30};
        const int i = g.integer(10);
        int j = g.integer(9);
        if (j >= i) ++j;
        const V d = sub(k.q, k.p), p = k.p;
        k.p = add(p, scale(d, kF[i]));
        k.q = add(p, scale(d, kF[j]));
      }
      if (g.integer(3) == 0) {
        k.p = nudge(g, k.p);
        k.q = nudge(g, k.q);
      }
      break;
  }
  return k;
}

}  // namespace internal

/// The case `index` of (query, family) for `seed`.
inline QueryCase generate(Query qy, Family fam, std::uint64_t seed,
                          std::uint64_t index) {
  scenes::Rng g(seed * 0x9e3779b97f4a7c15ULL ^ (std::uint64_t(qy) << 52) ^
                (std::uint64_t(fam) << 56) ^ index);
  switch (fam) {
    case Family::kUniform:
      return internal::pose(g, internal::uniformLocal(qy, g), false, false);
    case Family::kNear:
      return internal::pose(
          g, internal::nearLocal(qy, g, internal::nearDelta(g)), true, true);
    case Family::kFar: {
      QueryCase k =
          g.coin()
              ? internal::pose(g, internal::uniformLocal(qy, g), false, false)
              : internal::pose(
                    g, internal::nearLocal(qy, g, internal::nearDelta(g)),
                    false, true);
      const double mag = g.logUniform(1e3, 1e9);
      const Vec3<double> T =
          scenes::internal::scale(scenes::internal::randomUnit(g), mag);
      k.pose.t = scenes::internal::add(k.pose.t, T);
      k.p = scenes::internal::add(k.p, T);
      k.q = scenes::internal::add(k.q, T);
      return k;
    }
    case Family::kDegenerate: {
      QueryCase k = internal::degenerateLocal(qy, g);
      // Exact poses keep exact touching exact; one in four is random.
      if (g.integer(4) == 0) return internal::pose(g, k, false, false);
      k.pose = scenes::internal::exactPose(g);
      k.p = scenes::internal::toWorld(k.pose, k.p);
      k.q = scenes::internal::toWorld(k.pose, k.q);
      return k;
    }
  }
  return {};
}

}  // namespace tricyl::qscenes
