// SPDX-License-Identifier: BSD-3-Clause
// The methods tricyl-compare runs, the oracle glue and the case text format.
#include <fcl/fcl.h>

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>

#include "harness.h"
#include "mesh_scenes.h"
#include "oracle.h"
#include "tricyl/mesh_cylinder.h"
#include "tricyl/triangle_cylinder.h"
#ifdef TRICYL_COMPARE_HAVE_SOLVER
#include "tricyl/fcl_solver.h"
#endif
#ifdef TRICYL_COMPARE_HAVE_QUERIES
#include "query_oracles.h"
#include "tricyl/line_cylinder.h"
#include "tricyl/point_cone.h"
#include "tricyl/point_cylinder.h"
#include "tricyl/segment_cylinder.h"
#include "tricyl/sphere_cylinder.h"
#endif

namespace tricyl::compare {

namespace {

constexpr const char* kMethodNames[kMethodCount] = {"tricyl",
                                                    "diagnostic_uncertified",
                                                    "tricyl_float",
                                                    "tricyl_fcl",
                                                    "tricyl_fcl_contact",
                                                    "fcl_libccd_1e-6",
                                                    "fcl_libccd_default",
                                                    "fcl_indep"};

using Bvh = fcl::BVHModel<fcl::OBBRSSd>;

std::shared_ptr<void> buildBvh(const std::vector<Triangle<double>>& tris) {
  auto m = std::make_shared<Bvh>();
  m->beginModel(int(tris.size()), int(3 * tris.size()));
  for (const auto& t : tris)
    m->addTriangle(fcl::Vector3d(t.a.x, t.a.y, t.a.z),
                   fcl::Vector3d(t.b.x, t.b.y, t.b.z),
                   fcl::Vector3d(t.c.x, t.c.y, t.c.z));
  m->endModel();
  return m;
}

/// The transform an FCL method is given: always a proper rotation.
fcl::Transform3d toFcl(const Pose<double>& pose) {
  const Pose<double> p = fclPose(pose);
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) tf.linear()(i, j) = p.R[i][j];
  tf.translation() = fcl::Vector3d(p.t.x, p.t.y, p.t.z);
  return tf;
}

fcl::Vector3d toFcl(const Vec3<double>& v) { return {v.x, v.y, v.z}; }

// Rounds through a volatile: GCC 12 at -O2/-O3 was seen to fold a
// double -> float -> double round trip into the identity for some vector
// lanes (see tests/triangle_cylinder_regressions_test.cpp,
// FloatRoundTripFoldedByOptimizer); the float method would then be judged
// on unrounded input. The volatile store forces the rounding.
float f(double v) {
  volatile float r = static_cast<float>(v);
  return r;
}
Vec3<float> toFloat(const Vec3<double>& v) { return {f(v.x), f(v.y), f(v.z)}; }
Vec3<double> widen(const Vec3<float>& v) { return {v.x, v.y, v.z}; }

Cylinder<float> toFloat(const Cylinder<double>& c) {
  return {f(c.radius), f(c.lz)};
}
Pose<float> toFloat(const Pose<double>& p) {
  Pose<float> q{};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) q.R[i][j] = f(p.R[i][j]);
  q.t = toFloat(p.t);
  return q;
}
Triangle<float> toFloat(const Triangle<double>& t) {
  return {toFloat(t.a), toFloat(t.b), toFloat(t.c)};
}

/// Exact oracle over a mesh: the cull is conservative, so only triangles it
/// cannot rule out reach the rational test. Stops at the first hit.
bool meshOracle(const scenes::TriCase& k,
                const std::vector<Triangle<double>>& tris) {
  const meshes::Cull cull(k);
  for (const auto& t : tris)
    if (cull.mayTouch(t) && oracle::triangleCylinder(k.cyl, k.pose, t))
      return true;
  return false;
}

scenes::TriCase scaled(const scenes::TriCase& k, double factor) {
  scenes::TriCase s = k;
  s.cyl.radius *= factor;
  s.cyl.lz *= factor;
  return s;
}

}  // namespace

bool isImproper(const Pose<double>& p) {
  const auto& R = p.R;
  // Every generator's R is a rotation or a reflection (|det| ~ 1), so the
  // sign of the rounded determinant is the true one.
  const double det = R[0][0] * (R[1][1] * R[2][2] - R[1][2] * R[2][1]) -
                     R[0][1] * (R[1][0] * R[2][2] - R[1][2] * R[2][0]) +
                     R[0][2] * (R[1][0] * R[2][1] - R[1][1] * R[2][0]);
  return det < 0;
}

Pose<double> fclPose(const Pose<double>& p) {
  if (!isImproper(p)) return p;
  Pose<double> q = p;
  // 0.0 - x: exact, and +0 (not -0) for a zero entry.
  for (int i = 0; i < 3; ++i) q.R[i][2] = 0.0 - p.R[i][2];
  return q;
}

std::vector<std::uint32_t> oracleTriangles(const Case& c) {
  std::vector<std::uint32_t> out;
  const meshes::Cull cull(c.k);
  for (std::size_t i = 0; i < c.mesh->tris.size(); ++i)
    if (cull.mayTouch(c.mesh->tris[i]) &&
        oracle::triangleCylinder(c.k.cyl, c.k.pose, c.mesh->tris[i]))
      out.push_back(std::uint32_t(i));
  return out;
}

const char* methodName(Method m) {
  const int i = int(m);
  return i >= 0 && i < kMethodCount ? kMethodNames[i] : "?";
}

std::optional<Method> parseMethod(std::string_view s) {
  for (int i = 0; i < kMethodCount; ++i)
    if (s == kMethodNames[i]) return Method(i);
  if (s == "tricyl_fast") return Method::kDiagnosticUncertified;  // old name
  return std::nullopt;
}

bool isFcl(Method m) {
  return m == Method::kFclLibccd1e6 || m == Method::kFclLibccdDefault ||
         m == Method::kFclIndep || m == Method::kTricylFcl ||
         m == Method::kTricylFclContact;
}

const char* queryName(Query q) {
  switch (q) {
    case Query::kTriangle:
      return "triangle";
    case Query::kPointCylinder:
      return "point_cylinder";
    case Query::kPointCone:
      return "point_cone";
    case Query::kSphere:
      return "sphere";
    case Query::kSegment:
      return "segment";
    case Query::kLine:
      return "line";
  }
  return "?";
}

bool haveQueries() {
#ifdef TRICYL_COMPARE_HAVE_QUERIES
  return true;
#else
  return false;
#endif
}

bool methodApplies(Query q, Method m) {
  if (q == Query::kTriangle) return true;
  if (m == Method::kTricyl || m == Method::kTricylFloat) return true;
  return q == Query::kSphere && m == Method::kFclLibccd1e6;
}

bool methodApplies(const CaseSet& set, Method m) {
  if (!set.mesh) return methodApplies(set.query, m);
  const bool solver = m == Method::kTricylFcl || m == Method::kTricylFclContact;
  if (set.mesh_path == MeshPath::kScan) return !solver;
  return solver || m == Method::kFclLibccd1e6 ||
         m == Method::kFclLibccdDefault || m == Method::kFclIndep;
}

bool methodAvailable(Method m) {
#ifdef TRICYL_COMPARE_HAVE_SOLVER
  (void)m;
  return true;
#else
  return m != Method::kTricylFcl && m != Method::kTricylFclContact;
#endif
}

void prepareMesh(Mesh& mesh) {
  mesh.tris_f.clear();
  const meshes::IndexedMesh im = meshes::indexed(mesh.tris);
  mesh.vertices = im.v;
  mesh.indices = im.f;
  mesh.vertices_f.clear();
  for (double v : im.v) mesh.vertices_f.push_back(f(v));
  const double inf = std::numeric_limits<double>::infinity();
  mesh.lo = {inf, inf, inf};
  mesh.hi = {-inf, -inf, -inf};
  for (const auto& t : mesh.tris) {
    for (const auto* v : {&t.a, &t.b, &t.c}) {
      mesh.lo = {std::fmin(mesh.lo.x, v->x), std::fmin(mesh.lo.y, v->y),
                 std::fmin(mesh.lo.z, v->z)};
      mesh.hi = {std::fmax(mesh.hi.x, v->x), std::fmax(mesh.hi.y, v->y),
                 std::fmax(mesh.hi.z, v->z)};
    }
    mesh.tris_f.push_back(
        {widen(toFloat(t.a)), widen(toFloat(t.b)), widen(toFloat(t.c))});
  }
  mesh.fcl_model = buildBvh(mesh.tris);
}

Case roundToFloat(const Case& c) {
  Case r = c;
  const Cylinder<float> cf = toFloat(c.k.cyl);
  r.k.cyl = {cf.radius, cf.lz};
  const Pose<float> pf = toFloat(c.k.pose);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r.k.pose.R[i][j] = pf.R[i][j];
  r.k.pose.t = widen(pf.t);
  const Triangle<float> tf = toFloat(c.k.tri);
  r.k.tri = {widen(tf.a), widen(tf.b), widen(tf.c)};
  r.p = widen(toFloat(c.p));
  r.q = widen(toFloat(c.q));
  r.rho = f(c.rho);
  return r;
}

namespace {
/// The exact verdict of a query case (c already float-rounded if needed).
bool queryTruth(const Case& c, const Cylinder<double>& cyl) {
#ifdef TRICYL_COMPARE_HAVE_QUERIES
  switch (c.query) {
    case Query::kPointCylinder:
      return oracle::pointInCylinder(cyl, c.k.pose, c.p);
    case Query::kPointCone:
      return oracle::pointInCone({cyl.radius, cyl.lz}, c.k.pose, c.p);
    case Query::kSphere:
      return oracle::sphereCylinder(cyl, c.k.pose, {c.p, c.rho});
    case Query::kSegment:
      return oracle::segmentCylinder(cyl, c.k.pose, {c.p, c.q});
    case Query::kLine:
      return oracle::lineCylinder(cyl, c.k.pose, {c.p, c.q});
    case Query::kTriangle:
      break;
  }
#else
  (void)c;
  (void)cyl;
#endif
  throw std::logic_error("tricyl-compare: query cases are not built in");
}
}  // namespace

bool oracleTruth(const Case& c, bool float_input) {
  if (c.query != Query::kTriangle) return queryTruth(c, c.k.cyl);
  if (c.mesh)
    return meshOracle(c.k, float_input ? c.mesh->tris_f : c.mesh->tris);
  return oracle::triangleCylinder(c.k.cyl, c.k.pose, c.k.tri);
}

namespace {
bool oracleTruthScaled(const Case& c, bool float_input, double factor) {
  const scenes::TriCase k = scaled(c.k, factor);
  if (c.query != Query::kTriangle) return queryTruth(c, k.cyl);
  if (c.mesh) return meshOracle(k, float_input ? c.mesh->tris_f : c.mesh->tris);
  return oracle::triangleCylinder(k.cyl, k.pose, k.tri);
}
}  // namespace

double errorSize(const Case& c, bool truth, bool float_input) {
  if (std::isfinite(c.k.delta)) return std::fabs(c.k.delta);
  // Intersecting: shrink by (1 - s); disjoint: grow by (1 + s). Find the
  // flip point on a log scale in [1e-18, cap].
  constexpr double kCap = 1e6;
  auto flips = [&](double s) {
    const double factor = truth ? std::fmax(0.0, 1 - s) : 1 + s;
    return oracleTruthScaled(c, float_input, factor) != truth;
  };
  double lo = 1e-18, hi = truth ? 1.0 : kCap;
  if (!flips(hi)) return hi;
  if (flips(lo)) return lo;
  while (hi / lo > 1.03) {
    const double mid = std::sqrt(lo * hi);
    (flips(mid) ? hi : lo) = mid;
  }
  return hi;
}

struct Evaluator::Impl {
  fcl::detail::GJKSolver_libccd<double> ccd_1e6;
  fcl::detail::GJKSolver_libccd<double> ccd_default;
  fcl::detail::GJKSolver_indep<double> indep;
#ifdef TRICYL_COMPARE_HAVE_SOLVER
  tricyl::Solver<double> solver;  // collision_tolerance as fcl::collide sets
  Impl() {
    ccd_1e6.collision_tolerance = 1e-6;
    solver.collision_tolerance = 1e-6;
  }
#else
  Impl() { ccd_1e6.collision_tolerance = 1e-6; }
#endif

  bool triangle(Method m, const scenes::TriCase& k) {
    switch (m) {
      case Method::kTricyl:
        return tryIntersect(k.cyl, k.pose, k.tri) == Answer::kIntersect;
      case Method::kDiagnosticUncertified:
        return diagnostic::intersectUncertified(k.cyl, k.pose, k.tri);
      case Method::kTricylFloat:
        return tryIntersect(toFloat(k.cyl), toFloat(k.pose), toFloat(k.tri)) ==
               Answer::kIntersect;
      default:
        break;
    }
    return fclTriangle(m, fcl::Cylinderd(k.cyl.radius, k.cyl.lz), toFcl(k.pose),
                       k.tri);
  }

  // The harness's conservative cull, then fn per triangle: the brute-force
  // loop of the methods that have no batch scan of their own.
  template <class Fn>
  static bool scan(const scenes::TriCase& k,
                   const std::vector<Triangle<double>>& tris, Fn&& fn) {
    const meshes::Cull cull(k);
    for (const auto& t : tris)
      if (cull.mayTouch(t) && fn(t)) return true;
    return false;
  }

  /// One triangle through the FCL solver of method m (tf already proper).
  bool fclTriangle(Method m, const fcl::Cylinderd& cyl,
                   const fcl::Transform3d& tf, const Triangle<double>& t) {
    const fcl::Vector3d a = toFcl(t.a), b = toFcl(t.b), c = toFcl(t.c);
    switch (m) {
      case Method::kFclLibccd1e6:
        return ccd_1e6.shapeTriangleIntersect(cyl, tf, a, b, c, nullptr,
                                              nullptr, nullptr);
      case Method::kFclLibccdDefault:
        return ccd_default.shapeTriangleIntersect(cyl, tf, a, b, c, nullptr,
                                                  nullptr, nullptr);
      case Method::kFclIndep:
        return indep.shapeTriangleIntersect(cyl, tf, a, b, c, nullptr, nullptr,
                                            nullptr);
#ifdef TRICYL_COMPARE_HAVE_SOLVER
      case Method::kTricylFcl:
        return solver.shapeTriangleIntersect(cyl, tf, a, b, c, nullptr, nullptr,
                                             nullptr);
      case Method::kTricylFclContact: {
        fcl::Vector3d point, normal;
        double depth = 0;
        return solver.shapeTriangleIntersect(cyl, tf, a, b, c, &point, &depth,
                                             &normal);
      }
#endif
      default:
        return false;
    }
  }

  // mesh_scan: every triangle, no BVH, first hit ends the scan.
  bool meshScan(Method m, const Case& c) {
    const scenes::TriCase& k = c.k;
    const Mesh& mesh = *c.mesh;
    switch (m) {
      case Method::kTricyl: {
        const MeshView<double> view{mesh.vertices.data(),
                                    mesh.vertices.size() / 3,
                                    mesh.indices.data(), mesh.tris.size()};
        std::size_t first = 0;
        return tryIntersectAny(k.cyl, k.pose, view, &first) ==
               Answer::kIntersect;
      }
      case Method::kTricylFloat: {
        const MeshView<float> view{mesh.vertices_f.data(),
                                   mesh.vertices_f.size() / 3,
                                   mesh.indices.data(), mesh.tris.size()};
        std::size_t first = 0;
        return tryIntersectAny(toFloat(k.cyl), toFloat(k.pose), view, &first) ==
               Answer::kIntersect;
      }
      case Method::kDiagnosticUncertified:
        return scan(k, mesh.tris, [&](const Triangle<double>& t) {
          return diagnostic::intersectUncertified(k.cyl, k.pose, t);
        });
      default:
        break;
    }
    const fcl::Cylinderd cyl(k.cyl.radius, k.cyl.lz);
    const fcl::Transform3d tf = toFcl(k.pose);
    return scan(k, mesh.tris, [&](const Triangle<double>& t) {
      return fclTriangle(m, cyl, tf, t);
    });
  }

  // mesh_bvh: fcl::collide (or tricyl::collide) with a one-cylinder object
  // against the OBBRSS model, the way a planner calls it, exhaustive; the
  // request picks the solver and tolerance.
  bool meshBvh(Method m, const Case& c, std::vector<std::uint32_t>* tris) {
    const scenes::TriCase& k = c.k;
    fcl::CollisionRequestd request;
    request.num_max_contacts = 1u << 30;
    if (m == Method::kFclLibccdDefault)
      request.gjk_tolerance = fcl::constants<double>::gjk_default_tolerance();
    if (m == Method::kFclIndep) request.gjk_solver_type = fcl::GST_INDEP;
    fcl::CollisionResultd result;
    const fcl::Cylinderd cyl(k.cyl.radius, k.cyl.lz);
    const auto* model = static_cast<const Bvh*>(c.mesh->fcl_model.get());
#ifdef TRICYL_COMPARE_HAVE_SOLVER
    if (m == Method::kTricylFcl || m == Method::kTricylFclContact) {
      request.enable_contact = m == Method::kTricylFclContact;
      tricyl::collide(static_cast<const fcl::CollisionGeometryd*>(&cyl),
                      toFcl(k.pose), model, fcl::Transform3d::Identity(),
                      request, result);
    } else
#endif
    {
      fcl::collide(&cyl, toFcl(k.pose), model, fcl::Transform3d::Identity(),
                   request, result);
    }
    if (tris) {
      tris->clear();
      for (std::size_t i = 0; i < result.numContacts(); ++i) {
        const fcl::Contactd& ct = result.getContact(i);
        tris->push_back(std::uint32_t(ct.o1 == model ? ct.b1 : ct.b2));
      }
    }
    return result.isCollision();
  }
};

Evaluator::Evaluator() : impl_(std::make_unique<Impl>()) {}
Evaluator::~Evaluator() = default;

bool Evaluator::run(Method m, const Case& c, std::vector<std::uint32_t>* tris) {
#ifdef TRICYL_COMPARE_HAVE_QUERIES
  if (c.query != Query::kTriangle) {
    const scenes::TriCase& k = c.k;
    if (m == Method::kFclLibccd1e6) {  // Sphere-Cylinder only
      const fcl::Sphered sph(c.rho);
      fcl::Transform3d tfs = fcl::Transform3d::Identity();
      tfs.translation() = toFcl(c.p);
      return impl_->ccd_1e6.shapeIntersect(
          sph, tfs, fcl::Cylinderd(k.cyl.radius, k.cyl.lz), toFcl(k.pose),
          static_cast<std::vector<fcl::ContactPointd>*>(nullptr));
    }
    const bool fl = m == Method::kTricylFloat;
    const Pose<float> pf = fl ? toFloat(k.pose) : Pose<float>{};
    const Cylinder<float> cf = fl ? toFloat(k.cyl) : Cylinder<float>{};
    switch (c.query) {
      case Query::kPointCylinder:
        return (fl ? tryContains(cf, pf, toFloat(c.p))
                   : tryContains(k.cyl, k.pose, c.p)) == Answer::kIntersect;
      case Query::kPointCone:
        return (fl ? tryContains(Cone<float>{cf.radius, cf.lz}, pf,
                                 toFloat(c.p))
                   : tryContains(Cone<double>{k.cyl.radius, k.cyl.lz}, k.pose,
                                 c.p)) == Answer::kIntersect;
      case Query::kSphere:
        return (fl ? tryIntersect(cf, pf, Sphere<float>{toFloat(c.p), f(c.rho)})
                   : tryIntersect(k.cyl, k.pose, Sphere<double>{c.p, c.rho})) ==
               Answer::kIntersect;
      case Query::kSegment:
        return (fl ? tryIntersect(cf, pf,
                                  Segment<float>{toFloat(c.p), toFloat(c.q)})
                   : tryIntersect(k.cyl, k.pose, Segment<double>{c.p, c.q})) ==
               Answer::kIntersect;
      case Query::kLine:
        return (fl ? tryIntersect(cf, pf,
                                  Line<float>{toFloat(c.p), toFloat(c.q)})
                   : tryIntersect(k.cyl, k.pose, Line<double>{c.p, c.q})) ==
               Answer::kIntersect;
      case Query::kTriangle:
        break;
    }
    return false;
  }
#endif
  if (c.mesh)
    return c.mesh_path == MeshPath::kBvh ? impl_->meshBvh(m, c, tris)
                                         : impl_->meshScan(m, c);
  return impl_->triangle(m, c.k);
}

bool tricylDecide(const Case& c, int* stage) {
  *stage = -1;
  if (c.mesh) {  // the batch scan, whatever path the case's set measures
    Case scan = c;
    scan.mesh_path = MeshPath::kScan;
    Evaluator ev;
    return ev.run(Method::kTricyl, scan);
  }
  Decision d{Answer::kInvalidInput, Stage::kInvalid};
  switch (c.query) {
    case Query::kTriangle:
      d = decideIntersect(c.k.cyl, c.k.pose, c.k.tri);
      break;
#ifdef TRICYL_COMPARE_HAVE_QUERIES
    case Query::kPointCylinder:
      d = decideContains(c.k.cyl, c.k.pose, c.p);
      break;
    case Query::kPointCone:
      d = decideContains(Cone<double>{c.k.cyl.radius, c.k.cyl.lz}, c.k.pose,
                         c.p);
      break;
    case Query::kSphere:
      d = decideIntersect(c.k.cyl, c.k.pose, Sphere<double>{c.p, c.rho});
      break;
    case Query::kSegment:
      d = decideIntersect(c.k.cyl, c.k.pose, Segment<double>{c.p, c.q});
      break;
    case Query::kLine:
      d = decideIntersect(c.k.cyl, c.k.pose, Line<double>{c.p, c.q});
      break;
#endif
    default:
      throw std::logic_error("tricyl-compare: query cases are not built in");
  }
  *stage = int(d.stage);
  return d.answer == Answer::kIntersect;
}

std::string formatCaseHex(const scenes::TriCase& k) {
  std::string s;
  char buf[40];
  auto put = [&](double v) {
    std::snprintf(buf, sizeof buf, "%a", v);
    if (!s.empty()) s += ' ';
    s += buf;
  };
  put(k.cyl.radius);
  put(k.cyl.lz);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) put(k.pose.R[i][j]);
  for (const auto* v : {&k.pose.t, &k.tri.a, &k.tri.b, &k.tri.c}) {
    put(v->x);
    put(v->y);
    put(v->z);
  }
  return s;
}

std::optional<scenes::TriCase> parseCaseHex(std::string_view line) {
  std::string s(line);
  double v[23];
  const char* p = s.c_str();
  for (double& x : v) {
    char* end = nullptr;
    x = std::strtod(p, &end);
    if (end == p) return std::nullopt;
    p = end;
  }
  scenes::TriCase k;
  k.cyl = {v[0], v[1]};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) k.pose.R[i][j] = v[2 + 3 * i + j];
  k.pose.t = {v[11], v[12], v[13]};
  k.tri = {{v[14], v[15], v[16]}, {v[17], v[18], v[19]}, {v[20], v[21], v[22]}};
  k.feature = "replay";
  return k;
}

std::vector<scenes::TriCase> readCaseFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open case file " + path);
  std::vector<scenes::TriCase> out;
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    if (line.rfind("case ", 0) != 0) continue;
    auto k = parseCaseHex(std::string_view(line).substr(5));
    if (!k)
      throw std::runtime_error(path + ":" + std::to_string(lineno) +
                               ": expected 23 numbers after 'case'");
    out.push_back(*k);
  }
  return out;
}

}  // namespace tricyl::compare
