"""wefm: Python bindings (ctypes, pure Python) of the Weighted Edge Flattening Method library.

The shared library is found through $WEFM_LIBRARY, a copy next to this package, the build tree of
a source checkout, or the system search path (see wefm._loader).
"""
from . import _structs
from ._api import lib as _lib
from ._records import MeshInfo, MeshReport, Report
from ._structs import (EDGE_AUTO, EDGE_FREE, EDGE_PERIODIC, EDGE_ROTATIONAL, EDGE_SCAR, FALLBACK_GRID_REFUSED,
                       FALLBACK_NONE, FALLBACK_NOT_FOUR_SIDED, FALLBACK_POOR_GRID, MESH_AUTO, MESH_FREE,
                       MESH_TRANSFINITE, METHOD_GLOBAL, METHOD_ROLLOUT, SOLVER_AUTO, SOLVER_CHOLMOD,
                       SOLVER_EIGEN)
from ._version import FALLBACK_VERSION
from .domain_mesh import DomainMesh
from .errors import (BufferTooSmallError, CancelledError, InternalError, InvalidArgumentError,
                     InvalidConstraintError, InvalidMeshError, InvalidStateError,
                     InvalidTopologyError, NotConvergedError, NotConvergedWarning,
                     NotPositiveDefiniteError, NullArgumentError, OutOfMemoryError,
                     OutOfRangeError, OutsideDomainError, SingularError, UnsupportedError,
                     WefmError, WefmIOError, status_name)
from ._loader import LibraryNotFoundError
from .face import Face
from .flatten import FlattenResult, flatten
from .mesh_io import Mesh, read_mesh, read_seams
from .options import MeshOptions, Options


def _library_version():
    raw = _lib.version()
    return raw.decode() if raw else FALLBACK_VERSION


__version__ = _library_version()
library_path = _lib.path
"""The path or name libwefm was loaded from."""


def has_suitesparse():
    """True if the loaded library factorises with SuiteSparse CHOLMOD."""
    return bool(_lib.has_suitesparse())


def version_number():
    """The library's WEFM_VERSION_NUMBER (MAJOR*10000 + MINOR*100 + PATCH)."""
    return _lib.version_number()
