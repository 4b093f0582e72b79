"""A closed cylinder cut along a generator: the seam's two sides under the periodic mode."""
import numpy as np

import wefm
from conftest import cylinder, seam_pairs

RINGS, SECTORS = 4, 12


def solved_cylinder(mode):
    xyz, tri = cylinder(RINGS, SECTORS, cut=False)
    f = wefm.Face(xyz, tri)
    f.add_seams(seam_pairs(RINGS, SECTORS))
    f.build()
    repeated = [e for e in range(f.edge_count()) if f.edge_is_repeated(e)]
    assert len(repeated) == 1
    f.set_edge_mode(repeated[0], mode)
    f.solve()
    return f, repeated[0]


def test_periodic_seam_sides_are_translates():
    f, edge = solved_cylinder("periodic")
    with f:
        assert f.edge_modes[edge] == wefm.EDGE_PERIODIC
        uv = f.uv
        seam_vertices = np.unique(seam_pairs(RINGS, SECTORS))
        shifts = []
        for v in seam_vertices:
            uses = f.vertex_uses(v)
            assert len(uses) == 2
            shifts.append(uv[uses[1]] - uv[uses[0]])
        shifts = np.array(shifts)
        # One translation for every seam vertex (up to the order of the two uses).
        shifts *= np.sign(shifts @ shifts[0])[:, None]
        assert np.abs(shifts - shifts[0]).max() < 1e-9 * np.linalg.norm(shifts[0])
        assert np.linalg.norm(shifts[0]) > 0.5 * np.sqrt(f.report.uv_area)
        assert f.report.angle_distortion_max < 1 + 1e-8


def test_edge_scores_have_one_slot_per_mode():
    f, edge = solved_cylinder("auto")
    with f:
        scores = f.edge_scores(edge)
        assert scores.shape == (5,)
        assert f.edge_modes[edge] in (wefm.EDGE_FREE, wefm.EDGE_PERIODIC, wefm.EDGE_SCAR,
                                      wefm.EDGE_ROTATIONAL)
        # The mode chosen by AUTO was tried, so its score is known.
        assert not np.isnan(scores[f.edge_modes[edge]])


def test_no_seams_is_the_same_face_as_no_call():
    # An empty list, or np.loadtxt of a seam file holding only comments (shape (0, 1)), adds no
    # seam: the face solves exactly as if add_seams had not been called.
    xyz, tri = cylinder(RINGS, SECTORS, cut=True)
    with wefm.Face(xyz, tri) as plain:
        plain.solve()
        expected = plain.uv.copy()
    for empty in ([], np.zeros((0, 1), dtype=np.int64), np.zeros((0, 2), dtype=np.int32)):
        with wefm.Face(xyz, tri) as f:
            f.add_seams(empty)
            f.solve()
            assert np.array_equal(f.uv, expected)


def test_seams_of_the_wrong_width_are_refused():
    xyz, tri = cylinder(RINGS, SECTORS, cut=True)
    with wefm.Face(xyz, tri) as f:
        try:
            f.add_seams([[0, 1, 2]])
        except ValueError as err:
            assert "shape (n, 2)" in str(err)
        else:
            raise AssertionError("a row of three indices was accepted")
