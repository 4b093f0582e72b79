"""Face methods for the topology (edges, loops, seams, edge modes) and the vertex uses."""
import ctypes
from ctypes import c_int32, c_int64

import numpy as np

from ._api import lib
from ._arrays import int32_list, ptr, query, rows
from .options import edge_mode_value


class TopologyMixin:
    def clear_topology(self):
        """Back to the derived topology (boundary cycles, no seams)."""
        self._call("face_clear_topology")

    def add_edge(self, chain):
        """Add an edge as a chain of vertex indices along facet edges; returns its id."""
        chain = int32_list(chain, "chain")
        edge_id = c_int32(-1)
        self._call("face_add_edge", chain.size, ptr(chain, c_int32), ctypes.byref(edge_id))
        return edge_id.value

    def add_loop(self, edges, reversed=None):
        """Add a loop of edge uses (face on the left); reversed[j] true traverses edges[j] backwards."""
        edges = int32_list(edges, "edges")
        flags = None
        if reversed is not None:
            flags = int32_list(np.asarray(reversed, dtype=bool).astype(np.int32), "reversed")
            if flags.size != edges.size:
                raise ValueError("reversed has %d entries for %d edges" % (flags.size, edges.size))
        loop_id = c_int32(-1)
        self._call("face_add_loop", edges.size, ptr(edges, c_int32), ptr(flags, c_int32),
                   ctypes.byref(loop_id))
        return loop_id.value

    def set_outer_loop(self, loop):
        """Designate the outer loop (a loop id, or a boundary-cycle index); -1 = automatic."""
        self._call("face_set_outer_loop", loop)

    def add_seams(self, vertex_pairs):
        """Cut along facet edges given as an (n, 2) array of vertex indices."""
        pairs = rows(vertex_pairs, 2, np.int32, "vertex_pairs")
        self._call("face_add_seams", pairs.shape[0], ptr(pairs, c_int32))

    def set_edge_mode(self, edge, mode):
        """Force the mode of a repeated edge: wefm.EDGE_* or "free"/"periodic"/"scar"/"rotational"."""
        self._call("face_set_edge_mode", edge, edge_mode_value(mode))

    def build(self):
        """Build and validate the topology and vertex uses now (solve does it too)."""
        self._call("face_build")

    def _count(self, name):
        n = c_int64(0)
        self._call(name, ctypes.byref(n))
        return n.value

    def edge_count(self):
        return self._count("face_edge_count")

    def edge(self, edge):
        """Vertex chain of one edge."""
        return query(lib.face_get_edge, (self.handle, edge), np.int32, 1, self.handle,
                     "wefm_face_get_edge")

    def edges(self):
        """Vertex chains of all edges."""
        return [self.edge(e) for e in range(self.edge_count())]

    def edge_is_repeated(self, edge):
        flag = c_int32(0)
        self._call("face_edge_is_repeated", edge, ctypes.byref(flag))
        return bool(flag.value)

    def loop_count(self):
        return self._count("face_loop_count")

    def loop(self, loop):
        """Edge uses of a loop as an (n, 2) array of (edge id, reversed flag)."""
        return query(lib.face_get_loop, (self.handle, loop), np.int32, 2, self.handle,
                     "wefm_face_get_loop")

    def loop_uses(self, loop):
        """Vertex uses along a loop in order (face on the left)."""
        return query(lib.face_get_loop_uses, (self.handle, loop), np.int32, 1, self.handle,
                     "wefm_face_get_loop_uses")

    def outer_loop(self):
        loop = c_int32(-1)
        self._call("face_outer_loop", ctypes.byref(loop))
        return loop.value

    # ---- vertex uses (the unknowns) -------------------------------------------------------

    def use_count(self):
        return self._count("face_use_count")

    @property
    def use_vertex(self):
        """The vertex of every use, shape (n_uses,)."""
        return query(lib.face_get_use_vertices, (self.handle,), np.int32, 1, self.handle,
                     "wefm_face_get_use_vertices")

    @property
    def triangle_uses(self):
        """The uses of every triangle in corner order, shape (n_triangles, 3)."""
        return query(lib.face_get_triangle_uses, (self.handle,), np.int32, 3, self.handle,
                     "wefm_face_get_triangle_uses")

    def vertex_uses(self, vertex):
        """The uses of one vertex (several when it lies on a repeated edge)."""
        return query(lib.face_get_vertex_uses, (self.handle, vertex), np.int32, 1, self.handle,
                     "wefm_face_get_vertex_uses")
