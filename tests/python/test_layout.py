"""The ctypes mirrors (and the Fortran bind(C) types) have the C compiler's layout.

The C and Fortran layouts come from helper programs built by CMake (tests/python/c/struct_layout.c,
tests/fortran/struct_layout.f90) whose paths ctest passes in WEFM_LAYOUT_C / WEFM_LAYOUT_FORTRAN.
"""
import ctypes
import os
import subprocess

import pytest

from wefm import _structs as S

MIRRORS = {"wefm_options": S.Options, "wefm_mesh_info": S.MeshInfo, "wefm_report": S.Report,
           "wefm_mesh_options": S.MeshOptions, "wefm_mesh_report": S.MeshReport}


def ctypes_layout():
    out = {}
    for name, cls in MIRRORS.items():
        out[(name, "sizeof")] = ctypes.sizeof(cls)
        for field, _ in cls._fields_:
            out[(name, field)] = getattr(cls, field).offset
    return out


def program_layout(env_var):
    exe = os.environ.get(env_var)
    if not exe:
        pytest.skip("%s not set (ctest sets it to the built helper)" % env_var)
    text = subprocess.run([exe], check=True, capture_output=True, text=True).stdout
    out = {}
    for line in text.splitlines():
        struct, field, value = line.split()
        out[(struct, field)] = int(value)
    return out


@pytest.mark.parametrize("env_var", ["WEFM_LAYOUT_C", "WEFM_LAYOUT_FORTRAN"])
def test_layout_matches(env_var):
    assert program_layout(env_var) == ctypes_layout()
