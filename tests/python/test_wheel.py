"""The wheel built at the repository root (pyproject.toml, setup.py): its tag, its contents, the
library's RUNPATH, and a face flattened through the installed copy.

The wheel packages the library under test (WEFM_WHEEL_LIBRARY = $WEFM_LIBRARY, set by ctest), so no
CMake build runs; setuptools works in a temporary folder (WEFM_WHEEL_WORK).
"""
import glob
import os
import subprocess
import sys
import sysconfig
import zipfile

import numpy as np
import pytest

import wefm
from conftest import bumpy_patch

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LIBRARY = os.environ.get("WEFM_LIBRARY")
READELF = os.environ.get("WEFM_READELF", "readelf")

pytestmark = pytest.mark.skipif(not LIBRARY, reason="WEFM_LIBRARY (the library to package) not set")


@pytest.fixture(scope="module")
def wheel(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("wheel")
    env = dict(os.environ, WEFM_WHEEL_LIBRARY=LIBRARY, WEFM_WHEEL_WORK=str(tmp / "work"))
    subprocess.run([sys.executable, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps", "--no-index",
                    "-q", "-w", str(tmp / "dist"), ROOT], check=True, env=env)
    found = glob.glob(str(tmp / "dist" / "*.whl"))
    assert len(found) == 1, found
    return found[0]


def runpath(path):
    out = subprocess.run([READELF, "-d", path], check=True, capture_output=True, text=True).stdout
    return [line.split("[", 1)[1].rstrip("]") for line in out.splitlines() if "(RUNPATH)" in line or "(RPATH)" in line]


def test_name_and_tag(wheel):
    platform = sysconfig.get_platform().replace("-", "_").replace(".", "_")
    # The package's version is the library's (CMake's project version; wefm_version() reports it).
    assert os.path.basename(wheel) == "wefm-%s-py3-none-%s.whl" % (wefm.__version__, platform)
    with zipfile.ZipFile(wheel) as z:
        meta = z.read("wefm-%s.dist-info/WHEEL" % wefm.__version__).decode()
    assert "Root-Is-Purelib: false" in meta
    assert "Tag: py3-none-%s" % platform in meta.splitlines()


def test_contents(wheel, tmp_path):
    sources = sorted(os.path.basename(p) for p in glob.glob(os.path.join(ROOT, "bindings", "python", "wefm", "*.py")))
    with zipfile.ZipFile(wheel) as z:
        names = z.namelist()
        z.extract("wefm/libwefm.so", tmp_path)
    package = sorted(n[len("wefm/"):] for n in names if n.startswith("wefm/"))
    assert package == sorted(sources + ["libwefm.so"])
    assert all(n.startswith(("wefm/", "wefm-")) for n in names), names
    assert any(n.endswith(".dist-info/LICENSE") for n in names)
    assert runpath(str(tmp_path / "wefm" / "libwefm.so")) == ["$ORIGIN"]


def test_installed_copy_flattens(wheel, tmp_path):
    site = tmp_path / "site"
    subprocess.run([sys.executable, "-m", "pip", "install", "--no-build-isolation", "--no-deps", "--no-index", "-q",
                    "--target", str(site), wheel], check=True)
    v, t = bumpy_patch()
    np.save(tmp_path / "v.npy", v)
    np.save(tmp_path / "t.npy", t)
    script = ("import sys, numpy as np, wefm\n"
              "r = wefm.flatten(np.load('v.npy'), np.load('t.npy'))\n"
              "np.save('uv.npy', r.uv)\n"
              "print(wefm.library_path)\n")
    env = {k: val for k, val in os.environ.items() if k not in ("WEFM_LIBRARY", "LD_LIBRARY_PATH")}
    env["PYTHONPATH"] = str(site)
    done = subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env, check=True, capture_output=True,
                          text=True)
    # The installed package loaded its own copy, not the build tree's library.
    assert done.stdout.strip() == str(site / "wefm" / "libwefm.so")
    uv = np.load(tmp_path / "uv.npy")
    assert np.array_equal(uv, wefm.flatten(v, t).uv)
