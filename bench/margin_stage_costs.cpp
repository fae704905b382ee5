// SPDX-License-Identifier: BSD-3-Clause
// tricyl-margin-stage-costs: what each stage of withinDistance costs, beside
// intersect on the same scenes in the same run, and its worst case on
// hostile inputs (the margin counterpart of tricyl-stage-costs). A report,
// not a test: it asserts nothing.
//
// 1. Tie-heavy scenes: the distance families' scenes (compare/
//    distance_families.cpp: the six families, three in four translated by
//    1e-15 .. 1e3 of the size), each with the margins of the harness: 0,
//    1e-3 and 1e-2 of the size, one uniform in [0, 10%], and, for a
//    disjoint pair, the distance d itself and d -+ 1, 4, 2^20 ulps (d from
//    tricyl::distance, certified to a few ulps: the margins are ties or
//    within a few ulps of one). 4096 queries per family, visited in an
//    order the branch predictor cannot learn (bench/walk.h); mean per query
//    of whole passes, then every query timed one by one (the clock's cost
//    subtracted), by the deciding stage.
// 2. Hostile inputs, as set 5 of tricyl-stage-costs: every coordinate,
//    translation, radius, length, rotation entry and the margin with a
//    random exponent in 2^-1070 .. 2^1020 (outside the range gate: the GMP
//    paths), and a second set inside the range gate (lengths
//    2^-1070 .. 2^40, rotation entries below 2 in magnitude, the margin
//    within 2^-40 .. 1 of the largest length so that the tori are reached).
//    Each query timed three times, the least kept (a preemption of the
//    shared machine is not the query's cost); median, p99, max.
// 3. Hostile thresholds: the queries of the set outside the range gate
//    with their margin at the threshold where the answer flips (the two
//    adjacent doubles lo < hi with withinDistance false at lo and true at
//    hi, found by bisection on the bit patterns; both answers are exact, so
//    the bracket is the true one): at lo every part of the neighbourhood
//    is decided and misses, one of them by a hair, the slowest queries
//    there are. Timed as in 2, at lo and at hi.
// 4. Wide-spread tangencies: an edge tangent to a rim torus whose tube is
//    2^-1000 .. 2^-800 of the cylinder while the edge's ends are
//    2^900 .. 2^1020 away (the construction of the test
//    WideSpreadTiesAgreeWithConstruction, tests/triangle_cylinder_margin_
//    test.cpp), margins at the tangency distance and 1 ulp either side:
//    the quartic's Sturm sequence on coefficients of about 12,000 bits.
//
// Usage: tricyl-margin-stage-costs [passes] [--dump N] [--only SECTION]
//   --dump N: also print the N slowest hostile queries as hex floats
//   (cylinder r lz, R row-major, t, the three vertices, margin);
//   --only ties|outside|inside|thresholds|tangents: run one section (for
//   a profiler);
//   --count N: N hostile queries per set (default 20,000; the thresholds
//   take the first N / 50 queries of the set outside the gate);
//   --replay FILE: time the queries of FILE instead (lines in the --dump
//   format, "<time> us:" prefix optional, '#' comments; the regression
//   list bench/data/margin_worst.txt holds the slowest of past runs).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "scenes.h"
#include "stage_report.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"
#include "tricyl/triangle_cylinder_margin.h"
#include "walk.h"

namespace {

using tricyl::Answer;
using tricyl::Decision;
using tricyl::bench::Clock;
using tricyl::bench::ns;
using tricyl::bench::quantile;
using tricyl::scenes::Family;
using tricyl::scenes::TriCase;

constexpr int kCases = 4096;

struct MarginCase {
  TriCase k;
  double m;
};

/// kCases margin queries of family f with the harness's margins.
std::vector<MarginCase> tieHeavy(Family f) {
  std::vector<MarginCase> v;
  for (std::uint64_t i = 0; v.size() < std::size_t(kCases); ++i) {
    const TriCase k = tricyl::scenes::distanceCase(f, 20261125u, i);
    const double size = std::max(k.cyl.radius, k.cyl.lz);
    tricyl::scenes::Rng g(i * 0x9e3779b97f4a7c15ULL ^ std::uint64_t(f));
    std::vector<double> ms = {0.0, 1e-3 * size, 1e-2 * size,
                              0.1 * size * g.uniform()};
    tricyl::DistanceResult<double> d{};
    if (tricyl::tryDistance(k.cyl, k.pose, k.tri, &d) == Answer::kDisjoint) {
      const double dt = d.distance;
      for (double ulps : {1.0, 4.0, 1048576.0}) {
        int ex = 0;
        (void)std::frexp(dt, &ex);
        const double ulp = std::ldexp(1.0, std::max(ex - 1, -1022) - 52);
        if (dt - ulps * ulp >= 0) ms.push_back(dt - ulps * ulp);
        ms.push_back(dt + ulps * ulp);
      }
      ms.push_back(dt);
    }
    for (double m : ms)
      if (v.size() < std::size_t(kCases)) v.push_back({k, m});
  }
  return v;
}

struct Hostile {
  tricyl::Cylinder<double> cyl;
  tricyl::Pose<double> pose;
  tricyl::Triangle<double> tri;
  double m;
};

/// Random exponents: `len_hi` the largest exponent of a length, `rot_hi`
/// of a rotation entry; the margin's exponent is drawn relative to the
/// largest length when `margin_rel` (else like a length).
std::vector<Hostile> hostileSet(std::uint64_t seed, int n, int len_hi,
                                int rot_hi, bool margin_rel) {
  std::uint64_t x = seed;
  auto next = [&x]() {
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return x;
  };
  std::vector<Hostile> v;
  for (int i = 0; i < n; ++i) {
    const TriCase k = tricyl::scenes::randomExponentCase(next, len_hi, rot_hi);
    Hostile h{k.cyl, k.pose, k.tri, 0};
    if (margin_rel) {
      double big = std::max(h.cyl.radius, h.cyl.lz);
      for (const auto* p : {&h.tri.a, &h.tri.b, &h.tri.c, &h.pose.t})
        big =
            std::max({big, std::fabs(p->x), std::fabs(p->y), std::fabs(p->z)});
      h.m = std::ldexp(std::fabs(tricyl::scenes::randomExponent(next, -40, 0)),
                       std::ilogb(big));
    } else {
      h.m = std::fabs(tricyl::scenes::randomExponent(next, -1070, len_hi));
    }
    v.push_back(h);
  }
  return v;
}

void hostileReport(const char* title, const std::vector<Hostile>& v, int dump) {
  std::vector<double> tw, ti;
  std::vector<std::pair<double, int>> worst;
  long hits = 0, by[8] = {};
  double max_by[8] = {};
  for (std::size_t i = 0; i < v.size(); ++i) {
    const Hostile& h = v[i];
    double best = 1e300, best_i = 1e300;
    Decision d{};
    for (int rep = 0; rep < 3; ++rep) {
      const auto a = Clock::now();
      d = tricyl::decideWithinDistance(h.cyl, h.pose, h.tri, h.m);
      const auto b = Clock::now();
      hits += tricyl::tryIntersect(h.cyl, h.pose, h.tri) == Answer::kIntersect;
      const auto c = Clock::now();
      best = std::min(best, ns(b - a));
      best_i = std::min(best_i, ns(c - b));
    }
    hits += d.answer == Answer::kIntersect;
    ++by[int(d.stage)];
    max_by[int(d.stage)] = std::max(max_by[int(d.stage)], best);
    tw.push_back(best);
    ti.push_back(best_i);
    worst.push_back({best, int(i)});
  }
  std::printf(
      "\n## %s (%zu queries)\n\n| query | median | p99 | max |\n"
      "|---|---:|---:|---:|\n",
      title, v.size());
  std::printf("| withinDistance | %.1f us | %.1f us | %.1f us |\n",
              quantile(tw, 0.5) / 1e3, quantile(tw, 0.99) / 1e3,
              *std::max_element(tw.begin(), tw.end()) / 1e3);
  std::printf("| intersect | %.1f us | %.1f us | %.1f us |\n",
              quantile(ti, 0.5) / 1e3, quantile(ti, 0.99) / 1e3,
              *std::max_element(ti.begin(), ti.end()) / 1e3);
  std::printf("\nwithinDistance by deciding stage:");
  for (tricyl::Stage s : {tricyl::Stage::kEarlyOut, tricyl::Stage::kFastPath,
                          tricyl::Stage::kRunning, tricyl::Stage::kExtended,
                          tricyl::Stage::kExact, tricyl::Stage::kExactGmp,
                          tricyl::Stage::kInvalid})
    if (by[int(s)] > 0)
      std::printf(" %s %ld (max %.1f us);", tricyl::bench::stageName(s),
                  by[int(s)], max_by[int(s)] / 1e3);
  std::printf(" (%ld hits)\n", hits);
  if (dump > 0) {
    std::sort(worst.rbegin(), worst.rend());
    std::printf("\nslowest:\n");
    for (int j = 0; j < dump && j < int(worst.size()); ++j) {
      const Hostile& h = v[std::size_t(worst[std::size_t(j)].second)];
      std::printf("%.1f us:", worst[std::size_t(j)].first / 1e3);
      const double vals[] = {
          h.cyl.radius,   h.cyl.lz,       h.pose.R[0][0], h.pose.R[0][1],
          h.pose.R[0][2], h.pose.R[1][0], h.pose.R[1][1], h.pose.R[1][2],
          h.pose.R[2][0], h.pose.R[2][1], h.pose.R[2][2], h.pose.t.x,
          h.pose.t.y,     h.pose.t.z,     h.tri.a.x,      h.tri.a.y,
          h.tri.a.z,      h.tri.b.x,      h.tri.b.y,      h.tri.b.z,
          h.tri.c.x,      h.tri.c.y,      h.tri.c.z,      h.m};
      for (double x : vals) std::printf(" %a", x);
      std::printf("\n");
    }
  }
}

/// Section 3: the first n queries of `v` with a threshold (disjoint at
/// margin 0, within at the largest double), the margin set to lo and hi.
void thresholdReport(const std::vector<Hostile>& v, std::size_t n, int dump) {
  auto at = [](std::int64_t b) {
    double x;
    std::memcpy(&x, &b, sizeof x);
    return x;
  };
  std::vector<Hostile> lo_set, hi_set;
  for (const Hostile& h0 : v) {
    if (lo_set.size() >= n) break;
    auto within = [&](double m) {
      return tricyl::tryWithinDistance(h0.cyl, h0.pose, h0.tri, m) ==
             Answer::kIntersect;
    };
    std::int64_t lo = 0, hi = 0x7fefffffffffffff;
    if (within(0) || !within(at(hi))) continue;
    while (hi - lo > 1) {
      const std::int64_t mid = lo + (hi - lo) / 2;
      (within(at(mid)) ? hi : lo) = mid;
    }
    Hostile h = h0;
    h.m = at(lo);
    lo_set.push_back(h);
    h.m = at(hi);
    hi_set.push_back(h);
  }
  hostileReport("Thresholds outside the range gate, margin lo (false)", lo_set,
                dump);
  hostileReport("Thresholds outside the range gate, margin hi (true)", hi_set,
                dump);
}

/// Section 4: n tangent edges (dense mantissas; half reach through a
/// rotation entry), each with the margins d, d - 1 ulp, d + 1 ulp.
void tangentReport(int n, int dump) {
  tricyl::scenes::Rng g(0x74616e67u);
  auto mantissa = [&g](int bits) {  // in [1, 2), `bits` significant bits
    return 1.0 + std::ldexp(double(g.next() >> (64 - (bits - 1))), 1 - bits);
  };
  std::vector<Hostile> v;
  for (int i = 0; i < n; ++i) {
    const double a = i % 2 == 0 ? 3 : 4, b = 7 - a;
    const double e = std::ldexp(mantissa(48), -1000 + int(g.next() % 200));
    const double r = std::ldexp(mantissa(53), int(g.next() % 41) - 20);
    const double lz = std::ldexp(mantissa(53), int(g.next() % 41) - 20);
    const double h = lz / 2,
                 A = std::ldexp(mantissa(53), 900 + int(g.next() % 121));
    Hostile q{{r, lz}, tricyl::identityPose<double>(), {}, 0};
    q.pose.t = {-a * e, 0, -b * e};
    if (g.next() % 2 == 0)
      q.pose.R[1][1] = std::ldexp(mantissa(53), 900 + int(g.next() % 121));
    q.tri = {{r, -A, h}, {r, A, h}, {r, A, h + std::max(lz, r)}};
    for (double m :
         {5 * e, std::nextafter(5 * e, 0.0), std::nextafter(5 * e, 1.0)}) {
      q.m = m;
      v.push_back(q);
    }
  }
  hostileReport(
      "Wide-spread tangencies (tube 2^-1000 .. 2^-800, ends 2^900 .. 2^1020)",
      v, dump);
}

/// The queries of a --dump listing (24 hex floats a line after an optional
/// "<time> us:" prefix; blank lines and '#' comments skipped).
std::vector<Hostile> readReplay(const char* path) {
  std::vector<Hostile> v;
  std::FILE* f = std::fopen(path, "r");
  if (f == nullptr) {
    std::fprintf(stderr, "cannot open %s\n", path);
    return v;
  }
  char line[4096];
  while (std::fgets(line, sizeof line, f) != nullptr) {
    const char* p = line;
    if (const char* colon = std::strchr(line, ':')) p = colon + 1;
    double x[24];
    int n = 0;
    char* end = nullptr;
    while (n < 24) {
      x[n] = std::strtod(p, &end);
      if (end == p) break;
      p = end;
      ++n;
    }
    if (line[0] == '#' || n != 24) continue;
    Hostile h{{x[0], x[1]}, tricyl::identityPose<double>(), {}, x[23]};
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) h.pose.R[j][k] = x[2 + 3 * j + k];
    h.pose.t = {x[11], x[12], x[13]};
    h.tri = {
        {x[14], x[15], x[16]}, {x[17], x[18], x[19]}, {x[20], x[21], x[22]}};
    v.push_back(h);
  }
  std::fclose(f);
  return v;
}

}  // namespace

int main(int argc, char** argv) {
  int passes = 10, dump = 0, count = 20000;
  std::string only, replay;
  for (int i = 1; i < argc; ++i) {
    if (std::strcmp(argv[i], "--dump") == 0 && i + 1 < argc)
      dump = std::atoi(argv[++i]);
    else if (std::strcmp(argv[i], "--count") == 0 && i + 1 < argc)
      count = std::max(1, std::atoi(argv[++i]));
    else if (std::strcmp(argv[i], "--only") == 0 && i + 1 < argc)
      only = argv[++i];
    else if (std::strcmp(argv[i], "--replay") == 0 && i + 1 < argc)
      replay = argv[++i];
    else
      passes = std::max(1, std::atoi(argv[i]));
  }
  const double clock_ns = tricyl::bench::clockOverheadNs();
  if (!replay.empty()) {
    const std::vector<Hostile> v = readReplay(replay.c_str());
    for (int p = 0; p < passes; ++p) hostileReport(replay.c_str(), v, dump);
    return 0;
  }
  auto runs = [&only](const char* s) { return only.empty() || only == s; };
  if (runs("ties")) {
    std::printf(
        "# tricyl-margin-stage-costs\n\n%d margin queries per family (the "
        "harness's tie-heavy margins), %d passes; clock overhead %.1f ns "
        "(subtracted from single-query times)\n\n",
        kCases, passes, clock_ns);
    std::printf(
        "| family | withinDistance mean | intersect mean | ratio | "
        "withinDistance median | p99 | max |\n|---|---:|---:|---:|---:|---:|"
        "---:|\n");
    std::vector<std::string> stage_rows;
    for (Family fam : tricyl::scenes::kAllFamilies) {
      const std::vector<MarginCase> v = tieHeavy(fam);
      const tricyl::bench::FamilyCosts fw = tricyl::bench::measureFamily(
          v, passes, clock_ns, [](const MarginCase& c) {
            return tricyl::decideWithinDistance(c.k.cyl, c.k.pose, c.k.tri,
                                                c.m);
          });
      const tricyl::bench::FamilyCosts fi = tricyl::bench::measureFamily(
          v, passes, clock_ns, [](const MarginCase& c) {
            return tricyl::decideIntersect(c.k.cyl, c.k.pose, c.k.tri);
          });
      std::printf(
          "| %s | %.1f ns | %.1f ns | %.2f | %.1f ns | %.0f ns | %.0f ns |\n",
          tricyl::scenes::familyName(fam), fw.mean, fi.mean, fw.mean / fi.mean,
          quantile(fw.all, 0.5), quantile(fw.all, 0.99),
          *std::max_element(fw.all.begin(), fw.all.end()));
      for (const auto& r :
           tricyl::bench::stageRows(tricyl::scenes::familyName(fam), fw))
        stage_rows.push_back(r);
      if (fw.hits + fi.hits == -1) std::printf("\n");  // keep answers alive
    }
    std::printf(
        "\n## withinDistance by stage (queries timed one by one)\n\n| family "
        "| stage | share | mean | p99 | max "
        "|\n|---|---|---:|---:|---:|---:|\n");
    for (const auto& r : stage_rows) std::printf("%s", r.c_str());
  }
  if (runs("outside"))
    hostileReport(
        "Random exponents, outside the range gate (2^-1070 .. 2^1020)",
        hostileSet(0x9e3779b97f4a7c15ULL, count, 1020, 1020, false), dump);
  if (runs("thresholds"))
    thresholdReport(hostileSet(0x9e3779b97f4a7c15ULL, count, 1020, 1020, false),
                    std::size_t(std::max(1, count / 50)), dump);
  if (runs("tangents")) tangentReport(std::max(1, count / 100), dump);
  if (runs("inside"))
    hostileReport(
        "Random exponents inside the range gate (lengths 2^-1070 .. 2^40, "
        "rotation entries < 2, margin 2^-40 .. 1 of the largest length)",
        hostileSet(0x5851f42d4c957f2dULL, count, 40, 0, true), dump);
  return 0;
}
