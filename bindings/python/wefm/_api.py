"""The prototypes of wefm.h (_prototypes, generated from the header) applied to the loaded library.

Handles are passed as c_void_p. Every integer and char* argument is checked before ctypes converts it
(_checked: ctypes would wrap 2**32 + 3 to 3), with the parameter's name from the header in the
message. A symbol the loaded library does not export (an older or partial build) becomes a stub
raising NotImplementedError when called, so the rest of the API stays usable.
tests/python/test_api_coverage.py checks the table against the header.
"""
from ctypes import c_char_p

from . import _loader
from ._checked import C_INTEGERS, c_integer, c_string
from ._prototypes import PROGRESS_FN, PROTOTYPES  # noqa: F401 (face.py imports both from here)


def _checked(fn, name, params, argtypes):
    """fn with its integer and char* arguments checked first (a plain call when it has none)."""
    names = params.split()
    ints = [(i, "wefm_%s: %s" % (name, names[i]), t) for i, t in enumerate(argtypes) if t in C_INTEGERS]
    strings = [(i, "wefm_%s: %s" % (name, names[i])) for i, t in enumerate(argtypes) if t is c_char_p]
    if not ints and not strings:
        return fn

    def call(*args):
        args = list(args)
        for i, what, ctype in ints:
            if i < len(args):  # a wrong count is left to ctypes' own TypeError
                args[i] = c_integer(args[i], ctype, what)
        for i, what in strings:
            if i < len(args):
                c_string(args[i], what)
        return fn(*args)

    call.__name__ = "wefm_" + name
    call.raw = fn
    return call


def _missing(name, path):
    def stub(*_args):
        raise NotImplementedError("the loaded libwefm (%s) does not export wefm_%s" % (path, name))
    stub.missing = True
    return stub


class _Lib:
    """The library with short names: lib.face_solve(h) calls wefm_face_solve(h)."""

    def __init__(self, cdll, path):
        self.cdll = cdll
        self.path = path
        self.missing = []
        for name, (restype, params, argtypes) in PROTOTYPES.items():
            try:
                fn = getattr(cdll, "wefm_" + name)
            except AttributeError:
                self.missing.append("wefm_" + name)
                setattr(self, name, _missing(name, path))
                continue
            fn.restype = restype
            fn.argtypes = argtypes
            setattr(self, name, _checked(fn, name, params, argtypes))


lib = _Lib(*_loader.load())
