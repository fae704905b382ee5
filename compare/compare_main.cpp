// SPDX-License-Identifier: BSD-3-Clause
// tricyl-compare: tricyl against FCL's GJK/libccd paths, settled by an exact
// oracle. See compare/README.md.
//
//   tricyl-compare --out DIR [--cases N] [--seed S] [--families a,b,...]
//                  [--methods m,...] [--mesh FILE...] [--threads T]
//                  [--timeout SECONDS] [--sweep-cases N] [--mesh-cases N]
//                  [--replay FILE] [--no-plots] [--quiet]
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <exception>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "harness.h"
#if defined(TRICYL_COMPARE_HAVE_DISTANCE)
#include "distance_families.h"
#endif
#include "known_cases.h"
#include "mesh_scenes.h"
#include "report.h"
#include "runner.h"
#include "scenes.h"
#include "sweeps.h"
#ifdef TRICYL_COMPARE_HAVE_QUERIES
#include "query_scenes.h"
#endif

namespace {

using namespace tricyl::compare;

std::string joinArgs(int argc, char** argv) {
  std::string s;
  for (int i = 0; i < argc; ++i) {
    if (i) s += ' ';
    s += argv[i];
  }
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "tricyl-compare: exact triangle-cylinder tests (tricyl) against FCL "
      "0.7's GJK/libccd paths, every answer settled by an exact GMP oracle."};
  std::string out = "report";
  std::uint64_t cases = 40000, seed = 1;
  std::uint64_t sweep_cases = 1500;
  long mesh_cases = -1;
  std::vector<std::string> families, method_names, mesh_files;
  unsigned hw = std::thread::hardware_concurrency();
  int threads = int(hw ? std::min(hw, 2u) : 2u);
  double timeout = 1.0;
  std::string replay;
  std::vector<std::string> queries;
  long query_cases = -1;
  bool no_plots = false, quiet = false;
  app.add_option("--out,-o", out, "output folder (created)")
      ->capture_default_str();
  app.add_option("--cases,-n", cases, "cases per triangle family")
      ->capture_default_str();
  app.add_option("--seed,-s", seed,
                 "seed; a case is a function of (seed, "
                 "family, index)")
      ->capture_default_str();
  app.add_option("--families", families,
                 "families to run (default: all): uniform near far thin "
                 "sliver aligned mesh_scan mesh_bvh ('mesh' for both)")
      ->delimiter(',');
  app.add_option("--methods", method_names,
                 "methods to run (default: all): tricyl diagnostic_uncertified "
                 "tricyl_float tricyl_fcl tricyl_fcl_contact fcl_libccd_1e-6 "
                 "fcl_libccd_default fcl_indep")
      ->delimiter(',');
  app.add_option("--mesh", mesh_files,
                 "OBJ files for the mesh families (replace the built-in "
                 "sphere, torus and terrain; the word 'builtin' adds those)");
  app.add_option("--mesh-cases", mesh_cases,
                 "cases of each mesh family (default: cases / 10)");
  app.add_option(
         "--queries", queries,
         "cylinder queries to run, each over its families "
         "uniform, near, far, degenerate (default: all built: "
         "point_cylinder point_cone sphere segment line; 'none' for none)")
      ->delimiter(',');
  app.add_option("--query-cases", query_cases,
                 "cases per query x family (default: cases / 10)");
  app.add_option("--sweep-cases", sweep_cases,
                 "cases per stability sweep point; 0 disables the sweeps")
      ->capture_default_str();
  app.add_option("--threads,-j", threads, "worker processes")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
  app.add_option("--timeout", timeout, "time limit per FCL query, seconds")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  app.add_option("--replay", replay,
                 "run the methods on the cases of FILE ('case' lines of "
                 "hangs.txt, hex floats) instead of the families")
      ->check(CLI::ExistingFile);
  long distance_cases = 1000, margin_cases = 100;
  app.add_option("--distance-cases", distance_cases,
                 "cases per distance family (0: none; needs the MPFR "
                 "distance oracle)")
      ->capture_default_str();
  app.add_option("--margin-cases", margin_cases,
                 "scenes per margin family (each with up to 11 margins)")
      ->capture_default_str();
  app.add_flag("--no-plots", no_plots, "do not run gnuplot");
  app.add_flag("--quiet,-q", quiet, "no progress bar");
  CLI11_PARSE(app, argc, argv);

  try {
    RunOptions opt;
    opt.workers = threads;
    opt.timeout_s = timeout;
    opt.progress = !quiet;
    if (method_names.empty()) {
      for (int i = 0; i < kMethodCount; ++i)
        if (methodAvailable(Method(i))) opt.methods.push_back(Method(i));
    } else {
      for (const auto& n : method_names) {
        auto m = parseMethod(n);
        if (!m) {
          std::fprintf(stderr, "tricyl-compare: unknown method '%s'\n",
                       n.c_str());
          return 2;
        }
        if (!methodAvailable(*m)) {
          std::fprintf(stderr,
                       "tricyl-compare: method '%s' needs tricyl::fcl, which "
                       "this build does not have\n",
                       n.c_str());
          return 2;
        }
        opt.methods.push_back(*m);
      }
    }

    std::vector<CaseSet> sets;
    std::vector<std::unique_ptr<Mesh>> meshes;
    ReportInfo info;
    info.command_line = joinArgs(argc, argv);
    info.seed = seed;
    info.cases = cases;
    info.options = opt;
    info.plots = !no_plots;

    if (!replay.empty()) {
      const auto ks = readCaseFile(replay);
      if (ks.empty()) {
        std::fprintf(stderr, "tricyl-compare: no 'case' lines in %s\n",
                     replay.c_str());
        return 2;
      }
      for (std::size_t i = 0; i < ks.size(); ++i) {
        const tricyl::scenes::TriCase k = ks[i];
        sets.push_back({"family", "replay" + std::to_string(i), kNaN, 1,
                        [k](std::uint64_t) {
                          return Case{k, nullptr};
                        }});
      }
      info.cases = 1;
      sweep_cases = 0;
    } else {
      std::vector<std::string> fams = families;
      if (fams.empty()) {
        for (auto f : tricyl::scenes::kAllFamilies)
          fams.push_back(tricyl::scenes::familyName(f));
        fams.push_back("mesh");
      }
      std::vector<MeshPath> mesh_paths;
      for (const auto& name : fams) {
        if (name == "mesh" || name == "mesh_scan" || name == "mesh_bvh") {
          for (MeshPath p : {MeshPath::kScan, MeshPath::kBvh})
            if ((name == "mesh" || name == meshFamilyName(p)) &&
                std::find(mesh_paths.begin(), mesh_paths.end(), p) ==
                    mesh_paths.end())
              mesh_paths.push_back(p);
          continue;
        }
        auto f = tricyl::scenes::parseFamily(name);
        if (!f) {
          std::fprintf(stderr, "tricyl-compare: unknown family '%s'\n",
                       name.c_str());
          return 2;
        }
        const auto fam = *f;
        sets.push_back(
            {"family", name, kNaN, cases, [fam, seed](std::uint64_t i) {
               return Case{tricyl::scenes::generate(fam, seed, i), nullptr};
             }});
      }
      if (!mesh_paths.empty()) {
        if (mesh_files.empty()) mesh_files = {"builtin"};
        for (const auto& path : mesh_files) {
          if (path == "builtin") {
            for (auto& [name, tris] : meshes::builtinMeshes()) {
              meshes.push_back(std::make_unique<Mesh>());
              meshes.back()->name = name;
              meshes.back()->tris = std::move(tris);
            }
          } else {
            meshes.push_back(std::make_unique<Mesh>());
            meshes.back()->name = path.substr(path.rfind('/') + 1);
            meshes.back()->tris = meshes::readObj(path);
          }
        }
        for (auto& m : meshes) {
          prepareMesh(*m);
          info.meshes.push_back(m->name + " (" +
                                std::to_string(m->tris.size()) + " triangles)");
        }
        const std::uint64_t n =
            mesh_cases >= 0 ? std::uint64_t(mesh_cases) : cases / 10;
        info.mesh_cases = n;
        std::vector<const Mesh*> ms;
        for (auto& m : meshes) ms.push_back(m.get());
        // Both paths answer the same cases (same seed and index).
        for (MeshPath p : mesh_paths) {
          CaseSet set{"family", meshFamilyName(p), kNaN, n,
                      [ms, seed, p](std::uint64_t i) {
                        const Mesh* m = ms[i % ms.size()];
                        Case c{meshes::meshCase(m->tris, m->lo, m->hi, seed,
                                                i / ms.size()),
                               m};
                        c.mesh_path = p;
                        return c;
                      }};
          set.mesh = true;
          set.mesh_path = p;
          sets.push_back(set);
        }
      }
      // The cylinder queries, when built in.
      std::vector<Query> qs;
      if (queries.empty()) {
        if (haveQueries() && families.empty())
          qs = {Query::kPointCylinder, Query::kPointCone, Query::kSphere,
                Query::kSegment, Query::kLine};
      } else {
        for (const auto& name : queries) {
          if (name == "none") continue;
          bool found = false;
          for (Query q : {Query::kPointCylinder, Query::kPointCone,
                          Query::kSphere, Query::kSegment, Query::kLine})
            if (name == queryName(q)) {
              qs.push_back(q);
              found = true;
            }
          if (!found || !haveQueries()) {
            std::fprintf(stderr,
                         "tricyl-compare: unknown or unavailable query '%s'\n",
                         name.c_str());
            return 2;
          }
        }
      }
      info.query_cases =
          qs.empty()
              ? 0
              : (query_cases >= 0 ? std::uint64_t(query_cases) : cases / 10);
#ifdef TRICYL_COMPARE_HAVE_QUERIES
      for (Query q : qs)
        for (auto fam : tricyl::qscenes::kAllFamilies) {
          const auto qq = tricyl::qscenes::Query(int(q));
          CaseSet set{
              "family",
              std::string(queryName(q)) + "/" +
                  tricyl::qscenes::familyName(fam),
              kNaN, info.query_cases, [qq, q, fam, seed](std::uint64_t i) {
                const auto k = tricyl::qscenes::generate(qq, fam, seed, i);
                Case c;
                c.query = q;
                c.k.cyl = k.cyl;
                c.k.pose = k.pose;
                c.k.feature = k.feature;
                c.p = k.p;
                c.q = k.q;
                c.rho = k.rho;
                return c;
              }};
          set.query = q;
          sets.push_back(set);
        }
#endif
      // The known cases (compare/known_cases.h), in every default run.
      if (families.empty()) {
        const tricyl::scenes::TriCase k = discHangCase();
        sets.push_back({"case", "disc_hang", kNaN, 1, [k](std::uint64_t) {
                          return Case{k, nullptr};
                        }});
      }
      if (sweep_cases > 0) {
        for (auto& s : sweeps::deltaSweep(seed, sweep_cases)) sets.push_back(s);
        for (auto& s : sweeps::translationSweep(seed, sweep_cases))
          sets.push_back(s);
        for (auto& s : sweeps::aspectSweep(seed, sweep_cases))
          sets.push_back(s);
      }
    }
    info.sweep_cases = sweep_cases;

    RunResult result = runAll(sets, opt);
    const auto figures = writeReport(out, sets, result, info);

    // The distance and margin families (distance_families.h): the triangle
    // families selected, in this process (FCL's GJK distance has an
    // iteration cap: no time limit needed).
    std::string distance_summary;
#if defined(TRICYL_COMPARE_HAVE_DISTANCE)
    if (replay.empty() && (distance_cases > 0 || margin_cases > 0)) {
      tricyl::distance_families::Options dopt;
      dopt.out = out;
      dopt.seed = seed;
      dopt.cases = std::max(0L, distance_cases);
      dopt.margin_cases = std::max(0L, margin_cases);
      dopt.plots = !no_plots;
      for (const auto& set : sets)
        if (set.kind == "family")
          if (auto f = tricyl::scenes::parseFamily(set.name))
            dopt.families.push_back(*f);
      if (!dopt.families.empty())
        distance_summary = tricyl::distance_families::run(dopt);
    }
#else
    (void)distance_cases;
    (void)margin_cases;
#endif

    // A short summary on stdout.
    std::printf(
        "tricyl-compare: %.1f s, %zu hangs; wrote %s/report.md, "
        "results.csv, results.json, stability.csv, hangs.txt, "
        "worst_cases.txt",
        result.wall_seconds, result.hangs.size(), out.c_str());
    for (const auto& f : figures)
      std::printf(", %s", f.substr(f.rfind('/') + 1).c_str());
    std::printf("\n");
    for (std::size_t s = 0; s < sets.size(); ++s) {
      if (sets[s].kind == "sweep") continue;
      std::printf("  %-10s", sets[s].name.c_str());
      for (Method m : opt.methods) {
        if (!methodApplies(sets[s], m)) continue;
        const MethodStats& ms = result.sets[s].method[int(m)];
        std::printf(
            "  %s %llu/%llu%s", methodName(m), (unsigned long long)ms.wrong(),
            (unsigned long long)ms.cases,
            ms.hangs ? (" (" + std::to_string(ms.hangs) + " hung)").c_str()
                     : "");
      }
      std::printf("\n");
    }
    std::printf("%s", distance_summary.c_str());
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "tricyl-compare: %s\n", e.what());
    return 1;
  }
}
