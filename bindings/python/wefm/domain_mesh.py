"""DomainMesh: the mesh of a solved domain mapped to 3D (wefm_domain_mesh)."""
import ctypes
import os

import numpy as np

from ._api import lib
from ._arrays import query
from ._handle import Handle
from ._records import MeshReport, new_mesh_report


class DomainMesh(Handle):
    """Returned by Face.mesh_domain(); a context manager like Face."""

    _release = "domain_mesh_release"

    @property
    def report(self):
        raw = new_mesh_report()
        self._call("domain_mesh_get_report", ctypes.byref(raw))
        return MeshReport.from_struct(raw)

    @property
    def uv(self):
        """Node UV, shape (n_nodes, 2)."""
        return query(lib.domain_mesh_get_uv, (self.handle,), np.float64, 2, None,
                     "wefm_domain_mesh_get_uv")

    @property
    def xyz(self):
        """Node 3D positions, shape (n_nodes, 3)."""
        return query(lib.domain_mesh_get_xyz, (self.handle,), np.float64, 3, None,
                     "wefm_domain_mesh_get_xyz")

    @property
    def elements(self):
        """Element node indices, shape (n_elements, nodes_per_element) with 3 or 4 columns."""
        width = self.report.nodes_per_element or 3
        return query(lib.domain_mesh_get_elements, (self.handle,), np.int32, width, None,
                     "wefm_domain_mesh_get_elements")

    def write_obj(self, path):
        """Write the 3D mesh as OBJ with vt = UV."""
        self._call("domain_mesh_write_obj", os.fsencode(path))
