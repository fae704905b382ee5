// SPDX-License-Identifier: BSD-3-Clause
// Batch triangle-cylinder test (mesh_cylinder.h): a vectorised vertex pass,
// a triangle pass over outcodes, and the scalar exact kernel for the rest.
// The bounds are derived next to the code that relies on them; docs/batch.md
// has the overview and the measured figures.
#include "tricyl/mesh_cylinder.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <string>
#include <type_traits>

#include "filter.h"
#include "tricyl/triangle_cylinder.h"

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TRICYL_AVX2_DISPATCH 1
#define TRICYL_TARGET_AVX2 __attribute__((target("avx2")))
#include <immintrin.h>
#define TRICYL_ALWAYS_INLINE __attribute__((always_inline)) inline
#else
#define TRICYL_AVX2_DISPATCH 0
#define TRICYL_ALWAYS_INLINE inline
#endif

namespace tricyl {
namespace {

using detail::FilterKernel;

/// Per-batch constants, all in double (float inputs widen exactly).
struct Setup {
  bool valid = false;     // cylinder and pose pass the kernel's validation
  bool local_ok = false;  // ... and its range gate: local outcodes usable
  bool box_ok = false;    // the certified world box exists
  double R[3][3] = {};
  double t[3] = {};
  double rho = 0;  // max |R_ij|, the filter's magnitude factor
  double H = 0;    // lz: the slab in doubled coordinates is |Z| <= H
  double r = 0;
  double E[3] = {};  // world box half extents, margins included
};

template <class S>
Setup makeSetup(const Cylinder<S>& cyl, const Pose<S>& pose, bool want_box) {
  Setup s;
  bool finite = true;  // std::isfinite raises no FP exception, even on NaN
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      s.R[i][j] = double(pose.R[i][j]);
      finite = finite && std::isfinite(s.R[i][j]);
    }
  s.t[0] = double(pose.t.x);
  s.t[1] = double(pose.t.y);
  s.t[2] = double(pose.t.z);
  s.r = double(cyl.radius);
  s.H = double(cyl.lz);
  for (double v : {s.t[0], s.t[1], s.t[2], s.r, s.H})
    finite = finite && std::isfinite(v);
  // Same rule as the kernel's validate(): -0 is a valid size. Nothing is
  // compared before finiteness is known (a NaN comparison raises FE_INVALID).
  s.valid = finite && s.r >= 0 && s.H >= 0;
  if (!s.valid) return s;
  double max_len = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) s.rho = std::max(s.rho, std::fabs(s.R[i][j]));
  for (double v : {s.t[0], s.t[1], s.t[2], s.r, s.H})
    max_len = std::max(max_len, std::fabs(v));
  s.local_ok = detail::rangeGateOk(max_len, s.rho);
  if (want_box) {
    // World box. The cylinder is {x : R^T (x - t) in C}. With
    // E = R^T R - I and |E|_2 <= eps < 1, R is invertible and
    //   x - t = R^-T y = R (I + E)^-1 y = R y + R F y,
    //   F = (I + E)^-1 - I,  |F|_2 <= eps / (1 - eps) <= 2 eps (eps <= 1/2).
    // For y in C (|y_xy| <= r, |y_2| <= h = lz/2, |y|_2 <= r + h):
    //   |(R y)_i|   <= r (|R_i0| + |R_i1|) + h |R_i2|,
    //   |(R F y)_i| <= |R_i|_2 |F|_2 |y|_2 <= |R_i|_1 2 eps (r + h).
    // eps: |E|_2 <= |E|_F <= sum_jk |E_jk|. Each E_jk is computed with three
    // products, two sums and one difference: its rounding error is at most
    // gamma_4 (S_jk + delta_jk) < 2^-50 (S_jk + 1), S_jk = sum_i |R_ij R_ik|
    // (a product's underflow, <= 2^-1074, is far inside the "+1").
    double eps = 0;
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        double e = 0, m = 0;
        for (int i = 0; i < 3; ++i) {
          e += s.R[i][j] * s.R[i][k];
          m += std::fabs(s.R[i][j] * s.R[i][k]);
        }
        e -= j == k ? 1.0 : 0.0;
        eps += std::fabs(e) + 0x1p-50 * (m + 1);
      }
    // Every sum above and below is of non-negative terms, computed with at
    // most ~12 roundings to nearest: a factor (1 + 2^-40) covers
    // (1 - 2^-53)^-12 many times over. The absolute 2^-1060 covers the
    // underflow of r |R_i0| and friends (each loses <= 2^-1074) and of
    // h = lz / 2.
    eps *= 1 + 0x1p-40;
    if (eps <= 0.5) {
      const double h = s.H * 0.5;
      s.box_ok = true;
      for (int i = 0; i < 3; ++i) {
        const double a0 = std::fabs(s.R[i][0]), a1 = std::fabs(s.R[i][1]),
                     a2 = std::fabs(s.R[i][2]);
        const double e =
            s.r * (a0 + a1) + h * a2 + (a0 + a1 + a2) * (2 * eps) * (s.r + h);
        s.E[i] = e * (1 + 0x1p-40) + 0x1p-1060;
        // Overflow leaves no usable box (the local pass still runs).
        s.box_ok = s.box_ok && s.E[i] <= DBL_MAX;
      }
    }
  }
  return s;
}

// ------------------------------------------------------------ vertex pass ---
// Code bits. World box (cull on): bit 2k is "x_k - t_k > E_k", bit 2k+1 is
// "t_k - x_k > E_k". Local (cull off): bit 0 Z > H, 1 Z < -H, 2 x > r,
// 3 x < -r, 4 y > r, 5 y < -r, each certified.

/// A coordinate as a double, and whether it is finite, decided on its bits:
/// a NaN or infinite value becomes 0 before any arithmetic touches it, so
/// the pass raises no FP exception on any input (a NaN in an ordered
/// comparison would raise FE_INVALID) and stays branch-free (an integer
/// select). `ok` is 1 or 0.
template <class S>
TRICYL_ALWAYS_INLINE double sanitized(S v, unsigned& ok) {
  static_assert(sizeof(S) == 4 || sizeof(S) == 8, "float or double");
  using Bits = std::conditional_t<sizeof(S) == 8, std::uint64_t, std::uint32_t>;
  constexpr Bits kExp =
      sizeof(S) == 8 ? Bits(0x7ff0000000000000ULL) : Bits(0x7f800000U);
  constexpr Bits kAbsMask =
      sizeof(S) == 8 ? Bits(0x7fffffffffffffffULL) : Bits(0x7fffffffU);
  Bits b;
  std::memcpy(&b, &v, sizeof b);
  const Bits fin = Bits((b & kAbsMask) < kExp);
  ok &= unsigned(fin);
  b &= Bits(0) - fin;  // all ones if finite, else 0 (+0.0)
  std::memcpy(&v, &b, sizeof b);
  return double(v);
}

/// World code of one vertex. fl(d) = (x - t)(1 + delta), |delta| <= u, and
/// a subnormal difference is exact, so fl(d) > E implies x - t > E / (1 + u)
/// >= the true half extent (E carries a relative margin of 2^-40). A vertex
/// with a NaN or infinite coordinate gets code 0 (never rejected: the
/// kernel reports it; `fin` is 0 for it). An overflowing difference is +-Inf
/// with the sign of the true value, which does exceed E.
TRICYL_ALWAYS_INLINE std::uint8_t worldCode(double px, double py, double pz,
                                            unsigned fin, const double (&t)[3],
                                            const double (&E)[3]) {
  const double d0 = px - t[0], d1 = py - t[1], d2 = pz - t[2];
  const unsigned c = unsigned(d0 > E[0]) | unsigned(-d0 > E[0]) << 1 |
                     unsigned(d1 > E[1]) << 2 | unsigned(-d1 > E[1]) << 3 |
                     unsigned(d2 > E[2]) << 4 | unsigned(-d2 > E[2]) << 5;
  return static_cast<std::uint8_t>(c & (0u - fin));
}

/// Local code of one vertex: the scalar kernel's early-out signs
/// (triangle_cylinder_impl.h, cases 0a/0b and the bounding square) with the
/// same values and the same FilterKernel bound: a value v with magnitude m
/// has a certified positive sign iff v > m 2^-47 + 2^-600 (filter.h). The
/// magnitudes are those the kernel's Fd arithmetic carries:
///   x, y: m = rho (|d0| + |d1| + |d2|);  Z = 2z: 2m;  lifted r, H: r, H;
///   Z - H, Z + H: 2m + H;  x - r, -x - r, y - r, -y - r: m + r.
/// The bound holds under the range gate, which the vertex must pass too
/// (finite, |coordinate| <= 2^40): otherwise code 0, and the vertex is
/// replaced by 0 first, so that nothing overflows (an overflowed difference
/// times a zero rotation entry would make a NaN and raise FE_INVALID).
TRICYL_ALWAYS_INLINE std::uint8_t localCode(double px, double py, double pz,
                                            unsigned fin, const Setup& s) {
  constexpr double kRel = FilterKernel::kRel, kAbs = FilterKernel::kAbs;
  // Bitwise, not &&: no branch in the loop, so that it vectorises.
  const unsigned gate = fin & unsigned(std::fabs(px) <= 0x1p40) &
                        unsigned(std::fabs(py) <= 0x1p40) &
                        unsigned(std::fabs(pz) <= 0x1p40);
  px = gate ? px : 0.0;
  py = gate ? py : 0.0;
  pz = gate ? pz : 0.0;
  const double d0 = px - s.t[0], d1 = py - s.t[1], d2 = pz - s.t[2];
  const double m = s.rho * (std::fabs(d0) + std::fabs(d1) + std::fabs(d2));
  const double x = s.R[0][0] * d0 + s.R[1][0] * d1 + s.R[2][0] * d2;
  const double y = s.R[0][1] * d0 + s.R[1][1] * d1 + s.R[2][1] * d2;
  const double z = s.R[0][2] * d0 + s.R[1][2] * d1 + s.R[2][2] * d2;
  const double Z = z + z;
  const double bz = ((m + m) + s.H) * kRel + kAbs;
  const double bxy = (m + s.r) * kRel + kAbs;
  const unsigned c =
      unsigned(Z - s.H > bz) | unsigned(Z + s.H < -bz) << 1 |
      unsigned(x - s.r > bxy) << 2 | unsigned(-x - s.r > bxy) << 3 |
      unsigned(y - s.r > bxy) << 4 | unsigned(-y - s.r > bxy) << 5;
  return static_cast<std::uint8_t>(c & (0u - gate));
}

/// Codes of n vertices whose coordinates are x[i k], y[i k], z[i k]
/// (k = kStride: 3 for interleaved xyz, 1 for separate arrays). Written
/// without branches or cross-iteration state so that the compiler
/// vectorises it; the Setup is copied to a local so that the stores through
/// `out` (a char type, which may alias anything) cannot be assumed to
/// change it.
template <class S, int kStride, bool kWorld>
TRICYL_ALWAYS_INLINE void codesBody(const Setup& setup, const S* x, const S* y,
                                    const S* z, std::size_t n,
                                    std::uint8_t* __restrict out) {
  const Setup s = setup;
  for (std::size_t i = 0; i < n; ++i) {
    unsigned fin = 1;
    const double px = sanitized(x[i * kStride], fin);
    const double py = sanitized(y[i * kStride], fin);
    const double pz = sanitized(z[i * kStride], fin);
    if constexpr (kWorld)
      out[i] = worldCode(px, py, pz, fin, s.t, s.E);
    else
      out[i] = localCode(px, py, pz, fin, s);
  }
}

template <class S, int kStride, bool kWorld>
void codesPortable(const Setup& s, const S* x, const S* y, const S* z,
                   std::size_t n, std::uint8_t* out) {
  codesBody<S, kStride, kWorld>(s, x, y, z, n, out);
}

#if TRICYL_AVX2_DISPATCH
// The same body compiled for AVX2. No FMA target: every operation rounds as
// in the portable build (tricyl also builds with -ffp-contract=off), so the
// codes, and hence everything downstream, are bit-identical.
template <class S, int kStride, bool kWorld>
TRICYL_TARGET_AVX2 void codesAvx2(const Setup& s, const S* x, const S* y,
                                  const S* z, std::size_t n,
                                  std::uint8_t* out) {
  codesBody<S, kStride, kWorld>(s, x, y, z, n, out);
}
#endif

#if TRICYL_AVX2_DISPATCH
// One axis of localCode for four lanes, in one comparison: fl(|v| - c) is
// fl(v - c) for v >= +0 and fl(-v - c) for v <= -0 (rounding is symmetric),
// and the sign bit of v picks which of the axis' two code bits (lo: v - c >
// b, hi: -v - c > b) it sets; blendv reads the sign bit directly.
// localCode's two tests per axis never both hold (c >= 0, b > 0), and for
// v = +-0 neither does, so the bits are its bits exactly.
TRICYL_TARGET_AVX2 TRICYL_ALWAYS_INLINE __m256i axisBits(__m256d v, __m256d c,
                                                         __m256d b, __m256i lo,
                                                         __m256i hi,
                                                         __m256d abs) {
  const __m256d beyond =
      _mm256_cmp_pd(_mm256_sub_pd(_mm256_and_pd(v, abs), c), b, _CMP_GT_OQ);
  const __m256d bit =
      _mm256_blendv_pd(_mm256_castsi256_pd(lo), _mm256_castsi256_pd(hi), v);
  return _mm256_castpd_si256(_mm256_and_pd(beyond, bit));
}

// localCode for four interleaved double vertices at once (the indexed-mesh
// layout), written out by hand: the compiler's vectorisation of codesBody for
// stride 3 took about 12 cycles a vertex (two thirds of the cull-off batch
// on bench_mesh_cylinder's grid), this about a third of that. Every lane
// computes localCode's values with its operations in its order (no FMA),
// and the six plane tests as three (axisBits: the same bits), so the codes
// are those of the portable pass bit for bit; the tail (< 4 vertices) runs
// localCode. (Three tests instead of six: 2.84 -> 2.41 ns per triangle on
// the 65k grid, cull off, four alternating runs; FCL's MPR takes 178 ns per
// triangle on that grid in the same recording, 74x.)
// The gate is applied to the bits before any arithmetic: |v| <= 2^40 (as an
// integer compare of the sign-cleared bits, which also rejects NaN and Inf),
// else all three coordinates become +0 and the code 0, as in localCode.
TRICYL_TARGET_AVX2 void codesLocalAvx2Interleaved(const Setup& s,
                                                  const double* v,
                                                  std::size_t n,
                                                  std::uint8_t* out) {
  constexpr double kRel = FilterKernel::kRel, kAbs = FilterKernel::kAbs;
  const __m256i abs_bits = _mm256_set1_epi64x(0x7fffffffffffffffLL);
  const __m256i lim = _mm256_set1_epi64x(0x4270000000000000LL);  // 2^40
  const __m256d abs = _mm256_castsi256_pd(abs_bits);
  const __m256d t0 = _mm256_set1_pd(s.t[0]), t1 = _mm256_set1_pd(s.t[1]),
                t2 = _mm256_set1_pd(s.t[2]);
  const __m256d R00 = _mm256_set1_pd(s.R[0][0]),
                R10 = _mm256_set1_pd(s.R[1][0]),
                R20 = _mm256_set1_pd(s.R[2][0]),
                R01 = _mm256_set1_pd(s.R[0][1]),
                R11 = _mm256_set1_pd(s.R[1][1]),
                R21 = _mm256_set1_pd(s.R[2][1]),
                R02 = _mm256_set1_pd(s.R[0][2]),
                R12 = _mm256_set1_pd(s.R[1][2]),
                R22 = _mm256_set1_pd(s.R[2][2]);
  const __m256d rho = _mm256_set1_pd(s.rho), H = _mm256_set1_pd(s.H),
                r = _mm256_set1_pd(s.r), kr = _mm256_set1_pd(kRel),
                ka = _mm256_set1_pd(kAbs);
  const __m256i bit[6] = {_mm256_set1_epi64x(1),  _mm256_set1_epi64x(2),
                          _mm256_set1_epi64x(4),  _mm256_set1_epi64x(8),
                          _mm256_set1_epi64x(16), _mm256_set1_epi64x(32)};
  const __m256i pick = _mm256_setr_epi32(0, 2, 4, 6, 0, 2, 4, 6);
  std::size_t i = 0;
  for (; i + 4 <= n; i += 4) {
    const double* p = v + 3 * i;
    const __m256d a = _mm256_loadu_pd(p);      // x0 y0 z0 x1
    const __m256d b = _mm256_loadu_pd(p + 4);  // y1 z1 x2 y2
    const __m256d c = _mm256_loadu_pd(p + 8);  // z2 x3 y3 z3
    __m256d px = _mm256_permute4x64_pd(
        _mm256_blend_pd(_mm256_blend_pd(a, b, 0x4), c, 0x2), 0x6c);
    __m256d py = _mm256_permute4x64_pd(
        _mm256_blend_pd(_mm256_blend_pd(a, b, 0x9), c, 0x4), 0xb1);
    __m256d pz = _mm256_permute4x64_pd(
        _mm256_blend_pd(_mm256_blend_pd(a, b, 0x2), c, 0x9), 0xc6);
    const __m256i bad = _mm256_or_si256(
        _mm256_or_si256(
            _mm256_cmpgt_epi64(
                _mm256_and_si256(_mm256_castpd_si256(px), abs_bits), lim),
            _mm256_cmpgt_epi64(
                _mm256_and_si256(_mm256_castpd_si256(py), abs_bits), lim)),
        _mm256_cmpgt_epi64(_mm256_and_si256(_mm256_castpd_si256(pz), abs_bits),
                           lim));
    const __m256d badd = _mm256_castsi256_pd(bad);
    px = _mm256_andnot_pd(badd, px);
    py = _mm256_andnot_pd(badd, py);
    pz = _mm256_andnot_pd(badd, pz);
    const __m256d d0 = _mm256_sub_pd(px, t0), d1 = _mm256_sub_pd(py, t1),
                  d2 = _mm256_sub_pd(pz, t2);
    const __m256d m = _mm256_mul_pd(
        rho, _mm256_add_pd(
                 _mm256_add_pd(_mm256_and_pd(d0, abs), _mm256_and_pd(d1, abs)),
                 _mm256_and_pd(d2, abs)));
    const __m256d x = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(R00, d0), _mm256_mul_pd(R10, d1)),
        _mm256_mul_pd(R20, d2));
    const __m256d y = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(R01, d0), _mm256_mul_pd(R11, d1)),
        _mm256_mul_pd(R21, d2));
    const __m256d z = _mm256_add_pd(
        _mm256_add_pd(_mm256_mul_pd(R02, d0), _mm256_mul_pd(R12, d1)),
        _mm256_mul_pd(R22, d2));
    const __m256d Z = _mm256_add_pd(z, z);
    const __m256d bz = _mm256_add_pd(
        _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(m, m), H), kr), ka);
    const __m256d bxy =
        _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(m, r), kr), ka);
    __m256i code = _mm256_or_si256(
        _mm256_or_si256(axisBits(Z, H, bz, bit[0], bit[1], abs),
                        axisBits(x, r, bxy, bit[2], bit[3], abs)),
        axisBits(y, r, bxy, bit[4], bit[5], abs));
    code = _mm256_andnot_si256(bad, code);
    // One byte per 64-bit lane (each < 64): the low dwords, then pack.
    const __m128i lo =
        _mm256_castsi256_si128(_mm256_permutevar8x32_epi32(code, pick));
    const __m128i packed = _mm_packus_epi16(_mm_packus_epi32(lo, lo), lo);
    const int four = _mm_cvtsi128_si32(packed);
    std::memcpy(out + i, &four, 4);
  }
  for (; i < n; ++i) {
    unsigned fin = 1;
    const double px = sanitized(v[3 * i], fin);
    const double py = sanitized(v[3 * i + 1], fin);
    const double pz = sanitized(v[3 * i + 2], fin);
    out[i] = localCode(px, py, pz, fin, s);
  }
}
#endif

Isa resolveIsa(Isa requested) {
  if (requested == Isa::kPortable) return Isa::kPortable;
  return detectedIsa();  // kAuto and kAvx2 alike: AVX2 only if present
}

template <class S, int kStride>
void vertexCodes(const Setup& s, bool world, Isa isa, const S* x, const S* y,
                 const S* z, std::size_t n, std::uint8_t* out) {
#if TRICYL_AVX2_DISPATCH
  if (isa == Isa::kAvx2) {
    if constexpr (std::is_same_v<S, double> && kStride == 3) {
      if (!world) {
        codesLocalAvx2Interleaved(s, x, n, out);
        return;
      }
    }
    if (world)
      codesAvx2<S, kStride, true>(s, x, y, z, n, out);
    else
      codesAvx2<S, kStride, false>(s, x, y, z, n, out);
    return;
  }
#else
  (void)isa;
#endif
  if (world)
    codesPortable<S, kStride, true>(s, x, y, z, n, out);
  else
    codesPortable<S, kStride, false>(s, x, y, z, n, out);
}

// ---------------------------------------------------------- triangle pass ---

enum class Verdict : unsigned char { kMiss, kHit, kInvalid };

/// A triangle the outcodes could not reject: the scalar kernel decides.
template <class S>
Verdict kernelVerdict(const Cylinder<S>& cyl, const Pose<S>& pose,
                      const Triangle<S>& tri) {
  switch (tryIntersect(cyl, pose, tri)) {
    case Answer::kIntersect:
      return Verdict::kHit;
    case Answer::kDisjoint:
      return Verdict::kMiss;
    default:
      return Verdict::kInvalid;
  }
}

/// Triangles are taken in blocks: a branch-free pass over the block's codes
/// writes the indices of the survivors (triangles the codes cannot reject,
/// and triangles with a bad index) into a buffer, then only the survivors
/// are visited, in index order. The counters live in locals (a store
/// through BatchStats* could alias the caller's mask words, which are also
/// unsigned long) and are written once at the end.
constexpr std::size_t kBlock = 1024;

struct Counters {
  std::size_t triangles = 0, rejected = 0, kernel = 0, hits = 0;
  void store(BatchStats* st, bool world) const {
    st->triangles = triangles;
    (world ? st->culled : st->early_out) = rejected;
    st->kernel = kernel;
    st->hits = hits;
  }
};

/// Decides one block's survivors in index order with the scalar kernel.
/// triangleAt(i, &tri) fills triangle i and returns false when it cannot
/// (an index out of range: reported as invalid, never read). Calls visit for
/// every hit or invalid triangle; returns false when visit asks to stop.
template <class S, class TriangleAt, class Visit>
bool decideSurvivors(const Cylinder<S>& cyl, const Pose<S>& pose,
                     std::size_t base, const std::uint32_t* survivors,
                     std::size_t m, TriangleAt&& triangleAt, Counters* n,
                     Visit& visit) {
  for (std::size_t j = 0; j < m; ++j) {
    const std::size_t i = base + survivors[j];
    Triangle<S> tri;
    Verdict verdict = Verdict::kInvalid;
    if (triangleAt(i, &tri)) {
      ++n->kernel;
      verdict = kernelVerdict(cyl, pose, tri);
    }
    if (verdict == Verdict::kMiss) continue;
    n->hits += verdict == Verdict::kHit;
    if (!visit(i, verdict)) return false;
  }
  return true;
}

/// Scans the triangles of `mesh` in index order and calls visit(i, verdict)
/// for every hit or invalid triangle (never for a miss) until it returns
/// false. Requires s.valid.
template <class S, class Visit>
void scanMesh(const Setup& s, const Cylinder<S>& cyl, const Pose<S>& pose,
              const MeshView<S>& mesh, const BatchOptions& opt, BatchStats* st,
              Visit&& visit) {
  const bool world = opt.cull && s.box_ok;
  const std::size_t nv = mesh.num_vertices;
  // (nv == 0: no pointer arithmetic on a possibly null `vertices`.)
  const bool use_codes = (world || s.local_ok) && nv > 0;
  st->cull_used = world;
  st->isa = resolveIsa(opt.isa);
  // Codes: on the stack for small meshes, else one allocation per call.
  constexpr std::size_t kStack = 2048;
  std::uint8_t stack_codes[kStack];
  std::vector<std::uint8_t> heap_codes;
  std::uint8_t* codes = stack_codes;
  if (use_codes && nv > kStack) {
    heap_codes.resize(nv);
    codes = heap_codes.data();
  }
  if (use_codes)
    vertexCodes<S, 3>(s, world, st->isa, mesh.vertices, mesh.vertices + 1,
                      mesh.vertices + 2, nv, codes);
  const S* v = mesh.vertices;
  const std::uint32_t* idx = mesh.indices;
  Counters n;
  std::uint32_t survivors[kBlock];
  for (std::size_t base = 0; base < mesh.num_triangles; base += kBlock) {
    const std::size_t len = std::min(kBlock, mesh.num_triangles - base);
    n.triangles += len;
    std::size_t m = 0;
    const std::uint32_t* fb = idx + 3 * base;
    if (use_codes) {
      for (std::size_t k = 0; k < len; ++k) {
        const std::uint32_t* f = fb + 3 * k;
        const std::uint32_t f0 = f[0], f1 = f[1], f2 = f[2];
        // f0 | f1 | f2 >= max(f0, f1, f2): below nv, all three are in
        // range (one compare for the common case). Otherwise check each; a
        // bad index survives, to be reported below, and is never read.
        if ((f0 | f1 | f2) >= nv && (f0 >= nv || f1 >= nv || f2 >= nv)) {
          survivors[m++] = std::uint32_t(k);
          continue;
        }
        if ((codes[f0] & codes[f1] & codes[f2]) == 0)
          survivors[m++] = std::uint32_t(k);
      }
    } else {
      for (std::size_t k = 0; k < len; ++k) survivors[k] = std::uint32_t(k);
      m = len;
    }
    n.rejected += len - m;
    auto at = [&](std::size_t i, Triangle<S>* tri) {
      const std::uint32_t* f = idx + 3 * i;
      if (f[0] >= nv || f[1] >= nv || f[2] >= nv) return false;
      auto vertex = [v](std::uint32_t k) {
        return Vec3<S>{v[3 * std::size_t(k)], v[3 * std::size_t(k) + 1],
                       v[3 * std::size_t(k) + 2]};
      };
      *tri = {vertex(f[0]), vertex(f[1]), vertex(f[2])};
      return true;
    };
    if (!decideSurvivors<S>(cyl, pose, base, survivors, m, at, &n, visit))
      break;
  }
  n.store(st, world);
}

/// The same over a structure of arrays: codes per block, on the stack (the
/// "any" form stops within the block of its first hit).
template <class S, class Visit>
void scanArrays(const Setup& s, const Cylinder<S>& cyl, const Pose<S>& pose,
                const TriangleArrays<S>& tris, const BatchOptions& opt,
                BatchStats* st, Visit&& visit) {
  const bool world = opt.cull && s.box_ok;
  const bool use_codes = world || s.local_ok;
  st->cull_used = world;
  st->isa = resolveIsa(opt.isa);
  std::uint8_t ca[kBlock], cb[kBlock], cc[kBlock];
  std::uint32_t survivors[kBlock];
  Counters n;
  for (std::size_t base = 0; base < tris.num_triangles; base += kBlock) {
    const std::size_t len = std::min(kBlock, tris.num_triangles - base);
    n.triangles += len;
    std::size_t m = 0;
    if (use_codes) {
      vertexCodes<S, 1>(s, world, st->isa, tris.ax + base, tris.ay + base,
                        tris.az + base, len, ca);
      vertexCodes<S, 1>(s, world, st->isa, tris.bx + base, tris.by + base,
                        tris.bz + base, len, cb);
      vertexCodes<S, 1>(s, world, st->isa, tris.cx + base, tris.cy + base,
                        tris.cz + base, len, cc);
      for (std::size_t k = 0; k < len; ++k) {
        survivors[m] = std::uint32_t(k);
        m += std::size_t((ca[k] & cb[k] & cc[k]) == 0);
      }
    } else {
      for (std::size_t k = 0; k < len; ++k) survivors[k] = std::uint32_t(k);
      m = len;
    }
    n.rejected += len - m;
    auto at = [&tris](std::size_t i, Triangle<S>* tri) {
      *tri = {{tris.ax[i], tris.ay[i], tris.az[i]},
              {tris.bx[i], tris.by[i], tris.bz[i]},
              {tris.cx[i], tris.cy[i], tris.cz[i]}};
      return true;
    };
    if (!decideSurvivors<S>(cyl, pose, base, survivors, m, at, &n, visit))
      break;
  }
  n.store(st, world);
}

[[noreturn]] void throwInvalid(const char* what) {
  throw InvalidInput(std::string("tricyl::") + what +
                     ": NaN or infinite input, a negative radius or length, "
                     "or a vertex index out of range");
}

std::size_t maskWords(std::size_t n) { return (n + 63) / 64; }

void setBit(std::uint64_t* mask, std::size_t i) {
  mask[i / 64] |= std::uint64_t(1) << (i % 64);
}

/// Mask scan over either source; returns the answer, *hits the set bits.
template <class S, class Source, class Scan>
Answer maskImpl(const Cylinder<S>& cyl, const Pose<S>& pose, const Source& src,
                std::size_t n, std::uint64_t* mask, std::size_t* hits,
                const BatchOptions& opt, BatchStats* stats, Scan scan) {
  BatchStats local;
  BatchStats* st = stats != nullptr ? stats : &local;
  *st = BatchStats{};
  std::fill(mask, mask + maskWords(n), std::uint64_t(0));
  const Setup s = makeSetup(cyl, pose, opt.cull);
  std::size_t count = 0;
  if (!s.valid) {
    for (std::size_t i = 0; i < n; ++i) setBit(mask, i);
    if (hits != nullptr) *hits = n;
    return Answer::kInvalidInput;
  }
  bool invalid = false;
  scan(s, cyl, pose, src, opt, st, [&](std::size_t i, Verdict v) {
    setBit(mask, i);  // a hit, or invalid: "in collision"
    ++count;
    invalid = invalid || v == Verdict::kInvalid;
    return true;
  });
  if (hits != nullptr) *hits = count;
  if (invalid) return Answer::kInvalidInput;
  return count > 0 ? Answer::kIntersect : Answer::kDisjoint;
}

template <class S, class Source, class Scan>
Answer anyImpl(const Cylinder<S>& cyl, const Pose<S>& pose, const Source& src,
               std::size_t* first, const BatchOptions& opt, BatchStats* stats,
               Scan scan) {
  BatchStats local;
  BatchStats* st = stats != nullptr ? stats : &local;
  *st = BatchStats{};
  const Setup s = makeSetup(cyl, pose, opt.cull);
  if (!s.valid) {
    if (first != nullptr) *first = 0;
    return Answer::kInvalidInput;
  }
  Answer answer = Answer::kDisjoint;
  scan(s, cyl, pose, src, opt, st, [&](std::size_t i, Verdict v) {
    answer = v == Verdict::kHit ? Answer::kIntersect : Answer::kInvalidInput;
    if (first != nullptr) *first = i;
    return false;
  });
  return answer;
}

/// The checked "any": the lowest hit, nothing, or InvalidInput.
std::optional<std::size_t> checkedAny(Answer answer, std::size_t first) {
  if (answer == Answer::kInvalidInput) throwInvalid("intersectAny");
  if (answer == Answer::kIntersect) return first;
  return std::nullopt;
}

struct MeshScan {
  template <class S, class Visit>
  void operator()(const Setup& s, const Cylinder<S>& cyl, const Pose<S>& pose,
                  const MeshView<S>& mesh, const BatchOptions& opt,
                  BatchStats* st, Visit&& visit) const {
    scanMesh(s, cyl, pose, mesh, opt, st, visit);
  }
};

struct ArrayScan {
  template <class S, class Visit>
  void operator()(const Setup& s, const Cylinder<S>& cyl, const Pose<S>& pose,
                  const TriangleArrays<S>& tris, const BatchOptions& opt,
                  BatchStats* st, Visit&& visit) const {
    scanArrays(s, cyl, pose, tris, opt, st, visit);
  }
};

}  // namespace

Isa detectedIsa() noexcept {
#if TRICYL_AVX2_DISPATCH
  static const bool has_avx2 = __builtin_cpu_supports("avx2") != 0;
  return has_avx2 ? Isa::kAvx2 : Isa::kPortable;
#else
  return Isa::kPortable;
#endif
}

template <class S>
Answer tryIntersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                        const MeshView<S>& mesh, std::uint64_t* mask,
                        std::size_t* hits, const BatchOptions& options,
                        BatchStats* stats) noexcept {
  return maskImpl(cylinder, pose, mesh, mesh.num_triangles, mask, hits, options,
                  stats, MeshScan{});
}

template <class S>
Answer tryIntersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                        const TriangleArrays<S>& triangles, std::uint64_t* mask,
                        std::size_t* hits, const BatchOptions& options,
                        BatchStats* stats) noexcept {
  return maskImpl(cylinder, pose, triangles, triangles.num_triangles, mask,
                  hits, options, stats, ArrayScan{});
}

template <class S>
Answer tryIntersectAny(const Cylinder<S>& cylinder, const Pose<S>& pose,
                       const MeshView<S>& mesh, std::size_t* first,
                       const BatchOptions& options,
                       BatchStats* stats) noexcept {
  return anyImpl(cylinder, pose, mesh, first, options, stats, MeshScan{});
}

template <class S>
std::size_t intersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const MeshView<S>& mesh, std::uint64_t* mask,
                          const BatchOptions& options, BatchStats* stats) {
  std::size_t hits = 0;
  if (maskImpl(cylinder, pose, mesh, mesh.num_triangles, mask, &hits, options,
               stats, MeshScan{}) == Answer::kInvalidInput)
    throwInvalid("intersectMask");
  return hits;
}

template <class S>
std::size_t intersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const TriangleArrays<S>& triangles,
                          std::uint64_t* mask, const BatchOptions& options,
                          BatchStats* stats) {
  std::size_t hits = 0;
  if (maskImpl(cylinder, pose, triangles, triangles.num_triangles, mask, &hits,
               options, stats, ArrayScan{}) == Answer::kInvalidInput)
    throwInvalid("intersectMask");
  return hits;
}

template <class S>
std::size_t intersectIndices(const Cylinder<S>& cylinder, const Pose<S>& pose,
                             const MeshView<S>& mesh,
                             std::vector<std::uint32_t>* out,
                             const BatchOptions& options, BatchStats* stats) {
  BatchStats local;
  BatchStats* st = stats != nullptr ? stats : &local;
  *st = BatchStats{};
  const Setup s = makeSetup(cylinder, pose, options.cull);
  if (!s.valid) throwInvalid("intersectIndices");
  const std::size_t before = out->size();
  bool invalid = false;
  scanMesh(s, cylinder, pose, mesh, options, st, [&](std::size_t i, Verdict v) {
    if (v == Verdict::kInvalid) {
      invalid = true;
      return false;
    }
    if (v == Verdict::kHit) out->push_back(std::uint32_t(i));
    return true;
  });
  if (invalid) {
    out->resize(before);
    throwInvalid("intersectIndices");
  }
  return out->size() - before;
}

template <class S>
std::optional<std::size_t> intersectAny(const Cylinder<S>& cylinder,
                                        const Pose<S>& pose,
                                        const MeshView<S>& mesh,
                                        const BatchOptions& options,
                                        BatchStats* stats) {
  // Two statements: anyImpl must write `first` before it is read (the
  // order in which a call's arguments are evaluated is unspecified).
  std::size_t first = 0;
  const Answer answer =
      anyImpl(cylinder, pose, mesh, &first, options, stats, MeshScan{});
  return checkedAny(answer, first);
}

template <class S>
std::optional<std::size_t> intersectAny(const Cylinder<S>& cylinder,
                                        const Pose<S>& pose,
                                        const TriangleArrays<S>& triangles,
                                        const BatchOptions& options,
                                        BatchStats* stats) {
  // Two statements: anyImpl must write `first` before it is read (the
  // order in which a call's arguments are evaluated is unspecified).
  std::size_t first = 0;
  const Answer answer =
      anyImpl(cylinder, pose, triangles, &first, options, stats, ArrayScan{});
  return checkedAny(answer, first);
}

#define TRICYL_MESH_CYLINDER_INSTANTIATE(S)                                    \
  template std::size_t intersectMask(const Cylinder<S>&, const Pose<S>&,       \
                                     const MeshView<S>&, std::uint64_t*,       \
                                     const BatchOptions&, BatchStats*);        \
  template std::size_t intersectMask(const Cylinder<S>&, const Pose<S>&,       \
                                     const TriangleArrays<S>&, std::uint64_t*, \
                                     const BatchOptions&, BatchStats*);        \
  template std::size_t intersectIndices(                                       \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&,                  \
      std::vector<std::uint32_t>*, const BatchOptions&, BatchStats*);          \
  template std::optional<std::size_t> intersectAny(                            \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&,                  \
      const BatchOptions&, BatchStats*);                                       \
  template std::optional<std::size_t> intersectAny(                            \
      const Cylinder<S>&, const Pose<S>&, const TriangleArrays<S>&,            \
      const BatchOptions&, BatchStats*);                                       \
  template Answer tryIntersectMask(                                            \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&, std::uint64_t*,  \
      std::size_t*, const BatchOptions&, BatchStats*) noexcept;                \
  template Answer tryIntersectMask(const Cylinder<S>&, const Pose<S>&,         \
                                   const TriangleArrays<S>&, std::uint64_t*,   \
                                   std::size_t*, const BatchOptions&,          \
                                   BatchStats*) noexcept;                      \
  template Answer tryIntersectAny(const Cylinder<S>&, const Pose<S>&,          \
                                  const MeshView<S>&, std::size_t*,            \
                                  const BatchOptions&, BatchStats*) noexcept;
TRICYL_MESH_CYLINDER_INSTANTIATE(float)
TRICYL_MESH_CYLINDER_INSTANTIATE(double)
#undef TRICYL_MESH_CYLINDER_INSTANTIATE

}  // namespace tricyl
