"""A face called from inside its own progress callback (wefm.h, "Re-entrancy"): changes raise
InvalidStateError (re-raised by solve(), which the callback's exception cancels), reads work, and
closing the face from the callback does not free it under its solve."""
import numpy as np
import pytest

import wefm
from conftest import cylinder


@pytest.mark.parametrize("change", [
    lambda f: f.add_pin(0, 5.0, 5.0),
    lambda f: f.clear_topology(),
    lambda f: f.set_mesh(*cylinder(rings=2, sectors=6)),
    lambda f: f.solve(),
    lambda f: f.set_options(s=0.0),
], ids=["add_pin", "clear_topology", "set_mesh", "solve", "set_options"])
def test_a_change_from_the_callback_raises_invalid_state_and_changes_nothing(change):
    with wefm.Face(*cylinder()) as f:
        f.solve()
        before = f.uv.copy()

        def callback(fraction, stage):
            change(f)

        f.set_progress_callback(callback)
        with pytest.raises(wefm.InvalidStateError, match="progress callback"):
            f.solve()
        f.set_progress_callback(None)
        assert f.has_result and np.array_equal(f.uv, before)  # the previous result, unchanged
        assert f.solve() is not None


def test_reads_from_the_callback_work():
    with wefm.Face(*cylinder()) as f:
        f.solve()
        seen = []
        f.set_progress_callback(lambda fraction, stage: seen.append((f.has_result, f.uv.shape)))
        f.solve()
        assert seen and all(s == (True, seen[0][1]) for s in seen)


def test_closing_the_face_from_its_callback_does_not_free_it_under_the_solve():
    f = wefm.Face(*cylinder())
    f.set_progress_callback(lambda fraction, stage: f.close())
    with pytest.raises(ValueError, match="closed"):
        f.solve()  # the solve ran to its end; the closed Python object then refuses the report
    assert f.closed
