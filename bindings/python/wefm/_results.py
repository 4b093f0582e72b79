"""Face methods reading a solve's results, mapping points, writing files and meshing the domain."""
import collections
import ctypes
import os
from ctypes import c_double, c_int32

import numpy as np

from ._api import lib
from ._arrays import ptr, query, rows
from ._records import Report, new_report
from .domain_mesh import DomainMesh
from .options import MeshOptions


class Mapped(collections.namedtuple("Mapped", "points status triangle")):
    """Result of a point mapping: points (n, 3 or 2), per-point status (WEFM_OK or
    WEFM_ERROR_OUTSIDE_DOMAIN) and containing triangle (-1 if none)."""

    @property
    def inside(self):
        return self.status == 0


class ResultsMixin:
    @property
    def has_result(self):
        solved = c_int32(0)
        self._call("face_has_result", ctypes.byref(solved))
        return bool(solved.value)

    @property
    def uv(self):
        """UV of every use, shape (n_uses, 2)."""
        return query(lib.face_get_uv, (self.handle,), np.float64, 2, self.handle, "wefm_face_get_uv")

    @property
    def edge_modes(self):
        """Resolved wefm_edge_mode per edge (non-repeated edges give EDGE_FREE)."""
        return query(lib.face_get_edge_modes, (self.handle,), np.int32, 1, self.handle,
                     "wefm_face_get_edge_modes")

    def edge_scores(self, edge):
        """Score per candidate mode of a repeated edge, indexed by wefm_edge_mode (NaN = not tried)."""
        return query(lib.face_get_edge_scores, (self.handle, edge), np.float64, 1, self.handle,
                     "wefm_face_get_edge_scores")

    @property
    def report(self):
        raw = new_report()
        self._call("face_get_report", ctypes.byref(raw))
        return Report.from_struct(raw)

    @property
    def step_history(self):
        """Per continuation step: (s, rho iterations, final rho change), shape (n_steps, 3)."""
        return query(lib.face_get_step_history, (self.handle,), np.float64, 3, self.handle,
                     "wefm_face_get_step_history")

    def _map(self, name, points, width_in, width_out):
        pts = rows(points, width_in, np.float64, "points")
        n = pts.shape[0]
        out = np.empty((n, width_out), dtype=np.float64)
        status = np.empty(n, dtype=np.int32)
        tri = np.empty(n, dtype=np.int32)
        self._call(name, n, ptr(pts, c_double), ptr(out, c_double), ptr(status, c_int32),
                   ptr(tri, c_int32))
        return Mapped(out, status, tri)

    def map_uv_to_3d(self, uv):
        """Map (n, 2) UV points to 3D. Outside points get the nearest domain point's image."""
        return self._map("face_map_uv_to_3d", uv, 2, 3)

    def map_3d_to_uv(self, xyz):
        """Map (n, 3) points to UV through the closest point of the triangulation."""
        return self._map("face_map_3d_to_uv", xyz, 3, 2)

    def write_obj(self, path):
        """Write OBJ with v (3D), vt (UV per use) and f v/vt."""
        self._call("face_write_obj", os.fsencode(path))

    # ---- meshing the domain ---------------------------------------------------------------

    def set_edge_nodes(self, edge, xyz):
        """Use these 3D nodes (n, 3; along the edge, ends included) instead of the global size."""
        nodes = rows(xyz, 3, np.float64, "xyz")
        self._call("face_set_edge_nodes", edge, nodes.shape[0], ptr(nodes, c_double))

    def clear_edge_nodes(self):
        self._call("face_clear_edge_nodes")

    def mesh_domain(self, options=None, **kwargs):
        """Mesh the solved domain: mesh_domain(size=0.1) or mesh_domain(MeshOptions(...))."""
        opts = MeshOptions(**kwargs) if options is None else MeshOptions._wrap(options._struct).update(**kwargs)
        out = ctypes.c_void_p()
        self._call("face_mesh_domain", ctypes.byref(opts._struct), ctypes.byref(out))
        return DomainMesh(out.value)
