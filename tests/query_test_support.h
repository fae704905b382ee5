// SPDX-License-Identifier: BSD-3-Clause
// Shared driver for the random oracle-agreement tests of the cylinder query
// family (tests/{point_cylinder,point_cone,sphere_cylinder,segment_cylinder}
// _test.cpp): seeded cases from compare/query_scenes.h, checked against the
// exact oracles of compare/query_oracles.h, in double on every case and in
// float (inputs rounded to float, oracle re-run on the rounded input) on
// every 4th.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "query_oracles.h"
#include "query_scenes.h"
#include "test_support.h"
#include "tricyl/tricyl.h"

namespace tricyl::test {

using qscenes::Family;
using qscenes::Query;
using qscenes::QueryCase;

/// A failing case as text that can be pasted back into a regression test.
inline std::string dump(const QueryCase& k) {
  char buf[1024];
  const auto& R = k.pose.R;
  std::snprintf(buf, sizeof buf,
                "r=%a lz=%a rho=%a\nR=%a %a %a / %a %a %a / %a %a %a\n"
                "t=%a %a %a\np=%a %a %a\nq=%a %a %a\nfeature=%s",
                k.cyl.radius, k.cyl.lz, k.rho, R[0][0], R[0][1], R[0][2],
                R[1][0], R[1][1], R[1][2], R[2][0], R[2][1], R[2][2],
                k.pose.t.x, k.pose.t.y, k.pose.t.z, k.p.x, k.p.y, k.p.z, k.q.x,
                k.q.y, k.q.z, k.feature);
  return buf;
}

/// Rounds through a volatile (see triangle_cylinder_random_test.cpp: GCC
/// was seen to fold a double -> float -> double round trip).
template <class S>
S opaque(double x) {
  volatile S s = S(x);
  return s;
}

template <class S>
Vec3<S> vec(const Vec3<double>& v) {
  return {opaque<S>(v.x), opaque<S>(v.y), opaque<S>(v.z)};
}

template <class S>
struct Typed {
  Cylinder<S> cyl;
  Pose<S> pose;
  Vec3<S> p, q;
  S rho;
};

template <class S>
Typed<S> typed(const QueryCase& k) {
  Typed<S> t;
  t.cyl = {opaque<S>(k.cyl.radius), opaque<S>(k.cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) t.pose.R[i][j] = opaque<S>(k.pose.R[i][j]);
  t.pose.t = vec<S>(k.pose.t);
  t.p = vec<S>(k.p);
  t.q = vec<S>(k.q);
  t.rho = opaque<S>(k.rho);
  return t;
}

/// The case rounded to S and widened back (for the oracle).
template <class S>
QueryCase roundedTo(const QueryCase& k) {
  const Typed<S> t = typed<S>(k);
  QueryCase o = k;
  o.cyl = {double(t.cyl.radius), double(t.cyl.lz)};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) o.pose.R[i][j] = double(t.pose.R[i][j]);
  o.pose.t = {double(t.pose.t.x), double(t.pose.t.y), double(t.pose.t.z)};
  o.p = {double(t.p.x), double(t.p.y), double(t.p.z)};
  o.q = {double(t.q.x), double(t.q.y), double(t.q.z)};
  o.rho = double(t.rho);
  return o;
}

struct AgreementStats {
  long cases = 0, hits = 0, float_cases = 0, failures = 0;
  test::StageCounts stages;
};

/// `decide(Typed<S>) -> Decision` for S = double and float (a generic
/// lambda), `truth(QueryCase) -> bool` the oracle.
template <class Decide, class Truth>
AgreementStats runAgreement(Query qy, Family fam, long n, const Decide& decide,
                            const Truth& truth) {
  const std::uint64_t seed = baseSeed();
  AgreementStats st;
  for (long i = 0; i < n && st.failures < 5; ++i) {
    const QueryCase k = qscenes::generate(qy, fam, seed, std::uint64_t(i));
    const bool expect = truth(k);
    const Decision d = decide(typed<double>(k));
    ++st.cases;
    st.stages.add(d.stage);
    st.hits += expect;
    if ((d.answer == Answer::kIntersect) != expect) {
      ++st.failures;
      ADD_FAILURE() << "double, index " << i << ", oracle says " << expect
                    << "\n"
                    << dump(k);
    }
    if (i % 4 == 0) {
      const QueryCase kf = roundedTo<float>(k);
      const bool expect_f = truth(kf);
      ++st.float_cases;
      if ((decide(typed<float>(k)).answer == Answer::kIntersect) != expect_f) {
        ++st.failures;
        ADD_FAILURE() << "float, index " << i << ", oracle says " << expect_f
                      << "\n"
                      << dump(kf);
      }
    }
  }
  std::printf(
      "[ stats    ] %s: %ld cases (+%ld float), %ld hits, 0 expected "
      "disagreements, %ld found; %s\n",
      qscenes::familyName(fam), st.cases, st.float_cases, st.hits, st.failures,
      st.stages.summary(st.cases).c_str());
  return st;
}

/// For the invalid-input tests of the point queries: FP traps are off while
/// it lives; the values those tests pass.
template <class S>
struct InvalidInputs {
  NoFpTraps no_traps;
  const S nan = std::numeric_limits<S>::quiet_NaN();
  const S inf = std::numeric_limits<S>::infinity();
  const Pose<S> I = identityPose<S>();
  const Vec3<S> o{0, 0, 0};

  /// contains() on a Solid<S>{radius, length} (Cylinder or Cone) throws
  /// InvalidInput for a negative radius, a negative length and a NaN radius.
  template <template <class> class Solid>
  void expectBadSizesThrow() const {
    EXPECT_THROW(contains(Solid<S>{-1, 1}, I, o), InvalidInput);
    EXPECT_THROW(contains(Solid<S>{1, -1}, I, o), InvalidInput);
    EXPECT_THROW(contains(Solid<S>{nan, 1}, I, o), InvalidInput);
  }
};

/// A random axis form of a solid, as the sources write it (origin O, unit
/// axis N, length L, radius R), rounded to S.
template <class S>
struct AxisForm {
  Vec3<S> O, N;
  S L, R;
};

/// O in [-2, 2]^3, N uniform on the sphere, L in [0.1, 3], R in [0.1, 2].
template <class S>
AxisForm<S> randomAxisForm(scenes::Rng& g) {
  const auto n = scenes::internal::randomUnit(g);
  AxisForm<S> a;
  a.O = {S(g.uniform(-2, 2)), S(g.uniform(-2, 2)), S(g.uniform(-2, 2))};
  a.N = {S(n.x), S(n.y), S(n.z)};
  a.L = S(g.uniform(0.1, 3));
  a.R = S(g.uniform(0.1, 2));
  return a;
}

/// P's coordinates in the axis form, in double: dp = (P - O).N and t2 the
/// squared distance |(P - O) - dp N|^2 from the axis.
struct AxialCoords {
  double dp, t2;
};

template <class S>
AxialCoords axialCoords(const AxisForm<S>& a, const Vec3<S>& P) {
  const Vec3<S>& O = a.O;
  const Vec3<S>& N = a.N;
  const double v[3] = {double(P.x) - O.x, double(P.y) - O.y, double(P.z) - O.z};
  const double dp = v[0] * N.x + v[1] * N.y + v[2] * N.z;
  const double t2 = (v[0] - dp * N.x) * (v[0] - dp * N.x) +
                    (v[1] - dp * N.y) * (v[1] - dp * N.y) +
                    (v[2] - dp * N.z) * (v[2] - dp * N.z);
  return {dp, t2};
}

/// The contract's invariances of an interval query on {p, q} (a segment or
/// a line), on n seeded cases of qy/fam: reversing {p, q} maps the interval
/// to [1 - hi, 1 - lo]; an exact rigid motion of the world (a signed axis
/// permutation applied to pose, p and q) and scaling every length by 2^e
/// (cases where that is not exact are skipped) leave it unchanged.
/// Shape is Segment or Line; `close(got, base) -> bool` compares one end.
/// Seed baseSeed() + 5, scaled(20000) cases, stops after 5 failures.
template <template <class> class Shape, class Close>
void expectIntervalInvariances(Query qy, Family fam, const Close& close) {
  const std::uint64_t seed = baseSeed() + 5;
  SCOPED_TRACE(seedTrace(seed));
  const long n = scaled(20000);
  auto clipPQ = [](const Cylinder<double>& cyl, const Pose<double>& pose,
                   const Vec3<double>& p, const Vec3<double>& q) {
    return clip(cyl, pose, Shape<double>{p, q});
  };
  long failures = 0;
  for (long i = 0; i < n && failures < 5; ++i) {
    const QueryCase k = qscenes::generate(qy, fam, seed, std::uint64_t(i));
    const auto base = clipPQ(k.cyl, k.pose, k.p, k.q);
    auto same = [&](const std::optional<Interval<double>>& o, bool reversed,
                    const char* what) {
      bool ok = o.has_value() == base.has_value();
      if (ok && o) {
        const double lo = reversed ? 1 - o->hi : o->lo;
        const double hi = reversed ? 1 - o->lo : o->hi;
        ok = close(lo, base->lo) && close(hi, base->hi);
      }
      if (!ok) {
        ++failures;
        ADD_FAILURE() << what << ", index " << i << "\n" << dump(k);
      }
    };
    same(clipPQ(k.cyl, k.pose, k.q, k.p), true, "reversed");
    const SignedPermutation move = SignedPermutation::nth(i);
    const Pose<double> moved = move(k.pose);
    same(clipPQ(k.cyl, moved, move(k.p), move(k.q)), false, "rigid motion");
    // Scaling by 2^e is exact unless something becomes subnormal or
    // overflows, so cases with such values are skipped.
    auto scalable = [](double v) {
      return v == 0 || (std::fabs(v) > 0x1p-900 && std::fabs(v) < 0x1p900);
    };
    bool exact_scaling = scalable(k.cyl.radius) && scalable(k.cyl.lz);
    for (const Vec3<double>& v : {k.p, k.q, k.pose.t})
      exact_scaling =
          exact_scaling && scalable(v.x) && scalable(v.y) && scalable(v.z);
    if (exact_scaling) {
      const int e = (i & 8) ? -37 : 29;
      auto sc = [e](const Vec3<double>& x) {
        return Vec3<double>{std::ldexp(x.x, e), std::ldexp(x.y, e),
                            std::ldexp(x.z, e)};
      };
      Pose<double> sp = k.pose;
      sp.t = sc(k.pose.t);
      same(clipPQ(Cylinder<double>{std::ldexp(k.cyl.radius, e),
                                   std::ldexp(k.cyl.lz, e)},
                  sp, sc(k.p), sc(k.q)),
           false, "scaled");
    }
  }
  EXPECT_EQ(failures, 0);
}

inline std::string familyParamName(
    const ::testing::TestParamInfo<Family>& info) {
  return qscenes::familyName(info.param);
}

}  // namespace tricyl::test
