#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Writes the seed corpus of the fuzz targets (fuzz/corpus/<query>/).

Each seed uses the plainest encoding of fuzz/fuzz_input.h: a flags byte, then
every scalar as tag 0 + its raw little-endian bit pattern (8 bytes for double,
4 for float). Flags: 0 = free R (9 scalars), 1 = signed axis permutation (one
byte), 2 = identity pose; +4 = points given in the shape's frame; +8 =
float.
  triangle_cylinder (decode): radius, lz, R (if free), t (not in mode 2),
    a, b, c.
  point_cylinder, point_cone, sphere_cylinder, segment_cylinder,
  line_cylinder (QueryInput + decodePoint / decodeSphere / decodeSegment):
    the shape as radius, lz, R, t (as above), or with flags +0x10 the axis
    form O, N, L, R (cylinderFromAxis / coneFromApex), or with +0x20 the
    endpoints form a, b, R (cylinderFromEndpoints); then the point x / the
    centre and rho / the segment's (the line's) p and q.

Usage: python3 scripts/make_fuzz_corpus.py   (rewrites the directories)
"""
import math
import os
import shutil
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
CORPUS = os.path.join(ROOT, "fuzz", "corpus")
NAN = float("nan")
INF = float("inf")
I3 = [1, 0, 0, 0, 1, 0, 0, 0, 1]


def enc(flags, scalars, perm=None):
    fmt = "<f" if flags & 8 else "<d"
    out = bytes([flags])
    vals = list(scalars)
    # radius, lz come first; a permutation byte follows them in mode 1.
    out += b"".join(b"\x00" + struct.pack(fmt, v) for v in vals[:2])
    if flags & 3 == 1:
        out += bytes([perm or 0])
    out += b"".join(b"\x00" + struct.pack(fmt, v) for v in vals[2:])
    return out


def posed(cyl, R, t, tri, flags=0):
    return enc(flags, list(cyl) + list(R) + list(t) + [x for v in tri for x in v])


def ident(cyl, tri, flags=2):
    return enc(flags, list(cyl) + [x for v in tri for x in v])


def perm(cyl, k, t, tri, flags=1):
    return enc(flags, list(cyl) + list(t) + [x for v in tri for x in v], perm=k)


def up(x):
    return math.nextafter(x, INF)


def down(x):
    return math.nextafter(x, -INF)


seeds = {}
# Issue 9, literal (hex floats from `issues show 9`).
h = float.fromhex
seeds["issue9_disc_rim"] = posed(
    (h("0x1.8523b2c7f16bfp+9"), h("0x1.1d3482e4f382bp-20")),
    [h(x) for x in ("0x1.48b62eb9de056p-2", "-0x1.5f07bdb4e0192p-1",
                    "-0x1.4e872644fc344p-1", "0x1.5c2a442996f94p-2",
                    "0x1.746386dd0c053p-1", "-0x1.313b183115a55p-1",
                    "0x1.c493d98a71998p-1", "-0x1.f850245fded6p-6",
                    "0x1.ddc88111b7d02p-2")],
    [h("-0x1.51bb1180c6b4p-1"), h("0x1.a407417745a74p+0"), h("0x1.286f93e83346p-1")],
    [[h("-0x1.3534e5984faf4p+6"), h("-0x1.a6f71157db70ep+8"), h("-0x1.44a19c5402542p+9")],
     [h("-0x1.6fc68327e9913p+7"), h("-0x1.4d2ce616c4b6cp+8"), h("-0x1.55e5b744efdp+9")],
     [h("-0x1.5d58739ed8ec2p+6"), h("-0x1.6c8a172168b19p+8"), h("-0x1.3777f50c50d2cp+9")]])
# The published trap: the triangle's plane contains the axis (disjoint).
seeds["axis_plane_trap"] = ident((0.5, 4), [(1, 0, -1), (2, 0, -1), (1.5, 0, 1)])
# Touching the side, the cap, the rim; one ulp away.
seeds["touch_side"] = ident((1, 2), [(1, -1, 0), (1, 1, 0), (1, 0, 0.5)])
seeds["side_one_ulp_off"] = ident((1, 2), [(up(1), -1, 0), (up(1), 1, 0), (up(1), 0, 0.5)])
seeds["touch_cap"] = ident((1, 2), [(-5, -5, 1), (5, -5, 1), (0, 5, 1)])
seeds["cap_one_ulp_off"] = ident((1, 2), [(-5, -5, up(1)), (5, -5, up(1)), (0, 5, up(1))])
seeds["touch_rim_point"] = ident((1, 2), [(1, 0, 1), (3, 0, 3), (3, 1, 1)])
seeds["edge_tangent_disc"] = ident((1, 2), [(-3, 1, 0), (3, 1, 0), (0, 5, 0)])
seeds["triangle_inside"] = ident((3, 3), [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
seeds["cylinder_pierces_triangle"] = ident((0.1, 10), [(-5, -5, 0), (5, -5, 0), (0, 5, 0)])
# Degenerate sizes and triangles.
seeds["r_zero_segment"] = ident((0, 2), [(-1, -1, 0.5), (1, -1, 0.5), (0, 1, 0.5)])
seeds["lz_zero_disk"] = ident((1, 0), [(0.5, 0, -1), (0.5, 0, 1), (0.6, 0.1, 1)])
seeds["both_zero_point"] = ident((0, 0), [(0, 0, 0), (0, 0, 0), (0, 0, 0)])
seeds["minus_zero_sizes"] = ident((-0.0, -0.0), [(-1, -1, 0), (1, -1, 0), (0, 1, 0)])
seeds["point_triangle_on_rim"] = ident((1, 2), [(0.6, 0.8, 1), (0.6, 0.8, 1), (0.6, 0.8, 1)])
seeds["collinear_crossing"] = ident((1, 2), [(-3, 0.5, 0), (0, 0.5, 0), (3, 0.5, 0)])
# Hostile input.
seeds["nan_radius"] = ident((NAN, 2), [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
seeds["inf_lz"] = ident((1, INF), [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
seeds["neg_radius"] = ident((-1, 2), [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
seeds["neg_denorm_lz"] = ident((1, -5e-324), [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
seeds["nan_vertex"] = ident((1, 2), [(0, 0, 0), (NAN, 0, 0), (0, 1, 0)])
seeds["inf_in_R"] = posed((1, 2), [1, 0, 0, 0, INF, 0, 0, 0, 1], (0, 0, 0),
                          [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
seeds["neg_inf_t"] = posed((1, 2), I3, (0, -INF, 0), [(0, 0, 0), (1, 0, 0), (0, 1, 0)])
# Huge, tiny and mixed magnitudes (outside the filters' range gate).
seeds["huge_touch_side"] = ident((1e300, 2e300), [(1e300, -1e300, 0), (1e300, 1e300, 0), (1e300, 0, 5e299)])
seeds["huge_one_ulp_off"] = ident((1e300, 2e300), [(up(1e300), -1e300, 0), (up(1e300), 1e300, 0), (up(1e300), 0, 5e299)])
seeds["max_coordinates"] = ident((1.7976931348623157e308, 1.7976931348623157e308),
                                 [(-1.7976931348623157e308, 0, 0), (1.7976931348623157e308, 0, 0), (0, 1.7976931348623157e308, 0)])
seeds["subnormal_touch"] = ident((5e-324, 1e-323), [(5e-324, -5e-324, 0), (5e-324, 5e-324, 0), (1e-323, 0, 0)])
seeds["subnormal_off"] = ident((5e-324, 1e-323), [(1e-323, -5e-324, 0), (1e-323, 5e-324, 0), (1.5e-323, 0, 0)])
seeds["tiny_cyl_huge_tri"] = ident((1e-300, 1e-300), [(-1e300, -1e300, 0), (1e300, -1e300, 0), (0, 1e300, 0)])
seeds["huge_cyl_tiny_tri"] = ident((1e300, 1e-300), [(0, 0, 0), (1e-300, 0, 0), (0, 1e-300, 0)])
seeds["range_gate_edge"] = ident((2.0**40, 2.0**40), [(2.0**40, 0, 0), (up(2.0**40), 1, 0), (2.0**40, -1, 0)])
seeds["huge_translation"] = posed((1, 2), I3, (1e300, -1e300, 1e300),
                                  [(1e300, -1e300, 1e300), (up(1e300), -1e300, 1e300), (1e300, up(-1e300), 1e300)])
# Poses: a Pythagorean rotation, a non-orthonormal R, axis permutations,
# the local-frame mode.
R345 = [0.6, -0.8, 0, 0.8, 0.6, 0, 0, 0, 1]
seeds["rot345_touch"] = posed((1, 2), R345, (0.5, -0.25, 3), [(1.1, -0.25, 3), (1.1, 1, 3), (2, 0, 3.5)])
seeds["scaled_R"] = posed((1, 2), [2, 0, 0, 0, 2, 0, 0, 0, 2], (0, 0, 0), [(2, -1, 0), (2, 1, 0), (3, 0, 0)])
seeds["near_singular_R"] = posed((1, 2), [1, 1, 0, 1, up(1), 0, 0, 0, 1e-300], (0, 0, 0),
                                 [(1, 0, 0), (0, 1, 0), (0, 0, 1)])
seeds["perm_touch_cap"] = perm((1, 2), 9, (0, 0, 0), [(-5, 1, -5), (5, 1, -5), (0, 1, 5)])
seeds["perm_side_off"] = perm((1, 2), 40, (3, 0, 0), [(up(4), -1, 0), (up(4), 1, 0), (up(4), 0, 0.5)])
seeds["local_frame_rim"] = posed((1, 2), R345, (7, -3, 2), [(1, 0, 1), (2, 0, 2), (2, 1, 1)], flags=4)
seeds["local_frame_thin"] = posed((778.0, 1e-6), [0.36, -0.48, -0.8, 0.48, 0.64 + 0.0, -0.6, 0.8, 0, 0.6],
                                  (0.1, 0.2, 0.3), [(778, 0, 0), (800, 10, 5e-7), (790, -10, -5e-7)], flags=4)
# float inputs.
seeds["float_touch_side"] = ident((1, 2), [(1, -1, 0), (1, 1, 0), (1, 0, 0.5)], flags=2 | 8)
seeds["float_axis_plane_trap"] = ident((0.5, 4), [(1, 0, -1), (2, 0, -1), (1.5, 0, 1)], flags=2 | 8)
seeds["float_huge"] = ident((3e38, 3e38), [(3e38, -3e38, 0), (3e38, 3e38, 0), (3e38, 0, 1e38)], flags=2 | 8)
seeds["float_nan"] = ident((1, 2), [(NAN, 0, 0), (1, 0, 0), (0, 1, 0)], flags=2 | 8)
seeds["float_rot345"] = posed((1, 2), R345, (0.5, -0.25, 3), [(1.1, -0.25, 3), (1.1, 1, 3), (2, 0, 3.5)], flags=8)
# Structured tags (copies, ulp moves), so the fuzzer starts from them too:
# r = 1, lz = 2, identity, a = (r, -1, 0) as a copy, b = (r + 1 ulp...).
seeds["structured_ties"] = bytes([2]) + b"\x03\x02" + b"\x03\x05" + \
    b"\x04\x00" + b"\x03\x03" + b"\x03\x00" + b"\x05\x07\x00" + b"\x03\x02" + b"\x03\x00" + \
    b"\x04\x00" + b"\x03\x00" + b"\x03\x04"


# ---------------------------------------------------------------------------
# The cylinder query targets.
FLOAT = 8
LOCAL = 4
AXIS = 0x10
ENDPOINTS = 0x20


def qenc(flags, parts):
    """flags byte, then each part: a number as tag 0 + its bits, bytes raw."""
    fmt = "<f" if flags & FLOAT else "<d"
    out = bytes([flags])
    for v in parts:
        out += v if isinstance(v, bytes) else b"\x00" + struct.pack(fmt, v)
    return out


def flat(points):
    return [x for v in points for x in v]


def q_ident(size, points, flags=0):
    """Identity pose (mode 2): radius, lz, then the query's scalars."""
    return qenc(flags | 2, list(size) + flat(points))


def q_posed(size, R, t, points, flags=0):
    return qenc(flags, list(size) + list(R) + list(t) + flat(points))


def q_perm(size, k, t, points, flags=0):
    return qenc(flags | 1, list(size) + [bytes([k])] + list(t) + flat(points))


def q_axis(O, N, L, R, points, flags=0):
    return qenc(flags | AXIS, list(O) + list(N) + [L, R] + flat(points))


def q_endpoints(a, b, R, points, flags=0):
    return qenc(flags | ENDPOINTS, list(a) + list(b) + [R] + flat(points))


def sph(center, rho):
    """The sphere's scalars: the centre's three, then rho (a 4-vector)."""
    return list(center) + [rho]


DMAX = 1.7976931348623157e308
# Pose of point_cylinder_test's ExactBoundaryPosed: local z -> world x,
# local x -> world -y, local y -> world z, t = (1, 0, 0.5).
RPERM = [0, 0, 1, -1, 0, 0, 0, 1, 0]

# point_cylinder: r = 1, lz = 4 unless stated (tests/point_cylinder_test.cpp).
pc = {}
for name, x in [("centre", (0, 0, 0)), ("top_cap_centre", (0, 0, 2)),
                ("on_side", (1, 0, 0)), ("rounded_0.6_0.8", (0.6, 0.8, -1)),
                ("on_top_cap", (0.75, 0.5, 2)), ("top_rim", (1, 0, 2)),
                ("bottom_rim", (0, -1, -2)), ("beyond_side", (1.0625, 0, 0)),
                ("beyond_top_cap", (0, 0, 2.0625)),
                ("beyond_rim", (1, 0, 2.0625)),
                ("side_one_ulp_out", (up(1), 0, 0)),
                ("cap_one_ulp_out", (0, 0, up(2)))]:
    pc[name] = q_ident((1, 4), [x])
pc["posed_rim"] = q_posed((0.625, 2), RPERM, (1, 0, 0.5), [(2, -0.375, 1)])
pc["posed_side_one_ulp_out"] = q_posed((0.625, 2), RPERM, (1, 0, 0.5),
                                       [(1, -up(0.375), 1)])
pc["perm_rim"] = q_perm((1, 4), 13, (3, -2, 1), [(3, -1, 3)])
pc["local_frame_rim_rot345"] = q_posed((1, 4), R345, (0.5, -0.25, 3),
                                       [(1, 0, 2)], flags=LOCAL)
pc["r_zero_axis"] = q_ident((0, 2), [(0, 0, -0.5)])
pc["r_zero_denorm_off"] = q_ident((0, 2), [(5e-324, 0, 0)])
pc["lz_zero_disk_edge"] = q_ident((1, 0), [(0, 1, -0.0)])
pc["lz_zero_denorm_off"] = q_ident((1, 0), [(0, 0, 5e-324)])
pc["both_zero_origin"] = q_ident((0, 0), [(0, 0, 0)])
pc["minus_zero_sizes"] = q_ident((-0.0, -0.0), [(0, 0, 0)])
pc["huge_on_side"] = q_ident((1e300, 2e300), [(1e300, 0, 1e300)])
pc["max_coordinates"] = q_ident((DMAX, DMAX), [(DMAX, 0, 0)])
pc["subnormal_side"] = q_ident((5e-324, 1e-323), [(0, 5e-324, 5e-324)])
pc["huge_translation"] = q_posed((1, 2), I3, (1e300, -1e300, 1e300),
                                 [(1e300, -1e300, up(1e300))])
pc["near_singular_R"] = q_posed((1, 2), [1, 1, 0, 1, up(1), 0, 0, 0, 1e-300],
                                (0, 0, 0), [(1, 1, 1)])
pc["nan_radius"] = q_ident((NAN, 2), [(0, 0, 0)])
pc["neg_radius"] = q_ident((-1, 2), [(0, 0, 0)])
pc["inf_lz"] = q_ident((1, INF), [(0, 0, 0)])
pc["neg_denorm_lz"] = q_ident((1, -5e-324), [(0, 0, 0)])
pc["nan_point"] = q_ident((1, 2), [(NAN, 0, 0)])
pc["inf_in_R"] = q_posed((1, 2), [1, 0, 0, 0, 1, 0, 0, 0, INF], (0, 0, 0),
                         [(0, 0, 0)])
pc["neg_inf_t"] = q_posed((1, 2), I3, (0, -INF, 0), [(0, 0, 0)])
# The endpoint forms (tests' EndpointFormExactCases), and directions the
# header's "a few ulps" does not cover (|N| overflows / underflows).
pc["axis_rim"] = q_axis((1, 2, 3), (0, 0, 1), 4, 0.5, [(1.5, 2, 7)])
pc["axis_rim_one_ulp_out"] = q_axis((1, 2, 3), (0, 0, 1), 4, 0.5,
                                    [(1.5, 2, up(7))])
pc["axis_origin"] = q_axis((1, 2, 3), (0, 0, 1), 4, 0.5, [(1, 2, 3)])
pc["axis_nonunit_345"] = q_axis((0, 0, 0), (0, 3, 4), 5, 1, [(1, 1.8, 2.4)])
pc["axis_minus_z"] = q_axis((0, 0, 0), (0, 0, -1), 2, 1, [(1, 0, -2)])
pc["axis_N_zero"] = q_axis((0, 0, 0), (0, 0, 0), 2, 1, [(1, 0, 1)])
pc["axis_N_huge"] = q_axis((0, 0, 0), (1e200, 0, 0), 2, 1, [(1, 0, 0)])
pc["axis_N_tiny"] = q_axis((0, 0, 0), (1e-200, 0, 0), 2, 1, [(1, 0, 0)])
pc["axis_overflowing_t"] = q_axis((DMAX, 0, 0), (1, 0, 0), DMAX, 1,
                                  [(DMAX, 0, 0)])
pc["endpoints_rim"] = q_endpoints((0, 0, 0), (-2, 0, 0), 1, [(-2, 0, 1)])
pc["endpoints_outside"] = q_endpoints((0, 0, 0), (-2, 0, 0), 1,
                                      [(0.25, 0, 0)])
pc["endpoints_disk"] = q_endpoints((1, 1, 1), (1, 1, 1), 1, [(2, 1, 1)])
pc["endpoints_disk_above"] = q_endpoints((1, 1, 1), (1, 1, 1), 1,
                                         [(1, 1, 1.5)])
pc["endpoints_diagonal"] = q_endpoints((0, 0, 0), (1, 1, 1), 0.5,
                                       [(0.5, 0.5, 0.5)])
pc["endpoints_overflowing_d"] = q_endpoints((-DMAX, 0, 0), (DMAX, 0, 0), 1,
                                            [(0, 0, 0)])
pc["axis_local_point"] = q_axis((1, 2, 3), (1, 1, 1), 2, 0.5, [(0.5, 0, 1)],
                                flags=LOCAL)
pc["float_top_rim"] = q_ident((1, 4), [(1, 0, 2)], flags=FLOAT)
pc["float_side_one_ulp_out"] = q_ident((1, 4), [(1.0000001192092896, 0, 0)],
                                       flags=FLOAT)
pc["float_nan"] = q_ident((1, 4), [(NAN, 0, 0)], flags=FLOAT)
pc["float_huge"] = q_ident((3e38, 3e38), [(3e38, 0, 1e38)], flags=FLOAT)
pc["float_axis_rim"] = q_axis((1, 2, 3), (0, 0, 1), 4, 0.5, [(1.5, 2, 7)],
                              flags=FLOAT)
pc["float_endpoints_disk"] = q_endpoints((1, 1, 1), (1, 1, 1), 1, [(2, 1, 1)],
                                         flags=FLOAT)
# Structured tags: r = 1, lz = 2 (specials), identity; x = (r moved by one
# ulp up, -0, lz/2 as a copy scaled by 2^-1).
pc["structured_ulp_tie"] = bytes([2]) + b"\x03\x02" + b"\x03\x05" + \
    b"\x05\x18\x00" + b"\x03\x01" + b"\x05\x10\x01"

# point_cone: r = 1, lz = 2 (apex (0, 0, 1), base z = -1) unless stated
# (tests/point_cone_test.cpp).
pk = {}
for name, x in [("apex", (0, 0, 1)), ("above_apex", (0, 0, up(1))),
                ("beside_apex", (5e-324, 0, 1)), ("centre", (0, 0, 0)),
                ("base_centre", (0, 0, -1)), ("below_base", (0, 0, down(-1))),
                ("base_rim", (1, 0, -1)), ("beyond_rim", (up(1), 0, -1)),
                ("slant_mid", (0.5, 0, 0)), ("slant_mid_out", (up(0.5), 0, 0)),
                ("slant_mid_in", (down(0.5), 0, 0)),
                ("slant_high", (0, -0.25, 0.5)),
                ("slant_high_out", (0, -0.25, up(0.5))),
                ("in_cylinder_not_cone", (0.75, 0, 0)),
                ("slant_pythagorean", (0.375, 0.5, -0.25)),
                ("slant_pythagorean_out", (0.375, up(0.5), -0.25))]:
    pk[name] = q_ident((1, 2), [x])
pk["lz_zero_disk_edge"] = q_ident((1, 0), [(0, 1, 0)])
pk["lz_zero_outside"] = q_ident((1, 0), [(2, 0, 0)])
pk["lz_zero_denorm_off"] = q_ident((1, 0), [(0, 0, 5e-324)])
pk["r_zero_axis"] = q_ident((0, 2), [(0, 0, -0.5)])
pk["r_zero_denorm_off"] = q_ident((0, 2), [(5e-324, 0, 0)])
pk["both_zero_origin"] = q_ident((0, 0), [(0, 0, 0)])
pk["both_zero_denorm_off"] = q_ident((0, 0), [(0, 5e-324, 0)])
pk["posed_slant"] = q_posed((1, 2), R345, (0.5, -0.25, 3), [(0.5, 0.25, 3)],
                            flags=LOCAL)
pk["perm_apex"] = q_perm((1, 2), 7, (1, 2, 3), [(1, 2, 4)])
pk["huge_slant"] = q_ident((1e300, 2e300), [(5e299, 0, 0)])
pk["subnormal_slant"] = q_ident((1e-323, 2e-323), [(5e-324, 0, 0)])
pk["nan_lz"] = q_ident((1, NAN), [(0, 0, 0)])
pk["neg_lz"] = q_ident((1, -1), [(0, 0, 0)])
pk["inf_point"] = q_ident((1, 2), [(0, 0, INF)])
pk["inf_in_R"] = q_posed((1, 2), [INF, 0, 0, 0, 1, 0, 0, 0, 1], (0, 0, 0),
                         [(0, 0, 0)])
pk["apex_form_apex"] = q_axis((0, 0, 0), (0, 0, 1), 2, 1, [(0, 0, 0)])
pk["apex_form_base_rim"] = q_axis((0, 0, 0), (0, 0, 1), 2, 1, [(1, 0, 2)])
pk["apex_form_behind_apex"] = q_axis((0, 0, 0), (0, 0, 1), 2, 1,
                                     [(0, 0, down(0))])
pk["apex_form_nonunit"] = q_axis((1, 1, 1), (0, -2, 0), 4, 2,
                                 [(1, -1, 1)])
pk["apex_form_N_zero"] = q_axis((0, 0, 0), (0, 0, 0), 2, 1, [(0, 0, -1)])
pk["apex_form_diagonal"] = q_axis((0, 0, 0), (1, 1, 1), 3, 1,
                                  [(1, 1, 1)])
pk["float_slant_mid"] = q_ident((1, 2), [(0.5, 0, 0)], flags=FLOAT)
pk["float_above_apex"] = q_ident((1, 2), [(0, 0, 1.0000001192092896)],
                                 flags=FLOAT)
pk["float_apex_form"] = q_axis((0, 0, 0), (0, 0, 1), 2, 1, [(1, 0, 2)],
                               flags=FLOAT)

# sphere_cylinder: r = 1, lz = 2 unless stated (tests/sphere_cylinder_test.cpp).
ss = {}
for name, c in [("centre_inside", (0, 0, 0, 0.5)),
                ("rho_zero_inside", (0.25, 0, 0.5, 0)),
                ("touch_side", (1.5, 0, 0, 0.5)),
                ("miss_side_one_ulp", (1.5, 0, 0, down(0.5))),
                ("touch_side_near_cap", (0, -1.5, 0.999, 0.5)),
                ("touch_top_cap", (0.5, 0, 1.5, 0.5)),
                ("miss_top_cap_one_ulp", (0.5, 0, 1.5, down(0.5))),
                ("touch_bottom_cap", (0, 0.75, -1.25, 0.25)),
                ("touch_rim", (1.375, 0, 1.5, 0.625)),
                ("miss_rim_one_ulp", (1.375, 0, 1.5, down(0.625))),
                ("touch_bottom_rim", (0, -1.375, -1.5, 0.625)),
                ("too_high_near_rim", (1, 0, 2.5, 1.25)),
                ("hit_near_rim", (1, 0, 2.25, 1.25)),
                ("source_r_plus_rho_trap", (1.5, 0, 1.5, 0.5)),
                ("rho_zero_on_rim", (0, 1, -1, 0))]:
    ss[name] = q_ident((1, 2), [sph(c[:3], c[3])])
ss["r_zero_touch"] = q_ident((0, 2), [sph((0.5, 0, 0), 0.5)])
ss["r_zero_rim_point"] = q_ident((0, 2), [sph((0.375, 0, 1.5), 0.625)])
ss["lz_zero_touch"] = q_ident((1, 0), [sph((0, 0, 0.5), 0.5)])
ss["lz_zero_miss"] = q_ident((1, 0), [sph((0, 0, 0.5), down(0.5))])
ss["both_zero_touch"] = q_ident((0, 0), [sph((0.375, 0.5, 0), 0.625)])
ss["R_twice_identity"] = q_posed((1, 2), [2, 0, 0, 0, 2, 0, 0, 0, 2],
                                 (0, 0, 0), [sph((1, 0, 0), 1)])
ss["R_twice_identity_miss"] = q_posed((1, 2), [2, 0, 0, 0, 2, 0, 0, 0, 2],
                                      (0, 0, 0), [sph((1, 0, 0), down(1))])
ss["rot345_local_rim"] = q_posed((1, 2), R345, (0.5, -0.25, 3),
                                 [sph((1.375, 0, 1.5), 0.625)], flags=LOCAL)
ss["perm_touch_cap"] = q_perm((1, 2), 21, (0, 0, 0), [sph((0, 1.5, 0), 0.5)])
ss["huge_touch_rim"] = q_ident((1e300, 2e300),
                               [sph((1.375e300, 0, 1.5e300), 6.25e299)])
ss["subnormal_touch"] = q_ident((5e-324, 1e-323),
                                [sph((1.5e-323, 0, 0), 1e-323)])
ss["max_rho"] = q_ident((1, 2), [sph((DMAX, 0, 0), DMAX)])
ss["neg_rho"] = q_ident((1, 2), [sph((0, 0, 0), -1)])
ss["neg_zero_rho"] = q_ident((1, 2), [sph((0, 0, 1), -0.0)])
ss["nan_rho"] = q_ident((1, 2), [sph((0, 0, 0), NAN)])
ss["inf_rho"] = q_ident((1, 2), [sph((0, 0, 0), INF)])
ss["nan_centre"] = q_ident((1, 2), [sph((NAN, 0, 0), 1)])
ss["neg_radius"] = q_ident((-1, 2), [sph((0, 0, 0), 1)])
ss["inf_lz"] = q_ident((1, INF), [sph((0, 0, 0), 1)])
ss["axis_touch_rim"] = q_axis((0, 0, -1), (0, 0, 3), 2, 1,
                              [sph((1.375, 0, 1.5), 0.625)])
ss["endpoints_touch_side"] = q_endpoints((-1, 0, 0), (1, 0, 0), 1,
                                         [sph((0, 1.5, 0), 0.5)])
ss["endpoints_point_cyl"] = q_endpoints((2, 2, 2), (2, 2, 2), 0,
                                        [sph((2, 2, 3), 1)])
ss["float_touch_rim"] = q_ident((1, 2), [sph((1.375, 0, 1.5), 0.625)],
                                flags=FLOAT)
ss["float_miss_rim"] = q_ident((1, 2), [sph((1.375, 0, 1.5), 0.62499994)],
                               flags=FLOAT)
ss["float_nan_rho"] = q_ident((1, 2), [sph((0, 0, 0), NAN)], flags=FLOAT)

# segment_cylinder: r = 1, lz = 2 unless stated
# (tests/segment_cylinder_test.cpp).
sg = {}
# The source pseudo-code's failures (issue 5).
sg["source_fail_inside"] = q_ident((1, 2), [(0.25, 0, -0.5),
                                            (-0.25, 0.25, 0.5)])
sg["source_fail_root_beyond_cap"] = q_ident((1, 2), [(-2, 0, 0.5),
                                                     (2, 0, 3.5)])
sg["source_fail_both_caps"] = q_ident((1, 2), [(0.125, 0, -3),
                                               (-0.125, 0, 3)])
sg["source_fail_from_above"] = q_ident((1, 2), [(0.25, 0, 3.5),
                                                (0.25, 0.25, 0)])
for name, p, q in [
        ("point_inside", (0, 0, 0), (0, 0, 0)),
        ("point_outside", (2, 0, 0), (2, 0, 0)),
        ("through_axis", (-2, 0, 0), (2, 0, 0)),
        ("perpendicular_miss", (-2, 1.5, 0), (2, 1.5, 0)),
        ("parallel_inside", (0.5, 0, -3), (0.5, 0, 3)),
        ("along_axis", (0, 0, -2), (0, 0, 2)),
        ("parallel_on_side", (1, 0, -2), (1, 0, 2)),
        ("parallel_one_ulp_out", (up(1), 0, -2), (up(1), 0, 2)),
        ("tangent_side", (1, -1, 0), (1, 1, 0)),
        ("tangent_one_ulp_out", (up(1), -1, 0), (up(1), 1, 0)),
        ("slanted_tangent", (-1, 1, -0.5), (1, 1, 0.5)),
        ("out_through_rim", (0, 0, 0), (2, 0, 2)),
        ("rim_only_freesteel_crack", (2, 0, 0), (0, 0, 2)),
        ("grazing_rim", (1, -1, 1), (1, 1, 1)),
        ("rim_one_ulp_above", (1, -1, up(1)), (1, 1, up(1))),
        ("in_top_cap_plane", (-2, 0, 1), (2, 0, 1)),
        ("in_bottom_cap_plane", (-2, 0, -1), (2, 0, -1)),
        ("ending_on_top_cap", (0, 0, 3), (0, 0, 1)),
        ("through_both_caps", (0.5, 0, 3), (0.5, 0, -3))]:
    sg[name] = q_ident((1, 2), [p, q])
sg["r_zero_crossing"] = q_ident((0, 2), [(-1, 0, 0.5), (1, 0, 0.5)])
sg["r_zero_slanted"] = q_ident((0, 2), [(-1, 0, 0.5), (1, 0, 1)])
sg["r_zero_miss"] = q_ident((0, 2), [(-1, 1e-3, 0), (1, 1e-3, 0)])
sg["lz_zero_axis"] = q_ident((1, 0), [(0, 0, -1), (0, 0, 1)])
sg["lz_zero_in_plane"] = q_ident((1, 0), [(-2, 0, 0), (2, 0, 0)])
sg["lz_zero_miss"] = q_ident((1, 0), [(2, 0, -1), (2, 0, 1)])
sg["near_tangent_grazing"] = q_ident((1, 2), [(down(1), -1, 0),
                                              (down(1), 1, 0)])
sg["long_grazing"] = q_ident((1, 2), [(1, -1e15, 0), (1, 1e15, 1e-300)])
sg["huge_tangent"] = q_ident((1e300, 2e300), [(1e300, -1e300, 0),
                                              (1e300, 1e300, 0)])
sg["max_coordinates"] = q_ident((DMAX, DMAX), [(-DMAX, 0, 0), (DMAX, 0, 0)])
sg["subnormal_tangent"] = q_ident((5e-324, 1e-323), [(5e-324, -5e-324, 0),
                                                      (5e-324, 5e-324, 0)])
sg["tiny_cyl_huge_segment"] = q_ident((1e-300, 1e-300), [(-1e300, 0, 0),
                                                         (1e300, 0, 0)])
sg["huge_cyl_tiny_segment"] = q_ident((1e300, 1e-300), [(0, 0, 0),
                                                        (1e-300, 0, 0)])
sg["rot345_local_rim_crack"] = q_posed((1, 2), R345, (0.5, -0.25, 3),
                                       [(2, 0, 0), (0, 0, 2)], flags=LOCAL)
sg["perm_parallel_side"] = q_perm((1, 2), 33, (1, 2, 3),
                                  [(2, 2, 1), (2, 2, 5)])
sg["huge_translation"] = q_posed((1, 2), I3, (1e300, -1e300, 1e300),
                                 [(1e300, -1e300, 1e300),
                                  (up(1e300), -1e300, 1e300)])
sg["nan_endpoint"] = q_ident((1, 2), [(0, NAN, 0), (1, 0, 0)])
sg["inf_endpoint"] = q_ident((1, 2), [(0, 0, 0), (INF, 0, 0)])
sg["neg_radius"] = q_ident((-1, 1), [(0, 0, 0), (1, 0, 0)])
sg["neg_lz"] = q_ident((1, -1), [(0, 0, 0), (1, 0, 0)])
sg["nan_in_R"] = q_posed((1, 1), [1, 0, 0, 0, 1, 0, 0, 0, NAN], (0, 0, 0),
                         [(0, 0, 0), (1, 0, 0)])
sg["axis_through_caps"] = q_axis((0, 0, 0), (0, 0, 1), 2, 1,
                                 [(0.5, 0, -1), (0.5, 0, 3)])
sg["axis_diagonal_tangent"] = q_axis((0, 0, 0), (1, 1, 0), 4, 1,
                                     [(0, 0, 1), (4, 4, 1)])
sg["endpoints_through_axis"] = q_endpoints((0, 0, -1), (0, 0, 1), 1,
                                           [(-2, 0, 0), (2, 0, 0)])
sg["endpoints_disk_crossing"] = q_endpoints((1, 1, 1), (1, 1, 1), 1,
                                            [(1, 1, 0), (1, 1, 2)])
sg["float_tangent"] = q_ident((1, 2), [(1, -1, 0), (1, 1, 0)], flags=FLOAT)
sg["float_through_both_caps"] = q_ident((1, 2), [(0.5, 0, 3), (0.5, 0, -3)],
                                        flags=FLOAT)
sg["float_rim_crack"] = q_ident((1, 2), [(2, 0, 0), (0, 0, 2)], flags=FLOAT)
sg["float_near_tangent"] = q_ident((1, 2), [(0.99999994, -1, 0),
                                            (0.99999994, 1, 0)], flags=FLOAT)
sg["float_nan"] = q_ident((1, 2), [(NAN, 0, 0), (1, 0, 0)], flags=FLOAT)
# Structured tags: r = 1, lz = 2, identity; p = (r, -1, 0) with x as a copy
# of r, q = (x of p moved one ulp, 1, 0).
sg["structured_tangent_ulp"] = bytes([2]) + b"\x03\x02" + b"\x03\x05" + \
    b"\x04\x00" + b"\x03\x03" + b"\x03\x00" + \
    b"\x05\x18\x02" + b"\x03\x02" + b"\x03\x00"

# line_cylinder: the segment layout (p, q: the line through them), so every
# segment seed is a line seed too; plus the line's own cases
# (tests/line_cylinder_test.cpp): features behind p, p == q, parameters
# beyond the float / double range.
DMIN = 5e-324
ln = dict(sg)
for name, p, q in [
        ("parallel_on_side_above", (0, 1, 5), (0, 1, 6)),
        ("cylinder_behind_p", (2, 0, 0), (3, 0, 0)),
        ("oblique_through_axis", (0, 0, 0), (1, 1, 4)),
        ("through_both_rims", (0, 0, 0), (2, 0, 2)),
        ("tangent_behind_p", (1, 1, 0), (1, 2, 0)),
        ("rim_only_behind_p", (3, 0, -1), (4, 0, -2)),
        ("horizontal_above", (-2, 0, 1.5), (2, 0, 1.5)),
        ("axis_from_above", (0, 0, 3), (0, 0, 1)),
        ("p_q_2^-40_apart", (0, 0, 0), (2.0**-40, 0, 0)),
        ("p_eq_q_inside", (0, 0, 0), (0, 0, 0)),
        ("p_eq_q_on_rim", (1, 0, 1), (1, 0, 1)),
        ("p_eq_q_outside", (2, 0, 0), (2, 0, 0)),
        ("overflow_both_ends", (0, 0, 0), (DMIN, 0, 0)),
        ("huge_finite_end", (1, 0, 0), (1 - 2.0**-53, 0, 0)),
        ("huge_negative_end", (0, 0, 1), (0, 0, up(1))),
        ("tangent_at_p_subnormal_dir", (1, 0, 0), (1, DMIN, 0)),
        ("cap_plane_subnormal_dir", (0, 0, 1), (0, DMIN, 1))]:
    ln[name] = q_ident((1, 2), [p, q])
ln["one_end_overflowing"] = q_posed((1, 2), I3, (0, 0, -1),
                                    [(0, 0, 0), (0, 0, -DMIN)])
ln["one_end_overflowing_reversed"] = q_posed((1, 2), I3, (0, 0, -1),
                                             [(0, 0, -DMIN), (0, 0, 0)])
ln["singular_R_inside"] = q_posed((1, 2), [0] * 9, (5, 0, 0),
                                  [(5, 0, 0), (7, 1, 0)])
ln["huge_cylinder_subnormal_dir"] = q_ident((DMAX / 4, DMAX / 4),
                                            [(0, 0, 0), (0, 0, DMIN)])
ln["float_2^-100_apart"] = q_ident((1, 2), [(0, 0, 0), (2.0**-100, 0, 0)],
                                   flags=FLOAT)
ln["float_2^-140_apart"] = q_ident((1, 2), [(0, 0, 0), (2.0**-140, 0, 0)],
                                   flags=FLOAT)
ln["float_p_eq_q_inside"] = q_ident((1, 2), [(0.5, 0, 0), (0.5, 0, 0)],
                                    flags=FLOAT)


def write_corpus(query, seeds):
    out = os.path.join(CORPUS, query)
    if os.path.isdir(out):
        shutil.rmtree(out)
    os.makedirs(out)
    for name, data in sorted(seeds.items()):
        with open(os.path.join(out, name), "wb") as f:
            f.write(data)
    print(f"{len(seeds)} seeds in {os.path.relpath(out, ROOT)}")


# fuzz_triangle_cylinder_margin: the triangle layout, then the margin.
def with_margin(data, m):
    return data + b"\x00" + struct.pack("<f" if data[0] & 8 else "<d", m)


mg = {name + "_m0.5": with_margin(data, 0.5) for name, data in seeds.items()}
# Exact ties at distance 5/16 from the rim circle of r = 1, lz = 2: a vertex,
# an edge tangent to the tube, a face whose interior alone comes near
# (tests/triangle_cylinder_margin_test.cpp, ExactTies); at d and 1 ulp below.
for name, tri in [
        ("vertex_rim", [(1.1875, 0, 1.25), (4.1875, 1, 5.25), (4.1875, -1, 5.25)]),
        ("edge_rim", [(1.1875, -0.5, 1.25), (1.1875, 0.5, 1.25), (4.1875, 0, 5.25)]),
        ("face_rim", [(9.1875, 0, -4.75), (-6.8125, 10, 7.25), (-6.8125, -10, 7.25)])]:
    mg[name + "_tie"] = with_margin(ident((1, 2), tri), 0.3125)
    mg[name + "_one_ulp_below"] = with_margin(ident((1, 2), tri), down(0.3125))
    mg[name + "_float_tie"] = with_margin(ident((1, 2), tri, flags=2 | 8), 0.3125)
mg["corner_box_says_yes"] = with_margin(ident((1, 2), [(1.5, 0, 1.5), (3, 0, 3), (3, 1, 3)]), 0.5)
mg["perm_corner"] = with_margin(perm((1, 2), 17, (1, 2, 3), [(1.5, 0, 1.5), (3, 0, 3), (3, 1, 3)], flags=1 | 4), 0.75)
mg["margin_nan"] = with_margin(ident((1, 2), [(0, 0, 0), (1, 0, 0), (0, 1, 0)]), NAN)
mg["margin_inf"] = with_margin(ident((1, 2), [(0, 0, 0), (1, 0, 0), (0, 1, 0)]), INF)
mg["margin_negative"] = with_margin(ident((1, 2), [(0, 0, 0), (1, 0, 0), (0, 1, 0)]), -0.5)
mg["margin_minus_zero"] = with_margin(ident((1, 2), [(5, 0, 0), (6, 0, 0), (5, 1, 0)]), -0.0)
mg["margin_huge"] = with_margin(ident((1e300, 1e300), [(1.7e308, 0, 0), (1.7e308, 1, 0), (1.7e308, 0, 1)]), 1.7e308)
mg["margin_subnormal"] = with_margin(ident((1, 2), [(up(1), -1, 0), (up(1), 1, 0), (up(1), 0, 0.5)]), 5e-324)


write_corpus("triangle_cylinder", seeds)
write_corpus("triangle_cylinder_margin", mg)
write_corpus("point_cylinder", pc)
write_corpus("point_cone", pk)
write_corpus("sphere_cylinder", ss)
write_corpus("segment_cylinder", sg)
write_corpus("line_cylinder", ln)
