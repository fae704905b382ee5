// SPDX-License-Identifier: BSD-3-Clause
// Dispatch for the triangle-cylinder test: validate, filter, fall back.
#include "tricyl/triangle_cylinder.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <type_traits>

// TRICYL_PORTABLE_PROLOGUE (CMake option of the same name): the portable
// prologue even where SSE2 is available, so that CI pins it to the SIMD
// prologues' answers on x86-64 (tests/answers_digest_check.sh, issue 20).
#if defined(__SSE2__) && !defined(TRICYL_PORTABLE_PROLOGUE)
#define TRICYL_SSE2 1
#include <emmintrin.h>
#else
#define TRICYL_SSE2 0
#endif
#if TRICYL_SSE2 && defined(__x86_64__) && \
    (defined(__GNUC__) || defined(__clang__))
#define TRICYL_FAST_AVX2 1
#include <immintrin.h>
#else
#define TRICYL_FAST_AVX2 0
#endif

#include "filter.h"
#include "line_cylinder_impl.h"
#include "stages.h"
#include "triangle_cylinder_impl.h"

#if defined(__GNUC__) || defined(__clang__)
#define TRICYL_ALWAYS_INLINE inline __attribute__((always_inline))
#define TRICYL_NOINLINE __attribute__((noinline))
#define TRICYL_FLATTEN __attribute__((flatten))
#else
#define TRICYL_ALWAYS_INLINE inline
#define TRICYL_NOINLINE
#define TRICYL_FLATTEN
#endif

namespace tricyl {
namespace {

using detail::FilterKernel;
using detail::NaiveKernel;
using detail::Sign;
using detail::Tri;

// The double kernel works on references to the caller's values; float
// inputs are widened first (float -> double is exact, so the double kernel
// is exact for float inputs).
struct Inputs {
  const Cylinder<double>& cyl;
  const Pose<double>& pose;
  const Triangle<double>& tri;
};

struct Widened {
  Cylinder<double> cyl;
  Pose<double> pose;
  Triangle<double> tri;
};

template <class S>
Vec3<double> widen(const Vec3<S>& v) {
  return {double(v.x), double(v.y), double(v.z)};
}

Widened widen(const Cylinder<float>& cyl, const Pose<float>& pose,
              const Triangle<float>& tri) {
  Widened w;
  w.cyl = {double(cyl.radius), double(cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) w.pose.R[i][j] = double(pose.R[i][j]);
  w.pose.t = widen(pose.t);
  w.tri = {widen(tri.a), widen(tri.b), widen(tri.c)};
  return w;
}

static_assert(sizeof(Pose<double>) == 12 * sizeof(double) &&
                  sizeof(Triangle<double>) == 9 * sizeof(double) &&
                  sizeof(Cylinder<double>) == 2 * sizeof(double),
              "the aggregates are arrays of doubles without padding");

// |x| as bits. For non-negative doubles the bit pattern orders like the
// value, and a double is finite iff (bits & ~sign) < 0x7ff0...0.
template <size_t N>
std::uint64_t maxAbsBits(const void* p) {
  std::uint64_t b[N];
  std::memcpy(b, p, sizeof b);
  std::uint64_t m = 0;
  for (size_t i = 0; i < N; ++i) {
    const std::uint64_t a = b[i] & ~(std::uint64_t(1) << 63);
    m = a > m ? a : m;
  }
  return m;
}

// One pass over the input bits. Returns false for NaN/Inf anywhere or a
// negative radius or length (-0 is fine); otherwise the largest magnitudes
// of the lengths and of the rotation entries, for the filter's range gate.
bool validate(const Inputs& in, double* max_len, double* max_unitless) {
  constexpr std::uint64_t kInf = 0x7ff0000000000000ULL;
  const std::uint64_t mu = maxAbsBits<9>(&in.pose.R[0][0]);
  std::uint64_t ml = maxAbsBits<9>(&in.tri);
  const std::uint64_t mt = maxAbsBits<3>(&in.pose.t);
  const std::uint64_t mc = maxAbsBits<2>(&in.cyl);
  ml = ml > mt ? ml : mt;
  ml = ml > mc ? ml : mc;
  if (ml >= kInf || mu >= kInf) return false;
  std::memcpy(max_len, &ml, sizeof ml);
  std::memcpy(max_unitless, &mu, sizeof mu);
  return in.cyl.radius >= 0 && in.cyl.lz >= 0;  // -0 passes
}

// A degenerate triangle's hull (docs/exactness.md, section 6). Three
// exactly collinear vertices span the segment between the two extreme ones
// (a repeated vertex and a single point included); the answer is then the
// segment query's. The triangle kernel meets such input through signs that
// are exactly zero (the projected area; for a repeated vertex an edge of
// length zero), which need the exact stage, several times per query; the
// segment kernel has no such sign, and decides them in double.
//   Collinear: (b - a) x (c - a) = 0 exactly, a query of its own (degree 2
// in the inputs' differences): FilterKernel certifies a non-zero component
// for every triangle that is not close to degenerate, and the adaptive run
// decides the rest exactly.
//   Ends: if the vertices differ in coordinate k, the line's direction has a
// non-zero k component, so coordinate k orders the points along it, and the
// vertices with the least and greatest coordinate k are the ends (exact
// comparisons of doubles). If they differ in no coordinate, the hull is the
// point a.
template <class K>
Tri collinear(const Triangle<double>& t) {
  auto d = [](double p, double q) { return K::inputDiff(p, q); };
  const auto ux = d(t.b.x, t.a.x), uy = d(t.b.y, t.a.y), uz = d(t.b.z, t.a.z);
  const auto vx = d(t.c.x, t.a.x), vy = d(t.c.y, t.a.y), vz = d(t.c.z, t.a.z);
  Tri zero = isZero(K::sign(ux * vy - uy * vx));
  if (zero == Tri::kFalse) return zero;
  zero = kAnd(zero, isZero(K::sign(uy * vz - uz * vy)));
  if (zero == Tri::kFalse) return zero;
  return kAnd(zero, isZero(K::sign(uz * vx - ux * vz)));
}

Segment<double> collinearHull(const Triangle<double>& t) {
  const Vec3<double>* v[3] = {&t.a, &t.b, &t.c};
  for (int axis = 0; axis < 3; ++axis) {
    auto at = [axis](const Vec3<double>* p) {
      return axis == 0 ? p->x : (axis == 1 ? p->y : p->z);
    };
    int lo = 0, hi = 0;
    for (int i = 1; i < 3; ++i) {
      if (at(v[i]) < at(v[lo])) lo = i;
      if (at(v[i]) > at(v[hi])) hi = i;
    }
    if (at(v[lo]) < at(v[hi])) return {*v[lo], *v[hi]};
  }
  return {t.a, t.a};
}

bool shortRotation(const Pose<double>& pose);

// The local coordinates in double word, x, y and Z of each vertex, with
// their bounds (DwKernel::toLocal: the a-priori bound of dwCoordinate),
// computed once per query and read by the running stage (rounded) and by
// the double-word stage.
struct DwFrame {
  detail::DwRun c[3][3];  // [vertex][x, y, Z]
};
template <bool kFma>
TRICYL_ALWAYS_INLINE void dwFrame(const Inputs& in, DwFrame* f) {
  using K = detail::DwKernel<kFma>;
  const Vec3<double>* P[3] = {&in.tri.a, &in.tri.b, &in.tri.c};
  for (int i = 0; i < 3; ++i) {
    typename K::Num c[3];
    K::toLocal(in.pose, *P[i], c[0], c[1], c[2]);
    for (int j = 0; j < 3; ++j) f->c[i][j] = {c[j].v, c[j].e};
  }
}

// The double-word stages (src/dw_kernel.h): the tests in `tests` alone, on
// the frame `f`, in straight-line double-word arithmetic: K = DwKernel (a
// running bound, exact values tracked) or DwFilterKernel (a magnitude
// bound); `left`: the tests it left undecided. Flattened (every call
// inlined), so that the copy compiled for FMA (TRICYL_FMA_DISPATCH) runs FMA
// throughout; both copies give the same bits.
template <class K>
TRICYL_ALWAYS_INLINE Tri frameTests(const Inputs& in, const DwFrame& f,
                                    std::uint32_t tests, std::uint32_t* left,
                                    detail::EarlyOuts* early) {
  detail::TriCylLocal<K> q;
  for (int i = 0; i < 3; ++i) {
    q.x[i] = K::leaf(f.c[i][0]);
    q.y[i] = K::leaf(f.c[i][1]);
    q.Z[i] = K::leaf(f.c[i][2]);
  }
  q.H = K::lift(in.cyl.lz);
  q.r = K::lift(in.cyl.radius);
  return detail::triangleCylinderUndecided<K>(q, tests, left, early);
}
template <bool kFma>
TRICYL_ALWAYS_INLINE Tri dwTests(const Inputs& in, const DwFrame& f,
                                 std::uint32_t tests, std::uint32_t* left,
                                 detail::EarlyOuts* early) {
  return frameTests<detail::DwKernel<kFma>>(in, f, tests, left, early);
}
template <bool kFma>
TRICYL_ALWAYS_INLINE Tri dwfTests(const Inputs& in, const DwFrame& f,
                                  std::uint32_t tests, std::uint32_t* left,
                                  detail::EarlyOuts* early) {
  return frameTests<detail::DwFilterKernel<kFma>>(in, f, tests, left, early);
}
#if TRICYL_FMA_DISPATCH
__attribute__((target("fma"), flatten, noinline)) Tri dwfTestsFma(
    const Inputs& in, const DwFrame& f, std::uint32_t tests,
    std::uint32_t* left, detail::EarlyOuts* early) {
  return dwfTests<true>(in, f, tests, left, early);
}
#endif
TRICYL_FLATTEN TRICYL_NOINLINE Tri dwfTestsPlain(const Inputs& in,
                                                 const DwFrame& f,
                                                 std::uint32_t tests,
                                                 std::uint32_t* left,
                                                 detail::EarlyOuts* early) {
  return dwfTests<TRICYL_HAVE_FMA != 0>(in, f, tests, left, early);
}
Tri dwfStage(const Inputs& in, const DwFrame& f, std::uint32_t tests,
             std::uint32_t* left, detail::EarlyOuts* early) {
#if TRICYL_FMA_DISPATCH
  if (detail::fmaAtRunTime()) return dwfTestsFma(in, f, tests, left, early);
#endif
  return dwfTestsPlain(in, f, tests, left, early);
}
#if TRICYL_FMA_DISPATCH
__attribute__((target("fma"), flatten, noinline)) void dwFrameFma(
    const Inputs& in, DwFrame* f) {
  dwFrame<true>(in, f);
}
__attribute__((target("fma"), flatten, noinline)) Tri dwTestsFma(
    const Inputs& in, const DwFrame& f, std::uint32_t tests,
    std::uint32_t* left, detail::EarlyOuts* early) {
  return dwTests<true>(in, f, tests, left, early);
}
#endif
TRICYL_FLATTEN TRICYL_NOINLINE void dwFramePlain(const Inputs& in, DwFrame* f) {
  dwFrame<TRICYL_HAVE_FMA != 0>(in, f);
}
TRICYL_FLATTEN TRICYL_NOINLINE Tri dwTestsPlain(const Inputs& in,
                                                const DwFrame& f,
                                                std::uint32_t tests,
                                                std::uint32_t* left,
                                                detail::EarlyOuts* early) {
  return dwTests<TRICYL_HAVE_FMA != 0>(in, f, tests, left, early);
}
#if TRICYL_FAST_AVX2
extern const bool kHasAvx2;
void dwFrameAvx2Fma(const Inputs& in, DwFrame* f);
#endif
void dwFrameStage(const Inputs& in, DwFrame* f) {
#if TRICYL_FAST_AVX2
  if (kHasAvx2 && detail::fmaAtRunTime()) return dwFrameAvx2Fma(in, f);
#endif
#if TRICYL_FMA_DISPATCH
  if (detail::fmaAtRunTime()) return dwFrameFma(in, f);
#endif
  dwFramePlain(in, f);
}
Tri dwStage(const Inputs& in, const DwFrame& f, std::uint32_t tests,
            std::uint32_t* left, detail::EarlyOuts* early) {
#if TRICYL_FMA_DISPATCH
  if (detail::fmaAtRunTime()) return dwTestsFma(in, f, tests, left, early);
#endif
  return dwTestsPlain(in, f, tests, left, early);
}

// The frame again, each coordinate accurate to its own size
// (dwCoordinateAccurate, src/dw_kernel.h) where that is tighter than the
// frame's bound: exact coordinates are kept. Returns whether some bound
// shrank (then the double-word stage runs once more).
TRICYL_NOINLINE bool dwFrameAccurate(const Inputs& in, DwFrame* f) {
  const Vec3<double>* P[3] = {&in.tri.a, &in.tri.b, &in.tri.c};
  bool tighter = false;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      detail::DwRun& c = f->c[i][j];
      detail::DwRun r;
      if (c.e == 0 || !detail::dwCoordinateAccurate(in.pose, *P[i], j, &r))
        continue;
      if (r.e + std::fabs(r.v.lo) < c.e + std::fabs(c.v.lo)) {
        c = r;
        tighter = true;
      }
    }
  }
  return tighter;
}

// The running frame from the double-word frame: each coordinate rounded to
// its high part, with the bound e + |lo| (|E - hi| <= |E - (hi + lo)| +
// |lo|), rounded up by the factor 1 + 2^-50 (one addition rounded by at
// most 1 + 2^-53). An exact coordinate (e = 0, then lo = 0) keeps the
// bound 0.
template <class K>
detail::TriCylLocal<K> runningFrame(const Inputs& in, const DwFrame& f) {
  detail::TriCylLocal<K> q;
  auto leaf = [](const detail::DwRun& c) {
    return typename K::Num{c.v.hi, (c.e + std::fabs(c.v.lo)) * (1 + 0x1p-50)};
  };
  for (int i = 0; i < 3; ++i) {
    q.x[i] = leaf(f.c[i][0]);
    q.y[i] = leaf(f.c[i][1]);
    q.Z[i] = leaf(f.c[i][2]);
  }
  q.H = K::lift(in.cyl.lz);
  q.r = K::lift(in.cyl.radius);
  return q;
}

// The local frame as toLocal<FilterKernel> computes it: one magnitude
// m_i = rho s_i per vertex (rho = max |R_jk|), z doubled; and the cylinder.
struct Local {
  double x[4], y[4], Z[4], m[4];  // [3]: scratch (the AVX2 lane 3)
  double r, H;
  // What the filter certified on its way, for the stages after it (set
  // when it leaves the query open; the scalar filter leaves both false):
  // twice the projected area A2 = o01 + o12 + o20 is not 0, so the
  // triangle is not degenerate (the projection of three collinear points is
  // collinear); each of the six early-outs has a vertex certainly not
  // beyond its plane, so none can decide in any arithmetic (EarlyOuts).
  bool area_nonzero, early_settled;
};

detail::TriCylLocal<detail::AdaptiveKernel> adaptiveLocal(const Inputs& in,
                                                          const Local& L);

// The whole sequence for validated inputs (src/stages.h): the double filter
// (unless the fast path already ran it and it could not decide), the
// degenerate hand-off, the running and double-word stages on the tests the
// filter left undecided, and the tape's exact stage on what that left.
// `undecided`: 0, or the tests the fast path's filter left undecided
// (detail::TestMask). `fast`: the fast path's local frame when it ran (then
// the inputs are valid and inside the gate: not validated again).
Decision decide(const Inputs& in, std::uint32_t undecided,
                const Local* fast = nullptr) {
  // With `fast`, max_len and max_unitless stay 0 (inside the gate) until
  // the degenerate hand-off needs them.
  double max_len = 0, max_unitless = 0;
  if (fast == nullptr && !validate(in, &max_len, &max_unitless))
    return {Answer::kInvalidInput, Stage::kInvalid};
  const bool gate = detail::rangeGateOk(max_len, max_unitless);
  if (gate && undecided == 0) {
    bool early = false;
    detail::TestMask mask;
    const auto q =
        detail::makeLocal<FilterKernel>(in.cyl, in.pose, in.tri, max_unitless);
    const Tri t = detail::triangleCylinder<FilterKernel>(q, &early, &mask);
    if (t != Tri::kUnknown)
      return {detail::toAnswer(t), early ? Stage::kEarlyOut : Stage::kFastPath};
    undecided = mask.unknown;
  }
  // What the fast path's filter certified on its way (Local), when it ran
  // and left `undecided` open.
  const bool filtered = fast != nullptr && undecided != 0;
  // Outside the gate no filter ran: every test.
  if (undecided == 0) undecided = detail::kAllTests;
  // A certified non-zero projected area: not degenerate, no hand-off.
  const Decision degenerate =
      filtered && fast->area_nonzero
          ? Decision{Answer::kDisjoint, Stage::kFastPath}
          : detail::runStages(
                [&](auto tag, bool*) {
                  return collinear<typename decltype(tag)::type>(in.tri);
                },
                max_len, max_unitless);
  if (degenerate.answer == Answer::kIntersect) {
    if (fast != nullptr) validate(in, &max_len, &max_unitless);
    detail::LinearInputs seg;
    seg.cyl = in.cyl;
    seg.pose = in.pose;
    const Segment<double> hull = collinearHull(in.tri);
    seg.p = hull.p;
    seg.q = hull.q;
    // The hull's inputs are among the triangle's: the same gate holds.
    seg.max_len = max_len;
    seg.max_unitless = max_unitless;
    return detail::runStages(
        [&](auto tag, bool* early) {
          return detail::SegmentPred<typename decltype(tag)::type>::run(seg,
                                                                        early);
        },
        max_len, max_unitless);
  }
  if (gate) {
    // The undecided tests with a running bound in double (it follows the
    // values, where the filter's follows the magnitudes: it certifies
    // most signs that cancellation left open), then in double word.
    // Both read the double-word frame, computed once: its coordinates,
    // rounded, are accurate to their own size, where the fast path's are
    // accurate to the vertex's world terms (a needle's local x and y, far
    // below them, are decided here instead of in double word), and it
    // knows which coordinates are exact doubles. The running pass ends at
    // its first undecided test (TestMask::stop_at_unknown): the double-word
    // filter (DwFilterKernel), then the double-word stage, re-run that test
    // and the ones after it.
    //   An exact pose (shortRotation) skips the running pass: on exact data
    // it makes exact ties, which only a kernel that tracks exact values
    // decides (the double-word stage does, section 4.5 of
    // docs/exactness.md), and near ties in an exact frame are what the
    // running pass fails on; the running pass decided too few of the rest
    // to pay for its failures (bench/results/2026-11-26-triangle-stages-f.md).
    using detail::RunningDoubleKernel;
    using detail::triangleCylinderUndecided;
    std::uint32_t left = undecided;
    Tri t;
    // Settled by the filter, or here: the stages skip them.
    detail::EarlyOuts early;
    early.settled = filtered && fast->early_settled;
    DwFrame frame;
    dwFrameStage(in, &frame);
    detail::tls_exact_zero = false;
    if (!shortRotation(in.pose)) {
      t = triangleCylinderUndecided<RunningDoubleKernel>(
          runningFrame<RunningDoubleKernel>(in, frame), undecided, &left,
          &early, /*stop_at_unknown=*/true);
      if (t != Tri::kUnknown) return {detail::toAnswer(t), Stage::kRunning};
      // Then the double-word filter: values in double word, a magnitude
      // bound, about a third fewer instructions than the tracked
      // double-word stage, whose bound it matches on all but exact ties,
      // which a rounded pose almost never makes.
      undecided = left;
      t = dwfStage(in, frame, undecided, &left, &early);
      if (t != Tri::kUnknown) return {detail::toAnswer(t), Stage::kExtended};
    }
    undecided = left;
    t = dwStage(in, frame, undecided, &left, &early);
    // What the frame's bound left open, once more on coordinates accurate
    // to their own size (needles, discs), before the tape.
    if (t == Tri::kUnknown && dwFrameAccurate(in, &frame)) {
      undecided = left;
      t = dwStage(in, frame, undecided, &left, &early);
    }
    if (t != Tri::kUnknown)
      return {detail::toAnswer(t),
              detail::tls_exact_zero ? Stage::kExact : Stage::kExtended};
    undecided = left;
  }
  Decision d = detail::runAdaptive(
      [&](auto tag, bool*) {
        using K = typename decltype(tag)::type;
        if constexpr (std::is_same_v<K, detail::AdaptiveKernel>) {
          // The fast path's local frame, when it ran: the same values, not
          // computed twice (Tape::coordinates).
          if (fast != nullptr)
            return detail::triangleCylinderUndecided<K>(
                adaptiveLocal(in, *fast), undecided);
        }
        const auto q =
            detail::makeLocal<K>(in.cyl, in.pose, in.tri, max_unitless);
        return detail::triangleCylinderUndecided<K>(q, undecided);
      },
      gate);
  // The double-word stage ran first (inside the gate).
  if (gate && d.stage == Stage::kFastPath) d.stage = Stage::kExtended;
  return d;
}

// Widening a signalling NaN raises FE_INVALID: float inputs are checked by
// their bits before they are widened.
bool floatBitsFinite(const Cylinder<float>& cylinder, const Pose<float>& pose,
                     const Triangle<float>& triangle) {
  static_assert(sizeof(float) == sizeof(std::uint32_t), "binary32");
  const void* parts[3] = {&cylinder, &pose, &triangle};
  const size_t counts[3] = {2, 12, 9};
  for (int k = 0; k < 3; ++k)
    for (size_t i = 0; i < counts[k]; ++i) {
      std::uint32_t b;
      std::memcpy(&b, static_cast<const char*>(parts[k]) + 4 * i, 4);
      if ((b & 0x7f800000u) == 0x7f800000u) return false;
    }
  return true;
}

TRICYL_NOINLINE Decision decideSlow(const Cylinder<double>& cylinder,
                                    const Pose<double>& pose,
                                    const Triangle<double>& triangle,
                                    std::uint32_t undecided, const Local* L) {
  return decide(Inputs{cylinder, pose, triangle}, undecided,
                undecided != 0 ? L : nullptr);
}
TRICYL_NOINLINE Decision decideSlow(const Cylinder<float>& cylinder,
                                    const Pose<float>& pose,
                                    const Triangle<float>& triangle,
                                    std::uint32_t undecided,
                                    const Local* /*L*/) {
  if (!floatBitsFinite(cylinder, pose, triangle))
    return {Answer::kInvalidInput, Stage::kInvalid};
  const Widened w = widen(cylinder, pose, triangle);
  return decide(Inputs{w.cyl, w.pose, w.tri}, undecided);
}

// ---------------------------------------------------------------------------

// The scalar fast path: the double filter (FilterKernel) with validation and
// range gate fused into the arithmetic, and branch-free early-outs. It
// computes bit for bit the values and bounds that makeLocal<FilterKernel> and
// triangleCylinder<FilterKernel> compute, so every answer it gives is one the
// filter gives; it only reaches them with fewer instructions and branches.
//
// Validation and range gate of the fast path (docs/exactness.md,
// "Validation"). Like validate(), it reads only bit patterns, so no input
// (NaN, signalling NaN, Inf) ever reaches a floating-point instruction before
// it is known to be finite: the library raises no floating-point exception on
// any input. The fast path runs only if every length input (triangle,
// translation, radius, lz) has |x| < 2^40, every rotation entry |R_jk| < 2,
// and r >= 0, lz >= 0 (-0 passes): a subset of what validate() and
// rangeGateOk() accept (they allow |x| = 2^40 and |R_jk| = 2), so every
// query the fast path takes is one the filter would have run on, with the
// same values and bounds. Everything else (invalid input, gate misses) takes
// decideSlow, which decides exactly as before.
enum class Fast { kGateMiss, kDecided, kUnknown };
// What the prologue found: a gate miss, a certified early-out (disjoint), a
// certified common point (test (V): a vertex inside the solid; with AVX2
// also test (X): an edge crossing a cap plane inside the cap disk), a
// certified separation after the early-outs (AVX2: edge separation), or
// nothing yet.
enum class Pre { kGateMiss, kEarlyOut, kHit, kDisjoint, kOpen };

// Whether every rotation entry has at most 27 significant bits (the low 26
// bits of its significand zero): exact poses (signed permutations, short
// dyadics) do, rounded rotations almost never; only then is it worth
// checking the coordinates for exactness.
bool shortRotation(const Pose<double>& pose) {
  std::uint64_t low = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      std::uint64_t b;
      std::memcpy(&b, &pose.R[i][j], sizeof b);
      low |= b;
    }
  return (low & ((std::uint64_t(1) << 26) - 1)) == 0;
}

// The adaptive run's local frame from the fast path's (double inputs).
detail::TriCylLocal<detail::AdaptiveKernel> adaptiveLocal(const Inputs& in,
                                                          const Local& L) {
  detail::TriCylLocal<detail::AdaptiveKernel> q;
  detail::Tape* tape = detail::tls_tape;
  const Vec3<double>* P[3] = {&in.tri.a, &in.tri.b, &in.tri.c};
  for (int i = 0; i < 3; ++i)
    tape->coordinates(in.pose, *P[i], L.x[i], L.y[i], L.Z[i], L.m[i], q.x[i],
                      q.y[i], q.Z[i]);
  q.H = detail::AdaptiveKernel::lift(in.cyl.lz);
  q.r = detail::AdaptiveKernel::lift(in.cyl.radius);
  return q;
}

// Early-outs, the certified signs of triangleCylinder: Z_i - H and Z_i + H
// have magnitude fl(2 m_i + lz), x_i - r, -x_i - r, y_i - r and -y_i - r
// have fl(m_i + r); a sign is certain beyond fl(m kRel) + kAbs. The triangle
// is beyond a plane iff all three vertices are. fl(-x - r) and fl(-Z - H)
// are the negations of fl(x + r) and fl(Z + H) (rounding is symmetric), so
// "fl(-Z - H) > b" is "fl(Z + H) < -b", the bottom test of triangleCylinder.
// The prologues use the magnitude 2 s_i >= m_i = rho s_i instead (the gate
// admits |R_jk| <= 2 only, and rounding is monotone: fl(rho s) <= fl(2 s)),
// so the bounds are the kernel's or larger and rho is not needed before the
// early-outs; filterTests re-runs them with m_i for what gets through.
constexpr double kRel = FilterKernel::kRel, kAbs = FilterKernel::kAbs;

#if TRICYL_SSE2
// SSE2 (every x86-64): lane 0 = x, lane 1 = y. Each operation below is the
// scalar IEEE operation of the portable version, lane by lane, in the same
// order, so the values are bit for bit those of makeLocal<FilterKernel>.
template <class S>
__m128d load2(const S* p);
template <>
TRICYL_ALWAYS_INLINE __m128d load2(const double* p) {
  return _mm_loadu_pd(p);
}
template <>
TRICYL_ALWAYS_INLINE __m128d load2(const float* p) {
  return _mm_cvtps_pd(
      _mm_castsi128_ps(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p))));
}
template <class S>
TRICYL_ALWAYS_INLINE __m128d load1(const S* p) {
  return _mm_set_sd(double(*p));
}

// The top 16 bits of |x| (sign cleared) order like |x|, and a 16-bit signed
// max (pmaxsw) of them is exact. For double, |x| < 2^40 iff the top 16 bits
// of |x| are <= 0x426f (2^40 = 0x4270 0000 0000 0000) and |x| < 2 iff they are
// <= 0x3fff; for float, 2^40 = 0x5380 0000 and 2 = 0x4000 0000. NaN and Inf
// (exponent all ones: top bits >= 0x7ff0, resp. 0x7f80) exceed both.
template <class S>
struct GateBits;
template <>
struct GateBits<double> {
  static constexpr short kLen = 0x426f, kRot = 0x3fff;
  static __m128i mask() { return _mm_set1_epi64x(0x7fff000000000000LL); }
};
template <>
struct GateBits<float> {
  static constexpr short kLen = 0x537f, kRot = 0x3fff;
  static __m128i mask() { return _mm_set1_epi32(0x7fff0000); }
};
static_assert(sizeof(Pose<float>) == 12 * sizeof(float) &&
                  sizeof(Triangle<float>) == 9 * sizeof(float) &&
                  sizeof(Cylinder<float>) == 2 * sizeof(float),
              "the aggregates are arrays of floats without padding");

TRICYL_ALWAYS_INLINE __m128i ld16(const char* p) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
}
TRICYL_ALWAYS_INLINE __m128i ld8(const char* p) {
  return _mm_loadl_epi64(reinterpret_cast<const __m128i*>(p));
}
TRICYL_ALWAYS_INLINE __m128i ld4(const char* p) {
  int v;
  std::memcpy(&v, p, sizeof v);
  return _mm_cvtsi32_si128(v);
}

template <class S>
TRICYL_ALWAYS_INLINE bool gateBitsOk(const Cylinder<S>& cyl,
                                     const Pose<S>& pose,
                                     const Triangle<S>& tri) {
  const char* T = reinterpret_cast<const char*>(&tri);
  const char* P = reinterpret_cast<const char*>(&pose);
  const char* C = reinterpret_cast<const char*>(&cyl);
  const __m128i k = GateBits<S>::mask();
  auto top = [k](__m128i v) { return _mm_and_si128(v, k); };
  auto mx = [](__m128i u, __m128i v) { return _mm_max_epi16(u, v); };
  __m128i len, rot;
  if constexpr (sizeof(S) == 8) {  // R: bytes 0..71, t: 72..95
    len = mx(mx(top(ld16(T)), top(ld16(T + 16))),
             mx(top(ld16(T + 32)), top(ld16(T + 48))));
    len =
        mx(mx(len, top(ld8(T + 64))), mx(top(ld16(P + 72)), top(ld8(P + 88))));
    len = mx(len, top(ld16(C)));
    rot = mx(mx(top(ld16(P)), top(ld16(P + 16))),
             mx(top(ld16(P + 32)), top(ld16(P + 48))));
    rot = mx(rot, top(ld8(P + 64)));
  } else {  // R: bytes 0..35, t: 36..47
    len = mx(mx(top(ld16(T)), top(ld16(T + 16))), top(ld4(T + 32)));
    len = mx(mx(len, top(ld4(P + 36))), mx(top(ld8(P + 40)), top(ld8(C))));
    rot = mx(mx(top(ld16(P)), top(ld16(P + 16))), top(ld4(P + 32)));
  }
  const __m128i bad =
      _mm_or_si128(_mm_cmpgt_epi16(len, _mm_set1_epi16(GateBits<S>::kLen)),
                   _mm_cmpgt_epi16(rot, _mm_set1_epi16(GateBits<S>::kRot)));
  return _mm_movemask_epi8(bad) == 0;
}

template <class S>
TRICYL_ALWAYS_INLINE Pre prologue(const Cylinder<S>& cyl, const Pose<S>& pose,
                                  const Triangle<S>& tri, Local* L) {
  if (!gateBitsOk(cyl, pose, tri)) return Pre::kGateMiss;
  const double r = double(cyl.radius), H = double(cyl.lz);
  if (!(r >= 0) || !(H >= 0)) return Pre::kGateMiss;  // finite: no trap
  const __m128d abs = _mm_castsi128_pd(_mm_set1_epi64x(0x7fffffffffffffffLL));
  // Rotation: rows 0..2, columns (0, 1) packed, column 2 as (R02, R12), R22.
  const __m128d R0 = load2(&pose.R[0][0]), R1 = load2(&pose.R[1][0]),
                R2 = load2(&pose.R[2][0]);
  const __m128d R2c =
      _mm_unpacklo_pd(load1(&pose.R[0][2]), load1(&pose.R[1][2]));
  const __m128d R22 = load1(&pose.R[2][2]);
  const __m128d a0 = _mm_and_pd(R0, abs), a1 = _mm_and_pd(R1, abs),
                a2 = _mm_and_pd(R2, abs), a3 = _mm_and_pd(R2c, abs),
                a4 = _mm_and_pd(R22, abs);
  __m128d rho2 = _mm_max_pd(_mm_max_pd(a0, a1), _mm_max_pd(a2, a3));
  rho2 = _mm_max_sd(_mm_max_sd(rho2, _mm_unpackhi_pd(rho2, rho2)), a4);
  const double rho = _mm_cvtsd_f64(rho2);

  const __m128d txy = load2(&pose.t.x), tz = load1(&pose.t.z);
  const __m128d rr = _mm_set1_pd(r), HH = _mm_set1_pd(H);
  const __m128d neg = _mm_set1_pd(-0.0);
  const __m128d negZ = _mm_set_pd(-0.0, 0.0);  // (Z, -Z)
  const Vec3<S>* P[3] = {&tri.a, &tri.b, &tri.c};
  __m128d pos_all = _mm_castsi128_pd(_mm_set1_epi32(-1));
  __m128d neg_all = pos_all, z_all = pos_all;
  __m128d vin = _mm_setzero_pd();
  const __m128d r2 = _mm_set_sd(r * r);  // FilterKernel: r2 = {r r, r r}
  for (int i = 0; i < 3; ++i) {
    const __m128d dxy = _mm_sub_pd(load2(&P[i]->x), txy);
    const __m128d dz = _mm_sub_sd(load1(&P[i]->z), tz);
    const __m128d axy = _mm_and_pd(dxy, abs);
    const __m128d s = _mm_add_sd(_mm_add_sd(axy, _mm_unpackhi_pd(axy, axy)),
                                 _mm_and_pd(dz, abs));
    const __m128d bx = _mm_unpacklo_pd(dxy, dxy),
                  by = _mm_unpackhi_pd(dxy, dxy), bz = _mm_unpacklo_pd(dz, dz);
    const __m128d xy = _mm_add_pd(
        _mm_add_pd(_mm_mul_pd(R0, bx), _mm_mul_pd(R1, by)), _mm_mul_pd(R2, bz));
    const __m128d zz = _mm_mul_pd(R2c, dxy);  // (R02 d0, R12 d1)
    const __m128d z = _mm_add_sd(_mm_add_sd(zz, _mm_unpackhi_pd(zz, zz)),
                                 _mm_mul_sd(R22, dz));
    const __m128d Z = _mm_add_sd(z, z);
    const double m = rho * _mm_cvtsd_f64(s);
    _mm_storel_pd(&L->x[i], xy);
    _mm_storeh_pd(&L->y[i], xy);
    L->Z[i] = _mm_cvtsd_f64(Z);
    L->m[i] = m;
    // Early-outs with the magnitude 2 s >= m (see prologueAvx2).
    const double me = _mm_cvtsd_f64(_mm_add_sd(s, s));
    const __m128d bxy = _mm_set1_pd((me + r) * kRel + kAbs);
    const __m128d bze = _mm_set1_pd(((me + me) + H) * kRel + kAbs);
    const __m128d bzz = _mm_set1_pd(((m + m) + H) * kRel + kAbs);
    pos_all = _mm_and_pd(pos_all, _mm_cmplt_pd(bxy, _mm_sub_pd(xy, rr)));
    neg_all = _mm_and_pd(
        neg_all, _mm_cmplt_pd(bxy, _mm_sub_pd(_mm_xor_pd(xy, neg), rr)));
    const __m128d ZH = _mm_sub_pd(_mm_xor_pd(_mm_unpacklo_pd(Z, Z), negZ), HH);
    z_all = _mm_and_pd(z_all, _mm_cmplt_pd(bze, ZH));
    // (V): in the slab (fl(Z - H) < -b and fl(-Z - H) < -b, i.e.
    // fl(Z + H) > b) and fl(fl(r2 - x x) - y y) > b' with the magnitude
    // fl(fl(r2 + m m) + m m), as triangleCylinderTests evaluates it.
    const __m128d slab = _mm_cmplt_pd(ZH, _mm_xor_pd(bzz, neg));
    const __m128d xy2 = _mm_mul_pd(xy, xy);
    const __m128d v =
        _mm_sub_sd(_mm_sub_sd(r2, xy2), _mm_unpackhi_pd(xy2, xy2));
    const double mm = m * m;
    const __m128d bv = _mm_set_sd(((r * r + mm) + mm) * kRel + kAbs);
    vin =
        _mm_or_pd(vin, _mm_and_pd(_mm_and_pd(slab, _mm_unpackhi_pd(slab, slab)),
                                  _mm_cmpgt_sd(v, bv)));
  }
  L->r = r;
  L->H = H;
  const int beyond =
      _mm_movemask_pd(_mm_or_pd(_mm_or_pd(pos_all, neg_all), z_all));
  if (beyond != 0) return Pre::kEarlyOut;
  return (_mm_movemask_pd(vin) & 1) != 0 ? Pre::kHit : Pre::kOpen;
}
#else
// Portable version: the bit-level validate() and rangeGateOk() of
// decideSlow (float inputs widened first), then the same arithmetic.
template <class S>
TRICYL_ALWAYS_INLINE Pre prologue(const Cylinder<S>& cyl, const Pose<S>& pose,
                                  const Triangle<S>& tri, Local* L) {
  Widened w;
  if constexpr (std::is_same_v<S, float>) {
    if (!floatBitsFinite(cyl, pose, tri)) return Pre::kGateMiss;
    w = widen(cyl, pose, tri);
  } else {
    w = {cyl, pose, tri};
  }
  double max_len = 0, rho = 0;
  if (!validate(Inputs{w.cyl, w.pose, w.tri}, &max_len, &rho) ||
      !detail::rangeGateOk(max_len, rho))
    return Pre::kGateMiss;
  const auto& R = w.pose.R;
  const double r = w.cyl.radius, H = w.cyl.lz;
  L->r = r;
  L->H = H;
  const Vec3<double>* P[3] = {&w.tri.a, &w.tri.b, &w.tri.c};
  unsigned beyond = 63;
  bool vin = false;
  const double r2 = r * r;
  for (int i = 0; i < 3; ++i) {
    const double d0 = P[i]->x - w.pose.t.x, d1 = P[i]->y - w.pose.t.y,
                 d2 = P[i]->z - w.pose.t.z;
    const double s = std::fabs(d0) + std::fabs(d1) + std::fabs(d2);
    const double x = R[0][0] * d0 + R[1][0] * d1 + R[2][0] * d2;
    const double y = R[0][1] * d0 + R[1][1] * d1 + R[2][1] * d2;
    const double z = R[0][2] * d0 + R[1][2] * d1 + R[2][2] * d2;
    const double Z = z + z, m = rho * s;
    L->x[i] = x;
    L->y[i] = y;
    L->Z[i] = Z;
    L->m[i] = m;
    // Early-outs with the magnitude 2 s >= m (see prologueAvx2).
    const double me = s + s;
    const double bze = ((me + me) + H) * kRel + kAbs;
    const double bx = (me + r) * kRel + kAbs;
    beyond &= unsigned(Z - H > bze) | unsigned(-Z - H > bze) << 1 |
              unsigned(x - r > bx) << 2 | unsigned(-x - r > bx) << 3 |
              unsigned(y - r > bx) << 4 | unsigned(-y - r > bx) << 5;
    const double bz = ((m + m) + H) * kRel + kAbs;
    const double mm = m * m;
    vin |= (Z - H < -bz) & (Z + H > bz) &
           ((r2 - x * x) - y * y > ((r2 + mm) + mm) * kRel + kAbs);
  }
  if (beyond != 0) return Pre::kEarlyOut;
  return vin ? Pre::kHit : Pre::kOpen;
}
#endif

#if TRICYL_FAST_AVX2
// The same prologue with AVX2 (chosen at run time), lanes = the three
// vertices (lane 3 repeats vertex 2, so "all lanes" and "any lane" are
// "all vertices" and "any vertex"). Every lane operation is the scalar IEEE
// operation of the portable version in the same order (no FMA: the target
// is "avx2" only and -ffp-contract=off), so the local coordinates are those
// of the SSE2 and portable versions, bit for bit; its bounds are theirs or
// larger (the magnitude 2 s, see prologueAvx2Body).
#define TRICYL_AVX2_FN __attribute__((target("avx2"), always_inline)) inline
// (a, b, c, c) and (v, v, v, v); the AVX2 arithmetic reads doubles only
// (float inputs are widened first, in prologueAvx2).
TRICYL_AVX2_FN __m256d lanes(const double& a, const double& b,
                             const double& c) {
  return _mm256_set_pd(c, c, b, a);
}
TRICYL_AVX2_FN __m256d bcast(const double& v) {
  return _mm256_broadcast_sd(&v);  // a load, not a shuffle
}

// The gate of gateBitsOk in 256-bit registers (the same admitted set, fewer
// instructions): |x| < 2^40 iff the bits of |x| (sign cleared) are <=
// 0x426f ffff ffff ffff (double) or 0x537f ffff (float), and |R_jk| < 2 iff
// they are <= 0x3fff ffff ffff ffff or 0x3fff ffff; non-negative bit
// patterns order like their values under a signed comparison, and NaN and
// Inf (exponent all ones) exceed both limits. Double compares the top 16
// bits of each word after 16-bit maxima (as gateBitsOk does) and also reads
// the signs of r and lz; float compares whole words. Every load stays inside
// the aggregates (the static_asserts above pin their layout).
__attribute__((target("avx2"), always_inline)) inline __m256i ld32(
    const char* p) {
  return _mm256_loadu_si256(reinterpret_cast<const __m256i*>(p));
}
// v & top: the bits of each word the double gate compares.
__attribute__((target("avx2"), always_inline)) inline __m256i andTop(
    __m256i top, __m256i v) {
  return _mm256_and_si256(v, top);
}

template <class S>
__attribute__((target("avx2"), always_inline)) inline bool gateBitsOkAvx2(
    const Cylinder<S>& cyl, const Pose<S>& pose, const Triangle<S>& tri) {
  const char* T = reinterpret_cast<const char*>(&tri);
  const char* P = reinterpret_cast<const char*>(&pose);
  const char* C = reinterpret_cast<const char*>(&cyl);
  __m256i bad;
  __m128i bad2;
  if constexpr (sizeof(S) == 8) {
    // T: ax ay az bx | by bz cx cy | cz;  P: R00 R01 R02 R10 | R11 R12 R20 R21
    // | R22 tx ty tz;  C: r lz. Each 64-bit word keeps only its top 16 bits,
    // sign cleared (|x| < 2^40 iff they are <= 0x426f, |R_jk| < 2 iff <=
    // 0x3fff: the limits' low 48 bits are all ones), so that 16-bit maxima
    // merge the words with the same limit before one compare (the other
    // 16-bit lanes are 0). And r, lz >= 0 (-0 passes): the bits with the sign
    // flipped are > 0 as a signed word only for a negative non-zero value.
    const __m256i top = _mm256_set1_epi64x(0x7fff000000000000LL);
    const __m256i len = _mm256_set1_epi64x(0x426fLL << 48);
    const __m256i rot = _mm256_set1_epi64x(0x3fffLL << 48);
    const __m256i mix = _mm256_blend_epi32(len, rot, 0x03);  // (rot, len x3)
    const __m128i c = ld16(C);
    const __m128i hi2 = _mm256_castsi256_si128(top);
    const __m256i lens = _mm256_max_epi16(
        _mm256_max_epi16(andTop(top, ld32(T)), andTop(top, ld32(T + 32))),
        _mm256_zextsi128_si256(_mm_max_epi16(_mm_and_si128(c, hi2),
                                             _mm_and_si128(ld8(T + 64), hi2))));
    const __m256i rots =
        _mm256_max_epi16(andTop(top, ld32(P)), andTop(top, ld32(P + 32)));
    const __m128i negative = _mm_cmpgt_epi64(
        _mm_xor_si128(c, _mm_set1_epi64x(std::int64_t(0x8000000000000000ULL))),
        _mm_setzero_si128());
    bad = _mm256_or_si256(_mm256_or_si256(_mm256_cmpgt_epi16(lens, len),
                                          _mm256_cmpgt_epi16(rots, rot)),
                          _mm256_cmpgt_epi16(andTop(top, ld32(P + 64)), mix));
    bad2 = negative;
  } else {
    // T: ax ay az bx by bz cx cy | cz;  P: R00 .. R21 | R22 tx ty tz;
    // C: r lz.
    const __m256i a = _mm256_set1_epi32(0x7fffffff);
    const __m256i len = _mm256_set1_epi32(0x537fffff);
    const __m256i rot = _mm256_set1_epi32(0x3fffffff);
    const __m128i a2 = _mm256_castsi256_si128(a);
    const __m128i len2 = _mm256_castsi256_si128(len);
    const __m128i mix2 = _mm_blend_epi32(len2, _mm256_castsi256_si128(rot), 1);
    bad =
        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_and_si256(ld32(T), a), len),
                        _mm256_cmpgt_epi32(_mm256_and_si256(ld32(P), a), rot));
    const __m128i rest = _mm_unpacklo_epi64(ld8(C), ld4(T + 32));  // r lz cz 0
    bad2 = _mm_or_si128(_mm_cmpgt_epi32(_mm_and_si128(ld16(P + 32), a2), mix2),
                        _mm_cmpgt_epi32(_mm_and_si128(rest, a2), len2));
  }
  return (_mm256_testz_si256(bad, bad) & _mm_testz_si128(bad2, bad2)) != 0;
}

// FilterKernel::sign's bound for the magnitude m, lane by lane.
__attribute__((target("avx2"), always_inline)) inline __m256d bound(
    __m256d m, __m256d k_rel, __m256d k_abs) {
  return _mm256_add_pd(_mm256_mul_pd(m, k_rel), k_abs);
}

// The per-edge quantities shared by the lane tests below, computed once:
// lanes = edges (0,1), (1,2), (2,0) (lane 3 repeats (2,0)), from vertex lanes
// x, y, Z and the per-vertex magnitude `me` (Z: 2 me). Each pair is an Fd,
// value and magnitude, evaluated as the kernel evaluates it.
struct EdgeLanes {
  __m256d xj, yj, Zj, mj;  // the edge's second end (lanes (1, 2, 0, 0))
  __m256d ex, ey, mE;      // P_j - P_i, magnitude m_j + m_i
  __m256d L, mL;           // ex ex + ey ey
  __m256d o, mo;           // x_i y_j - x_j y_i (the (A) orientation, (E)'s c)
};

__attribute__((target("avx2"), always_inline)) inline EdgeLanes edgeLanes(
    __m256d x, __m256d y, __m256d Z, __m256d me) {
  constexpr int kNext = 0x09;  // lanes (1, 2, 0, 0)
  EdgeLanes e;
  e.xj = _mm256_permute4x64_pd(x, kNext);
  e.yj = _mm256_permute4x64_pd(y, kNext);
  e.Zj = _mm256_permute4x64_pd(Z, kNext);
  e.mj = _mm256_permute4x64_pd(me, kNext);
  e.ex = _mm256_sub_pd(e.xj, x);
  e.ey = _mm256_sub_pd(e.yj, y);
  e.mE = _mm256_add_pd(e.mj, me);
  e.L = _mm256_add_pd(_mm256_mul_pd(e.ex, e.ex), _mm256_mul_pd(e.ey, e.ey));
  e.mL = _mm256_add_pd(_mm256_mul_pd(e.mE, e.mE), _mm256_mul_pd(e.mE, e.mE));
  e.o = _mm256_sub_pd(_mm256_mul_pd(x, e.yj), _mm256_mul_pd(e.xj, y));
  e.mo = _mm256_add_pd(_mm256_mul_pd(me, e.mj), _mm256_mul_pd(e.mj, me));
  return e;
}

// Test (E) of the kernel for the three edges at once, branch-free, with the
// magnitude `me` per vertex (Z: 2 me): the closest point of edge (i, j)'s
// projection to the axis is interior, within r of it, and inside the slab.
// The same Fd expressions as triangleCylinderTests, values and magnitudes in
// separate registers, except the slab condition: here H L -+ (Z_i L +
// g (Z_j - Z_i)), the kernel's (H -+ Z_i) L -+ g (Z_j - Z_i), the same
// polynomial grouped so that an edge in a cap plane is an exact 0. Each is a
// certified sign of that polynomial, so the lanes still decide only what is
// true; every one of the six signs must be certain. (Eberly's polygon test "an
// edge within r of the origin", on an unclipped edge.)
__attribute__((target("avx2"), always_inline)) inline bool edgeHitAvx2(
    const EdgeLanes& e, __m256d x, __m256d y, __m256d Z, __m256d me, __m256d r2,
    __m256d HH) {
  const __m256d kr = _mm256_set1_pd(kRel), ka = _mm256_set1_pd(kAbs);
  const __m256d m2 = _mm256_add_pd(me, me), m2j = _mm256_add_pd(e.mj, e.mj);
  // r2 L - c c, with c = o.
  const __m256d near_ =
      _mm256_sub_pd(_mm256_mul_pd(r2, e.L), _mm256_mul_pd(e.o, e.o));
  const __m256d mnear =
      _mm256_add_pd(_mm256_mul_pd(r2, e.mL), _mm256_mul_pd(e.mo, e.mo));
  // g = -(x_i ex + y_i ey), L - g.
  const __m256d g = _mm256_xor_pd(
      _mm256_add_pd(_mm256_mul_pd(x, e.ex), _mm256_mul_pd(y, e.ey)),
      _mm256_set1_pd(-0.0));
  const __m256d mg =
      _mm256_add_pd(_mm256_mul_pd(me, e.mE), _mm256_mul_pd(me, e.mE));
  const __m256d Lg = _mm256_sub_pd(e.L, g);
  const __m256d mLg = _mm256_add_pd(e.mL, mg);
  // zL = Z_i L + g (Z_j - Z_i), HL = H L; HL - zL and HL + zL.
  const __m256d zL = _mm256_add_pd(_mm256_mul_pd(Z, e.L),
                                   _mm256_mul_pd(g, _mm256_sub_pd(e.Zj, Z)));
  const __m256d mzL = _mm256_add_pd(_mm256_mul_pd(m2, e.mL),
                                    _mm256_mul_pd(mg, _mm256_add_pd(m2j, m2)));
  const __m256d HL = _mm256_mul_pd(HH, e.L);
  const __m256d bHz =
      bound(_mm256_add_pd(_mm256_mul_pd(HH, e.mL), mzL), kr, ka);
  __m256d ok = _mm256_cmp_pd(e.L, bound(e.mL, kr, ka), _CMP_GT_OQ);
  ok =
      _mm256_and_pd(ok, _mm256_cmp_pd(near_, bound(mnear, kr, ka), _CMP_GT_OQ));
  ok = _mm256_and_pd(ok, _mm256_cmp_pd(g, bound(mg, kr, ka), _CMP_GT_OQ));
  ok = _mm256_and_pd(ok, _mm256_cmp_pd(Lg, bound(mLg, kr, ka), _CMP_GT_OQ));
  ok = _mm256_and_pd(ok, _mm256_cmp_pd(_mm256_sub_pd(HL, zL), bHz, _CMP_GT_OQ));
  ok = _mm256_and_pd(ok, _mm256_cmp_pd(_mm256_add_pd(HL, zL), bHz, _CMP_GT_OQ));
  return _mm256_movemask_pd(ok) != 0;
}

// edgeSeparates (below) for the three edges at once, branch-free, with the
// magnitude `me` per vertex: the same Fd expressions, values and magnitudes
// in separate registers, so a lane it reports is a separation
// FilterKernel::sign certifies (docs/exactness.md, "Edge separation").
// A2 = (o01 + o12) + o20 (twice the projected area, the kernel's (A)
// grouping) in every lane, and its magnitude (FilterKernel).
__attribute__((target("avx2"), always_inline)) inline void areaLanes(
    const EdgeLanes& e, __m256d* A2, __m256d* mA) {
  *A2 = _mm256_add_pd(_mm256_add_pd(_mm256_permute4x64_pd(e.o, 0x00),
                                    _mm256_permute4x64_pd(e.o, 0x55)),
                      _mm256_permute4x64_pd(e.o, 0xaa));
  *mA = _mm256_add_pd(_mm256_add_pd(_mm256_permute4x64_pd(e.mo, 0x00),
                                    _mm256_permute4x64_pd(e.mo, 0x55)),
                      _mm256_permute4x64_pd(e.mo, 0xaa));
}

// A2, mA: areaLanes(e).
__attribute__((target("avx2"), always_inline)) inline bool edgeSeparatesAvx2(
    const EdgeLanes& e, __m256d A2, __m256d mA, __m256d r2) {
  const __m256d kr = _mm256_set1_pd(kRel), ka = _mm256_set1_pd(kAbs);
  const __m256d neg = _mm256_set1_pd(-0.0);
  const __m256d bA = bound(mA, kr, ka);
  const __m256d bo = bound(e.mo, kr, ka);
  // The origin strictly beyond edge i's line: sign(o_i) = -sign(A2) != 0.
  const __m256d outside = _mm256_or_pd(
      _mm256_and_pd(_mm256_cmp_pd(A2, bA, _CMP_GT_OQ),
                    _mm256_cmp_pd(e.o, _mm256_xor_pd(bo, neg), _CMP_LT_OQ)),
      _mm256_and_pd(_mm256_cmp_pd(A2, _mm256_xor_pd(bA, neg), _CMP_LT_OQ),
                    _mm256_cmp_pd(e.o, bo, _CMP_GT_OQ)));
  // ... and farther than r from it: o^2 - r2 L > 0.
  const __m256d d =
      _mm256_sub_pd(_mm256_mul_pd(e.o, e.o), _mm256_mul_pd(r2, e.L));
  const __m256d md =
      _mm256_add_pd(_mm256_mul_pd(e.mo, e.mo), _mm256_mul_pd(r2, e.mL));
  const __m256d distant = _mm256_cmp_pd(d, bound(md, kr, ka), _CMP_GT_OQ);
  return _mm256_movemask_pd(_mm256_and_pd(outside, distant)) != 0;
}

// Test (X)'s value r^2 W^2 - X^2 - Y^2 for the cap plane with a_k = Z_k -+ H
// (lanes = edges: X = x_i a_j - x_j a_i, Y likewise, W = a_j - a_i), and
// its magnitude, the same for both planes: with ma_k = 2 m_k + H,
// X and Y have m_i ma_j + m_j ma_i and W has ma_j + ma_i.
__attribute__((target("avx2"), always_inline)) inline __m256d capValue(
    const EdgeLanes& e, __m256d x, __m256d y, __m256d a, __m256d r2) {
  constexpr int kNext = 0x09;  // lanes (1, 2, 0, 0): the edge's second end
  const __m256d aj = _mm256_permute4x64_pd(a, kNext);
  const __m256d X = _mm256_sub_pd(_mm256_mul_pd(x, aj), _mm256_mul_pd(e.xj, a));
  const __m256d Y = _mm256_sub_pd(_mm256_mul_pd(y, aj), _mm256_mul_pd(e.yj, a));
  const __m256d W = _mm256_sub_pd(aj, a);
  return _mm256_sub_pd(_mm256_sub_pd(_mm256_mul_pd(r2, _mm256_mul_pd(W, W)),
                                     _mm256_mul_pd(X, X)),
                       _mm256_mul_pd(Y, Y));
}
__attribute__((target("avx2"), always_inline)) inline __m256d capMagnitude(
    const EdgeLanes& e, __m256d m, __m256d ma, __m256d r2) {
  constexpr int kNext = 0x09;
  const __m256d maj = _mm256_permute4x64_pd(ma, kNext);
  const __m256d mX =
      _mm256_add_pd(_mm256_mul_pd(m, maj), _mm256_mul_pd(e.mj, ma));
  const __m256d mW = _mm256_add_pd(maj, ma);
  return _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(r2, _mm256_mul_pd(mW, mW)),
                                     _mm256_mul_pd(mX, mX)),
                       _mm256_mul_pd(mX, mX));
}

// Test (X) of the kernel for the six edge/cap-plane crossings, branch-free,
// lanes = edges: the same Fd expressions as triangleCylinderTests, value and
// magnitude in separate registers, in the same order, so each "true" is a
// sign the kernel certifies. For the plane Z = sH, a_k = Z_k - sH with
// magnitude ma_k = fl(2 m_k + H); the edge crosses it strictly iff a_i, a_j
// have certified opposite signs, at the point (X, Y) / W with
//   X = x_i a_j - x_j a_i,  Y = y_i a_j - y_j a_i,  W = a_j - a_i,
// inside the cap disk iff fl(fl(r2 (W W) - X X) - Y Y) is certainly >= 0.
// True iff some crossing is certainly inside its cap disk: the triangle and
// the cylinder then share that point. (Eberly's cases 3b-5: the clipped
// polygon's vertex on a cap.) Anything undecided is left to the kernel.
__attribute__((target("avx2"), always_inline)) inline bool capCrossingHit(
    const EdgeLanes& e, __m256d x, __m256d y, __m256d m, __m256d Z,
    __m256d a_top, __m256d ba, __m256d r2, __m256d HH) {
  constexpr int kNext = 0x09;  // lanes (1, 2, 0, 0): the edge's second end
  const __m256d kr = _mm256_set1_pd(kRel), ka = _mm256_set1_pd(kAbs);
  const __m256d neg = _mm256_set1_pd(-0.0);
  const __m256d ma = _mm256_add_pd(_mm256_add_pd(m, m), HH);
  const __m256d baj = _mm256_permute4x64_pd(ba, kNext);
  const __m256d nba = _mm256_xor_pd(ba, neg), nbaj = _mm256_xor_pd(baj, neg);
  const __m256d be = bound(capMagnitude(e, m, ma, r2), kr, ka);
  __m256d hit = _mm256_setzero_pd();
  for (int s = 0; s < 2; ++s) {
    const __m256d a = s == 0 ? a_top : _mm256_add_pd(Z, HH);  // Z - H, Z + H
    const __m256d aj = _mm256_permute4x64_pd(a, kNext);
    const __m256d cross =
        _mm256_or_pd(_mm256_and_pd(_mm256_cmp_pd(a, nba, _CMP_LT_OQ),
                                   _mm256_cmp_pd(aj, baj, _CMP_GT_OQ)),
                     _mm256_and_pd(_mm256_cmp_pd(a, ba, _CMP_GT_OQ),
                                   _mm256_cmp_pd(aj, nbaj, _CMP_LT_OQ)));
    const __m256d v = capValue(e, x, y, a, r2);
    hit = _mm256_or_pd(hit,
                       _mm256_and_pd(cross, _mm256_cmp_pd(v, be, _CMP_GT_OQ)));
  }
  return _mm256_movemask_pd(hit) != 0;
}

// The arithmetic of the prologue, on double inputs that passed the gate.
__attribute__((target("avx2"), always_inline)) inline Pre prologueAvx2Body(
    const Pose<double>& pose, const Triangle<double>& tri, double r, double H,
    Local* L) {
  const __m256d abs =
      _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  const __m256d neg = _mm256_set1_pd(-0.0);
  const auto& R = pose.R;

  const __m256d d0 =
      _mm256_sub_pd(lanes(tri.a.x, tri.b.x, tri.c.x), bcast(pose.t.x));
  const __m256d d1 =
      _mm256_sub_pd(lanes(tri.a.y, tri.b.y, tri.c.y), bcast(pose.t.y));
  const __m256d d2 =
      _mm256_sub_pd(lanes(tri.a.z, tri.b.z, tri.c.z), bcast(pose.t.z));
  const __m256d s = _mm256_add_pd(
      _mm256_add_pd(_mm256_and_pd(d0, abs), _mm256_and_pd(d1, abs)),
      _mm256_and_pd(d2, abs));
  // The early-outs use the magnitude 2 s >= rho s = m (the gate admits only
  // |R_jk| < 2, and rounding is monotone: fl(rho s) <= fl(2 s) = 2 s), which
  // needs no rho; every bound below is >= the kernel's, so each early-out is
  // one the kernel takes. m itself is computed only if they fail.
  const __m256d me = _mm256_add_pd(s, s);
  const __m256d x =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(bcast(R[0][0]), d0),
                                  _mm256_mul_pd(bcast(R[1][0]), d1)),
                    _mm256_mul_pd(bcast(R[2][0]), d2));
  const __m256d y =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(bcast(R[0][1]), d0),
                                  _mm256_mul_pd(bcast(R[1][1]), d1)),
                    _mm256_mul_pd(bcast(R[2][1]), d2));
  const __m256d z =
      _mm256_add_pd(_mm256_add_pd(_mm256_mul_pd(bcast(R[0][2]), d0),
                                  _mm256_mul_pd(bcast(R[1][2]), d1)),
                    _mm256_mul_pd(bcast(R[2][2]), d2));
  const __m256d Z = _mm256_add_pd(z, z);

  const __m256d rr = _mm256_set1_pd(r), HH = _mm256_set1_pd(H);
  const __m256d kr = _mm256_set1_pd(kRel), ka = _mm256_set1_pd(kAbs);
  const __m256d bx =
      _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(me, rr), kr), ka);
  const __m256d bze = _mm256_add_pd(
      _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(me, me), HH), kr), ka);
  // A plane x = r or x = -r separates iff every vertex has fl(|x| - r) > b
  // (fl(|x| - r) is fl(x - r) for x > 0 and fl(-x - r) for x < 0: rounding
  // is symmetric) and the three x have the same sign (sign bits 0 or 15; x =
  // +-0 never passes the first test). Likewise y, and Z with H.
  const __m256d zt = _mm256_sub_pd(Z, HH);  // Z - H
  const int cx = _mm256_movemask_pd(
      _mm256_cmp_pd(_mm256_sub_pd(_mm256_and_pd(x, abs), rr), bx, _CMP_GT_OQ));
  const int cy = _mm256_movemask_pd(
      _mm256_cmp_pd(_mm256_sub_pd(_mm256_and_pd(y, abs), rr), bx, _CMP_GT_OQ));
  const int cz = _mm256_movemask_pd(
      _mm256_cmp_pd(_mm256_sub_pd(_mm256_and_pd(Z, abs), HH), bze, _CMP_GT_OQ));
  const int sx = _mm256_movemask_pd(x), sy = _mm256_movemask_pd(y),
            sz = _mm256_movemask_pd(Z);
  auto same = [](int sgn) { return (sgn == 0) | (sgn == 15); };
  const int early = ((cx == 15) & same(sx)) | ((cy == 15) & same(sy)) |
                    ((cz == 15) & same(sz));

  // (V), then (X), also with the magnitude 2 s >= m: a looser bound is still
  // a valid one, and the few queries it leaves undecided (a vertex or a
  // crossing within about 2^-45 relative of the boundary) are decided by the
  // remaining tests, which re-run (V) and (X) with the per-vertex m.
  // (V) is evaluated whether or not an early-out applies, and one branch
  // takes both (85 % of uniform queries): the outcome of a query is not
  // predictable from the previous ones, and a mispredicted branch here costs
  // more than (V)'s 20 instructions (uniform, cases in an order the predictor
  // cannot learn, Zen 3: 42 ns, about 9x FCL's MPR at 385 ns, before; 33 ns,
  // 11.4x, after, bench_triangle_cylinder interleaved with FCL). Both can
  // never hold (a vertex certainly inside is not certainly beyond a plane
  // that bounds the solid); the early-out is reported first either way.
  const __m256d zb = _mm256_sub_pd(_mm256_xor_pd(Z, neg), HH);  // -Z - H
  const __m256d nbz = _mm256_xor_pd(bze, neg);
  const __m256d slab = _mm256_and_pd(_mm256_cmp_pd(zt, nbz, _CMP_LT_OQ),
                                     _mm256_cmp_pd(zb, nbz, _CMP_LT_OQ));
  const __m256d r2 = _mm256_set1_pd(r * r);
  const __m256d mm = _mm256_mul_pd(me, me);
  const __m256d v = _mm256_sub_pd(_mm256_sub_pd(r2, _mm256_mul_pd(x, x)),
                                  _mm256_mul_pd(y, y));
  const __m256d bv = _mm256_add_pd(
      _mm256_mul_pd(_mm256_add_pd(_mm256_add_pd(r2, mm), mm), kr), ka);
  const int vin =
      _mm256_movemask_pd(_mm256_and_pd(slab, _mm256_cmp_pd(v, bv, _CMP_GT_OQ)));
  if ((early | vin) != 0) return Pre(int(Pre::kHit) - early);
  const EdgeLanes e = edgeLanes(x, y, Z, me);
  if (capCrossingHit(e, x, y, me, Z, zt, bze, r2, HH)) return Pre::kHit;
  __m256d A2, mA;
  areaLanes(e, &A2, &mA);
  if (edgeSeparatesAvx2(e, A2, mA, r2)) return Pre::kDisjoint;
  if (edgeHitAvx2(e, x, y, Z, me, r2, HH)) return Pre::kHit;

  // rho = max |R_jk|, the same value as the scalar max.
  const __m256d r0 =
      _mm256_and_pd(_mm256_set_pd(double(R[1][0]), double(R[0][2]),
                                  double(R[0][1]), double(R[0][0])),
                    abs);
  const __m256d r1 =
      _mm256_and_pd(_mm256_set_pd(double(R[2][1]), double(R[2][0]),
                                  double(R[1][2]), double(R[1][1])),
                    abs);
  const __m256d rm = _mm256_max_pd(r0, r1);
  __m128d rh =
      _mm_max_pd(_mm256_castpd256_pd128(rm), _mm256_extractf128_pd(rm, 1));
  rh = _mm_max_sd(
      _mm_max_sd(rh, _mm_unpackhi_pd(rh, rh)),
      _mm_and_pd(_mm_set1_pd(double(R[2][2])), _mm256_castpd256_pd128(abs)));
  const __m256d rho = _mm256_broadcastsd_pd(rh);
  _mm256_storeu_pd(L->x, x);  // only the remaining tests read L
  _mm256_storeu_pd(L->y, y);
  _mm256_storeu_pd(L->Z, Z);
  _mm256_storeu_pd(L->m, _mm256_mul_pd(rho, s));
  L->r = r;
  L->H = H;
  return Pre::kOpen;
}

// The gate, then the arithmetic in double. Float inputs (finite: the gate
// read their bits) are widened once, exactly, by vector conversions into
// double aggregates of the same layout, so the arithmetic reads doubles.
template <class S>
__attribute__((target("avx2"))) inline Pre prologueAvx2(const Cylinder<S>& cyl,
                                                        const Pose<S>& pose,
                                                        const Triangle<S>& tri,
                                                        Local* L) {
  if (!gateBitsOkAvx2(cyl, pose, tri)) return Pre::kGateMiss;
  const double r = double(cyl.radius), H = double(cyl.lz);
  if constexpr (sizeof(S) == 4) {  // (double: the gate read the signs)
    if (!(r >= 0) || !(H >= 0)) return Pre::kGateMiss;  // finite: no trap
  }
  if constexpr (sizeof(S) == 8) {
    return prologueAvx2Body(pose, tri, r, H, L);
  } else {
    static_assert(sizeof(Pose<double>) == 12 * sizeof(double) &&
                  sizeof(Triangle<double>) == 9 * sizeof(double));
    // Byte-wise views of the float aggregates (pinned layout above), and
    // buffers that become the double aggregates by memcpy.
    const char* p = reinterpret_cast<const char*>(&pose);
    const char* t = reinterpret_cast<const char*>(&tri);
    auto ld4f = [](const char* q) {
      __m128 v;
      std::memcpy(&v, q, sizeof v);
      return v;
    };
    alignas(32) double P[12], T[12];
    _mm256_store_pd(P, _mm256_cvtps_pd(ld4f(p)));
    _mm256_store_pd(P + 4, _mm256_cvtps_pd(ld4f(p + 16)));
    _mm256_store_pd(P + 8, _mm256_cvtps_pd(ld4f(p + 32)));
    _mm256_store_pd(T, _mm256_cvtps_pd(ld4f(t)));
    _mm256_store_pd(T + 4, _mm256_cvtps_pd(ld4f(t + 16)));
    T[8] = double(tri.c.z);
    Pose<double> pd;
    Triangle<double> td;
    std::memcpy(&pd, P, sizeof pd);
    std::memcpy(&td, T, sizeof td);
    return prologueAvx2Body(pd, td, r, H, L);
  }
}
// dwFrame in lanes (lanes = vertices a, b, c, c), for CPUs with AVX2 and
// FMA: every lane runs dwCoordinate's operations in its order, the
// TwoProduct by FMA (exact, as Dekker's: the same bits), so the frame is
// the scalar one bit for bit.
__attribute__((target("avx2,fma"), always_inline)) inline void twoSum4(
    __m256d a, __m256d b, __m256d* s, __m256d* e) {
  *s = _mm256_add_pd(a, b);
  const __m256d bb = _mm256_sub_pd(*s, a);
  *e = _mm256_add_pd(_mm256_sub_pd(a, _mm256_sub_pd(*s, bb)),
                     _mm256_sub_pd(b, bb));
}
__attribute__((target("avx2,fma"), noinline)) void dwFrameAvx2Fma(
    const Inputs& in, DwFrame* f) {
  const Triangle<double>& T = in.tri;
  const Pose<double>& P = in.pose;
  const __m256d abs =
      _mm256_castsi256_pd(_mm256_set1_epi64x(0x7fffffffffffffffLL));
  const __m256d zero = _mm256_setzero_pd();
  const __m256d pk[3] = {lanes(T.a.x, T.b.x, T.c.x), lanes(T.a.y, T.b.y, T.c.y),
                         lanes(T.a.z, T.b.z, T.c.z)};
  const double tk[3] = {P.t.x, P.t.y, P.t.z};
  __m256d D[3], l[3], aD[3], Dz[3];
  for (int k = 0; k < 3; ++k) {
    twoSum4(pk[k], _mm256_set1_pd(-tk[k]), &D[k], &l[k]);
    aD[k] = _mm256_and_pd(D[k], abs);
    Dz[k] = _mm256_cmp_pd(D[k], zero, _CMP_EQ_OQ);
  }
  const __m256d exact_min = _mm256_set1_pd(detail::kProdExactMin);
  for (int j = 0; j < 3; ++j) {
    __m256d Pk[3], e[3], q[3], ok[3];
    __m256d m = zero;
    for (int k = 0; k < 3; ++k) {
      const double Rkj = P.R[k][j];
      const __m256d R = _mm256_set1_pd(Rkj);
      Pk[k] = _mm256_mul_pd(R, D[k]);
      e[k] = _mm256_fmsub_pd(R, D[k], Pk[k]);
      q[k] = _mm256_mul_pd(R, l[k]);
      m = _mm256_add_pd(m,
                        _mm256_mul_pd(_mm256_set1_pd(std::fabs(Rkj)), aD[k]));
      // Term k exact: a zero factor, or no low part, no product error and
      // no underflow.
      const __m256d exact_term = _mm256_and_pd(
          _mm256_and_pd(_mm256_cmp_pd(l[k], zero, _CMP_EQ_OQ),
                        _mm256_cmp_pd(e[k], zero, _CMP_EQ_OQ)),
          _mm256_cmp_pd(_mm256_and_pd(Pk[k], abs), exact_min, _CMP_GE_OQ));
      ok[k] = Rkj == 0 ? _mm256_castsi256_pd(_mm256_set1_epi64x(-1))
                       : _mm256_or_pd(Dz[k], exact_term);
    }
    __m256d s1, f1, s, f2;
    twoSum4(Pk[0], Pk[1], &s1, &f1);
    twoSum4(s1, Pk[2], &s, &f2);
    const __m256d low = _mm256_add_pd(
        _mm256_add_pd(_mm256_add_pd(_mm256_add_pd(_mm256_add_pd(f1, f2),
                                                  _mm256_add_pd(e[0], e[1])),
                                    e[2]),
                      _mm256_add_pd(q[0], q[1])),
        q[2]);
    __m256d hi, lo;
    twoSum4(s, low, &hi, &lo);
    __m256d err = _mm256_add_pd(_mm256_mul_pd(_mm256_set1_pd(0x1p-100), m),
                                _mm256_set1_pd(detail::kDwTiny));
    const __m256d exact = _mm256_and_pd(
        _mm256_and_pd(_mm256_and_pd(_mm256_cmp_pd(low, zero, _CMP_EQ_OQ),
                                    _mm256_cmp_pd(f1, zero, _CMP_EQ_OQ)),
                      _mm256_cmp_pd(f2, zero, _CMP_EQ_OQ)),
        _mm256_and_pd(_mm256_and_pd(ok[0], ok[1]), ok[2]));
    err = _mm256_andnot_pd(exact, err);
    if (j == 2) {  // Z = 2 z: exact scaling
      hi = _mm256_add_pd(hi, hi);
      lo = _mm256_add_pd(lo, lo);
      err = _mm256_add_pd(err, err);
    }
    alignas(32) double H[4], Lo[4], E[4];
    _mm256_store_pd(H, hi);
    _mm256_store_pd(Lo, lo);
    _mm256_store_pd(E, err);
    for (int i = 0; i < 3; ++i) f->c[i][j] = {{H[i], Lo[i]}, E[i]};
  }
}
#undef TRICYL_AVX2_FN
#endif

// A separating line in the projection (docs/exactness.md, "Edge
// separation"): with o_ij = x_i y_j - x_j y_i (twice the signed area of the
// origin, P_i, P_j) and A2 = o01 + o12 + o20 (twice the projected area), the
// origin lies strictly on the other side of edge ij's line than the third
// vertex iff sign(o_ij) = -sign(A2) != 0, and its distance to that line,
// |o_ij| / |P_j - P_i|, exceeds r iff o_ij^2 - r^2 L > 0 with
// L = |P_j - P_i|^2 (> 0 here, since o_ij != 0). Then the whole disk lies in
// the open half-plane beyond the line, the projected triangle in the closed
// one on the other side: the projections are disjoint, so are the solids.
// Each sign is certified by FilterKernel::sign (degree <= 8, depth <= 9, the
// same quantities (A) and (E) evaluate), so "true" is an exact fact; any
// undecided sign just skips the test.
inline bool edgeSeparates(const detail::TriCylLocal<FilterKernel>& q) {
  using detail::Fd;
  const Fd* x = q.x;
  const Fd* y = q.y;
  const Fd o[3] = {x[0] * y[1] - x[1] * y[0], x[1] * y[2] - x[2] * y[1],
                   x[2] * y[0] - x[0] * y[2]};
  const Sign sA = FilterKernel::sign(o[0] + o[1] + o[2]);
  if (sA != Sign::kPos && sA != Sign::kNeg) return false;
  const Sign outside = sA == Sign::kPos ? Sign::kNeg : Sign::kPos;
  const Fd r2 = q.r * q.r;
  for (int i = 0; i < 3; ++i) {
    if (FilterKernel::sign(o[i]) != outside) continue;
    const int j = i == 2 ? 0 : i + 1;
    const Fd ex = x[j] - x[i], ey = y[j] - y[i];
    const Fd len2 = ex * ex + ey * ey;
    if (FilterKernel::sign(o[i] * o[i] - r2 * len2) == Sign::kPos) return true;
  }
  return false;
}

// The triangle's own plane separates (docs/exactness.md, "Plane
// separation"). In the coordinates (x, y, Z) the solid is x^2 + y^2 <= r^2,
// |Z| <= H, so n.p <= r |(n_x, n_y)| + H |n_Z| on it for any n; the triangle
// lies in n.p = d with n = (P1 - P0) x (P2 - P0), d = n.P0. It is disjoint
// if |d| > r |(n_x, n_y)| + H |n_Z|. With s = the sign of the computed d
// (any choice works: s d <= |d| exactly), q1 = s d - H n_Z and
// q2 = s d + H n_Z certainly positive give s d - H |n_Z| = min(q1, q2) > 0,
// and q1^2, q2^2 > r^2 (n_x^2 + n_y^2) give (|d| - H |n_Z|)^2 >= min^2 >
// r^2 |(n_x, n_y)|^2: the plane misses the solid. A degenerate triangle
// (n = 0) never passes (q1 = q2 = 0 exactly). Depth <= 14, degree 6 in the
// local coordinates (12 in the inputs), magnitudes below 2^280 under the
// gate: FilterKernel::sign applies as for the kernel's own predicates.
inline bool planeSeparates(const detail::TriCylLocal<FilterKernel>& q) {
  using detail::Fd;
  const Fd* x = q.x;
  const Fd* y = q.y;
  const Fd* Z = q.Z;
  const Fd ux = x[1] - x[0], uy = y[1] - y[0], uz = Z[1] - Z[0];
  const Fd vx = x[2] - x[0], vy = y[2] - y[0], vz = Z[2] - Z[0];
  const Fd nx = uy * vz - uz * vy, ny = uz * vx - ux * vz,
           nz = ux * vy - uy * vx;
  Fd d = nx * x[0] + ny * y[0] + nz * Z[0];
  if (d.v < 0) d = -d;  // exact; s d <= |d| whatever s is
  const Fd Hn = q.H * nz;
  const Fd q1 = d - Hn, q2 = d + Hn;
  if (FilterKernel::sign(q1) != Sign::kPos ||
      FilterKernel::sign(q2) != Sign::kPos)
    return false;
  const Fd rN = (q.r * q.r) * (nx * nx + ny * ny);
  return FilterKernel::sign(q1 * q1 - rN) == Sign::kPos &&
         FilterKernel::sign(q2 * q2 - rN) == Sign::kPos;
}

// A separating line in the projection perpendicular to a vertex's direction
// (docs/exactness.md, "Direction separation"): with u = P_k (projected), if
// every vertex has P_j . u > r |u|, the projected triangle lies in the open
// half-plane {p . u > r |u|}, which the disk (p . u <= |p| |u| <= r |u|)
// does not meet. Certified as P_j . u > 0 and (P_j . u)^2 > r^2 |u|^2 for
// j = 0, 1, 2 (degree 4, depth <= 9).
inline bool directionSeparates(const detail::TriCylLocal<FilterKernel>& q) {
  using detail::Fd;
  const Fd* x = q.x;
  const Fd* y = q.y;
  const Fd r2 = q.r * q.r;
  for (int k = 0; k < 3; ++k) {
    const Fd ru = r2 * (x[k] * x[k] + y[k] * y[k]);
    bool all = true;
    for (int j = 0; j < 3 && all; ++j) {
      const Fd s = x[j] * x[k] + y[j] * y[k];
      all = FilterKernel::sign(s) == Sign::kPos &&
            FilterKernel::sign(s * s - ru) == Sign::kPos;
    }
    if (all) return true;
  }
  return false;
}

// The rest of the double filter after the early-outs (not inlined: the
// early-outs decide most queries).
// `undecided`: set to the tests left undecided when it returns kUnknown
// (detail::TestMask).
TRICYL_NOINLINE Tri filterTests(const Local& L, std::uint32_t* undecided) {
  // FilterKernel::sign, branch-free: kPos (1), kNeg (-1) or kUnknown (2).
  auto sgn = [](double v, double b) {
    const int pos = v > b, neg = v < -b;
    return Sign(2 - pos - 3 * neg);
  };
  Sign top[3], bot[3];
  detail::TriCylLocal<FilterKernel> q;
  for (int i = 0; i < 3; ++i) {
    const double m = L.m[i], m2 = m + m;
    const double bz = (m2 + L.H) * kRel + kAbs;
    top[i] = sgn(L.Z[i] - L.H, bz);
    bot[i] = sgn(L.Z[i] + L.H, bz);
    q.x[i] = {L.x[i], m};
    q.y[i] = {L.y[i], m};
    q.Z[i] = {L.Z[i], m2};
  }
  q.H = FilterKernel::lift(L.H);
  q.r = FilterKernel::lift(L.r);
  // The certificates the AVX2 prologue has no lanes for first (it tried the
  // early-outs and edge separation, with the magnitude 2 s).
  if (planeSeparates(q) || directionSeparates(q)) return Tri::kFalse;
  // The kernel's own early-outs with the per-vertex magnitudes (the
  // prologues' use the looser 2 s).
  if (detail::certainlyBeyond<FilterKernel>(q, top, bot)) return Tri::kFalse;
  if (edgeSeparates(q)) return Tri::kFalse;
  detail::TestMask mask;
  const Tri t = detail::triangleCylinderTests<FilterKernel>(q, top, bot, &mask);
  *undecided = mask.unknown;
  return t;
}

#if TRICYL_FAST_AVX2
// filterTests with AVX2 lanes (lanes = vertices, and edges (0,1), (1,2),
// (2,0); lane 3 repeats vertex 2 and edge (2,0)): the same certified
// verdicts, reached with fewer instructions. Every value below is a
// FilterKernel evaluation, a rounded value and its rounded magnitude by the
// Fd rules (a +- b: magnitude m_a + m_b; a b: m_a m_b; leaves x_i, y_i
// with m_i, Z_i with 2 m_i, H and r with themselves), of the polynomial the
// scalar kernel evaluates for that test, so each verdict is one
// FilterKernel::sign certifies (src/filter.h: any such evaluation of depth
// <= 56 is within 2^-47 m + 2^-600 of the exact value). A test's verdict
// is a pair of lane masks, certainly true (t) and certainly false (f);
// neither is "undecided", and its bit goes to `undecided` as in
// filterTests. (V), (X) and (E) run in lanes; (A) and (B), one test per
// triangle or per cap with a shape that depends on the signs, run in the
// scalar kernel (triangleCylinderTests restricted to them); the
// certificates of disjointness (plane, direction, bounding square, edge
// separation) run only for what the fifteen tests leave open.
struct LaneTri {
  __m256d t, f;
};
// The sign lanes of v with magnitude mv: certainly positive, certainly
// negative.
__attribute__((target("avx2"), always_inline)) inline void signLanes(
    __m256d v, __m256d mv, __m256d* pos, __m256d* neg) {
  const __m256d b = bound(mv, _mm256_set1_pd(kRel), _mm256_set1_pd(kAbs));
  *pos = _mm256_cmp_pd(v, b, _CMP_GT_OQ);
  *neg = _mm256_cmp_pd(v, _mm256_xor_pd(b, _mm256_set1_pd(-0.0)), _CMP_LT_OQ);
}
// Bits 0..2 of a lane mask (lane 3 repeats lane 2).
__attribute__((target("avx2"), always_inline)) inline std::uint32_t bits3(
    __m256d mask) {
  return std::uint32_t(_mm256_movemask_pd(mask)) & 7u;
}

__attribute__((target("avx2"), noinline)) Tri filterTestsAvx2(
    const Local& L, std::uint32_t* undecided, Local* out) {
  using detail::kTestA;
  using detail::kTestB;
  using detail::kTestE;
  using detail::kTestV;
  using detail::kTestX;
  constexpr int kNext = 0x09;  // lanes (1, 2, 0, 0): an edge's second end
  const __m256d x = _mm256_loadu_pd(L.x), y = _mm256_loadu_pd(L.y),
                Z = _mm256_loadu_pd(L.Z), m = _mm256_loadu_pd(L.m);
  const __m256d HH = _mm256_set1_pd(L.H), r2 = _mm256_set1_pd(L.r * L.r);
  const __m256d m2 = _mm256_add_pd(m, m);
  // Slab signs: a = Z - H (cap 0) and Z + H (cap 1), magnitude 2 m + H.
  const __m256d ma = _mm256_add_pd(m2, HH);
  const __m256d a0 = _mm256_sub_pd(Z, HH), a1 = _mm256_add_pd(Z, HH);
  __m256d pos0, neg0, pos1, neg1;
  signLanes(a0, ma, &pos0, &neg0);
  signLanes(a1, ma, &pos1, &neg1);

  // (V): in the slab (Z - H <= 0 <= Z + H) and r^2 - x^2 - y^2 >= 0.
  __m256d vp, vn;
  signLanes(_mm256_sub_pd(_mm256_sub_pd(r2, _mm256_mul_pd(x, x)),
                          _mm256_mul_pd(y, y)),
            _mm256_add_pd(_mm256_add_pd(r2, _mm256_mul_pd(m, m)),
                          _mm256_mul_pd(m, m)),
            &vp, &vn);
  const LaneTri V = {_mm256_and_pd(_mm256_and_pd(neg0, pos1), vp),
                     _mm256_or_pd(_mm256_or_pd(pos0, neg1), vn)};

  // (X) on each cap: a_i, a_j certainly of opposite signs, and
  // r^2 W^2 - X^2 - Y^2 >= 0 with X = x_i a_j - x_j a_i, Y likewise,
  // W = a_j - a_i.
  const EdgeLanes e = edgeLanes(x, y, Z, m);
  const __m256d mXv = capMagnitude(e, m, ma, r2);
  LaneTri X[2];
  for (int s = 0; s < 2; ++s) {
    const __m256d a = s == 0 ? a0 : a1;
    const __m256d pi = s == 0 ? pos0 : pos1, ni = s == 0 ? neg0 : neg1;
    const __m256d pj = _mm256_permute4x64_pd(pi, kNext),
                  nj = _mm256_permute4x64_pd(ni, kNext);
    const __m256d cross_t =
        _mm256_or_pd(_mm256_and_pd(ni, pj), _mm256_and_pd(pi, nj));
    const __m256d cross_f =
        _mm256_and_pd(_mm256_or_pd(pi, nj), _mm256_or_pd(ni, pj));
    __m256d p, n;
    signLanes(capValue(e, x, y, a, r2), mXv, &p, &n);
    X[s] = {_mm256_and_pd(cross_t, p), _mm256_or_pd(cross_f, n)};
  }

  // (E): L > 0, r^2 L - c^2 >= 0 (c = x_i y_j - x_j y_i), g >= 0,
  // L - g >= 0, (H - Z_i) L - g (Z_j - Z_i) >= 0 and
  // (H + Z_i) L + g (Z_j - Z_i) >= 0, g = -(x_i ex + y_i ey): the kernel's
  // grouping.
  __m256d Et, Ef;
  {
    __m256d p, n;
    signLanes(e.L, e.mL, &p, &n);
    Et = p;
    Ef = n;
    signLanes(_mm256_sub_pd(_mm256_mul_pd(r2, e.L), _mm256_mul_pd(e.o, e.o)),
              _mm256_add_pd(_mm256_mul_pd(r2, e.mL), _mm256_mul_pd(e.mo, e.mo)),
              &p, &n);
    Et = _mm256_and_pd(Et, p);
    Ef = _mm256_or_pd(Ef, n);
    const __m256d g = _mm256_xor_pd(
        _mm256_add_pd(_mm256_mul_pd(x, e.ex), _mm256_mul_pd(y, e.ey)),
        _mm256_set1_pd(-0.0));
    const __m256d mg =
        _mm256_add_pd(_mm256_mul_pd(m, e.mE), _mm256_mul_pd(m, e.mE));
    signLanes(g, mg, &p, &n);
    Et = _mm256_and_pd(Et, p);
    Ef = _mm256_or_pd(Ef, n);
    signLanes(_mm256_sub_pd(e.L, g), _mm256_add_pd(e.mL, mg), &p, &n);
    Et = _mm256_and_pd(Et, p);
    Ef = _mm256_or_pd(Ef, n);
    const __m256d gz = _mm256_mul_pd(g, _mm256_sub_pd(e.Zj, Z));
    const __m256d mgz =
        _mm256_mul_pd(mg, _mm256_add_pd(_mm256_add_pd(e.mj, e.mj), m2));
    const __m256d mside =
        _mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(HH, m2), e.mL), mgz);
    signLanes(_mm256_sub_pd(_mm256_mul_pd(_mm256_sub_pd(HH, Z), e.L), gz),
              mside, &p, &n);
    Et = _mm256_and_pd(Et, p);
    Ef = _mm256_or_pd(Ef, n);
    signLanes(_mm256_add_pd(_mm256_mul_pd(_mm256_add_pd(HH, Z), e.L), gz),
              mside, &p, &n);
    Et = _mm256_and_pd(Et, p);
    Ef = _mm256_or_pd(Ef, n);
  }
  const __m256d any_t =
      _mm256_or_pd(_mm256_or_pd(V.t, Et), _mm256_or_pd(X[0].t, X[1].t));
  if (bits3(any_t) != 0) return Tri::kTrue;
  std::uint32_t open =
      (7u & ~bits3(V.f)) << kTestV | (7u & ~bits3(X[0].f)) << kTestX |
      (7u & ~bits3(X[1].f)) << (kTestX + 3) | (7u & ~bits3(Ef)) << kTestE;

  // (A) and (B) in the scalar kernel, with the lanes' slab signs.
  auto sgn = [](std::uint32_t p, std::uint32_t n, int i) {
    return (p >> i & 1)   ? Sign::kPos
           : (n >> i & 1) ? Sign::kNeg
                          : Sign::kUnknown;
  };
  const std::uint32_t p0 = bits3(pos0), n0 = bits3(neg0), p1 = bits3(pos1),
                      n1 = bits3(neg1);
  Sign top[3], bot[3];
  detail::TriCylLocal<FilterKernel> q;
  for (int i = 0; i < 3; ++i) {
    top[i] = sgn(p0, n0, i);
    bot[i] = sgn(p1, n1, i);
    q.x[i] = {L.x[i], L.m[i]};
    q.y[i] = {L.y[i], L.m[i]};
    q.Z[i] = {L.Z[i], L.m[i] + L.m[i]};
  }
  q.H = FilterKernel::lift(L.H);
  q.r = FilterKernel::lift(L.r);
  if (open == 0) {
    detail::TestMask mask;
    mask.run = 1u << kTestA | 3u << kTestB;
    if (detail::triangleCylinderTests<FilterKernel>(q, top, bot, &mask) ==
        Tri::kTrue)
      return Tri::kTrue;
    open |= mask.unknown;
    if (open == 0) return Tri::kFalse;
  } else {
    open |= 1u << kTestA | 3u << kTestB;
  }
  // Certificates of disjointness for what the tests leave open: the
  // early-outs of certainlyBeyond (the slab; x - r, -x - r, y - r and
  // -y - r with magnitude m + r), edge separation, direction separation.
  // (planeSeparates, which the scalar filter also tries, decides too few
  // of these queries to pay for itself here.)
  const __m256d rr = _mm256_set1_pd(L.r), mr = _mm256_add_pd(m, rr);
  const __m256d nx = _mm256_xor_pd(x, _mm256_set1_pd(-0.0)),
                ny = _mm256_xor_pd(y, _mm256_set1_pd(-0.0));
  __m256d bp, bn;
  std::uint32_t beyond = (p0 == 7) | (n1 == 7);
  // Each early-out settled: some vertex certainly not beyond its plane
  // (Z - H < 0; -Z - H < 0, i.e. Z + H > 0; x - r < 0, ...).
  bool settled = (n0 != 0) & (p1 != 0);
  signLanes(_mm256_sub_pd(x, rr), mr, &bp, &bn);
  beyond |= bits3(bp) == 7;
  settled &= bits3(bn) != 0;
  signLanes(_mm256_sub_pd(nx, rr), mr, &bp, &bn);
  beyond |= bits3(bp) == 7;
  settled &= bits3(bn) != 0;
  signLanes(_mm256_sub_pd(y, rr), mr, &bp, &bn);
  beyond |= bits3(bp) == 7;
  settled &= bits3(bn) != 0;
  signLanes(_mm256_sub_pd(ny, rr), mr, &bp, &bn);
  beyond |= bits3(bp) == 7;
  settled &= bits3(bn) != 0;
  __m256d A2, mA;
  areaLanes(e, &A2, &mA);
  if (beyond || edgeSeparatesAvx2(e, A2, mA, r2) || directionSeparates(q))
    return Tri::kFalse;
  *undecided = open;
  // For the stages after the filter (Local).
  __m256d ap, an;
  signLanes(A2, mA, &ap, &an);
  out->area_nonzero = (_mm256_movemask_pd(_mm256_or_pd(ap, an)) & 1) != 0;
  out->early_settled = settled;
  return Tri::kUnknown;
}
#endif

// The scalar fast path: the double filter (FilterKernel) with validation and
// range gate fused into the arithmetic, and branch-free early-outs. It
// computes bit for bit the values and bounds that makeLocal<FilterKernel> and
// triangleCylinder<FilterKernel> compute, so every answer it gives is one the
// filter gives; it only reaches them with fewer instructions and branches.
template <bool kAvx2, class S>
TRICYL_ALWAYS_INLINE Fast decideFast(const Cylinder<S>& cyl,
                                     const Pose<S>& pose,
                                     const Triangle<S>& tri, Decision* out,
                                     std::uint32_t* undecided, Local* Lout) {
  Local& L = *Lout;
#if TRICYL_FAST_AVX2
  const Pre f =
      kAvx2 ? prologueAvx2(cyl, pose, tri, &L) : prologue(cyl, pose, tri, &L);
#else
  const Pre f = prologue(cyl, pose, tri, &L);
#endif
  // One branch for the three decided outcomes, the answer from a table.
  static_assert(int(Pre::kEarlyOut) == 1 && int(Pre::kHit) == 2 &&
                int(Pre::kDisjoint) == 3);
  if (unsigned(int(f) - 1) < 3u) {
    static constexpr Decision kBy[3] = {{Answer::kDisjoint, Stage::kEarlyOut},
                                        {Answer::kIntersect, Stage::kFastPath},
                                        {Answer::kDisjoint, Stage::kFastPath}};
    *out = kBy[int(f) - 1];
    return Fast::kDecided;
  }
  if (f == Pre::kGateMiss) return Fast::kGateMiss;
#if TRICYL_FAST_AVX2
  const Tri t =
      kAvx2 ? filterTestsAvx2(L, undecided, &L) : filterTests(L, undecided);
#else
  const Tri t = filterTests(L, undecided);
#endif
  if (t == Tri::kUnknown) {
    if (!kAvx2) L.area_nonzero = L.early_settled = false;  // not certified
    return Fast::kUnknown;
  }
  *out = {detail::toAnswer(t), Stage::kFastPath};
  return Fast::kDecided;
}

// Set by diagnostic::filterOnly: decideBody stops after the fast path.
thread_local bool tls_stop_after_filter = false;

template <bool kAvx2, class S>
TRICYL_ALWAYS_INLINE Decision decideBody(const Cylinder<S>& cylinder,
                                         const Pose<S>& pose,
                                         const Triangle<S>& triangle) {
  Decision d;
  std::uint32_t undecided = 0;
  Local L;
  const Fast f =
      decideFast<kAvx2>(cylinder, pose, triangle, &d, &undecided, &L);
  if (f == Fast::kDecided) return d;
  if (tls_stop_after_filter)  // diagnostic::filterOnly: no answer
    return {Answer::kInvalidInput,
            f == Fast::kUnknown ? Stage::kFastPath : Stage::kInvalid};
  return decideSlow(cylinder, pose, triangle,
                    f == Fast::kUnknown ? undecided : 0, &L);
}

#if TRICYL_FAST_AVX2
// Chosen once per process. Before this flag is initialised (a static
// constructor of another translation unit calling in) it reads false and the
// baseline path runs: same answers.
// TRICYL_SCALAR_BASELINE=1 in the environment keeps the baseline path (to
// test it on AVX2 machines).
const bool kHasAvx2 = __builtin_cpu_supports("avx2") != 0 &&
                      std::getenv("TRICYL_SCALAR_BASELINE") == nullptr;

// The fast path's gate as prologueAvx2 applies it (for
// diagnostic::fastPathGate).
template <class S>
__attribute__((target("avx2"), noinline)) bool gateAvx2(
    const Cylinder<S>& cylinder, const Pose<S>& pose,
    const Triangle<S>& triangle) {
  return gateBitsOkAvx2(cylinder, pose, triangle) && cylinder.radius >= 0 &&
         cylinder.lz >= 0;
}

template <class S>
__attribute__((target("avx2"), noinline)) Decision decideAvx2(
    const Cylinder<S>& cylinder, const Pose<S>& pose,
    const Triangle<S>& triangle) {
  return decideBody<true>(cylinder, pose, triangle);
}
#endif

// The baseline path out of line too, so that the entry points stay a
// test and a call (no stack frame of their own).
template <class S>
TRICYL_NOINLINE Decision decideBaseline(const Cylinder<S>& cylinder,
                                        const Pose<S>& pose,
                                        const Triangle<S>& triangle) {
  return decideBody<false>(cylinder, pose, triangle);
}

template <class S>
TRICYL_ALWAYS_INLINE Decision decideAny(const Cylinder<S>& cylinder,
                                        const Pose<S>& pose,
                                        const Triangle<S>& triangle) {
#if TRICYL_FAST_AVX2
  if (kHasAvx2) return decideAvx2(cylinder, pose, triangle);
#endif
  return decideBaseline(cylinder, pose, triangle);
}

bool checked(Decision d) {
  if (d.answer == Answer::kInvalidInput)
    throw InvalidInput(
        "tricyl::intersect(cylinder, triangle): NaN or infinite input, or a "
        "negative radius or length");
  return d.answer == Answer::kIntersect;
}

}  // namespace

template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Triangle<S>& triangle) noexcept {
  return decideAny(cylinder, pose, triangle);
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle) noexcept {
  return decideAny(cylinder, pose, triangle).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Triangle<S>& triangle) {
  return checked(decideAny(cylinder, pose, triangle));
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Triangle<S>& triangle) {
  return checked(decideAny(cylinder, identityPose<S>(), triangle));
}

namespace diagnostic {
template <class S>
bool intersectUncertified(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const Triangle<S>& triangle) noexcept {
  Widened in;
  if constexpr (std::is_same_v<S, float>) {
    in = widen(cylinder, pose, triangle);
  } else {
    in = {cylinder, pose, triangle};
  }
  const auto q = detail::makeLocal<NaiveKernel>(in.cyl, in.pose, in.tri, 1.0);
  bool early = false;
  return detail::triangleCylinder<NaiveKernel>(q, &early) == Tri::kTrue;
}

template <class S>
int fastPathGate(const Cylinder<S>& cylinder, const Pose<S>& pose,
                 const Triangle<S>& triangle) noexcept {
#if TRICYL_FAST_AVX2
  if (kHasAvx2) return gateAvx2(cylinder, pose, triangle) ? 1 : 0;
#endif
  (void)cylinder, (void)pose, (void)triangle;
  return -1;
}
template <class S>
int filterOnly(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Triangle<S>& triangle) noexcept {
  tls_stop_after_filter = true;
  const Decision d = decideAny(cylinder, pose, triangle);
  tls_stop_after_filter = false;
  if (d.answer != Answer::kInvalidInput) return 1;  // the fast path decided
  return d.stage == Stage::kFastPath ? 0 : -1;
}
template int filterOnly(const Cylinder<float>&, const Pose<float>&,
                        const Triangle<float>&) noexcept;
template int filterOnly(const Cylinder<double>&, const Pose<double>&,
                        const Triangle<double>&) noexcept;

int dwFramePathsAgree(const Pose<double>& pose,
                      const Triangle<double>& triangle) noexcept {
#if TRICYL_FAST_AVX2
  if (!kHasAvx2 || !detail::fmaAtRunTime()) return -1;
  const Cylinder<double> cyl{1, 1};  // not read by the frame
  const Inputs in{cyl, pose, triangle};
  DwFrame lanes, scalar;
  dwFrameAvx2Fma(in, &lanes);
#if TRICYL_FMA_DISPATCH
  dwFrameFma(in, &scalar);
#else
  dwFramePlain(in, &scalar);
#endif
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const detail::DwRun &a = lanes.c[i][j], &b = scalar.c[i][j];
      if (!(a.v.hi == b.v.hi && a.v.lo == b.v.lo && a.e == b.e)) return 0;
    }
  return 1;
#else
  (void)pose, (void)triangle;
  return -1;
#endif
}

template int fastPathGate(const Cylinder<float>&, const Pose<float>&,
                          const Triangle<float>&) noexcept;
template int fastPathGate(const Cylinder<double>&, const Pose<double>&,
                          const Triangle<double>&) noexcept;

template bool intersectUncertified(const Cylinder<float>&, const Pose<float>&,
                                   const Triangle<float>&) noexcept;
template bool intersectUncertified(const Cylinder<double>&, const Pose<double>&,
                                   const Triangle<double>&) noexcept;
}  // namespace diagnostic

template bool intersect(const Cylinder<float>&, const Pose<float>&,
                        const Triangle<float>&);
template bool intersect(const Cylinder<double>&, const Pose<double>&,
                        const Triangle<double>&);
template bool intersect(const Cylinder<float>&, const Triangle<float>&);
template bool intersect(const Cylinder<double>&, const Triangle<double>&);
template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                             const Triangle<float>&) noexcept;
template Answer tryIntersect(const Cylinder<double>&, const Pose<double>&,
                             const Triangle<double>&) noexcept;
template Decision decideIntersect(const Cylinder<float>&, const Pose<float>&,
                                  const Triangle<float>&) noexcept;
template Decision decideIntersect(const Cylinder<double>&, const Pose<double>&,
                                  const Triangle<double>&) noexcept;

}  // namespace tricyl
