#!/usr/bin/env python3
"""`wefm model` end to end on the checked-in STEP cylinder: usage: cli_model_test.py WEFM CYLINDER.step"""
import json
import os
import subprocess
import sys
import tempfile


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
        # A missing model is an I/O error naming the file.
        p = subprocess.run([wefm, "model", os.path.join(tmp, "nope.step"), "-o", out], capture_output=True, text=True)
        assert p.returncode == 3 and "nope.step" in p.stderr, (p.returncode, p.stderr)
    print("ok")


if __name__ == "__main__":
    main()
