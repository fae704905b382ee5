// SPDX-License-Identifier: BSD-3-Clause
// tricyl-compare's distance and margin families (distance_families.h).
#include "distance_families.h"

#include <fcl/geometry/shape/cylinder.h>
#include <fcl/narrowphase/detail/gjk_solver_indep.h>
#include <fcl/narrowphase/detail/gjk_solver_libccd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "distance_oracle.h"
#include "harness.h"
#include "margin_oracle.h"
#include "tricyl/triangle_cylinder.h"
#include "tricyl/triangle_cylinder_distance.h"
#include "tricyl/triangle_cylinder_margin.h"

namespace tricyl::distance_families {
namespace {

using Clock = std::chrono::steady_clock;
using V3 = fcl::Vector3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

// The methods, each through the entry point a user calls.
enum M : int { kTricyl, kLibccd6, kLibccdDefault, kIndep, kM };
constexpr const char* kNames[kM] = {"tricyl", "fcl_libccd_1e-6",
                                    "fcl_libccd_default", "fcl_indep"};
constexpr const char* kColors[kM] = {"#d62728", "#1f77b4", "#2ca02c",
                                     "#9467bd"};
constexpr int kMarkers[kM] = {7, 5, 9, 11};

/// One method's answer to one case.
struct Reply {
  double d = 0;       // the distance reported (0 when it says "meeting")
  bool meet = false;  // it says the sets meet (tricyl: kIntersect; FCL:
                      // the call returned false, distance -1)
  Vec3<double> on_cyl{}, on_tri{};
  double ns = 0;      // the call's time
  double bound = -1;  // tricyl's certified error_bound (FCL: none, -1)
  double d_tight = 0, bound_tight = -1;  // after tightenDistance (untimed)
};

fcl::Transform3d toTf(const Pose<double>& p) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) tf.linear()(i, j) = p.R[i][j];
  tf.translation() = V3(p.t.x, p.t.y, p.t.z);
  return tf;
}

Vec3<double> vec(const V3& v) { return {v[0], v[1], v[2]}; }
V3 fv(const Vec3<double>& v) { return V3(v.x, v.y, v.z); }

class Methods {
 public:
  Methods() {
    libccd6_.distance_tolerance = 1e-6;  // fcl::distance's default request
    libccd_default_.distance_tolerance =
        fcl::constants<double>::gjk_default_tolerance();
  }

  Reply run(int m, const scenes::TriCase& k) const {
    Reply r;
    if (m == kTricyl) {
      DistanceResult<double> d;
      const auto t0 = Clock::now();
      const Answer a = tryDistance(k.cyl, k.pose, k.tri, &d);
      const auto t1 = Clock::now();
      r.ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
      r.meet = a != Answer::kDisjoint;
      r.d = r.meet ? 0 : d.distance;
      r.on_cyl = d.point_on_cylinder;
      r.on_tri = d.point_on_triangle;
      r.bound = r.meet ? -1 : d.error_bound;
      if (!r.meet) {  // the opt-in tightening, outside the timed call
        tightenDistance(k.cyl, k.pose, k.tri, &d);
        r.d_tight = d.distance;
        r.bound_tight = d.error_bound;
      }
      return r;
    }
    // FCL gets a proper rotation (harness.h, fclPose: the same world solid).
    const fcl::Cylinderd cyl(k.cyl.radius, k.cyl.lz);
    const fcl::Transform3d tf = toTf(compare::fclPose(k.pose));
    const V3 a = fv(k.tri.a), b = fv(k.tri.b), c = fv(k.tri.c);
    double d = 0;
    V3 p1 = V3::Zero(), p2 = V3::Zero();
    bool ok = false;
    const auto t0 = Clock::now();
    if (m == kLibccd6)
      ok = libccd6_.shapeTriangleDistance(cyl, tf, a, b, c, &d, &p1, &p2);
    else if (m == kLibccdDefault)
      ok =
          libccd_default_.shapeTriangleDistance(cyl, tf, a, b, c, &d, &p1, &p2);
    else
      ok = indep_.shapeTriangleDistance(cyl, tf, a, b, c, &d, &p1, &p2);
    const auto t1 = Clock::now();
    r.ns = std::chrono::duration<double, std::nano>(t1 - t0).count();
    r.meet = !ok || !(d > 0);
    r.d = r.meet ? 0 : d;
    r.on_cyl = vec(p1);  // FCL documents both as world points
    r.on_tri = vec(p2);
    return r;
  }

 private:
  fcl::detail::GJKSolver_libccd<double> libccd6_, libccd_default_;
  fcl::detail::GJKSolver_indep<double> indep_;
};

/// Per-call values, summarised by quantiles.
struct Sample {
  std::vector<double> v;
  void add(double x) { v.push_back(x); }
  double q(double p) const {
    if (v.empty()) return std::nan("");
    std::vector<double> c = v;
    const std::size_t k =
        std::min(c.size() - 1, std::size_t(p * double(c.size())));
    std::nth_element(c.begin(), c.begin() + std::ptrdiff_t(k), c.end());
    return c[k];
  }
  double max() const {
    double m = v.empty() ? std::nan("") : -kInf;
    for (double x : v) m = std::max(m, x);
    return m;
  }
  double mean() const {
    double s = 0;
    for (double x : v) s += x;
    return v.empty() ? std::nan("") : s / double(v.size());
  }
};

struct Row {
  long cases = 0, disjoint = 0;
  long said_apart_when_meeting = 0;  // distance > 0, sets meet
  long said_meeting_when_apart = 0;  // distance 0 / -1, sets apart
  Sample rel;                        // relative error, disjoint cases
  Sample ulps;                       // error in ulps of the true distance
  Sample points;                     // nearest points off their sets,
                                     // relative to the true distance
  Sample ns;                         // time per call
  Sample bound_ulps;                 // tricyl: error_bound in ulps of d
  long bound_over8 = 0;              // ... wider than 8 ulps
  long bound_violated = 0;           // |d - true| > error_bound
  long tight_over8 = 0;              // > 8 ulps after tightenDistance
  long tight_violated = 0;           // ... and violated
  double worst_ulps = -1;            // the case with the largest error
  scenes::TriCase worst{};
  long signs() const {
    return said_apart_when_meeting + said_meeting_when_apart;
  }
};

struct MarginRow {
  long answers = 0, ties = 0;
  long wrong[kM] = {};
  long wrong_ties[kM] = {};
  Sample within_ns, intersect_ns;  // tricyl::withinDistance, intersect
};

std::string fmt(double x) {
  if (std::isnan(x)) return "-";
  char b[32];
  if (x == 0) return "0";
  if (std::isinf(x)) return "inf";
  std::snprintf(b, sizeof b, "%.2g", x);
  return b;
}

std::string fmtNs(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.0f", x);
  return b;
}

void writeFigure(const std::string& dir,
                 const std::vector<scenes::Family>& fams,
                 const std::vector<std::vector<Row>>& rows, bool plots) {
  const std::string name = "distance_error_vs_time";
  std::ofstream g(dir + "/" + name + ".gp");
  g << "# gnuplot script written by tricyl-compare; run: gnuplot " << name
    << ".gp\n"
    << "set terminal pngcairo size 1000,700 noenhanced\n"
    << "set output '" << name << ".png'\n"
    << "set logscale xy\nset grid\n"
    << "set xlabel 'mean time per distance query (ns, log)'\n"
    << "set ylabel 'p99 relative error of the distance (log; 1e-17 = "
       "none)'\n"
    << "set title 'Distance: p99 relative error against mean time, one "
       "point per family'\n"
    << "set key outside right\n";
  for (int m = 0; m < kM; ++m) {
    g << "$m" << m << " << EOD\n";
    for (std::size_t f = 0; f < fams.size(); ++f) {
      const Row& r = rows[f][std::size_t(m)];
      double e = r.rel.q(0.99);
      if (!(e > 1e-17)) e = 1e-17;
      g << r.ns.mean() << " " << e << " " << scenes::familyName(fams[f])
        << "\n";
    }
    g << "EOD\n";
  }
  g << "plot ";
  for (int m = 0; m < kM; ++m)
    g << (m ? ", \\\n  " : "") << "$m" << m << " using 1:2 with points pt "
      << kMarkers[m] << " ps 1.6 lc rgb '" << kColors[m] << "' title '"
      << kNames[m] << "', $m" << m
      << " using 1:2:3 with labels offset 0,1 font ',8' notitle";
  g << "\n";
  g.close();
  if (plots && std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string cmd =
        "cd '" + dir + "' && gnuplot '" + name + ".gp' >/dev/null 2>&1";
    if (std::system(cmd.c_str()) != 0)
      std::fprintf(stderr, "tricyl-compare: gnuplot failed on %s.gp\n",
                   name.c_str());
  }
}

}  // namespace

std::string run(const Options& o) {
  const Methods methods;
  const std::vector<scenes::Family>& fams = o.families;
  std::vector<std::vector<Row>> rows(fams.size(), std::vector<Row>(kM));
  std::vector<MarginRow> mrows(fams.size());
  const auto wall0 = Clock::now();

  for (std::size_t f = 0; f < fams.size(); ++f) {
    // ---- distances ----
    for (long i = 0; i < o.cases; ++i) {
      const scenes::TriCase k =
          scenes::distanceCase(fams[f], o.seed, std::uint64_t(i));
      const oracle::DistanceEnclosure e =
          oracle::distanceEnclosure(k.cyl, k.pose, k.tri);
      const double truth = e.mid_hi;
      for (int m = 0; m < kM; ++m) {
        // Rotate which method runs first (caches, predictors).
        const int mm = int((m + i) % kM);
        const Reply r = methods.run(mm, k);
        Row& row = rows[f][std::size_t(mm)];
        ++row.cases;
        row.ns.add(r.ns);
        if (e.intersect) {
          if (!r.meet) ++row.said_apart_when_meeting;
          continue;
        }
        ++row.disjoint;
        if (r.meet) {
          ++row.said_meeting_when_apart;
          row.rel.add(1);  // a distance of 0 for a positive one
          row.ulps.add(kInf);
          continue;
        }
        row.rel.add(oracle::relativeError(e, r.d));
        if (r.bound >= 0) {
          int ex = 0;
          (void)std::frexp(r.d, &ex);
          const double b =
              r.bound / std::ldexp(1.0, std::max(ex - 1, -1022) - 52);
          row.bound_ulps.add(b);
          if (b > 8) ++row.bound_over8;
          if (r.d - r.bound > e.hi || r.d + r.bound < e.lo)
            ++row.bound_violated;
          (void)std::frexp(r.d_tight, &ex);
          if (r.bound_tight > 8 * std::ldexp(1.0, std::max(ex - 1, -1022) - 52))
            ++row.tight_over8;
          if (r.d_tight - r.bound_tight > e.hi ||
              r.d_tight + r.bound_tight < e.lo)
            ++row.tight_violated;
        }
        const double ulps = oracle::ulpsError(e, r.d);
        row.ulps.add(ulps);
        if (ulps > row.worst_ulps) {
          row.worst_ulps = ulps;
          row.worst = k;
        }
        const double off =
            std::max(oracle::pointCylinderDistance(k.cyl, k.pose, r.on_cyl),
                     oracle::pointTriangleDistance(k.tri, r.on_tri));
        row.points.add(truth > 0 ? off / truth : kInf);
      }
    }
    // ---- margins ----
    MarginRow& mr = mrows[f];
    for (long i = 0; i < o.margin_cases; ++i) {
      const scenes::TriCase k = scenes::distanceCase(
          fams[f], o.seed ^ 0x6d617267696eULL, std::uint64_t(i));
      const oracle::DistanceEnclosure e =
          oracle::distanceEnclosure(k.cyl, k.pose, k.tri);
      const double size = std::max(k.cyl.radius, k.cyl.lz);
      scenes::Rng g(o.seed ^ (std::uint64_t(i) << 20) ^
                    (std::uint64_t(fams[f]) << 56));
      std::vector<std::pair<double, bool>> margins = {
          {0.0, false},
          {1e-3 * size, false},
          {1e-2 * size, false},
          {0.1 * size * g.uniform(), false}};
      if (!e.intersect && e.mid_hi > 0) {
        const double dt = e.mid_hi;
        for (double ulps : {1.0, 4.0, 1048576.0}) {
          int ex = 0;
          (void)std::frexp(dt, &ex);
          const double ulp = std::ldexp(1.0, std::max(ex - 1, -1022) - 52);
          if (dt - ulps * ulp >= 0) margins.push_back({dt - ulps * ulp, true});
          margins.push_back({dt + ulps * ulp, true});
        }
        margins.push_back({dt, true});
      }
      Reply fcl[kM];
      for (int m = 1; m < kM; ++m) fcl[m] = methods.run(m, k);
      {
        const auto t0 = Clock::now();
        const Answer a = tryIntersect(k.cyl, k.pose, k.tri);
        const auto t1 = Clock::now();
        (void)a;
        mr.intersect_ns.add(
            std::chrono::duration<double, std::nano>(t1 - t0).count());
      }
      for (const auto& [margin, tie] : margins) {
        if (!(std::isfinite(margin) && margin >= 0)) continue;
        const bool truth =
            margin_oracle::withinDistance(k.cyl, k.pose, k.tri, margin);
        ++mr.answers;
        if (tie) ++mr.ties;
        const auto t0 = Clock::now();
        const bool ours = tryWithinDistance(k.cyl, k.pose, k.tri, margin) !=
                          Answer::kDisjoint;
        const auto t1 = Clock::now();
        mr.within_ns.add(
            std::chrono::duration<double, std::nano>(t1 - t0).count());
        bool said[kM];
        said[kTricyl] = ours;
        for (int m = 1; m < kM; ++m)
          said[m] = fcl[m].meet || fcl[m].d <= margin;
        for (int m = 0; m < kM; ++m)
          if (said[m] != truth) {
            ++mr.wrong[m];
            if (tie) ++mr.wrong_ties[m];
          }
      }
    }
  }
  const double wall =
      std::chrono::duration<double>(Clock::now() - wall0).count();

  // ---- outputs ----
  std::ofstream csv(o.out + "/distance.csv");
  csv << "family,method,cases,disjoint,sign_disagreements,apart_when_meeting,"
         "meeting_when_apart,rel_err_median,rel_err_p99,rel_err_max,"
         "ulps_max,points_off_rel_p99,points_off_rel_max,mean_ns,median_ns,"
         "p99_ns,x_libccd_1e-6\n";
  std::ostringstream md;
  md << "# Distance and margin families\n\n"
     << "Command: `tricyl-compare --distance-cases " << o.cases
     << " --margin-cases " << o.margin_cases << " --seed " << o.seed << "`; "
     << fmt(wall) << " s.\n\n"
     << "Each family's scenes (the six kinds of the intersection families), "
        "three in four moved apart along a random direction by 10^-15 .. "
        "10^3 (log-uniform) of the cylinder's size max(r, lz). Every answer "
        "settled by the 333-bit MPFR oracle (support/distance_oracle.h: an "
        "enclosure of the true distance, relative width <= 2^-200 on these "
        "cases, far below what it judges). *rel. error*: |d - true| / true "
        "over the disjoint cases (a distance of 0 or -1 for a disjoint pair "
        "counts 1); *ulps*: the error in units in the last place of the true "
        "distance; *sign*: a positive distance for a pair the exact Boolean "
        "says meets, or 0 / -1 for one it says is apart; *points off*: the "
        "larger distance of the two nearest points to their sets, over the "
        "true distance (FCL documents both as world points; "
        "`GJKSolver_indep` returns them in the cylinder's frame); time per "
        "call (ns) and the mean of `fcl_libccd_1e-6` over the method's mean "
        "(x libccd, same run). `fcl_libccd_1e-6`: `GJKSolver_libccd` with "
        "distance_tolerance 1e-6 (its default, and fcl::distance's); "
        "`fcl_libccd_default`: with FCL's gjk_default_tolerance; "
        "`fcl_indep`: `GJKSolver_indep` with its defaults.\n\n"
     << "| family | method | cases (apart) | sign | rel. error median / p99 "
        "/ max | max ulps | points off p99 / max | mean / median / p99 ns | "
        "x libccd |\n|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t f = 0; f < fams.size(); ++f) {
    const double ref = rows[f][kLibccd6].ns.mean();
    for (int m = 0; m < kM; ++m) {
      const Row& r = rows[f][std::size_t(m)];
      const double x = ref / r.ns.mean();
      md << "| " << scenes::familyName(fams[f]) << " | " << kNames[m] << " | "
         << r.cases << " (" << r.disjoint << ") | " << r.signs() << " | "
         << fmt(r.rel.q(0.5)) << " / " << fmt(r.rel.q(0.99)) << " / "
         << fmt(r.rel.max()) << " | " << fmt(r.ulps.max()) << " | "
         << fmt(r.points.q(0.99)) << " / " << fmt(r.points.max()) << " | "
         << fmtNs(r.ns.mean()) << " / " << fmtNs(r.ns.q(0.5)) << " / "
         << fmtNs(r.ns.q(0.99)) << " | " << fmt(x) << " |\n";
      csv << scenes::familyName(fams[f]) << "," << kNames[m] << "," << r.cases
          << "," << r.disjoint << "," << r.signs() << ","
          << r.said_apart_when_meeting << "," << r.said_meeting_when_apart
          << "," << r.rel.q(0.5) << "," << r.rel.q(0.99) << "," << r.rel.max()
          << "," << r.ulps.max() << "," << r.points.q(0.99) << ","
          << r.points.max() << "," << r.ns.mean() << "," << r.ns.q(0.5) << ","
          << r.ns.q(0.99) << "," << x << "\n";
    }
  }
  // tricyl's certified bound: how wide it is, and that it holds.
  md << "\ntricyl's `error_bound` (certified: |d - true| <= error_bound), "
        "in ulps of the returned distance over the disjoint cases: median / "
        "p99 / max, how many are wider than 8 ulps (distances below about "
        "2^-45 of the problem's size: docs/distance.md, section 6) and how "
        "many the oracle finds violated; then the same two counts after the "
        "opt-in `tightenDistance` (not timed above).\n\n"
     << "| family | apart | error_bound ulps median / p99 / max | > 8 ulps | "
        "violated | tightenDistance: > 8 ulps / violated |\n"
        "|---|---|---|---|---|---|\n";
  std::ofstream bcsv(o.out + "/distance_bound.csv");
  bcsv << "family,disjoint,bound_ulps_median,bound_ulps_p99,bound_ulps_max,"
          "bound_over8,bound_violated,tight_over8,tight_violated\n";
  for (std::size_t f = 0; f < fams.size(); ++f) {
    const Row& r = rows[f][kTricyl];
    md << "| " << scenes::familyName(fams[f]) << " | " << r.disjoint << " | "
       << fmt(r.bound_ulps.q(0.5)) << " / " << fmt(r.bound_ulps.q(0.99))
       << " / " << fmt(r.bound_ulps.max()) << " | " << r.bound_over8 << " | "
       << r.bound_violated << " | " << r.tight_over8 << " / "
       << r.tight_violated << " |\n";
    bcsv << scenes::familyName(fams[f]) << "," << r.disjoint << ","
         << r.bound_ulps.q(0.5) << "," << r.bound_ulps.q(0.99) << ","
         << r.bound_ulps.max() << "," << r.bound_over8 << ","
         << r.bound_violated << "," << r.tight_over8 << "," << r.tight_violated
         << "\n";
  }
  md << "\n![distance error vs time](distance_error_vs_time.png)\n\n"
     << "## Margin Booleans\n\n"
     << "Per family " << o.margin_cases
     << " scenes (the distance families' generator, another seed), margins "
        "0, 10^-3 and 10^-2 of the size and a uniform draw in [0, 0.1] of "
        "it, and, for a disjoint scene, the true distance itself and 1, 4 "
        "and 2^20 ulps either side of it (*ties*). Every answer settled by "
        "the exact GMP margin oracle (compare/margin_oracle.h: sign "
        "conditions on the Minkowski decomposition, rational arithmetic). "
        "tricyl: `tryWithinDistance`; FCL: its distance <= margin (a "
        "'meeting' answer counts as within). Time: `withinDistance` against "
        "`tryIntersect` on the same scenes, mean ns per call.\n\n"
     << "| family | answers (ties) | wrong: tricyl | fcl_libccd_1e-6 | "
        "fcl_libccd_default | fcl_indep | wrong on ties: tricyl / libccd 1e-6 "
        "/ libccd default / indep | withinDistance / intersect mean ns |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  std::ofstream mcsv(o.out + "/margin.csv");
  mcsv << "family,answers,ties,wrong_tricyl,wrong_libccd_1e-6,"
          "wrong_libccd_default,wrong_indep,ties_wrong_tricyl,"
          "ties_wrong_libccd_1e-6,ties_wrong_libccd_default,ties_wrong_indep,"
          "within_mean_ns,intersect_mean_ns\n";
  for (std::size_t f = 0; f < fams.size(); ++f) {
    const MarginRow& r = mrows[f];
    md << "| " << scenes::familyName(fams[f]) << " | " << r.answers << " ("
       << r.ties << ") | " << r.wrong[0] << " | " << r.wrong[1] << " | "
       << r.wrong[2] << " | " << r.wrong[3] << " | " << r.wrong_ties[0] << " / "
       << r.wrong_ties[1] << " / " << r.wrong_ties[2] << " / "
       << r.wrong_ties[3] << " | " << fmtNs(r.within_ns.mean()) << " / "
       << fmtNs(r.intersect_ns.mean()) << " |\n";
    mcsv << scenes::familyName(fams[f]) << "," << r.answers << "," << r.ties;
    for (int m = 0; m < kM; ++m) mcsv << "," << r.wrong[m];
    for (int m = 0; m < kM; ++m) mcsv << "," << r.wrong_ties[m];
    mcsv << "," << r.within_ns.mean() << "," << r.intersect_ns.mean() << "\n";
  }
  md << "\nThe case with the largest error in ulps per family and method: "
        "distance_worst_cases.txt (bit-exact, `case` lines as in "
        "worst_cases.txt).\n";
  std::ofstream(o.out + "/distance.md") << md.str();
  {
    std::ofstream w(o.out + "/distance_worst_cases.txt");
    w << "# tricyl-compare distance families: per family and method, the "
         "disjoint case with the largest error in ulps of the true "
         "distance\n";
    for (std::size_t f = 0; f < fams.size(); ++f)
      for (int m = 0; m < kM; ++m) {
        const Row& r = rows[f][std::size_t(m)];
        if (r.worst_ulps < 0) continue;
        w << "# " << scenes::familyName(fams[f]) << " " << kNames[m] << " ulps "
          << r.worst_ulps << "\ncase " << compare::formatCaseHex(r.worst)
          << "\n";
      }
  }
  writeFigure(o.out, fams, rows, o.plots);

  std::ostringstream s;
  s << "distance families (" << fmt(wall) << " s): wrote " << o.out
    << "/distance.md, distance.csv, margin.csv, distance_worst_cases.txt, "
       "distance_error_vs_time.gp\n";
  for (std::size_t f = 0; f < fams.size(); ++f) {
    s << "  " << scenes::familyName(fams[f]);
    for (int m = 0; m < kM; ++m) {
      const Row& r = rows[f][std::size_t(m)];
      s << "  " << kNames[m] << " p99 " << fmt(r.rel.q(0.99)) << " sign "
        << r.signs() << " " << fmtNs(r.ns.mean()) << "ns";
    }
    s << "  | margin wrong tricyl " << mrows[f].wrong[0] << " libccd "
      << mrows[f].wrong[1] << "\n";
  }
  return s.str();
}

}  // namespace tricyl::distance_families
