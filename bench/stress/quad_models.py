#!/usr/bin/env python3
"""Quad-dominant or all-quad whole models against Gmsh's recombination (issue 32): every model at
h = R x the bounding-box diagonal, `wefm mesh-model MODEL --size-ratio R --elements quad-dominant -j 1`
and `gmsh MODEL -2 -clmax h -setnumber Mesh.RecombineAll 1 -nt 1` (Blossom); with `--elements quad`,
wefm's all-quad meshes against Gmsh's with `-setnumber Mesh.SubdivisionAlgorithm 1` too (both split
every element into quads, sides about h / 2). Whole processes under a time limit; both MSH files read back and measured here alike: quads and triangles, the quads' share of the
3D area, the scaled Jacobian of the quads (min over the corners of (e1 x e2) . n / (|e1| |e2|), n the
quad's mean normal; below 0 is folded or inverted), element edges used once (open) or more than twice
(non-manifold), and wall time. wefm's report says which open or non-manifold edges its B-rep explains,
and how many four-sided faces it meshed mapped.

    quad_models.py WEFM OUTDIR MODEL... [--ratio R] [--timeout S] [--elements quad-dominant|quad]
    quad_models.py - OUTDIR - --table-only     # the table of an earlier run again (WEFM, MODEL ignored)

Prints a Markdown table and a summary; writes OUTDIR/quads.json. Needs /usr/bin/python3 (numpy, meshio).
"""
import argparse
import json
import os
import subprocess
import sys
import time

import meshio
import numpy as np


def measure(path):
    m = meshio.read(path)
    P = m.points
    quads = [c.data for c in m.cells if c.type == "quad"]
    tris = [c.data for c in m.cells if c.type == "triangle"]
    Q = np.vstack(quads) if quads else np.zeros((0, 4), int)
    T = np.vstack(tris) if tris else np.zeros((0, 3), int)
    out = {"quads": len(Q), "triangles": len(T)}
    tri_area = lambda a, b, c: 0.5 * np.linalg.norm(np.cross(P[b] - P[a], P[c] - P[a]), axis=1)
    qa = tri_area(Q[:, 0], Q[:, 1], Q[:, 2]).sum() + tri_area(Q[:, 0], Q[:, 2], Q[:, 3]).sum() if len(Q) else 0.0
    ta = tri_area(T[:, 0], T[:, 1], T[:, 2]).sum() if len(T) else 0.0
    out["quad_area"] = float(qa / (qa + ta)) if qa + ta > 0 else 0.0
    if len(Q):
        p = [P[Q[:, k]] for k in range(4)]
        cr = [np.cross(p[(k + 1) % 4] - p[k], p[(k + 3) % 4] - p[k]) for k in range(4)]
        n = sum(cr)
        nn = np.linalg.norm(n, axis=1)
        n = n / np.where(nn > 0, nn, 1)[:, None]
        sj = np.min([np.einsum("ij,ij->i", cr[k], n) /
                     np.maximum(np.linalg.norm(p[(k + 1) % 4] - p[k], axis=1) * np.linalg.norm(p[(k + 3) % 4] - p[k], axis=1), 1e-300)
                     for k in range(4)], axis=0)
        sj = np.where(nn > 0, sj, 0.0)
        out.update(sj_min=float(sj.min()), sj_mean=float(sj.mean()), folded=int((sj <= 0).sum()))
    edges = {}
    for E in (Q, T):
        k = E.shape[1]
        for i in range(k):
            a, b = np.minimum(E[:, i], E[:, (i + 1) % k]), np.maximum(E[:, i], E[:, (i + 1) % k])
            for key in zip(a.tolist(), b.tolist()):
                edges[key] = edges.get(key, 0) + 1
    uses = np.array(list(edges.values())) if edges else np.zeros(0)
    out.update(open=int((uses == 1).sum()), non_manifold=int((uses > 2).sum()))
    return out


def timed(cmd, log, timeout):
    t0 = time.monotonic()
    try:
        with open(log, "w") as f:
            rc = subprocess.run(cmd, stdout=f, stderr=subprocess.STDOUT, timeout=timeout).returncode
    except subprocess.TimeoutExpired:
        rc = "timeout"
    return rc, time.monotonic() - t0


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("wefm")
    ap.add_argument("outdir")
    ap.add_argument("models", nargs="+")
    ap.add_argument("--ratio", type=float, default=0.025)
    ap.add_argument("--timeout", type=float, default=300)
    ap.add_argument("--elements", choices=["quad-dominant", "quad"], default="quad-dominant")
    ap.add_argument("--table-only", action="store_true", help="print the table of OUTDIR/quads.json again, running nothing")
    a = ap.parse_args()
    if a.table_only:
        rows = json.load(open(os.path.join(a.outdir, "quads.json")))
        for r in rows:  # runs from before the mapped column: their reports have it
            path = os.path.join(a.outdir, r["model"] + ".wefm.json")
            if "mapped" not in r["wefm"] and os.path.exists(path):
                r["wefm"]["mapped"] = json.load(open(path)).get("mapped")
        print_table(rows)
        return
    subdivide = ["-setnumber", "Mesh.SubdivisionAlgorithm", "1"] if a.elements == "quad" else []
    os.makedirs(a.outdir, exist_ok=True)
    rows = []
    for model in a.models:
        name = os.path.splitext(os.path.basename(model))[0]
        base = os.path.join(a.outdir, name)
        rc, wall = timed([a.wefm, "mesh-model", model, "--size-ratio", repr(a.ratio), "--elements", a.elements, "-j", "1",
                          "-o", base + ".wefm.msh", "--report", base + ".wefm.json", "-q"], base + ".wefm.log", a.timeout)
        row = {"model": name, "wefm": {"exit": rc, "wall": wall}}
        if rc in (0, 5) and os.path.exists(base + ".wefm.json"):
            rep = json.load(open(base + ".wefm.json"))
            row["h"] = rep["size"]
            c = rep["conformity"]
            row["wefm"].update(measure(base + ".wefm.msh"), unexplained=c["unexplained_open_edges"] + c["unexplained_non_manifold_edges"],
                               mapped=rep.get("mapped"))
            rc, wall = timed(["gmsh", model, "-2", "-clmax", repr(rep["size"]), "-setnumber", "Mesh.RecombineAll", "1", *subdivide, "-nt", "1",
                              "-format", "msh41", "-o", base + ".gmsh.msh"], base + ".gmsh.log", a.timeout)
            row["gmsh"] = {"exit": rc, "wall": wall}
            if rc == 0 and os.path.exists(base + ".gmsh.msh"):
                try:
                    row["gmsh"].update(measure(base + ".gmsh.msh"))
                except Exception as e:  # a mesh meshio cannot read
                    row["gmsh"]["error"] = str(e)[:80]
        rows.append(row)
        print(json.dumps(row), file=sys.stderr, flush=True)
    json.dump(rows, open(os.path.join(a.outdir, "quads.json"), "w"), indent=1)
    print_table(rows)


def print_table(rows):
    """The Markdown table and the summary line of a run's rows."""
    def cell(r, who):
        x = r.get(who, {})
        if "quads" not in x:
            return [str(x.get("exit", "-"))] + ["-"] * 5
        sj = f"{x['sj_min']:.2f} / {x['sj_mean']:.3f}" if "sj_min" in x else "-"
        return [str(x["exit"]), f"{x['quads']} + {x['triangles']}", f"{100 * x['quad_area']:.1f}", sj, f"{x['open']}/{x['non_manifold']}", f"{x['wall']:.1f}"]

    def mapped(r):
        m = r.get("wefm", {}).get("mapped")
        return f"{m['mapped']} / {m['candidates']}" if m else "-"
    print("| model | h | wefm exit | wefm quads + tris | wefm % area in quads | wefm SJ min / mean | wefm open/nm | wefm s | wefm mapped / four-sided | "
          "gmsh exit | gmsh quads + tris | gmsh % area in quads | gmsh SJ min / mean | gmsh open/nm | gmsh s |")
    print("|---|---:|" + "---|" * 13)
    for r in rows:
        print("| " + " | ".join([r["model"], f"{r['h']:.4g}" if "h" in r else "-"] + cell(r, "wefm") + [mapped(r)] + cell(r, "gmsh")) + " |")
    both = [r for r in rows if "sj_mean" in r["wefm"] and "sj_mean" in r.get("gmsh", {})]
    ok = [r for r in rows if "quads" in r["wefm"]]
    print(f"\n{len(rows)} models: wefm exit 0 on {sum(1 for r in rows if r['wefm']['exit'] == 0)}, "
          f"unexplained edges on {sum(1 for r in ok if r['wefm']['unexplained'])}, "
          f"at least 95 % of the area in quads on {sum(1 for r in ok if r['wefm']['quad_area'] >= 0.95)}, "
          f"min scaled Jacobian >= 0.3 on {sum(1 for r in ok if r['wefm'].get('sj_min', 0) >= 0.3)}, "
          f"folded or inverted quads on {sum(1 for r in ok if r['wefm'].get('folded', 0))}; where both make quads ({len(both)}): "
          f"mean scaled Jacobian >= Gmsh's on {sum(1 for r in both if r['wefm']['sj_mean'] >= r['gmsh']['sj_mean'])}, "
          f"wall {sum(r['wefm']['wall'] for r in both):.1f} s against Gmsh's {sum(r['gmsh']['wall'] for r in both):.1f} s")
    ms = [r["wefm"]["mapped"] for r in ok if r["wefm"].get("mapped")]
    if ms:
        print(f"mapped faces: {sum(m['mapped'] for m in ms)} of {sum(m['candidates'] for m in ms)} four-sided or named "
              f"({sum(m['planned_free'] for m in ms)} planned free, {sum(m['meshed_free'] for m in ms)} meshed free), "
              f"{sum(m['recounted_edges'] for m in ms)} edges recounted, {sum(m['mismatched'] for m in ms)} mapped faces with unlike opposite counts")


if __name__ == "__main__":
    main()
