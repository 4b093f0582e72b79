"""Package version when the library cannot say (kept equal to pyproject.toml and the C library)."""
FALLBACK_VERSION = "0.1.0"
