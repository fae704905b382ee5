// SPDX-License-Identifier: BSD-3-Clause
// The per-sign stages of the cylinder queries (src/per_sign.h): every
// certified sign of every stage against the exact value, on the polynomials
// the sphere, segment and line queries evaluate, over the four query
// families (compare/query_scenes.h, seeded; TRICYL_SEED overrides, the seed
// and index are printed on failure):
//   - the double filter with the shallow-depth constant 2^-49;
//   - the double-word stage with the a-priori bound (2^-90 of the filter's
//     magnitude): its value within 2^-95 of that magnitude (the derived
//     bound) of the exact one, and the FMA path bit for bit;
//   - the double-word stage: its value within its bound of the exact one,
//     and, on x86-64 built without FMA, the run-time FMA path giving the
//     same double words, bit for bit, as Dekker's TwoProduct;
//   - the exact-in-double test: when it says exact, the value is exact;
//   - the whole query: PerSign's answer equals GMP's (KernelCtx<ExactKernel>).
#include "per_sign.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "cylinder_queries_impl.h"
#include "query_scenes.h"
#include "test_support.h"

namespace tricyl {
namespace {

using detail::DwArith;
using detail::DwEt;
using detail::DwPrioriArith;
using detail::DwPt;
using detail::ExactDoubleArith;
using detail::ExpansionArith;
using detail::Fd;
using detail::KernelArith;
using detail::Sign;
using qscenes::Family;
using qscenes::Query;
using qscenes::QueryCase;

/// The double-word path of this build without run-time dispatch.
constexpr bool kPlainFma = TRICYL_HAVE_FMA != 0;

int signOf(Sign s) { return s == Sign::kPos ? 1 : (s == Sign::kNeg ? -1 : 0); }

/// |dw - exact| <= its bound (as dwSign reads it), decided exactly in GMP.
template <bool kFma>
bool withinBound(const DwEt<kFma>& d, const detail::Dyadic& exact) {
  using detail::ExactKernel;
  const detail::Dyadic diff =
      ExactKernel::lift(d.v.hi) + ExactKernel::lift(d.v.lo) - exact;
  const detail::Dyadic slack =
      ExactKernel::lift(d.e * (1 + 0x1p-40) + 0x1p-600);
  return sgn((slack - diff).m) >= 0 && sgn((slack + diff).m) >= 0;
}

/// |h + l - exact| <= the a-priori bound of dwPrioriSign for the filter's
/// magnitude m, without its room (0x1.2p-92 m + 2^-600, src/per_sign.h),
/// decided exactly: the derivation's bound itself, not only the signs it
/// certifies.
template <bool kFma>
bool withinPrioriBound(const detail::DwPt<kFma>& d, double m,
                       const detail::Dyadic& exact) {
  using detail::ExactKernel;
  const detail::Dyadic diff =
      ExactKernel::lift(d.h) + ExactKernel::lift(d.l) - exact;
  const detail::Dyadic slack =
      ExactKernel::lift(m * 0x1.2p-92) + ExactKernel::lift(0x1p-600);
  return sgn((slack - diff).m) >= 0 && sgn((slack + diff).m) >= 0;
}

/// Checks one polynomial `pred` of a query in every arithmetic against its
/// exact value (GMP); certified[] counts the signs each stage certified.
template <class Q, class P>
void checkPredicate(const Q& q, const P& pred, long* certified) {
  const typename Q::template Frame<KernelArith<detail::ExactKernel>> fx(q);
  const detail::Dyadic exact = pred(fx);
  const int truth = sgn(exact.m);
  // The expansions, where they can (not near underflow): the exact sign.
  const typename Q::template Frame<ExpansionArith> fxe(q);
  const detail::Expansion xe = pred(fxe);
  if (xe.ok()) {
    EXPECT_EQ(xe.sign(), truth);
  }
  // Double filter with the shallow constant.
  const typename Q::template Frame<KernelArith<detail::FilterKernel>> ff(q);
  const Sign sf = detail::shallowSign(pred(ff));
  if (sf != Sign::kUnknown) {
    EXPECT_EQ(signOf(sf), truth);
    ++certified[0];
  }
  // Double word with the a-priori bound from the filter's magnitude: the
  // bound holds; a certified sign is the true one; the FMA path gives the
  // same double words.
  const double mag = pred(ff).m;
  const typename Q::template Frame<DwPrioriArith<kPlainFma>> fp(q);
  const DwPt<kPlainFma> dp = pred(fp);
  EXPECT_TRUE(withinPrioriBound(dp, mag, exact))
      << "a-priori compensated " << dp.h << " + " << dp.l << ", magnitude "
      << mag;
  const Sign sp = detail::dwPrioriSign(dp, mag);
  if (sp != Sign::kUnknown) {
    EXPECT_EQ(signOf(sp), truth);
    ++certified[1];
  }
#if TRICYL_FMA_DISPATCH
  if (detail::fmaAtRunTime()) {
    const typename Q::template Frame<DwPrioriArith<true>> fpm(q);
    const DwPt<true> pm = pred(fpm);
    EXPECT_EQ(std::memcmp(&pm, &dp, sizeof pm), 0)
        << "FMA path " << pm.h << " + " << pm.l << " vs " << dp.h << " + "
        << dp.l;
  }
#endif
  // Double word: the bound holds; a certified sign is the true one.
  const typename Q::template Frame<DwArith<kPlainFma>> fd(q);
  const DwEt<kPlainFma> d = pred(fd);
  EXPECT_TRUE(withinBound(d, exact))
      << "double word " << d.v.hi << " + " << d.v.lo << ", bound " << d.e;
  const Sign sd = detail::dwSign(d);
  if (sd != Sign::kUnknown) {
    EXPECT_EQ(signOf(sd), truth);
    ++certified[2];
  }
#if TRICYL_FMA_DISPATCH
  if (detail::fmaAtRunTime()) {
    const typename Q::template Frame<DwArith<true>> fm(q);
    const DwEt<true> m = pred(fm);
    EXPECT_EQ(std::memcmp(&m, &d, sizeof m), 0)
        << "FMA path " << m.v.hi << " + " << m.v.lo << " vs " << d.v.hi << " + "
        << d.v.lo;
  }
#endif
  // Exact in double.
  const typename Q::template Frame<ExactDoubleArith> fe(q);
  const detail::Xd xd = pred(fe);
  if (xd.exact) {
    EXPECT_EQ((xd.v > 0) - (xd.v < 0), truth);
    ++certified[3];
  }
}

constexpr Family kFamilies[] = {Family::kUniform, Family::kNear, Family::kFar,
                                Family::kDegenerate};

/// The range gate of the case; *mu: its largest rotation entry magnitude.
bool insideGate(const QueryCase& k, double* mu_out) {
  double ml = std::fabs(k.rho);
  for (double v : {k.cyl.radius, k.cyl.lz, k.p.x, k.p.y, k.p.z, k.q.x, k.q.y,
                   k.q.z, k.pose.t.x, k.pose.t.y, k.pose.t.z})
    ml = std::max(ml, std::fabs(v));
  double mu = 0;
  for (const auto& row : k.pose.R)
    for (double v : row) mu = std::max(mu, std::fabs(v));
  *mu_out = mu;
  return detail::rangeGateOk(ml, mu);
}

TEST(PerSign, SphereSignsOfEveryStageAreExact) {
  const std::uint64_t seed = test::baseSeed();
  long certified[4] = {0, 0, 0, 0};
  for (Family fam : kFamilies)
    for (int i = 0; i < test::scaled(1500); ++i) {
      const QueryCase k = qscenes::generate(Query::kSphere, fam, seed, i);
      double mu = 0;
      if (!insideGate(k, &mu)) continue;
      SCOPED_TRACE(testing::Message()
                   << "seed " << seed << ", family " << qscenes::familyName(fam)
                   << ", index " << i);
      const Sphere<double> sph{k.p, k.rho};
      const detail::SphereQuery q{k.cyl, k.pose, sph, mu};
      checkPredicate(
          q,
          [](const auto& f) {
            return (f.rho + f.rho) - detail::sphereHeight(f);
          },
          certified);
      checkPredicate(
          q, [](const auto& f) { return detail::sphereHeight(f); }, certified);
      checkPredicate(
          q, [](const auto& f) { return detail::diskGap(f.c, f.r + f.rho); },
          certified);
      checkPredicate(
          q,
          [](const auto& f) {
            const auto E = detail::sphereHeight(f);
            const auto G = detail::times4(f.rho * f.rho) - E * E;
            const auto T = detail::sphereT(f);
            return detail::times4(detail::times4(f.r * f.r)) * G - T * T;
          },
          certified);
      if (testing::Test::HasFailure()) return;
    }
  std::printf(
      "[ stats    ] sphere signs certified: filter %ld, a-priori double "
      "word %ld, "
      "running double word %ld, exact in double %ld\n",
      certified[0], certified[1], certified[2], certified[3]);
}

template <bool kSegment>
void linearSigns(Query qy) {
  const std::uint64_t seed = test::baseSeed();
  long certified[4] = {0, 0, 0, 0};
  for (Family fam : kFamilies)
    for (int i = 0; i < test::scaled(1000); ++i) {
      const QueryCase k = qscenes::generate(qy, fam, seed, i);
      double mu = 0;
      if (!insideGate(k, &mu)) continue;
      SCOPED_TRACE(testing::Message()
                   << "seed " << seed << ", family " << qscenes::familyName(fam)
                   << ", index " << i);
      const detail::LinearQuery<kSegment> q(k.cyl, k.pose, k.p, k.q, mu);
      checkPredicate(
          q, [](const auto& f) { return detail::axisDistanceGap(f); },
          certified);
      for (int side : {1, -1})
        checkPredicate(
            q,
            [side](const auto& f) { return detail::capCrossingGap(f, side); },
            certified);
      for (int side : {1, -1})
        checkPredicate(
            q,
            [side](const auto& f) { return detail::axisFootHeight(f, side); },
            certified);
      checkPredicate(
          q,
          [](const auto& f) {
            return detail::axisLen(f) - detail::axisFoot(f);
          },
          certified);
      checkPredicate(
          q, [](const auto& f) { return detail::diskGap(f.a(), f.r); },
          certified);
      if (kSegment)
        checkPredicate(
            q, [](const auto& f) { return detail::diskGap(f.b(), f.r); },
            certified);
      if (testing::Test::HasFailure()) return;
    }
  std::printf(
      "[ stats    ] %s signs certified: filter %ld, a-priori double word "
      "%ld, running double word %ld, exact in double %ld\n",
      kSegment ? "segment" : "line", certified[0], certified[1], certified[2],
      certified[3]);
}

TEST(PerSign, SegmentSignsOfEveryStageAreExact) {
  linearSigns<true>(Query::kSegment);
}
TEST(PerSign, LineSignsOfEveryStageAreExact) {
  linearSigns<false>(Query::kLine);
}

/// The whole query: PerSign (every stage) against GMP alone.
TEST(PerSign, QueriesAgreeWithGmpAlone) {
  const std::uint64_t seed = test::baseSeed();
  for (Family fam : kFamilies)
    for (int i = 0; i < test::scaled(1000); ++i) {
      SCOPED_TRACE(testing::Message()
                   << "seed " << seed << ", family " << qscenes::familyName(fam)
                   << ", index " << i);
      const QueryCase ks = qscenes::generate(Query::kSphere, fam, seed, i);
      double mu = 0;
      if (insideGate(ks, &mu)) {
        const Sphere<double> sph{ks.p, ks.rho};
        const detail::SphereQuery q{ks.cyl, ks.pose, sph, mu};
        bool e1 = false, e2 = false;
        detail::PerSign<detail::SphereQuery> ps(q);
        detail::KernelCtx<detail::ExactKernel, detail::SphereQuery> gmp(q);
        EXPECT_EQ(detail::sphereCylinder(ps, &e1),
                  detail::sphereCylinder(gmp, &e2));
      }
      for (Query qy : {Query::kSegment, Query::kLine}) {
        const QueryCase k = qscenes::generate(qy, fam, seed, i);
        if (!insideGate(k, &mu)) continue;
        bool e1 = false, e2 = false;
        if (qy == Query::kSegment) {
          const detail::SegmentQuery q(k.cyl, k.pose, k.p, k.q, mu);
          detail::PerSign<detail::SegmentQuery> ps(q);
          detail::KernelCtx<detail::ExactKernel, detail::SegmentQuery> gmp(q);
          EXPECT_EQ(detail::segmentCylinder(ps, &e1),
                    detail::segmentCylinder(gmp, &e2));
        } else {
          const detail::LineQuery q(k.cyl, k.pose, k.p, k.q, mu);
          detail::PerSign<detail::LineQuery> ps(q);
          detail::KernelCtx<detail::ExactKernel, detail::LineQuery> gmp(q);
          EXPECT_EQ(detail::lineCylinder(ps, &e1),
                    detail::lineCylinder(gmp, &e2));
        }
      }
      if (testing::Test::HasFailure()) return;
    }
}

}  // namespace
}  // namespace tricyl
