// SPDX-License-Identifier: BSD-3-Clause
// tricyl-answers-digest: the answers of a fixed set of queries, as one hash
// (issue 20: the same answers on every compiler and platform). Every query
// kind (triangle in double and in float, point in cylinder, point in cone,
// sphere, segment with its interval, line with its interval) over six
// families, the hard ones included: uniform, near (a feature within
// 10^-1 .. 10^-15 or 1..4 ulps of the surface), far (unit scenes at 10^6 ..
// 10^8 from the origin), thin (needles and thin cylinders), degenerate
// (slivers, collinear and repeated vertices, p == q, subnormal and
// axis-parallel directions) and aligned (exact poses and dyadic features
// exactly on rims, caps and sides: exact ties).
//
// The inputs are generated with integer arithmetic and correctly rounded
// +, -, *, /, sqrt only (no libm transcendental, no std:: distribution, no
// long double, no FMA: built with -ffp-contract=off), so they are the same
// bits on every platform. The digest covers the answers and the interval
// ends (their bits); the stage that decided each query is printed as a
// histogram, outside the digest: it is what may differ between platforms.
//
// Usage: tricyl-answers-digest [--cases N] [--dump FILE]
//   N: cases per kind and family (default 1250: 7 x 6 x 1250 = 52,500
//   queries). FILE: one line per query (kind, family, index, answer,
//   interval bits), to find the query behind a differing digest.
#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "scenes.h"  // Rng (xoshiro256**), randomPose, exactPose: libm-free
#include "tricyl/tricyl.h"

namespace {

using tricyl::Answer;
using tricyl::Cone;
using tricyl::Cylinder;
using tricyl::Decision;
using tricyl::Interval;
using tricyl::Line;
using tricyl::Pose;
using tricyl::Segment;
using tricyl::Sphere;
using tricyl::Stage;
using tricyl::Triangle;
using V = tricyl::Vec3<double>;
namespace scenes = tricyl::scenes;
using scenes::Rng;

V add(V a, V b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
V mul(V a, double s) { return {a.x * s, a.y * s, a.z * s}; }

enum Kind { kTriangle, kTriangleF, kPoint, kCone, kSphere, kSegment, kLine };
constexpr int kKinds = 7;
const char* const kKindNames[kKinds] = {
    "triangle", "triangle_f", "point", "cone", "sphere", "segment", "line"};
enum Fam { kUniform, kNear, kFar, kThin, kDegenerate, kAligned };
constexpr int kFams = 6;
const char* const kFamNames[kFams] = {"uniform", "near",       "far",
                                      "thin",    "degenerate", "aligned"};

/// A scene in the cylinder's local frame, then posed.
struct Scene {
  Cylinder<double> cyl{1, 2};
  Pose<double> pose = tricyl::identityPose<double>();
  V a{0, 0, 0}, b{0, 0, 0}, c{0, 0, 0};  // triangle; a: point, centre, p
  double rho = 0;                        // sphere radius
};

/// Relative offsets for near cases: +-k 2^-52 (k = 1..4) or +-10^-j
/// (j = 1..15; 10^j is exact in double, so the quotient is correctly
/// rounded).
double nearDelta(Rng& g) {
  double d;
  if (g.integer(4) == 0) {
    d = double(1 + g.integer(4)) * 0x1p-52;
  } else {
    double p = 1;
    for (int j = 1 + g.integer(15); j > 0; --j) p *= 10;
    d = 1 / p;
  }
  return g.coin() ? d : -d;
}

/// A point of the unit circle from a rational parameter (no sin/cos).
void circle(Rng& g, double* c, double* s) {
  const double t = g.uniform(-1, 1);
  const double n = 1 + t * t;
  *c = (1 - t * t) / n;
  *s = 2 * t / n;
  if (g.coin()) *c = -*c;
}

/// log-uniform-ish in [2^lo, 2^hi): a power of two times [1, 2).
double magnitude(Rng& g, int lo, int hi) {
  double m = 1 + g.uniform();
  int e = lo + g.integer(hi - lo);
  for (; e > 0; --e) m *= 2;
  for (; e < 0; ++e) m /= 2;
  return m;
}

/// A surface point of the cylinder (side, cap or rim), its outward normal
/// (not normalised on the rim) and a tangent direction.
void surfacePoint(Rng& g, const Cylinder<double>& cyl, double delta, V* p, V* n,
                  V* t) {
  const double r = cyl.radius, h = cyl.lz / 2;
  double c, s;
  circle(g, &c, &s);
  const int where = g.integer(3);
  const double zs = g.coin() ? 1 : -1;
  if (where == 0) {  // side
    const double z = g.uniform(-h, h);
    *p = {r * (1 + delta) * c, r * (1 + delta) * s, z};
    *n = {c, s, 0};
    *t = g.coin() ? V{-s, c, 0} : V{0, 0, 1};
  } else if (where == 1) {  // cap
    const double q = g.uniform(0, r);
    *p = {q * c, q * s, zs * h * (1 + delta)};
    *n = {0, 0, zs};
    *t = {-s, c, 0};
  } else {  // rim
    *p = {r * (1 + delta) * c, r * (1 + delta) * s, zs * h * (1 + delta)};
    *n = {c, s, zs};
    *t = {-s, c, 0};
  }
}

Scene uniformScene(Rng& g) {
  Scene k;
  k.cyl = {magnitude(g, -3, 1), magnitude(g, -3, 2)};
  const V ctr{g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)};
  const double size = magnitude(g, -4, 1);
  k.a = add(ctr, mul(scenes::internal::randomUnit(g), size));
  k.b = add(ctr, mul(scenes::internal::randomUnit(g), size));
  k.c = add(ctr, mul(scenes::internal::randomUnit(g), size));
  k.rho = magnitude(g, -4, 0);
  k.pose = scenes::internal::randomPose(g, 1);
  return k;
}

/// A feature within delta of the surface, the rest pointing outward, so
/// the scene touches (or misses by delta) at that feature only.
Scene nearScene(Rng& g, Kind kind) {
  Scene k;
  k.cyl = {magnitude(g, -2, 2), magnitude(g, -2, 3)};
  const double delta = nearDelta(g);
  V p, n, t;
  surfacePoint(g, k.cyl, delta, &p, &n, &t);
  const double size = magnitude(g, -3, 1);
  if (kind == kSphere) {
    k.rho = size;
    k.a = add(p, mul(n, size * (1 + delta)));
  } else if (kind == kSegment || kind == kLine) {
    // Tangent through the touching point (grazing), or ending at it.
    const double a = g.uniform(0, size), b = g.uniform(0, size);
    if (g.coin()) {
      k.a = add(p, mul(t, -a));
      k.b = add(p, mul(t, b));
    } else {
      k.a = p;
      k.b = add(p, mul(add(n, mul(t, g.uniform(-1, 1))), size));
    }
  } else {
    // (One draw per statement: the order in which a call's arguments are
    // evaluated is unspecified, and GCC and clang differ.)
    const double u = g.uniform(-size, size), v = g.uniform(0.1, 1),
                 w = g.uniform(-size, size);
    k.a = p;
    k.b = add(p, add(mul(n, size), mul(t, u)));
    k.c = add(p, add(mul(n, size * v), mul(t, w)));
  }
  if (kind == kCone) {  // the cone's side: r (h - z) / lz at height z
    const double h = k.cyl.lz / 2, z = g.uniform(-h, h);
    double c, s;
    circle(g, &c, &s);
    const double q = k.cyl.radius * (h - z) / k.cyl.lz * (1 + delta);
    k.a = {q * c, q * s, z};
  }
  k.pose = scenes::internal::randomPose(g, 10);
  return k;
}

/// Unit-size scenes far from the origin: the local frame cancels.
Scene farScene(Rng& g, Kind kind) {
  Scene k = g.coin() ? uniformScene(g) : nearScene(g, kind);
  const double far = magnitude(g, 20, 27);  // 10^6 .. 10^8
  k.pose.t = {k.pose.t.x + far, k.pose.t.y - far / 2, k.pose.t.z + far / 4};
  return k;
}

/// Needles and thin cylinders.
Scene thinScene(Rng& g, Kind kind) {
  Scene k = g.coin() ? uniformScene(g) : nearScene(g, kind);
  if (g.coin()) {
    k.cyl.radius = magnitude(g, -30, -10);  // a wire
    k.cyl.lz = magnitude(g, 0, 4);
  } else {  // a needle: a, b, c nearly collinear
    const V d = scenes::internal::randomUnit(g);
    const double len = magnitude(g, 0, 2), w = magnitude(g, -40, -15);
    k.b = add(k.a, mul(d, len));
    const double along = g.uniform();
    const V off = scenes::internal::randomUnit(g);
    k.c = add(add(k.a, mul(d, len * along)), mul(off, w));
  }
  return k;
}

/// Degenerate inputs: collinear and repeated vertices, p == q, subnormal
/// directions, directions parallel to the axis, zero sizes.
Scene degenerateScene(Rng& g) {
  Scene k = uniformScene(g);
  const double dmin = std::numeric_limits<double>::denorm_min();
  switch (g.integer(7)) {
    case 0:  // collinear (exactly: c = a + 2 (b - a) with dyadic values)
      k.a = {double(g.integer(9) - 4) / 4, double(g.integer(9) - 4) / 4,
             double(g.integer(9) - 4) / 4};
      k.b = add(k.a, V{0.25, -0.5, 0.125});
      k.c = add(k.a, V{0.5, -1, 0.25});
      break;
    case 1:  // a repeated vertex, or all three
      k.b = k.a;
      if (g.coin()) k.c = k.a;
      break;
    case 2:  // a subnormal direction through the interior or the side
      k.b = add(k.a, V{g.coin() ? dmin : 0, g.coin() ? dmin : 0, 0});
      break;
    case 3:  // parallel to the axis in the local frame, identity pose
      k.pose = tricyl::identityPose<double>();
      k.b = add(k.a, V{0, 0, g.uniform(-1, 1)});
      break;
    case 4:  // zero sizes
      if (g.coin())
        k.cyl.radius = 0;
      else
        k.cyl.lz = 0;
      break;
    case 5:  // a sliver: c within 2^-40 of the segment ab
      k.c = add(mul(add(k.a, k.b), 0.5), V{0x1p-40, -0x1p-41, 0x1p-42});
      break;
    default:  // a point on the side, the rest of the triangle outside
      k.pose = scenes::internal::exactPose(g);
      k.a = {k.cyl.radius, 0, 0};
      break;
  }
  return k;
}

/// Exact poses, dyadic sizes and features exactly on the boundary: ties.
Scene alignedScene(Rng& g) {
  Scene k;
  k.cyl = {double(1 + g.integer(8)) / 4, double(1 + g.integer(8)) / 2};
  k.pose = scenes::internal::exactPose(g);
  const double r = k.cyl.radius, h = k.cyl.lz / 2;
  auto dy = [&](double m) { return double(g.integer(17) - 8) / 8 * m; };
  const V rim{r, 0, g.coin() ? h : -h};
  const V side{0, g.coin() ? r : -r, dy(h)};
  const V cap{dy(r) / 2, dy(r) / 2, g.coin() ? h : -h};
  const V on[3] = {rim, side, cap};
  k.a = on[g.integer(3)];
  switch (g.integer(3)) {
    case 0:  // in the cap plane
      k.b = {k.a.x + dy(2), k.a.y + dy(2), k.a.z};
      k.c = {k.a.x + dy(2), k.a.y - dy(2), k.a.z};
      break;
    case 1:  // along the side
      k.b = {k.a.x, k.a.y, k.a.z + dy(1)};
      k.c = {k.a.x + dy(1), k.a.y, k.a.z};
      break;
    default:  // anywhere dyadic
      k.b = {dy(2), dy(2), dy(2)};
      k.c = {dy(2), dy(2), dy(2)};
      break;
  }
  k.rho = double(g.integer(5)) / 4;
  return k;
}

Scene generate(Kind kind, Fam fam, std::uint64_t index) {
  Rng g(0x7269636c64696765ULL ^ (std::uint64_t(kind) << 56) ^
        (std::uint64_t(fam) << 48) ^ index);
  switch (fam) {
    case kUniform:
      return uniformScene(g);
    case kNear:
      return nearScene(g, kind);
    case kFar:
      return farScene(g, kind);
    case kThin:
      return thinScene(g, kind);
    case kDegenerate:
      return degenerateScene(g);
    default:
      return alignedScene(g);
  }
}

V toWorld(const Pose<double>& p, V l) {
  return scenes::internal::toWorld(p, l);
}

/// FNV-1a, 64 bits, over explicitly little-endian bytes.
struct Hash {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void byte(unsigned char b) {
    h ^= b;
    h *= 0x100000001b3ULL;
  }
  void u64(std::uint64_t v) {
    for (int i = 0; i < 8; ++i) byte(static_cast<unsigned char>(v >> (8 * i)));
  }
  void f64(double v) {
    std::uint64_t b;
    std::memcpy(&b, &v, 8);
    u64(b);
  }
};

template <class S>
tricyl::Vec3<S> as(V v) {
  return {S(v.x), S(v.y), S(v.z)};
}
template <class S>
Pose<S> as(const Pose<double>& p) {
  Pose<S> q;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) q.R[i][j] = S(p.R[i][j]);
  q.t = as<S>(p.t);
  return q;
}

/// One query's result, as dumped and compared.
struct Rec {
  int answer;
  double lo, hi;  // the interval (segment, line), else 0
};

/// The interval ends of two platforms agree within the documented bound:
/// each is within 1.9e-15 max(1, |s*|) of the exact s* (absolutely for a
/// segment), so two of them within twice that.
bool endsAgree(double a, double b) {
  if (a == b) return true;  // infinities included
  const double m = std::max({1.0, std::fabs(a), std::fabs(b)});
  return std::fabs(a - b) <= 2 * 1.9e-15 * m;
}

}  // namespace

int main(int argc, char** argv) {
  long n = 1250;
  const char* dump_path = nullptr;
  const char* compare_path = nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--cases" && i + 1 < argc) {
      n = std::atol(argv[++i]);
    } else if (a == "--dump" && i + 1 < argc) {
      dump_path = argv[++i];
    } else if (a == "--compare" && i + 1 < argc) {
      compare_path = argv[++i];
    } else {
      std::fprintf(stderr,
                   "usage: %s [--cases N] [--dump FILE] [--compare FILE]\n",
                   argv[0]);
      return 2;
    }
  }
  std::FILE* dump = dump_path ? std::fopen(dump_path, "w") : nullptr;
  if (dump_path && !dump) {
    std::perror(dump_path);
    return 2;
  }
  Hash answers_hash, intervals_hash;
  long stages[kKinds][8] = {};
  long answers[kKinds][3] = {};
  std::vector<Rec> recs;
  recs.reserve(std::size_t(kKinds * kFams * n));
  std::printf("tricyl-answers-digest: %ld cases per kind and family\n", n);
  for (int kind = 0; kind < kKinds; ++kind) {
    for (int fam = 0; fam < kFams; ++fam)
      for (long i = 0; i < n; ++i) {
        const Scene k = generate(Kind(kind), Fam(fam), std::uint64_t(i));
        const V a = toWorld(k.pose, k.a), b = toWorld(k.pose, k.b),
                c = toWorld(k.pose, k.c);
        Decision d{Answer::kInvalidInput, Stage::kInvalid};
        Interval<double> iv{0, 0};
        bool has_iv = false;
        switch (Kind(kind)) {
          case kTriangle:
            d = tricyl::decideIntersect(k.cyl, k.pose,
                                        Triangle<double>{a, b, c});
            break;
          case kTriangleF: {
            const Cylinder<float> cf{float(k.cyl.radius), float(k.cyl.lz)};
            d = tricyl::decideIntersect(
                cf, as<float>(k.pose),
                Triangle<float>{as<float>(a), as<float>(b), as<float>(c)});
            break;
          }
          case kPoint:
            d = tricyl::decideContains(k.cyl, k.pose, a);
            break;
          case kCone:
            d = tricyl::decideContains(Cone<double>{k.cyl.radius, k.cyl.lz},
                                       k.pose, a);
            break;
          case kSphere:
            d = tricyl::decideIntersect(k.cyl, k.pose,
                                        Sphere<double>{a, k.rho});
            break;
          case kSegment:
          case kLine: {
            Answer ca;
            if (kind == kSegment) {
              d = tricyl::decideIntersect(k.cyl, k.pose, Segment<double>{a, b});
              ca = tricyl::tryClip(k.cyl, k.pose, Segment<double>{a, b}, &iv);
            } else {
              d = tricyl::decideIntersect(k.cyl, k.pose, Line<double>{a, b});
              ca = tricyl::tryClip(k.cyl, k.pose, Line<double>{a, b}, &iv);
            }
            has_iv = ca == Answer::kIntersect;
            if (ca != d.answer) {
              std::fprintf(stderr, "%s %s %ld: clip and Boolean differ\n",
                           kKindNames[kind], kFamNames[fam], i);
              return 1;
            }
            break;
          }
        }
        answers_hash.byte(static_cast<unsigned char>(d.answer));
        if (!has_iv) iv = {0, 0};
        if (has_iv) {
          intervals_hash.f64(iv.lo);
          intervals_hash.f64(iv.hi);
        }
        recs.push_back({int(d.answer), iv.lo, iv.hi});
        ++answers[kind][int(d.answer)];
        ++stages[kind][int(d.stage)];
        if (dump)
          std::fprintf(dump, "%s %s %ld %d %a %a\n", kKindNames[kind],
                       kFamNames[fam], i, int(d.answer), iv.lo, iv.hi);
      }
    std::printf(
        "%-10s intersect %5ld disjoint %5ld invalid %3ld | stages:"
        " early %4ld fast %4ld running %4ld double-word %4ld exact %4ld"
        " GMP %4ld\n",
        kKindNames[kind], answers[kind][1], answers[kind][0], answers[kind][2],
        stages[kind][int(Stage::kEarlyOut)],
        stages[kind][int(Stage::kFastPath)], stages[kind][int(Stage::kRunning)],
        stages[kind][int(Stage::kExtended)], stages[kind][int(Stage::kExact)],
        stages[kind][int(Stage::kExactGmp)]);
  }
  if (dump) std::fclose(dump);
  // The digests: the answers (every query, every kind) and the interval
  // ends' bits, each one value on every platform (see the header comment of
  // tests/answers_digest_check.sh).
  std::printf("queries %zu\n", recs.size());
  std::printf("answers %016llx\n",
              static_cast<unsigned long long>(answers_hash.h));
  std::printf("intervals %016llx\n",
              static_cast<unsigned long long>(intervals_hash.h));
  if (!compare_path) return 0;

  // Against another platform's dump: the same answers, bit for bit, and
  // interval ends within the documented bound of each other.
  std::FILE* ref = std::fopen(compare_path, "r");
  if (!ref) {
    std::perror(compare_path);
    return 2;
  }
  long answer_diffs = 0, end_diffs = 0, beyond = 0, read = 0;
  double worst = 0;
  char kname[32], fname[32], lo_s[64], hi_s[64];
  long idx;
  int ans;
  while (std::fscanf(ref, "%31s %31s %ld %d %63s %63s", kname, fname, &idx,
                     &ans, lo_s, hi_s) == 6) {
    if (std::size_t(read) >= recs.size()) break;
    const Rec& r = recs[std::size_t(read++)];
    const double lo = std::strtod(lo_s, nullptr),
                 hi = std::strtod(hi_s, nullptr);
    if (ans != r.answer) {
      if (++answer_diffs <= 10)
        std::fprintf(stderr, "ANSWER differs: %s %s %ld: %d here, %d there\n",
                     kname, fname, idx, r.answer, ans);
      continue;
    }
    for (const auto& [x, y] : {std::pair{r.lo, lo}, std::pair{r.hi, hi}}) {
      if (x == y) continue;
      ++end_diffs;
      const double m = std::max({1.0, std::fabs(x), std::fabs(y)});
      if (std::isfinite(x) && std::isfinite(y))
        worst = std::max(worst, std::fabs(x - y) / m);
      if (!endsAgree(x, y) && ++beyond <= 10)
        std::fprintf(stderr, "END beyond the bound: %s %s %ld: %a vs %a\n",
                     kname, fname, idx, x, y);
    }
  }
  std::fclose(ref);
  std::printf(
      "compared with %s: %ld queries, answers differing %ld, "
      "interval ends differing %ld (largest difference %.3g relative;"
      " beyond 2 x 1.9e-15: %ld)\n",
      compare_path, read, answer_diffs, end_diffs, worst, beyond);
  if (std::size_t(read) != recs.size()) {
    std::fprintf(stderr, "the dump has %ld queries, this run %zu\n", read,
                 recs.size());
    return 1;
  }
  return answer_diffs == 0 && beyond == 0 ? 0 : 1;
}
