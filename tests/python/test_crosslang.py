"""The same face solved from C, Python and Fortran gives the same UVs (to 1e-12).

C and Fortran run as helper programs (paths in WEFM_CROSSLANG_C / WEFM_CROSSLANG_FORTRAN, set by
ctest) on a mesh written here; each writes its UVs with 17 significant digits.
"""
import os
import subprocess

import numpy as np
import pytest

import wefm
from conftest import bumpy_patch

TOLERANCE = 1e-12


def write_mesh(path, xyz, tri):
    with open(path, "w") as f:
        f.write("%d %d\n" % (len(xyz), len(tri)))
        np.savetxt(f, xyz, fmt="%.17g")
        np.savetxt(f, tri, fmt="%d")


def solve_with(env_var, mesh, out):
    exe = os.environ.get(env_var)
    if not exe:
        pytest.skip("%s not set (ctest sets it to the built helper)" % env_var)
    subprocess.run([exe, str(mesh), str(out)], check=True, timeout=120)
    return np.loadtxt(out, ndmin=2)


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    xyz, tri = bumpy_patch()
    mesh = tmp_path_factory.mktemp("crosslang") / "mesh.txt"
    write_mesh(mesh, xyz, tri)
    with wefm.Face() as f:
        f.set_mesh(xyz, tri)
        f.solve()
        return mesh, f.uv


@pytest.mark.parametrize("env_var", ["WEFM_CROSSLANG_C", "WEFM_CROSSLANG_FORTRAN"])
def test_same_uv_as_python(case, env_var, tmp_path):
    mesh, uv_python = case
    uv_other = solve_with(env_var, mesh, tmp_path / "uv.txt")
    assert uv_other.shape == uv_python.shape
    diff = np.abs(uv_other - uv_python).max()
    print("%s: max |UV difference| vs Python = %.3g" % (env_var, diff))
    assert diff <= TOLERANCE
