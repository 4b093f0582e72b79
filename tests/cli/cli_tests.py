#!/usr/bin/env python3
"""End-to-end tests of the `wefm` command-line tool: cli_tests.py WEFM_BINARY CASE.

Each case builds its small inputs in a fresh temporary directory (meshes.py), runs the binary and
checks properties of what it wrote (counts, orientation, JSON fields, XML), not just exit codes.
Standard library only, so any python3 runs it.
"""
import json
import math
import os
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import meshes  # noqa: E402

WEFM = None
SVG_NS = "{http://www.w3.org/2000/svg}"


class Failure(Exception):
    pass


def check(cond, what):
    if not cond:
        raise Failure(what)


def run(*args, expect=None, env=None):
    p = subprocess.run([WEFM, *map(str, args)], capture_output=True, text=True, timeout=120,
                       env=None if env is None else {**os.environ, **env})
    if expect is not None and p.returncode != expect:
        raise Failure(f"wefm {' '.join(map(str, args))}: exit {p.returncode}, expected {expect}\n"
                      f"stdout:\n{p.stdout}\nstderr:\n{p.stderr}")
    return p


def read_obj(path):
    V, VT, F = [], [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                V.append(tuple(map(float, p[1:4])))
            elif p[0] == "vt":
                VT.append(tuple(map(float, p[1:3])))
            elif p[0] == "f":
                check(len(p) == 4, f"{path}: non-triangle face line {line!r}")
                F.append([tuple(int(x) - 1 for x in q.split("/")) for q in p[1:]])
    return V, VT, F


def signed_uv_areas(VT, F):
    out = []
    for t in F:
        (u0, v0), (u1, v1), (u2, v2) = (VT[c[1]] for c in t)
        out.append(0.5 * ((u1 - u0) * (v2 - v0) - (v1 - v0) * (u2 - u0)))
    return out


def area3(V, t):
    p, q, r = (V[k] for k in t)
    u = [q[i] - p[i] for i in range(3)]
    v = [r[i] - p[i] for i in range(3)]
    n = (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])
    return 0.5 * sum(c * c for c in n) ** 0.5


def check_uv_obj(path, V_in, T_in, exact_order=True, tol=1e-12):
    """The OBJ holds the input's vertices (v), one vt per use, the input's triangles, none flipped."""
    V, VT, F = read_obj(path)
    check(len(V) == len(V_in), f"{path}: {len(V)} v lines, input has {len(V_in)} vertices")
    check(len(F) == len(T_in), f"{path}: {len(F)} f lines, input has {len(T_in)} triangles")
    check(len(VT) >= len(V), f"{path}: {len(VT)} vt lines < {len(V)} vertices")
    used = {c[1] for t in F for c in t}
    check(used == set(range(len(VT))), f"{path}: vt indices do not cover 0..{len(VT) - 1} exactly")
    if exact_order:
        for a, b in zip(V, V_in):
            check(max(abs(x - y) for x, y in zip(a, b)) < tol, f"{path}: vertex {a} differs from input {b}")
        check([tuple(c[0] for c in t) for t in F] == [tuple(t) for t in T_in], f"{path}: triangles differ from input")
    else:  # STL: vertices were merged and renumbered; compare triangles by their float32 corner positions
        key = lambda p: tuple(round(x, 5) for x in p)
        got = sorted(tuple(key(V[c[0]]) for c in t) for t in F)
        want = sorted(tuple(key(V_in[k]) for k in t) for t in T_in)
        check(got == want, f"{path}: triangles (by position) differ from input")
    areas = signed_uv_areas(VT, F)
    check(all(a > 0 for a in areas) or all(a < 0 for a in areas), f"{path}: UV triangles not consistently oriented")
    return V, VT, F


def check_report(path, n_vertices, n_triangles, obj_vt):
    r = json.load(open(path))
    for key in ["wefm_version", "input", "status", "score", "flipped_triangles", "boundary_intersections",
                "area_distortion_mean", "area_distortion_max", "angle_distortion_mean", "angle_distortion_max",
                "uv_area", "area_3d", "s", "converged", "edge_decisions", "iterations", "counters", "timings",
                "peak_memory_mb", "mesh", "topology", "outputs"]:
        check(key in r, f"{path}: no field {key}")
    check(r["status"] == "ok" and r["exit_code"] == 0, f"{path}: status {r['status']}")
    check(r["mesh"]["vertices"] == n_vertices and r["mesh"]["triangles"] == n_triangles, f"{path}: mesh counts")
    check(r["topology"]["uses"] == obj_vt, f"{path}: uses {r['topology']['uses']} != vt lines {obj_vt}")
    check(r["flipped_triangles"] == 0 and r["boundary_intersections"] == 0, f"{path}: flips/overlaps")
    check(0 < r["score"] <= 1, f"{path}: score {r['score']}")
    check(r["area_distortion_mean"] <= r["area_distortion_max"], f"{path}: distortion mean > max")
    check(r["angle_distortion_mean"] >= 1 - 1e-9, f"{path}: angle distortion below 1")
    check(r["counters"]["numeric_factorizations"] >= 1 and r["counters"]["solves"] >= 1, f"{path}: counters")
    check(r["timings"]["total"] >= 0 and r["iterations"]["s_steps"] >= 1, f"{path}: timings/iterations")
    # At the default s = 1 no continuation step is longer than 1: none is tentative.
    check(r["iterations"]["abandoned_steps"] == 0, f"{path}: abandoned steps at s = 1")
    check(abs(r["s"] - 1.0) < 1e-12, f"{path}: default s should be reached (1), got {r['s']}")
    return r


def check_svg(path, n_triangles):
    root = ET.parse(path).getroot()  # raises on malformed XML
    check(root.tag == SVG_NS + "svg", f"{path}: root is {root.tag}")
    polys = root.findall(f".//{SVG_NS}polygon")
    check(len(polys) == n_triangles, f"{path}: {len(polys)} polygons for {n_triangles} triangles")
    check(root.find(f".//{SVG_NS}linearGradient") is not None, f"{path}: no legend gradient")
    loops = root.find(f".//{SVG_NS}g[@id='loops']")
    check(loops is not None and loops.find(f"{SVG_NS}path").get("d"), f"{path}: loops not drawn")
    return root


# ---------------------------------------------------------------------------------------------------

def case_format(fmt, tmp):
    V, T = meshes.patch()
    ext = {"stl_ascii": "stl", "stl_binary": "stl"}.get(fmt, fmt)
    src = os.path.join(tmp, f"patch.{ext}")
    meshes.WRITERS[fmt](src, V, T)
    out = os.path.join(tmp, "out", "patch_uv.obj")
    rep = os.path.join(tmp, "out", "report.json")
    svg = os.path.join(tmp, "out", "domain.svg")
    p = run("flatten", src, "-o", out, "--report", rep, "--svg", svg, expect=0)
    is_stl = fmt.startswith("stl")
    # OFF and PLY come back through float32 in this library version (see apps/README.md), so
    # positions are compared to 1e-6 there; OBJ keeps doubles exactly.
    _, VT, _ = check_uv_obj(out, V, T, exact_order=not is_stl, tol=1e-12 if fmt == "obj" else 1e-6)
    r = check_report(rep, len(V), len(T), len(VT))
    merged = r["mesh"]["merged_vertices"]
    # STL: 3 corners per triangle merged to the shared vertices. How many the library counts as
    # "merged" (all duplicates or only those its own tolerance pass merged) is its business; other
    # formats merge nothing.
    check(0 <= merged <= 3 * len(T) - len(V) if is_stl else merged == 0, f"{fmt}: merged_vertices {merged}")
    check(f"{merged} merged vertices" in p.stdout, f"summary does not print merged vertices:\n{p.stdout}")
    check(r["outputs"].get("uv_mesh") == out and r["outputs"].get("domain_picture") == svg, f"report outputs {r['outputs']}")
    check_svg(svg, len(T))
    for what in [out, rep, svg]:
        check(what in p.stdout, f"summary does not say where {what} went:\n{p.stdout}")


def case_info(tmp):
    V, T = meshes.patch()
    for fmt in meshes.WRITERS:
        ext = {"stl_ascii": "stl", "stl_binary": "stl"}.get(fmt, fmt)
        src = os.path.join(tmp, f"{fmt}.{ext}")
        meshes.WRITERS[fmt](src, V, T)
        j = json.loads(run("info", src, "--json", expect=0).stdout)
        check(j["vertices"] == len(V) and j["triangles"] == len(T), f"{fmt}: info counts {j}")
        check(j["boundary_loops"] == 1 and j["components"] == 1 and j["genus"] == 0, f"{fmt}: info topology {j}")
        check(j["non_manifold_edges"] == 0 and j["duplicate_triangles"] == 0, f"{fmt}: defects {j}")
        check(abs(j["bbox_max"][0] - 1.0) < 1e-6 and abs(j["bbox_min"][0]) < 1e-6, f"{fmt}: bbox {j}")
        want_area = sum(area3(V, t) for t in T)
        check(abs(j["area"] - want_area) < 1e-5 * want_area, f"{fmt}: area {j['area']} vs {want_area}")
        check(fmt.startswith("stl") or j["merged_vertices"] == 0, f"{fmt}: merged {j['merged_vertices']}")
        text = run("info", src, expect=0).stdout
        check(f"triangles" in text and f" {len(T)}\n" in text and "mean edge length" in text, f"info text:\n{text}")
    run("info", os.path.join(tmp, "missing.obj"), expect=3)


def case_batch(tmp):
    V, T = meshes.patch()
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    meshes.write_obj(os.path.join(d, "good.obj"), V, T)
    with open(os.path.join(d, "broken.obj"), "w") as f:
        f.write("v 0 0 0\nv 1 0 0\nf 1 2 7\nthis is not a mesh\n")
    out = os.path.join(tmp, "out")
    p = run("batch", d, "-o", out, "-j", "2", "--summary-json", os.path.join(tmp, "summary.json"))
    check(p.returncode != 0, f"batch with a broken file exited 0\n{p.stdout}{p.stderr}")
    _, VT, _ = check_uv_obj(os.path.join(out, "good.obj"), V, T)
    check_report(os.path.join(out, "good.json"), len(V), len(T), len(VT))
    check(not os.path.exists(os.path.join(out, "broken.obj")), "broken face produced an OBJ")
    rows = {r["name"]: r for r in json.load(open(os.path.join(tmp, "summary.json")))}
    check(rows["good"]["status"] == "ok" and rows["good"]["triangles"] == len(T), f"summary good row {rows['good']}")
    check(rows["broken"]["status"] != "ok" and rows["broken"]["exit_code"] in (3, 4), f"broken row {rows['broken']}")
    lines = p.stdout.splitlines()
    check(any(l.startswith("good ") and l.rstrip().endswith("ok") for l in lines), f"table lacks good row:\n{p.stdout}")
    check(any(l.startswith("broken ") for l in lines), f"table lacks broken row:\n{p.stdout}")
    check("broken.obj" in p.stderr, f"the broken file is not named on stderr:\n{p.stderr}")
    # A data/real-like folder of face folders: face.seam with data is picked up, comment-only is not.
    real = os.path.join(tmp, "real")
    Vc, Tc, seam, bottom, top = meshes.cylinder()
    os.makedirs(os.path.join(real, "cyl"))
    meshes.write_obj(os.path.join(real, "cyl", "face.obj"), Vc, Tc)
    with open(os.path.join(real, "cyl", "face.seam"), "w") as f:
        f.write("# seam edge ids: 20\n" + "".join(f"{a} {b}\n" for a, b in zip(seam, seam[1:])))
    json.dump(meshes.cylinder_topology(seam, bottom, top), open(os.path.join(real, "cyl", "topo.json"), "w"))
    os.makedirs(os.path.join(real, "flat"))
    meshes.write_obj(os.path.join(real, "flat", "face.obj"), V, T)
    with open(os.path.join(real, "flat", "face.seam"), "w") as f:
        f.write("# seam edge ids: none\n")
    for extra in ([], ["--use-topology"]):
        out2 = os.path.join(tmp, "out_real" + "".join(extra))
        p = run("batch", real, "-o", out2, "-j", "2", "-q", *extra, expect=0)
        _, VTc, _ = check_uv_obj(os.path.join(out2, "cyl.obj"), Vc, Tc)
        check(len(VTc) == len(Vc) + len(seam), f"cylinder cut: {len(VTc)} uses, want {len(Vc) + len(seam)}")
        rc = json.load(open(os.path.join(out2, "cyl.json")))
        check(rc["topology"]["repeated_edges"] == 1, f"{extra}: repeated edges {rc['topology']}")
        if extra:
            check(rc["edge_decisions"][0]["id"] == 20, f"topology ids not used: {rc['edge_decisions']}")
        check_uv_obj(os.path.join(out2, "flat.obj"), V, T)
        check(p.stderr == "", f"--quiet batch wrote to stderr:\n{p.stderr}")


def case_usage(tmp):
    V, T = meshes.patch()
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, V, T)
    o = os.path.join(tmp, "o.obj")
    for args in [[], ["frobnicate"], ["flatten"], ["flatten", src], ["flatten", src, "-o", o, "--bogus"],
                 ["flatten", src, "-o", o, "--s", "abc"], ["flatten", src, "-o", o, "--method", "magic"],
                 ["flatten", src, "-o", o, "--edge-mode-of", "3"], ["flatten", src, "-o", o, "--s"],
                 ["flatten", src, "-o", o, "--seams", "a", "--topology", "b"], ["flatten", src, "-o", o, "--s", "7"],
                 ["info"], ["batch", tmp], ["batch", tmp, "-o", o, "-j", "0"]]:
        p = run(*args, expect=2)
        check(p.stderr.strip() or not args, f"wefm {args}: exit 2 without a message")
    check(not os.path.exists(o), "a usage error still wrote an output")
    h = run("--help", expect=0).stdout
    check("flatten" in h and "batch" in h and "info" in h and "Exit codes" in h, f"--help:\n{h}")
    fh = run("flatten", "--help", expect=0).stdout
    for opt in ["--s ", "--k ", "--boundary-weight", "--method", "--no-curvature-adjust", "--s-step", "--rho-tolerance",
                "--max-rho-iterations", "--min-beta", "--solver", "--edge-mode ", "--edge-mode-of", "--auto-cut",
                "--threads", "--score-threshold", "--outer-loop", "--seams", "--topology", "--write-topology",
                "--report", "--svg", "--quiet", "--output"]:
        check(opt in fh, f"flatten --help lacks {opt}")
    check("[default: 1]" in fh and "[default: global]" in fh, f"flatten --help lacks defaults:\n{fh}")
    v = run("--version", expect=0).stdout
    check(v.startswith("wefm ") and v.split()[1].count(".") == 2, f"--version: {v}")


def case_unreadable(tmp):
    V, T = meshes.patch()
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, V, T)
    p = run("flatten", os.path.join(tmp, "nope.obj"), "-o", os.path.join(tmp, "o.obj"), expect=3)
    check("nope.obj" in p.stderr, f"message does not name the file: {p.stderr}")
    blocker = os.path.join(tmp, "file")
    open(blocker, "w").close()
    run("flatten", src, "-o", os.path.join(blocker, "o.obj"), expect=3)  # parent is a file
    run("flatten", src, "-o", os.path.join(tmp, "o.obj"), "--seams", os.path.join(tmp, "nope.seam"), expect=3)
    run("flatten", src, "-o", os.path.join(tmp, "o.obj"), "--topology", os.path.join(tmp, "nope.json"), expect=3)
    with open(os.path.join(tmp, "x.xyz"), "w") as f:
        f.write("1 2 3\n")
    run("flatten", os.path.join(tmp, "x.xyz"), "-o", os.path.join(tmp, "o.obj"), expect=3)


def cylinder_files(tmp, seam_mode=None):
    V, T, seam, bottom, top = meshes.cylinder()
    src = os.path.join(tmp, "cyl.obj")
    meshes.write_obj(src, V, T)
    topo = os.path.join(tmp, "cyl_topo.json")
    json.dump(meshes.cylinder_topology(seam, bottom, top, seam_mode), open(topo, "w"), indent=1)
    return V, T, seam, src, topo


def case_topology(tmp):
    V, T, seam, src, topo = cylinder_files(tmp)
    out, rep, svg = (os.path.join(tmp, n) for n in ("cyl_uv.obj", "cyl.json", "cyl.svg"))
    p = run("flatten", src, "-o", out, "--topology", topo, "--report", rep, "--svg", svg, expect=0)
    _, VT, F = check_uv_obj(out, V, T)
    check(len(VT) == len(V) + len(seam), f"cut cylinder has {len(VT)} uses, want {len(V) + len(seam)}")
    r = check_report(rep, len(V), len(T), len(VT))
    check(r["topology"]["edges"] == 3 and r["topology"]["loops"] == 1 and r["topology"]["repeated_edges"] == 1,
          f"topology {r['topology']}")
    d = r["edge_decisions"]
    check(len(d) == 1 and d[0]["id"] == 20 and d[0]["requested"] == "auto", f"edge decisions {d}")
    check(d[0]["mode"] in ("free", "periodic", "scar", "rotational"), f"mode {d[0]['mode']}")
    check(any(v is not None for v in d[0]["scores"].values()), f"no scores tried: {d[0]}")
    check("id 20" in p.stdout, f"summary lacks the repeated edge decision:\n{p.stdout}")
    # Both sides of the seam are drawn in the seam colour.
    root = check_svg(svg, len(T))
    seams = root.find(f".//{SVG_NS}g[@id='seams']/{SVG_NS}path").get("d")
    check(seams.count("M") == 2 * (len(seam) - 1), f"seam segments drawn: {seams.count('M')}")
    # Forcing the mode per edge (by the file's id) is honoured and reported.
    run("flatten", src, "-o", out, "--topology", topo, "--report", rep, "--edge-mode-of", "20=periodic", expect=0)
    d = json.load(open(rep))["edge_decisions"][0]
    check(d["mode"] == "periodic" and d["requested"] == "periodic", f"forced mode: {d}")
    # The same cut from a seam file.
    seams_file = os.path.join(tmp, "cyl.seam")
    with open(seams_file, "w") as f:
        f.write("# generator at angle 0\n\n" + "".join(f"{a} {b}\n" for a, b in zip(seam, seam[1:])))
    run("flatten", src, "-o", out, "--seams", seams_file, "--report", rep, expect=0)
    _, VT2, _ = check_uv_obj(out, V, T)
    check(len(VT2) == len(V) + len(seam), f"seam file cut: {len(VT2)} uses")
    check(json.load(open(rep))["topology"]["repeated_edges"] == 1, "seam file: no repeated edge")


def case_topology_bad(tmp):
    V, T, seam, src, topo = cylinder_files(tmp)
    good = json.load(open(topo))
    out = os.path.join(tmp, "o.obj")

    def bad(name, doc, *want):
        path = os.path.join(tmp, name)
        with open(path, "w") as f:
            f.write(doc if isinstance(doc, str) else json.dumps(doc))
        p = run("flatten", src, "-o", out, "--topology", path, expect=4)
        for w in (name, *want):
            check(w in p.stderr, f"{name}: message lacks {w!r}: {p.stderr}")
        check(not os.path.exists(out), f"{name}: wrote an output")

    doc = json.loads(json.dumps(good))
    doc["edges"][1]["vertices"] = [seam[0], seam[2]]  # not a facet edge
    bad("not_facet.json", doc, "edge", "20")
    doc = json.loads(json.dumps(good))
    doc["loops"][0][2]["edge"] = 99
    bad("unknown_edge.json", doc, "loop 0", "99")
    doc = json.loads(json.dumps(good))
    doc["edges"][0]["vertices"] = [0, 1, 100000]
    bad("out_of_range.json", doc, "edge", "10")
    doc = json.loads(json.dumps(good))
    doc["edges"][2]["mode"] = "sideways"
    bad("bad_mode.json", doc, "id 30", "mode")
    doc = json.loads(json.dumps(good))
    del doc["loops"][0][3]  # the seam used once: the loop does not close
    bad("open_loop.json", doc, "loop")
    bad("not_json.json", "{ edges: [", "JSON")


def case_write_topology(tmp):
    V, T, seam, src, topo = cylinder_files(tmp)
    o1, o2, t1, t2 = (os.path.join(tmp, n) for n in ("a.obj", "b.obj", "t1.json", "t2.json"))
    run("flatten", src, "-o", o1, "--topology", topo, "--edge-mode-of", "20=periodic", "--write-topology", t1, expect=0)
    w = json.load(open(t1))
    check([e["id"] for e in w["edges"]] == [10, 20, 30], f"written ids {[e['id'] for e in w['edges']]}")
    check(w["edges"][1]["vertices"] == seam and w["edges"][1]["repeated"] is True, f"written seam {w['edges'][1]}")
    check(w["edges"][1]["mode"] == "periodic", f"written mode {w['edges'][1]}")
    check(w["loops"] == json.load(open(topo))["loops"] and w["outer_loop"] == 0, f"written loops {w['loops']}")
    run("flatten", src, "-o", o2, "--topology", t1, "--write-topology", t2, expect=0)
    check(json.load(open(t2)) == w, "second write differs from the first")
    _, VT1, F1 = read_obj(o1)
    _, VT2, F2 = read_obj(o2)
    diff = max(abs(a - b) for t1_, t2_ in zip(F1, F2) for c1, c2 in zip(t1_, t2_) for a, b in zip(VT1[c1[1]], VT2[c2[1]]))
    check(diff < 1e-9, f"UV differs after the round trip by {diff}")
    # Derived topology (boundary cycles of a disk) round-trips too.
    Vp, Tp = meshes.patch()
    ps = os.path.join(tmp, "patch.obj")
    meshes.write_obj(ps, Vp, Tp)
    run("flatten", ps, "-o", o1, "--write-topology", t1, expect=0)
    w = json.load(open(t1))
    check(len(w["loops"]) == 1 and all(not e["repeated"] for e in w["edges"]), f"derived topology {w}")
    run("flatten", ps, "-o", o2, "--topology", t1, expect=0)
    _, VT1, F1 = read_obj(o1)
    _, VT2, F2 = read_obj(o2)
    diff = max(abs(a - b) for t1_, t2_ in zip(F1, F2) for c1, c2 in zip(t1_, t2_) for a, b in zip(VT1[c1[1]], VT2[c2[1]]))
    check(diff < 1e-9, f"derived topology: UV differs after the round trip by {diff}")


def case_auto_cut(tmp):
    V, T, seam, bottom, top = meshes.cylinder()
    src, out, rep, t1 = (os.path.join(tmp, n) for n in ("cyl.obj", "o.obj", "r.json", "t1.json"))
    meshes.write_obj(src, V, T)
    run("flatten", src, "-o", out, "--auto-cut", "--report", rep, "--write-topology", t1, expect=0)
    r = json.load(open(rep))
    check(r["auto_cut"] is True and r["auto_cut_edges"] == 3 and abs(r["auto_cut_length"] - 1.5) < 1e-12,
          f"auto-cut report {r}")
    check(r["auto_cut_uncut_kept"] is False and r["auto_cut_other_score"] < r["score"], f"uncut comparison {r}")
    check(r["angle_distortion_max"] < 1 + 1e-7, f"cut cylinder not exact: {r['angle_distortion_max']}")
    # The derived cut is written as a repeated edge along a generator (vertex i + n*j, one i), periodic.
    w = json.load(open(t1))
    rep_edges = [e for e in w["edges"] if e.get("repeated")]
    check(len(rep_edges) == 1 and len(w["loops"]) == 1, f"written topology {w}")
    chain = rep_edges[0]["vertices"]
    check(len(chain) == 4 and len({v % 12 for v in chain}) == 1, f"cut chain {chain}")
    check(rep_edges[0]["mode"] == "periodic", f"cut mode {rep_edges[0]}")
    # Read back without --auto-cut: the same layout.
    out2 = os.path.join(tmp, "o2.obj")
    run("flatten", src, "-o", out2, "--topology", t1, expect=0)
    _, VT1, F1 = read_obj(out)
    _, VT2, F2 = read_obj(out2)
    diff = max(abs(a - b) for t1_, t2_ in zip(F1, F2) for c1, c2 in zip(t1_, t2_) for a, b in zip(VT1[c1[1]], VT2[c2[1]]))
    check(diff < 1e-9, f"UV differs after the topology round trip by {diff}")
    # Closed surfaces: refused without --auto-cut (the message names it), slit with it; a torus is refused.
    octa = os.path.join(tmp, "octa.obj")
    meshes.write_obj(octa, [(1, 0, 0), (-1, 0, 0), (0, 1, 0), (0, -1, 0), (0, 0, 1), (0, 0, -1)],
                     [(0, 2, 4), (2, 1, 4), (1, 3, 4), (3, 0, 4), (2, 0, 5), (1, 2, 5), (3, 1, 5), (0, 3, 5)])
    p = run("flatten", octa, "-o", out, expect=4)
    check("auto_cut" in p.stderr, f"closed surface message:\n{p.stderr}")
    run("flatten", octa, "-o", out, "--auto-cut", "--report", rep, expect=0)
    r = json.load(open(rep))
    check(r["auto_cut"] is True and r["flipped_triangles"] == 0 and r["boundary_intersections"] == 0, f"octahedron {r}")
    n, m = 12, 6
    tv = [((2 + 0.6 * math.cos(2 * math.pi * j / m)) * math.cos(2 * math.pi * i / n),
           (2 + 0.6 * math.cos(2 * math.pi * j / m)) * math.sin(2 * math.pi * i / n), 0.6 * math.sin(2 * math.pi * j / m))
          for j in range(m) for i in range(n)]
    idx = lambda i, j: (i % n) + n * (j % m)
    tt = [t for j in range(m) for i in range(n)
          for t in ((idx(i, j), idx(i + 1, j), idx(i + 1, j + 1)), (idx(i, j), idx(i + 1, j + 1), idx(i, j + 1)))]
    torus = os.path.join(tmp, "torus.obj")
    meshes.write_obj(torus, tv, tt)
    p = run("flatten", torus, "-o", out, "--auto-cut", expect=4)
    check("genus 1" in p.stderr, f"torus message:\n{p.stderr}")


def case_progress_quiet(tmp):
    V, T = meshes.patch()
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, V, T)
    p = run("flatten", src, "-o", os.path.join(tmp, "o.obj"), expect=0)
    lines = [l for l in p.stderr.splitlines() if l.startswith("progress: ")]
    check(lines, f"no progress lines on a non-terminal stderr:\n{p.stderr}")
    check(all(l.rstrip().endswith("%") for l in lines) and "\r" not in p.stderr, f"progress format:\n{p.stderr}")
    check(len(lines) <= 40, f"{len(lines)} progress lines: too chatty")
    check("score" in p.stdout and "flipped" in p.stdout, f"summary:\n{p.stdout}")
    q = run("flatten", src, "-o", os.path.join(tmp, "o.obj"), "--quiet", expect=0)
    check(q.stdout == "" and q.stderr == "", f"--quiet printed:\n{q.stdout}{q.stderr}")


def huge_page_malloc_expected(env, input_bytes):
    """True or False where the tool's start-up conditions decide clearly; None where free memory
    is too close to its 2 GB threshold to tell from here (it moves between the two checks)."""
    env = {**os.environ, **env}
    if input_bytes < 256 << 10:  # a small face is not worth a second process start
        return False
    if env.get("WEFM_HUGE_PAGES") == "0" or env.get("LD_PRELOAD"):
        return False
    tunables = env.get("GLIBC_TUNABLES", "")
    if "glibc.malloc.hugetlb" in tunables:
        return "glibc.malloc.hugetlb=1" in tunables
    libc = (os.confstr("CS_GNU_LIBC_VERSION") or "").split()
    if len(libc) != 2 or libc[0] != "glibc" or tuple(int(x) for x in libc[1].split(".")[:2]) < (2, 35):
        return False
    try:
        with open("/sys/kernel/mm/transparent_hugepage/enabled") as f:
            if "[madvise]" not in f.read():
                return False
        with open("/proc/meminfo") as f:
            free_kb = next(int(line.split()[1]) for line in f if line.startswith("MemFree:"))
    except (OSError, StopIteration):
        return False
    gb = 1024 * 1024
    return False if free_kb < 1.5 * gb else None if free_kb < 2.5 * gb else True


def case_huge_page_malloc(tmp):
    # Starting again with huge-page malloc changes where memory comes from, never the result: the
    # UV OBJ is byte-identical with and without it, and the report says which way each run went.
    # The same small patch as it is and padded with comment lines past the 256 KB below which the
    # tool does not start again (the size of the files it reads is its measure of the face).
    V, T = meshes.patch()
    small = os.path.join(tmp, "p.obj")
    meshes.write_obj(small, V, T)
    big = os.path.join(tmp, "p_padded.obj")
    with open(small) as f, open(big, "w") as g:
        g.write(f.read())
        g.write(("# padding" + " " * 90 + "\n") * (2621 + 1))
    check(os.path.getsize(small) < 256 << 10 <= os.path.getsize(big), "the padded patch straddles the threshold")
    for src in (small, big):
        outs = {}
        size = os.path.getsize(src)
        for name, env in [("default", {}), ("off", {"WEFM_HUGE_PAGES": "0"}),
                          ("glibc_off", {"GLIBC_TUNABLES": "glibc.malloc.hugetlb=0"}),
                          ("other_tunable", {"GLIBC_TUNABLES": "glibc.malloc.check=0"})]:
            tag = f"{os.path.basename(src)} {name}"
            out, rep = os.path.join(tmp, f"{name}.obj"), os.path.join(tmp, f"{name}.json")
            run("flatten", src, "-o", out, "--report", rep, "-q", expect=0, env=env)
            with open(out, "rb") as f:
                outs[tag] = f.read()
            with open(rep) as f:
                active = json.load(f)["huge_page_malloc"]
            expected = huge_page_malloc_expected(env, size)
            check(active is expected or expected is None and isinstance(active, bool),
                  f"{tag}: huge_page_malloc {active}, expected {expected}")
        check(len(set(outs.values())) == 1, f"{os.path.basename(src)}: the UV OBJ depends on huge-page malloc")


def case_threads(tmp):
    # flatten uses every hardware thread unless told, and the thread count never changes the
    # layout: the UV OBJ is byte-identical for --threads 1, 2, 3 and the default, at s = 1 (the
    # continuation's threaded passes) as at s = 0.
    V, T = meshes.patch()
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, V, T)
    for s in ("0", "1"):
        outs = {}
        for name, extra in [("default", []), ("1", ["--threads", "1"]), ("2", ["--threads", "2"]), ("3", ["--threads", "3"])]:
            out, rep = os.path.join(tmp, f"t{name}_s{s}.obj"), os.path.join(tmp, f"t{name}_s{s}.json")
            run("flatten", src, "-o", out, "--report", rep, "--s", s, "-q", *extra, expect=0)
            with open(out, "rb") as f:
                outs[name] = f.read()
            with open(rep) as f:
                threads = json.load(f)["threads"]
            expected = max(1, os.cpu_count() or 1) if name == "default" else int(name)
            check(threads == expected, f"s={s} {name}: report threads {threads}, expected {expected}")
        check(len(set(outs.values())) == 1, f"s={s}: the UV OBJ depends on the thread count")


def case_png(tmp):
    V, T = meshes.patch()
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, V, T)
    png = os.path.join(tmp, "d.png")
    run("flatten", src, "-o", os.path.join(tmp, "o.obj"), "--svg", png, "-q", expect=0)
    data = open(png, "rb").read()
    check(data[:8] == b"\x89PNG\r\n\x1a\n" and data[12:16] == b"IHDR", "not a PNG")
    w, h = struct.unpack(">II", data[16:24])
    check(100 < w <= 4000 and 100 < h <= 4000, f"PNG size {w}x{h}")
    check(b"IEND" in data[-12:], "PNG not terminated")


def case_not_converged(tmp):
    """A capped rho iteration must still write the best result and exit 5 with a warning."""
    V, T = meshes.patch()
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, V, T)
    out, rep = os.path.join(tmp, "o.obj"), os.path.join(tmp, "r.json")
    p = run("flatten", src, "-o", out, "--report", rep, "--max-rho-iterations", "1", "--rho-tolerance", "1e-15")
    check(p.returncode == 5, f"exit {p.returncode}, want 5\n{p.stderr}")
    check("warning" in p.stderr and "converge" in p.stderr, f"no warning: {p.stderr}")
    check_uv_obj(out, V, T)
    r = json.load(open(rep))
    check(r["status"] == "not_converged" and r["converged"] is False and r["exit_code"] == 5, f"report {r['status']}")


def read_faces(path):
    """Vertices and face vertex lists (any arity) of an OBJ."""
    V, F = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if p and p[0] == "v":
                V.append(tuple(map(float, p[1:4])))
            elif p and p[0] == "f":
                F.append([int(q.split("/")[0]) - 1 for q in p[1:]])
    return V, F


def case_mesh(tmp):
    """wefm mesh: transfinite quads on a periodic cylinder strip, free triangles with report and SVG."""
    V, T, seam, src, topo = cylinder_files(tmp, seam_mode="periodic")
    out, rep = os.path.join(tmp, "cyl_mesh.obj"), os.path.join(tmp, "cyl_mesh.json")
    chord = 2 * math.sin(math.pi / 12)
    p = run("mesh", src, "--topology", topo, "--size", chord, "--type", "transfinite", "-o", out, "--report", rep, "--s", 0,
            expect=0)
    MV, MF = read_faces(out)
    check(MF and all(len(f) == 4 for f in MF), "transfinite mesh must be quads")
    check(len(MF) == 12 * 3, f"{len(MF)} quads, want 12 around x 3 along")
    for x, y, z in MV:  # every node on the facetted cylinder: between the facets' inradius and 1
        r = math.hypot(x, y)
        check(math.cos(math.pi / 12) - 1e-9 <= r <= 1 + 1e-9 and -1e-9 <= z <= 1.5 + 1e-9, f"node off the surface {x, y, z}")
    r = json.load(open(rep))
    m = r["mesh"]
    check(r["type"] == "transfinite" and m["nodes_per_element"] == 4 and m["elements"] == len(MF), f"report {m}")
    check(m["wiggle_max"] < 1e-6 and m["scaled_jacobian_min"] > 0.99, f"wiggle/Jacobian {m}")
    check("wiggle" in p.stdout and "quads" in p.stdout, f"summary: {p.stdout}")
    DV, DF = read_faces(os.path.join(tmp, "cyl_mesh.domain.obj"))
    check(len(DV) == len(MV) and DF == MF and all(v[2] == 0 for v in DV), "domain mesh mismatches the 3D mesh")
    # --type auto finds the strip four-sided (seam, end, seam, end) and makes the same grid.
    aout, arep = os.path.join(tmp, "cyl_auto.obj"), os.path.join(tmp, "cyl_auto.json")
    run("mesh", src, "--topology", topo, "--size", chord, "--type", "auto", "-o", aout, "--report", arep, "--s", 0, "-q", expect=0)
    a = json.load(open(arep))
    check(a["type"] == "transfinite" and a["type_asked"] == "auto" and read_faces(aout)[1] == MF, f"auto: {a['type']}, {a['mesh']}")
    check(a["automatic_fallback"] is None and "refused_grid_scaled_jacobian_min" not in a, f"auto's fallback: {a}")
    # Free meshing of a curved patch, with the picture.
    PV, PT = meshes.patch(9, 7)
    psrc, pout, prep, psvg = (os.path.join(tmp, n) for n in ("patch.obj", "patch_mesh.obj", "patch.json", "patch.svg"))
    meshes.write_obj(psrc, PV, PT)
    run("mesh", psrc, "--size", 0.05, "-o", pout, "--report", prep, "--svg", psvg, "-q", expect=0)
    check(json.load(open(prep))["type"] == "free", "a free mesh reported as another type")
    # Without -q the solve and the meshing both show progress on a non-terminal stderr.
    shown = run("mesh", psrc, "--size", 0.05, "-o", os.path.join(tmp, "shown.obj"), expect=0)
    stages = {l.split()[1] for l in shown.stderr.splitlines() if l.startswith("progress: ")}
    check("mesh" in stages and len(stages) >= 2, f"wefm mesh progress stages {stages}:\n{shown.stderr}")
    # A mesh over --max-elements is a meshing failure (5), not bad usage, and writes nothing.
    capped = os.path.join(tmp, "capped.obj")
    p = run("mesh", psrc, "--size", 0.05, "--max-elements", 10, "-o", capped, expect=5)
    check("max_elements" in p.stderr and not os.path.exists(capped), f"capped mesh: {p.stderr}")
    m = json.load(open(prep))["mesh"]
    _, F = read_faces(pout)
    check(m["nodes_per_element"] == 3 and m["elements"] == len(F) and all(len(f) == 3 for f in F), f"free mesh {m}")
    check(m["lambda_min"] >= 0.5 and m["lambda_mesh"] >= 0.9, f"free mesh quality {m}")
    root = ET.parse(psvg).getroot()
    polys = root.findall(f"{SVG_NS}polygon")
    check(len(polys) == len(F), f"svg has {len(polys)} polygons for {len(F)} triangles")
    legend = [g for g in root.findall(f"{SVG_NS}g") if g.get("id") == "legend"]
    texts = " ".join(t.text or "" for g in legend for t in g.iter(f"{SVG_NS}text"))
    check(len(legend) == 1 and "lambda" in texts and f"{len(F)} elements" in texts and
          f"min lambda {m['lambda_min']:.3f}" in texts, f"svg legend: {texts!r}")
    # Usage errors.
    run("mesh", psrc, "-o", pout, expect=2)  # no --size
    run("mesh", psrc, "--size", 0.1, "--type", "paved", "-o", pout, expect=2)
    run("mesh", psrc, "--size", 0.1, "--type", "transfinite", "--corners", "1,2,3", "-o", pout, expect=2)


CASES = {f"format_{fmt}": (lambda tmp, fmt=fmt: case_format(fmt, tmp)) for fmt in meshes.WRITERS}
CASES.update(info=case_info, batch=case_batch, usage=case_usage, unreadable=case_unreadable, topology=case_topology,
             topology_bad=case_topology_bad, write_topology=case_write_topology, progress_quiet=case_progress_quiet,
             png=case_png, not_converged=case_not_converged, mesh=case_mesh, auto_cut=case_auto_cut,
             huge_page_malloc=case_huge_page_malloc, threads=case_threads)


def run_cases(cases, script):
    """The drivers' command line: SCRIPT WEFM_BINARY CASE|all, each case in a fresh temporary folder."""
    global WEFM
    if len(sys.argv) != 3 or sys.argv[2] not in list(cases) + ["all"]:
        print(f"usage: {script} WEFM_BINARY CASE  (CASE: all, {', '.join(cases)})")
        return 2
    WEFM = os.path.abspath(sys.argv[1])
    failed = 0
    for name in (cases if sys.argv[2] == "all" else [sys.argv[2]]):
        with tempfile.TemporaryDirectory(prefix=f"wefm_cli_{name}_") as tmp:
            try:
                cases[name](tmp)
                print(f"ok   {name}")
            except Failure as e:
                failed += 1
                print(f"FAIL {name}: {e}")
    return 1 if failed else 0


def main():
    return run_cases(CASES, "cli_tests.py")


if __name__ == "__main__":
    sys.exit(main())
