"""wefm.flatten(): one call from arrays to UVs."""
import collections

from .errors import NotConvergedError
from .face import Face

FlattenResult = collections.namedtuple("FlattenResult", "uv use_vertex triangle_uses report")
FlattenResult.__doc__ = """uv (n_uses, 2) float64; use_vertex (n_uses,) int32 (the vertex of each use);
triangle_uses (n_triangles, 3) int32 (each triangle's uses, corner order); report (wefm.Report)."""


def _collect(face):
    return FlattenResult(face.uv, face.use_vertex, face.triangle_uses, face.report)


def flatten(vertices, triangles, s=1.0, seams=None, strict=True, **options):
    """Flatten a triangulated face. `seams`: (n, 2) vertex pairs of facet edges to cut along.
    Other keyword arguments are wefm_options fields (method="rollout", k=0.5, ...).

    When the iteration cap is reached (NotConvergedError) the best result is still computed: with
    strict=True the exception is raised with the FlattenResult in its .result attribute; with
    strict=False a NotConvergedWarning is issued and the result returned.
    """
    with Face() as face:
        face.set_mesh(vertices, triangles)
        if seams is not None:
            face.add_seams(seams)
        face.set_options(s=s, **options)
        try:
            face.solve(strict=strict)
        except NotConvergedError as exc:
            exc.result = _collect(face)
            raise
        return _collect(face)
