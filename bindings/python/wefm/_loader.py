"""Find and load libwefm.

Order (first that loads wins):
  1. $WEFM_LIBRARY, a path to the shared library (ctest sets it to the freshly built target);
  2. a libwefm.so* next to this package (a copy bundled by WEFM_PYTHON_BUNDLE_LIBRARY or by hand);
  3. the build trees of the source checkout this package sits in (bindings/python/wefm -> repo root):
     build*/capi and build/*/capi (the CMake presets), newest first;
  4. ctypes.util.find_library("wefm") and the plain soname on the system search path.
"""
import ctypes
import ctypes.util
import glob
import os


class LibraryNotFoundError(ImportError):
    """libwefm could not be loaded; `tried` lists every candidate with the reason it failed."""

    def __init__(self, tried):
        self.tried = tried
        lines = ["could not load libwefm; tried (set WEFM_LIBRARY=/path/to/libwefm.so):"]
        lines += ["  %s: %s" % (path, why) for path, why in tried]
        super().__init__("\n".join(lines))

    def __reduce__(self):
        return (type(self), (self.tried,))


def _package_dir():
    return os.path.dirname(os.path.abspath(__file__))


def _bundled_candidates():
    found = glob.glob(os.path.join(_package_dir(), "libwefm.so*"))
    # Prefer the shortest name (libwefm.so, then libwefm.so.0, ...): they are the same library.
    return sorted(found, key=len) or [os.path.join(_package_dir(), "libwefm.so")]


def _build_tree_candidates():
    # bindings/python/wefm -> bindings/python -> bindings -> repository root
    repo = os.path.dirname(os.path.dirname(os.path.dirname(_package_dir())))
    # Only trust the layout if this really is the wefm source tree.
    if not os.path.isfile(os.path.join(repo, "capi", "include", "wefm", "wefm.h")):
        return []
    patterns = [os.path.join(repo, "build*", "capi", "libwefm.so"),
                os.path.join(repo, "build", "*", "capi", "libwefm.so"),
                os.path.join(repo, "build", "capi", "libwefm.so")]
    found = {p for pattern in patterns for p in glob.glob(pattern)}
    return sorted(found, key=os.path.getmtime, reverse=True)


def _system_candidates():
    names = []
    found = ctypes.util.find_library("wefm")
    if found:
        names.append(found)
    names += ["libwefm.so.0", "libwefm.so"]
    return names


def candidates():
    """Every path or name that load() would try, in order."""
    out = []
    env = os.environ.get("WEFM_LIBRARY")
    if env:
        out.append(env)
    out += _bundled_candidates()
    out += _build_tree_candidates()
    out += _system_candidates()
    return out


def load():
    tried = []
    env = os.environ.get("WEFM_LIBRARY")
    for path in candidates():
        is_path = os.sep in path
        if is_path and not os.path.exists(path):
            tried.append((path, "no such file"))
            # An explicit WEFM_LIBRARY that is wrong is a user error: do not silently pick another.
            if path == env:
                raise LibraryNotFoundError(tried)
            continue
        try:
            return ctypes.CDLL(path), path
        except OSError as exc:
            tried.append((path, str(exc)))
            if path == env:
                raise LibraryNotFoundError(tried) from exc
    raise LibraryNotFoundError(tried)
