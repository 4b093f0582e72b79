"""scripts/gen_bindings.py: a field added to wefm.h reaches every generated file, the check catches a
stale file, and declarations it cannot map stop it with a message naming them."""
import os
import re
import subprocess
import sys

import pytest

from wefm import _structs as S
from wefm.options import EDGE_MODE_NAMES

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")
GENERATOR = os.path.join(ROOT, "scripts", "gen_bindings.py")
HEADER = os.path.join(ROOT, "capi", "include", "wefm", "wefm.h")
OUTPUTS = ["bindings/python/wefm/_structs.py", "bindings/python/wefm/_prototypes.py",
           "bindings/fortran/wefm_types.inc", "bindings/fortran/wefm_interfaces.inc",
           "tests/python/c/struct_layout.c", "tests/fortran/struct_layout.f90"]


def run(*args):
    return subprocess.run([sys.executable, GENERATOR] + list(args), capture_output=True, text=True)


def header_with(tmp_path, old, new):
    with open(HEADER) as f:
        text = f.read()
    assert old in text
    path = tmp_path / "wefm.h"
    path.write_text(text.replace(old, new, 1))
    return str(path)


def test_a_new_report_field_reaches_every_struct_mirror(tmp_path):
    header = header_with(tmp_path, "} wefm_report;", "  int64_t test_only_field;\n} wefm_report;")
    out = tmp_path / "out"
    assert run("--header", header, "--out", str(out)).returncode == 0
    for rel in ["bindings/python/wefm/_structs.py", "bindings/fortran/wefm_types.inc",
                "tests/python/c/struct_layout.c", "tests/fortran/struct_layout.f90"]:
        assert "test_only_field" in (out / rel).read_text(), rel
    structs = (out / "bindings/python/wefm/_structs.py").read_text()
    assert re.search(r'\("abandoned_steps", c_int32\),\n\s+\("test_only_field", c_int64\),\n\s+\]', structs)


def test_check_passes_on_fresh_output_and_fails_with_a_diff_on_stale(tmp_path):
    out = tmp_path / "out"
    assert run("--out", str(out)).returncode == 0
    assert sorted(str(p.relative_to(out)) for p in out.rglob("*") if p.is_file()) == sorted(OUTPUTS)
    assert run("--check", "--out", str(out)).returncode == 0
    inc = out / "bindings/fortran/wefm_types.inc"
    inc.write_text(inc.read_text().replace("WEFM_ERROR_INTERNAL = 99", "WEFM_ERROR_INTERNAL = 98"))
    stale = run("--check", "--out", str(out))
    assert stale.returncode == 1
    assert "-integer(c_int), parameter :: WEFM_ERROR_INTERNAL = 98" in stale.stdout
    assert "+integer(c_int), parameter :: WEFM_ERROR_INTERNAL = 99" in stale.stdout
    assert "1 generated file(s) are stale" in stale.stdout


def test_check_reports_a_missing_output(tmp_path):
    out = tmp_path / "out"
    assert run("--out", str(out)).returncode == 0
    os.remove(out / "bindings/python/wefm/_prototypes.py")
    stale = run("--check", "--out", str(out))
    assert stale.returncode == 1 and "+++ generated/bindings/python/wefm/_prototypes.py" in stale.stdout


@pytest.mark.parametrize("old, new, message", [
    ("} wefm_report;", "  float test_only_field;\n} wefm_report;", "field type 'float' of 'float test_only_field'"),
    ("WEFM_API wefm_status wefm_face_cancel(wefm_face* face);",
     "WEFM_API wefm_status wefm_face_cancel(wefm_face* face, double* weights);",
     "wefm_face_cancel: parameter weights: double* is one output value or an array?"),
    ("WEFM_API wefm_status wefm_face_cancel(wefm_face* face);",
     "WEFM_API wefm_status wefm_face_cancel(wefm_face* face, long double x);",
     "wefm_face_cancel: cannot read the declaration 'long double x'"),
    ("WEFM_API wefm_status wefm_face_cancel(wefm_face* face);",
     "WEFM_API float wefm_face_cancel(wefm_face* face);",
     "wefm_face_cancel: return type 'float' has no mapping"),
])
def test_declarations_it_cannot_map_stop_it_with_their_name(tmp_path, old, new, message):
    out = tmp_path / "out"
    result = run("--header", header_with(tmp_path, old, new), "--out", str(out))
    assert result.returncode == 2
    assert message in result.stderr
    assert not out.exists()  # nothing half-written


def test_a_missing_header_is_an_error_not_a_traceback(tmp_path):
    result = run("--header", str(tmp_path / "none.h"), "--out", str(tmp_path / "out"))
    assert result.returncode == 2 and "none.h" in result.stderr and "Traceback" not in result.stderr


def test_edge_mode_names_follow_the_generated_enum():
    for name in EDGE_MODE_NAMES:
        assert EDGE_MODE_NAMES[getattr(S, "EDGE_" + name.upper())] == name
    assert len(EDGE_MODE_NAMES) == len([n for n in dir(S) if n.startswith("EDGE_")])
