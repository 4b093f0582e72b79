"""Shared mesh builders for the Python binding tests.

Run with: WEFM_LIBRARY=<build>/capi/libwefm.so PYTHONPATH=bindings/python /usr/bin/python3 -m pytest -q tests/python
(ctest sets both). Meshes are built here with numpy so every expected value is known exactly.
"""
import os

import numpy as np
import pytest

import wefm

DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data")


def grid_triangles(rows, cols, wrap=False):
    """Triangles of a (rows+1) x (cols+1) vertex grid, vertex (i, j) = i * (cols + 1) + j,
    counter-clockwise seen from +z for a flat grid. With wrap, column `cols` is column 0 again
    (a closed band of rows+1 rings of `cols` vertices, vertex (i, j) = i * cols + j % cols)."""
    width = cols if wrap else cols + 1

    def vid(i, j):
        return i * width + (j % cols if wrap else j)

    tris = []
    for i in range(rows):
        for j in range(cols):
            a, b, c, d = vid(i, j), vid(i, j + 1), vid(i + 1, j + 1), vid(i + 1, j)
            tris += [(a, b, c), (a, c, d)]
    return np.array(tris, dtype=np.int32)


def flat_square(n=6):
    """Unit square in z = 0 as an n x n grid."""
    u, v = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    xyz = np.column_stack([u.ravel(), v.ravel(), np.zeros(u.size)])
    return xyz, grid_triangles(n, n)


def cylinder(rings=5, sectors=16, radius=1.0, height=2.0, cut=True):
    """A cylinder band; cut=True duplicates the first column of vertices as column `sectors`, so
    the band is a disk (cut open along a generator); cut=False gives the closed annulus."""
    cols = sectors + 1 if cut else sectors
    theta = 2 * np.pi * np.arange(cols) / sectors
    z = np.linspace(0, height, rings + 1)
    t, zz = np.meshgrid(theta, z)
    xyz = np.column_stack([radius * np.cos(t).ravel(), radius * np.sin(t).ravel(), zz.ravel()])
    return xyz, grid_triangles(rings, sectors, wrap=not cut)


def bumpy_patch(n=10):
    """A doubly curved patch: not developable, so the solve iterates (rho fixed point)."""
    u, v = np.meshgrid(np.linspace(0, 1, n + 1), np.linspace(0, 1, n + 1))
    z = 0.3 * np.sin(2.0 * u) * np.cos(3.0 * v)
    return np.column_stack([u.ravel(), v.ravel(), z.ravel()]), grid_triangles(n, n)


def seam_pairs(rings, sectors):
    """Facet edges along the generator theta = 0 of the closed cylinder(cut=False)."""
    return np.array([(i * sectors, (i + 1) * sectors) for i in range(rings)], dtype=np.int32)


def requires(symbol):
    """Skip (visibly) when the loaded library does not export `symbol` yet."""
    return pytest.mark.skipif("wefm_" + symbol in wefm._lib.missing,
                              reason="libwefm has no wefm_%s" % symbol)


@pytest.fixture
def pyramid_path():
    return os.path.join(DATA, "pyramid5.obj")
