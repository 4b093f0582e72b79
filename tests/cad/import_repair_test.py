#!/usr/bin/env python3
"""`wefm mesh-model` on the small public models whose faces the CAD import once handed over in a shape
no flattener accepts (issue 28, "every face meshed"), at 1/40 of the bounding-box diagonal:

- gmsh_CylinderInnerLoopCrossingSeam.brep: a hole in a cylinder whose two lobes meet on the seam
  (BRepMesh's facets form two fans at that vertex);
- gmsh_PeriodicFaceWithLargeTolerance.brep: holes whose wires touch the outer wire at a vertex;
- gmsh_SlenderSurface.brep: an INTERNAL face (its edges read as constraint lines: "no wire");
- gmsh_U_Joint_2.stp: B-spline faces with a pole where BRepMesh leaves two facets on the same three
  nodes facing opposite ways, hanging on the rest by the pole alone (two fans there).

For each: exit 0, every face meshed with triangles of non-zero quality, and the mesh's edges used as
the B-rep says (the report's conformity counts nothing unexplained). The figures are the tool's own
report of its own mesh, none is written here.

usage: import_repair_test.py WEFM CAD_MORE_DIR
"""
import json
import os
import subprocess
import sys
import tempfile

MODELS = ["gmsh_CylinderInnerLoopCrossingSeam.brep", "gmsh_PeriodicFaceWithLargeTolerance.brep",
          "gmsh_SlenderSurface.brep", "gmsh_U_Joint_2.stp"]


def check(wefm, model, tmp):
    name = os.path.basename(model)
    msh, rep = os.path.join(tmp, name + ".msh"), os.path.join(tmp, name + ".json")
    p = subprocess.run([wefm, "mesh-model", model, "-o", msh, "--size-ratio", "0.025", "--report", rep, "-q"],
                       capture_output=True, text=True, timeout=120)
    assert p.returncode == 0, f"{name}: exit {p.returncode}\n{p.stderr[-2000:]}"
    r = json.load(open(rep))
    for f in r["faces"]:
        assert f["status"] == "ok", f"{name}: face {f['face']} {f['status']}: {f['reason']}"
        assert f["elements"] > 0 and f["lambda_min"] > 0, f"{name}: face {f['face']}: {f}"
    c = r["conformity"]
    assert c["unexplained_open_edges"] == 0 and c["unexplained_non_manifold_edges"] == 0, f"{name}: {c}"
    assert c["zero_area_triangles"] == 0, f"{name}: {c}"
    print(f"{name}: {len(r['faces'])} faces meshed, {r['triangles']} triangles, min lambda {r['lambda_min']:.3f}")


def main():
    wefm, folder = sys.argv[1:3]
    missing = [m for m in MODELS if not os.path.exists(os.path.join(folder, m))]
    if missing:
        print(f"the models {missing} are not in {folder}")
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        for m in MODELS:
            check(wefm, os.path.join(folder, m), tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
