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
#pragma once

#include <cfloat>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

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

/// Layout: a flags byte, then the scalars.
///   flags & 3: 0 or 3 = R as 9 free scalars; 1 = a signed axis permutation
///              (one byte); 2 = the identity pose (R = I, t = 0; no t is
///              read, so the local-frame overload can be compared).
///   flags & 4: the triangle's vertices are given in the cylinder frame and
///              mapped to the world by the pose in S arithmetic (rounded),
///              which puts them near the cylinder under any rotation.
/// Order: radius, lz, R (if free), t (unless identity), a, b, c.
template <class S>
Case<S> decode(const std::uint8_t* data, std::size_t size) {
  ByteReader in(data, size);
  ScalarDecoder<S> dec(&in);
  Case<S> c;
  const std::uint8_t flags = in.byte();
  c.cyl.radius = dec.next();
  c.cyl.lz = dec.next();
  switch (flags & 3) {
    case 1:
      signedPermutation(in.byte(), c.pose.R);
      break;
    case 2:
      c.pose = identityPose<S>();
      c.identity_pose = true;
      break;
    default:
      for (auto& row : c.pose.R)
        for (S& v : row) v = dec.next();
  }
  if (!c.identity_pose) c.pose.t = {dec.next(), dec.next(), dec.next()};
  Vec3<S>* verts[3] = {&c.tri.a, &c.tri.b, &c.tri.c};
  for (Vec3<S>* v : verts) *v = {dec.next(), dec.next(), dec.next()};
  if ((flags & 4) && !c.identity_pose) {
    for (Vec3<S>* v : verts) {
      const S y[3] = {v->x, v->y, v->z};
      S w[3];
      for (int i = 0; i < 3; ++i) {
        w[i] = c.pose.R[i][0] * y[0];
        w[i] += c.pose.R[i][1] * y[1];
        w[i] += c.pose.R[i][2] * y[2];
      }
      *v = {w[0] + c.pose.t.x, w[1] + c.pose.t.y, w[2] + c.pose.t.z};
    }
  }
  return c;
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

}  // namespace tricyl::fuzz
