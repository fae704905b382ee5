// SPDX-License-Identifier: BSD-3-Clause
/// @file
/// Triangle vs finite solid cylinder: exact Boolean test-intersection.
///
/// ## Contract
/// - Cylinder: FCL's convention (see types.h): the closed solid
///       C = { y : y0^2 + y1^2 <= r^2, |y2| <= lz/2 },  r >= 0, lz >= 0.
///   r = 0 (the axis segment) and lz = 0 (a flat disk) are valid.
/// - Pose {R, t}: a world point x is in the cylinder iff y = R^T (x - t),
///   evaluated exactly, is in C. R is used exactly as given.
/// - Triangle: three world points (or local points, for the local overload);
///   the closed convex hull. Collinear and coincident vertices are valid.
/// - Answer: true iff the two closed sets share a point. Touching counts.
///   The answer is exact for the float or double inputs as given: there is no
///   epsilon and no tolerance parameter anywhere on this path.
/// - Bounded time: no iteration. Most queries are decided by the certified
///   double filter (tens of ns); a sign it cannot certify is re-decided by
///   itself in double-word, then exactly (stack expansions, GMP only outside
///   their exponent window), see docs/exactness.md.
///
/// ## Invalid input
/// - `intersect` throws tricyl::InvalidInput if any coordinate, pose entry,
///   radius or length is NaN or infinite, or if radius or lz is negative.
/// - `tryIntersect` is noexcept and returns Answer::kInvalidInput instead.
/// - Validation reads bit patterns before any arithmetic: no input, valid or
///   not (NaN, signalling NaN, Inf), raises FE_INVALID or FE_DIVBYZERO.
///
/// ## Method
/// After D. Eberly, "Intersection of a Triangle and a Cylinder", 2010.
/// Eberly moves the triangle into the cylinder frame, clips it to the slab
/// |z| <= h/2 (cases 0a..5 of his Figure 1), projects the clipped piece onto
/// the xy-plane and tests that convex point, segment or polygon against the
/// disk: a vertex inside the disk, an edge within distance r, or the origin
/// inside the polygon. We evaluate exactly the same tests, but without ever
/// constructing the clipped polygon: its vertices are triangle vertices inside
/// the slab and crossings of triangle edges with the planes z = +-h/2, both
/// written homogeneously; its edges are slab-clipped triangle edges and the
/// chords z = +-h/2 of the triangle; "origin inside" is "the axis segment
/// meets the triangle". Every decision is the sign of a polynomial of degree
/// <= 8 in the inputs, so it can be certified in floating point or evaluated
/// exactly. The case map (Figure 1 -> predicate) is in
/// src/triangle_cylinder_impl.h and docs/exactness.md.
///
/// Two traps of the published versions are avoided by construction: a
/// triangle whose plane contains the axis (projection = segment through the
/// origin) is never answered by an "origin inside the polygon" test (the axis
/// test requires a non-zero projected area), and each slab side is tested
/// against its own plane (there is no shared clip routine to get wrong).
#pragma once

#include "tricyl/types.h"

namespace tricyl {

/// World-frame triangle vs posed cylinder. Throws InvalidInput (see above).
template <class S>
bool intersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Triangle<S>& triangle);

/// Triangle already in the cylinder's frame. Throws InvalidInput.
template <class S>
bool intersect(const Cylinder<S>& cylinder, const Triangle<S>& triangle);

/// Non-throwing form: kIntersect, kDisjoint or kInvalidInput.
template <class S>
Answer tryIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                    const Triangle<S>& triangle) noexcept;

/// As tryIntersect, and also reports which stage decided (statistics).
template <class S>
Decision decideIntersect(const Cylinder<S>& cylinder, const Pose<S>& pose,
                         const Triangle<S>& triangle) noexcept;

namespace diagnostic {
/// The floating-point fast path WITHOUT its certificate and WITHOUT the exact
/// fallback: every sign is taken from the rounded value. This is what the
/// same algorithm answers in plain double arithmetic. It exists only so that
/// the comparison harness can show what exactness costs; it is not exact and
/// must not be used to decide anything.
template <class S>
bool intersectUncertified(const Cylinder<S>& cylinder, const Pose<S>& pose,
                          const Triangle<S>& triangle) noexcept;

/// Whether the vectorised (AVX2) fast path's bit-level gate admits these
/// inputs: 1 (admitted: every length |x| < 2^40, every |R_jk| < 2, r >= 0,
/// lz >= 0, nothing NaN or infinite), 0 (rejected: the query takes the
/// validating path), or -1 (no AVX2 path in this build or on this CPU).
/// For tests of the gate itself; the answer of a query never depends on it.
template <class S>
int fastPathGate(const Cylinder<S>& cylinder, const Pose<S>& pose,
                 const Triangle<S>& triangle) noexcept;

/// The fast path alone, as decideIntersect runs it (validation, range gate,
/// prologue and the double filter), stopped there: 1 if it decided the
/// query, 0 if it left the query to the stages after it, -1 if the query
/// does not take it (outside its gate, or invalid). Its only use is to
/// time the filter's part of a query, so that the stage report
/// (tricyl-stage-costs) can give what the stages after it cost; it
/// answers nothing.
template <class S>
int filterOnly(const Cylinder<S>& cylinder, const Pose<S>& pose,
               const Triangle<S>& triangle) noexcept;

/// Whether the vectorised (AVX2 with FMA) double-word local frame of the
/// triangle's vertices (the running and double-word stages' coordinates,
/// docs/exactness.md section 4) equals the scalar one, value for value
/// (hi, lo and bound of every coordinate): 1 (equal), 0 (they differ: a
/// bug), or -1 (no vectorised path in this build or on this CPU). For the
/// test that pins the two paths to each other. Inputs inside the fast
/// path's gate only (every length |x| < 2^40, every |R_jk| < 2, finite).
int dwFramePathsAgree(const Pose<double>& pose,
                      const Triangle<double>& triangle) noexcept;
}  // namespace diagnostic

extern template bool intersect(const Cylinder<float>&, const Pose<float>&,
                               const Triangle<float>&);
extern template bool intersect(const Cylinder<double>&, const Pose<double>&,
                               const Triangle<double>&);
extern template bool intersect(const Cylinder<float>&, const Triangle<float>&);
extern template bool intersect(const Cylinder<double>&,
                               const Triangle<double>&);
extern template Answer tryIntersect(const Cylinder<float>&, const Pose<float>&,
                                    const Triangle<float>&) noexcept;
extern template Answer tryIntersect(const Cylinder<double>&,
                                    const Pose<double>&,
                                    const Triangle<double>&) noexcept;
extern template Decision decideIntersect(const Cylinder<float>&,
                                         const Pose<float>&,
                                         const Triangle<float>&) noexcept;
extern template Decision decideIntersect(const Cylinder<double>&,
                                         const Pose<double>&,
                                         const Triangle<double>&) noexcept;
namespace diagnostic {
extern template bool intersectUncertified(const Cylinder<float>&,
                                          const Pose<float>&,
                                          const Triangle<float>&) noexcept;
extern template bool intersectUncertified(const Cylinder<double>&,
                                          const Pose<double>&,
                                          const Triangle<double>&) noexcept;
extern template int filterOnly(const Cylinder<float>&, const Pose<float>&,
                               const Triangle<float>&) noexcept;
extern template int filterOnly(const Cylinder<double>&, const Pose<double>&,
                               const Triangle<double>&) noexcept;
extern template int fastPathGate(const Cylinder<float>&, const Pose<float>&,
                                 const Triangle<float>&) noexcept;
extern template int fastPathGate(const Cylinder<double>&, const Pose<double>&,
                                 const Triangle<double>&) noexcept;
}  // namespace diagnostic

}  // namespace tricyl
