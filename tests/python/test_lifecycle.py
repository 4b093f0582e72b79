"""Handles: the context manager releases, closed objects refuse calls, finalisers are safe."""
import gc

import pytest

import wefm
from conftest import flat_square


def test_context_manager_releases_the_handle():
    with wefm.Face() as f:
        assert not f.closed
        f.set_mesh(*flat_square(2))
    assert f.closed
    with pytest.raises(ValueError, match="closed"):
        f.solve()
    f.close()                                        # idempotent


def test_exception_inside_with_block_still_releases():
    with pytest.raises(RuntimeError):
        with wefm.Face() as f:
            raise RuntimeError
    assert f.closed


def test_garbage_collected_faces_release_themselves():
    for _ in range(200):
        f = wefm.Face(*flat_square(2))
        f.set_progress_callback(lambda fraction, stage: False)
        del f
    gc.collect()


def test_retained_handle_outlives_the_python_object():
    lib = wefm._lib
    f = wefm.Face(*flat_square(2))
    raw = f.handle
    assert lib.face_retain(raw) == 0
    f.close()
    assert lib.face_solve(raw) == 0                  # still alive: we hold the second reference
    lib.face_release(raw)
