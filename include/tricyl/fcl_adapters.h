// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Adapters from FCL 0.7's types to tricyl's, so that an FCL user converts
/// nothing by hand. Header-only; needs FCL's headers (CMake target
/// tricyl::fcl, or tricyl::tricyl plus FCL's include directories).
///
/// Every conversion copies the numbers bit for bit, so a tricyl query on the
/// converted values answers exactly for the values FCL holds:
///
/// - `fcl::Transform3<S>` tf: toPose(tf), R = tf.linear(), t =
///   tf.translation().
/// - `fcl::Cylinder<S>` c: toCylinder(c), {c.radius, c.lz} (the same
///   convention).
/// - `fcl::Vector3<S>` (an Eigen vector) v: toVec3(v).
/// - three `fcl::Vector3<S>` a, b, c: toTriangle(a, b, c).
/// - `fcl::TriangleP<S>` t: toTriangle(t), {t.a, t.b, t.c} in the
///   TriangleP's own frame; toTriangle(t, tf), the world-frame triangle
///   tf * t.a, ... as tricyl::Solver computes it.
/// - `fcl::BVHModel<BV>` model: BvhMeshView<S>(model), a MeshView for the
///   batch scan (mesh_cylinder.h).
///
/// Example: the batch scan over an FCL mesh (its vertices are in the
/// model's frame, so the cylinder's pose is given in that frame):
/// @code
/// const tricyl::BvhMeshView<double> mesh(*model);   // once per model
/// std::vector<std::uint64_t> mask((mesh.num_triangles + 63) / 64);
/// tricyl::intersectMask(tricyl::toCylinder(fcl_cylinder),
///                       tricyl::toPose(cylinder_in_mesh_frame), mesh,
///                       mask.data());
/// @endcode
#pragma once

#include <fcl/common/types.h>
#include <fcl/geometry/bvh/BVH_model.h>
#include <fcl/geometry/shape/cylinder.h>
#include <fcl/geometry/shape/triangle_p.h>

#include <cstddef>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "tricyl/mesh_cylinder.h"
#include "tricyl/types.h"

namespace tricyl {

/// FCL's Transform3 as a tricyl::Pose, bit for bit: R[i][j] = linear()(i, j),
/// t = translation(). The rotation is used as given (never
/// re-orthonormalised), as every tricyl query uses a Pose.
template <class S>
Pose<S> toPose(const fcl::Transform3<S>& tf) {
  Pose<S> pose;
  const auto& L = tf.linear();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) pose.R[i][j] = L(i, j);
  pose.t = {tf.translation()(0), tf.translation()(1), tf.translation()(2)};
  return pose;
}

/// FCL's Cylinder as a tricyl::Cylinder: the same convention (centred, axis
/// +z, radius, full length lz), the same numbers.
template <class S>
Cylinder<S> toCylinder(const fcl::Cylinder<S>& cylinder) {
  return Cylinder<S>{cylinder.radius, cylinder.lz};
}

/// An FCL (Eigen) 3-vector as a tricyl::Vec3.
template <class S>
Vec3<S> toVec3(const fcl::Vector3<S>& v) {
  return Vec3<S>{v[0], v[1], v[2]};
}

/// The triangle with vertices a, b, c (FCL / Eigen vectors).
template <class S>
Triangle<S> toTriangle(const fcl::Vector3<S>& a, const fcl::Vector3<S>& b,
                       const fcl::Vector3<S>& c) {
  return Triangle<S>{toVec3(a), toVec3(b), toVec3(c)};
}

/// An fcl::TriangleP in its own frame: {t.a, t.b, t.c}.
template <class S>
Triangle<S> toTriangle(const fcl::TriangleP<S>& t) {
  return toTriangle(t.a, t.b, t.c);
}

/// An fcl::TriangleP placed at `tf`, in the world frame: tf * t.a, tf * t.b,
/// tf * t.c, rounded by the same Eigen expression tricyl::Solver uses for
/// the TriangleP/Cylinder pair, so a query on this triangle gives the
/// Solver's answer.
template <class S>
Triangle<S> toTriangle(const fcl::TriangleP<S>& t,
                       const fcl::Transform3<S>& tf) {
  const fcl::Vector3<S> a = tf * t.a;
  const fcl::Vector3<S> b = tf * t.b;
  const fcl::Vector3<S> c = tf * t.c;
  return toTriangle(a, b, c);
}

/// A MeshView (mesh_cylinder.h) of an FCL mesh, for the batch scan: the
/// vertices are BORROWED (the model's own array, or the vector given; keep
/// it alive and unchanged while the view is used), the fcl::Triangle indices
/// (std::size_t) are copied once into the 32-bit indices the scan reads.
///
/// Being a MeshView, it is passed as one: intersectMask(cylinder, pose,
/// view, mask), intersectIndices, intersectAny, tryIntersectMask,
/// tryIntersectAny. The triangles are in the frame of the vertices (the
/// model frame of a BVHModel), so `pose` is the cylinder's pose in that
/// frame. For a posed mesh, tricyl::collide (fcl_solver.h) answers for the
/// world-frame triangles FCL builds instead.
///
/// Indices: an index >= the number of vertices is kept invalid (stored as
/// 2^32 - 1), so the scan reports that triangle as its contract says (the
/// checked forms throw InvalidInput, the try forms count it as a hit). A
/// mesh of 2^32 - 1 vertices or more cannot be addressed by 32-bit indices:
/// the constructors throw std::length_error.
template <class S>
class BvhMeshView : public MeshView<S> {
 public:
  /// The vertices and triangles of a built (or building) BVHModel: its
  /// `vertices` and `tri_indices` arrays. A point-cloud model has no
  /// triangles. BV may be any of FCL's bounding volumes over S.
  template <class BV>
  explicit BvhMeshView(const fcl::BVHModel<BV>& model)
      : BvhMeshView(model.vertices, std::size_t(model.num_vertices),
                    model.tri_indices,
                    model.tri_indices != nullptr ? std::size_t(model.num_tris)
                                                 : std::size_t(0)) {
    static_assert(std::is_same_v<typename BV::S, S>,
                  "BvhMeshView<S> needs a BVHModel over S");
  }

  /// The arrays FCL's BVHModel::addSubModel takes.
  BvhMeshView(const std::vector<fcl::Vector3<S>>& points,
              const std::vector<fcl::Triangle>& triangles)
      : BvhMeshView(points.data(), points.size(), triangles.data(),
                    triangles.size()) {}

  /// Borrows the `point_count` vertices at `points`; copies the indices of
  /// the `triangle_count` triangles at `triangles`.
  BvhMeshView(const fcl::Vector3<S>* points, std::size_t point_count,
              const fcl::Triangle* triangles, std::size_t triangle_count)
      : MeshView<S>{nullptr, point_count, nullptr, triangle_count} {
    // An Eigen 3-vector is three S, unpadded: the array is xyz xyz ...
    static_assert(sizeof(fcl::Vector3<S>) == 3 * sizeof(S),
                  "fcl::Vector3<S> is not three packed S");
    constexpr std::uint32_t kInvalid =
        std::numeric_limits<std::uint32_t>::max();
    if (point_count >= kInvalid)
      throw std::length_error(
          "tricyl::BvhMeshView: too many vertices for 32-bit indices");
    this->vertices = points != nullptr ? points->data() : nullptr;
    indices_.resize(3 * triangle_count);
    for (std::size_t i = 0; i < triangle_count; ++i)
      for (int k = 0; k < 3; ++k) {
        const std::size_t v = triangles[i][k];
        indices_[3 * i + k] = v < point_count ? std::uint32_t(v) : kInvalid;
      }
    this->indices = indices_.data();
  }

  /// Copies keep borrowing the same vertices and own their indices.
  BvhMeshView(const BvhMeshView& other)
      : MeshView<S>(other), indices_(other.indices_) {
    this->indices = indices_.data();
  }
  /// Moves keep the index array (no copy).
  BvhMeshView(BvhMeshView&& other) noexcept
      : MeshView<S>(other), indices_(std::move(other.indices_)) {
    this->indices = indices_.data();
    other.indices = other.indices_.data();
    other.num_triangles = 0;
  }
  /// As the copy constructor.
  BvhMeshView& operator=(const BvhMeshView& other) {
    if (this != &other) {
      MeshView<S>::operator=(other);
      indices_ = other.indices_;
      this->indices = indices_.data();
    }
    return *this;
  }
  /// As the move constructor.
  BvhMeshView& operator=(BvhMeshView&& other) noexcept {
    if (this != &other) {
      MeshView<S>::operator=(other);
      indices_ = std::move(other.indices_);
      this->indices = indices_.data();
      other.indices = other.indices_.data();
      other.num_triangles = 0;
    }
    return *this;
  }
  ~BvhMeshView() = default;

 private:
  std::vector<std::uint32_t> indices_;
};

}  // namespace tricyl
