// SPDX-License-Identifier: BSD-3-Clause
// tricyl-compare: the pieces shared by the executable and its tests.
//
// A run is a list of CaseSets (a scene family, a mesh family, or one point
// of a stability sweep). Every case of every set is settled by the exact
// oracle (compare/oracle.h) and then answered by every selected Method; the
// answers, timings and oracle verdicts are aggregated into per (set, method)
// statistics. The evaluation happens in forked worker processes so that a
// method that never returns (libccd's MPR has no iteration cap) can be
// killed after a per-query time limit; see runner.cpp.
//
// Fairness: FCL's solvers convert the rotation into a quaternion, so they
// answer for a different solid when det R = -1. Every method that runs
// inside FCL gets fclPose(k.pose), a proper rotation of the same solid
// (see fclPose); tricyl's own rows get the pose as generated, which its
// contract allows.
#pragma once

#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scenes.h"
#include "tricyl/types.h"

namespace tricyl::compare {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

enum class Method : int {
  kTricyl = 0,  ///< tricyl::tryIntersect: exact (filter + fallback); on
                ///< mesh_scan, the batch scan tricyl::tryIntersectAny
  kDiagnosticUncertified,  ///< diagnostic::intersectUncertified: the same
                           ///< algorithm without certificate (not a product
                           ///< mode: it shows what the certificate buys)
  kTricylFloat,            ///< the case rounded to float, then tricyl (exact)
  kTricylFcl,              ///< tricyl::Solver<double> inside FCL (Boolean only)
  kTricylFclContact,       ///< tricyl::Solver<double>, contact data requested
  kFclLibccd1e6,           ///< GJKSolver_libccd, collision_tolerance = 1e-6
  kFclLibccdDefault,       ///< GJKSolver_libccd, its own default (~2e-14)
  kFclIndep,               ///< GJKSolver_indep with its defaults
  kCount
};
inline constexpr int kMethodCount = int(Method::kCount);

const char* methodName(Method m);
std::optional<Method> parseMethod(std::string_view s);
/// True for the methods that run FCL code (and so may never return): they
/// run under the per-query time limit. Includes tricyl::Solver's methods,
/// which run inside FCL's narrow phase.
bool isFcl(Method m);
/// False for tricyl::Solver's methods when tricyl::fcl was not built.
bool methodAvailable(Method m);
/// True if the method answers the float-rounded input (its truth differs).
inline bool usesFloatInput(Method m) { return m == Method::kTricylFloat; }

/// The pose an FCL method is given: `p` itself when det R >= 0, otherwise R
/// with its third column negated. The cylinder {|z| <= lz/2, x^2 + y^2 <=
/// r^2} is symmetric under z -> -z, so R diag(1, 1, -1) maps it onto the
/// same world solid, and the negation is exact: the oracle's verdict is
/// unchanged, and FCL gets a proper rotation (det +1) when R is a rotation
/// or a reflection (every generator's R).
Pose<double> fclPose(const Pose<double>& p);
/// True if fclPose(p) differs from p (det R < 0).
bool isImproper(const Pose<double>& p);

/// A triangle mesh, world coordinates, plus what the methods need.
struct Mesh {
  std::string name;
  std::vector<Triangle<double>> tris;
  std::vector<Triangle<double>> tris_f;  ///< tris rounded to float, as double
  Vec3<double> lo{}, hi{};               ///< bounding box of the vertices
  /// The indexed form tricyl's batch scan takes (equal vertices merged),
  /// in double and rounded to float; triangle i is tris[i].
  std::vector<double> vertices;
  std::vector<float> vertices_f;
  std::vector<std::uint32_t> indices;
  std::shared_ptr<void> fcl_model;  ///< built by prepareMesh (FCL BVH)
};

/// How a mesh case is answered (like with like, one family each):
///   kScan  every triangle of the mesh, no BVH: tricyl's batch scan
///          (tryIntersectAny) beside a brute-force loop of each FCL solver's
///          shapeTriangleIntersect (behind the harness's conservative
///          bounding-sphere cull, which only helps FCL); first hit ends it.
///   kBvh   the OBBRSS BVHModel through the entry points a planner calls:
///          tricyl::collide beside fcl::collide, exhaustive
///          (num_max_contacts large), so that every colliding triangle they
///          report is checked against the oracle's set.
enum class MeshPath : int { kScan = 0, kBvh = 1 };
/// "mesh_scan" / "mesh_bvh": the family names of the two paths.
inline const char* meshFamilyName(MeshPath p) {
  return p == MeshPath::kBvh ? "mesh_bvh" : "mesh_scan";
}

/// Builds the bounding box, the float copy and the FCL models.
void prepareMesh(Mesh& mesh);

/// What a case asks: triangle vs cylinder (the default), or one of the
/// cylinder queries.
enum class Query : int {
  kTriangle = -1,
  kPointCylinder = 0,  ///< point in cylinder: p
  kPointCone = 1,      ///< point in cone Cone{k.cyl.radius, k.cyl.lz}: p
  kSphere = 2,         ///< sphere {p, rho} vs cylinder
  kSegment = 3,        ///< segment [p, q] vs cylinder
  kLine = 4,           ///< the line through p and q vs cylinder
};
const char* queryName(Query q);
/// True if the cylinder queries were built in (tricyl's point, cone, sphere,
/// segment and line tests plus compare/query_scenes.h, query_oracles.h).
bool haveQueries();
/// Whether method `m` has an implementation for query `q` (triangles: every
/// method; point/cone/segment/line: tricyl, tricyl_float; sphere: also
/// fcl_libccd_1e-6, i.e. FCL's detail::sphereCylinderIntersect, to which
/// every FCL solver dispatches Sphere-Cylinder).
bool methodApplies(Query q, Method m);

/// One configuration. For mesh cases k.tri is unused and `mesh` is set. For
/// query cases k.cyl, k.pose and k.feature are used with p, q, rho.
struct Case {
  scenes::TriCase k;
  const Mesh* mesh = nullptr;
  MeshPath mesh_path = MeshPath::kScan;  ///< mesh cases only
  Query query = Query::kTriangle;
  Vec3<double> p{}, q{};
  double rho = 0;
};

struct CaseSet {
  std::string kind;     ///< "family", "sweep" or "case" (known cases)
  std::string name;     ///< family name, or the swept quantity
  double param = kNaN;  ///< sweep abscissa (|delta|, |t|, lz / 2r)
  std::uint64_t count = 0;
  std::function<Case(std::uint64_t)> make;
  Query query = Query::kTriangle;        ///< what every case of the set asks
  bool mesh = false;                     ///< a mesh family (cases carry a mesh)
  MeshPath mesh_path = MeshPath::kScan;  ///< for mesh families
};

/// Whether method `m` runs on the cases of `set`: methodApplies for the
/// query; on mesh_scan every method but tricyl::Solver's (a scan has no
/// BVH for tricyl::collide); on mesh_bvh the methods with a BVH traversal
/// (tricyl_fcl, tricyl_fcl_contact and the fcl_* methods).
bool methodApplies(const CaseSet& set, Method m);

/// Triangle-level result of an exhaustive mesh query (mesh_bvh): how many
/// triangles the oracle says collide, how many of them the method did not
/// report, and how many it reported that do not collide.
struct TriangleCounts {
  std::uint32_t oracle = 0, missed = 0, extra = 0;
};
/// The oracle's set of colliding triangles of a mesh case (indices into
/// c.mesh->tris).
std::vector<std::uint32_t> oracleTriangles(const Case& c);

/// The case with every input rounded to float (and widened back: exact).
Case roundToFloat(const Case& c);

/// Exact oracle verdict for a triangle or mesh case. With `float_input`, `c`
/// must be roundToFloat of a case, and a mesh is taken as its float copy.
bool oracleTruth(const Case& c, bool float_input = false);

/// The size of the error a wrong answer makes: |delta| for near cases (the
/// generator's intended relative offset), otherwise the smallest relative
/// scaling s of the cylinder about its centre (radius and length times 1+s
/// for a disjoint case, 1-s for an intersecting one) at which the exact
/// answer flips, found by bisection in log scale to about 3 %. It is a
/// relative clearance (disjoint) or penetration (intersecting); capped at 1e6.
double errorSize(const Case& c, bool truth, bool float_input = false);

/// tricyl's exact answer to `c` and the stage that decided it
/// (int(tricyl::Stage); -1 for mesh cases, which are many kernel calls).
bool tricylDecide(const Case& c, int* stage);

/// Answers case `c` with method `m` once. Not thread-safe across Evaluators;
/// each worker has its own.
class Evaluator {
 public:
  Evaluator();
  ~Evaluator();
  Evaluator(const Evaluator&) = delete;
  Evaluator& operator=(const Evaluator&) = delete;
  /// The answer. Method::kTricylFloat rounds `c` to float itself. For a
  /// mesh_bvh case, `tris` (if given) receives the indices of the triangles
  /// the method reported (exhaustive request), unsorted.
  bool run(Method m, const Case& c, std::vector<std::uint32_t>* tris = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// Bit-exact text form of a triangle case (hex floats, "%a"):
///   r lz R00 R01 R02 R10 .. R22 tx ty tz ax ay az bx by bz cx cy cz
std::string formatCaseHex(const scenes::TriCase& k);
/// Parses formatCaseHex's output (decimal floats are accepted too).
std::optional<scenes::TriCase> parseCaseHex(std::string_view line);
/// Reads a hangs.txt / replay file: lines starting with "case " hold a case
/// after the keyword; '#' lines and blank lines are ignored.
std::vector<scenes::TriCase> readCaseFile(const std::string& path);

}  // namespace tricyl::compare
