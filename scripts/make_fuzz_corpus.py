#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets (fuzz/corpus/<query>/).

Each seed uses the plainest encoding of fuzz/fuzz_input.h: a flags byte, then
every scalar as tag 0 + its raw little-endian bit pattern (8 bytes for double,
4 for float). Flags: 0 = free R (9 scalars), 1 = signed axis permutation (one
byte), 2 = identity pose; +4 = triangle given in the cylinder frame; +8 =
float. Scalar order: radius, lz, R (if free), t (not in mode 2), a, b, c.

Usage: python3 scripts/make_fuzz_corpus.py   (rewrites the directory)
"""
import math
import os
import shutil
import struct

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
OUT = os.path.join(ROOT, "fuzz", "corpus", "triangle_cylinder")
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

if os.path.isdir(OUT):
    shutil.rmtree(OUT)
os.makedirs(OUT)
for name, data in sorted(seeds.items()):
    with open(os.path.join(OUT, name), "wb") as f:
        f.write(data)
print(f"{len(seeds)} seeds in {os.path.relpath(OUT, ROOT)}")
