"""Struct init and read-only Python records (dataclasses) built from the ctypes mirrors.

The records are generated from the mirrors' field lists, so a field added to a mirror shows up in
the record without a second list to keep in sync.
"""
import ctypes
import dataclasses

from . import _structs as S
from ._api import lib

# wefm_*_init writes sizeof(struct) as the *library* was compiled. A newer library with a grown struct
# would write past a mirror sized for an older header, so let it write into a roomy scratch buffer
# and keep only the bytes this package knows, then claim exactly that size.
_SLACK = 4096


def initialised(cls, init_fn):
    scratch = (ctypes.c_char * (ctypes.sizeof(cls) + _SLACK))()
    init_fn(ctypes.cast(scratch, ctypes.POINTER(cls)))
    out = cls.from_buffer_copy(scratch)
    out.struct_size = ctypes.sizeof(cls)
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
    cls.from_struct = classmethod(lambda c, st: c(**S.struct_to_dict(st)))
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
