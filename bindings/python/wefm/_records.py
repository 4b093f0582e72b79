"""Struct init and read-only Python records (dataclasses) built from the ctypes mirrors.

The records are generated from the mirrors' field lists, so a field added to a mirror shows up in
the record without a second list to keep in sync.
"""
import ctypes
import dataclasses

from . import _structs as S
from ._api import lib
from .errors import check

# wefm_*_init takes the size of the struct as the caller sees it (here: the ctypes mirror) and
# writes no more than that, so an older mirror is never overrun by a newer library.
def initialised(cls, init_fn):
    out = cls()
    check(init_fn(ctypes.byref(out), ctypes.sizeof(cls)), function=getattr(init_fn, "__name__", ""))
    return out


def struct_to_dict(struct):
    """Plain-Python copy of a struct's fields (arrays become tuples), without struct_size."""
    out = {}
    for name, _ in struct._fields_:
        if name == "struct_size":
            continue
        value = getattr(struct, name)
        out[name] = tuple(value) if isinstance(value, ctypes.Array) else value
    return out


def _record(name, struct_cls, doc):
    fields = []
    for field, ctype in struct_cls._fields_:
        if field == "struct_size":
            continue
        kind = tuple if issubclass(ctype, ctypes.Array) else (float if ctype is ctypes.c_double else int)
        fields.append((field, kind))
    cls = dataclasses.make_dataclass(name, fields, frozen=True)
    cls.__doc__ = doc
    cls.__module__ = "wefm"
    cls.as_dict = dataclasses.asdict
    cls.from_struct = classmethod(lambda c, st: c(**struct_to_dict(st)))
    return cls


Report = _record("Report", S.Report, "Quality and cost of a solve (struct wefm_report).")
MeshInfo = _record("MeshInfo", S.MeshInfo, "What a user checks before flattening (struct wefm_mesh_info).")
MeshReport = _record("MeshReport", S.MeshReport, "Quality of a domain mesh (struct wefm_mesh_report).")


def new_report():
    return initialised(S.Report, lib.report_init)


def new_mesh_info():
    return initialised(S.MeshInfo, lib.mesh_info_init)


def new_mesh_report():
    return initialised(S.MeshReport, lib.mesh_report_init)
