// SPDX-License-Identifier: BSD-3-Clause
// The floor of the scalar triangle-cylinder design (the 20x target;
// docs/performance.md): truncated versions of the world-pose entry point's
// first stage, each adding one piece of work that an exact answer needs,
// timed on the same cases, in the same order, with FCL in the same iteration
// (BM_Floor in bench_triangle_cylinder.cpp).
//
// None of these is a kernel: levels 1 to 4 answer nothing for the queries
// their tests leave open, and levels 1 and 2 certify nothing. Each is a
// lower bound on what a query costs in this design:
//   0  loop: one input read and compared (the benchmark loop and the call);
//   1  transform: y = R^T (p - t) for the three vertices in the lanes of one
//      AVX2 register, and the six bounding-box plane tests (all vertices
//      beyond x = r, x = -r, y = +-r, or z = +-lz/2), branch-free, no bound;
//   2  + gate: the 23 inputs' bit patterns checked first (finite, |x| < 2^40,
//      |R_jk| < 2: the range under which the bounds hold), one branch that
//      is always taken the same way here;
//   3  + bounds: each plane test certified, as the kernel's first stage does
//      it (per-vertex magnitude 2 (|d0| + |d1| + |d2|), FilterKernel's
//      relative and absolute constants);
//   4  + (V): a vertex certainly inside the solid (the kernel's second
//      cheapest answer), still branch-free;
//   5  + branch: one branch on the outcome, as any kernel takes to do more
//      work for the queries still open; here it does none.
// The kernel itself (BM_Tricyl, BM_Paired) is level 5 plus the work for
// the queries still open (their share of uniform: bench/results/README.md).
// Same arithmetic as src/triangle_cylinder.cpp's prologueAvx2Body up to the
// branch; written again here (the bench must not reach into the library's
// anonymous namespace), without FMA, like the kernel.
#pragma once

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define TRICYL_BENCH_FLOOR 1
#include <immintrin.h>

#include "filter.h"  // detail::FilterKernel::kRel, kAbs
#include "tricyl/triangle_cylinder.h"

namespace tricyl::bench::scalar_floor {

inline constexpr int kLevels = 6;
inline constexpr const char* kLevelNames[kLevels] = {
    "loop", "transform", "+gate", "+bounds", "+vertex", "+branch"};

#define TRICYL_FLOOR_FN __attribute__((target("avx2"), always_inline)) inline
TRICYL_FLOOR_FN __m256i ld32(const char* q) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(q));
}
TRICYL_FLOOR_FN __m256d lanes(double a, double b, double c) {
  return _mm256_set_pd(c, c, b, a);
}
TRICYL_FLOOR_FN __m256d bc(const double& v) { return _mm256_broadcast_sd(&v); }
// Local coordinate k of the three vertices: R0k d0 + R1k d1 + R2k d2.
TRICYL_FLOOR_FN __m256d row(const Pose<double>& pose, int k, __m256d d0,
                            __m256d d1, __m256d d2) {
  const auto& R = pose.R;
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(bc(R[0][k]), d0),
                                     _mm256_mul_pd(bc(R[1][k]), d1)),
                       _mm256_mul_pd(bc(R[2][k]), d2));
}
#undef TRICYL_FLOOR_FN

// 0: not intersecting; 1: an early-out (disjoint); 2: (V), a vertex inside;
// 3: open (level 5 only). Levels 1 to 4 return 1 + 2 (V) for hits of both,
// which never occur together.
template <int kLevel>
__attribute__((target("avx2"), noinline)) int query(
    const Cylinder<double>& cyl, const Pose<double>& pose,
    const Triangle<double>& tri) {
  if constexpr (kLevel == 0) {
    return tri.a.x > pose.t.x;
  } else {
    if constexpr (kLevel >= 2) {
      // Top 16 bits of each word, sign cleared; 16-bit maxima; one compare
      // per limit (|x| < 2^40: <= 0x426f; |R_jk| < 2: <= 0x3fff), and the
      // signs of r and lz. Loads stay inside the aggregates (9, 12 and 2
      // doubles, contiguous).
      const char* T = reinterpret_cast<const char*>(&tri);
      const char* P = reinterpret_cast<const char*>(&pose);
      const char* C = reinterpret_cast<const char*>(&cyl);
      auto ld16 = [](const char* q) {
        return _mm_loadu_si128(reinterpret_cast<const __m128i*>(q));
      };
      auto ld8 = [](const char* q) {
        return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(q));
      };
      const __m256i top = _mm256_set1_epi64x(0x7fff000000000000LL);
      const __m128i top2 = _mm256_castsi256_si128(top);
      const __m256i len = _mm256_set1_epi64x(0x426fLL << 48);
      const __m256i rot = _mm256_set1_epi64x(0x3fffLL << 48);
      const __m256i mix = _mm256_blend_epi32(len, rot, 0x03);
      const __m128i c = ld16(C);
      const __m256i lens = _mm256_max_epi16(
          _mm256_max_epi16(_mm256_and_si256(ld32(T), top),
                           _mm256_and_si256(ld32(T + 32), top)),
          _mm256_zextsi128_si256(_mm_max_epi16(
              _mm_and_si128(c, top2), _mm_and_si128(ld8(T + 64), top2))));
      const __m256i rots = _mm256_max_epi16(
          _mm256_and_si256(ld32(P), top), _mm256_and_si256(ld32(P + 32), top));
      const __m256i bad = _mm256_or_si256(
          _mm256_or_si256(_mm256_cmpgt_epi16(lens, len),
                          _mm256_cmpgt_epi16(rots, rot)),
          _mm256_cmpgt_epi16(_mm256_and_si256(ld32(P + 64), top), mix));
      const __m128i negative = _mm_cmpgt_epi64(
          _mm_xor_si128(c,
                        _mm_set1_epi64x(std::int64_t(0x8000000000000000ULL))),
          _mm_setzero_si128());
      if (!(_mm256_testz_si256(bad, bad) & _mm_testz_si128(negative, negative)))
        return -1;
    }
    const __m256d d0 =
        _mm256_sub_pd(lanes(tri.a.x, tri.b.x, tri.c.x), bc(pose.t.x));
    const __m256d d1 =
        _mm256_sub_pd(lanes(tri.a.y, tri.b.y, tri.c.y), bc(pose.t.y));
    const __m256d d2 =
        _mm256_sub_pd(lanes(tri.a.z, tri.b.z, tri.c.z), bc(pose.t.z));
    const __m256d x = row(pose, 0, d0, d1, d2), y = row(pose, 1, d0, d1, d2),
                  z = row(pose, 2, d0, d1, d2);
    const __m256d Z = _mm256_add_pd(z, z);
    const __m256d abs =
        _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
    const __m256d r = bc(cyl.radius), H = bc(cyl.lz);
    __m256d bx = _mm256_setzero_pd(), bz = bx, me = bx;
    if constexpr (kLevel >= 3) {
      const __m256d kr = _mm256_set1_pd(detail::FilterKernel::kRel);
      const __m256d ka = _mm256_set1_pd(detail::FilterKernel::kAbs);
      const __m256d s = _mm256_add_pd(
          _mm256_add_pd(_mm256_and_pd(d0, abs), _mm256_and_pd(d1, abs)),
          _mm256_and_pd(d2, abs));
      me = _mm256_add_pd(s, s);
      bx = _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(me, r), kr), ka);
      bz = _mm256_add_pd(
          _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(me, me), H), kr), ka);
    }
    const __m256d zt = _mm256_sub_pd(_mm256_and_pd(Z, abs), H);
    const int cx = _mm256_movemask_pd(
        _mm256_cmp_pd(_mm256_sub_pd(_mm256_and_pd(x, abs), r), bx, _CMP_GT_OQ));
    const int cy = _mm256_movemask_pd(
        _mm256_cmp_pd(_mm256_sub_pd(_mm256_and_pd(y, abs), r), bx, _CMP_GT_OQ));
    const int cz = _mm256_movemask_pd(_mm256_cmp_pd(zt, bz, _CMP_GT_OQ));
    const int sx = _mm256_movemask_pd(x), sy = _mm256_movemask_pd(y),
              sz = _mm256_movemask_pd(Z);
    auto same = [](int g) { return int((g == 0) | (g == 15)); };
    const int early = ((cx == 15) & same(sx)) | ((cy == 15) & same(sy)) |
                      ((cz == 15) & same(sz));
    int vin = 0;
    if constexpr (kLevel >= 4) {
      const __m256d nbz = _mm256_xor_pd(bz, _mm256_set1_pd(-0.0));
      const __m256d slab = _mm256_cmp_pd(zt, nbz, _CMP_LT_OQ);
      const __m256d r2 = _mm256_mul_pd(r, r), mm = _mm256_mul_pd(me, me);
      const __m256d v = _mm256_sub_pd(_mm256_sub_pd(r2, _mm256_mul_pd(x, x)),
                                      _mm256_mul_pd(y, y));
      const __m256d bv = _mm256_add_pd(
          _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(r2, mm), mm),
                        _mm256_set1_pd(detail::FilterKernel::kRel)),
          _mm256_set1_pd(detail::FilterKernel::kAbs));
      vin = int(_mm256_movemask_pd(_mm256_and_pd(
                    slab, _mm256_cmp_pd(v, bv, _CMP_GT_OQ))) != 0);
    }
    if constexpr (kLevel >= 5) {
      if ((early | vin) != 0) return early != 0 ? 1 : 2;
      // The open side: in the kernel, the rest of the tests. Here a value
      // that depends on the computed coordinates, so none is dead code.
      return 3 + int(_mm256_cvtsd_f64(x) > 0);
    }
    return early + 2 * vin;
  }
}

using QueryFn = int (*)(const Cylinder<double>&, const Pose<double>&,
                        const Triangle<double>&);
inline constexpr QueryFn kQuery[kLevels] = {query<0>, query<1>, query<2>,
                                            query<3>, query<4>, query<5>};

}  // namespace tricyl::bench::scalar_floor
#endif
