"""Status codes surface as typed exceptions carrying the library's message."""
import ctypes
import re
import subprocess
import sys

import numpy as np
import pytest

import wefm
from conftest import cylinder, flat_square


def test_nan_vertex_is_an_invalid_mesh_naming_the_vertex():
    xyz, tri = flat_square()
    xyz[7, 1] = np.nan
    with wefm.Face() as f:
        with pytest.raises(wefm.InvalidMeshError) as err:
            f.set_mesh(xyz, tri)
    e = err.value
    assert e.status == 6 and e.status_name == "WEFM_ERROR_INVALID_MESH"
    assert re.search(r"\b7\b", e.message), e.message


def test_out_of_range_index_is_an_invalid_mesh():
    xyz, tri = flat_square()
    tri = tri.copy()
    tri[3, 2] = 999
    with wefm.Face() as f:
        with pytest.raises(wefm.InvalidMeshError) as err:
            f.set_mesh(xyz, tri)
    assert "999" in err.value.message, err.value.message


def test_rejected_mesh_leaves_the_face_as_it_was():
    xyz, tri = flat_square()
    with wefm.Face() as f:
        f.set_mesh(xyz, tri)
        bad = xyz.copy()
        bad[0, 0] = np.inf
        with pytest.raises(wefm.InvalidMeshError):
            f.set_mesh(bad, tri)
        f.solve()
        assert f.uv.shape == (len(xyz), 2)


def test_queries_before_solve_are_invalid_state():
    with wefm.Face() as f:
        with pytest.raises(wefm.InvalidStateError):
            f.solve()                                # no mesh yet
        f.set_mesh(*flat_square())
        assert not f.has_result
        with pytest.raises(wefm.InvalidStateError):
            f.uv
        with pytest.raises(wefm.InvalidStateError):
            f.report
        assert f.last_error                          # the handle carries the message


def test_too_small_buffer_writes_nothing_and_reports_the_size():
    lib = wefm._lib
    with wefm.Face(*flat_square(2)) as f:
        f.solve()
        n_uses = f.use_count()
        buf = (ctypes.c_double * 4)(*[-7.0] * 4)
        count = ctypes.c_int64(0)
        status = lib.face_get_uv(f.handle, buf, 2, ctypes.byref(count))
        assert status == wefm._structs.ERROR_BUFFER_TOO_SMALL
        assert count.value == 2 * n_uses             # ELEMENTS, not uses
        assert list(buf) == [-7.0] * 4


def test_null_handle_is_reported_not_crashed():
    assert wefm._lib.face_solve(None) == wefm._structs.ERROR_NULL_ARGUMENT
    wefm._lib.face_release(None)


def test_seam_that_is_not_a_facet_edge_is_invalid_topology():
    xyz, tri = flat_square(4)
    with wefm.Face(xyz, tri) as f:
        with pytest.raises(wefm.InvalidTopologyError):
            f.add_seams([(0, 24)])                   # opposite corners: no such facet edge
            f.build()


def test_bad_shapes_are_value_errors_before_any_call():
    xyz, tri = flat_square()
    with wefm.Face() as f:
        with pytest.raises(ValueError, match="vertices"):
            f.set_mesh(xyz[:, :2], tri)
        with pytest.raises(ValueError, match="triangles"):
            f.set_mesh(xyz, tri[:, :2])
        with pytest.raises(ValueError, match="integers"):
            f.set_mesh(xyz, tri.astype(float))


def test_missing_file_is_an_io_error():
    with pytest.raises(wefm.WefmIOError) as err:
        wefm.read_mesh("/nonexistent/face.obj")
    assert isinstance(err.value, OSError)
    assert "nonexistent" in err.value.message, err.value.message


def test_unloadable_library_lists_what_was_tried(tmp_path):
    env = {"WEFM_LIBRARY": str(tmp_path / "nope.so"), "PYTHONPATH": ":".join(sys.path)}
    run = subprocess.run([sys.executable, "-c", "import wefm"], env=env, capture_output=True, text=True)
    assert run.returncode != 0
    assert "LibraryNotFoundError" in run.stderr and "nope.so" in run.stderr


def test_out_of_domain_option_is_rejected_and_the_result_kept():
    xyz, tri = cylinder(cut=True)
    with wefm.Face(xyz, tri) as f:
        f.solve()
        before = f.uv
        with pytest.raises(wefm.InvalidArgumentError):
            f.set_options(s=7.0)                     # s must lie in [0, 2]
        np.testing.assert_array_equal(f.uv, before)
