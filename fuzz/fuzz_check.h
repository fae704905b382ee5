// SPDX-License-Identifier: BSD-3-Clause
// Property checking shared by the fuzz targets: failure reporting (the case
// in hex floats, then abort, which libFuzzer records as a crash input), the
// floating-point trap scope and a few exact helpers.
#pragma once

#include <fenv.h>

#include <array>
#include <cstdio>
#include <cstdlib>

#include "fuzz_input.h"
#include "tricyl/types.h"

namespace tricyl::fuzz {

[[noreturn]] inline void fail(const char* what, const char* detail) {
  std::fprintf(stderr, "tricyl fuzz: PROPERTY VIOLATED: %s (%s)\n", what,
               detail);
  std::abort();
}

/// On a violation prints the case (print(c), found by argument-dependent
/// lookup in tricyl::fuzz) and aborts.
template <class C>
void check(bool ok, const char* what, const C& c) {
  if (ok) return;
  print(c);
  fail(what, sizeof(typename C::Scalar) == 8 ? "double" : "float");
}

/// Prints every decoded case when TRICYL_FUZZ_PRINT is set (replaying one
/// input by hand).
template <class C>
void maybePrint(const C& c) {
  if (std::getenv("TRICYL_FUZZ_PRINT")) print(c);
}

/// Traps FE_INVALID and FE_DIVBYZERO for its scope (valid input only: the
/// README promises no NaN is ever produced on valid input).
struct FpTraps {
  FpTraps() {
    feclearexcept(FE_ALL_EXCEPT);
    feenableexcept(FE_INVALID | FE_DIVBYZERO);
  }
  ~FpTraps() {
    fedisableexcept(FE_ALL_EXCEPT);
    feclearexcept(FE_ALL_EXCEPT);
  }
  FpTraps(const FpTraps&) = delete;
  FpTraps& operator=(const FpTraps&) = delete;
};

// float -> double is exact: the oracles (double inputs) see the same values.
template <class S>
Vec3<double> widen(const Vec3<S>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

template <class S>
Pose<double> widen(const Pose<S>& p) {
  Pose<double> d;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) d.R[i][j] = double(p.R[i][j]);
  d.t = widen(p.t);
  return d;
}

template <class S>
Vec3<S> neg(const Vec3<S>& v) {
  return {-v.x, -v.y, -v.z};
}

/// The five other orders of a triangle's vertices.
template <class S>
std::array<Triangle<S>, 5> otherVertexOrders(const Triangle<S>& t) {
  return {{{t.a, t.c, t.b},
           {t.b, t.a, t.c},
           {t.b, t.c, t.a},
           {t.c, t.a, t.b},
           {t.c, t.b, t.a}}};
}

/// The pose of the point reflection of the whole scene (t negated; the
/// caller negates the world points): y = R^T (x - t) becomes -y, exactly.
template <class S>
Pose<S> reflectedPose(const Pose<S>& p) {
  Pose<S> out = p;
  out.t = neg(p.t);
  return out;
}

/// The triangle of the point reflection of the scene (with
/// reflectedPose): every vertex negated, exactly.
template <class S>
Triangle<S> reflectedTriangle(const Triangle<S>& t) {
  return {neg(t.a), neg(t.b), neg(t.c)};
}

/// The same world placement turned a quarter about the shape's axis: the
/// columns of R become (c1, -c0, c2), so y becomes (y1, -y0, y2), exactly;
/// with flip_axis also c2 -> -c2 (y2 -> -y2). Every shape here is
/// symmetric under the quarter turn; the cylinder also under the flip.
template <class S>
Pose<S> quarterTurnPose(const Pose<S>& p, bool flip_axis) {
  Pose<S> out = p;
  for (int i = 0; i < 3; ++i) {
    out.R[i][0] = p.R[i][1];
    out.R[i][1] = -p.R[i][0];
    out.R[i][2] = flip_axis ? -p.R[i][2] : p.R[i][2];
  }
  return out;
}

}  // namespace tricyl::fuzz
