// SPDX-License-Identifier: BSD-3-Clause
// Tests of the comparison harness (issue 4) and its time limit (issue 9):
// the oracle on hand cases, the near generator's claimed clearance checked
// exactly, the output files of a small end-to-end run, and the libccd hang
// of issue 9 detected and recorded within the time limit.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "harness.h"
#include "known_cases.h"
#include "mesh_scenes.h"
#include "obj_mesh.h"
#include "oracle.h"
#include "runner.h"
#include "scenes.h"
#include "test_support.h"

namespace tricyl {
namespace {

using compare::Case;
using compare::CaseSet;
using compare::Method;
using scenes::TriCase;

Triangle<double> tri(Vec3<double> a, Vec3<double> b, Vec3<double> c) {
  return {a, b, c};
}

// ------------------------------------------------------------ the oracle

// Hand cases with dyadic inputs, each decided by inspection. Cylinder r = 1,
// lz = 2 (|z| <= 1) at the identity unless stated.
TEST(CompareOracle, HandCases) {
  const Cylinder<double> cyl{1, 2};
  const Pose<double> id = identityPose<double>();
  // Far away.
  EXPECT_FALSE(
      oracle::triangleCylinder(cyl, id, tri({5, 5, 5}, {6, 5, 5}, {5, 6, 5})));
  // Through the axis: a large triangle in the plane z = 0.
  EXPECT_TRUE(oracle::triangleCylinder(
      cyl, id, tri({-4, -4, 0}, {4, -4, 0}, {0, 4, 0})));
  // A vertex exactly on the side (touching counts).
  EXPECT_TRUE(
      oracle::triangleCylinder(cyl, id, tri({1, 0, 0}, {2, 1, 0}, {2, -1, 0})));
  // The same pushed out by 2^-40: disjoint.
  EXPECT_FALSE(oracle::triangleCylinder(
      cyl, id, tri({1 + 0x1p-40, 0, 0}, {2, 1, 0}, {2, -1, 0})));
  // An edge touching the rim circle at (1, 0, 1), in the cap plane.
  EXPECT_TRUE(
      oracle::triangleCylinder(cyl, id, tri({1, -1, 1}, {1, 1, 1}, {2, 0, 3})));
  // A face in the cap plane z = 1 over the disk; then lifted by 2^-50.
  EXPECT_TRUE(oracle::triangleCylinder(
      cyl, id, tri({-0.5, -0.5, 1}, {0.5, -0.5, 1}, {0, 0.5, 1})));
  EXPECT_FALSE(oracle::triangleCylinder(
      cyl, id,
      tri({-0.5, -0.5, 1 + 0x1p-50}, {0.5, -0.5, 1 + 0x1p-50},
          {0, 0.5, 1 + 0x1p-50})));
  // A triangle whose plane contains the axis, passing beside it: the
  // projection is a segment through the disk, so it meets the cylinder.
  EXPECT_TRUE(oracle::triangleCylinder(
      cyl, id, tri({-3, 0, -3}, {3, 0, -3}, {0, 0, 3})));
  // The plane contains the axis but the triangle is beyond the rim corner:
  // the segment {x = 2 .. 3, y = 0}: disjoint.
  EXPECT_FALSE(oracle::triangleCylinder(
      cyl, id, tri({2, 0, -3}, {3, 0, -3}, {2, 0, 3})));
  // Degenerate: a point inside; a segment crossing above the cap.
  EXPECT_TRUE(
      oracle::triangleCylinder(cyl, id, tri({0, 0, 0}, {0, 0, 0}, {0, 0, 0})));
  EXPECT_FALSE(oracle::triangleCylinder(
      cyl, id, tri({-2, 0, 1.5}, {2, 0, 1.5}, {0, 0, 1.5})));
  // A posed cylinder: axis along world x (R maps local z to world x),
  // translated by (8, 0, 0); the triangle crosses x = 8 + 1 at y = 0.
  Pose<double> p{};
  p.R[0][2] = 1;   // world x = local z
  p.R[1][1] = 1;   // world y = local y
  p.R[2][0] = -1;  // world z = -local x
  p.t = {8, 0, 0};
  EXPECT_TRUE(oracle::triangleCylinder(
      cyl, p, tri({9, -0.5, 0}, {9, 0.5, 0}, {10, 0, 0})));
  EXPECT_FALSE(oracle::triangleCylinder(
      cyl, p, tri({9.25, -0.5, 0}, {9.25, 0.5, 0}, {10, 0, 0})));
}

// ------------------------------------------------------------- meshes

// The mesh oracle skips triangles with a bounding-sphere cull; the cull must
// be conservative: the culled verdict equals the verdict over every
// triangle. Also checks that touching placements produce both answers.
TEST(CompareMesh, CullIsConservative) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  int hits = 0, n = 0;
  for (auto& [name, tris] : compare::meshes::builtinMeshes()) {
    compare::Mesh mesh;
    mesh.name = name;
    mesh.tris = tris;
    compare::prepareMesh(mesh);
    for (std::uint64_t i = 0; i < 16; ++i, ++n) {
      const TriCase k =
          compare::meshes::meshCase(mesh.tris, mesh.lo, mesh.hi, seed, i);
      bool all = false;
      for (const auto& t : mesh.tris)
        if (oracle::triangleCylinder(k.cyl, k.pose, t)) {
          all = true;
          break;
        }
      EXPECT_EQ(compare::oracleTruth(Case{k, &mesh}), all)
          << name << " case " << i << " " << k.feature;
      hits += all;
    }
  }
  EXPECT_GT(hits, 0);
  EXPECT_LT(hits, n);
}

// The shared OBJ reader (support/obj_mesh.h): polygons fanned, negative
// and slash-form indices, and every coordinate the correctly rounded value
// of its decimal (tinyobjloader's own parser is off by an ulp on some).
TEST(CompareMesh, ObjReaderKeepsTheFileNumbers) {
  char tmpl[] = "/tmp/tricyl_obj_test_XXXXXX";
  const int fd = mkstemp(tmpl);
  ASSERT_GE(fd, 0);
  close(fd);
  const char* coords[] = {"0.122622", "-2653.83", "-457.654", "1e-300",
                          "0.1",      "3",        "0.7",      "-0.3"};
  {
    std::ofstream f(tmpl);
    f << "# a quad and a triangle\no shape\n"
      << "v " << coords[0] << ' ' << coords[1] << ' ' << coords[2] << '\n'
      << "v " << coords[3] << ' ' << coords[4] << ' ' << coords[5] << '\n'
      << "v " << coords[6] << ' ' << coords[7] << " 0\n"
      << "v 1 1 1\nvn 0 0 1\nf 1//1 2//1 3//1 4//1\nf -1 -2 -3\n";
  }
  const auto m = tricyl::obj::read(tmpl);
  std::remove(tmpl);
  ASSERT_EQ(m.numVertices(), 4u);
  for (int i = 0; i < 8; ++i)
    EXPECT_EQ(m.vertices[std::size_t(i)], std::strtod(coords[i], nullptr))
        << coords[i];
  ASSERT_EQ(m.numTriangles(), 3u);
  // The quad: two triangles over its four vertices, sharing a diagonal
  // (tinyobjloader picks the diagonal).
  std::set<std::uint32_t> all, shared;
  for (int k = 0; k < 6; ++k) all.insert(m.indices[std::size_t(k)]);
  for (int k = 0; k < 3; ++k)
    for (int l = 3; l < 6; ++l)
      if (m.indices[std::size_t(k)] == m.indices[std::size_t(l)])
        shared.insert(m.indices[std::size_t(k)]);
  EXPECT_EQ(all, (std::set<std::uint32_t>{0, 1, 2, 3}));
  EXPECT_TRUE(shared == (std::set<std::uint32_t>{0, 2}) ||
              shared == (std::set<std::uint32_t>{1, 3}));
  // Negative indices count back from the last vertex.
  EXPECT_EQ(std::vector<std::uint32_t>(m.indices.begin() + 6, m.indices.end()),
            (std::vector<std::uint32_t>{3, 2, 1}));
  EXPECT_THROW(tricyl::obj::read("/nonexistent/x.obj"), std::runtime_error);
}

TEST(CompareMesh, ReadsTheSharedObjFiles) {
  const std::string dir = TRICYL_MESH_DIR;
  struct stat st;
  if (stat((dir + "/env.obj").c_str(), &st) != 0)
    GTEST_SKIP() << "no shared meshes at " << dir;
  EXPECT_EQ(compare::meshes::readObj(dir + "/env.obj").size(), 2180u);
  EXPECT_EQ(compare::meshes::readObj(dir + "/rob.obj").size(), 216u);
  EXPECT_EQ(compare::meshes::readObj(dir + "/bunny.obj").size(), 3674u);
}

// ------------------------------------------------------ generator claims

TriCase scaledCyl(TriCase k, double f) {
  k.cyl.radius *= f;
  k.cyl.lz *= f;
  return k;
}

// Every near feature is built so that, in the cylinder frame, the triangle
// meets the cylinder scaled about its centre by f iff f >= 1 + delta (the
// touching feature is the triangle's closest point to the scaled surface;
// see nearCase in scenes.h). The world mapping rounds, so the claim holds to
// an accuracy eta of a few ulps of the coordinates relative to the feature
// size: eta = 64 eps max|coordinate| / min(r, lz / 2). Checked exactly with
// the GMP oracle on both sides of 1 + delta.
TEST(CompareGenerators, NearCasesHaveTheClaimedClearance) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  const long n = test::scaled(3000);
  long checked = 0, below_resolution = 0;
  for (long i = 0; i < n; ++i) {
    const TriCase k = scenes::generate(scenes::Family::kNear, seed, i);
    ASSERT_TRUE(std::isfinite(k.delta)) << "index " << i;
    double mag = 0;
    for (const auto* v : {&k.pose.t, &k.tri.a, &k.tri.b, &k.tri.c})
      mag = std::fmax(mag,
                      std::fmax(std::fabs(v->x),
                                std::fmax(std::fabs(v->y), std::fabs(v->z))));
    const double size = std::fmin(k.cyl.radius, k.cyl.lz / 2);
    const double eta = 64 * 0x1p-52 * mag / size;
    if (std::fabs(k.delta) <= 2 * eta) {
      ++below_resolution;
      continue;
    }
    ++checked;
    const double f_out = (1 + k.delta) * (1 - eta);  // just below the flip
    const double f_in = (1 + k.delta) * (1 + eta);   // just above it
    const TriCase lo = scaledCyl(k, f_out), hi = scaledCyl(k, f_in);
    EXPECT_FALSE(oracle::triangleCylinder(lo.cyl, lo.pose, lo.tri))
        << "index " << i << " feature " << k.feature << " delta " << k.delta;
    EXPECT_TRUE(oracle::triangleCylinder(hi.cyl, hi.pose, hi.tri))
        << "index " << i << " feature " << k.feature << " delta " << k.delta;
    // And so the unscaled case is on the side delta's sign says.
    EXPECT_EQ(oracle::triangleCylinder(k.cyl, k.pose, k.tri), k.delta < 0)
        << "index " << i << " feature " << k.feature << " delta " << k.delta;
  }
  // Offsets of 1e-15 and a few ulps are below the construction's accuracy;
  // everything from 1e-1 to about 1e-13 must have been checked.
  EXPECT_GT(checked, n / 2);
  RecordProperty("checked", int(checked));
  RecordProperty("below_resolution", int(below_resolution));
}

// The sets are a pure function of (seed, index): the basis of "results do
// not depend on the thread count".
TEST(CompareGenerators, CasesAreDeterministic) {
  for (auto f : scenes::kAllFamilies)
    for (std::uint64_t i : {0u, 7u, 1234u}) {
      const TriCase a = scenes::generate(f, 5, i),
                    b = scenes::generate(f, 5, i);
      EXPECT_EQ(compare::formatCaseHex(a), compare::formatCaseHex(b));
    }
}

TEST(CompareCaseText, HexRoundTripIsBitExact) {
  for (auto f : scenes::kAllFamilies) {
    const TriCase k = scenes::generate(f, 11, 3);
    const auto back = compare::parseCaseHex(compare::formatCaseHex(k));
    ASSERT_TRUE(back.has_value());
    EXPECT_EQ(compare::formatCaseHex(*back), compare::formatCaseHex(k));
    EXPECT_EQ(std::memcmp(&back->tri, &k.tri, sizeof k.tri), 0);
    EXPECT_EQ(std::memcmp(&back->pose, &k.pose, sizeof k.pose), 0);
  }
  EXPECT_FALSE(compare::parseCaseHex("1 2 3").has_value());
}

// -------------------------------------------------- issue 9: the hang

// The case of issue 9 (compare/known_cases.h): GJKSolver_libccd<double>
// with its default tolerance never returns on it; the harness must kill the
// query at its time limit, count it in `hangs`, and go on.
TriCase issue9Case() { return compare::discHangCase(); }

TEST(CompareTimeLimit, DiscHangIsDetectedWithinTheLimit) {
  const TriCase k = issue9Case();
  ASSERT_TRUE(oracle::triangleCylinder(k.cyl, k.pose, k.tri));
  std::vector<CaseSet> sets = {
      {"family", "issue9", compare::kNaN, 1, [k](std::uint64_t) {
         return Case{k, nullptr};
       }}};
  compare::RunOptions opt;
  opt.methods = {Method::kTricyl, Method::kFclLibccdDefault,
                 Method::kFclLibccd1e6};
  // tricyl::Solver inside FCL must answer it (issue 9), contact path too.
  for (Method m : {Method::kTricylFcl, Method::kTricylFclContact})
    if (compare::methodAvailable(m)) opt.methods.push_back(m);
  opt.workers = 1;
  opt.timeout_s = 0.5;
  opt.progress = false;
  const auto t0 = std::chrono::steady_clock::now();
  compare::RunResult r = compare::runAll(sets, opt);
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
          .count();
  // The limit plus fork and poll slack, far from "never".
  EXPECT_LT(secs, 5.0);
  ASSERT_EQ(r.hangs.size(), 1u);
  EXPECT_EQ(r.hangs[0].method, Method::kFclLibccdDefault);
  const auto& st = r.sets[0];
  EXPECT_EQ(st.cases, 1u);
  EXPECT_EQ(st.method[int(Method::kFclLibccdDefault)].hangs, 1u);
  EXPECT_EQ(st.method[int(Method::kFclLibccdDefault)].ns.size(), 0u)
      << "a hung query must not be timed";
  // The methods after the hung one still ran (the worker was restarted).
  EXPECT_EQ(st.method[int(Method::kFclLibccd1e6)].cases, 1u);
  EXPECT_EQ(st.method[int(Method::kFclLibccd1e6)].hangs, 0u);
  // tricyl answers it, correctly, and so does its FCL solver.
  for (Method m : opt.methods) {
    if (m == Method::kFclLibccdDefault || m == Method::kFclLibccd1e6) continue;
    EXPECT_EQ(st.method[int(m)].cases, 1u) << compare::methodName(m);
    EXPECT_EQ(st.method[int(m)].wrong(), 0u) << compare::methodName(m);
  }
}

// FCL gets proper rotations: a pose with det R = -1 reaches the FCL methods
// as R diag(1, 1, -1), which has det +1 and describes the same solid (the
// oracle's verdict is the same, exactly), and is left alone otherwise.
TEST(CompareFairness, ImproperPosesReachFclAsTheSameSolid) {
  const std::uint64_t seed = test::baseSeed();
  SCOPED_TRACE(test::seedTrace(seed));
  int improper = 0;
  for (auto f : {scenes::Family::kNear, scenes::Family::kAligned})
    for (std::uint64_t i = 0; i < 400; ++i) {
      const TriCase k = scenes::generate(f, seed, i);
      const Pose<double> p = compare::fclPose(k.pose);
      if (!compare::isImproper(k.pose)) {
        EXPECT_EQ(compare::formatCaseHex({k.cyl, p, k.tri}),
                  compare::formatCaseHex(k));
        continue;
      }
      ++improper;
      EXPECT_FALSE(compare::isImproper(p));
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
          EXPECT_EQ(p.R[r][c], c == 2 ? -k.pose.R[r][c] : k.pose.R[r][c]);
      EXPECT_EQ(oracle::triangleCylinder(k.cyl, p, k.tri),
                oracle::triangleCylinder(k.cyl, k.pose, k.tri))
          << scenes::familyName(f) << " " << i;
    }
  // A quarter of the exact (axis-permutation) poses, half the cases.
  EXPECT_GT(improper, 100);
}

// The aligned case of seed 1, index 25990 (r = 0.75, lz = 2, a signed
// permutation with det R = -1, the triangle's plane containing the axis):
// handed the mirrored matrix, libccd never returned with either tolerance.
// The harness hands FCL the proper rotation of the same solid, on which
// every FCL method answers; the case is counted as improper.
TEST(CompareFairness, AlignedMirroredCaseGetsAProperPose) {
  const auto k = compare::parseCaseHex(
      "0x1.8p-1 0x1p+1 -0x1p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 -0x1p+0 0x0p+0 "
      "0x1p+0 0x0p+0 -0x1p-1 0x0p+0 0x1p+1 0x1.6p+0 0x1p-1 0x1.7p-2 -0x1p-1 "
      "-0x1.cp-1 0x1p+1 -0x1.2p+1 0x1.ap+0 0x1.c4p+1");
  ASSERT_TRUE(k.has_value());
  EXPECT_EQ(compare::formatCaseHex(*k),
            compare::formatCaseHex(
                scenes::generate(scenes::Family::kAligned, 1, 25990)))
      << "the aligned generator changed; update the literal";
  ASSERT_TRUE(compare::isImproper(k->pose));
  const TriCase kk = *k;
  std::vector<CaseSet> sets = {
      {"family", "aligned25990", compare::kNaN, 1, [kk](std::uint64_t) {
         return Case{kk, nullptr};
       }}};
  compare::RunOptions opt;
  opt.methods = {Method::kFclLibccd1e6, Method::kTricyl,
                 Method::kFclLibccdDefault, Method::kFclIndep};
  for (Method m : {Method::kTricylFcl, Method::kTricylFclContact})
    if (compare::methodAvailable(m)) opt.methods.push_back(m);
  opt.workers = 1;
  opt.timeout_s = 0.5;
  opt.progress = false;
  compare::RunResult r = compare::runAll(sets, opt);
  EXPECT_EQ(r.hangs.size(), 0u);
  EXPECT_EQ(r.sets[0].improper, 1u);
  for (Method m : opt.methods)
    EXPECT_EQ(r.sets[0].method[int(m)].cases, 1u) << compare::methodName(m);
  EXPECT_EQ(r.sets[0].method[int(Method::kTricyl)].wrong(), 0u);
  for (Method m : {Method::kTricylFcl, Method::kTricylFclContact})
    if (compare::methodAvailable(m)) {
      EXPECT_EQ(r.sets[0].method[int(m)].wrong(), 0u) << compare::methodName(m);
    }
}

// The statistics do not depend on the number of workers.
TEST(CompareRunner, CountsDoNotDependOnWorkers) {
  std::vector<CaseSet> sets;
  for (auto f : {scenes::Family::kNear, scenes::Family::kAligned})
    sets.push_back({"family", scenes::familyName(f), compare::kNaN, 300,
                    [f](std::uint64_t i) {
                      return Case{scenes::generate(f, 3, i), nullptr};
                    }});
  compare::RunOptions opt;
  opt.methods = {Method::kTricyl, Method::kDiagnosticUncertified,
                 Method::kTricylFloat, Method::kFclLibccd1e6,
                 Method::kFclIndep};
  opt.progress = false;
  opt.unit = 37;
  opt.workers = 1;
  compare::RunResult a = compare::runAll(sets, opt);
  opt.workers = 3;
  compare::RunResult b = compare::runAll(sets, opt);
  for (std::size_t s = 0; s < sets.size(); ++s) {
    EXPECT_EQ(a.sets[s].cases, 300u);
    EXPECT_EQ(a.sets[s].hits, b.sets[s].hits);
    EXPECT_EQ(a.sets[s].stage, b.sets[s].stage);
    for (Method m : opt.methods) {
      const auto &x = a.sets[s].method[int(m)], &y = b.sets[s].method[int(m)];
      EXPECT_EQ(x.cases, 300u);
      EXPECT_EQ(x.false_positives, y.false_positives) << compare::methodName(m);
      EXPECT_EQ(x.false_negatives, y.false_negatives) << compare::methodName(m);
      EXPECT_EQ(x.hangs, y.hangs);
      EXPECT_EQ(x.max_fp_size, y.max_fp_size);
      EXPECT_EQ(x.worst_fp_index, y.worst_fp_index) << compare::methodName(m);
      EXPECT_EQ(x.worst_fn_index, y.worst_fn_index) << compare::methodName(m);
    }
    EXPECT_EQ(a.sets[s].method[0].wrong(), 0u) << "tricyl must be exact";
  }
}

// ------------------------------------------- end to end: the executable

#ifdef TRICYL_COMPARE_EXE
std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

TEST(CompareEndToEnd, SmallRunWritesParsableReports) {
  char tmpl[] = "/tmp/tricyl_compare_test_XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  const std::string cmd = std::string("'") + TRICYL_COMPARE_EXE + "' --out '" +
                          dir + "' --cases 150 --mesh-cases 30 " +
                          "--sweep-cases 8 --threads 2 --distance-cases 40 " +
                          "--margin-cases 4 --quiet > '" + dir +
                          "/stdout.txt' 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << slurp(dir + "/stdout.txt");

  // results.json parses and has one row per family x method.
  const auto j = nlohmann::json::parse(slurp(dir + "/results.json"));
  const std::set<std::string> fams = {"uniform", "near",   "far",
                                      "thin",    "sliver", "aligned"};
  // Rows expected per family: every available method that applies.
  auto expected = [](bool mesh, compare::MeshPath path) {
    CaseSet set;
    set.mesh = mesh;
    set.mesh_path = path;
    std::size_t n = 0;
    for (int m = 0; m < compare::kMethodCount; ++m)
      n += compare::methodAvailable(Method(m)) &&
           compare::methodApplies(set, Method(m));
    return n;
  };
  std::map<std::string, std::size_t> rows_of;
  for (const auto& row : j["results"]) {
    const std::string fam = row["family"].get<std::string>();
    ++rows_of[fam];
    if (!fams.count(fam) && fam.rfind("mesh_", 0) != 0 && fam != "disc_hang") {
      // a cylinder query: "<query>/<family>"
      EXPECT_TRUE(compare::haveQueries()) << fam;
      EXPECT_NE(fam.find('/'), std::string::npos) << fam;
    }
  }
  for (const auto& f : fams)
    EXPECT_EQ(rows_of[f], expected(false, compare::MeshPath::kScan)) << f;
  EXPECT_EQ(rows_of["mesh_scan"], expected(true, compare::MeshPath::kScan));
  EXPECT_EQ(rows_of["mesh_bvh"], expected(true, compare::MeshPath::kBvh));
  // The known disc case runs in every default run, and hangs libccd at its
  // default tolerance only, on the pose as given (a proper rotation).
  EXPECT_EQ(rows_of["disc_hang"], expected(false, compare::MeshPath::kScan));
  ASSERT_EQ(j["hangs"].size(), 1u);
  EXPECT_EQ(j["hangs"][0]["set"], "disc_hang");
  EXPECT_EQ(j["hangs"][0]["method"], "fcl_libccd_default");
  EXPECT_EQ(j["hangs"][0]["case_hex"],
            compare::formatCaseHex(compare::discHangCase()));
  // The exhaustive BVH rows carry triangle counts; tricyl::collide's are
  // exact (none missed, none false).
  for (const auto& row : j["results"])
    if (row["family"] == "mesh_bvh" && row["method"] == "tricyl_fcl") {
      EXPECT_EQ(row["missed_triangles"], 0);
      EXPECT_EQ(row["extra_triangles"], 0);
    }
  EXPECT_FALSE(j["stability"].empty());
  EXPECT_FALSE(j["stages"].empty());
  EXPECT_FALSE(j["agreement"].empty());
  ASSERT_TRUE(j.contains("worst_cases"));
  for (const auto& w : j["worst_cases"])
    EXPECT_NE(w["method"], "tricyl") << "tricyl has no misclassified case";
  EXPECT_NE(slurp(dir + "/worst_cases.txt").find("# tricyl-compare"),
            std::string::npos);
  for (const auto& row : j["results"]) {
    if (row["method"] == "tricyl") {
      EXPECT_EQ(row["false_positives"], 0) << row["family"];
      EXPECT_EQ(row["false_negatives"], 0) << row["family"];
      EXPECT_EQ(row["hangs"], 0) << row["family"];
    }
  }

  // results.csv has the required columns, and the same rows.
  std::ifstream csv(dir + "/results.csv");
  std::string header;
  ASSERT_TRUE(std::getline(csv, header));
  const auto cols = splitCsv(header);
  for (const char* c :
       {"family", "method", "cases", "false_positives", "false_negatives",
        "hangs", "ns_mean", "ns_median", "ns_p99", "ns_max"})
    EXPECT_NE(std::find(cols.begin(), cols.end(), c), cols.end()) << c;
  std::size_t rows = 0;
  std::set<std::string> methods;
  for (std::string line; std::getline(csv, line);) {
    const auto f = splitCsv(line);
    ASSERT_EQ(f.size(), cols.size()) << line;
    methods.insert(f[1]);
    ++rows;
  }
  EXPECT_EQ(rows, j["results"].size());
  EXPECT_TRUE(methods.count("tricyl"));
  for (const auto& m : methods)
    EXPECT_TRUE(m.rfind("tricyl", 0) == 0 || m.rfind("fcl", 0) == 0 ||
                m == "diagnostic_uncertified")
        << m;

  const std::string md = slurp(dir + "/report.md");
  EXPECT_NE(md.find("## Per family"), std::string::npos);
  EXPECT_NE(md.find("## Agreement with tricyl"), std::string::npos);
  EXPECT_NE(slurp(dir + "/error_vs_time.gp").find("plot"), std::string::npos);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    struct stat st;
    EXPECT_EQ(stat((dir + "/error_vs_time.png").c_str(), &st), 0);
    EXPECT_EQ(stat((dir + "/stability_delta.png").c_str(), &st), 0);
  }
#if defined(TRICYL_COMPARE_HAVE_DISTANCE)
  // The distance families: one row per family x method; tricyl's distance
  // is 0 exactly when the exact Boolean says the sets meet, so it never
  // disagrees with it in sign, and it never misjudges a margin.
  {
    std::istringstream dcsv(slurp(dir + "/distance.csv"));
    std::string line;
    std::getline(dcsv, line);  // header
    std::size_t drows = 0;
    while (std::getline(dcsv, line)) {
      ++drows;
      const std::vector<std::string> f = splitCsv(line);
      ASSERT_GE(f.size(), 5u) << line;
      EXPECT_TRUE(fams.count(f[0])) << line;
      if (f[1] == "tricyl") {
        EXPECT_EQ(f[4], "0") << line;  // sign disagreements
      }
    }
    EXPECT_EQ(drows, fams.size() * 4);
    // tricyl's error_bound holds on every case, before and after
    // tightenDistance (columns bound_violated, tight_violated).
    std::istringstream bcsv(slurp(dir + "/distance_bound.csv"));
    std::getline(bcsv, line);  // header
    std::size_t brows = 0;
    while (std::getline(bcsv, line)) {
      ++brows;
      const std::vector<std::string> f = splitCsv(line);
      ASSERT_EQ(f.size(), 9u) << line;
      EXPECT_EQ(f[6], "0") << line;
      EXPECT_EQ(f[8], "0") << line;
    }
    EXPECT_EQ(brows, fams.size());
    std::istringstream mcsv(slurp(dir + "/margin.csv"));
    std::getline(mcsv, line);
    std::size_t mrows = 0;
    while (std::getline(mcsv, line)) {
      ++mrows;
      const std::vector<std::string> f = splitCsv(line);
      ASSERT_GE(f.size(), 4u) << line;
      EXPECT_EQ(f[3], "0") << line;  // tricyl's wrong margin answers
    }
    EXPECT_EQ(mrows, fams.size());
    EXPECT_NE(slurp(dir + "/distance_error_vs_time.gp").find("plot"),
              std::string::npos);
  }
#endif
  std::system(("rm -rf '" + dir + "'").c_str());
}

// The replay path: the issue 9 case from a hangs.txt-style file, through the
// executable, reports the hang in results.csv within the limit.
TEST(CompareEndToEnd, ReplayReportsTheDiscHang) {
  char tmpl[] = "/tmp/tricyl_compare_replay_XXXXXX";
  ASSERT_NE(mkdtemp(tmpl), nullptr);
  const std::string dir = tmpl;
  {
    std::ofstream f(dir + "/case.txt");
    f << "# issue 9\ncase " << compare::formatCaseHex(issue9Case()) << "\n";
  }
  const std::string cmd = std::string("'") + TRICYL_COMPARE_EXE +
                          "' --replay '" + dir + "/case.txt' --out '" + dir +
                          "/out' --methods tricyl,fcl_libccd_default "
                          "--timeout 0.5 --no-plots --quiet > /dev/null 2>&1";
  const auto t0 = std::chrono::steady_clock::now();
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - t0)
                .count(),
            10.0);
  const auto j = nlohmann::json::parse(slurp(dir + "/out/results.json"));
  ASSERT_EQ(j["hangs"].size(), 1u);
  EXPECT_EQ(j["hangs"][0]["case_hex"], compare::formatCaseHex(issue9Case()));
  for (const auto& row : j["results"])
    if (row["method"] == "fcl_libccd_default") {
      EXPECT_EQ(row["hangs"], 1);
    }
  EXPECT_NE(slurp(dir + "/out/hangs.txt")
                .find("case " + compare::formatCaseHex(issue9Case())),
            std::string::npos);
  std::system(("rm -rf '" + dir + "'").c_str());
}
#endif

}  // namespace
}  // namespace tricyl
