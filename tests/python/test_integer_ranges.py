"""Integers crossing into C are range-checked, never wrapped (wefm/_checked.py).

ctypes converts a Python int by masking, so 2**32 + 3 reached an int32_t parameter as 3: a pin on
use 3, a mode on edge 0, an iteration cap of 3. Every integer parameter, every integer option field
and every integer array now refuses what its C type cannot hold, naming the parameter.
"""
import ctypes
import os
import re

import numpy as np
import pytest

import wefm
from wefm import _api
from wefm._checked import c_range
from conftest import cylinder, flat_square, seam_pairs

WRAPS_TO_3 = 2**32 + 3


def solved_square():
    f = wefm.Face(*flat_square(4))
    f.solve()
    return f


def test_add_pin_past_int32_is_refused_and_pins_nothing():
    with wefm.Face(*flat_square(4)) as f:
        with pytest.raises(OverflowError, match=r"\buse = 4294967299\b.*int32"):
            f.add_pin(WRAPS_TO_3, 0.0, 0.0)
        with pytest.raises(OverflowError, match=r"\buse\b"):
            f.add_pin(-2**31 - 1, 0.0, 0.0)
        # Nothing reached the library: the first constraint it accepts still gets the first id.
        assert f.add_pin(3, 0.0, 0.0) == 0


def test_non_integer_indices_are_refused_not_truncated():
    with wefm.Face(*flat_square(4)) as f:
        with pytest.raises(TypeError, match=r"\buse must be an integer"):
            f.add_pin(3.7, 0.0, 0.0)
        with pytest.raises(TypeError, match=r"\bedge must be an integer"):
            f.set_edge_mode("0", "periodic")
        assert f.add_pin(np.int64(3), 0.0, 0.0) == 0  # numpy integers are integers


def test_set_edge_mode_past_int32_leaves_edge_0_alone():
    xyz, tri = cylinder(rings=3, sectors=12, cut=False)
    with wefm.Face(xyz, tri) as f:
        f.add_seams(seam_pairs(3, 12))
        f.build()
        with pytest.raises(OverflowError, match=r"wefm_face_set_edge_mode: edge = 4294967296"):
            f.set_edge_mode(2**32, "scar")
        f.solve()
        assert wefm.EDGE_SCAR not in f.edge_modes


def test_other_index_parameters_are_checked():
    with solved_square() as f:
        for call, name in [(lambda: f.edge(2**31), "edge"), (lambda: f.loop(-2**31 - 1), "loop"),
                           (lambda: f.loop_uses(2**40), "loop"), (lambda: f.vertex_uses(2**32), "vertex"),
                           (lambda: f.edge_scores(2**32), "edge"), (lambda: f.edge_is_repeated(2**32), "edge"),
                           (lambda: f.set_outer_loop(2**31), "loop"),
                           (lambda: f.set_edge_nodes(2**32, np.zeros((2, 3))), "edge")]:
            with pytest.raises(OverflowError, match=r"\b%s = " % name):
                call()


def test_options_past_their_c_type_are_refused_and_left_unchanged():
    with wefm.Face(*flat_square(4)) as f:
        before = f.options
        with pytest.raises(OverflowError, match=r"Options\.max_rho_iterations = 4294967299"):
            f.set_options(max_rho_iterations=WRAPS_TO_3)
        with pytest.raises(OverflowError, match=r"max_rho_iterations"):
            f.solve(max_rho_iterations=WRAPS_TO_3)
        assert f.options == before and not f.has_result
    opts = wefm.Options()
    with pytest.raises(OverflowError, match=r"Options\.threads"):
        opts.threads = -2**31 - 1
    with pytest.raises(TypeError, match=r"Options\.threads must be an integer"):
        opts.threads = 2.5
    with pytest.raises(OverflowError, match=r"Options\.max_rollout_sweeps"):
        wefm.Options(max_rollout_sweeps=2**31)
    with pytest.raises(OverflowError, match=r"Face|max_rho_iterations"):
        wefm.Face(max_rho_iterations=2**63)
    assert wefm.Options(auto_cut=True).auto_cut == 1 and wefm.Options(threads=np.int16(2)).threads == 2


def test_mesh_options_past_their_c_type_are_refused():
    with pytest.raises(OverflowError, match=r"MeshOptions\.corners\[3\] = 2147483648"):
        wefm.MeshOptions(corners=(0, 1, 2, 2**31))
    with pytest.raises(OverflowError, match=r"MeshOptions\.max_elements = 9223372036854775808"):
        wefm.MeshOptions(max_elements=2**63)
    with pytest.raises(OverflowError, match=r"MeshOptions\.smoothing_iterations"):
        wefm.MeshOptions(smoothing_iterations=-2**31 - 1)
    assert wefm.MeshOptions(corners=(0, 1, 2, 3)).corners == (0, 1, 2, 3)


def test_index_arrays_are_checked_before_conversion():
    xyz, tri = flat_square(4)
    with wefm.Face(xyz, tri) as f:
        seams = np.array([[2**32, 1]], dtype=np.int64)   # astype(int32) would give [[0, 1]]
        with pytest.raises(OverflowError, match=r"vertex_pairs: value = 4294967296 .*int32"):
            f.add_seams(seams)
        with pytest.raises(OverflowError, match=r"chain: value"):
            f.add_edge(np.array([0, 2**32 + 1], dtype=np.uint64))
        with pytest.raises(OverflowError, match=r"uses: value"):
            f.add_constraint([2**32 + 3], [1.0])
        with pytest.raises(OverflowError, match=r"edges: value"):
            f.add_loop([-2**31 - 1])
        assert f.edge_count() == len(f.edges())      # nothing was added by the refused calls
        assert f.add_pin(3, 0.0, 0.0) == 0
    huge = tri.astype(np.uint64)
    huge[0, 0] = 2**63 + 5                           # int64 would wrap it negative
    with wefm.Face() as f:
        with pytest.raises(OverflowError, match=r"triangles: value = 9223372036854775813"):
            f.set_mesh(xyz, huge)
        objects = tri.astype(object)
        objects[0, 0] = 2**70                        # beyond 64 bits numpy keeps Python ints
        with pytest.raises(OverflowError, match=r"triangles: value = %d" % 2**70):
            f.set_mesh(xyz, objects)
        f.set_mesh(xyz, tri.astype(np.uint16))       # small unsigned indices are fine
        assert f.triangle_uses.shape == tri.shape
    wide = tri.astype(np.int64)
    wide[0, 0] = 2**32                               # Mesh.from_arrays converted with astype
    with pytest.raises(OverflowError, match=r"triangles: value = 4294967296"):
        wefm.Mesh.from_arrays(xyz, wide)


def test_float_index_arrays_are_still_refused():
    xyz, tri = flat_square(4)
    with wefm.Face() as f:
        with pytest.raises(ValueError, match="must hold integers"):
            f.set_mesh(xyz, tri.astype(float))
        with pytest.raises(ValueError, match="must hold integers"):
            f.set_mesh(xyz, tri.astype(object) * 1.0)


def test_paths_with_a_nul_byte_are_refused(tmp_path):
    with solved_square() as f:
        target = tmp_path / "out.obj"
        with pytest.raises(ValueError, match=r"wefm_face_write_obj: path contains a NUL"):
            f.write_obj(str(target) + "\0.txt")      # C would have written out.obj
        assert not target.exists()
    with pytest.raises(ValueError, match=r"wefm_mesh_read: path contains a NUL"):
        wefm.Mesh.read(str(tmp_path / "a.obj\0b"))


def _int_params():
    """(function, index, name, ctype) of every integer parameter in the ctypes table."""
    for fn, (_, params, argtypes) in _api.PROTOTYPES.items():
        for i, (name, ctype) in enumerate(zip(params.split(), argtypes)):
            if ctype in (ctypes.c_int, ctypes.c_int32, ctypes.c_int64, ctypes.c_size_t):
                yield fn, i, name, ctype


@pytest.mark.parametrize("fn,index,name,ctype", list(_int_params()),
                         ids=lambda v: v if isinstance(v, str) else None)
def test_every_integer_parameter_is_checked_before_the_call(fn, index, name, ctype):
    """Out of range on each side: refused by the binding (the other arguments are NULL/0, so a
    call that got through would return a status instead of raising)."""
    _, _, argtypes = _api.PROTOTYPES[fn]
    lo, hi = c_range(ctype)
    for bad in (hi + 1, lo - 1):
        args = [0 if t in (ctypes.c_int, ctypes.c_int32, ctypes.c_int64, ctypes.c_size_t, ctypes.c_double)
                else None for t in argtypes]
        args[index] = bad
        with pytest.raises(OverflowError, match=r"wefm_%s: %s = %d" % (fn, name, bad)):
            getattr(wefm._lib, fn)(*args)


def test_the_integer_table_reaches_the_known_parameters():
    names = {(fn, name) for fn, _, name, _ in _int_params()}
    assert {("face_add_pin", "use"), ("face_set_edge_mode", "edge"), ("face_set_edge_mode", "mode"),
            ("face_set_outer_loop", "loop"), ("face_set_edge_nodes", "edge"),
            ("options_init", "struct_size")} <= names
