"""Every function of wefm.h is declared in the ctypes table and the Fortran module."""
import os
import re

from wefm._api import PROTOTYPES

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def header_functions():
    with open(os.path.join(ROOT, "capi", "include", "wefm", "wefm.h")) as f:
        text = f.read()
    return set(re.findall(r"^WEFM_API\b[^(;]*?\b(wefm_\w+)\s*\(", text, re.M))


def test_header_parse_found_the_api():
    names = header_functions()
    assert {"wefm_face_solve", "wefm_domain_mesh_write_obj", "wefm_options_init"} <= names
    assert len(names) > 60


def test_ctypes_table_matches_the_header():
    assert {"wefm_" + n for n in PROTOTYPES} == header_functions()


def test_fortran_module_binds_every_function():
    path = os.path.join(ROOT, "bindings", "fortran", "wefm_interfaces.inc")
    with open(path) as f:
        bound = set(re.findall(r'bind\(C,\s*name="(wefm_\w+)"\)', f.read()))
    assert bound == header_functions()


def header_parameters():
    """{function: [parameter names]} of wefm.h (comments removed)."""
    with open(os.path.join(ROOT, "capi", "include", "wefm", "wefm.h")) as f:
        text = re.sub(r"/\*.*?\*/", "", f.read(), flags=re.S)
    out = {}
    for m in re.finditer(r"^WEFM_API\b[^(;]*?\b(wefm_\w+)\s*\(([^)]*)\)", text, re.M):
        params = m.group(2).strip()
        out[m.group(1)] = [] if params in ("", "void") else [re.findall(r"\w+", p)[-1]
                                                            for p in params.split(",")]
    return out


def test_ctypes_table_names_and_counts_every_parameter_as_the_header():
    """The names appear in the binding's range errors; the counts keep argtypes complete."""
    header = header_parameters()
    for name, (_, params, argtypes) in PROTOTYPES.items():
        assert params.split() == header["wefm_" + name], name
        assert len(argtypes) == len(params.split()), name
