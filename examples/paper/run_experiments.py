#!/usr/bin/env python3
"""Reproduce the paper's meshing experiments (Beatty & Mukherjee 2008, §5) and write docs/RESULTS.md.

    WEFM_LIBRARY=build/release/capi/libwefm.so PYTHONPATH=bindings/python \\
        /usr/bin/python3 examples/paper/run_experiments.py [--out docs]

For each face of paper_faces.py, every s in S_VALUES with the boundary term on (mu = 1) and off
(mu = 0): flatten, mesh the domain (transfinite or free), and tabulate Lo's lambda (geometric mean,
minimum, share below 0.6), the wiggle factor of the rail lines and the time of each step. Pictures
of the domain meshes (s = 0.3, boundary term on, coarser size so they stay small) go to
OUT/results/*.svg.
"""
import argparse
import os
import platform
import sys
import time

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import paper_faces  # noqa: E402
import wefm  # noqa: E402

S_VALUES = (0.0, 0.3, 0.8, 1.0, 2.0)
TARGET_ELEMENTS = {"transfinite": 5000, "free": 15000}


def area(xyz, tri):
    a, b, c = xyz[tri[:, 0]], xyz[tri[:, 1]], xyz[tri[:, 2]]
    return 0.5 * np.linalg.norm(np.cross(b - a, c - a), axis=1).sum()


def rails(elements):
    """Interior rows and columns of a transfinite quad grid numbered j * (n + 1) + i (the library's
    order), as the library measures them."""
    width = int(elements[0, 3] - elements[0, 0])
    count = int(elements.max()) + 1
    rows = count // width
    grid = np.arange(count).reshape(rows, width)
    return list(grid[1:-1]) + list(grid.T[1:-1])


def raw_wiggle(xyz, rail):
    """Eq. 12 as printed: second differences of the rail's segment vectors over |mean vector|^2,
    the surface's own bending included."""
    L = np.diff(xyz[rail], axis=0)
    mean = L.mean(axis=0)
    return (np.linalg.norm(np.diff(L, axis=0), axis=1) ** 2).sum() / len(L) / max(mean @ mean, 1e-300)


def svg(path, uv, elements, xyz):
    lo, hi = uv.min(axis=0), uv.max(axis=0)
    scale = 800.0 / max(hi - lo)
    P = (uv - lo) * scale
    P[:, 1] = (hi[1] - lo[1]) * scale - P[:, 1]
    out = ['<svg xmlns="http://www.w3.org/2000/svg" width="%d" height="%d">' % (P[:, 0].max() + 20, P[:, 1].max() + 20)]
    for e in elements:
        a, b, c = xyz[e[0]], xyz[e[1]], xyz[e[2]]
        lam = 4 * np.sqrt(3) * 0.5 * np.linalg.norm(np.cross(b - a, c - a)) / ((b - a) @ (b - a) + (c - b) @ (c - b) + (a - c) @ (a - c))
        t = min(1.0, max(0.0, (lam - 0.6) / 0.4))
        pts = " ".join("%.1f,%.1f" % (P[k, 0] + 10, P[k, 1] + 10) for k in e)
        out.append('<polygon fill="rgb(%d,%d,80)" stroke="black" stroke-width="0.3" points="%s"/>' % (255 * (1 - t), 55 + 200 * t, pts))
    out.append("</svg>")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def run_face(name, gen, kind, pictures):
    xyz, tri = gen()
    h = np.sqrt(area(xyz, tri) / (0.433 * TARGET_ELEMENTS[kind])) if kind == "free" else np.sqrt(area(xyz, tri) / TARGET_ELEMENTS[kind])
    rows = []
    for mu in (1.0, 0.0):
        for s in S_VALUES:
            with wefm.Face(xyz, tri) as f:
                t0 = time.perf_counter()
                rep = f.solve(strict=False, s=s, boundary_weight=mu)
                t_flat = time.perf_counter() - t0
                t0 = time.perf_counter()
                with f.mesh_domain(size=h, type=kind) as dm:
                    t_mesh = time.perf_counter() - t0
                    r = dm.report
                    row = dict(s=s, mu=mu, score=rep.score, flips=rep.flipped_triangles, t_flat=t_flat, t_mesh=t_mesh,
                               elements=r.elements, lam=r.lambda_mesh, lmin=r.lambda_min, below=r.fraction_below_0_6,
                               wmax=r.wiggle_max, wmean=r.wiggle_mean, sj=r.scaled_jacobian_min, raw=float("nan"))
                    if kind == "transfinite":
                        X, E = dm.xyz, dm.elements
                        row["raw"] = max(raw_wiggle(X, rl) for rl in rails(E))
                if pictures and s == 0.3 and mu == 1.0:
                    with f.mesh_domain(size=3.5 * h, type=kind, quads=0) as pic:
                        svg(os.path.join(pictures, name + ".svg"), pic.uv, pic.elements, pic.xyz)
            rows.append(row)
            print("%-24s s=%.1f mu=%.0f  lambda %.4f min %.4f wiggle %.3g  (%.2f s + %.2f s)" %
                  (name, s, mu, row["lam"], row["lmin"], row["wmax"], t_flat, t_mesh), flush=True)
    return len(tri), h, rows


def table(kind, rows):
    head = "| s | boundary term | score | λ_mesh | min λ | < 0.6 |"
    head += " wiggle max | wiggle mean | raw eq. 12 max | min scaled Jacobian |" if kind == "transfinite" else ""
    head += " elements | flatten (s) | mesh (s) |"
    out = [head, "|" + "---|" * (head.count("|") - 1)]
    for r in rows:
        line = "| %.1f | %s | %.4f | %.4f | %.4f | %.2f%% |" % (r["s"], "on" if r["mu"] else "off", r["score"], r["lam"], r["lmin"], 100 * r["below"])
        if kind == "transfinite":
            line += " %.2e | %.2e | %.2e | %.4f |" % (r["wmax"], r["wmean"], r["raw"], r["sj"])
        line += " %d | %.2f | %.2f |" % (r["elements"], r["t_flat"], r["t_mesh"])
        out.append(line)
    return "\n".join(out)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--out", default=os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "docs"))
    args = ap.parse_args()
    pictures = os.path.join(args.out, "results")
    os.makedirs(pictures, exist_ok=True)
    sections = []
    for name, (gen, kind) in paper_faces.FACES.items():
        n_tri, h, rows = run_face(name, gen, kind, pictures)
        sections.append("### %s (%s mesh)\n\nInput: %d triangles (`examples/paper/paper_faces.py`). Mesh size h = %.4f.\n"
                        "Picture: [results/%s.svg](results/%s.svg) (s = 0.3, boundary term on, size 3.5 h, triangles coloured by λ).\n\n%s\n"
                        % (name.replace("_", " "), kind, n_tri, h, name, name, table(kind, rows)))
    # Only our section of RESULTS.md is rewritten (between the markers); other generators own the rest.
    path = os.path.join(args.out, "RESULTS.md")
    text = open(path).read() if os.path.exists(path) else "# Results\n"
    block = BEGIN + "\n" + HEADER % (platform.machine(), platform.python_version()) + "\n".join(sections) + FOOTER + END
    if BEGIN in text and END in text:
        text = text[:text.index(BEGIN)] + block + text[text.index(END) + len(END):]
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    with open(path, "w") as f:
        f.write(text)


BEGIN, END = "<!-- paper-results:begin -->", "<!-- paper-results:end -->"

HEADER = """## Meshing the domain: the paper's experiments

Generated by `examples/paper/run_experiments.py` (rerun it to refresh this section; machine %s, Python %s).
Every mesh is measured on its **3D** image: Lo's λ = 4√3·area / Σ l² per triangle (quads: the two
triangles of the shorter diagonal), λ_mesh their geometric mean, min λ, the share below λ_cr = 0.6;
for transfinite meshes the minimum scaled Jacobian of the quads and the wiggle factor of every rail
line (eq. 12). Times are wall-clock seconds of the flatten (all continuation steps) and of meshing
(boundary, mesh, smoothing, mapping) on a shared 2-core machine.

Wiggle factors are over the interior rail lines (the boundary ones are the boundary discretisation:
the same 3D points for every domain). Two wiggle columns: *wiggle* is what the library reports, eq. 12 with the component of each second
difference along the surface normal removed (waviness within the surface; a rail that follows the
surface's own bending scores 0, so a cut cylinder scores 0); *raw eq. 12* is the formula as printed,
second differences of the 3D segment vectors over |mean vector|², which also counts the normal
curvature every rail on a curved face must have.

"""

FOOTER = """
### Reading the tables against the paper

- **Curved plate with holes, free mesh** (issue target: λ_mesh ≥ 0.95 and min λ ≥ 0.5 near 15k
  triangles at s = 0.8 with the boundary term): met in every row, s = 0.8 / on included (λ_mesh
  ≈ 0.99). The free mesher places its nodes frontally at the 3D size, stepping through the map's
  metric, and moves them only where the 3D quality improves, so the domain's own distortion is
  largely absorbed: λ barely moves with s or the boundary term here, unlike the paper, whose mesher
  took the UV size at face value.
- **Vessel wall, transfinite**: the paper reports wiggle 0.12 for a conformal domain without the
  boundary term and 0.007 at s = 0.3 with it. We do **not** reproduce that trend: our wiggle is ~1e-3
  for every s and both settings of the boundary term (below the paper's 0.007 everywhere). The reason
  is our patch: it is bounded by two meridians and two parallels of a surface of revolution, and the
  conformal map of such a patch is already a rectangle (a Mercator-like map), so no domain bends the
  Coons lines. The paper's wall is a different part; a patch whose boundary cuts across meridians
  would be needed to show the effect, and is not built here.
- **Helical strip, transfinite**: every row is the same to four digits; the helicoid strip's domains
  hardly depend on s (score ≥ 0.999), so neither do its meshes.
- Quad λ values near 0.85 are those of the right triangles of nearly square quads (λ = √3/2 for an
  exact square), not poor elements; the scaled Jacobian is the quads' measure.
"""


if __name__ == "__main__":
    main()
