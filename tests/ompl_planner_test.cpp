// SPDX-License-Identifier: BSD-3-Clause
// OMPL planning with tricyl (issue 22), judged by the exact oracle of
// compare/ (GMP, compare/oracle.h), never by tricyl itself:
// - a seeded RRTConnect plan through env.obj with the example's validity
//   checker and motion validator: every state the validator checks is free
//   for the grown cylinder, and the robot itself is free at states far
//   denser than the validator's (examples/ompl_planner/planner.h proves
//   the motion free from the first property; the second checks it);
// - near-surface states (the checked cylinder tangent to a face, pushed in
//   or out by 1e-12 .. 1e-2 of the mesh's diagonal): tricyl::collide, direct
//   and through FCL's broadphase, agrees with the oracle on every one.
// Skipped, with a message, when ../shared/data/meshes is absent.
#include <gtest/gtest.h>
#include <ompl/geometric/PathSimplifier.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>

#include <string>

#include "planning_harness.h"

namespace {

namespace og = ompl::geometric;
using example::CheckPath;
using example::CylinderValidityChecker;

struct Loaded {
  example::Mesh mesh;
  example::Scene scene;
  tricyl::compare::Mesh oracle;
};

bool load(const std::string& name, Loaded* out) {
  const std::string path = std::string(TRICYL_MESH_DIR) + "/" + name + ".obj";
  if (!example::readObj(path, &out->mesh) ||
      !example::sceneFor(name, out->mesh, &out->scene))
    return false;
  out->oracle = planning::oracleMesh(name, out->mesh);
  return true;
}

constexpr unsigned kPlanSeed = 4;

TEST(OmplPlanner, SeededPlanIsFreeByTheOracle) {
  Loaded d;
  if (!load("env", &d)) GTEST_SKIP() << "env.obj not found in " TRICYL_MESH_DIR;
  ompl::RNG::setSeed(kPlanSeed);  // before any OMPL generator exists
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const example::Scene& sc = d.scene;
  auto robot =
      std::make_shared<fcl::Cylinderd>(sc.checkedRadius(), sc.checkedLength());
  const example::Environment env(d.mesh);
  planning::Problem p = planning::makeProblem(sc, [&](const auto& si) {
    return std::make_shared<CylinderValidityChecker>(si, robot, env,
                                                     CheckPath::kDirect);
  });
  ASSERT_TRUE(planning::solveFirst(*p.setup, 100000)) << "seed " << kPlanSeed;
  const auto si = p.setup->getSpaceInformation();
  const og::PathGeometric raw = p.setup->getSolutionPath();
  og::PathGeometric simplified = raw;
  og::PathSimplifier(si).simplifyMax(simplified);
  ASSERT_TRUE(raw.check());

  const CylinderValidityChecker direct(si, robot, env, CheckPath::kDirect),
      broad(si, robot, env, CheckPath::kBroadphase);
  ompl::base::State* s = si->allocState();
  for (const og::PathGeometric* path :
       std::initializer_list<const og::PathGeometric*>{&raw, &simplified}) {
    if (path == &simplified && !simplified.check()) continue;  // not used
    SCOPED_TRACE(path == &raw ? "planner's path" : "simplified path");
    // Every state the motion validator checks, as it checks them.
    int checked = 0, wrong = 0, broad_wrong = 0, hits = 0;
    for (std::size_t i = 0; i + 1 < path->getStateCount(); ++i) {
      const auto* a = path->getState(i);
      const auto* b = path->getState(i + 1);
      const unsigned n = p.motion->steps(a, b);
      for (unsigned j = i == 0 ? 0 : 1; j <= n; ++j) {
        si->getStateSpace()->interpolate(a, b, double(j) / n, s);
        if (j == n) si->copyState(s, b);
        const fcl::Transform3d tf = example::toTransform(s);
        const bool truth = planning::oracleCollides(
            d.oracle, sc.checkedRadius(), sc.checkedLength(), tf);
        hits += truth;
        wrong += direct.collides(tf) != truth;
        broad_wrong += broad.collides(tf) != truth;
        ++checked;
      }
    }
    EXPECT_EQ(hits, 0) << "of " << checked << " states, seed " << kPlanSeed;
    EXPECT_EQ(wrong, 0) << "seed " << kPlanSeed;
    EXPECT_EQ(broad_wrong, 0) << "seed " << kPlanSeed;
    std::printf("[ info ] %s: %d validator states, all free\n",
                path == &raw ? "planner's path" : "simplified path", checked);
  }
  si->freeState(s);
  // The path the example hands on (the simplified one when it passes its
  // check), robot itself, at 8 times the validator's density: the motion is
  // free between the checked states too.
  const og::PathGeometric& final_path = simplified.check() ? simplified : raw;
  int dense_hits = 0;
  const auto dense = planning::densePath(final_path, *p.motion, sc.step / 8);
  for (const auto& tf : dense)
    dense_hits += planning::oracleCollides(d.oracle, sc.radius, sc.length, tf);
  EXPECT_EQ(dense_hits, 0) << "of " << dense.size() << " states, seed "
                           << kPlanSeed;
  EXPECT_GT(dense.size(), 8u * (final_path.getStateCount() - 1));
  std::printf("[ info ] final path: %zu dense states, all free\n",
              dense.size());
}

// tricyl::collide (direct and broadphase) against the oracle on states
// tangent to the mesh's faces, pushed in and out by tiny amounts.
void nearSurface(const std::string& name, std::uint64_t count) {
  Loaded d;
  if (!load(name, &d))
    GTEST_SKIP() << name << ".obj not found in " TRICYL_MESH_DIR;
  const example::Scene& sc = d.scene;
  auto robot =
      std::make_shared<fcl::Cylinderd>(sc.checkedRadius(), sc.checkedLength());
  const example::Environment env(d.mesh);
  auto space = example::makeSpace(sc.lo, sc.hi, sc.reach());
  auto si = std::make_shared<ompl::base::SpaceInformation>(space);
  const CylinderValidityChecker direct(si, robot, env, CheckPath::kDirect),
      broad(si, robot, env, CheckPath::kBroadphase);
  const std::uint64_t seed = 22;
  std::uint64_t hits = 0, wrong = 0, broad_wrong = 0;
  for (std::uint64_t i = 0; i < count; ++i) {
    const planning::NearPose np = planning::nearPose(
        d.oracle, sc.checkedRadius(), sc.checkedLength(), seed, i);
    const bool truth = planning::oracleCollides(d.oracle, sc.checkedRadius(),
                                                sc.checkedLength(), np.tf);
    hits += truth;
    const bool a = direct.collides(np.tf), b = broad.collides(np.tf);
    wrong += a != truth;
    broad_wrong += b != truth;
    if (a != truth || b != truth)
      ADD_FAILURE() << name << " seed " << seed << " index " << i << " ("
                    << np.feature << ", offset " << np.offset << "): oracle "
                    << truth << ", direct " << a << ", broadphase " << b;
    if (wrong + broad_wrong > 10) break;
  }
  EXPECT_EQ(wrong, 0u);
  EXPECT_EQ(broad_wrong, 0u);
  // Both answers occur in numbers, so the test can fail either way (other
  // faces near the tangent one make most states touch on env.obj).
  EXPECT_GT(hits, count / 20);
  EXPECT_LT(hits, count - count / 20);
  std::printf(
      "[ info ] %s: %llu near-surface states, %llu touching, tricyl "
      "0 wrong\n",
      name.c_str(), static_cast<unsigned long long>(count),
      static_cast<unsigned long long>(hits));
}

TEST(OmplPlanner, NearSurfaceEnvMatchesTheOracle) { nearSurface("env", 3000); }
TEST(OmplPlanner, NearSurfaceBunnyMatchesTheOracle) {
  nearSurface("bunny", 3000);
}

}  // namespace
