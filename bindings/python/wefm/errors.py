"""wefm_status codes as Python exceptions.

Every non-OK status raises a subclass of WefmError carrying .status (the int), .status_name
("WEFM_ERROR_...") and .message (the handle's wefm_face_last_error(), or the thread-local
wefm_last_error() for calls without a handle).
"""
from . import _structs as S
from ._api import lib


class WefmError(Exception):
    """Base of every error raised by the wefm bindings for a failing library call."""

    def __init__(self, status, message="", function=""):
        self.status = int(status)
        self.status_name = status_name(status)
        self.message = message
        self.function = function
        where = "%s: " % function if function else ""
        super().__init__("%s%s: %s" % (where, self.status_name, message or "(no message)"))

    def __reduce__(self):
        # Exception's default would call __init__ with the formatted text only (a worker's error
        # could then not be unpickled by multiprocessing); attributes such as .result follow.
        return (type(self), (self.status, self.message, self.function), self.__dict__)


class NullArgumentError(WefmError):
    """WEFM_ERROR_NULL_ARGUMENT: a bug in the bindings if it ever surfaces."""


class InvalidArgumentError(WefmError, ValueError):
    """WEFM_ERROR_INVALID_ARGUMENT."""


class OutOfRangeError(WefmError, IndexError):
    """WEFM_ERROR_OUT_OF_RANGE: an index is negative or past the end."""


class BufferTooSmallError(WefmError):
    """WEFM_ERROR_BUFFER_TOO_SMALL: a bug in the bindings if it ever surfaces (they size buffers)."""


class InvalidStateError(WefmError):
    """WEFM_ERROR_INVALID_STATE: call out of order (solve before a mesh, query before solve)."""


class InvalidMeshError(WefmError, ValueError):
    """WEFM_ERROR_INVALID_MESH: NaN, bad indices, degenerate/duplicate/non-manifold input."""


class InvalidTopologyError(WefmError, ValueError):
    """WEFM_ERROR_INVALID_TOPOLOGY: edges, loops or seams that do not match the mesh."""


class InvalidConstraintError(WefmError, ValueError):
    """WEFM_ERROR_INVALID_CONSTRAINT."""


class SingularError(WefmError):
    """WEFM_ERROR_SINGULAR: contradictory or insufficient constraints."""


class NotPositiveDefiniteError(WefmError):
    """WEFM_ERROR_NOT_POSITIVE_DEFINITE."""


class NotConvergedError(WefmError):
    """WEFM_ERROR_NOT_CONVERGED: an iteration cap was reached but the best result was kept.

    The result stays on the Face (face.uv, face.report, ...); wefm.flatten() attaches it to the
    exception as .result. Pass strict=False to solve()/flatten() to get a warning instead.
    """
    result = None


class CancelledError(WefmError):
    """WEFM_ERROR_CANCELLED: by Face.cancel() or a progress callback returning True."""


class OutOfMemoryError(WefmError, MemoryError):
    """WEFM_ERROR_OUT_OF_MEMORY."""


class WefmIOError(WefmError, OSError):
    """WEFM_ERROR_IO: a file could not be read or written."""


class UnsupportedError(WefmError):
    """WEFM_ERROR_UNSUPPORTED: a format or feature not in this build."""


class OutsideDomainError(WefmError):
    """WEFM_ERROR_OUTSIDE_DOMAIN (normally reported per point, not raised)."""


class InternalError(WefmError):
    """WEFM_ERROR_INTERNAL: a library bug; please report it with the message."""


class NotConvergedWarning(UserWarning):
    """Issued instead of NotConvergedError when strict=False."""


_BY_STATUS = {
    S.ERROR_NULL_ARGUMENT: NullArgumentError,
    S.ERROR_INVALID_ARGUMENT: InvalidArgumentError,
    S.ERROR_OUT_OF_RANGE: OutOfRangeError,
    S.ERROR_BUFFER_TOO_SMALL: BufferTooSmallError,
    S.ERROR_INVALID_STATE: InvalidStateError,
    S.ERROR_INVALID_MESH: InvalidMeshError,
    S.ERROR_INVALID_TOPOLOGY: InvalidTopologyError,
    S.ERROR_INVALID_CONSTRAINT: InvalidConstraintError,
    S.ERROR_SINGULAR: SingularError,
    S.ERROR_NOT_POSITIVE_DEFINITE: NotPositiveDefiniteError,
    S.ERROR_NOT_CONVERGED: NotConvergedError,
    S.ERROR_CANCELLED: CancelledError,
    S.ERROR_OUT_OF_MEMORY: OutOfMemoryError,
    S.ERROR_IO: WefmIOError,
    S.ERROR_UNSUPPORTED: UnsupportedError,
    S.ERROR_OUTSIDE_DOMAIN: OutsideDomainError,
    S.ERROR_INTERNAL: InternalError,
}


def status_name(status):
    name = lib.status_string(int(status))
    return name.decode("utf-8", "replace") if name else "WEFM_ERROR_UNKNOWN"


def _decode(raw):
    return raw.decode("utf-8", "replace") if raw else ""


def error_for(status, handle=None, function=""):
    """The exception for `status`, with the message of face handle `handle`, else the thread-local one.

    No fallback from an empty face message to wefm_last_error(): that slot may hold a stale message
    from an unrelated earlier call. wefm_mesh_* and wefm_domain_mesh_* have no per-handle message, so
    their callers pass handle=None.
    """
    message = _decode(lib.face_last_error(handle)) if handle else _decode(lib.last_error())
    return _BY_STATUS.get(int(status), WefmError)(status, message, function)


def check(status, handle=None, function=""):
    """Raise unless status is WEFM_OK. `handle` is a face handle whose message to use, or None."""
    if status != S.OK:
        raise error_for(status, handle, function)
