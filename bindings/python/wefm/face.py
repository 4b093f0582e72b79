"""Face: one wefm_face handle with the whole face API as methods.

    with wefm.Face() as f:
        f.set_mesh(vertices, triangles)
        f.add_seams(pairs)
        report = f.solve(s=1.0)
        uv = f.uv

Not-converged policy: solve(strict=True) raises NotConvergedError, but the library keeps the best
result, so f.uv / f.report still work after catching it; solve(strict=False) issues a
NotConvergedWarning and returns the report instead.
"""
import ctypes
import warnings
from ctypes import c_double

import numpy as np

from . import _structs as S
from ._api import PROGRESS_FN, lib
from ._arrays import indices, ptr, rows
from ._constraints import ConstraintsMixin
from ._handle import Handle, new_handle
from ._results import ResultsMixin
from ._topology import TopologyMixin
from .errors import NotConvergedError, NotConvergedWarning, error_for
from .options import Options


class Face(Handle, TopologyMixin, ConstraintsMixin, ResultsMixin):
    _release = "face_release"
    _errors_on_handle = True

    def __init__(self, vertices=None, triangles=None, **options):
        super().__init__(new_handle(lib.face_create))
        self._progress = None         # the CFUNCTYPE object: must outlive every solve using it
        self._progress_error = None   # an exception raised inside the Python callback
        if vertices is not None or triangles is not None:
            self.set_mesh(vertices, triangles)
        if options:
            self.set_options(**options)

    @property
    def last_error(self):
        """wefm_face_last_error(): message of the last failing call on this face."""
        raw = lib.face_last_error(self.handle)
        return raw.decode("utf-8", "replace") if raw else ""

    # ---- mesh and options -----------------------------------------------------------------

    def set_mesh(self, vertices, triangles):
        """Set the triangulation: vertices (n, 3) float, triangles (m, 3) int32 or int64 (0-based).
        Clears topology, constraints and results."""
        xyz = rows(vertices, 3, np.float64, "vertices")
        tri = indices(triangles, 3, "triangles")
        if tri.dtype == np.int64:
            self._call("face_set_mesh_i64", xyz.shape[0], ptr(xyz, c_double), tri.shape[0],
                       ptr(tri, ctypes.c_int64))
        else:
            self._call("face_set_mesh", xyz.shape[0], ptr(xyz, c_double), tri.shape[0],
                       ptr(tri, ctypes.c_int32))

    def load(self, path, merge_tolerance=0.0):
        """Read a mesh file (OBJ, OFF, STL, PLY) straight into this face (wefm_face_set_mesh_from)."""
        from .mesh_io import Mesh
        with Mesh.read(path, merge_tolerance) as mesh:
            self._call("face_set_mesh_from", mesh.handle)

    @property
    def options(self):
        """A copy of the face's current options (an Options object)."""
        raw = Options()._struct
        self._call("face_get_options", ctypes.byref(raw))
        return Options._wrap(raw)

    @options.setter
    def options(self, value):
        self.set_options(value)

    def set_options(self, options=None, **kwargs):
        """Replace the options by `options` (an Options) updated with kwargs; with no Options,
        update the face's current options by kwargs."""
        opts = self.options if options is None else Options._wrap(options._struct)
        opts.update(**kwargs)
        self._call("face_set_options", ctypes.byref(opts._struct))

    # ---- solving --------------------------------------------------------------------------

    def set_progress_callback(self, callback):
        """callback(fraction, stage) -> truthy to cancel; None removes it.
        An exception raised by the callback cancels the solve and is re-raised by solve()."""
        if callback is None:
            self._call("face_set_progress_callback", PROGRESS_FN(), None)
            self._progress = None
            return

        def trampoline(_user, fraction, stage):
            try:
                return 1 if callback(fraction, stage.decode() if stage else "") else 0
            except BaseException as exc:  # cannot cross the C frames: stash and cancel
                self._progress_error = exc
                return 1

        fn = PROGRESS_FN(trampoline)
        self._call("face_set_progress_callback", fn, None)
        self._progress = fn

    def solve(self, strict=True, **options):
        """Flatten with the face's options updated by kwargs; returns the Report.
        See the module docstring for strict and non-convergence."""
        if options:
            self.set_options(**options)
        self._progress_error = None
        status = lib.face_solve(self.handle)
        if self._progress_error is not None:
            exc, self._progress_error = self._progress_error, None
            raise exc from error_for(status, self.handle, "wefm_face_solve")
        if status == S.ERROR_NOT_CONVERGED and not strict:
            warnings.warn(str(error_for(status, self.handle, "wefm_face_solve")),
                          NotConvergedWarning, stacklevel=2)
        elif status != S.OK:
            raise error_for(status, self.handle, "wefm_face_solve")
        return self.report

    def cancel(self):
        """Ask a solve running on another thread to stop (thread-safe; ctypes drops the GIL
        during solve, so a Python thread can call this)."""
        self._call("face_cancel")


__all__ = ["Face", "NotConvergedError"]
