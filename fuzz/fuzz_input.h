// SPDX-License-Identifier: BSD-3-Clause
// Decoding raw fuzzer bytes into query inputs (shared by the fuzz targets).
//
// Every scalar is produced by a one-byte tag followed by its payload, so the
// fuzzer can reach both arbitrary bit patterns and structured values:
//   tag % 8 == 0, 1  the next 8 bytes are the double's bit pattern (4 bytes,
//                    a float's, in float mode): NaNs with any payload, +-Inf,
//                    subnormals, +-0, 1e+-300, everything;
//            2       int8 mantissa times 2^int8 (small dyadics, exact ties);
//            3       a table of special values (NaN, Inf, DBL_MAX, the
//                    smallest subnormal, 1e+-300, 1 +- 1 ulp, ...);
//            4       a copy of an earlier scalar (exact ties between inputs);
//            5       an earlier scalar times 2^k (k in -3..3), moved by
//                    -2..2 ulps (lz/2 against a coordinate, near-ties);
//            6       an earlier scalar negated;
//            7       int16 / 256 (moderate values).
// A missing byte reads as 0, so every byte string decodes to some input.
//
// Two layouts share this scalar coding: decode() for the triangle target
// (unchanged, its corpus stays valid) and QueryInput + the per-query
// decoders (decodePoint, decodeSphere, decodeSegment) for the cylinder query
// targets, documented at QueryInput.
#pragma once

#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

#include "tricyl/endpoint_form.h"
#include "tricyl/types.h"

namespace tricyl::fuzz {

class ByteReader {
 public:
  ByteReader(const std::uint8_t* data, std::size_t size)
      : data_(data), size_(size) {}
  std::uint8_t byte() { return pos_ < size_ ? data_[pos_++] : 0; }
  template <class U>
  U bits() {
    U u = 0;
    for (std::size_t i = 0; i < sizeof(U); ++i) u |= U(byte()) << (8 * i);
    return u;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

template <class S>
S specialValue(std::uint8_t k) {
  using L = std::numeric_limits<S>;
  const S table[] = {
      S(0), -S(0), S(1), S(-1), S(0.5), S(2), L::quiet_NaN(), -L::quiet_NaN(),
      L::infinity(), -L::infinity(), L::max(), L::lowest(), L::min(),
      L::denorm_min(), -L::denorm_min(), std::nextafter(S(1), S(2)),
      std::nextafter(S(1), S(0)), L::epsilon(), L::signaling_NaN(), S(3),
      S(0.75), S(0.6), S(0.8), S(1e-7),
      // double-only magnitudes; in float mode these round
      // (exactly as a user's conversion would): Inf or 0.
      S(sizeof(S) == 8 ? 1e300 : 1e38), S(sizeof(S) == 8 ? -1e300 : -1e38),
      S(sizeof(S) == 8 ? 1e-300 : 1e-38), S(sizeof(S) == 8 ? 1e150 : 1e19),
      S(sizeof(S) == 8 ? 1e-150 : 1e-19), S(0x1p40),
      std::nextafter(S(0x1p40), S(0x1p41)), S(0x1p-600 * (sizeof(S) == 8))};
  return table[k % (sizeof(table) / sizeof(table[0]))];
}

template <class U, class S>
S fromBits(U u) {
  static_assert(sizeof(U) == sizeof(S));
  S s;
  std::memcpy(&s, &u, sizeof s);
  return s;
}

/// Decodes scalars of type S (float or double) as described above.
template <class S>
class ScalarDecoder {
 public:
  explicit ScalarDecoder(ByteReader* in) : in_(in) {}

  S next() {
    const std::uint8_t tag = in_->byte();
    S v = S(0);
    switch (tag % 8) {
      case 0:
      case 1:
        if constexpr (sizeof(S) == 8)
          v = fromBits<std::uint64_t, S>(in_->bits<std::uint64_t>());
        else
          v = fromBits<std::uint32_t, S>(in_->bits<std::uint32_t>());
        break;
      case 2: {
        const auto m = static_cast<std::int8_t>(in_->byte());
        const auto e = static_cast<std::int8_t>(in_->byte());
        v = std::ldexp(S(m), e);
        break;
      }
      case 3:
        v = specialValue<S>(in_->byte());
        break;
      case 4:
        v = earlier();
        break;
      case 5: {
        const std::uint8_t k = in_->byte();
        v = std::ldexp(earlier(), int(k % 7) - 3);
        const int ulps = int((k / 7) % 5) - 2;
        for (int i = 0; i < ulps; ++i)
          v = std::nextafter(v, std::numeric_limits<S>::infinity());
        for (int i = 0; i > ulps; --i)
          v = std::nextafter(v, -std::numeric_limits<S>::infinity());
        break;
      }
      case 6:
        v = -earlier();
        break;
      default:
        v = S(static_cast<std::int16_t>(in_->bits<std::uint16_t>())) / S(256);
        break;
    }
    seen_.push_back(v);
    return v;
  }

 private:
  S earlier() {
    const std::uint8_t i = in_->byte();
    return seen_.empty() ? S(0) : seen_[i % seen_.size()];
  }
  ByteReader* in_;
  std::vector<S> seen_;
};

/// One decoded query.
template <class S>
struct Case {
  using Scalar = S;
  Cylinder<S> cyl{};
  Pose<S> pose{};
  Triangle<S> tri{};
  bool identity_pose = false;
};

/// Signed axis permutations (48 of them, 24 proper rotations): exact
/// rotations with which the fuzzer reaches axis-aligned ties.
template <class S>
void signedPermutation(std::uint8_t k, S R[3][3]) {
  static const int perms[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2},
                                  {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  const int* p = perms[k % 6];
  const int signs = (k / 6) % 8;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      R[i][j] = (p[i] == j) ? ((signs >> i) & 1 ? S(-1) : S(1)) : S(0);
}

/// Reads the pose of mode `mode` (flags & 3, see decode()) after the sizes:
/// 0 or 3 = R as 9 free scalars then t; 1 = a signed axis permutation (one
/// byte) then t; 2 = the identity (nothing read).
template <class S>
Pose<S> readPose(ByteReader* in, ScalarDecoder<S>* dec, std::uint8_t mode,
                 bool* identity) {
  Pose<S> pose{};
  *identity = false;
  switch (mode & 3) {
    case 1:
      signedPermutation(in->byte(), pose.R);
      break;
    case 2:
      pose = identityPose<S>();
      *identity = true;
      break;
    default:
      for (auto& row : pose.R)
        for (S& v : row) v = dec->next();
  }
  if (!*identity) pose.t = {dec->next(), dec->next(), dec->next()};
  return pose;
}

/// R y + t in S arithmetic (rounded; may overflow): a point given in the
/// shape's frame, placed near the shape under any pose.
template <class S>
Vec3<S> toWorld(const Pose<S>& pose, const Vec3<S>& v) {
  const S y[3] = {v.x, v.y, v.z};
  S w[3];
  for (int i = 0; i < 3; ++i) {
    w[i] = pose.R[i][0] * y[0];
    w[i] += pose.R[i][1] * y[1];
    w[i] += pose.R[i][2] * y[2];
  }
  return {w[0] + pose.t.x, w[1] + pose.t.y, w[2] + pose.t.z};
}

/// Layout: a flags byte, then the scalars.
///   flags & 3: 0 or 3 = R as 9 free scalars; 1 = a signed axis permutation
///              (one byte); 2 = the identity pose (R = I, t = 0; no t is
///              read, so the local-frame overload can be compared).
///   flags & 4: the triangle's vertices are given in the cylinder frame and
///              mapped to the world by the pose in S arithmetic (rounded),
///              which puts them near the cylinder under any rotation.
/// Order: radius, lz, R (if free), t (unless identity), a, b, c.
/// decodeCase reads from a reader and decoder that the caller may go on
/// reading (fuzz_triangle_cylinder_margin reads the margin after it).
template <class S>
Case<S> decodeCase(ByteReader* in, ScalarDecoder<S>* dec) {
  Case<S> c;
  const std::uint8_t flags = in->byte();
  c.cyl.radius = dec->next();
  c.cyl.lz = dec->next();
  c.pose = readPose(in, dec, flags, &c.identity_pose);
  Vec3<S>* verts[3] = {&c.tri.a, &c.tri.b, &c.tri.c};
  for (Vec3<S>* v : verts) *v = {dec->next(), dec->next(), dec->next()};
  if ((flags & 4) && !c.identity_pose)
    for (Vec3<S>* v : verts) *v = toWorld(c.pose, *v);
  return c;
}

template <class S>
Case<S> decode(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  ScalarDecoder<S> dec(&in);
  return decodeCase(&in, &dec);
}

template <class S>
bool finite(S v) {
  return std::isfinite(v);
}

/// The documented validity rule: everything finite, radius and lz >= 0
/// (-0 is zero, valid).
template <class S>
bool valid(const Case<S>& c) {
  bool ok = finite(c.cyl.radius) && finite(c.cyl.lz) && !(c.cyl.radius < 0) &&
            !(c.cyl.lz < 0);
  for (const auto& row : c.pose.R)
    for (S v : row) ok = ok && finite(v);
  const Vec3<S> vs[4] = {c.pose.t, c.tri.a, c.tri.b, c.tri.c};
  for (const auto& v : vs) ok = ok && finite(v.x) && finite(v.y) && finite(v.z);
  return ok;
}

inline void printScalar(const char* name, double v) {
  std::fprintf(stderr, "%s = %a\n", name, v);
}

/// Prints a case bit-exactly (hex floats; float values widened exactly).
template <class S>
void print(const Case<S>& c) {
  std::fprintf(stderr, "scalar = %s\n", sizeof(S) == 8 ? "double" : "float");
  printScalar("r ", double(c.cyl.radius));
  printScalar("lz", double(c.cyl.lz));
  for (int i = 0; i < 3; ++i)
    std::fprintf(stderr, "R[%d] = %a %a %a\n", i, double(c.pose.R[i][0]),
                 double(c.pose.R[i][1]), double(c.pose.R[i][2]));
  const Vec3<S> vs[4] = {c.pose.t, c.tri.a, c.tri.b, c.tri.c};
  const char* names[4] = {"t", "a", "b", "c"};
  for (int k = 0; k < 4; ++k)
    std::fprintf(stderr, "%s = %a %a %a\n", names[k], double(vs[k].x),
                 double(vs[k].y), double(vs[k].z));
}

// ---------------------------------------------------------------------------
// The cylinder query targets (fuzz_point_cylinder, fuzz_point_cone,
// fuzz_sphere_cylinder, fuzz_segment_cylinder).

/// How the shape and its pose are given (flags bits 4-5).
enum class Form : std::uint8_t {
  kDirect = 0,     ///< radius, lz, pose as decode() reads them
  kAxis = 1,       ///< cylinderFromAxis(O, N, L, R) / coneFromApex(O, N, L, R)
  kEndpoints = 2,  ///< cylinderFromEndpoints(a, b, R)
};

enum class ShapeKind { kCylinder, kCone };

/// A shape's sizes and pose exactly as the query receives them, plus the
/// endpoint-form inputs they were built from (form != kDirect).
template <class S>
struct Placed {
  ShapeKind kind = ShapeKind::kCylinder;
  S radius{}, lz{};
  Pose<S> pose{};
  bool identity_pose = false;
  bool local_points = false;
  Form form = Form::kDirect;
  Vec3<S> O{}, N{};  ///< axis form: O, N; endpoints form: a, b
  S L{}, R{};        ///< L (axis form only), R
};

/// The query targets' layout: a flags byte, then the scalars.
///   flags & 3:        pose mode as in decode() (direct form only);
///   flags & 4:        the query's points (point, sphere centre, segment
///                     ends) are given in the shape's frame and mapped to
///                     the world by the pose in S arithmetic (toWorld);
///   flags & 8:        float (4-byte patterns), else double;
///   (flags >> 4) & 3: the form: 0 or 3 direct (radius, lz, then R and t
///                     as decode() reads them); 1 axis form: O, N, L, R
///                     (cylinderFromAxis, or coneFromApex for the cone);
///                     2 endpoints form: a, b, R (cylinderFromEndpoints;
///                     the cone reads the axis form instead);
///   flags & 0xc0:     free for the targets;
/// then the query's own scalars (decodePoint, decodeSphere, decodeSegment).
template <class S>
class QueryInput {
 public:
  QueryInput(const std::uint8_t* data, std::size_t size)
      : in_(data, size), dec_(&in_), flags_(in_.byte()) {}
  std::uint8_t flags() const { return flags_; }
  S scalar() { return dec_.next(); }
  Vec3<S> vec3() { return {dec_.next(), dec_.next(), dec_.next()}; }

  Placed<S> placed(ShapeKind kind) {
    Placed<S> p;
    p.kind = kind;
    p.local_points = flags_ & 4;
    int form = (flags_ >> 4) & 3;
    if (form == 3) form = 0;
    if (kind == ShapeKind::kCone && form == 2) form = 1;
    p.form = Form(form);
    switch (p.form) {
      case Form::kDirect:
        p.radius = scalar();
        p.lz = scalar();
        p.pose = readPose(&in_, &dec_, flags_, &p.identity_pose);
        // As decode(): an identity pose takes the points as given (R y + t
        // would turn an infinite coordinate into NaN through 0 * Inf).
        if (p.identity_pose) p.local_points = false;
        break;
      case Form::kAxis:
        p.O = vec3();
        p.N = vec3();
        p.L = scalar();
        p.R = scalar();
        if (kind == ShapeKind::kCone) {
          const PosedCone<S> pc = coneFromApex(p.O, p.N, p.L, p.R);
          p.radius = pc.cone.radius;
          p.lz = pc.cone.lz;
          p.pose = pc.pose;
        } else {
          const PosedCylinder<S> pc = cylinderFromAxis(p.O, p.N, p.L, p.R);
          p.radius = pc.cylinder.radius;
          p.lz = pc.cylinder.lz;
          p.pose = pc.pose;
        }
        break;
      case Form::kEndpoints: {
        p.O = vec3();
        p.N = vec3();
        p.R = scalar();
        const PosedCylinder<S> pc = cylinderFromEndpoints(p.O, p.N, p.R);
        p.radius = pc.cylinder.radius;
        p.lz = pc.cylinder.lz;
        p.pose = pc.pose;
        break;
      }
    }
    return p;
  }

  /// A point of the query, mapped to the world if the flags say so.
  Vec3<S> point(const Placed<S>& p) {
    const Vec3<S> v = vec3();
    return p.local_points ? toWorld(p.pose, v) : v;
  }

 private:
  ByteReader in_;
  ScalarDecoder<S> dec_;
  std::uint8_t flags_;
};

template <class S>
bool finite(const Vec3<S>& v) {
  return finite(v.x) && finite(v.y) && finite(v.z);
}

/// The documented validity rule of every query for the shape and pose:
/// sizes finite and >= 0 (-0 is zero, valid), R and t finite.
template <class S>
bool valid(const Placed<S>& p) {
  bool ok = finite(p.radius) && finite(p.lz) && !(p.radius < 0) &&
            !(p.lz < 0) && finite(p.pose.t);
  for (const auto& row : p.pose.R)
    for (S v : row) ok = ok && finite(v);
  return ok;
}

inline void printVec(const char* name, const Vec3<double>& v) {
  std::fprintf(stderr, "%s = %a %a %a\n", name, v.x, v.y, v.z);
}
template <class S>
void printVec(const char* name, const Vec3<S>& v) {
  printVec(name, Vec3<double>{double(v.x), double(v.y), double(v.z)});
}

/// Prints the shape and pose bit-exactly, with the endpoint-form inputs.
template <class S>
void print(const Placed<S>& p) {
  std::fprintf(stderr, "scalar = %s, shape = %s\n",
               sizeof(S) == 8 ? "double" : "float",
               p.kind == ShapeKind::kCone ? "cone" : "cylinder");
  if (p.form == Form::kAxis) {
    std::fprintf(
        stderr, "form = %s(O, N, L, R)\n",
        p.kind == ShapeKind::kCone ? "coneFromApex" : "cylinderFromAxis");
    printVec("O", p.O);
    printVec("N", p.N);
    printScalar("L", double(p.L));
    printScalar("R", double(p.R));
  } else if (p.form == Form::kEndpoints) {
    std::fprintf(stderr, "form = cylinderFromEndpoints(a, b, R)\n");
    printVec("a", p.O);
    printVec("b", p.N);
    printScalar("R", double(p.R));
  }
  printScalar("r ", double(p.radius));
  printScalar("lz", double(p.lz));
  for (int i = 0; i < 3; ++i)
    std::fprintf(stderr, "R[%d] = %a %a %a\n", i, double(p.pose.R[i][0]),
                 double(p.pose.R[i][1]), double(p.pose.R[i][2]));
  printVec("t", p.pose.t);
}

/// A point query (point in cylinder or cone).
template <class S>
struct PointCase {
  using Scalar = S;
  Placed<S> shape;
  Vec3<S> x{};
};

/// Layout: as QueryInput, then the point x.
template <class S>
PointCase<S> decodePoint(const std::uint8_t* data, std::size_t size,
                         ShapeKind kind) {
  QueryInput<S> in(data, size);
  PointCase<S> c;
  c.shape = in.placed(kind);
  c.x = in.point(c.shape);
  return c;
}

template <class S>
bool valid(const PointCase<S>& c) {
  return valid(c.shape) && finite(c.x);
}

template <class S>
void print(const PointCase<S>& c) {
  print(c.shape);
  printVec("x", c.x);
}

/// Sphere vs cylinder.
template <class S>
struct SphereCase {
  using Scalar = S;
  Placed<S> shape;
  Sphere<S> sphere{};
};

/// Layout: as QueryInput, then the centre, then the sphere's radius.
template <class S>
SphereCase<S> decodeSphere(const std::uint8_t* data, std::size_t size) {
  QueryInput<S> in(data, size);
  SphereCase<S> c;
  c.shape = in.placed(ShapeKind::kCylinder);
  c.sphere.center = in.point(c.shape);
  c.sphere.radius = in.scalar();
  return c;
}

template <class S>
bool valid(const SphereCase<S>& c) {
  return valid(c.shape) && finite(c.sphere.center) && finite(c.sphere.radius) &&
         !(c.sphere.radius < 0);
}

template <class S>
void print(const SphereCase<S>& c) {
  print(c.shape);
  printVec("center", c.sphere.center);
  printScalar("rho", double(c.sphere.radius));
}

/// Segment vs cylinder (and its interval).
template <class S>
struct SegmentCase {
  using Scalar = S;
  Placed<S> shape;
  Segment<S> seg{};
};

/// Layout: as QueryInput, then p, then q.
template <class S>
SegmentCase<S> decodeSegment(const std::uint8_t* data, std::size_t size) {
  QueryInput<S> in(data, size);
  SegmentCase<S> c;
  c.shape = in.placed(ShapeKind::kCylinder);
  c.seg.p = in.point(c.shape);
  c.seg.q = in.point(c.shape);
  return c;
}

template <class S>
bool valid(const SegmentCase<S>& c) {
  return valid(c.shape) && finite(c.seg.p) && finite(c.seg.q);
}

template <class S>
void print(const SegmentCase<S>& c) {
  print(c.shape);
  printVec("p", c.seg.p);
  printVec("q", c.seg.q);
}

}  // namespace tricyl::fuzz
