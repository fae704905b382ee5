// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Many triangles vs one finite solid cylinder: the batch form of
/// triangle_cylinder.h, for planners that test a cylinder against a mesh.
///
/// ## Contract
/// - Cylinder, Pose and the per-triangle answer are exactly those of
///   tricyl::tryIntersect(cylinder, pose, Triangle) (triangle_cylinder.h):
///   for every triangle the batch answer IS the kernel's answer, bit for bit,
///   whatever the options (cull on or off, vertex pass in AVX2 or portable
///   code). Touching counts; degenerate triangles are valid.
/// - MeshView<S>: an indexed mesh, borrowed (never copied or owned):
///   `vertices` holds 3 * num_vertices coordinates (x, y, z of vertex 0, then
///   vertex 1, ...), `indices` holds 3 * num_triangles vertex numbers;
///   triangle i is (indices[3i], indices[3i+1], indices[3i+2]).
/// - TriangleArrays<S>: structure of arrays, triangle i is
///   ((ax[i], ay[i], az[i]), (bx[i], ...), (cx[i], ...)).
/// - intersectMask: bit (i % 64) of mask[i / 64] is set iff triangle i meets
///   the cylinder; mask must hold (num_triangles + 63) / 64 words, all of
///   which are overwritten (bits past num_triangles are 0). Returns the number
///   of hits.
/// - intersectIndices: the hits' indices in ascending order, appended.
/// - intersectAny: the LOWEST index of a triangle that meets the cylinder, or
///   nullopt; the triangle scan stops there.
///
/// ## Method (docs/batch.md)
/// 1. Setup once per batch: validation, the kernel's range gate and filter
///    constants, and (cull on) a certified world-frame box around the
///    cylinder.
/// 2. Vertex pass, branch-free and vectorised (AVX2 when the CPU has it,
///    detected at run time; SSE2/portable otherwise; no FMA, so both give the
///    same bits): a code per vertex. Cull on: which faces of the world box the
///    vertex is strictly beyond (6 compares, no transform). Cull off: the
///    kernel's own certified early-out signs in the cylinder frame (slab
///    Z > H, Z < -H; square x > r, x < -r, y > r, y < -r), computed with the
///    same double error bound as the scalar filter.
/// 3. Triangle pass: a triangle whose three codes share a bit lies strictly
///    beyond one plane of a region containing the cylinder: disjoint. Every
///    other triangle goes to the scalar exact kernel (tryIntersect).
///    Both rejections are certified, so no answer depends on them.
/// The world box needs R close to orthonormal (|R^T R - I| <= 1/2 in the
/// Frobenius norm, certified); otherwise the cull is skipped and the local
/// pass runs instead (BatchStats::cull_used says which).
///
/// ## Invalid input
/// - Checked forms (intersectMask, intersectIndices, intersectAny) throw
///   tricyl::InvalidInput for a NaN/Inf or negative cylinder size, a non-finite
///   pose, a triangle with a NaN/Inf coordinate, or a vertex index >=
///   num_vertices (never read out of bounds). A null pointer with a non-zero
///   count is a precondition violation (not checked).
/// - tryIntersectMask / tryIntersectAny (noexcept) return
///   Answer::kInvalidInput in those cases and treat what cannot be evaluated
///   as "in collision" (the safe answer for a planner): every bit is set when
///   the cylinder or pose is invalid, and the bit of each invalid triangle
///   (bad coordinate or index) is set; tryIntersectAny reports the lowest
///   index that is a hit or invalid, whichever comes first.
///
/// THREADS: every function is reentrant; nothing is shared between calls.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "tricyl/types.h"

namespace tricyl {

/// An indexed triangle mesh, borrowed. See the header comment.
template <class S>
struct MeshView {
  const S* vertices;             ///< 3 * num_vertices coordinates, xyz xyz...
  std::size_t num_vertices;      ///< number of vertices
  const std::uint32_t* indices;  ///< 3 * num_triangles vertex numbers
  std::size_t num_triangles;     ///< number of triangles
};

/// Triangles as a structure of arrays, borrowed. Triangle i is
/// (a_i, b_i, c_i) with a_i = (ax[i], ay[i], az[i]) and so on.
template <class S>
struct TriangleArrays {
  const S* ax;                ///< x of the first vertices
  const S* ay;                ///< y of the first vertices
  const S* az;                ///< z of the first vertices
  const S* bx;                ///< x of the second vertices
  const S* by;                ///< y of the second vertices
  const S* bz;                ///< z of the second vertices
  const S* cx;                ///< x of the third vertices
  const S* cy;                ///< y of the third vertices
  const S* cz;                ///< z of the third vertices
  std::size_t num_triangles;  ///< number of triangles
};

/// Which code runs the vertex pass. The answers never depend on it.
enum class Isa : unsigned char {
  kAuto = 0,      ///< AVX2 when the CPU has it, portable otherwise
  kPortable = 1,  ///< the baseline build (SSE2 on x86-64)
  kAvx2 = 2,      ///< AVX2 (falls back to portable on a CPU without it)
};

/// Options of a batch query. The answers never depend on them.
struct BatchOptions {
  bool cull = true;      ///< world-frame box cull (no transform) first
  Isa isa = Isa::kAuto;  ///< vertex-pass code path
};

/// What a batch query did (statistics; never changes an answer).
struct BatchStats {
  std::size_t triangles = 0;  ///< triangles looked at
  std::size_t culled = 0;     ///< rejected by the world box (cull on)
  std::size_t early_out = 0;  ///< rejected by the local outcodes (cull off)
  std::size_t kernel = 0;     ///< answered by the scalar exact kernel
  std::size_t hits = 0;       ///< triangles that meet the cylinder
  bool cull_used = false;     ///< the world box was usable and used
  Isa isa = Isa::kPortable;   ///< the vertex pass that ran
};

/// The vertex pass this process uses for Isa::kAuto.
Isa detectedIsa() noexcept;

/// Per-triangle answers as a bit mask; returns the number of hits. Throws
/// InvalidInput (header comment).
template <class S>
std::size_t intersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const MeshView<S>& mesh, std::uint64_t* mask,
                          const BatchOptions& options = {},
                          BatchStats* stats = nullptr);

/// The same for triangles given as a structure of arrays.
template <class S>
std::size_t intersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const TriangleArrays<S>& triangles,
                          std::uint64_t* mask, const BatchOptions& options = {},
                          BatchStats* stats = nullptr);

/// Appends the indices of the triangles that meet the cylinder, ascending;
/// returns how many were appended. Throws InvalidInput.
template <class S>
std::size_t intersectIndices(const Cylinder<S>& cylinder, const Pose<S>& pose,
                             const MeshView<S>& mesh,
                             std::vector<std::uint32_t>* out,
                             const BatchOptions& options = {},
                             BatchStats* stats = nullptr);

/// The lowest index of a triangle that meets the cylinder, or nullopt.
/// Throws InvalidInput for an invalid cylinder or pose, or when an invalid
/// triangle (bad coordinate or index) comes before the first hit.
template <class S>
std::optional<std::size_t> intersectAny(const Cylinder<S>& cylinder,
                                        const Pose<S>& pose,
                                        const MeshView<S>& mesh,
                                        const BatchOptions& options = {},
                                        BatchStats* stats = nullptr);

/// The same for triangles given as a structure of arrays.
template <class S>
std::optional<std::size_t> intersectAny(const Cylinder<S>& cylinder,
                                        const Pose<S>& pose,
                                        const TriangleArrays<S>& triangles,
                                        const BatchOptions& options = {},
                                        BatchStats* stats = nullptr);

/// Non-throwing mask: kIntersect (some hit), kDisjoint (none) or
/// kInvalidInput (header comment: invalid triangles are marked as hits).
/// `hits`, if given, receives the number of set bits.
template <class S>
Answer tryIntersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                        const MeshView<S>& mesh, std::uint64_t* mask,
                        std::size_t* hits = nullptr,
                        const BatchOptions& options = {},
                        BatchStats* stats = nullptr) noexcept;

/// The same for triangles given as a structure of arrays.
template <class S>
Answer tryIntersectMask(const Cylinder<S>& cylinder, const Pose<S>& pose,
                        const TriangleArrays<S>& triangles, std::uint64_t* mask,
                        std::size_t* hits = nullptr,
                        const BatchOptions& options = {},
                        BatchStats* stats = nullptr) noexcept;

/// Non-throwing "any": kIntersect with *first the lowest hit, kDisjoint, or
/// kInvalidInput with *first the lowest invalid triangle (or 0 when the
/// cylinder or pose is invalid) when no hit precedes it.
template <class S>
Answer tryIntersectAny(const Cylinder<S>& cylinder, const Pose<S>& pose,
                       const MeshView<S>& mesh, std::size_t* first,
                       const BatchOptions& options = {},
                       BatchStats* stats = nullptr) noexcept;

#define TRICYL_MESH_CYLINDER_EXTERN(S)                                        \
  extern template std::size_t intersectMask(                                  \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&, std::uint64_t*, \
      const BatchOptions&, BatchStats*);                                      \
  extern template std::size_t intersectMask(                                  \
      const Cylinder<S>&, const Pose<S>&, const TriangleArrays<S>&,           \
      std::uint64_t*, const BatchOptions&, BatchStats*);                      \
  extern template std::size_t intersectIndices(                               \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&,                 \
      std::vector<std::uint32_t>*, const BatchOptions&, BatchStats*);         \
  extern template std::optional<std::size_t> intersectAny(                    \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&,                 \
      const BatchOptions&, BatchStats*);                                      \
  extern template std::optional<std::size_t> intersectAny(                    \
      const Cylinder<S>&, const Pose<S>&, const TriangleArrays<S>&,           \
      const BatchOptions&, BatchStats*);                                      \
  extern template Answer tryIntersectMask(                                    \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&, std::uint64_t*, \
      std::size_t*, const BatchOptions&, BatchStats*) noexcept;               \
  extern template Answer tryIntersectMask(                                    \
      const Cylinder<S>&, const Pose<S>&, const TriangleArrays<S>&,           \
      std::uint64_t*, std::size_t*, const BatchOptions&,                      \
      BatchStats*) noexcept;                                                  \
  extern template Answer tryIntersectAny(                                     \
      const Cylinder<S>&, const Pose<S>&, const MeshView<S>&, std::size_t*,   \
      const BatchOptions&, BatchStats*) noexcept;
TRICYL_MESH_CYLINDER_EXTERN(float)
TRICYL_MESH_CYLINDER_EXTERN(double)
#undef TRICYL_MESH_CYLINDER_EXTERN

}  // namespace tricyl
