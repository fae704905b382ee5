// SPDX-License-Identifier: BSD-3-Clause
// Output files of tricyl-compare. Every number in report.md comes from the
// same rows as results.csv / results.json.
#include "report.h"

#include <sys/stat.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

namespace tricyl::compare {

namespace {

using nlohmann::json;

struct Row {
  std::string family;
  Method method;
  std::uint64_t cases, fp, fn, hangs;
  double error_rate, max_clear, max_pen, ns_median, ns_p99, ns_max;
  std::uint64_t timed;
  double ns_mean;
  std::uint64_t tri_oracle, tri_missed, tri_extra;
};

Row makeRow(const std::string& family, Method m, MethodStats ms) {
  Row r{family,
        m,
        ms.cases,
        ms.false_positives,
        ms.false_negatives,
        ms.hangs,
        0,
        ms.max_fp_size,
        ms.max_fn_size,
        kNaN,
        kNaN,
        kNaN,
        ms.ns.size(),
        mean(ms.ns),
        ms.tri_oracle,
        ms.tri_missed,
        ms.tri_extra};
  r.error_rate = ms.cases ? double(ms.wrong()) / double(ms.cases) : 0.0;
  r.ns_median = percentile(ms.ns, 50);
  r.ns_p99 = percentile(ms.ns, 99);
  r.ns_max = percentile(ms.ns, 100);
  return r;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

/// A number for the tables: integers plainly, others in 3 significant digits.
std::string num(double v) {
  if (std::isnan(v)) return "n/a";
  if (v == 0) return "0";
  if (std::fabs(v) >= 1e-3 && std::fabs(v) < 1e5) return fmt("%.3g", v);
  return fmt("%.2e", v);
}

std::string pct(double v) { return fmt("%.3g %%", 100 * v); }

json jnum(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

// Indexed by tricyl::Stage (5 is no longer produced).
const char* kStageNames[] = {"early_out", "fast_path", "exact",    "invalid",
                             "extended",  "running",   "exact_gmp"};

void mkdirs(const std::string& dir) {
  std::string cur;
  std::stringstream ss(dir);
  std::string part;
  if (!dir.empty() && dir[0] == '/') cur = "/";
  while (std::getline(ss, part, '/')) {
    if (part.empty()) continue;
    cur += part + "/";
    mkdir(cur.c_str(), 0777);
  }
  struct stat st;
  if (stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw std::runtime_error("cannot create output folder " + dir);
}

std::string machine() {
  std::string cpu = "unknown CPU";
  std::ifstream in("/proc/cpuinfo");
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  struct utsname u;
  uname(&u);
  return cpu + ", " + std::to_string(sysconf(_SC_NPROCESSORS_ONLN)) +
         " online cores, " + u.sysname + " " + u.release + ", g++ " +
         __VERSION__;
}

/// The floor on which zero error rates are drawn: a decade below the
/// smallest nonzero rate, at most 1e-6.
double floorFor(const std::vector<double>& rates) {
  double lo = 1e-6 * 10;
  for (double r : rates)
    if (r > 0) lo = std::min(lo, r);
  return std::pow(10.0, std::floor(std::log10(lo)) - 1);
}

// Per method (by enumerator): a colour and a gnuplot point type of its own,
// so that every series is told apart without colour too.
const char* kColors[] = {"#000000", "#1f77b4", "#2ca02c", "#17becf",
                         "#8c564b", "#d62728", "#ff7f0e", "#9467bd"};
const int kMarkers[] = {7, 6, 5, 4, 13, 9, 11, 12};
static_assert(std::size(kColors) == kMethodCount &&
              std::size(kMarkers) == kMethodCount);

/// The case as method m was given it: FCL's methods get fclPose.
scenes::TriCase asGiven(scenes::TriCase k, Method m) {
  if (isFcl(m)) k.pose = fclPose(k.pose);
  return k;
}

/// Enhanced-text escape for gnuplot single-quoted strings: '_' and '^'
/// would otherwise start sub/superscripts.
std::string gpText(const std::string& t) {
  std::string o;
  for (char ch : t) {
    if (ch == '_' || ch == '^' || ch == '{' || ch == '}' || ch == '@' ||
        ch == '&')
      o += '\\';
    o += ch;
  }
  return o;
}

bool runGnuplot(const std::string& dir, const std::string& script) {
  const std::string cmd =
      "cd '" + dir + "' && gnuplot '" + script + "' >/dev/null 2>&1";
  return std::system(cmd.c_str()) == 0;
}

bool haveGnuplot() {
  return std::system("command -v gnuplot >/dev/null 2>&1") == 0;
}

}  // namespace

std::vector<std::string> writeReport(const std::string& dir,
                                     const std::vector<CaseSet>& sets,
                                     RunResult& result,
                                     const ReportInfo& info) {
  mkdirs(dir);
  const auto& methods = info.options.methods;
  std::vector<std::string> figures;

  // ---- rows: families, totals, sweeps
  // family_sets: every reported set (triangle families, mesh families, and
  // the cylinder-query families); tri_sets: the six triangle families, which
  // the summary and the main figure are about; mesh_sets: mesh_scan and
  // mesh_bvh.
  std::vector<std::size_t> family_sets, sweep_sets, tri_sets, mesh_sets;
  for (std::size_t s = 0; s < sets.size(); ++s) {
    (sets[s].kind == "sweep" ? sweep_sets : family_sets).push_back(s);
    if (sets[s].kind == "family" && sets[s].query == Query::kTriangle)
      (sets[s].mesh ? mesh_sets : tri_sets).push_back(s);
  }
  auto applies = [&](std::size_t s, Method m) {
    return methodApplies(sets[s], m);
  };
  std::vector<Row> rows, totals;
  std::map<std::pair<std::string, int>, Row> by_key;
  for (std::size_t s : family_sets)
    for (Method m : methods) {
      if (!applies(s, m)) continue;
      rows.push_back(makeRow(sets[s].name, m, result.sets[s].method[int(m)]));
      by_key[{sets[s].name, int(m)}] = rows.back();
    }
  for (Method m : methods) {
    MethodStats all;
    for (std::size_t s : tri_sets) {
      if (!applies(s, m)) continue;
      const MethodStats& ms = result.sets[s].method[int(m)];
      all.cases += ms.cases;
      all.false_positives += ms.false_positives;
      all.false_negatives += ms.false_negatives;
      all.hangs += ms.hangs;
      all.max_fp_size = std::max(all.max_fp_size, ms.max_fp_size);
      all.max_fn_size = std::max(all.max_fn_size, ms.max_fn_size);
      all.ns.insert(all.ns.end(), ms.ns.begin(), ms.ns.end());
    }
    if (all.cases) totals.push_back(makeRow("all", m, std::move(all)));
  }
  struct SRow {
    std::string sweep;
    double param;
    Row row;
  };
  std::vector<SRow> srows;
  for (std::size_t s : sweep_sets)
    for (Method m : methods)
      srows.push_back(
          {sets[s].name, sets[s].param,
           makeRow(sets[s].name, m, result.sets[s].method[int(m)])});

  // ---- the worst misclassified case per (set, method, kind)
  struct Worst {
    std::size_t set;
    Method method;
    const char* kind;  // "false_positive" / "false_negative"
    double size;
    std::uint64_t index;
  };
  std::vector<Worst> worst;
  for (std::size_t s : family_sets)
    for (Method m : methods) {
      if (!applies(s, m)) continue;
      const MethodStats& ms = result.sets[s].method[int(m)];
      if (ms.worst_fp_index != MethodStats::kNoCase)
        worst.push_back(
            {s, m, "false_positive", ms.max_fp_size, ms.worst_fp_index});
      if (ms.worst_fn_index != MethodStats::kNoCase)
        worst.push_back(
            {s, m, "false_negative", ms.max_fn_size, ms.worst_fn_index});
    }
  {
    std::ofstream w(dir + "/worst_cases.txt");
    w << "# tricyl-compare: per family and method, the misclassified case "
         "with the largest error size\n"
      << "# (relative clearance for a false positive, penetration for a "
         "false negative; see compare/README.md).\n"
      << "# 'case' lines (triangle families) are bit-exact hex floats: r lz "
         "R00..R22 tx ty tz ax ay az bx by bz cx cy cz.\n"
      << "# Replay: tricyl-compare --replay worst_cases.txt --out DIR; other "
         "cases: the same --seed, family and index.\n";
    if (worst.empty()) w << "# none: no method misclassified any case\n";
    for (const Worst& x : worst) {
      const Case c = sets[x.set].make(x.index);
      w << "# family=" << sets[x.set].name << " method=" << methodName(x.method)
        << ' ' << x.kind << " size=" << fmt("%.3g", x.size)
        << " index=" << x.index << " seed=" << info.seed
        << " feature=" << c.k.feature << '\n';
      if (!c.mesh && c.query == Query::kTriangle)
        w << "case " << formatCaseHex(asGiven(c.k, x.method)) << '\n';
    }
  }

  // ---- results.csv
  {
    std::ofstream csv(dir + "/results.csv");
    csv << "family,method,cases,false_positives,false_negatives,hangs,errors,"
           "error_rate,max_missed_clearance,max_missed_penetration,ns_median,"
           "ns_p99,timed_queries,ns_max,ns_mean,oracle_triangles,"
           "missed_triangles,extra_triangles\n";
    for (const Row& r : rows)
      csv << r.family << ',' << methodName(r.method) << ',' << r.cases << ','
          << r.fp << ',' << r.fn << ',' << r.hangs << ','
          << (r.fp + r.fn + r.hangs) << ',' << fmt("%.6g", r.error_rate) << ','
          << fmt("%.6g", r.max_clear) << ',' << fmt("%.6g", r.max_pen) << ','
          << fmt("%.1f", r.ns_median) << ',' << fmt("%.1f", r.ns_p99) << ','
          << r.timed << ',' << fmt("%.1f", r.ns_max) << ','
          << fmt("%.1f", r.ns_mean) << ',' << r.tri_oracle << ','
          << r.tri_missed << ',' << r.tri_extra << '\n';
  }
  // ---- stability.csv
  {
    std::ofstream csv(dir + "/stability.csv");
    csv << "sweep,param,method,cases,false_positives,false_negatives,hangs,"
           "error_rate,ns_median,ns_mean\n";
    for (const SRow& s : srows)
      csv << s.sweep << ',' << fmt("%.6g", s.param) << ','
          << methodName(s.row.method) << ',' << s.row.cases << ',' << s.row.fp
          << ',' << s.row.fn << ',' << s.row.hangs << ','
          << fmt("%.6g", s.row.error_rate) << ','
          << fmt("%.1f", s.row.ns_median) << ',' << fmt("%.1f", s.row.ns_mean)
          << '\n';
  }
  // ---- hangs.txt (always written, so that "no hangs" is visible)
  {
    std::ofstream h(dir + "/hangs.txt");
    h << "# tricyl-compare hangs: queries that did not return within "
      << info.options.timeout_s << " s and were killed.\n"
      << "# Each 'case' line is bit-exact (hex floats): r lz R00 R01 R02 R10 "
         "R11 R12 R20 R21 R22 tx ty tz ax ay az bx by bz cx cy cz\n"
      << "# (fcl::Cylinderd(r, lz); pose linear() = R row-major, "
         "translation() = t; triangle a, b, c).\n"
      << "# The pose is the one FCL was given: a proper rotation (det R = "
         "+1) of the generated solid.\n"
      << "# Replay: tricyl-compare --replay hangs.txt --methods "
         "fcl_libccd_default --out DIR\n";
    if (result.hangs.empty()) h << "# none in this run\n";
    // One entry per case, listing every method that hung on it.
    std::map<std::pair<std::size_t, std::uint64_t>, std::string> hung;
    for (const HangRecord& hr : result.hangs) {
      std::string& ms = hung[{hr.set, hr.index}];
      ms += (ms.empty() ? "" : ",") + std::string(methodName(hr.method));
    }
    for (const auto& [key, ms] : hung) {
      const Case c = sets[key.first].make(key.second);
      h << "# set=" << sets[key.first].name << " index=" << key.second
        << " seed=" << info.seed << " methods=" << ms
        << " feature=" << c.k.feature;
      if (c.mesh) {
        h << " mesh=" << c.mesh->name
          << " (mesh case: the triangle fields are unused)\n# ";
      } else {
        h << "\ncase ";
      }
      h << formatCaseHex(asGiven(c.k, Method::kFclLibccd1e6)) << '\n';
    }
  }

  // ---- results.json
  {
    json j;
    j["tool"] = "tricyl-compare";
    j["command"] = info.command_line;
    j["seed"] = info.seed;
    j["cases_per_family"] = info.cases;
    j["mesh_cases"] = info.mesh_cases;
    j["sweep_cases_per_point"] = info.sweep_cases;
    j["query_cases"] = info.query_cases;
    j["timeout_s"] = info.options.timeout_s;
    j["workers"] = info.options.workers;
    j["wall_seconds"] = result.wall_seconds;
    j["machine"] = machine();
    j["meshes"] = info.meshes;
    j["timing_note"] =
        "ns per query over answered queries only; hung queries are excluded "
        "from ns_mean, ns_median, ns_p99 and ns_max and counted in hangs";
    j["pose_note"] =
        "methods that run inside FCL get every pose with det R = -1 as R "
        "diag(1, 1, -1), a proper rotation of the same solid; 'improper' in "
        "'stages' counts those cases per family";
    json jm = json::array();
    for (Method m : methods) jm.push_back(methodName(m));
    j["methods"] = jm;
    auto rowJson = [](const Row& r) {
      return json{{"family", r.family},
                  {"method", methodName(r.method)},
                  {"cases", r.cases},
                  {"false_positives", r.fp},
                  {"false_negatives", r.fn},
                  {"hangs", r.hangs},
                  {"errors", r.fp + r.fn + r.hangs},
                  {"error_rate", r.error_rate},
                  {"max_missed_clearance", r.max_clear},
                  {"max_missed_penetration", r.max_pen},
                  {"ns_mean", jnum(r.ns_mean)},
                  {"ns_median", jnum(r.ns_median)},
                  {"ns_p99", jnum(r.ns_p99)},
                  {"ns_max", jnum(r.ns_max)},
                  {"timed_queries", r.timed},
                  {"oracle_triangles", r.tri_oracle},
                  {"missed_triangles", r.tri_missed},
                  {"extra_triangles", r.tri_extra}};
    };
    json jr = json::array(), jt = json::array();
    for (const Row& r : rows) jr.push_back(rowJson(r));
    for (const Row& r : totals) jt.push_back(rowJson(r));
    j["results"] = jr;
    j["totals"] = jt;
    json js = json::array(), ja = json::array();
    for (std::size_t s : family_sets) {
      const SetStats& st = result.sets[s];
      json e{{"family", sets[s].name},
             {"cases", st.cases},
             {"oracle_hits", st.hits},
             {"improper", st.improper}};
      std::uint64_t staged = 0;
      for (auto v : st.stage) staged += v;
      for (int k = 0; k < int(std::size(kStageNames)); ++k)
        e[kStageNames[k]] = staged ? double(st.stage[k]) / double(staged) : 0.0;
      e["staged_queries"] = staged;
      js.push_back(e);
      for (Method m : methods) {
        if (m == Method::kTricyl || usesFloatInput(m) || !applies(s, m))
          continue;
        const MethodStats& ms = st.method[int(m)];
        ja.push_back({{"family", sets[s].name},
                      {"method", methodName(m)},
                      {"both_hit", ms.agree[1][1]},
                      {"both_miss", ms.agree[0][0]},
                      {"tricyl_hit_method_miss", ms.agree[1][0]},
                      {"tricyl_miss_method_hit", ms.agree[0][1]},
                      {"method_hang", ms.hangs}});
      }
    }
    json jf = json::array();
    for (std::size_t s : family_sets)
      for (const auto& [feat, fs] : result.sets[s].features) {
        json w;
        for (Method m : methods)
          if (applies(s, m)) w[methodName(m)] = fs.wrong[int(m)];
        jf.push_back({{"family", sets[s].name},
                      {"feature", feat},
                      {"cases", fs.cases},
                      {"errors", w}});
      }
    j["features"] = jf;
    j["stages"] = js;
    j["agreement"] = ja;
    json jsw = json::array();
    for (const SRow& s : srows) {
      json e = rowJson(s.row);
      e.erase("family");
      e["sweep"] = s.sweep;
      e["param"] = s.param;
      jsw.push_back(e);
    }
    j["stability"] = jsw;
    json jh = json::array();
    for (const HangRecord& hr : result.hangs)
      jh.push_back(
          {{"set", sets[hr.set].name},
           {"index", hr.index},
           {"method", methodName(hr.method)},
           {"case_hex",
            formatCaseHex(asGiven(sets[hr.set].make(hr.index).k, hr.method))}});
    j["hangs"] = jh;
    json jw = json::array();
    for (const Worst& x : worst) {
      const Case c = sets[x.set].make(x.index);
      json e{{"family", sets[x.set].name},
             {"method", methodName(x.method)},
             {"kind", x.kind},
             {"size", x.size},
             {"index", x.index},
             {"feature", c.k.feature}};
      if (!c.mesh && c.query == Query::kTriangle)
        e["case_hex"] = formatCaseHex(asGiven(c.k, x.method));
      jw.push_back(e);
    }
    j["worst_cases"] = jw;
    std::ofstream(dir + "/results.json") << j.dump(2) << '\n';
  }

  // ---- figures
  const bool gp = info.plots && haveGnuplot();
  // Error rate against time per query (mean: the throughput a caller pays;
  // or median), one series per method (its own colour and marker), one point
  // per set of `subset`, labelled with the set's name.
  auto plotErrorVsTime = [&](const std::string& name,
                             const std::vector<std::size_t>& subset,
                             const std::string& what, bool use_mean) {
    std::vector<std::string> fams;
    for (std::size_t s : subset) fams.push_back(sets[s].name);
    std::vector<const Row*> sel;
    for (const Row& r : rows)
      if (std::find(fams.begin(), fams.end(), r.family) != fams.end())
        sel.push_back(&r);
    std::vector<double> rates;
    for (const Row* r : sel) rates.push_back(r->error_rate);
    const double floor = floorFor(rates);
    std::ofstream g(dir + "/" + name + ".gp");
    g << "# gnuplot script written by tricyl-compare; run: gnuplot " << name
      << ".gp\n"
      << "set terminal pngcairo size 1100,750 font ',10'\n"
      << "set output '" << name << ".png'\n"
      << "set logscale xy\nset format y '10^{%L}'\nset format x '10^{%L}'\n"
      << "set xlabel '"
      << (use_mean ? "mean ns per query (log): the throughput a caller pays"
                   : "median ns per query (log)")
      << "'\n"
      << "set ylabel 'error rate = (false positives + false negatives + "
         "hangs) / cases (log)'\n"
      << "set title 'Error rate against " << (use_mean ? "mean" : "median")
      << " time per query: one series per method, one point per "
      << gpText(what) << "'\n"
      << "set key outside right top box\nset grid\n"
      << "set arrow from graph 0, first " << floor << " to graph 1, first "
      << floor << " nohead dt 2 lc rgb '#888888'\n"
      << "set yrange [" << floor / 4 << ":1.5]\n";
    std::vector<Method> shown;
    for (Method m : methods)
      for (const Row* r : sel)
        if (r->method == m) {
          shown.push_back(m);
          break;
        }
    // Data: per method a block "ns rate label".
    for (std::size_t mi = 0; mi < shown.size(); ++mi) {
      g << "$m" << mi << " << EOD\n";
      for (const Row* r : sel) {
        const double ns = use_mean ? r->ns_mean : r->ns_median;
        if (r->method == shown[mi] && std::isfinite(ns))
          // Points on the floor (no error) are not labelled: they crowd.
          g << ns << ' ' << (r->error_rate > 0 ? r->error_rate : floor) << " \""
            << (r->error_rate > 0 ? r->family : std::string()) << "\"\n";
      }
      g << "EOD\n";
    }
    g << "plot \\\n";
    for (std::size_t mi = 0; mi < shown.size(); ++mi) {
      const int mk = int(shown[mi]);
      g << "  $m" << mi << " using 1:2 with points pt " << kMarkers[mk % 8]
        << " ps 1.6 lc rgb '" << kColors[mk % 8] << "' title '"
        << gpText(methodName(shown[mi])) << "', \\\n"
        << "  $m" << mi
        << " using 1:2:3 with labels noenhanced font ',7' offset 0.8,0.5 left "
           "tc rgb '"
        << kColors[mk % 8] << "' notitle, \\\n";
    }
    g << "  NaN with lines dt 2 lc rgb '#888888' title 'error = 0: drawn on "
         "the floor "
      << num(floor) << "'\n";
    g.close();
    if (gp && runGnuplot(dir, name + ".gp"))
      figures.push_back(dir + "/" + name + ".png");
  };
  if (!tri_sets.empty()) {
    plotErrorVsTime("error_vs_time", tri_sets, "triangle family", true);
    plotErrorVsTime("error_vs_time_median", tri_sets, "triangle family", false);
  }
  if (!mesh_sets.empty())
    plotErrorVsTime("error_vs_time_mesh", mesh_sets, "mesh family", true);
  std::vector<std::size_t> query_sets;
  for (std::size_t s : family_sets)
    if (sets[s].query != Query::kTriangle) query_sets.push_back(s);
  if (!query_sets.empty())
    plotErrorVsTime("error_vs_time_queries", query_sets, "query/family", true);
  std::set<std::string> sweep_names;
  for (const SRow& s : srows) sweep_names.insert(s.sweep);
  const std::map<std::string, std::string> xlabels = {
      {"delta", "relative offset |delta| of the touching feature (log)"},
      {"translation", "translation |t| of both shapes (log), |delta| = 1e-3"},
      {"aspect", "aspect ratio lz / (2 r) (log), |delta| = 1e-3"}};
  for (const std::string& sw : sweep_names) {
    std::vector<double> rates;
    for (const SRow& s : srows)
      if (s.sweep == sw) rates.push_back(s.row.error_rate);
    const double floor = floorFor(rates);
    const std::string name = "stability_" + sw;
    std::ofstream g(dir + "/" + name + ".gp");
    g << "# gnuplot script written by tricyl-compare\n"
      << "set terminal pngcairo size 900,600 font ',10'\n"
      << "set output '" << name << ".png'\n"
      << "set logscale xy\nset format y '10^{%L}'\nset format x '10^{%L}'\n"
      << "set xlabel '" << (xlabels.count(sw) ? xlabels.at(sw) : sw + " (log)")
      << "'\n"
      << "set ylabel 'error rate (log)'\nset grid\n"
      << "set title 'Stability: error rate against " << sw
      << " (near-touching cases)'\nset key outside right top box\n"
      << "set arrow from graph 0, first " << floor << " to graph 1, first "
      << floor << " nohead dt 2 lc rgb '#888888'\n"
      << "set yrange [" << floor / 4 << ":1.5]\n";
    for (std::size_t mi = 0; mi < methods.size(); ++mi) {
      g << "$m" << mi << " << EOD\n";
      for (const SRow& s : srows)
        if (s.sweep == sw && s.row.method == methods[mi])
          g << s.param << ' '
            << (s.row.error_rate > 0 ? s.row.error_rate : floor) << '\n';
      g << "EOD\n";
    }
    g << "plot \\\n";
    for (std::size_t mi = 0; mi < methods.size(); ++mi)
      g << "  $m" << mi << " using 1:2 with linespoints pt "
        << kMarkers[int(methods[mi]) % 8] << " lw 1.5 lc rgb '"
        << kColors[int(methods[mi]) % 8] << "' title '"
        << gpText(methodName(methods[mi])) << "', \\\n";
    g << "  NaN with lines dt 2 lc rgb '#888888' title 'error = 0: drawn on "
         "the floor "
      << num(floor) << "'\n";
    g.close();
    if (gp && runGnuplot(dir, name + ".gp"))
      figures.push_back(dir + "/" + name + ".png");
  }

  // ---- report.md
  std::ofstream md(dir + "/report.md");
  md << "# tricyl-compare report\n\n"
     << "Command: `" << info.command_line << "`  \n"
     << "Seed " << info.seed << ", " << info.cases
     << " cases per triangle family";
  if (info.mesh_cases) md << ", " << info.mesh_cases << " mesh cases";
  if (info.sweep_cases)
    md << ", " << info.sweep_cases << " cases per stability point";
  if (info.query_cases)
    md << ", " << info.query_cases << " cases per cylinder query x family";
  md << "; " << info.options.workers << " worker processes; time limit "
     << info.options.timeout_s << " s per FCL query; wall time "
     << fmt("%.1f", result.wall_seconds) << " s.  \n"
     << "Machine: " << machine() << ".\n\n"
     << "Every answer is settled by the exact oracle (GMP rationals, "
        "`compare/oracle.h`); `tricyl_float` is settled on the float-rounded "
        "input it actually answers. An error is a false positive, a false "
        "negative or a hang; the error rate is errors / cases. **Timings "
        "exclude hung queries** (a hung query has no time; it is counted in "
        "`hangs`). Times are per query: the mean (what a caller pays per "
        "query over the family), the median, the 99th percentile and the "
        "maximum; `x FCL` is the mean of `fcl_libccd_1e-6` (the solver and "
        "tolerance `fcl::collide` uses) on the same family, in the same run, "
        "over the method's mean: above 1 the method is faster. See "
        "compare/README.md for how to read each column.\n\n"
        "**Proper rotations for FCL.** FCL's solvers turn the rotation into a "
        "quaternion, so on a pose with det R = -1 they would answer for a "
        "different cylinder. Every method that runs inside FCL (`fcl_*`, "
        "`tricyl_fcl*`) is given such a pose as R diag(1, 1, -1), a proper "
        "rotation of the same solid (the cylinder is symmetric under z -> "
        "-z; the oracle's verdict is the same); tricyl's own rows take the "
        "pose as generated, as its contract allows. Cases with det R = -1: ";
  {
    bool first = true;
    for (std::size_t s : family_sets)
      if (result.sets[s].improper) {
        md << (first ? "" : ", ") << sets[s].name << " "
           << result.sets[s].improper << " of " << result.sets[s].cases;
        first = false;
      }
    if (first) md << "none";
    md << ".\n\n";
  }
  if (!gp)
    md << "> gnuplot was not run (absent or --no-plots): the figures' "
          "scripts (*.gp) are written; run `gnuplot FILE.gp` in this "
          "folder.\n\n";

  // FCL's mean on the same rows over the method's mean (speed-up vs FCL).
  auto ratioFcl = [&](const Row& r, const Row* fcl) -> std::string {
    if (!fcl || !(fcl->ns_mean > 0) || !(r.ns_mean > 0)) return "n/a";
    return fmt("%.2f", fcl->ns_mean / r.ns_mean);
  };
  auto fclRow = [&](const std::string& family) -> const Row* {
    auto it = by_key.find({family, int(Method::kFclLibccd1e6)});
    return it == by_key.end() ? nullptr : &it->second;
  };
  const Row* fcl_total = nullptr;
  for (const Row& r : totals)
    if (r.method == Method::kFclLibccd1e6) fcl_total = &r;
  md << "## Summary over the six triangle families\n\n"
     << "| method | cases | false pos. | false neg. | hangs | error rate | "
        "ns mean | ns median | ns p99 | ns max | x FCL (mean) |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const Row& r : totals)
    md << "| " << methodName(r.method) << " | " << r.cases << " | " << r.fp
       << " | " << r.fn << " | " << r.hangs << " | " << pct(r.error_rate)
       << " | " << num(r.ns_mean) << " | " << num(r.ns_median) << " | "
       << num(r.ns_p99) << " | " << num(r.ns_max) << " | "
       << ratioFcl(r, fcl_total) << " |\n";
  md << "\n## Per family\n\n"
     << "Max missed clearance / penetration: the largest error size among "
        "the false positives / false negatives (relative: |delta| for near "
        "cases, else the relative scaling of the cylinder that flips the "
        "exact answer). `x FCL`: the mean time of `fcl_libccd_1e-6` on the "
        "same family over the method's mean. `mesh_scan` times a scan of "
        "every triangle without a BVH (tricyl's batch scan, "
        "`tricyl::tryIntersectAny`, beside a loop of each FCL solver's "
        "`shapeTriangleIntersect` behind the harness's bounding-sphere cull; "
        "first hit ends both); `mesh_bvh` times the OBBRSS `BVHModel` "
        "through `tricyl::collide` beside `fcl::collide`, exhaustive "
        "requests.\n\n";
  for (std::size_t s : family_sets) {
    md << "### " << sets[s].name << "\n\n"
       << "| method | cases | false pos. | false neg. | hangs | error rate | "
          "max missed clearance | max missed penetration | ns mean | ns "
          "median | ns p99 | ns max | x FCL (mean) |\n|---|---:|---:|---:|"
          "---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      if (r.family == sets[s].name)
        md << "| " << methodName(r.method) << " | " << r.cases << " | " << r.fp
           << " | " << r.fn << " | " << r.hangs << " | " << pct(r.error_rate)
           << " | " << num(r.max_clear) << " | " << num(r.max_pen) << " | "
           << num(r.ns_mean) << " | " << num(r.ns_median) << " | "
           << num(r.ns_p99) << " | " << num(r.ns_max) << " | "
           << ratioFcl(r, fclRow(r.family)) << " |\n";
    md << "\n";
  }
  // The triangle-level count of the exhaustive BVH queries.
  for (std::size_t s : mesh_sets) {
    if (sets[s].mesh_path != MeshPath::kBvh) continue;
    md << "## Colliding triangles reported by exhaustive BVH queries\n\n"
       << "On `" << sets[s].name
       << "`, each call asks for every colliding triangle "
          "(`num_max_contacts` unlimited). Per method, over its answered "
          "cases: the triangles the oracle says collide, those the method "
          "did not report (missed), and those it reported that do not "
          "collide (false). A hung call counts all its oracle triangles as "
          "missed. Meshes: ";
    for (std::size_t i = 0; i < info.meshes.size(); ++i)
      md << (i ? ", " : "") << info.meshes[i];
    md << ".\n\n| method | cases | oracle triangles | missed | false | "
          "wrong triangles |\n|---|---:|---:|---:|---:|---:|\n";
    for (const Row& r : rows)
      if (r.family == sets[s].name)
        md << "| " << methodName(r.method) << " | " << r.cases << " | "
           << r.tri_oracle << " | " << r.tri_missed << " | " << r.tri_extra
           << " | " << (r.tri_missed + r.tri_extra) << " |\n";
    md << "\n";
  }
  md << "## Which stage of tricyl decided\n\n"
     << "Share of the `tricyl` queries per deciding stage (mesh cases are "
        "many kernel calls and are not staged).\n\n"
     << "| family | cases | oracle hits | early-out | fast path | running "
        "double | extended | exact | exact GMP |\n"
        "|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t s : family_sets) {
    const SetStats& st = result.sets[s];
    std::uint64_t staged = 0;
    for (auto v : st.stage) staged += v;
    auto share = [&](Stage k) {
      return staged ? pct(double(st.stage[int(k)]) / double(staged))
                    : std::string("n/a");
    };
    md << "| " << sets[s].name << " | " << st.cases << " | " << st.hits << " | "
       << share(Stage::kEarlyOut) << " | " << share(Stage::kFastPath) << " | "
       << share(Stage::kRunning) << " | " << share(Stage::kExtended) << " | "
       << share(Stage::kExact) << " | " << share(Stage::kExactGmp) << " |\n";
  }
  md << "\n## Agreement with tricyl\n\n"
     << "tricyl's answer is exact, so where another method disagrees with "
        "it, that method is wrong. (`tricyl_float` answers a different, "
        "float-rounded input and is left out.) Columns: both say hit, both say "
        "miss, tricyl hit but the "
        "method missed, tricyl missed but the method hit, the method hung.\n\n"
     << "| family | method | both hit | both miss | tricyl hit / method miss "
        "| tricyl miss / method hit | hangs | agreement |\n"
        "|---|---|---:|---:|---:|---:|---:|---:|\n";
  for (std::size_t s : family_sets)
    for (Method m : methods) {
      if (m == Method::kTricyl || usesFloatInput(m) || !applies(s, m)) continue;
      const MethodStats& ms = result.sets[s].method[int(m)];
      const double agree =
          ms.cases ? double(ms.agree[0][0] + ms.agree[1][1]) / double(ms.cases)
                   : 0;
      md << "| " << sets[s].name << " | " << methodName(m) << " | "
         << ms.agree[1][1] << " | " << ms.agree[0][0] << " | " << ms.agree[1][0]
         << " | " << ms.agree[0][1] << " | " << ms.hangs << " | " << pct(agree)
         << " |\n";
    }
  md << "\n## Where the errors are: per generator feature\n\n"
     << "Errors (false positives + false negatives + hangs) per feature of "
        "the generator (scenes.h: which touching configuration, degeneracy "
        "or alignment the case was built around).\n\n";
  for (std::size_t s : family_sets) {
    const auto& feats = result.sets[s].features;
    if (feats.size() < 2) continue;
    md << "**" << sets[s].name << "**\n\n| feature | cases |";
    for (Method m : methods) md << ' ' << methodName(m) << " |";
    md << "\n|---|---:|";
    for (std::size_t i = 0; i < methods.size(); ++i) md << "---:|";
    md << '\n';
    for (const auto& [feat, fs] : feats) {
      md << "| " << feat << " | " << fs.cases << " |";
      for (Method m : methods)
        md << ' '
           << (applies(s, m) ? std::to_string(fs.wrong[int(m)])
                             : std::string("—"))
           << " |";
      md << '\n';
    }
    md << '\n';
  }
  if (!sweep_names.empty()) {
    md << "\n## Stability sweeps\n\n"
       << "Error rate per sweep point (near-touching cases, "
       << info.sweep_cases
       << " per point; see compare/sweeps.h). Data: stability.csv.\n\n";
    for (const std::string& sw : sweep_names) {
      md << "### " << sw << "\n\n| " << sw << " |";
      for (Method m : methods) md << ' ' << methodName(m) << " |";
      md << "\n|---:|";
      for (std::size_t i = 0; i < methods.size(); ++i) md << "---:|";
      md << '\n';
      std::vector<double> params;
      for (const SRow& s : srows)
        if (s.sweep == sw &&
            std::find(params.begin(), params.end(), s.param) == params.end())
          params.push_back(s.param);
      for (double p : params) {
        md << "| " << num(p) << " |";
        for (Method m : methods)
          for (const SRow& s : srows)
            if (s.sweep == sw && s.param == p && s.row.method == m)
              md << ' ' << pct(s.row.error_rate)
                 << (s.row.hangs
                         ? " (" + std::to_string(s.row.hangs) + " hangs)"
                         : std::string())
                 << " |";
        md << '\n';
      }
      md << "\n![" << sw << "](stability_" << sw << ".png)\n\n";
    }
  }
  md << "\n## Worst misclassified cases\n\n";
  if (worst.empty()) {
    md << "No method misclassified any case.\n";
  } else {
    md << "Per family and method, the false positive / false negative with "
          "the largest error size. Replay the triangle ones from "
          "`worst_cases.txt` (`tricyl-compare --replay worst_cases.txt`), any "
          "of them from (seed, family, index).\n\n"
          "| family | method | kind | size | index | feature |\n"
          "|---|---|---|---:|---:|---|\n";
    for (const Worst& x : worst)
      md << "| " << sets[x.set].name << " | " << methodName(x.method) << " | "
         << x.kind << " | " << num(x.size) << " | " << x.index << " | "
         << sets[x.set].make(x.index).k.feature << " |\n";
  }
  md << "\n## Hangs\n\n";
  if (result.hangs.empty()) {
    md << "No query exceeded the time limit in this run.\n";
  } else {
    md << result.hangs.size()
       << (result.hangs.size() == 1 ? " query" : " queries")
       << " did not return within the time limit; the worker was "
          "killed and restarted after each, and each is counted as a wrong "
          "answer in `hangs`. The cases are in `hangs.txt`, bit-exact (replay "
          "with `tricyl-compare --replay hangs.txt`).\n\n"
          "| set | index | method | feature | the case as the method got it "
          "(r lz R00..R22 t a b c, hex) |\n|---|---:|---|---|---|\n";
    for (std::size_t i = 0; i < result.hangs.size() && i < 50; ++i) {
      const HangRecord& hr = result.hangs[i];
      const Case c = sets[hr.set].make(hr.index);
      md << "| " << sets[hr.set].name << " | " << hr.index << " | "
         << methodName(hr.method) << " | " << c.k.feature << " | "
         << (c.mesh ? std::string("(mesh case)")
                    : "`" + formatCaseHex(asGiven(c.k, hr.method)) + "`")
         << " |\n";
    }
  }
  md << "\n## Figures\n\n![error rate against mean time](error_vs_time.png)"
        "\n\n![error rate against median time](error_vs_time_median.png)\n\n";
  if (!mesh_sets.empty())
    md << "![error rate against mean time, mesh families]"
          "(error_vs_time_mesh.png)\n\n";
  if (!query_sets.empty())
    md << "![error rate against time, cylinder queries]"
          "(error_vs_time_queries.png)\n\n";
  md << "Zero error rates cannot be drawn on a log axis: they are drawn on "
        "the dashed floor line, as the legend says.\n";
  return figures;
}

}  // namespace tricyl::compare
