"""Ownership of one reference to a ref-counted library handle."""
import ctypes

from .errors import check


class Handle:
    """Holds one reference (released by close(), the with-block exit or garbage collection)."""

    _release = None  # name of the lib release function, set by subclasses
    _errors_on_handle = False  # True when the handle has its own last-error slot (faces)

    def __init__(self, raw):
        self._raw = raw

    @property
    def handle(self):
        """The raw handle (int address) for calling libwefm directly; ValueError once closed."""
        if self._raw is None:
            raise ValueError("%s is closed" % type(self).__name__)
        return self._raw

    @property
    def closed(self):
        return self._raw is None

    def close(self):
        """Drop this object's reference; the library frees the handle at count zero. Idempotent."""
        raw, self._raw = self._raw, None
        if raw is not None:
            from ._api import lib  # late: module globals may already be gone at interpreter exit
            getattr(lib, self._release)(raw)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()
        return False

    def __del__(self):
        try:
            self.close()
        except Exception:  # never raise from a finaliser (e.g. during interpreter shutdown)
            pass

    # A copy of the object would hold the same raw pointer: two owners release it (heap corruption),
    # and in another process (multiprocessing, a pickle file) it points at nothing (a crash). The
    # data it was made from is what to send or copy.
    def _refuse_copy(self, *_args):
        raise TypeError("a wefm.%s cannot be pickled or copied: it owns a libwefm handle that is valid "
                        "only in this process and only once; pass the arrays and options it was made "
                        "from and build a new one" % type(self).__name__)

    __reduce__ = __reduce_ex__ = __getstate__ = __copy__ = __deepcopy__ = _refuse_copy

    def _call(self, name, *args):
        """Call lib.<name>(handle, *args) and raise on a non-OK status."""
        from ._api import lib
        raw = self.handle
        status = getattr(lib, name)(raw, *args)
        check(status, raw if self._errors_on_handle else None, "wefm_" + name)
        return status


def new_handle(create, *args):
    """Run a creating call whose last parameter is the out-handle; raise on failure."""
    out = ctypes.c_void_p()
    check(create(*args, ctypes.byref(out)), None, getattr(create, "__name__", ""))
    return out.value
