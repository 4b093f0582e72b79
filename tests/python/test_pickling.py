"""Objects owning a libwefm handle refuse pickling and copying; value objects copy by value.

A pickled Face used to carry its raw pointer: unpickled in another process it pointed at nothing
(a multiprocessing worker crashed), unpickled or copied in the same one it was released twice.
"""
import copy
import multiprocessing
import pickle

import numpy as np
import pytest

import wefm
from conftest import flat_square


def handle_owners():
    """A live Face, Mesh and DomainMesh (closed by the caller)."""
    face = wefm.Face(*flat_square(4))
    face.solve()
    return [face, wefm.Mesh.from_arrays(*flat_square(2)), face.mesh_domain(size=0.5)]


@pytest.mark.parametrize("operation", [pickle.dumps, copy.copy, copy.deepcopy,
                                       lambda o: pickle.dumps(o, protocol=0)],
                         ids=["pickle", "copy", "deepcopy", "pickle-protocol-0"])
def test_handle_owners_refuse_pickling_and_copying(operation):
    owners = handle_owners()
    try:
        for obj in owners:
            name = type(obj).__name__
            with pytest.raises(TypeError, match=r"wefm\.%s cannot be pickled or copied" % name):
                operation(obj)
            if operation is not copy.copy:          # a shallow copy of a list shares the items
                with pytest.raises(TypeError):
                    operation([obj])                # inside a container as well
        face = owners[0]
        assert face.uv.shape == (25, 2)             # the refused copy left the face intact
    finally:
        for obj in reversed(owners):
            obj.close()


def test_a_face_sent_to_a_worker_process_is_refused_in_the_parent():
    with wefm.Face(*flat_square(4)) as face:
        face.solve()
        with multiprocessing.get_context("fork").Pool(1) as pool:
            with pytest.raises(TypeError, match="cannot be pickled"):
                pool.apply_async(len, (face,)).get(timeout=120)
        assert face.report.converged


def test_options_copy_and_pickle_by_value():
    opts = wefm.Options(s=0.25, method="rollout", max_rho_iterations=7)
    for twin in (copy.copy(opts), copy.deepcopy(opts), pickle.loads(pickle.dumps(opts))):
        assert twin == opts and twin is not opts
        twin.max_rho_iterations = 8                 # a copy never shares the struct
        assert opts.max_rho_iterations == 7
    mesh_opts = wefm.MeshOptions(size=0.1, corners=(0, 3, 5, 9))
    assert pickle.loads(pickle.dumps(mesh_opts)) == mesh_opts
    assert copy.copy(mesh_opts).corners == (0, 3, 5, 9)


def test_reports_and_results_pickle():
    result = wefm.flatten(*flat_square(4))
    back = pickle.loads(pickle.dumps(result))
    assert repr(back.report) == repr(result.report)  # repr: NaN fields (not tried) compare unequal
    np.testing.assert_array_equal(back.uv, result.uv)


def test_errors_survive_pickling_with_their_status_and_attributes():
    with wefm.Face() as f, pytest.raises(wefm.InvalidStateError) as err:
        f.solve()                                   # no mesh yet
    back = pickle.loads(pickle.dumps(err.value))
    assert type(back) is wefm.InvalidStateError and back.message
    assert (back.status, back.status_name, back.message, back.function, str(back)) == \
        (err.value.status, err.value.status_name, err.value.message, err.value.function, str(err.value))
    late = wefm.NotConvergedError(11, "cap reached", "wefm_face_solve")
    late.result = ("kept",)
    assert pickle.loads(pickle.dumps(late)).result == ("kept",)
    missing = wefm.LibraryNotFoundError([("/x/libwefm.so", "no such file")])
    assert pickle.loads(pickle.dumps(missing)).tried == missing.tried
