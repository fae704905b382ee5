// SPDX-License-Identifier: BSD-3-Clause
// The batch query (mesh_cylinder.h, issue 6). Its contract is that every
// per-triangle answer equals tricyl::tryIntersect's, whatever the options,
// so the tests compare against the scalar kernel triangle by triangle (the
// kernel itself is checked against the exact oracle in the triangle tests),
// on built-in and real meshes, with placements that graze faces, edges and
// vertices (compare/mesh_scenes.h), and on poses chosen to stress the two
// rejection tests: near-orthonormal and far-from-orthonormal R, huge
// translations outside the filter's range gate, and touching triangles on
// the faces of the world box.
#include "tricyl/mesh_cylinder.h"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "mesh_scenes.h"
#include "test_support.h"
#include "tricyl/triangle_cylinder.h"

namespace tricyl {
namespace {

namespace meshes = compare::meshes;
using V = Vec3<double>;

/// An indexed mesh in scalar type S: the soup's vertices merged in double
/// (meshes::indexed, as a mesh file has them) and then narrowed.
template <class S>
struct Indexed {
  std::vector<S> v;
  std::vector<std::uint32_t> f;
  MeshView<S> view() const {
    return {v.data(), v.size() / 3, f.data(), f.size() / 3};
  }
  Triangle<S> tri(std::size_t i) const {
    auto at = [&](std::uint32_t k) {
      return Vec3<S>{v[3 * k], v[3 * k + 1], v[3 * k + 2]};
    };
    return {at(f[3 * i]), at(f[3 * i + 1]), at(f[3 * i + 2])};
  }
};

template <class S>
Indexed<S> indexed(const std::vector<Triangle<double>>& soup) {
  const meshes::IndexedMesh m = meshes::indexed(soup);
  return {std::vector<S>(m.v.begin(), m.v.end()), m.f};
}

/// The same triangles as a structure of arrays (owning storage).
template <class S>
struct Arrays {
  std::vector<S> c[9];
  TriangleArrays<S> view() const {
    return {c[0].data(), c[1].data(), c[2].data(), c[3].data(), c[4].data(),
            c[5].data(), c[6].data(), c[7].data(), c[8].data(), c[0].size()};
  }
};

template <class S>
Arrays<S> arrays(const Indexed<S>& m) {
  Arrays<S> a;
  for (std::size_t i = 0; i < m.f.size() / 3; ++i) {
    const Triangle<S> t = m.tri(i);
    const Vec3<S> p[3] = {t.a, t.b, t.c};
    for (int k = 0; k < 3; ++k) {
      a.c[3 * k].push_back(p[k].x);
      a.c[3 * k + 1].push_back(p[k].y);
      a.c[3 * k + 2].push_back(p[k].z);
    }
  }
  return a;
}

template <class S>
Pose<S> narrowPose(const Pose<double>& p) {
  Pose<S> q;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) q.R[i][j] = S(p.R[i][j]);
  q.t = {S(p.t.x), S(p.t.y), S(p.t.z)};
  return q;
}

bool bit(const std::vector<std::uint64_t>& mask, std::size_t i) {
  return (mask[i / 64] >> (i % 64)) & 1u;
}

const BatchOptions kAllOptions[] = {
    {true, Isa::kPortable},
    {true, Isa::kAvx2},
    {false, Isa::kPortable},
    {false, Isa::kAvx2},
};

std::string describe(const BatchOptions& o) {
  return std::string(o.cull ? "cull" : "no-cull") + "/" +
         (o.isa == Isa::kAvx2 ? "avx2" : "portable");
}

/// Totals over a test, to show that it exercised every path.
struct Coverage {
  std::size_t hits = 0, culled = 0, early = 0, kernel = 0, queries = 0;
};

/// Checks every entry point on one (cylinder, pose, mesh) against the
/// scalar kernel, for every option set.
template <class S>
void expectMatchesKernel(const Cylinder<S>& cyl, const Pose<S>& pose,
                         const Indexed<S>& mesh, const Arrays<S>& arr,
                         Coverage* cov) {
  const std::size_t n = mesh.f.size() / 3;
  std::vector<bool> ref(n);
  std::size_t ref_hits = 0, ref_first = n;
  for (std::size_t i = 0; i < n; ++i) {
    const Answer a = tryIntersect(cyl, pose, mesh.tri(i));
    ASSERT_NE(a, Answer::kInvalidInput);
    ref[i] = a == Answer::kIntersect;
    ref_hits += ref[i];
    if (ref[i] && ref_first == n) ref_first = i;
  }
  BatchStats by_option[std::size(kAllOptions)];
  for (std::size_t o = 0; o < std::size(kAllOptions); ++o) {
    const BatchOptions& opt = kAllOptions[o];
    SCOPED_TRACE(describe(opt));
    std::vector<std::uint64_t> mask((n + 63) / 64, ~std::uint64_t(0));
    BatchStats& st = by_option[o];
    const std::size_t hits =
        intersectMask(cyl, pose, mesh.view(), mask.data(), opt, &st);
    EXPECT_EQ(hits, ref_hits);
    std::size_t wrong = 0;
    for (std::size_t i = 0; i < n; ++i) wrong += bit(mask, i) != ref[i];
    EXPECT_EQ(wrong, 0u) << "triangles whose batch answer differs";
    for (std::size_t i = n; i < mask.size() * 64; ++i)
      ASSERT_FALSE(bit(mask, i)) << "bit past the end set: " << i;
    EXPECT_EQ(st.triangles, n);
    EXPECT_EQ(st.culled + st.early_out + st.kernel, n);
    EXPECT_EQ(st.hits, ref_hits);
    if (opt.isa == Isa::kAvx2) {
      EXPECT_EQ(st.isa, detectedIsa());
    }
    cov->hits += st.hits;
    cov->culled += st.culled;
    cov->early += st.early_out;
    cov->kernel += st.kernel;
    ++cov->queries;

    std::vector<std::uint64_t> mask2((n + 63) / 64);
    EXPECT_EQ(intersectMask(cyl, pose, arr.view(), mask2.data(), opt), hits);
    EXPECT_EQ(mask2, mask) << "structure-of-arrays input";

    std::vector<std::uint32_t> idx{7};  // appended to, never cleared
    EXPECT_EQ(intersectIndices(cyl, pose, mesh.view(), &idx, opt), hits);
    ASSERT_EQ(idx.size(), hits + 1);
    for (std::size_t k = 1; k < idx.size(); ++k) {
      EXPECT_TRUE(ref[idx[k]]);
      if (k > 1) {
        EXPECT_LT(idx[k - 1], idx[k]);
      }
    }

    const auto any = intersectAny(cyl, pose, mesh.view(), opt);
    const auto any2 = intersectAny(cyl, pose, arr.view(), opt);
    if (ref_first == n) {
      EXPECT_FALSE(any.has_value());
      EXPECT_FALSE(any2.has_value());
    } else {
      EXPECT_EQ(any, std::optional<std::size_t>(ref_first));
      EXPECT_EQ(any2, std::optional<std::size_t>(ref_first));
    }
  }
  // The AVX2 vertex passes compute the portable codes bit for bit, so the
  // same triangles are rejected, by the same test (kAllOptions: portable,
  // then AVX2, for each cull setting).
  for (std::size_t o = 0; o + 1 < std::size(kAllOptions); o += 2) {
    SCOPED_TRACE(describe(kAllOptions[o + 1]));
    EXPECT_EQ(by_option[o].culled, by_option[o + 1].culled);
    EXPECT_EQ(by_option[o].early_out, by_option[o + 1].early_out);
    EXPECT_EQ(by_option[o].kernel, by_option[o + 1].kernel);
  }
}

template <class S>
class MeshCylinderTyped : public ::testing::Test {};
using Scalars = ::testing::Types<float, double>;
TYPED_TEST_SUITE(MeshCylinderTyped, Scalars);

// Built-in meshes (sphere, torus, terrain), 60 placements each from the
// compare harness's mesh family: loose, and touching with a cap, the side
// or a rim, pushed in or out by relative offsets down to a few ulps.
TYPED_TEST(MeshCylinderTyped, BuiltinMeshesMatchKernel) {
  using S = TypeParam;
  const std::uint64_t seed = test::baseSeed() + 61;
  SCOPED_TRACE(test::seedTrace(seed));
  Coverage cov;
  for (const auto& [name, soup] : meshes::builtinMeshes()) {
    SCOPED_TRACE(name);
    const Indexed<S> mesh = indexed<S>(soup);
    const Arrays<S> arr = arrays(mesh);
    V lo, hi;
    meshes::bounds(soup, &lo, &hi);
    for (std::uint64_t k = 0; k < 60; ++k) {
      SCOPED_TRACE("placement " + std::to_string(k));
      const auto c = meshes::meshCase(soup, lo, hi, seed, k);
      expectMatchesKernel(Cylinder<S>{S(c.cyl.radius), S(c.cyl.lz)},
                          narrowPose<S>(c.pose), mesh, arr, &cov);
      if (::testing::Test::HasFailure()) return;
    }
  }
  // The test exercised hits and both rejection kinds and the kernel.
  EXPECT_GT(cov.hits, 0u);
  EXPECT_GT(cov.culled, 0u);
  EXPECT_GT(cov.early, 0u);
  EXPECT_GT(cov.kernel, 0u);
}

// Vertex coordinates at the edges of the local pass's gate and of double:
// exactly 2^40 (admitted) and the next double up (not: the kernel decides
// those triangles), -0, subnormals, and vertices far from everything, in
// every position of the AVX2 pass's four-vertex groups and of its scalar
// tail (9 vertices: two groups and one left over).
TEST(MeshCylinder, VertexPassGateValues) {
  const double big = 0x1p40, above = std::nextafter(0x1p40, 1e300);
  const double sub = std::numeric_limits<double>::denorm_min();
  const double vals[] = {0.0, -0.0, sub,  -sub,  0.25,   -0.75,
                         1.5, big,  -big, above, -above, 3e11};
  Coverage cov;
  for (std::uint64_t k = 0; k < 200; ++k) {
    Indexed<double> mesh;
    std::uint64_t h = k * 0x9e3779b97f4a7c15ULL + 1;
    auto next = [&] {
      h ^= h >> 31;
      h *= 0xbf58476d1ce4e5b9ULL;
      h ^= h >> 29;
      return vals[h % std::size(vals)];
    };
    for (int i = 0; i < 27; ++i) mesh.v.push_back(next());
    for (std::uint32_t a = 0; a < 9; ++a)
      for (std::uint32_t b : {(a + 1) % 9, (a + 4) % 9})
        mesh.f.insert(mesh.f.end(), {a, b, (a + 7) % 9});
    const Cylinder<double> cyl{0.5, 2};
    Pose<double> pose{{{0, 1, 0}, {0, 0, 1}, {1, 0, 0}}, {0.25, 0, -0.5}};
    SCOPED_TRACE("case " + std::to_string(k));
    expectMatchesKernel(cyl, pose, mesh, arrays(mesh), &cov);
    if (::testing::Test::HasFailure()) return;
  }
  EXPECT_GT(cov.hits, 0u);
  EXPECT_GT(cov.early, 0u);
  EXPECT_GT(cov.kernel, 0u);
}

// The real meshes of ../shared/data/meshes (env.obj: walls up to +-3000;
// bunny.obj), skipped with a message when absent.
TEST(MeshCylinder, RealMeshesMatchKernel) {
  const std::uint64_t seed = test::baseSeed() + 62;
  SCOPED_TRACE(test::seedTrace(seed));
  int found = 0;
  Coverage cov;
  for (const char* file : {"bunny.obj", "env.obj"}) {
    const std::string path = std::string(TRICYL_MESH_DIR) + "/" + file;
    std::vector<Triangle<double>> soup;
    try {
      soup = meshes::readObj(path);
    } catch (const std::exception&) {
      continue;
    }
    ++found;
    SCOPED_TRACE(file);
    const Indexed<double> mesh = indexed<double>(soup);
    const Arrays<double> arr = arrays(mesh);
    V lo, hi;
    meshes::bounds(soup, &lo, &hi);
    for (std::uint64_t k = 0; k < 12; ++k) {
      SCOPED_TRACE("placement " + std::to_string(k));
      const auto c = meshes::meshCase(soup, lo, hi, seed, k);
      expectMatchesKernel(c.cyl, c.pose, mesh, arr, &cov);
      if (HasFailure()) return;
    }
  }
  if (found == 0)
    GTEST_SKIP() << "no mesh files in " << TRICYL_MESH_DIR
                 << " (../shared/data/meshes)";
  EXPECT_GT(cov.hits, 0u);
}

/// A 16 x 16 grid of unit cells in the plane z = z0 (512 triangles).
std::vector<Triangle<double>> flatGrid(double z0, double cell) {
  return meshes::gridSurface(16, 16, [&](int i, int j) {
    return V{(i - 8) * cell, (j - 8) * cell, z0};
  });
}

Pose<double> rotationAbout(V axis, double angle, V t) {
  const double n =
      std::sqrt(axis.x * axis.x + axis.y * axis.y + axis.z * axis.z);
  const double x = axis.x / n, y = axis.y / n, z = axis.z / n;
  const double c = std::cos(angle), s = std::sin(angle), C = 1 - c;
  return Pose<double>{{{c + x * x * C, x * y * C - z * s, x * z * C + y * s},
                       {y * x * C + z * s, c + y * y * C, y * z * C - x * s},
                       {z * x * C - y * s, z * y * C + x * s, c + z * z * C}},
                      t};
}

// Stress the two rejection tests where they are tight or disabled.
TEST(MeshCylinder, AdversarialPosesMatchKernel) {
  Coverage cov;
  const Cylinder<double> cyl{0.75, 2.0};
  // Axis-aligned: the world box is the cylinder's own bounding box, and
  // grids lie exactly in the cap planes, exactly tangent at the box faces
  // and one ulp beyond them.
  for (double z0 :
       {1.0, std::nextafter(1.0, 2.0), -1.0, std::nextafter(-1.0, -2.0), 0.0}) {
    const Indexed<double> m = indexed<double>(flatGrid(z0, 0.25));
    expectMatchesKernel(cyl, identityPose<double>(), m, arrays(m), &cov);
  }
  // Vertical grid tangent to the side at x = r, and one ulp outside.
  for (double x0 : {0.75, std::nextafter(0.75, 1.0)}) {
    auto soup = meshes::gridSurface(16, 16, [&](int i, int j) {
      return V{x0, (i - 8) * 0.2, (j - 8) * 0.2};
    });
    const Indexed<double> m = indexed<double>(soup);
    expectMatchesKernel(cyl, identityPose<double>(), m, arrays(m), &cov);
  }
  const Indexed<double> grid = indexed<double>(flatGrid(0.3, 0.2));
  const Arrays<double> grid_arr = arrays(grid);
  // A tilted rotation, then the same scaled by 1 + 2^-30 and by 1.05
  // (sum |R^T R - I| = 3 (2 * 0.05 + 0.05^2) <= 1/2: the box is padded and
  // still used), by 1.2 and 2 (not orthonormal enough: cull skipped, local
  // pass instead), and a singular R (scale 0).
  const Pose<double> tilt = rotationAbout({1, 2, 3}, 0.7, {0.1, -0.2, 0.3});
  for (double scale : {1.0, 1 + 0x1p-30, 1.05, 1.2, 2.0, 0.0}) {
    SCOPED_TRACE("R scaled by " + std::to_string(scale));
    Pose<double> p = tilt;
    for (auto& row : p.R)
      for (double& e : row) e *= scale;
    expectMatchesKernel(cyl, p, grid, grid_arr, &cov);
    BatchStats st;
    std::vector<std::uint64_t> mask(8);
    intersectMask(cyl, p, grid.view(), mask.data(), {}, &st);
    EXPECT_EQ(st.cull_used, scale >= 1 && scale <= 1.05)
        << "the world box is certified for sum |R^T R - I| <= 1/2 only";
  }
  // Far from the origin: a translation beyond the filter's range gate
  // (2^40) leaves only the world box (and the exact kernel).
  for (double far : {1e9, 0x1p41, 1e15}) {
    SCOPED_TRACE("far " + std::to_string(far));
    std::vector<Triangle<double>> soup = flatGrid(0.3, 0.2);
    for (auto& t : soup)
      for (V* p : {&t.a, &t.b, &t.c}) p->x += far;
    const Indexed<double> m = indexed<double>(soup);
    const Pose<double> p = rotationAbout({0, 1, 1}, 0.3, {far, 0, 0});
    expectMatchesKernel(cyl, p, m, arrays(m), &cov);
  }
  // Huge and tiny cylinders.
  expectMatchesKernel(Cylinder<double>{1e-300, 1e-300}, tilt, grid, grid_arr,
                      &cov);
  expectMatchesKernel(Cylinder<double>{1e300, 4e-320}, tilt, grid, grid_arr,
                      &cov);
  EXPECT_GT(cov.hits, 0u);
  EXPECT_GT(cov.culled, 0u);
  EXPECT_GT(cov.early, 0u);
}

// Triangles lying, in the cylinder frame, exactly in a cap plane (inside
// the disk) or in a plane x = +-r / y = +-r tangent to the side, mapped to
// the world under random rotations: rounding scatters their true local
// coordinates a few ulps to either side of the plane, so a local outcode
// without its error margin would reject some that touch. (Checked: with
// the margins of localCode set to 0 this test fails.)
TEST(MeshCylinder, TrianglesOnTheBoundaryPlanesUnderRotation) {
  const std::uint64_t seed = test::baseSeed() + 63;
  SCOPED_TRACE(test::seedTrace(seed));
  scenes::Rng g(seed);
  Coverage cov;
  const Cylinder<double> cyl{0.625, 1.5};
  const double r = cyl.radius, h = cyl.lz / 2;
  for (int k = 0; k < 200; ++k) {
    const Pose<double> pose =
        rotationAbout({g.uniform(-1, 1), g.uniform(-1, 1), g.uniform(-1, 1)},
                      g.uniform(0, 6.3),
                      {g.uniform(-3, 3), g.uniform(-3, 3), g.uniform(-3, 3)});
    auto world = [&](V y) {
      return V{pose.R[0][0] * y.x + pose.R[0][1] * y.y + pose.R[0][2] * y.z +
                   pose.t.x,
               pose.R[1][0] * y.x + pose.R[1][1] * y.y + pose.R[1][2] * y.z +
                   pose.t.y,
               pose.R[2][0] * y.x + pose.R[2][1] * y.y + pose.R[2][2] * y.z +
                   pose.t.z};
    };
    std::vector<Triangle<double>> soup;
    for (int j = 0; j < 32; ++j) {
      // Small triangles: a corner (u, v) and two offsets of 1e-3.
      const double u = g.uniform(-0.4, 0.4), v = g.uniform(-0.4, 0.4);
      const double w = g.uniform(-0.7, 0.7);
      for (double side : {1.0, -1.0}) {
        auto cap = [&](double a, double b) { return V{a, b, side * h}; };
        soup.push_back({world(cap(u, v)), world(cap(u + 1e-3, v)),
                        world(cap(u, v + 1e-3))});
        auto sx = [&](double a, double b) { return V{side * r, a, b}; };
        soup.push_back(
            {world(sx(u, w)), world(sx(u + 1e-3, w)), world(sx(u, w + 1e-3))});
        auto sy = [&](double a, double b) { return V{a, side * r, b}; };
        soup.push_back(
            {world(sy(u, w)), world(sy(u + 1e-3, w)), world(sy(u, w + 1e-3))});
      }
    }
    const Indexed<double> m = indexed<double>(soup);
    expectMatchesKernel(cyl, pose, m, arrays(m), &cov);
    if (HasFailure()) return;
  }
  EXPECT_GT(cov.hits, 0u);
  EXPECT_GT(cov.kernel, 0u);
}

// Hostile input: a clear error from the checked forms, the documented safe
// answer from the non-throwing ones, no out-of-bounds read, and no FP
// exception (FE_INVALID and FE_DIVBYZERO trap in every test).
TEST(MeshCylinder, InvalidInput) {
  const Cylinder<double> cyl{0.5, 1.0};
  const Pose<double> pose = rotationAbout({1, 1, 0}, 0.4, {0, 0, 0.2});
  Indexed<double> m = indexed<double>(flatGrid(0.0, 0.1));
  const std::size_t n = m.f.size() / 3;
  std::vector<bool> ref(n);
  for (std::size_t i = 0; i < n; ++i)
    ref[i] = tryIntersect(cyl, pose, m.tri(i)) == Answer::kIntersect;
  for (const BatchOptions& opt : kAllOptions) {
    SCOPED_TRACE(describe(opt));
    for (double bad : {std::numeric_limits<double>::quiet_NaN(),
                       std::numeric_limits<double>::signaling_NaN(),
                       std::numeric_limits<double>::infinity(),
                       -std::numeric_limits<double>::infinity()}) {
      // One vertex far from the cylinder gets the bad coordinate: all its
      // triangles must be reported invalid (hit), not culled.
      Indexed<double> mb = m;
      const std::uint32_t victim = 0;  // a grid corner, far from the axis
      mb.v[3 * victim] = bad;
      std::vector<std::uint64_t> mask((n + 63) / 64);
      std::size_t hits = 0;
      EXPECT_EQ(tryIntersectMask(cyl, pose, mb.view(), mask.data(), &hits, opt),
                Answer::kInvalidInput);
      std::size_t count = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const bool uses = mb.f[3 * i] == victim || mb.f[3 * i + 1] == victim ||
                          mb.f[3 * i + 2] == victim;
        EXPECT_EQ(bit(mask, i), uses || ref[i]) << "triangle " << i;
        count += bit(mask, i);
      }
      EXPECT_EQ(hits, count);
      EXPECT_THROW(intersectMask(cyl, pose, mb.view(), mask.data(), opt),
                   InvalidInput);
      EXPECT_THROW(intersectAny(cyl, pose, mb.view(), opt), InvalidInput);
      std::vector<std::uint32_t> idx;
      EXPECT_THROW(intersectIndices(cyl, pose, mb.view(), &idx, opt),
                   InvalidInput);
      EXPECT_TRUE(idx.empty()) << "nothing appended on error";
      std::size_t first = 99;
      EXPECT_EQ(tryIntersectAny(cyl, pose, mb.view(), &first, opt),
                Answer::kInvalidInput);
      EXPECT_EQ(first, 0u);  // triangle 0 uses vertex 0
    }
    // A vertex index out of range: reported, never read.
    Indexed<double> mi = m;
    mi.f[3 * 5 + 1] = std::uint32_t(mi.v.size() / 3);
    std::vector<std::uint64_t> mask((n + 63) / 64);
    EXPECT_EQ(tryIntersectMask(cyl, pose, mi.view(), mask.data(), nullptr, opt),
              Answer::kInvalidInput);
    EXPECT_TRUE(bit(mask, 5));
    EXPECT_THROW(intersectMask(cyl, pose, mi.view(), mask.data(), opt),
                 InvalidInput);
    // Invalid cylinder or pose: everything "in collision".
    const double nan = std::numeric_limits<double>::quiet_NaN();
    Pose<double> bad_pose = pose;
    bad_pose.R[1][2] = nan;
    for (const auto& [c, p] : {std::pair{Cylinder<double>{-0.5, 1.0}, pose},
                               std::pair{Cylinder<double>{0.5, nan}, pose},
                               std::pair{cyl, bad_pose}}) {
      std::size_t hits = 0;
      EXPECT_EQ(tryIntersectMask(c, p, m.view(), mask.data(), &hits, opt),
                Answer::kInvalidInput);
      EXPECT_EQ(hits, n);
      for (std::size_t i = 0; i < n; ++i) ASSERT_TRUE(bit(mask, i));
      EXPECT_THROW(intersectAny(c, p, m.view(), opt), InvalidInput);
    }
    // -0 is a valid size (as in the kernel).
    EXPECT_NO_THROW(intersectMask(Cylinder<double>{-0.0, -0.0}, pose, m.view(),
                                  mask.data(), opt));
  }
}

TEST(MeshCylinder, EmptyInputs) {
  const Cylinder<double> cyl{0.5, 1.0};
  const MeshView<double> empty{nullptr, 0, nullptr, 0};
  std::uint64_t word = 0;
  EXPECT_EQ(intersectMask(cyl, identityPose<double>(), empty, &word), 0u);
  EXPECT_FALSE(intersectAny(cyl, identityPose<double>(), empty).has_value());
  const TriangleArrays<double> none{nullptr, nullptr, nullptr, nullptr, nullptr,
                                    nullptr, nullptr, nullptr, nullptr, 0};
  EXPECT_FALSE(intersectAny(cyl, identityPose<double>(), none).has_value());
}

}  // namespace
}  // namespace tricyl
