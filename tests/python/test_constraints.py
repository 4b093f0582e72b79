"""Pins and general complex constraints are honoured exactly."""
import os
import subprocess
import sys
import textwrap

import numpy as np

import wefm
from conftest import flat_square


def test_two_pins_fix_position_rotation_and_scale():
    xyz, tri = flat_square(3)
    with wefm.Face(xyz, tri) as f:
        use_of = {v: u for u, v in enumerate(f.use_vertex)}   # uses are not numbered like vertices
        f.add_pin(use_of[0], 1.0, 2.0)
        f.add_pin(use_of[3], (1.0, 3.0))             # vertex 3 is (1, 0, 0): turned by 90 degrees
        f.solve()
        uv = f.uv
    np.testing.assert_allclose(uv[use_of[0]], [1.0, 2.0], atol=1e-12)
    np.testing.assert_allclose(uv[use_of[3]], [1.0, 3.0], atol=1e-12)
    # The square is flat: the result is the exact rigid motion (x, y) -> (1 - y, 2 + x).
    expected = np.column_stack([1 - xyz[:, 1], 2 + xyz[:, 0]])
    np.testing.assert_allclose(uv[[use_of[v] for v in range(len(xyz))]], expected, atol=1e-9)


def test_complex_coefficients_rotate():
    xyz, tri = flat_square(3)
    with wefm.Face(xyz, tri) as f:
        use_of = {v: u for u, v in enumerate(f.use_vertex)}
        f.add_pin(use_of[0], 0j)
        # i * z = -1  <=>  z = i: the (1, 0, 0) corner lands on the +v axis.
        f.add_constraint([use_of[3]], np.array([1j]), rhs=-1)
        f.solve()
        uv = f.uv
    np.testing.assert_allclose(uv[use_of[3]], [0.0, 1.0], atol=1e-12)
    np.testing.assert_allclose(uv[use_of[15]], [-1.0, 1.0], atol=1e-9)   # (1, 1, 0) turned by 90 degrees


def run_isolated(body):
    """Run a snippet in a child interpreter so that a crash in the library fails only this test."""
    code = "import numpy as np, wefm\nfrom conftest import flat_square\n" + textwrap.dedent(body)
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    run = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True,
                         cwd=os.path.dirname(os.path.abspath(__file__)), timeout=120)
    assert run.returncode == 0, "exit %d\n%s%s" % (run.returncode, run.stdout, run.stderr)
    return run.stdout


def test_single_pin_only_translates_the_free_solution():
    run_isolated("""
        xyz, tri = flat_square(3)
        free = wefm.flatten(xyz, tri)
        with wefm.Face(xyz, tri) as f:
            use = f.vertex_uses(5)[0]
            f.add_pin(use, 10.0, -4.0)
            f.solve()
            shift = f.uv - free.uv
        assert np.allclose(shift[use], [10.0, -4.0] - free.uv[use], atol=0)
        assert np.abs(shift - shift[use]).max() < 1e-9, shift
    """)


def test_contradictory_pins_are_singular_or_rejected():
    run_isolated("""
        with wefm.Face(*flat_square(2)) as f:
            f.add_pin(0, 0, 0)
            f.add_pin(0, 1, 1)
            try:
                f.solve()
            except (wefm.SingularError, wefm.InvalidConstraintError):
                raise SystemExit(0)
            raise AssertionError("contradictory pins accepted: uv[0] = %s" % f.uv[0])
    """)


def test_clear_constraints_restores_the_gauge():
    xyz, tri = flat_square(2)
    with wefm.Face(xyz, tri) as f:
        free = f.solve() and f.uv
        f.add_pin(0, 5, 5)
        f.clear_constraints()
        f.solve()
        np.testing.assert_allclose(f.uv, free, atol=1e-12)
