#!/usr/bin/env python3
"""Whole-model meshing side by side: `wefm mesh-model` against `gmsh -2` (OCC kernel, its default
Frontal-Delaunay) on the same models at the same size h (a fraction of the bounding-box diagonal, 1/40 by
default as in the issue's reference). Both meshes are read back from their MSH 4.1 files and measured by the
same code: triangles, Lo's lambda (geometric mean lambda_mesh, min, share below 0.6), open and non-manifold
edges (conformity), and the wall and CPU (user + sys) time of each command on this machine, the
smallest over --repeat runs. Gmsh stays out of the library and
its build; this script only runs the `gmsh` program.

usage: compare_gmsh.py WEFM OUTDIR MODEL... [--size-ratio R] [--jobs N] [--gmsh GMSH] [--repeat N] [--markdown]
"""
import argparse
import json
import math
import os
import subprocess
import sys
import time
from collections import Counter


def read_msh41_triangles(path):
    """Nodes (tag -> xyz) and 3-node triangles of a MSH 4.1 ASCII file."""
    nodes, tris = {}, []
    with open(path) as f:
        lines = iter(f.read().split("\n"))
    for line in lines:
        if line == "$Nodes":
            blocks = int(next(lines).split()[0])
            for _ in range(blocks):
                _, _, parametric, n = map(int, next(lines).split())
                tags = [int(next(lines)) for _ in range(n)]
                for t in tags:
                    nodes[t] = tuple(map(float, next(lines).split()[:3]))
        elif line == "$Elements":
            blocks = int(next(lines).split()[0])
            for _ in range(blocks):
                _, _, etype, n = map(int, next(lines).split())
                for _ in range(n):
                    v = list(map(int, next(lines).split()))
                    if etype == 2:
                        tris.append(tuple(v[1:4]))
    return nodes, tris


def quality(nodes, tris):
    logs, below, lmin = 0.0, 0, 1.0
    for a, b, c in tris:
        p, q, r = nodes[a], nodes[b], nodes[c]
        e1 = [q[i] - p[i] for i in range(3)]
        e2 = [r[i] - p[i] for i in range(3)]
        e3 = [r[i] - q[i] for i in range(3)]
        cx = (e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0])
        area = 0.5 * math.sqrt(sum(x * x for x in cx))
        sq = sum(x * x for x in e1 + e2 + e3)
        lam = 4 * math.sqrt(3) * area / sq if sq > 0 else 0.0
        logs += math.log(max(lam, 1e-300))
        below += lam < 0.6
        lmin = min(lmin, lam)
    uses = Counter(tuple(sorted((t[i], t[(i + 1) % 3]))) for t in tris for i in range(3))
    n = max(1, len(tris))
    return {"triangles": len(tris), "lambda_mesh": math.exp(logs / n), "lambda_min": lmin, "below_0_6": below / n,
            "open_edges": sum(1 for k in uses.values() if k == 1),
            "non_manifold_edges": sum(1 for k in uses.values() if k > 2)}


def timed(cmd, log, repeat=1):
    """Exit code, and the smallest wall and CPU (user + sys) time over `repeat` runs: the machine is
    shared, so single runs vary by tens of percent."""
    wall = cpu = float("inf")
    rc = 0
    for _ in range(max(1, repeat)):
        t0 = time.monotonic()
        with open(log, "w") as out:
            p = subprocess.Popen(cmd, stdout=out, stderr=subprocess.STDOUT)
            _, status, usage = os.wait4(p.pid, 0)
        wall = min(wall, time.monotonic() - t0)
        cpu = min(cpu, usage.ru_utime + usage.ru_stime)
        rc = os.waitstatus_to_exitcode(status)
        if rc != 0:
            break
    return rc, wall, cpu


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("wefm")
    ap.add_argument("outdir")
    ap.add_argument("models", nargs="+")
    ap.add_argument("--size-ratio", type=float, default=0.025)
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--gmsh", default="gmsh")
    ap.add_argument("--repeat", type=int, default=1, help="runs per command; times are the minimum")
    ap.add_argument("--markdown", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.outdir, exist_ok=True)
    rows = []
    for model in a.models:
        name = os.path.splitext(os.path.basename(model))[0]
        w_msh, w_rep = (os.path.join(a.outdir, name + s) for s in (".wefm.msh", ".wefm.json"))
        rc_w, t_w, c_w = timed([a.wefm, "mesh-model", model, "--size-ratio", str(a.size_ratio), "-o", w_msh, "--report", w_rep,
                                "-j", str(a.jobs), "-q"], os.path.join(a.outdir, name + ".wefm.log"), a.repeat)
        h = json.load(open(w_rep))["size"] if os.path.exists(w_rep) else None
        row = {"model": name, "h": h, "wefm_exit": rc_w, "wefm_time": t_w, "wefm_cpu": c_w}
        if os.path.exists(w_msh):
            row["wefm"] = quality(*read_msh41_triangles(w_msh))
        if h is not None:
            g_msh = os.path.join(a.outdir, name + ".gmsh.msh")
            rc_g, t_g, c_g = timed([a.gmsh, model, "-2", "-clmax", repr(h), "-format", "msh41", "-o", g_msh],
                                   os.path.join(a.outdir, name + ".gmsh.log"), a.repeat)
            row.update(gmsh_exit=rc_g, gmsh_time=t_g, gmsh_cpu=c_g)
            if rc_g == 0 and os.path.exists(g_msh):
                row["gmsh"] = quality(*read_msh41_triangles(g_msh))
        rows.append(row)
    json.dump(rows, open(os.path.join(a.outdir, "compare_gmsh.json"), "w"), indent=1)

    def cells(r, who):
        q = r.get(who)
        t, c = r.get(who + "_time"), r.get(who + "_cpu")
        if not q:
            return ["-"] * 6 + [f"failed (exit {r.get(who + '_exit')})"]
        return [str(q["triangles"]), f"{q['lambda_mesh']:.4f}", f"{q['lambda_min']:.4f}", f"{100 * q['below_0_6']:.1f} %",
                f"{q['open_edges']}/{q['non_manifold_edges']}", f"{t:.2f} s", f"{c:.2f} s"]
    head = ["model", "h"] + [f"{w} {c}" for w in ("wefm", "gmsh") for c in
                             ("triangles", "lambda_mesh", "min lambda", "below 0.6", "open/non-manifold", "wall", "CPU")]
    body = [[r["model"], f"{r['h']:.4g}" if r["h"] else "-"] + cells(r, "wefm") + cells(r, "gmsh") for r in rows]
    if a.markdown:
        print("| " + " | ".join(head) + " |")
        print("|---|" + "---:|" * (len(head) - 1))
        for b in body:
            print("| " + " | ".join(b) + " |")
    else:
        widths = [max(len(x[i]) for x in [head] + body) for i in range(len(head))]
        for b in [head] + body:
            print("  ".join(x.rjust(w) for x, w in zip(b, widths)))


if __name__ == "__main__":
    sys.exit(main())
