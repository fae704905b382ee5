// Segment vs cylinder: the exact Boolean (three stages of src/filter.h) and
// the entry/exit interval.
//
// THE INTERVAL. In the cylinder frame (z doubled: Z = 2z, H = lz), with p0
// the local image of p and D = R^T (q - p) the local direction (computed
// from the input difference q - p, not as a difference of two local
// points, so that a short segment far from the pose keeps its relative
// accuracy):
//   slab:      |Z0 + s DZ| <= H                 s in [(-H - Z0)/DZ, (H -
//   Z0)/DZ]
//                                               (swapped if DZ < 0; all s if
//                                               DZ = 0, in the slab by the
//                                               Boolean);
//   cylinder:  A s^2 + 2 b s + C <= 0,  A = Dx^2 + Dy^2, b = x0 Dx + y0 Dy,
//              C = x0^2 + y0^2 - r^2,   roots (-b -+ sqrt(Delta)) / A with
//              Delta = b^2 - A C = r^2 A - c^2,  c = x0 Dy - y0 Dx
//              (Lagrange's identity; Delta >= 0 whenever the Boolean is
//              true). A = 0 (parallel to the axis): all s (C <= 0 by the
//              Boolean). Roots in the cancellation-free form q / A and
//              C / q, q = -(b + sign(b) sqrt(Delta)).
//   result:    [max(0, slab_lo, root_lo), min(1, slab_hi, root_hi)].
// Emptiness is NOT read from these numbers: it is the exact Boolean.
//
// ERROR BOUND. Stage 1 evaluates every candidate with the running error
// bound of ExtendedKernel (src/filter.h), first in double (with an explicit
// underflow allowance, see Rd), then, if that is not accurate enough, in
// long double (filter.h's Fl), extended here by division and square root
// (derivations at flDiv and flSqrt), which gives
// each candidate an enclosure [v - e, v + e] of its exact value. The exact
// max (min) of the candidates lies between the max (min) of the enclosures'
// lower ends and the max (min) of their upper ends; the result is the
// midpoint of that range and its half-width bounds the error. It is
// accepted when the half-width is <= 2^-49 for both ends; forming and
// rounding the midpoint adds <= 2^-53, so the double endpoints are within
// 1.9e-15 of the exact ones. Otherwise (grazing lines, where Delta cancels and
// sqrt amplifies its error to ~sqrt(e); segments exactly parallel to the axis
// in a general pose, whose A = 0 cannot be certified; inputs outside the range
// gate) stage 2 computes A, b, C, Delta, Z0, DZ EXACTLY (GMP dyadics from
// ExactKernel) and the candidates in GMP mpf with (bits of the exact
// values + 128) bits, then truncates to double: error < 1 ulp <= 2^-52.
#include "tricyl/segment_cylinder.h"

#include <gmpxx.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "cylinder_queries_impl.h"

namespace tricyl {
namespace {

using detail::Dyadic;
using detail::ExactKernel;
using detail::ExtendedKernel;
using detail::Fl;

struct SegInputs {
  Cylinder<double> cyl;
  Pose<double> pose;
  Segment<double> seg;
  double max_len = 0, max_unitless = 0;
};

template <class S>
SegInputs widenAll(const Cylinder<S>& cyl, const Pose<S>& pose,
                   const Segment<S>& seg) {
  SegInputs in;
  in.cyl = {double(cyl.radius), double(cyl.lz)};
  in.pose = detail::widen(pose);
  in.seg = {detail::widen(seg.p), detail::widen(seg.q)};
  return in;
}

bool validate(SegInputs& in) {
  const auto& p = in.seg.p;
  const auto& q = in.seg.q;
  return detail::scanFinite(
             {in.cyl.radius, in.cyl.lz, p.x, p.y, p.z, q.x, q.y, q.z}, in.pose,
             &in.max_len, &in.max_unitless) &&
         in.cyl.radius >= 0 && in.cyl.lz >= 0;
}

Decision decide(SegInputs& in) {
  if (!validate(in)) return {Answer::kInvalidInput, Stage::kInvalid};
  return detail::runStages(
      [&](auto tag, bool* early) {
        using K = typename decltype(tag)::type;
        detail::SegLocal<K> q;
        q.p[0] = detail::localPoint<K>(in.pose, in.seg.p, in.max_unitless);
        q.p[1] = detail::localPoint<K>(in.pose, in.seg.q, in.max_unitless);
        q.H = K::lift(in.cyl.lz);
        q.r = K::lift(in.cyl.radius);
        return detail::segmentCylinder<K>(q, early);
      },
      in.max_len, in.max_unitless);
}

// ---------------------------------------------------------------------------
// Stage 1 of the interval: long double with running error bounds.

// The running error bound of ExtendedKernel (src/filter.h) in plain double,
// for a cheaper first attempt: the same rules with u = 2^-53, plus an
// absolute 2^-1074 on every product and quotient for a possible underflow
// (sums of doubles are exact in the subnormal range), so no range argument
// is needed for it. The long double stage (filter.h's Fl, covered there by
// the range gate) runs only when this one cannot reach the accuracy.
struct Rd {
  double v, e;
};
constexpr double kU1d = 0x1p-53 * (1 + 0x1p-52);  // u' for double
inline Rd operator+(Rd a, Rd b) {
  const double v = a.v + b.v;
  return {v, a.e + b.e + kU1d * std::fabs(v)};
}
inline Rd operator-(Rd a, Rd b) {
  const double v = a.v - b.v;
  return {v, a.e + b.e + kU1d * std::fabs(v)};
}
inline Rd operator-(Rd a) { return {-a.v, a.e}; }
inline Rd operator*(Rd a, Rd b) {
  const double v = a.v * b.v;
  return {v, std::fabs(a.v) * b.e + std::fabs(b.v) * a.e + a.e * b.e +
                 kU1d * std::fabs(v) + 0x1p-1074};
}
struct RunningDoubleKernel {
  using Num = Rd;
  static constexpr bool kExact = false;
  static Num lift(double x) { return {x, 0}; }
  static Num inputDiff(double a, double b) {
    const double d = a - b;
    return {d, kU1d * std::fabs(d)};
  }
};

/// Per running type: u', the absolute underflow allowance of a product or
/// quotient, and the floating type.
template <class N>
struct Run;
template <>
struct Run<Fl> {
  using T = long double;
  static constexpr T kU1 = detail::kUL1;
  static constexpr T kTiny = 0;  // range gate: docs/exactness.md
};
template <>
struct Run<Rd> {
  using T = double;
  static constexpr T kU1 = kU1d;
  static constexpr T kTiny = 0x1p-1074;
};

// Slack for the rounding of the bound computations themselves (each bound
// is a sum of non-negative rounded terms, short by at most (1 - u)^k).
constexpr double kInfl = 1 + 0x1p-40;

/// a / b for |B - b.v| <= b.e < |b.v|: with Q = A / B,
///   |Q - a.v/b.v| = |A b.v - a.v B| / (|B| |b.v|)
///                <= (a.e |b.v| + |a.v| b.e) / ((|b.v| - b.e) |b.v|)
///                 = (a.e + |a.v / b.v| b.e) / (|b.v| - b.e),
/// plus the rounding of the division, u' |v| (+ the underflow allowance).
/// Returns false if |b.v| <= b.e (the divisor's sign is not certain) or the
/// bound is not finite.
template <class N>
bool flDiv(const N& a, const N& b, N* out) {
  using T = typename Run<N>::T;
  const T bv = std::fabs(b.v);
  const T be = b.e * T(kInfl);
  if (!(bv > be)) return false;
  const T v = a.v / b.v;
  const T e = (a.e + std::fabs(v) * be) / (bv - be) +
              Run<N>::kU1 * std::fabs(v) + Run<N>::kTiny;
  if (!(e <= std::numeric_limits<T>::max() / 4)) return false;
  *out = {v, e * T(kInfl)};
  return true;
}

/// sqrt(a) for an exact value A >= 0 (known from the Boolean) with
/// |A - a.v| <= a.e: sqrt(A) lies in [sqrt(max(0, v - e)), sqrt(v + e)];
/// v = sqrt(max(v, 0)), e = the larger distance to those ends, plus
/// 3 u' sqrt(v + e) for the three correctly rounded square roots.
template <class N>
N flSqrt(const N& a) {
  using T = typename Run<N>::T;
  const T e = a.e * T(kInfl);
  const T lo = std::sqrt(std::max(a.v - e, T(0)));
  const T hi = std::sqrt(std::max(a.v + e, T(0)));
  const T v = std::sqrt(std::max(a.v, T(0)));
  const T err = std::max(v - lo, hi - v) + 3 * Run<N>::kU1 * hi;
  return {v, err * T(kInfl)};
}

/// Lower and upper ends of an enclosure of the exact max (or min) of the
/// candidates added so far.
template <class T>
struct Extremum {
  T lo, hi;
  bool is_max;
  void add(T v, T e) {
    const T a = v - e, b = v + e;
    if (is_max) {
      lo = std::max(lo, a);
      hi = std::max(hi, b);
    } else {
      lo = std::min(lo, a);
      hi = std::min(hi, b);
    }
  }
};

constexpr double kAccept = 0x1p-49;

/// Stage 1 in the running type of kernel K (RunningDoubleKernel first,
/// then ExtendedKernel). False when the bound exceeds kAccept.
template <class K>
bool intervalRunning(const SegInputs& in, Interval<double>* out) {
  using N = typename K::Num;
  using T = typename Run<N>::T;
  N x0, y0, Z0, Dx, Dy, DZ;
  detail::toLocal<K>(in.pose, in.seg.p, 1.0, x0, y0, Z0);
  Pose<double> at_p = in.pose;
  at_p.t = in.seg.p;  // R^T (q - p)
  detail::toLocal<K>(at_p, in.seg.q, 1.0, Dx, Dy, DZ);
  const N H = K::lift(in.cyl.lz);
  const N r = K::lift(in.cyl.radius);

  Extremum<T> lo{0, 0, true};   // candidate 0
  Extremum<T> hi{1, 1, false};  // candidate 1

  // Slab. DZ exactly zero is recognised when its bound is zero too.
  if (!(DZ.v == 0 && DZ.e == 0)) {
    N s_bot, s_top;  // parameters of Z = -H and Z = +H
    if (!flDiv(-H - Z0, DZ, &s_bot) || !flDiv(H - Z0, DZ, &s_top)) return false;
    const bool up = DZ.v > 0;
    const N& a = up ? s_bot : s_top;
    const N& b = up ? s_top : s_bot;
    lo.add(a.v, a.e);
    hi.add(b.v, b.e);
  }
  // Infinite cylinder.
  const N A = Dx * Dx + Dy * Dy;
  if (!(A.v == 0 && A.e == 0)) {
    if (!(A.v > A.e * T(kInfl))) return false;  // A > 0 not certain
    const N b = x0 * Dx + y0 * Dy;
    const N C = x0 * x0 + y0 * y0 - r * r;
    const N c = x0 * Dy - y0 * Dx;
    const N delta = r * r * A - c * c;
    const N sq = flSqrt(delta);
    const N q = b.v >= 0 ? N(-(b + sq)) : N(sq - b);
    N r1, r2;
    if (!flDiv(q, A, &r1) || !flDiv(C, q, &r2)) return false;
    // The exact lower root is min(r1, r2), the upper max(r1, r2); both are
    // 1-Lipschitz, so enclosures of min/max come from the enclosures.
    const T l_lo = std::min(r1.v - r1.e, r2.v - r2.e);
    const T l_hi = std::min(r1.v + r1.e, r2.v + r2.e);
    const T u_lo = std::max(r1.v - r1.e, r2.v - r2.e);
    const T u_hi = std::max(r1.v + r1.e, r2.v + r2.e);
    lo.add((l_lo + l_hi) / 2, (l_hi - l_lo) / 2 * T(kInfl));
    hi.add((u_lo + u_hi) / 2, (u_hi - u_lo) / 2 * T(kInfl));
  }
  if (!(lo.hi - lo.lo <= T(2 * kAccept) && hi.hi - hi.lo <= T(2 * kAccept)))
    return false;
  // The midpoint of an enclosure of width <= 2^-48 in [-2^-48, 1 + 2^-48]:
  // rounding it (to double, in either type) adds <= 2^-53.
  out->lo = double(lo.lo / 2 + lo.hi / 2);
  out->hi = double(hi.lo / 2 + hi.hi / 2);
  return true;
}

// ---------------------------------------------------------------------------
// Stage 2: exact coefficients, multi-precision candidates.

size_t bitsOf(const Dyadic& d) { return mpz_sizeinbase(d.m.get_mpz_t(), 2); }

mpf_class toMpf(const Dyadic& d, mp_bitcnt_t prec) {
  mpf_class f(0, prec);
  mpf_set_z(f.get_mpf_t(), d.m.get_mpz_t());  // exact: prec >= bits of m
  if (d.e > 0)
    mpf_mul_2exp(f.get_mpf_t(), f.get_mpf_t(), mp_bitcnt_t(d.e));
  else if (d.e < 0)
    mpf_div_2exp(f.get_mpf_t(), f.get_mpf_t(), mp_bitcnt_t(-d.e));
  return f;
}

Interval<double> intervalExact(const SegInputs& in) {
  using K = ExactKernel;
  Dyadic x0, y0, Z0, Dx, Dy, DZ;
  detail::toLocal<K>(in.pose, in.seg.p, 1.0, x0, y0, Z0);
  Pose<double> at_p = in.pose;
  at_p.t = in.seg.p;
  detail::toLocal<K>(at_p, in.seg.q, 1.0, Dx, Dy, DZ);
  const Dyadic H = K::lift(in.cyl.lz);
  const Dyadic r = K::lift(in.cyl.radius);
  const Dyadic A = Dx * Dx + Dy * Dy;
  const Dyadic b = x0 * Dx + y0 * Dy;
  const Dyadic C = x0 * x0 + y0 * y0 - r * r;
  const Dyadic c = x0 * Dy - y0 * Dx;
  const Dyadic delta = r * r * A - c * c;
  const Dyadic nb = -H - Z0, nt = H - Z0;
  size_t bits = 64;
  for (const Dyadic* d :
       {&A, &b, &C, &delta, &nb, &nt, static_cast<const Dyadic*>(&DZ)})
    bits = std::max(bits, bitsOf(*d));
  const mp_bitcnt_t prec = mp_bitcnt_t(bits + 128);

  mpf_class lo(0, prec), hi(1, prec);
  if (sgn(DZ.m) != 0) {
    const mpf_class dz = toMpf(DZ, prec);
    mpf_class sb(toMpf(nb, prec) / dz, prec), st(toMpf(nt, prec) / dz, prec);
    if (sgn(DZ.m) < 0) std::swap(sb, st);
    if (sb > lo) lo = sb;
    if (st < hi) hi = st;
  }
  if (sgn(A.m) != 0 && sgn(delta.m) >= 0) {
    const mpf_class fA = toMpf(A, prec), fb = toMpf(b, prec);
    const mpf_class sq(sqrt(toMpf(delta, prec)), prec);
    const mpf_class q(
        sgn(b.m) >= 0 ? mpf_class(-(fb + sq), prec) : mpf_class(sq - fb, prec),
        prec);
    mpf_class r1(0, prec), r2(0, prec);
    if (sgn(q) != 0) {  // q = 0 iff b = 0 and Delta = 0: the double root 0
      r1 = q / fA;
      r2 = toMpf(C, prec) / q;
    }
    if (r1 > r2) std::swap(r1, r2);
    if (r1 > lo) lo = r1;
    if (r2 < hi) hi = r2;
  }
  return {lo.get_d(), hi.get_d()};  // truncation: < 1 ulp
}

Interval<double> interval(const SegInputs& in) {
  Interval<double> iv{0, 1};
  const bool gate = detail::rangeGateOk(in.max_len, in.max_unitless);
  if (!(gate && (intervalRunning<RunningDoubleKernel>(in, &iv) ||
                 intervalRunning<ExtendedKernel>(in, &iv))))
    iv = intervalExact(in);
  // The exact interval is non-empty (the Boolean said so), so a crossing of
  // the two approximations is a rounding artefact of at most the bound:
  // the midpoint is then within the bound of both exact ends.
  if (iv.lo > iv.hi) iv.lo = iv.hi = iv.lo / 2 + iv.hi / 2;
  iv.lo = std::min(std::max(iv.lo, 0.0), 1.0);
  iv.hi = std::min(std::max(iv.hi, 0.0), 1.0);
  return iv;
}

template <class S>
Answer clipAs(const Cylinder<S>& cyl, const Pose<S>& pose,
              const Segment<S>& seg, Interval<S>* out) {
  SegInputs in = widenAll(cyl, pose, seg);
  const Decision d = decide(in);
  if (d.answer != Answer::kIntersect) return d.answer;
  const Interval<double> iv = interval(in);
  *out = {S(iv.lo), S(iv.hi)};  // nearest: monotone, keeps lo <= hi
  return d.answer;
}

[[noreturn]] void throwInvalid(const char* what) {
  throw InvalidInput(std::string("tricyl::") + what +
                     "(cylinder, segment): NaN or infinite input, or a "
                     "negative radius or length");
}

}  // namespace

template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Segment<S>& segment) noexcept {
  SegInputs in = widenAll(cylinder, pose, segment);
  return decide(in);
}

template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Segment<S>& segment) noexcept {
  return decideIntersect(cylinder, pose, segment).answer;
}

template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Segment<S>& segment) {
  const Answer a = tryIntersect(cylinder, pose, segment);
  if (a == Answer::kInvalidInput) throwInvalid("intersect");
  return a == Answer::kIntersect;
}

template <class S>
Answer tryClip(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Segment<S>& segment, Interval<S>* out) noexcept {
  return clipAs(cylinder, pose, segment, out);
}

template <class S>
std::optional<Interval<S>> clip(const Cylinder<S>& cylinder,
                                const Pose<S>& pose,
                                const Segment<S>& segment) {
  Interval<S> iv{};
  const Answer a = clipAs(cylinder, pose, segment, &iv);
  if (a == Answer::kInvalidInput) throwInvalid("clip");
  if (a == Answer::kDisjoint) return std::nullopt;
  return iv;
}

template bool intersect(const Cylinder<float>&, const Pose<float>&,
                        const Segment<float>&);
template bool intersect(const Cylinder<double>&, const Pose<double>&,
                        const Segment<double>&);
template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                             const Segment<float>&) noexcept;
template Answer tryIntersect(const Cylinder<double>&, const Pose<double>&,
                             const Segment<double>&) noexcept;
template Decision decideIntersect(const Cylinder<float>&, const Pose<float>&,
                                  const Segment<float>&) noexcept;
template Decision decideIntersect(const Cylinder<double>&, const Pose<double>&,
                                  const Segment<double>&) noexcept;
template std::optional<Interval<float>> clip(const Cylinder<float>&,
                                             const Pose<float>&,
                                             const Segment<float>&);
template std::optional<Interval<double>> clip(const Cylinder<double>&,
                                              const Pose<double>&,
                                              const Segment<double>&);
template Answer tryClip(const Cylinder<float>&, const Pose<float>&,
                        const Segment<float>&, Interval<float>*) noexcept;
template Answer tryClip(const Cylinder<double>&, const Pose<double>&,
                        const Segment<double>&, Interval<double>*) noexcept;

}  // namespace tricyl
