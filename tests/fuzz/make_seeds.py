#!/usr/bin/env python3
"""Writes the seed corpus of the fuzz targets (tests/fuzz/corpus/*). Re-run after changing the input
layout of a target; the files are committed so the replay tests and scripts/fuzz.sh need no Python."""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def write(target, name, data):
    d = os.path.join(HERE, "corpus", target)
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, name), "wb") as f:
        f.write(bytes(data))


# ---- fuzz_capi: mesh, options, then operations (see fuzz_capi.cpp) ----
def grid(mode, w, h, bend=32, diag=0, mutations=()):
    b = [mode, w - 1, h - 1, bend] + [diag] * (w * h) + [len(mutations)]
    for m in mutations:
        b += m
    return b + [0]  # set_mesh through wefm_face_set_mesh


NO_OPTS = [0]
SOLVE = [10, 1]
QUERIES = [12, 1, 1, 1, 1]

write("capi", "grid_solve", grid(1, 3, 3) + NO_OPTS + SOLVE + QUERIES)
write("capi", "grid_s0_queries", grid(1, 4, 2) + [1, 0, 6] + SOLVE + QUERIES + [17])
write("capi", "annulus_seams", grid(3, 6, 2) + NO_OPTS + [2, 1, 1, 7, 7, 13] + SOLVE + QUERIES)
write("capi", "annulus_no_cut", grid(3, 5, 1) + NO_OPTS + SOLVE + [9])
write("capi", "pin_constraint", grid(1, 3, 3) + NO_OPTS + [5, 1, 7, 7, 7, 7, 7] + [6, 1, 1, 2, 7, 100, 7, 100, 7, 120, 7, 128, 7, 128, 7, 128] + SOLVE + QUERIES)
write("capi", "contradictory_pins", grid(1, 2, 2) + NO_OPTS + [5, 3, 7, 128, 7, 128, 5, 3, 7, 140, 7, 128] + SOLVE)
write("capi", "rollout", grid(2, 3, 3) + [1, 4, 2] + SOLVE + QUERIES)
write("capi", "edges_loops", grid(1, 2, 2) + NO_OPTS + [0, 2, 1, 2, 3, 1, 1, 0, 0, 1, 9] + SOLVE)
write("capi", "cancel_callback", grid(1, 3, 3) + NO_OPTS + [10, 0, 3] + QUERIES)
write("capi", "mutated", grid(1, 3, 3, mutations=[[0, 5, 0], [1, 7, 200]]) + NO_OPTS + SOLVE)
write("capi", "raw", [0, 3, 1] + [7, 130] * 18 + [1, 2, 3] + NO_OPTS + SOLVE)
write("capi", "i64_and_mesh_handle", grid(1, 2, 2)[:-1] + [1] + NO_OPTS + [15] + grid(1, 3, 2)[:-1] + [2] + SOLVE + QUERIES)

# ---- fuzz_mesh_read: extension byte (obj off stl ply), tolerance byte, file ----
EXT = {"obj": 0, "off": 1, "stl": 2, "ply": 3}


def mesh_file(name, ext, text, tol=0):
    data = text.encode() if isinstance(text, str) else text
    write("mesh_read", name, [EXT[ext], tol] + list(data))


QUAD = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0.2)]
mesh_file("obj_quad", "obj", "# quad\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0.2\nf 1 2 3 4\n")
mesh_file("obj_slashes", "obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2/1/1 3/1/1\nf -3 -1 -2\n")
mesh_file("obj_grid", "obj", "".join(f"v {i} {j} {0.1 * i * j}\n" for j in range(3) for i in range(3)) +
          "".join(f"f {j*3+i+1} {j*3+i+2} {j*3+i+5} {j*3+i+4}\n" for j in range(2) for i in range(2)))
mesh_file("off_quad", "off", "OFF\n4 1 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0.2\n4 0 1 2 3\n")
mesh_file("off_tris", "off", "OFF\n# c\n5 3 0\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0.5 2 0\n3 0 1 2\n3 0 2 3\n3 3 2 4\n")
mesh_file("ply_ascii", "ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
          "element face 2\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n3 0 1 2\n3 0 2 3\n")
ply_bin = (b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
           b"element face 1\nproperty list uchar int vertex_indices\nend_header\n" +
           struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + struct.pack("<B3i", 3, 0, 1, 2))
mesh_file("ply_binary", "ply", ply_bin)
stl_tris = [((0, 0, 0), (1, 0, 0), (1, 1, 0)), ((0, 0, 0), (1, 1, 0), (0, 1, 0))]
mesh_file("stl_ascii", "stl", "solid t\n" + "".join(
    "facet normal 0 0 1\nouter loop\n" + "".join(f"vertex {x} {y} {z}\n" for x, y, z in t) + "endloop\nendfacet\n"
    for t in stl_tris) + "endsolid t\n", tol=3)
stl_bin = b"\0" * 80 + struct.pack("<I", len(stl_tris)) + b"".join(
    struct.pack("<3f", 0, 0, 1) + b"".join(struct.pack("<3f", *v) for v in t) + b"\0\0" for t in stl_tris)
mesh_file("stl_binary", "stl", stl_bin, tol=200)
