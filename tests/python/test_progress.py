"""Progress callbacks: cancelling, exceptions inside the callback, and reuse afterwards."""
import pytest

import wefm
from conftest import cylinder

STAGES = {"topology", "coefficients", "assembly", "factorise", "solve", "repeated edges", "continuation", "rollout", "quality", "done", "mesh"}


def test_cancelling_callback_raises_and_face_stays_usable():
    calls = []

    def cancel_at_once(fraction, stage):
        calls.append((fraction, stage))
        return True

    with wefm.Face(*cylinder()) as f:
        f.set_progress_callback(cancel_at_once)
        with pytest.raises(wefm.CancelledError):
            f.solve()
        assert len(calls) == 1 and calls[0][1] in STAGES and 0 <= calls[0][0] <= 1
        assert not f.has_result                      # nothing before, nothing after a cancel
        seen = []
        f.set_progress_callback(lambda fraction, stage: seen.append(stage))
        report = f.solve()
        assert report.angle_distortion_max < 1 + 1e-8
        assert seen and set(seen) <= STAGES
        f.set_progress_callback(None)
        f.solve()


def test_exception_in_callback_cancels_and_is_reraised():
    def broken(fraction, stage):
        raise ZeroDivisionError("from the callback")

    with wefm.Face(*cylinder()) as f:
        f.set_progress_callback(broken)
        with pytest.raises(ZeroDivisionError) as err:
            f.solve()
        assert isinstance(err.value.__cause__, wefm.CancelledError)


def test_cancel_keeps_the_previous_result():
    with wefm.Face(*cylinder()) as f:
        f.solve()
        before = f.uv
        f.set_progress_callback(lambda fraction, stage: True)
        with pytest.raises(wefm.CancelledError):
            f.solve()
        assert f.has_result
        assert (f.uv == before).all()
