// SPDX-License-Identifier: BSD-3-Clause
// bench_planning (issue 22): tricyl::collide against stock fcl::collide
// inside a real planner, OMPL's RRTConnect, on the scenes of
// examples/ompl_planner (env.obj, bunny.obj).
//
// Six validity checkers, each examples/ompl_planner's CylinderValidityChecker:
//   tricyl                 tricyl::collide, the mesh as one BVH
//   stock                  fcl::collide, its default request (gjk_tolerance
//                          1e-6, what FCL's collide hands libccd)
//   stock_ccd_default      fcl::collide, gjk_tolerance at libccd's own
//                          default (constants::gjk_default_tolerance, ~2e-14)
// and the same three through FCL's broadphase (DynamicAABBTreeCollisionManager
// over the mesh's connected parts; tricyl::DefaultCollisionFunction or
// fcl::DefaultCollisionFunction).
//
// Planning: for every seed, every checker plans the same problem with the
// same OMPL seed to its first solution or an iteration cap: a fixed amount
// of work, never a time budget, so a faster checker is not handed more
// work. With identical answers every checker then makes the same checks in
// the same order; the report verifies it (count and a hash of the answer
// sequence per seed). Reported: plans solved, time to first solution
// (median and per seed), the number of validity checks and their mean,
// median and p99 time.
//
// Near-surface: states tangent to mesh faces pushed in or out by 1e-12 ..
// 1e-2 of the diagonal (bench/planning_harness.h), every answer settled by
// the exact oracle of compare/; wrong answers per checker.
//
// Every plan and every near-surface batch runs in a forked child, and every
// validity check is time-boxed as tricyl-compare does it (compare/
// runner.cpp): the child publishes the start time of the check in progress
// in shared memory; a check running longer than --timeout is killed with
// the child (libccd's MPR has no iteration cap, issue 9) and recorded as a
// hang (a plan: unsolved; near-surface: a wrong answer, resumed after it).
//
//   bench_planning [--meshes DIR] [--scenes env,bunny] [--seeds 20]
//                  [--near 20000] [--iterations 100000] [--timeout 1]
//                  [--out report.md]
#include <fenv.h>
#include <ompl/base/goals/GoalState.h>
#include <ompl/util/Console.h>
#include <ompl/util/RandomNumbers.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include "planning_harness.h"
#include "runner.h"  // compare/: percentile

namespace {

namespace ob = ompl::base;
using Clock = std::chrono::steady_clock;
using example::CheckPath;
using example::NarrowPhase;

std::int64_t nowNs() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             Clock::now().time_since_epoch())
      .count();
}

/// CPU time of this process (the planning child runs one thread): on a
/// shared machine it leaves out the time other jobs held the core, which
/// the wall time of a plan includes.
double cpuSeconds() {
  timespec ts{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
  return double(ts.tv_sec) + 1e-9 * double(ts.tv_nsec);
}

struct CheckerKind {
  const char* name;
  NarrowPhase narrow;
  CheckPath path;
  double gjk_tolerance;
};

const CheckerKind kCheckers[] = {
    {"tricyl", NarrowPhase::kTricyl, CheckPath::kDirect, 1e-6},
    {"stock", NarrowPhase::kStockFcl, CheckPath::kDirect, 1e-6},
    {"stock_ccd_default", NarrowPhase::kStockFcl, CheckPath::kDirect,
     fcl::constants<double>::gjk_default_tolerance()},
    {"tricyl_broadphase", NarrowPhase::kTricyl, CheckPath::kBroadphase, 1e-6},
    {"stock_broadphase", NarrowPhase::kStockFcl, CheckPath::kBroadphase, 1e-6},
    {"stock_ccd_default_broadphase", NarrowPhase::kStockFcl,
     CheckPath::kBroadphase, fcl::constants<double>::gjk_default_tolerance()},
};
constexpr int kNumCheckers = int(std::size(kCheckers));
/// The tricyl checker each one is compared with (same path).
int baselineOf(int c) {
  return kCheckers[c].path == CheckPath::kDirect ? 0 : 3;
}

std::shared_ptr<example::CylinderValidityChecker> makeChecker(
    const ob::SpaceInformationPtr& si, const example::Scene& sc,
    const example::Environment& env, const CheckerKind& k) {
  fcl::CollisionRequestd request;
  request.gjk_tolerance = k.gjk_tolerance;
  return std::make_shared<example::CylinderValidityChecker>(
      si,
      std::make_shared<fcl::Cylinderd>(sc.checkedRadius(), sc.checkedLength()),
      env, k.path, k.narrow, request);
}

// ------------------------------------------------------- the time box

/// Shared with the child: the start time of the check in progress (0 when
/// none) and the index of the near-surface state being checked.
struct Box {
  std::atomic<std::int64_t> started_ns{0};
  std::atomic<std::uint64_t> index{0};
};

enum class Outcome { kDone, kHung, kFailed };

/// Runs fn() (returning an exit code) in a forked child; kills it if a
/// check runs longer than timeout_s.
template <class Fn>
Outcome runBoxed(Box* box, double timeout_s, Fn&& fn) {
  box->started_ns = 0;
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = fork();
  if (pid < 0) {
    std::perror("fork");
    std::exit(2);
  }
  if (pid == 0) {
    // FCL measured as users run it: the default floating-point environment.
    fedisableexcept(FE_ALL_EXCEPT);
    _exit(fn());
  }
  const std::int64_t limit = std::int64_t(timeout_s * 1e9);
  for (;;) {
    int status = 0;
    if (waitpid(pid, &status, WNOHANG) == pid)
      return WIFEXITED(status) && WEXITSTATUS(status) == 0 ? Outcome::kDone
                                                           : Outcome::kFailed;
    const std::int64_t started = box->started_ns.load();
    if (started != 0 && nowNs() - started > limit) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      return Outcome::kHung;
    }
    usleep(1000);
  }
}

/// A file the child writes and the parent reads back.
struct TempFile {
  std::string path;
  TempFile() {
    char name[] = "/tmp/bench_planning_XXXXXX";
    const int fd = mkstemp(name);
    if (fd < 0) {
      std::perror("mkstemp");
      std::exit(2);
    }
    close(fd);
    path = name;
  }
  ~TempFile() { std::remove(path.c_str()); }
};

template <class T>
void putVec(std::FILE* f, const std::vector<T>& v) {
  const std::uint64_t n = v.size();
  std::fwrite(&n, sizeof n, 1, f);
  if (n) std::fwrite(v.data(), sizeof(T), n, f);
}
template <class T>
std::vector<T> getVec(std::FILE* f) {
  std::uint64_t n = 0;
  if (std::fread(&n, sizeof n, 1, f) != 1) return {};
  std::vector<T> v(n);
  if (n && std::fread(v.data(), sizeof(T), n, f) != n) v.clear();
  return v;
}

// ------------------------------------------------------------ planning

/// Times every check (the time stamp is the time box's) and keeps a hash
/// of the answer sequence.
class TimedChecker : public ob::StateValidityChecker {
 public:
  TimedChecker(const ob::SpaceInformationPtr& si,
               std::shared_ptr<example::CylinderValidityChecker> inner,
               Box* box)
      : ob::StateValidityChecker(si), inner_(std::move(inner)), box_(box) {}
  bool isValid(const ob::State* s) const override {
    const std::int64_t t0 = nowNs();
    box_->started_ns.store(t0, std::memory_order_relaxed);
    const bool valid = inner_->isValid(s);
    const std::int64_t t1 = nowNs();
    box_->started_ns.store(0, std::memory_order_relaxed);
    ns.push_back(float(t1 - t0));
    hash = (hash ^ (valid ? 0x9e3779b97f4a7c15ULL : 0x632be59bd9b4e019ULL)) *
           0x100000001b3ULL;
    return valid;
  }
  const example::CylinderValidityChecker& inner() const { return *inner_; }
  mutable std::vector<float> ns;
  mutable std::uint64_t hash = 0xcbf29ce484222325ULL;

 private:
  std::shared_ptr<example::CylinderValidityChecker> inner_;
  Box* box_;
};

struct PlanResult {
  Outcome outcome = Outcome::kFailed;
  bool solved = false;
  double seconds = 0;  // time to first solution (or to the cap), wall
  double cpu = 0;      // the same in CPU time of the (one-thread) child
  std::uint64_t hash = 0;
  std::uint64_t path_hash = 0;
  double path_length = 0;
  std::vector<float> ns;  // per check
};

struct SceneData {
  example::Mesh mesh;
  example::Scene scene;
  tricyl::compare::Mesh oracle;
  std::unique_ptr<example::Environment> env;
};

PlanResult plan(const SceneData& d, const CheckerKind& k, unsigned seed,
                unsigned long iterations, double timeout_s, Box* box) {
  TempFile file;
  PlanResult r;
  r.outcome = runBoxed(box, timeout_s, [&]() -> int {
    ompl::RNG::setSeed(seed);  // a fresh process: before any generator
    ompl::msg::setLogLevel(ompl::msg::LOG_ERROR);
    std::shared_ptr<TimedChecker> timed;
    planning::Problem p = planning::makeProblem(d.scene, [&](const auto& si) {
      timed = std::make_shared<TimedChecker>(
          si, makeChecker(si, d.scene, *d.env, k), box);
      return timed;
    });
    // Outside the timed region, as in a planner that keeps its checker:
    // the setup, and a first check of the start and the goal (cold caches
    // and first-touch page faults in the fresh process), not counted.
    p.setup->setup();
    for (int w = 0; w < 4; ++w) {
      const auto& pdef = p.setup->getProblemDefinition();
      timed->inner().isValid(pdef->getStartState(0));
      timed->inner().isValid(pdef->getGoal()->as<ob::GoalState>()->getState());
    }
    timed->ns.reserve(1 << 20);
    const auto t0 = Clock::now();
    const double c0 = cpuSeconds();
    const bool solved = planning::solveFirst(*p.setup, iterations);
    const double cpu = cpuSeconds() - c0;
    const double seconds =
        std::chrono::duration<double>(Clock::now() - t0).count();
    std::uint64_t path_hash = 0;
    double length = 0;
    if (solved) {
      const auto& path = p.setup->getSolutionPath();
      length = path.length();
      for (std::size_t i = 0; i < path.getStateCount(); ++i) {
        const fcl::Transform3d tf = example::toTransform(path.getState(i));
        for (int j = 0; j < 3; ++j) {
          std::uint64_t bits;
          const double x = tf.translation()[j];
          std::memcpy(&bits, &x, sizeof bits);
          path_hash = (path_hash ^ bits) * 0x100000001b3ULL;
        }
      }
    }
    std::FILE* f = std::fopen(file.path.c_str(), "wb");
    if (!f) return 3;
    const std::uint8_t s = solved;
    std::fwrite(&s, 1, 1, f);
    std::fwrite(&seconds, sizeof seconds, 1, f);
    std::fwrite(&cpu, sizeof cpu, 1, f);
    std::fwrite(&timed->hash, sizeof timed->hash, 1, f);
    std::fwrite(&path_hash, sizeof path_hash, 1, f);
    std::fwrite(&length, sizeof length, 1, f);
    putVec(f, timed->ns);
    return std::fclose(f) == 0 ? 0 : 3;
  });
  if (r.outcome != Outcome::kDone) return r;
  std::FILE* f = std::fopen(file.path.c_str(), "rb");
  std::uint8_t s = 0;
  bool ok = f && std::fread(&s, 1, 1, f) == 1 &&
            std::fread(&r.seconds, sizeof r.seconds, 1, f) == 1 &&
            std::fread(&r.cpu, sizeof r.cpu, 1, f) == 1 &&
            std::fread(&r.hash, sizeof r.hash, 1, f) == 1 &&
            std::fread(&r.path_hash, sizeof r.path_hash, 1, f) == 1 &&
            std::fread(&r.path_length, sizeof r.path_length, 1, f) == 1;
  if (ok) r.ns = getVec<float>(f);
  if (f) std::fclose(f);
  r.solved = ok && s;
  if (!ok) r.outcome = Outcome::kFailed;
  return r;
}

// -------------------------------------------------------- near surface

struct NearStats {
  std::uint64_t fp = 0, fn = 0, hangs = 0;
  std::map<std::string, std::uint64_t> wrong_by_feature;
  double min_wrong_offset = INFINITY, max_wrong_offset = 0;  // |offset|
  std::vector<float> ns;
};

/// Answers of checker k to states [0, n) in forked children, resuming
/// after a hung check.
NearStats nearSurface(const SceneData& d,
                      const std::vector<planning::NearPose>& poses,
                      const std::vector<std::uint8_t>& truth,
                      const CheckerKind& k, double timeout_s, Box* box) {
  NearStats st;
  std::vector<std::uint8_t> answers(poses.size(), 2);  // 2: hung
  std::vector<std::uint8_t> skip(poses.size(), 0);     // hung before
  st.ns.reserve(poses.size());
  std::uint64_t begin = 0;
  while (begin < poses.size()) {
    TempFile file;
    const Outcome o = runBoxed(box, timeout_s, [&]() -> int {
      auto si = std::make_shared<ob::SpaceInformation>(
          example::makeSpace(d.scene.lo, d.scene.hi, d.scene.reach()));
      const auto checker = makeChecker(si, d.scene, *d.env, k);
      std::FILE* f = std::fopen(file.path.c_str(), "wb");
      if (!f) return 3;
      // Warm-up, not counted (as for the plans): the first states again
      // after this batch's start, 2 passes of up to 16.
      for (int w = 0; w < 2; ++w)
        for (std::uint64_t i = begin;
             i < std::min<std::uint64_t>(begin + 16, poses.size()); ++i)
          if (!skip[i]) {
            box->index.store(i, std::memory_order_relaxed);
            box->started_ns.store(nowNs(), std::memory_order_relaxed);
            checker->collides(poses[i].tf);
            box->started_ns.store(0, std::memory_order_relaxed);
          }
      for (std::uint64_t i = begin; i < poses.size(); ++i) {
        if (skip[i]) continue;
        box->index.store(i, std::memory_order_relaxed);
        const std::int64_t t0 = nowNs();
        box->started_ns.store(t0, std::memory_order_relaxed);
        const bool hit = checker->collides(poses[i].tf);
        const std::int64_t t1 = nowNs();
        box->started_ns.store(0, std::memory_order_relaxed);
        const std::uint8_t a = hit;
        const float ns = float(t1 - t0);
        std::fwrite(&a, 1, 1, f);
        std::fwrite(&ns, sizeof ns, 1, f);
        if ((i & 255) == 0) std::fflush(f);  // a hang keeps what came before
      }
      return std::fclose(f) == 0 ? 0 : 3;
    });
    std::FILE* f = std::fopen(file.path.c_str(), "rb");
    std::uint64_t i = begin;
    std::uint8_t a;
    float ns;
    while (f && std::fread(&a, 1, 1, f) == 1 &&
           std::fread(&ns, sizeof ns, 1, f) == 1) {
      while (skip[i]) ++i;
      answers[i++] = a;
      st.ns.push_back(ns);
    }
    if (f) std::fclose(f);
    while (i < poses.size() && skip[i]) ++i;
    if (o == Outcome::kDone && i == poses.size()) break;
    if (o == Outcome::kFailed) {
      std::fprintf(stderr, "bench_planning: near-surface child failed\n");
      std::exit(2);
    }
    // Hung at box->index: the states before it that were not flushed are
    // run again; the hung one stays a hang and is skipped from now on.
    const std::uint64_t hung = box->index.load();
    skip[hung] = 1;
    begin = i;
    std::fprintf(stderr, "  %s: check %" PRIu64 " hung (> %.1f s), killed\n",
                 k.name, hung, timeout_s);
  }
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (answers[i] == truth[i]) continue;
    if (answers[i] == 2)
      ++st.hangs;
    else if (answers[i])
      ++st.fp;
    else
      ++st.fn;
    ++st.wrong_by_feature[poses[i].feature];
    const double off = std::fabs(poses[i].offset);
    st.min_wrong_offset = std::min(st.min_wrong_offset, off);
    st.max_wrong_offset = std::max(st.max_wrong_offset, off);
  }
  return st;
}

// -------------------------------------------------------------- report

double mean(const std::vector<float>& v) {
  if (v.empty()) return NAN;
  double s = 0;
  for (float x : v) s += x;
  return s / double(v.size());
}
double pct(std::vector<float> v, double p) {
  return tricyl::compare::percentile(v, p);
}
double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  const std::size_t n = v.size();
  return n % 2 ? v[n / 2] : (v[n / 2 - 1] + v[n / 2]) / 2;
}

struct Options {
  std::string meshes = TRICYL_MESH_DIR;
  std::vector<std::string> scenes = {"env", "bunny"};
  unsigned seeds = 20;
  std::uint64_t near = 20000;
  unsigned long iterations = 100000;
  double timeout = 1.0;
  std::string out;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  return out;
}

std::string runScene(const std::string& name, const Options& opt, Box* box) {
  SceneData d;
  const std::string file = opt.meshes + "/" + name + ".obj";
  if (!example::readObj(file, &d.mesh) ||
      !example::sceneFor(name, d.mesh, &d.scene)) {
    std::fprintf(stderr, "bench_planning: %s not readable or no scene\n",
                 file.c_str());
    return "";
  }
  d.oracle = planning::oracleMesh(name, d.mesh);
  d.env = std::make_unique<example::Environment>(d.mesh);
  const example::Scene& sc = d.scene;
  std::string md;
  char buf[512];
  auto put = [&md, &buf](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    md += buf;
  };
  put("## %s\n\n", name.c_str());
  put("%zu triangles (%zu connected parts in the broadphase tree); cylinder "
      "r %.4g, length %.4g, checked as r %.4g, length %.4g (motion step "
      "%.4g); planning box (%.4g %.4g %.4g) .. (%.4g %.4g %.4g); RRTConnect to "
      "its first solution or %lu iterations; seeds 1..%u.\n\n",
      d.mesh.triangles.size(), d.env->parts.size(), sc.radius, sc.length,
      sc.checkedRadius(), sc.checkedLength(), sc.step, sc.lo.x(), sc.lo.y(),
      sc.lo.z(), sc.hi.x(), sc.hi.y(), sc.hi.z(), opt.iterations, opt.seeds);

  // Planning: seed-major, the checkers interleaved, so that the machine's
  // drift touches all of them alike.
  std::vector<std::vector<PlanResult>> res(kNumCheckers,
                                           std::vector<PlanResult>(opt.seeds));
  for (unsigned s = 0; s < opt.seeds; ++s) {
    for (int c = 0; c < kNumCheckers; ++c) {
      res[c][s] =
          plan(d, kCheckers[c], s + 1, opt.iterations, opt.timeout, box);
      const PlanResult& r = res[c][s];
      std::fprintf(stderr,
                   "%s seed %u %-28s %s %8.1f ms (CPU %8.1f) %8zu checks\n",
                   name.c_str(), s + 1, kCheckers[c].name,
                   r.outcome == Outcome::kHung
                       ? "hung  "
                       : (r.outcome == Outcome::kFailed
                              ? "failed"
                              : (r.solved ? "solved" : "capped")),
                   r.seconds * 1e3, r.cpu * 1e3, r.ns.size());
    }
  }
  // Seeds solved by every checker: the like-for-like set for times.
  std::vector<unsigned> common;
  for (unsigned s = 0; s < opt.seeds; ++s) {
    bool all = true;
    for (int c = 0; c < kNumCheckers; ++c) all = all && res[c][s].solved;
    if (all) common.push_back(s);
  }
  put("### Planning\n\n");
  put("Time to first solution: median over the %zu seeds every checker "
      "solved. Checks: every validity check of every seed; ratios are "
      "stock / tricyl on the same path (direct or broadphase), from this "
      "run. Identical: seeds whose check count and answer sequence equal "
      "tricyl's on the same path.\n\n",
      common.size());
  put("| checker | solved | hung | time to first solution, median: wall ms "
      "| ratio | CPU ms | ratio | median per-seed ratio (CPU) | checks | mean "
      "ns/check | median | p99 | mean ratio | identical |\n|---|---:|---:|---:|"
      "---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n");
  std::vector<double> mean_ns(kNumCheckers), med_time(kNumCheckers),
      med_cpu(kNumCheckers);
  for (int c = 0; c < kNumCheckers; ++c) {
    std::vector<float> all;
    std::vector<double> times, cpus, ratios;
    unsigned solved = 0, hung = 0, identical = 0;
    const int b = baselineOf(c);
    for (unsigned s = 0; s < opt.seeds; ++s) {
      const PlanResult& r = res[c][s];
      solved += r.solved;
      hung += r.outcome == Outcome::kHung;
      all.insert(all.end(), r.ns.begin(), r.ns.end());
      identical +=
          r.outcome == Outcome::kDone && res[b][s].outcome == Outcome::kDone &&
          r.ns.size() == res[b][s].ns.size() && r.hash == res[b][s].hash;
    }
    for (unsigned s : common) {
      times.push_back(res[c][s].seconds);
      cpus.push_back(res[c][s].cpu);
      ratios.push_back(res[c][s].cpu / res[b][s].cpu);
    }
    mean_ns[c] = mean(all);
    med_time[c] = median(times);
    med_cpu[c] = median(cpus);
    put("| %s | %u/%u | %u | %.1f | %.2f | %.1f | %.2f | %.2f | %zu | %.0f | "
        "%.0f | %.0f | %.2f | %u/%u |\n",
        kCheckers[c].name, solved, opt.seeds, hung, med_time[c] * 1e3,
        med_time[c] / med_time[b], med_cpu[c] * 1e3, med_cpu[c] / med_cpu[b],
        median(ratios), all.size(), mean_ns[c], pct(all, 50), pct(all, 99),
        mean_ns[c] / mean_ns[b], identical, opt.seeds);
  }
  put("\nPer seed: time to first solution, wall / CPU ms, `-` unsolved, "
      "`hung` killed; checks as tricyl made them (`*`: a checker's count or "
      "answer sequence differs).\n\n| seed "
      "| checks | path length |");
  for (const auto& k : kCheckers) put(" %s |", k.name);
  put("\n|---:|---:|---:|");
  for (int c = 0; c < kNumCheckers; ++c) put("---:|");
  put("\n");
  for (unsigned s = 0; s < opt.seeds; ++s) {
    bool same = true;
    for (int c = 0; c < kNumCheckers; ++c)
      same = same && res[c][s].ns.size() == res[0][s].ns.size() &&
             res[c][s].hash == res[0][s].hash;
    put("| %u | %zu%s | %.4g |", s + 1, res[0][s].ns.size(), same ? "" : "*",
        res[0][s].path_length);
    for (int c = 0; c < kNumCheckers; ++c) {
      const PlanResult& r = res[c][s];
      if (r.outcome == Outcome::kHung)
        put(" hung |");
      else if (!r.solved)
        put(" - |");
      else
        put(" %.1f / %.1f |", r.seconds * 1e3, r.cpu * 1e3);
    }
    put("\n");
  }

  // Near surface.
  std::fprintf(stderr, "%s: %" PRIu64 " near-surface states, oracle...\n",
               name.c_str(), opt.near);
  std::vector<planning::NearPose> poses;
  std::vector<std::uint8_t> truth;
  for (std::uint64_t i = 0; i < opt.near; ++i) {
    poses.push_back(planning::nearPose(d.oracle, sc.checkedRadius(),
                                       sc.checkedLength(), 22, i));
    truth.push_back(planning::oracleCollides(
        d.oracle, sc.checkedRadius(), sc.checkedLength(), poses.back().tf));
  }
  const auto touching = std::count(truth.begin(), truth.end(), 1);
  put("\n### Near surface\n\n%" PRIu64
      " states (%td touching by the exact "
      "oracle): the checked cylinder tangent to a face (cap, side or rim), "
      "pushed along its normal by |offset| in [1e-12, 1e-2] x the diagonal, "
      "either way.\n\n| checker | false positives | false negatives | hangs "
      "| wrong by feature | \\|offset\\| of the wrong | mean ns/check | median "
      "| "
      "p99 | mean ratio |\n|---|---:|---:|---:|---|---|---:|---:|---:|---:|\n",
      opt.near, touching);
  std::vector<double> near_mean(kNumCheckers);
  for (int c = 0; c < kNumCheckers; ++c) {
    const NearStats st =
        nearSurface(d, poses, truth, kCheckers[c], opt.timeout, box);
    near_mean[c] = mean(st.ns);
    std::string feat;
    for (const auto& [f, n] : st.wrong_by_feature)
      feat += (feat.empty() ? "" : ", ") + f + " " + std::to_string(n);
    char range[64] = "-";
    if (st.fp + st.fn + st.hangs > 0)
      std::snprintf(range, sizeof range, "%.1e .. %.1e", st.min_wrong_offset,
                    st.max_wrong_offset);
    put("| %s | %" PRIu64 " | %" PRIu64 " | %" PRIu64
        " | %s | %s | %.0f | %.0f | %.0f | %.2f |\n",
        kCheckers[c].name, st.fp, st.fn, st.hangs,
        feat.empty() ? "-" : feat.c_str(), range, near_mean[c], pct(st.ns, 50),
        pct(st.ns, 99), near_mean[c] / near_mean[baselineOf(c)]);
    std::fprintf(stderr,
                 "%s near %-28s fp %" PRIu64 " fn %" PRIu64 " hangs %" PRIu64
                 "\n",
                 name.c_str(), kCheckers[c].name, st.fp, st.fn, st.hangs);
  }
  md += "\n";
  return md;
}

}  // namespace

int main(int argc, char** argv) {
  Options opt;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto next = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "bench_planning: %s needs a value\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--meshes")
      opt.meshes = next();
    else if (a == "--scenes")
      opt.scenes = split(next());
    else if (a == "--seeds")
      opt.seeds = unsigned(std::stoul(next()));
    else if (a == "--near")
      opt.near = std::stoull(next());
    else if (a == "--iterations")
      opt.iterations = std::stoul(next());
    else if (a == "--timeout")
      opt.timeout = std::stod(next());
    else if (a == "--out")
      opt.out = next();
    else {
      std::fprintf(stderr,
                   "usage: bench_planning [--meshes DIR] [--scenes env,bunny] "
                   "[--seeds N] [--near N] [--iterations N] [--timeout S] "
                   "[--out FILE]\n");
      return 2;
    }
  }
  void* mem = mmap(nullptr, sizeof(Box), PROT_READ | PROT_WRITE,
                   MAP_SHARED | MAP_ANONYMOUS, -1, 0);
  if (mem == MAP_FAILED) {
    std::perror("mmap");
    return 2;
  }
  Box* box = new (mem) Box;
  std::string md =
      "# Planning benchmark: tricyl vs stock FCL in OMPL RRTConnect\n\n";
  {
    std::string cmd;
    for (int i = 0; i < argc; ++i) cmd += std::string(i ? " " : "") + argv[i];
    char limit[32];
    std::snprintf(limit, sizeof limit, "%g", opt.timeout);
    md += "`" + cmd + "`; per-check time limit " + limit +
          " s (checks killed past it count as hangs).\n\n";
  }
  bool any = false;
  for (const auto& name : opt.scenes) {
    const std::string section = runScene(name, opt, box);
    any = any || !section.empty();
    md += section;
  }
  if (!any) {
    std::fprintf(stderr, "bench_planning: no scene could be read: skipped\n");
    return 77;
  }
  std::fputs(md.c_str(), stdout);
  if (!opt.out.empty()) {
    std::FILE* f = std::fopen(opt.out.c_str(), "w");
    if (!f) {
      std::perror(opt.out.c_str());
      return 2;
    }
    std::fputs(md.c_str(), f);
    std::fclose(f);
  }
  return 0;
}
