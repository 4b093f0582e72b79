"""The ctypes mirrors (and the Fortran bind(C) types) have the C compiler's layout.

The C and Fortran layouts come from helper programs built by CMake (tests/python/c/struct_layout.c,
tests/fortran/struct_layout.f90) whose paths ctest passes in WEFM_LAYOUT_C / WEFM_LAYOUT_FORTRAN.
The helpers and the mirrors are generated from one parse of wefm.h (scripts/gen_bindings.py); the
offsets and sizes are the C compiler's and gfortran's own, so a wrong type mapping shows here.
"""
import ctypes
import os
import subprocess
import xml.etree.ElementTree as ET

import pytest

from wefm import _structs as S

MIRRORS = S.STRUCTS  # every struct of wefm.h, as scripts/gen_bindings.py found them


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


def abi_layout():
    """Sizes and field offsets of the structs in capi/abi/wefm.abi: libabigail's reading of the
    library's debug information, pinned by the ABI check, independent of scripts/gen_bindings.py."""
    path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "capi", "abi", "wefm.abi")
    out = {}
    for decl in ET.parse(path).iter("class-decl"):
        name = decl.get("name")
        if name not in MIRRORS or decl.get("size-in-bits") is None:
            continue
        out[(name, "sizeof")] = int(decl.get("size-in-bits")) // 8
        for member in decl.iter("data-member"):
            field = member.find("var-decl").get("name")
            out[(name, field)] = int(member.get("layout-offset-in-bits")) // 8
    return out


def test_layout_matches_the_pinned_abi():
    """Every field the library was built with is mirrored, even one that would hide in padding."""
    assert abi_layout() == ctypes_layout()
