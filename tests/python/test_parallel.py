"""wefm.parallel on a LocalCluster of two worker processes: the same results as a serial run, in
input order, for paths (mesh files with a seam file, face folders) and arrays; failures raised or
returned as asked.

The serial reference runs in a child process with the thread settings Dask gives its workers
(distributed.nanny.pre-spawn-environ: OMP/OpenBLAS threads 1), because a supernodal factorisation
with another BLAS thread count may round differently (the last bits of the UVs).
"""
import os
import pickle
import subprocess
import sys

import numpy as np
import pytest

import wefm
import wefm.parallel
from conftest import bumpy_patch, cylinder, seam_pairs

distributed = pytest.importorskip("distributed")
dask = pytest.importorskip("dask")


def write_obj(path, v, t):
    with open(path, "w") as f:
        f.writelines("v %.17g %.17g %.17g\n" % tuple(p) for p in v)
        f.writelines("f %d %d %d\n" % tuple(q + 1 for q in tri) for tri in t)


@pytest.fixture(scope="module")
def inputs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("faces")
    items = []
    for k in range(4):
        write_obj(tmp / ("patch%d.obj" % k), *bumpy_patch(6 + 3 * k))
        items.append(str(tmp / ("patch%d.obj" % k)))
    write_obj(tmp / "cyl.obj", *cylinder(rings=4, sectors=16, cut=False))
    (tmp / "cyl.seam").write_text("# seam\n" + "".join("%d %d\n" % tuple(p) for p in seam_pairs(4, 16)))
    items.append(str(tmp / "cyl.obj"))
    folder = tmp / "face_folder"
    folder.mkdir()
    write_obj(folder / "face.obj", *bumpy_patch(11))
    (folder / "face.seam").write_text("# no seams\n")  # only comments: no cut
    items.append(str(folder))
    items.append(bumpy_patch(14))
    return items


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None) as cluster:
        with distributed.Client(cluster) as c:
            yield c


def serial_in_child(items, tmp_path):
    """flatten_faces(items) in a fresh process with the workers' thread settings."""
    (tmp_path / "items.pkl").write_bytes(pickle.dumps(items))
    env = dict(os.environ)
    env.update({k: str(v) for k, v in dask.config.get("distributed.nanny.pre-spawn-environ").items()})
    script = ("import pickle, wefm.parallel\n"
              "items = pickle.load(open('items.pkl', 'rb'))\n"
              "pickle.dump(wefm.parallel.flatten_faces(items), open('serial.pkl', 'wb'))\n")
    subprocess.run([sys.executable, "-c", script], cwd=tmp_path, env=env, check=True)
    return pickle.loads((tmp_path / "serial.pkl").read_bytes())


def same_result(a, b):
    for field in ("uv", "use_vertex", "triangle_uses"):
        x, y = getattr(a, field), getattr(b, field)
        assert x.dtype == y.dtype and x.shape == y.shape and x.tobytes() == y.tobytes(), field
    # The report's figures too, but not its wall times and the process's peak memory.
    ra, rb = a.report.as_dict(), b.report.as_dict()
    for key in ra:
        if not key.startswith("time") and key != "peak_memory_mb":
            assert np.array_equal(ra[key], rb[key], equal_nan=True), key


def test_dask_equals_serial(inputs, client, tmp_path):
    workers = client.run(os.getpid)
    assert len(set(workers.values())) == 2 and os.getpid() not in workers.values()
    parallel = wefm.parallel.flatten_faces(inputs, client)
    serial = serial_in_child(inputs, tmp_path)
    assert len(parallel) == len(serial) == len(inputs)
    for a, b in zip(serial, parallel):
        same_result(a, b)
    # Several faces per task: the same results, still in input order.
    chunked = wefm.parallel.flatten_faces(inputs, client, faces_per_task=3)
    assert len(chunked) == len(inputs)
    for a, b in zip(serial, chunked):
        same_result(a, b)
    # Input order is kept: each result belongs to its own input's mesh.
    cyl = wefm.parallel.load_face(inputs[4])
    assert parallel[4].triangle_uses.shape[0] == len(cyl[1])
    assert parallel[4].uv.shape[0] == len(cyl[0]) + len(np.unique(cyl[2]))  # seam vertices: two uses each
    assert parallel[-1].triangle_uses.shape[0] == len(inputs[-1][1])


def test_failures(inputs, client, tmp_path):
    broken = tmp_path / "broken.obj"
    broken.write_text("v 0 0 0\nv 1 0 0\nf 1 2 7\n")
    items = [inputs[0], str(broken), inputs[1]]
    with pytest.raises(wefm.WefmError):
        wefm.parallel.flatten_faces(items, client)
    got = wefm.parallel.flatten_faces(items, client, errors="return")
    assert isinstance(got[1], wefm.WefmError) and str(broken) in str(got[1])
    assert isinstance(got[0], wefm.FlattenResult) and isinstance(got[2], wefm.FlattenResult)
    with pytest.raises(ValueError):
        wefm.parallel.flatten_faces(items, client, errors="ignore")
    for bad in (0, 1.5, -2):
        with pytest.raises(ValueError):
            wefm.parallel.flatten_faces(items, client, faces_per_task=bad)
    with pytest.raises(wefm.WefmIOError):
        wefm.parallel.flatten_faces([str(tmp_path / "missing.obj")])


@pytest.mark.skipif(not os.environ.get("WEFM_CLI_MODEL"), reason="WEFM_CLI_MODEL (a wefm tool with CAD import) not set")
def test_models_through_the_tool(client, tmp_path):
    model = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "data", "cylinder.step")
    tool = os.environ["WEFM_CLI_MODEL"]
    args = ["-j", "1", "-q"]
    parallel = wefm.parallel.run_models([model], tmp_path / "dask", client, tool=tool, args=args)
    serial = wefm.parallel.run_models([model], tmp_path / "serial", tool=tool, args=args)
    assert [r["exit_code"] for r in parallel] == [r["exit_code"] for r in serial] == [0], parallel
    assert parallel[0]["argv"][:5] == [tool, "model", model, "-o", str(tmp_path / "dask" / "cylinder")]
    objs = sorted(os.listdir(tmp_path / "serial" / "cylinder"))
    objs = [name for name in objs if name.endswith(".obj")]
    assert objs and objs == sorted(n for n in os.listdir(tmp_path / "dask" / "cylinder") if n.endswith(".obj"))
    def data_lines(path):  # the '#' header names the output folder, which differs
        return [line for line in path.read_bytes().splitlines() if not line.startswith(b"#")]

    for name in objs:
        got = data_lines(tmp_path / "dask" / "cylinder" / name)
        assert got and got == data_lines(tmp_path / "serial" / "cylinder" / name), name
