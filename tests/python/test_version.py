"""The package version is the loaded library's."""
import re

import wefm


def test_version_comes_from_the_library():
    assert wefm.__version__ == wefm._lib.version().decode()
    major, minor, patch = map(int, re.fullmatch(r"(\d+)\.(\d+)\.(\d+)", wefm.__version__).groups())
    assert wefm.version_number() == major * 10000 + minor * 100 + patch


def test_static_fallback_matches_the_library():
    # pyproject.toml and wefm/_version.py carry the same number for installs without a library.
    assert wefm.FALLBACK_VERSION == wefm.__version__
