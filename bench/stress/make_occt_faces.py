#!/usr/bin/python3
"""Every face of CAD models tessellated by Open CASCADE at several settings, written like the real
sample (face.obj + face.seam per face), through `wefm model` (needs WEFM_WITH_OCCT).

  make_occt_faces.py WEFM OUT MODEL... [--deflections 0.001,0.003,0.0003] [--angles 0.5,0.2]

OUT/<model>_<deflection>_<angle>/fNNN/face.obj, face.seam (facet edges along the seam edges of the
face's topology, as `wefm flatten --seams` takes them) and topo.json (for `--topology`)."""
import argparse, json, os, shutil, subprocess

ap = argparse.ArgumentParser()
ap.add_argument("wefm"); ap.add_argument("out"); ap.add_argument("models", nargs="+")
ap.add_argument("--deflections", default="0.001,0.003,0.0003"); ap.add_argument("--angles", default="0.5,0.2")
a = ap.parse_args()
for model in a.models:
    for dfl in a.deflections.split(","):
        for ang in a.angles.split(","):
            tag = f"{os.path.basename(model)}_{dfl}_{ang}"
            work = os.path.join(a.out, tag, "_model")
            subprocess.run([a.wefm, "model", model, "-o", work, "-j", "1", "-q", "--deflection", dfl, "--angular-deflection", ang],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
            inp = os.path.join(work, "input")
            if not os.path.isdir(inp):
                print(f"{tag}: import failed"); continue
            n = 0
            for f in sorted(os.listdir(inp)):
                if not f.endswith(".obj"): continue
                face = os.path.join(a.out, tag, f[:-4]); os.makedirs(face, exist_ok=True)
                shutil.copy(os.path.join(inp, f), os.path.join(face, "face.obj"))
                topo = json.load(open(os.path.join(inp, f[:-4] + ".topo.json")))
                shutil.copy(os.path.join(inp, f[:-4] + ".topo.json"), os.path.join(face, "topo.json"))
                with open(os.path.join(face, "face.seam"), "w") as s:
                    s.write("# facet edges along the face's seam edges\n")
                    for e in topo["edges"]:
                        if e.get("seam"):
                            v = e["vertices"]
                            for p, q in zip(v, v[1:]): s.write(f"{p} {q}\n")
                n += 1
            shutil.rmtree(work)
            print(f"{tag}: {n} faces")
