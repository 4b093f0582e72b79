"""Options: defaults from the library, keyword updates, names for enum values."""
import ctypes

import pytest

import wefm
from conftest import bumpy_patch, cylinder


def test_defaults_are_the_library_defaults():
    raw = wefm._structs.Options()
    assert wefm._lib.options_init(ctypes.byref(raw), ctypes.sizeof(raw)) == 0
    assert raw.struct_size == ctypes.sizeof(wefm._structs.Options)   # the mirror has the C size
    assert wefm.Options().as_dict() == wefm._records.struct_to_dict(raw)


def test_face_options_round_trip():
    with wefm.Face(*cylinder()) as f:
        f.set_options(s=0.5, method="rollout", default_edge_mode="scar", auto_cut=True)
        o = f.options
        assert (o.s, o.method, o.default_edge_mode, o.auto_cut) == (0.5, wefm.METHOD_ROLLOUT,
                                                                    wefm.EDGE_SCAR, 1)
        f.options = wefm.Options(k=0.5)              # a whole Options object: the rest default
        assert f.options.s == wefm.Options().s and f.options.k == 0.5


def test_unknown_and_misspelt_values_are_rejected():
    with pytest.raises(TypeError, match="valid"):
        wefm.Options(smoothness=1)
    with pytest.raises(ValueError, match="rollout"):
        wefm.Options(method="newton")


def test_solve_keywords_reach_the_library():
    with wefm.Face(*cylinder()) as f:
        report = f.solve(s=0.0, s_step=0.25)
        assert report.s == 0.0
        assert f.options.s_step == 0.25


def test_continuation_steps_reach_the_report():
    # By default s = 2 is one tentative step on a smooth face; steps of 1 take two. Neither is abandoned.
    with wefm.Face(*bumpy_patch()) as f:
        one = f.solve(s=2.0)
        assert (one.s_steps, one.abandoned_steps) == (1, 0)
        two = f.solve(s=2.0, s_step=1.0)
        assert (two.s_steps, two.abandoned_steps) == (2, 0)
        assert abs(one.score - two.score) < 1e-4


def test_mesh_options_defaults():
    m = wefm.MeshOptions(size=0.1)
    assert m.size == 0.1 and m.corners == (-1, -1, -1, -1)
