#!/usr/bin/env python3
"""Quad-dominant and all-quad meshes of one-face CAD models against Gmsh's recombination (issue 32).

    quad_faces.py WEFM OUTDIR MODEL:H [MODEL:H ...]

For each model (a CAD file with one or a few faces) and size H: `wefm model MODEL -o OUTDIR/NAME` exports
each face as imported (input/fNNN.obj and .topo.json), `wefm mesh FACE --topology ... --size H
--elements quad-dominant|quad` meshes it, and `gmsh MODEL -2 -clmax H -setnumber Mesh.RecombineAll 1`
meshes the model (Blossom recombination). Both MSH files are read back with meshio and measured by the
same code here: quads and triangles, the quads' share of the 3D area, and the scaled Jacobian of the
quads (min over the four corners of (e1 x e2) . n / (|e1| |e2|), n the quad's mean normal, as the
library's report). Prints one JSON line per model. Needs /usr/bin/python3 (numpy, meshio) and gmsh.
"""
import glob
import json
import os
import subprocess
import sys

import meshio
import numpy as np


def scaled_jacobian(P, q):
    p = P[q]
    cr = [np.cross(p[(k + 1) % 4] - p[k], p[(k + 3) % 4] - p[k]) for k in range(4)]
    n = sum(cr)
    nn = np.linalg.norm(n)
    if nn == 0:
        return 0.0
    n = n / nn
    return min(cr[k].dot(n) / (np.linalg.norm(p[(k + 1) % 4] - p[k]) * np.linalg.norm(p[(k + 3) % 4] - p[k])) for k in range(4))


def area(P, t):
    return 0.5 * np.linalg.norm(np.cross(P[t[1]] - P[t[0]], P[t[2]] - P[t[0]]))


def measure(meshes):
    quads = tris = 0
    qa = ta = 0.0
    sj = []
    for m in meshes:
        P = m.points
        for c in m.cells:
            if c.type == "quad":
                quads += len(c.data)
                for q in c.data:
                    sj.append(scaled_jacobian(P, q))
                    qa += area(P, q[[0, 1, 2]]) + area(P, q[[0, 2, 3]])
            elif c.type == "triangle":
                tris += len(c.data)
                ta += sum(area(P, t) for t in c.data)
    return {"quads": quads, "triangles": tris, "quad_area": qa / (qa + ta) if qa + ta else 0.0,
            "sj_min": min(sj) if sj else None, "sj_mean": float(np.mean(sj)) if sj else None}


def main():
    if len(sys.argv) < 4:
        sys.exit(__doc__)
    wefm, out = sys.argv[1], sys.argv[2]
    for arg in sys.argv[3:]:
        model, h = arg.rsplit(":", 1)
        name = os.path.splitext(os.path.basename(model))[0]
        d = os.path.join(out, name)
        subprocess.run([wefm, "model", model, "-o", d, "-q"], capture_output=True)
        faces = sorted(glob.glob(os.path.join(d, "input", "f*.obj")))
        row = {"model": name, "h": float(h), "faces": len(faces)}
        for kind in ("quad-dominant", "quad"):
            meshes = []
            for f in faces:
                o = f"{d}/{os.path.basename(f)}.{kind}.msh"
                p = subprocess.run([wefm, "mesh", f, "--topology", f[:-4] + ".topo.json", "--size", h, "--elements", kind, "-o", o, "-q"],
                                   capture_output=True, text=True)
                if p.returncode:
                    meshes = None
                    row[kind] = f"exit {p.returncode}: {p.stderr.strip()[:120]}"
                    break
                meshes.append(meshio.read(o))
            if meshes is not None:
                row[kind] = measure(meshes)
        g = os.path.join(d, "gmsh.msh")
        subprocess.run(["gmsh", model, "-2", "-clmax", h, "-setnumber", "Mesh.RecombineAll", "1", "-o", g], capture_output=True)
        row["gmsh"] = measure([meshio.read(g)]) if os.path.exists(g) else "no mesh"
        print(json.dumps(row), flush=True)


if __name__ == "__main__":
    main()
