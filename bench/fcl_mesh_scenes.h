// SPDX-License-Identifier: BSD-3-Clause
// The cylinder poses of the FCL mesh benchmarks, shared by bench_fcl_collide
// (grazing scenes), bench_fcl_distance (clearance scenes) and
// tricyl-fcl-walk-counts (the same scenes, one call per pose, for callgrind).
#pragma once

#include <fcl/geometry/shape/cylinder.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <memory>
#include <random>
#include <vector>

#include "fcl_obj_model.h"

namespace tricyl::bench {

/// Cylinders and their poses.
struct CylinderPoses {
  std::vector<std::shared_ptr<fcl::Cylinderd>> cyls;
  std::vector<fcl::Transform3d> poses;
};

/// Grazing offsets, relative to the mesh's bounding-box diagonal: a planner
/// grazing an obstacle (exact contact, and just in or out of it).
constexpr double kGraze[] = {0,    1e-3,  -1e-3, 1e-6, -1e-6,
                             5e-7, -5e-7, 1e-9,  -1e-9};

/// A proper rotation whose third column (the cylinder's axis) is `z`.
inline fcl::Transform3d frameWithAxis(const fcl::Vector3d& z,
                                      const fcl::Vector3d& c) {
  using V3 = fcl::Vector3d;
  const V3 zn = z.normalized();
  V3 x = std::abs(zn.x()) < 0.9 ? V3(1, 0, 0) : V3(0, 1, 0);
  x = (x - x.dot(zn) * zn).normalized();
  const V3 y = zn.cross(x);
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  tf.linear().col(0) = x;
  tf.linear().col(1) = y;
  tf.linear().col(2) = zn;
  tf.translation() = c;
  return tf;
}

/// The random draws of the scenes below, in the order they make them.
class PoseSampler {
 public:
  PoseSampler(const FclObjModel& m, std::uint64_t seed)
      : v(m.v), t(m.t), diag(m.diag), rng_(seed) {}
  double uniform() { return u_(rng_); }
  /// A triangle drawn uniformly.
  const fcl::Triangle& triangle() {
    return t[std::size_t(uniform() * double(t.size())) % t.size()];
  }
  /// A uniformly random rotation (a normalised Gaussian quaternion).
  fcl::Matrix3d rotation() {
    Eigen::Quaterniond q(g_(rng_), g_(rng_), g_(rng_), g_(rng_));
    return q.normalized().toRotationMatrix();
  }

  const std::vector<fcl::Vector3d>& v;
  const std::vector<fcl::Triangle>& t;
  const double diag;

 private:
  std::mt19937_64 rng_;
  std::uniform_real_distribution<double> u_{0, 1};
  std::normal_distribution<double> g_;
};

/// `n` poses near the surface of `m` (seeded): a random triangle's centroid
/// moved by up to 3 % of the diagonal, random orientation, radius 0.3 .. 2.3
/// % and length 1 .. 6 % of the diagonal. With `grazing`, every other pose
/// touches a random face instead, pushed out or in by an offset of kGraze
/// (times the diagonal), alternately with its barrel (axis in the face's
/// plane, along an edge) and its cap (axis along the face normal).
inline CylinderPoses nearSurfacePoses(const FclObjModel& m, std::uint64_t seed,
                                      int n, bool grazing) {
  using V3 = fcl::Vector3d;
  CylinderPoses d;
  PoseSampler s(m, seed);
  const std::vector<V3>& v = s.v;
  const double diag = s.diag;
  for (int k = 0; k < n; ++k) {
    const fcl::Triangle& tr = s.triangle();
    const V3 c = (v[tr[0]] + v[tr[1]] + v[tr[2]]) / 3;
    const V3 nrm = (v[tr[1]] - v[tr[0]]).cross(v[tr[2]] - v[tr[0]]);
    if (grazing && k % 2 == 1 && nrm.norm() > 0) {
      const V3 nn = nrm.normalized();
      const double off = kGraze[std::size_t(k / 2) % std::size(kGraze)] * diag;
      const double r = diag * (0.003 + 0.02 * s.uniform());
      const double lz = diag * (0.01 + 0.05 * s.uniform());
      const bool barrel = (k / 2) % 2 == 0;
      d.poses.push_back(
          barrel ? frameWithAxis(v[tr[1]] - v[tr[0]], c + nn * (r + off))
                 : frameWithAxis(nn, c + nn * (lz / 2 + off)));
      d.cyls.push_back(std::make_shared<fcl::Cylinderd>(r, lz));
      continue;
    }
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = s.rotation();
    tf.translation() =
        c + diag * 0.03 *
                V3(s.uniform() - 0.5, s.uniform() - 0.5, s.uniform() - 0.5);
    d.poses.push_back(tf);
    d.cyls.push_back(
        std::make_shared<fcl::Cylinderd>(diag * (0.003 + 0.02 * s.uniform()),
                                         diag * (0.01 + 0.05 * s.uniform())));
  }
  return d;
}

/// `n` clearance poses (seeded): a random non-degenerate triangle's
/// centroid pushed out along its normal by 10^-6 .. 10^-1 of the diagonal
/// (log-uniform) beyond the cylinder's largest support r + lz/2, random
/// orientation, sizes as above: most poses are near but clear of the
/// surface (planner clearance queries), some touch other parts of it.
inline CylinderPoses clearancePoses(const FclObjModel& m, std::uint64_t seed,
                                    int n) {
  using V3 = fcl::Vector3d;
  CylinderPoses d;
  PoseSampler s(m, seed);
  const std::vector<V3>& v = s.v;
  const double diag = s.diag;
  while (int(d.poses.size()) < n) {
    const fcl::Triangle& tr = s.triangle();
    const V3 nrm = (v[tr[1]] - v[tr[0]]).cross(v[tr[2]] - v[tr[0]]);
    if (!(nrm.norm() > 0)) continue;
    const V3 c = (v[tr[0]] + v[tr[1]] + v[tr[2]]) / 3;
    const double r = diag * (0.003 + 0.02 * s.uniform());
    const double lz = diag * (0.01 + 0.05 * s.uniform());
    fcl::Transform3d tf = fcl::Transform3d::Identity();
    tf.linear() = s.rotation();
    const double off = diag * std::pow(10.0, -6 + 5 * s.uniform());
    tf.translation() = c + nrm.normalized() * (r + 0.5 * lz + off);
    d.poses.push_back(tf);
    d.cyls.push_back(std::make_shared<fcl::Cylinderd>(r, lz));
  }
  return d;
}

}  // namespace tricyl::bench
