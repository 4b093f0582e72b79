"""The wefm wheel: the ctypes package of bindings/python with libwefm.so, built by CMake, inside it.

Metadata is in pyproject.toml; this file only builds the library and tags the wheel. Where the
library comes from (environment variables):
  WEFM_WHEEL_LIBRARY=FILE  a libwefm.so built already (linked with RUNPATH $ORIGIN), packaged as it
                      is: no CMake runs (the tests package the library they test);
  WEFM_BUILD_DIR=DIR  an existing CMake build folder of this tree: `cmake --build DIR --target wefm`
                      (nothing to do when it is up to date) and its capi/libwefm.so is packaged;
  otherwise           build/python-wheel is configured (Release; the library alone: no tool, tests
                      or bindings; WEFM_CMAKE_ARGS adds options) and its `wefm` target built.
WEFM_WHEEL_WORK names the folder setuptools works in (default build/python-setuptools), so that
concurrent builds (the tests) do not share one. The library is linked with RUNPATH $ORIGIN
(capi/CMakeLists.txt). The tag is py3-none-<platform>: ctypes needs no CPython ABI, but the .so is
made for one platform.
"""
import os
import re
import shlex
import shutil
import subprocess

from setuptools import setup
from setuptools.command.build_py import build_py
from setuptools.dist import Distribution
from wheel.bdist_wheel import bdist_wheel

ROOT = os.path.dirname(os.path.abspath(__file__))
WORK = os.environ.get("WEFM_WHEEL_WORK") or os.path.join("build", "python-setuptools")


def project_version():
    with open(os.path.join(ROOT, "CMakeLists.txt")) as f:
        found = re.search(r"project\(\s*wefm\s+VERSION\s+([0-9.]+)", f.read())
    if not found:
        raise RuntimeError("CMakeLists.txt: no project(wefm VERSION ...)")
    return found.group(1)


def run(cmd):
    print("wefm wheel:", " ".join(shlex.quote(c) for c in cmd), flush=True)
    subprocess.run(cmd, check=True)


def cmake_library():
    """Builds the `wefm` target and returns the path of the real file libwefm.so points to."""
    given = os.environ.get("WEFM_WHEEL_LIBRARY")
    if given:
        if not os.path.isfile(given):
            raise RuntimeError("WEFM_WHEEL_LIBRARY=%s: no such file" % given)
        return os.path.realpath(given)
    build_dir = os.environ.get("WEFM_BUILD_DIR")
    if build_dir:
        build_dir = os.path.abspath(build_dir)
        if not os.path.isfile(os.path.join(build_dir, "CMakeCache.txt")):
            raise RuntimeError("WEFM_BUILD_DIR=%s is not a configured CMake build folder" % build_dir)
    else:
        build_dir = os.path.join(ROOT, "build", "python-wheel")
        run(["cmake", "-S", ROOT, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release", "-DWEFM_BUILD_APPS=OFF",
             "-DWEFM_BUILD_TESTS=OFF", "-DWEFM_BUILD_BINDINGS=OFF",
             *shlex.split(os.environ.get("WEFM_CMAKE_ARGS", ""))])
    run(["cmake", "--build", build_dir, "--target", "wefm"])
    library = os.path.join(build_dir, "capi", "libwefm.so")
    if not os.path.exists(library):
        raise RuntimeError("%s: not built" % library)
    return os.path.realpath(library)


class BuildPyWithLibrary(build_py):
    """The package's sources, then libwefm.so beside them (the loader's bundled copy)."""

    def run(self):
        super().run()
        target = os.path.join(self.build_lib, "wefm", "libwefm.so")
        shutil.copyfile(cmake_library(), target)
        os.chmod(target, 0o755)


class PlatformWheel(bdist_wheel):
    """py3-none-<platform>: any CPython 3 (ctypes, no extension module), one platform's .so."""

    def finalize_options(self):
        super().finalize_options()
        self.root_is_pure = False

    def get_tag(self):
        _, _, platform = super().get_tag()
        return "py3", "none", platform


class BinaryDistribution(Distribution):
    def has_ext_modules(self):
        return True  # installs into platlib and keeps the platform tag


os.makedirs(os.path.join(ROOT, WORK), exist_ok=True)
setup(version=project_version(),
      distclass=BinaryDistribution,
      cmdclass={"build_py": BuildPyWithLibrary, "bdist_wheel": PlatformWheel},
      options={"build": {"build_base": WORK}, "egg_info": {"egg_base": WORK}})
