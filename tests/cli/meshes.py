"""Small meshes for the CLI tests, written in every input format the tool reads.

Generated at test time instead of committed: a few lines of Python are easier to review than binary
STL files, and every format is derived from the same vertices and triangles so the tests can compare.
"""
import math
import struct


def patch(nx=5, ny=4):
    """A gently curved open patch (a disk): nx*ny vertices, 2*(nx-1)*(ny-1) triangles."""
    V = []
    for j in range(ny):
        for i in range(nx):
            x, y = i / (nx - 1), 0.8 * j / (ny - 1)
            V.append((x, y, 0.3 * (x - 0.5) ** 2 - 0.2 * (y - 0.4) ** 2))
    T = []
    for j in range(ny - 1):
        for i in range(nx - 1):
            a, b, c, d = j * nx + i, j * nx + i + 1, (j + 1) * nx + i + 1, (j + 1) * nx + i
            T += [(a, b, c), (a, c, d)]
    return V, T


def cylinder(n=12, m=4, radius=1.0, height=1.5):
    """An open cylinder (annulus): vertex (i, j) = i + n*j at angle 2*pi*i/n, height j. Outward normals.
    Returns V, T, the seam's vertex chain (the generator at angle 0, bottom to top) and the two circles."""
    V = [(radius * math.cos(2 * math.pi * i / n), radius * math.sin(2 * math.pi * i / n), height * j / (m - 1))
         for j in range(m) for i in range(n)]
    idx = lambda i, j: (i % n) + n * j
    T = []
    for j in range(m - 1):
        for i in range(n):
            a, b, c, d = idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1)
            T += [(a, b, c), (a, c, d)]
    seam = [idx(0, j) for j in range(m)]
    bottom = [idx(i, 0) for i in range(n)] + [idx(0, 0)]
    top = [idx(i, m - 1) for i in range(n)] + [idx(0, m - 1)]
    return V, T, seam, bottom, top


def cylinder_topology(seam, bottom, top, seam_mode=None):
    """topo.json of the cylinder cut along its seam: one loop bottom, seam, top reversed, seam reversed."""
    seam_edge = {"id": 20, "vertices": seam, "seam": True}
    if seam_mode:
        seam_edge["mode"] = seam_mode
    return {
        "edges": [{"id": 10, "vertices": bottom, "curve_type": "Circle"}, seam_edge,
                  {"id": 30, "vertices": top, "curve_type": "Circle"}],
        "loops": [[{"edge": 10, "reversed": False}, {"edge": 20, "reversed": False},
                   {"edge": 30, "reversed": True}, {"edge": 20, "reversed": True}]],
        "outer_loop": 0,
        "surface_type": "Cylinder",
    }


def write_obj(path, V, T):
    with open(path, "w") as f:
        f.writelines(f"v {x!r} {y!r} {z!r}\n" for x, y, z in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in T)


def write_off(path, V, T):
    with open(path, "w") as f:
        f.write(f"OFF\n{len(V)} {len(T)} 0\n")
        f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in V)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in T)


def write_ply(path, V, T):
    with open(path, "w") as f:
        f.write("ply\nformat ascii 1.0\n")
        f.write(f"element vertex {len(V)}\nproperty double x\nproperty double y\nproperty double z\n")
        f.write(f"element face {len(T)}\nproperty list uchar int vertex_indices\nend_header\n")
        f.writelines(f"{x!r} {y!r} {z!r}\n" for x, y, z in V)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in T)


def _normal(V, t):
    p, q, r = (V[k] for k in t)
    u = [q[i] - p[i] for i in range(3)]
    v = [r[i] - p[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    s = math.sqrt(sum(c * c for c in n)) or 1.0
    return tuple(c / s for c in n)


def write_stl_ascii(path, V, T):
    with open(path, "w") as f:
        f.write("solid patch\n")
        for t in T:
            f.write("facet normal %r %r %r\n outer loop\n" % _normal(V, t))
            for k in t:
                f.write("  vertex %r %r %r\n" % V[k])
            f.write(" endloop\nendfacet\n")
        f.write("endsolid patch\n")


def write_stl_binary(path, V, T):
    with open(path, "wb") as f:
        f.write(b"binary STL written by the wefm CLI tests".ljust(80, b" "))
        f.write(struct.pack("<I", len(T)))
        for t in T:
            f.write(struct.pack("<3f", *_normal(V, t)))
            for k in t:
                f.write(struct.pack("<3f", *V[k]))
            f.write(struct.pack("<H", 0))


WRITERS = {"obj": write_obj, "off": write_off, "ply": write_ply, "stl_ascii": write_stl_ascii,
           "stl_binary": write_stl_binary}
