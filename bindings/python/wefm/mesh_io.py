"""Triangle meshes read from files or built from arrays (wefm_mesh)."""
import ctypes
import os
from ctypes import c_double, c_int32

import numpy as np

from ._api import lib
from ._arrays import ptr, query, rows
from ._handle import Handle, new_handle
from ._records import MeshInfo, new_mesh_info


class Mesh(Handle):
    """A wefm_mesh handle. Errors on it carry wefm_last_error() (meshes have no message slot)."""

    _release = "mesh_release"

    @classmethod
    def read(cls, path, merge_tolerance=0.0):
        """Read OBJ, OFF, STL or PLY (by extension). merge_tolerance applies to STL (<= 0: 1e-9)."""
        return cls(new_handle(lib.mesh_read, os.fsencode(path), float(merge_tolerance)))

    @classmethod
    def from_arrays(cls, vertices, triangles):
        xyz = rows(vertices, 3, np.float64, "vertices")
        tri = rows(triangles, 3, np.int32, "triangles")
        return cls(new_handle(lib.mesh_create, xyz.shape[0], ptr(xyz, c_double), tri.shape[0],
                              ptr(tri, c_int32)))

    @property
    def vertices(self):
        return query(lib.mesh_get_vertices, (self.handle,), np.float64, 3, None, "wefm_mesh_get_vertices")

    @property
    def triangles(self):
        return query(lib.mesh_get_triangles, (self.handle,), np.int32, 3, None, "wefm_mesh_get_triangles")

    @property
    def info(self):
        raw = new_mesh_info()
        self._call("mesh_get_info", ctypes.byref(raw))
        return MeshInfo.from_struct(raw)


def read_mesh(path, merge_tolerance=0.0):
    """Read a mesh file -> (vertices (n, 3) float64, triangles (m, 3) int32, MeshInfo)."""
    with Mesh.read(path, merge_tolerance) as mesh:
        return mesh.vertices, mesh.triangles, mesh.info


def read_seams(path):
    """The (n, 2) int64 vertex pairs of a seam file: one "i j" pair of 0-based vertex indices a line,
    '#' comments; a file holding only comments has none (an empty array). A malformed line raises
    ValueError naming the file and the line ("in.seam:2: ...")."""
    pairs = []
    with open(path) as f:
        for number, line in enumerate(f, 1):
            fields = line.split("#", 1)[0].split()
            if not fields:
                continue
            if len(fields) != 2:
                raise ValueError("%s:%d: expected two vertex indices, got %r" % (path, number, line.strip()))
            pairs.append((int(fields[0]), int(fields[1])))
    return np.array(pairs, dtype=np.int64).reshape(-1, 2)
