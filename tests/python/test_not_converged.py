"""Non-convergence: raised by default with the best result still readable; a warning if not strict."""
import numpy as np
import pytest

import wefm
from conftest import bumpy_patch

CAPPED = dict(max_rho_iterations=1, rho_tolerance=1e-15)


def test_strict_solve_raises_but_keeps_the_result():
    with wefm.Face(*bumpy_patch()) as f:
        with pytest.raises(wefm.NotConvergedError) as err:
            f.solve(**CAPPED)
        assert err.value.status_name == "WEFM_ERROR_NOT_CONVERGED"
        assert f.has_result and not f.report.converged
        assert np.isfinite(f.uv).all()


def test_flatten_attaches_the_result_or_warns():
    xyz, tri = bumpy_patch()
    with pytest.raises(wefm.NotConvergedError) as err:
        wefm.flatten(xyz, tri, **CAPPED)
    assert err.value.result.uv.shape == (len(xyz), 2)
    with pytest.warns(wefm.NotConvergedWarning):
        r = wefm.flatten(xyz, tri, strict=False, **CAPPED)
    np.testing.assert_array_equal(r.uv, err.value.result.uv)
