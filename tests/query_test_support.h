// Shared driver for the random oracle-agreement tests of the cylinder query
// family (tests/{point_cylinder,point_cone,sphere_cylinder,segment_cylinder}
// _test.cpp): seeded cases from compare/query_scenes.h, checked against the
// exact oracles of compare/query_oracles.h, in double on every case and in
// float (inputs rounded to float, oracle re-run on the rounded input) on
// every 4th.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
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
  std::array<long, 5> stages{};
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
    ++st.stages[size_t(d.stage)];
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
      "disagreements, %ld found; early-out %ld, fast %ld, extended %ld, "
      "exact %ld (%.3f%%)\n",
      qscenes::familyName(fam), st.cases, st.float_cases, st.hits, st.failures,
      st.stages[0], st.stages[1], st.stages[4], st.stages[2],
      100.0 * double(st.stages[2]) / double(st.cases ? st.cases : 1));
  return st;
}

inline std::string familyParamName(
    const ::testing::TestParamInfo<Family>& info) {
  return qscenes::familyName(info.param);
}

}  // namespace tricyl::test
