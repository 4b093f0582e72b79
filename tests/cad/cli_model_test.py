#!/usr/bin/env python3
"""`wefm model` end to end on the checked-in STEP cylinder: usage: cli_model_test.py WEFM CYLINDER.step"""
import json
import os
import subprocess
import sys
import tempfile


def check_mesh_model(wefm, model, tmp):
    """wefm mesh-model: the closed cylinder solid gives one closed manifold mesh (every edge used by exactly
    two triangles), in OBJ and in MSH 4.1 with one physical group per face."""
    from collections import Counter
    obj, msh, rep = (os.path.join(tmp, n) for n in ("cyl.obj", "cyl.msh", "cyl_mesh.json"))
    for out in (obj, msh):
        p = subprocess.run([wefm, "mesh-model", model, "--size", "2", "-o", out, "--report", rep, "-q"],
                           capture_output=True, text=True)
        assert p.returncode == 0, f"mesh-model exit {p.returncode}: {p.stderr}"
    F = [tuple(int(x) - 1 for x in l.split()[1:4]) for l in open(obj) if l.startswith("f ")]
    V = [l for l in open(obj) if l.startswith("v ")]
    uses = Counter(tuple(sorted((t[i], t[(i + 1) % 3]))) for t in F for i in range(3))
    assert set(uses.values()) == {2}, f"not conforming: edge use counts {Counter(uses.values())}"
    assert len(V) - len(uses) + len(F) == 2, "a closed cylinder mesh is a sphere topologically"
    r = json.load(open(rep))
    assert r["conformity"]["open_edges"] == 0 and r["conformity"]["non_manifold_edges"] == 0, r["conformity"]
    assert r["triangles"] == len(F) and r["lambda_min"] >= 0.5, r
    assert [f["status"] for f in r["faces"]] == ["ok"] * 3, r["faces"]
    text = open(msh).read()
    assert text.startswith("$MeshFormat\n4.1 0 8\n"), text[:40]
    names = text.split("$PhysicalNames\n")[1].split("$EndPhysicalNames")[0].split("\n")
    assert names[0] == "3" and all('"face_' in n for n in names[1:4]), names
    elements = text.split("$Elements\n")[1].split("\n")[0].split()
    assert int(elements[1]) == len(F), elements


def check_plugin(wefm, model, tmp):
    """Open CASCADE is a plugin: the tool itself does not load it (every command would pay its dynamic
    linking), and a missing or foreign module is an I/O error that says so, not a crash."""
    needed = subprocess.run(["readelf", "-d", wefm], capture_output=True, text=True).stdout
    assert "NEEDED" in needed and "libTK" not in needed, needed
    plugin = os.path.join(os.path.dirname(wefm), "wefm-cad-occt.so")
    assert "libTK" in subprocess.run(["readelf", "-d", plugin], capture_output=True, text=True).stdout
    out = os.path.join(tmp, "plugin_out")
    # A shared object without the entry point: the C library's maths library.
    libm = next(p for p in ("/lib/x86_64-linux-gnu/libm.so.6", "/usr/lib/x86_64-linux-gnu/libm.so.6", "/lib64/libm.so.6",
                            "/usr/lib64/libm.so.6", "/lib/libm.so.6") if os.path.exists(p))
    cases = ((os.path.join(tmp, "none.so"), "no such file"),
             (wefm, wefm + ": "),  # an executable: dlerror's own words follow the path
             (libm, "not a CAD plugin of this wefm"))
    for path, why in cases:
        for command in ("model", "mesh-model"):
            extra = ["-o", out] if command == "model" else ["-o", out + ".obj", "--size", "2"]
            p = subprocess.run([wefm, command, model] + extra,
                               capture_output=True, text=True, env=dict(os.environ, WEFM_CAD_PLUGIN=path))
            assert p.returncode == 3, (command, path, p.returncode, p.stderr)
            assert "CAD import is not available" in p.stderr and why in p.stderr, (command, path, p.stderr)
    # Commands without a CAD model never open it: flatten works with the module unreachable.
    face = os.path.join(tmp, "tri.obj")
    with open(face, "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.2\nf 1 2 3\nf 2 4 3\n")
    p = subprocess.run([wefm, "flatten", face, "-o", os.path.join(tmp, "tri_uv.obj"), "-q"], capture_output=True,
                       text=True, env=dict(os.environ, WEFM_CAD_PLUGIN=os.path.join(tmp, "none.so")))
    assert p.returncode == 0, p.stderr


def check_options_first(wefm, model, tmp):
    """A solver option the library refuses is a usage error (exit 2) before the model is read: no face is
    imported or attempted, nothing is written. Before, mesh-model and model imported the whole model and
    then failed every face with the same message (exit 5, and mesh-model wrote an empty mesh)."""
    folder = os.path.join(tmp, "faces")
    os.makedirs(folder, exist_ok=True)
    with open(os.path.join(folder, "tri.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0.2\nf 1 2 3\nf 2 4 3\n")
    for bad in (["--s", "5"], ["--min-beta", "-1"], ["--k", "2"]):
        for cmd in (["mesh-model", model, "--size", "2", "-o", os.path.join(tmp, "bad.msh")],
                    ["model", model, "-o", os.path.join(tmp, "bad_model")],
                    ["batch", folder, "-o", os.path.join(tmp, "bad_batch")]):
            p = subprocess.run([wefm, *cmd, *bad], capture_output=True, text=True)
            what = f"{cmd[0]} {' '.join(bad)}"
            assert p.returncode == 2, f"{what}: exit {p.returncode}: {p.stderr}"
            assert "invalid option" in p.stderr and bad[0][2:].replace("-", "_") in p.stderr, f"{what}: {p.stderr}"
            assert "f001" not in p.stdout + p.stderr and "BRepMesh" not in p.stdout + p.stderr, f"{what}: worked first"
            for out in ("bad.msh", "bad_model", "bad_batch"):
                assert not os.path.exists(os.path.join(tmp, out)), f"{what}: wrote {out}"
    # A face the model does not have (the cylinder has 3) is known after reading it: exit 2 all the same,
    # nothing written, not a run with every face meshed free.
    p = subprocess.run([wefm, "mesh-model", model, "--size", "2", "--transfinite", "4", "-o", os.path.join(tmp, "bad.msh")],
                       capture_output=True, text=True)
    assert p.returncode == 2 and "--transfinite 4" in p.stderr and "3 faces" in p.stderr, (p.returncode, p.stderr)
    assert not os.path.exists(os.path.join(tmp, "bad.msh"))


def main():
    wefm, model = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as tmp:
        out = os.path.join(tmp, "out")
        atlas = os.path.join(tmp, "atlas.svg")
        p = subprocess.run([wefm, "model", model, "-o", out, "-j", "2", "--atlas", atlas, "--edge-mode", "periodic"],
                           capture_output=True, text=True)
        assert p.returncode == 0, f"exit {p.returncode}: {p.stderr}"
        assert "cylinder" in p.stdout and "plane" in p.stdout and "all" in p.stdout, p.stdout
        index = json.load(open(os.path.join(out, "index.json")))
        faces = index["faces"]
        assert [f["surface_type"] for f in faces].count("plane") == 2 and len(faces) == 3, faces
        assert index["summary"]["cylinder"]["ok"] == 1, index["summary"]
        for f in faces:
            assert f["status"] == "ok" and f["flipped_triangles"] == 0 and f["boundary_intersections"] == 0, f
            assert f["area_distortion_max"] < 1e-6, f
            for key in ("input_obj", "input_topology", "domain_obj", "report"):
                assert os.path.isfile(os.path.join(out, f["files"][key])), (key, f["files"])
        cyl = next(f for f in faces if f["surface_type"] == "cylinder")
        assert cyl["seam_edges"] == 1 and [d["mode"] for d in cyl["seam_decisions"]] == ["periodic"], cyl
        # The written face reproduces with wefm flatten --topology (the reproducer the index points at).
        topo = json.load(open(os.path.join(out, cyl["files"]["input_topology"])))
        seam = [e for e in topo["edges"] if e["seam"]]
        assert len(seam) == 1 and sum(u["edge"] == seam[0]["id"] for u in topo["loops"][0]) == 2, topo["loops"]
        rep = os.path.join(tmp, "r.json")
        p = subprocess.run([wefm, "flatten", os.path.join(out, cyl["files"]["input_obj"]), "--topology",
                            os.path.join(out, cyl["files"]["input_topology"]), "-o", os.path.join(tmp, "f.obj"),
                            "--edge-mode", "periodic", "--report", rep, "--quiet"], capture_output=True, text=True)
        assert p.returncode == 0, p.stderr
        assert abs(json.load(open(rep))["score"] - cyl["score"]) < 1e-9
        svg = open(atlas).read()
        assert svg.count("<polygon") == sum(f["triangles"] for f in faces), "atlas: one polygon per triangle"
        check_mesh_model(wefm, model, tmp)
        # A missing model is an I/O error naming the file.
        p = subprocess.run([wefm, "model", os.path.join(tmp, "nope.step"), "-o", out], capture_output=True, text=True)
        assert p.returncode == 3 and "nope.step" in p.stderr, (p.returncode, p.stderr)
        check_plugin(wefm, model, tmp)
        check_options_first(wefm, model, tmp)
    print("ok")


if __name__ == "__main__":
    main()
