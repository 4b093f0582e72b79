"""Faces and models on a Dask cluster (`distributed`): the way past one machine.

    from distributed import Client, LocalCluster
    import wefm.parallel

    with LocalCluster(n_workers=4, threads_per_worker=1, processes=True) as cluster, Client(cluster) as client:
        results = wefm.parallel.flatten_faces(["a.obj", "faces/f12", (vertices, triangles)], client, s=1.0)

A library handle lives in the process that made it and cannot be pickled, so what travels is a file
path or arrays, and what comes back is arrays (wefm.FlattenResult) or the exception: every task
builds its own Face in its worker. The results are those of flatten_face() run serially (client=None)
because the worker runs that same function on the same bytes. Use processes=True workers: each
worker process loads its own library. Models (CAD files) go through the `wefm` tool, which holds the
CAD import: run_models().
"""
import functools
import os
import subprocess

from .flatten import flatten
from .mesh_io import read_mesh, read_seams


def load_face(item):
    """(vertices, triangles, seams or None) of an input as `wefm batch` reads it: a mesh file with an
    optional <stem>.seam beside it, a face folder (face.obj, face.seam), or a (vertices, triangles
    [, seams]) tuple of arrays."""
    if isinstance(item, (str, os.PathLike)):
        path = os.fspath(item)
        if os.path.isdir(path):
            mesh, seam = os.path.join(path, "face.obj"), os.path.join(path, "face.seam")
        else:
            mesh, seam = path, os.path.splitext(path)[0] + ".seam"
        vertices, triangles, _ = read_mesh(mesh)
        seams = read_seams(seam) if os.path.isfile(seam) else None
        return vertices, triangles, seams
    if len(item) not in (2, 3):
        raise TypeError("an input is a path or a (vertices, triangles[, seams]) tuple, got %d items" % len(item))
    return item[0], item[1], item[2] if len(item) == 3 else None


def flatten_face(item, s=1.0, strict=True, **options):
    """Flattens one input (see load_face) in this process: wefm.flatten()'s FlattenResult."""
    vertices, triangles, seams = load_face(item)
    if seams is not None and len(seams) == 0:
        seams = None  # a seam file with only comments: no cut
    return flatten(vertices, triangles, s=s, seams=seams, strict=strict, **options)


def _task(items, errors, kwargs):
    out = []
    for item in items:
        try:
            out.append(flatten_face(item, **kwargs))
        except Exception as exc:  # noqa: BLE001 - returned to the caller, who asked for it
            if errors != "return":
                raise
            out.append(exc)
    return out


def flatten_faces(inputs, client=None, errors="raise", faces_per_task=1, **kwargs):
    """Flattens every input (paths or array tuples, see load_face) and returns the FlattenResults in
    input order. `client`: a distributed.Client (tasks run in its workers); None runs them here, one
    after the other. Keyword arguments go to wefm.flatten() (s, strict, options).
    errors="raise" re-raises the first failure (a WefmError, as in a serial loop); "return" puts the
    exception in that input's place and keeps the others.
    faces_per_task: inputs flattened one after the other in one task; more than 1 pays the
    scheduler's cost per task (milliseconds) once for several small faces."""
    if errors not in ("raise", "return"):
        raise ValueError("errors must be 'raise' or 'return', got %r" % (errors,))
    if int(faces_per_task) != faces_per_task or faces_per_task < 1:
        raise ValueError("faces_per_task must be a whole number >= 1, got %r" % (faces_per_task,))
    inputs = list(inputs)
    chunks = [inputs[k:k + faces_per_task] for k in range(0, len(inputs), int(faces_per_task))]
    if client is None:
        return [r for chunk in chunks for r in _task(chunk, errors, kwargs)]
    # pure=False: two equal inputs are still two tasks (their results are separate objects).
    futures = client.map(functools.partial(_task, errors=errors, kwargs=kwargs), chunks, pure=False)
    return [r for done in client.gather(futures) for r in done]


def _run_tool(argv):
    done = subprocess.run(argv, capture_output=True, text=True)
    return {"argv": argv, "exit_code": done.returncode, "stdout": done.stdout, "stderr": done.stderr}


def run_models(models, output_dir, client=None, command="model", tool="wefm", args=()):
    """Runs `TOOL COMMAND MODEL -o OUTPUT_DIR/<model stem>[.msh] ARGS` for every model (a CAD file
    on a file system the workers share), one task per model, and returns per model a dict of argv,
    exit_code, stdout and stderr, in input order. command="model" writes a folder of per-face
    files, "mesh-model" one .msh file. `tool`: the wefm executable as the workers see it."""
    argvs = []
    for model in models:
        stem = os.path.splitext(os.path.basename(os.fspath(model)))[0]
        target = os.path.join(os.fspath(output_dir), stem + (".msh" if command == "mesh-model" else ""))
        argvs.append([os.fspath(tool), command, os.fspath(model), "-o", target, *map(str, args)])
    if client is None:
        return [_run_tool(argv) for argv in argvs]
    return client.gather(client.map(_run_tool, argvs, pure=False))
