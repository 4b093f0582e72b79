"""The paper's example faces (Beatty & Mukherjee 2008, §5), built analytically with numpy.

Each generator returns (xyz, triangles): a structured triangulation of a parameter rectangle mapped
onto the surface, with the diagonal of each cell alternating so no direction is favoured.
"""
import numpy as np


def _grid(nu, nv, f, keep=None):
    u, v = np.meshgrid(np.linspace(0, 1, nu + 1), np.linspace(0, 1, nv + 1))
    xyz = f(u.ravel(), v.ravel())
    vid = lambda i, j: j * (nu + 1) + i  # noqa: E731
    tris = []
    for j in range(nv):
        for i in range(nu):
            if keep is not None and not keep((i + 0.5) / nu, (j + 0.5) / nv):
                continue
            a, b, c, d = vid(i, j), vid(i + 1, j), vid(i + 1, j + 1), vid(i, j + 1)
            tris += [(a, b, c), (a, c, d)] if (i + j) % 2 == 0 else [(a, b, d), (b, c, d)]
    tris = np.array(tris, dtype=np.int32)
    used = np.unique(tris)
    remap = -np.ones(len(xyz), dtype=np.int64)
    remap[used] = np.arange(len(used))
    return np.ascontiguousarray(xyz[used]), remap[tris].astype(np.int32)


def helical_strip(nu=160, nv=24, turns=0.75, r0=0.5, r1=1.0, pitch=0.5):
    """A strip of a helicoid (ruled, doubly curved with negative Gaussian curvature): radius from r0
    to r1, `turns` turns, rising `pitch` per turn. Four corners: a transfinite domain."""
    def f(u, v):
        t = 2 * np.pi * turns * u
        r = r0 + (r1 - r0) * v
        return np.column_stack([r * np.cos(t), r * np.sin(t), pitch * t / (2 * np.pi)])
    return _grid(nu, nv, f)


def vessel_wall(nu=90, nv=90, radius=1.0, length=1.0, head_angle=np.radians(70), sweep=np.pi / 2):
    """A pressure-vessel wall patch: a quarter of the cylindrical shell joined (tangent-continuous)
    to the spherical head, up to `head_angle` from the equator. The cylinder part is developable,
    the head is not: a conformal domain makes the transfinite rail lines wave where they meet."""
    s_cyl, s_head = length, radius * head_angle
    total = s_cyl + s_head

    def f(u, v):
        s = v * total
        th = sweep * u
        r = np.where(s <= s_cyl, radius, radius * np.cos((s - s_cyl) / radius))
        z = np.where(s <= s_cyl, s, s_cyl + radius * np.sin((s - s_cyl) / radius))
        return np.column_stack([r * np.cos(th), r * np.sin(th), z])
    return _grid(nu, nv, f)


def curved_plate_with_holes(nu=150, nv=90, width=2.0, height=1.2):
    """A frame-like doubly curved plate with six rectangular windows (3 x 2), cells dropped inside
    them: straight-sided holes whose corners are the only sharp boundary vertices."""
    wins = [(0.08 + 0.31 * i, 0.12 + 0.44 * j, 0.25, 0.32) for i in range(3) for j in range(2)]

    def keep(u, v):
        return not any(x <= u <= x + w and y <= v <= y + h for x, y, w, h in wins)

    def f(u, v):
        x, y = width * u, height * v
        z = 0.35 * (x - 1) ** 2 - 0.25 * (y - 0.6) ** 2 + 0.08 * np.sin(2.5 * x) * np.cos(3 * y)
        return np.column_stack([x, y, z])
    return _grid(nu, nv, f, keep)


FACES = {
    "helical_strip": (helical_strip, "transfinite"),
    "vessel_wall": (vessel_wall, "transfinite"),
    "curved_plate_with_holes": (curved_plate_with_holes, "free"),
}
