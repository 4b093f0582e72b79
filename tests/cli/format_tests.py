#!/usr/bin/env python3
"""Mesh and layout files by extension (OBJ, MSH 4.1, VTK, VTU, PLY), read back by meshio and by Gmsh:
format_tests.py WEFM_BINARY CASE [MODEL.step]

  flatten     a seamed cylinder and a flat patch in every format: points, triangles and UVs as the
              report and the OBJ say (a point per vertex use where the format holds one UV per point)
  mesh        free triangles and transfinite quads in every format, the domain mesh in the same format
  batch       --format: every face's file read back, counts as the summary says
  model       --format: per-face UV meshes of a CAD model, the face's number as its group (MODEL.step)
  mesh_model  the whole-model mesh in every format, counts and face groups as the report says (MODEL.step)
  unknown     an unknown extension or --format is exit 2 before any work, and writes nothing

Needs meshio (python3-meshio) and the gmsh program; without them the case is skipped (exit 77). Gmsh
4.8 reads MSH, VTK legacy and PLY (PLY triangles only: a quad comes in as its first three nodes); it
has no reader for OBJ or VTU. Each case prints its rows of the
table "command format meshio gmsh".
"""
import contextlib
import glob
import io
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import cli_tests  # noqa: E402
import meshes  # noqa: E402
from cli_tests import Failure, check, run  # noqa: E402

try:
    import meshio
    import numpy as np
except ImportError:
    meshio = None

FORMATS = ["obj", "msh", "vtk", "vtu", "ply"]
GMSH_READS = {"msh", "vtk", "ply"}
MODEL = None
TABLE = []


def read_meshio(path):
    with contextlib.redirect_stdout(io.StringIO()):  # meshio prints blank lines for some formats
        m = meshio.read(path)
    cells = {}
    for block in m.cells:
        cells[block.type] = cells.get(block.type, 0) + len(block.data)
    return m, cells


def read_gmsh(path, tmp):
    """Gmsh reads the file and writes it as MSH 4.1; None when Gmsh cannot read it."""
    out = os.path.join(tmp, "gmsh_" + os.path.basename(path) + ".msh")
    p = subprocess.run(["gmsh", path, "-0", "-o", out], capture_output=True, text=True, timeout=120)
    if "Error" in p.stdout + p.stderr or not os.path.exists(out):
        return None
    return read_meshio(out)


def uv_of(m, fmt):
    """One (u, v) per point as meshio gives them, or None."""
    if fmt == "ply":
        return np.column_stack([m.point_data["u"], m.point_data["v"]]) if "u" in m.point_data else None
    if fmt == "obj":
        return m.point_data.get("obj:vt")
    uv = m.point_data.get("uv")
    return None if uv is None else uv[:, :2]


def face_ids_of(m, fmt):
    """Per element, its face's number."""
    key = "gmsh:physical" if fmt == "msh" else "obj:group_ids" if fmt == "obj" else "face_id"
    return np.concatenate([np.ravel(a) for a in m.cell_data[key]]).astype(int)


def check_file(command, fmt, path, tmp, points, cells, uv=None, faces=None):
    """meshio and (for the formats it reads) Gmsh find `points` points and `cells` ({type: count});
    UVs equal `uv` (rows in point order) and the elements' face numbers the set `faces`."""
    check(os.path.exists(path), f"{command} {fmt}: {path} not written")
    m, got = read_meshio(path)
    check(len(m.points) == points and got == cells, f"{command} {fmt}: meshio {len(m.points)} points {got}, want {points} {cells}")
    if uv is not None:
        mu = uv_of(m, fmt)
        check(mu is not None and np.array_equal(np.asarray(mu, float), np.asarray(uv, float)), f"{command} {fmt}: UVs differ")
    if faces is not None:  # OBJ groups are numbered by meshio in order of appearance, not by face
        ids = set(face_ids_of(m, fmt).tolist())
        check(ids == set(faces) if fmt != "obj" else len(ids) == len(faces),
              f"{command} {fmt}: face groups {sorted(ids)}, want {sorted(faces)}")
    g = read_gmsh(path, tmp)
    if fmt == "ply" and "quad" in cells:  # Gmsh 4.8's PLY reader keeps a quad's first three nodes
        TABLE.append((command, fmt, "yes", "no (quads read as triangles)"))
        return
    if fmt in GMSH_READS:
        check(g is not None, f"{command} {fmt}: gmsh could not read {path}")
        gm, gcells = g
        check(len(gm.points) == points and gcells == cells, f"{command} {fmt}: gmsh {len(gm.points)} points {gcells}")
    TABLE.append((command, fmt, "yes", "yes" if g is not None else "no"))


def ply_cells(path):
    """{type: count} of an ASCII PLY's faces, read from its lines."""
    lines = open(path).read().splitlines()
    end = lines.index("end_header")
    vertices = next(int(l.split()[2]) for l in lines if l.startswith("element vertex "))
    faces = next(int(l.split()[2]) for l in lines if l.startswith("element face "))
    counts = {}
    for l in lines[end + 1 + vertices:end + 1 + vertices + faces]:
        kind = {"3": "triangle", "4": "quad"}[l.split()[0]]
        counts[kind] = counts.get(kind, 0) + 1
    return counts


def flatten_case(tmp, name, src, extra):
    """Every format of one face; OBJ first, the others checked against it and the report."""
    base = os.path.join(tmp, name)
    run("flatten", src, "-o", base + ".obj", "--report", base + ".json", "-q", *extra, expect=0)
    V, VT, F = cli_tests.read_obj(base + ".obj")
    rep = json.load(open(base + ".json"))
    check(rep["mesh"]["triangles"] == len(F) and rep["topology"]["uses"] == len(VT), f"flatten {name}: report {rep['mesh']}")
    # A point per vertex use: its position is its vertex's, its UV the use's.
    use_vertex = {}
    for t in F:
        for v, u in t:
            use_vertex[u] = v
    seamed = len(VT) > len(V)
    for fmt in FORMATS:
        out = f"{base}_{fmt}.{fmt}"
        run("flatten", src, "-o", out, "-q", *extra, expect=0)
        if fmt == "obj":
            check(open(out, "rb").read() == open(base + ".obj", "rb").read(), f"flatten {name}: OBJ differs between runs")
            if seamed:  # meshio's OBJ reader wants one vt per v: a seam's second vt has no point
                try:
                    meshio.read(out)
                    TABLE.append((f"flatten ({name})", fmt, "yes", "no"))
                except Exception:
                    TABLE.append((f"flatten ({name})", fmt, "no (one vt per use)", "no"))
                continue
            check_file(f"flatten ({name})", fmt, out, tmp, len(V), {"triangle": len(F)}, uv=VT, faces=None)
            continue
        check_file(f"flatten ({name})", fmt, out, tmp, len(VT), {"triangle": len(F)}, uv=VT, faces={1})
        m, _ = read_meshio(out)
        want = np.array([V[use_vertex[u]] for u in range(len(VT))])
        check(np.array_equal(m.points, want), f"flatten {name} {fmt}: a point is not at its vertex")
        tri = np.concatenate([b.data for b in m.cells])
        check(np.array_equal(tri, np.array([[u for _, u in t] for t in F])), f"flatten {name} {fmt}: triangles are not the uses'")
    return seamed


def case_flatten(tmp):
    V, T, seam, src, topo = cli_tests.cylinder_files(tmp)
    check(flatten_case(tmp, "cylinder", src, ["--topology", topo]), "the cylinder layout should have a seam")
    PV, PT = meshes.patch(6, 5)
    psrc = os.path.join(tmp, "patch_input.obj")
    meshes.write_obj(psrc, PV, PT)
    check(not flatten_case(tmp, "patch", psrc, []), "the patch has no seam")
    # The MSH names its physical group.
    text = open(os.path.join(tmp, "patch_msh.msh")).read()
    check(text.startswith("$MeshFormat\n4.1 0 8\n") and '2 1 "face_1"' in text, "flatten MSH: header or physical name")


def case_mesh(tmp):
    V, T, seam, src, topo = cli_tests.cylinder_files(tmp, seam_mode="periodic")
    PV, PT = meshes.patch(9, 7)
    psrc = os.path.join(tmp, "patch.obj")
    meshes.write_obj(psrc, PV, PT)
    runs = {"free": (psrc, ["--size", 0.08]),
            "transfinite": (src, ["--topology", topo, "--size", 2 * math.sin(math.pi / 12), "--type", "transfinite", "--s", 0]),
            # At 0.11 two triangles are left over: this run checks the writers of mixed elements.
            "quad-dominant": (psrc, ["--size", 0.11, "--elements", "quad-dominant"]),
            "quad": (psrc, ["--size", 0.08, "--elements", "quad"])}
    for kind, (inp, extra) in runs.items():
        for fmt in FORMATS:
            out, rep = os.path.join(tmp, f"{kind}.{fmt}"), os.path.join(tmp, f"{kind}_{fmt}.json")
            run("mesh", inp, *extra, "-o", out, "--report", rep, "-q", expect=0)
            m = json.load(open(rep))["mesh"]
            # Per kind of element, how many the report says (a quad-dominant mesh has both).
            cells = {"quad": m["quads"], "triangle": m["elements"] - m["quads"]} if m["nodes_per_element"] == 4 else {"triangle": m["elements"]}
            cells = {k: n for k, n in cells.items() if n}
            if kind == "quad-dominant":
                check(len(cells) == 2 and m["quad_area_fraction"] >= 0.95, f"mesh ({kind}): {m}")
            if kind == "quad":
                check(cells == {"quad": m["elements"]} and m["scaled_jacobian_min"] > 0, f"mesh ({kind}): {m}")
            obj = os.path.join(tmp, f"{kind}.obj")
            _, VT, _ = cli_tests.read_obj(obj) if "quad" not in cells else (None, None, None)
            if fmt == "ply" and len(cells) == 2:  # meshio 1.x cannot read a PLY face property over two cell kinds
                check(ply_cells(out) == cells, f"mesh ({kind}) ply: {ply_cells(out)}, want {cells}")
                check(ply_cells(os.path.join(tmp, f"{kind}.domain.{fmt}")) == cells, f"mesh ({kind}) ply: domain mesh")
                TABLE.append((f"mesh ({kind})", fmt, "no (face_id over triangles and quads)", "no"))
                continue
            check_file(f"mesh ({kind})", fmt, out, tmp, m["nodes"], cells, uv=VT)
            domain = os.path.join(tmp, f"{kind}.domain.{fmt}")
            d, dcells = read_meshio(domain)
            check(len(d.points) == m["nodes"] and dcells == cells and not np.any(d.points[:, 2]),
                  f"mesh ({kind}) {fmt}: domain mesh {len(d.points)} points {dcells}")
    check("$NodeData" in open(os.path.join(tmp, "free.msh")).read(), "mesh MSH: no uv view")


def case_batch(tmp):
    d = os.path.join(tmp, "in")
    os.makedirs(d)
    V, T = meshes.patch(4, 4)
    meshes.write_obj(os.path.join(d, "a.obj"), V, T)
    V, T, seam, _, _ = meshes.cylinder()  # cut along its seam: a point per vertex use
    meshes.write_obj(os.path.join(d, "cyl.obj"), V, T)
    with open(os.path.join(d, "cyl.seam"), "w") as f:
        f.write("".join(f"{a} {b}\n" for a, b in zip(seam, seam[1:])))
    for fmt in FORMATS:
        out, summary = os.path.join(tmp, "out_" + fmt), os.path.join(tmp, f"summary_{fmt}.json")
        run("batch", d, "-o", out, "--format", fmt, "-q", "-j", 1, "--summary-json", summary, expect=0)
        rows = json.load(open(summary))
        check(sorted(os.listdir(out)) == sorted([r["name"] + e for r in rows for e in ("." + fmt, ".json")]),
              f"batch {fmt}: files {os.listdir(out)}")
        for r in rows:
            rep = json.load(open(os.path.join(out, r["name"] + ".json")))
            nv, uses = rep["mesh"]["vertices"], rep["topology"]["uses"]
            path = os.path.join(out, f"{r['name']}.{fmt}")
            if fmt == "obj" and uses > nv:
                _, VT, F = cli_tests.read_obj(path)
                check(len(VT) == uses and len(F) == r["triangles"], f"batch obj: {r['name']} counts")
                TABLE.append((f"batch ({r['name']})", fmt, "no (one vt per use)", "no"))
                continue
            check(r["name"] != "cyl" or uses > nv, "batch: the cylinder should be cut")
            check_file(f"batch ({r['name']})", fmt, path, tmp, uses if fmt != "obj" else nv, {"triangle": r["triangles"]})


def case_model(tmp):
    for fmt in FORMATS:
        out = os.path.join(tmp, "model_" + fmt)
        run("model", MODEL, "-o", out, "--format", fmt, "-q", "--edge-mode", "periodic", "-j", 1, expect=0)
        index = json.load(open(os.path.join(out, "index.json")))
        for f in index["faces"]:
            path = os.path.join(out, f"{f['name']}.{fmt}")
            check(os.path.join(out, f["files"]["domain_obj"]) == path, f"model {fmt}: index names {f['files']}")
            rep = json.load(open(os.path.join(out, f["name"] + ".json")))
            nv, uses = rep["mesh"]["vertices"], rep["topology"]["uses"]
            if fmt == "obj":
                V, VT, F = cli_tests.read_obj(path)
                check(len(V) == nv and len(VT) == uses and len(F) == f["triangles"], f"model obj: {f['name']} counts")
                if uses > nv:  # a seam: meshio reads no OBJ with more vt than v (see the flatten case)
                    TABLE.append((f"model ({f['surface_type']})", fmt, "no (one vt per use)", "no"))
                    continue
            check_file(f"model ({f['surface_type']})", fmt, path, tmp, uses if fmt != "obj" else nv, {"triangle": f["triangles"]},
                       faces={f["face"]} if fmt != "obj" else None)
        check(all(p.endswith(".obj") for p in glob.glob(os.path.join(out, "input", "*.obj"))), "model: input faces")


def case_mesh_model(tmp):
    for fmt in FORMATS:
        out, rep = os.path.join(tmp, "cyl." + fmt), os.path.join(tmp, f"cyl_{fmt}.json")
        run("mesh-model", MODEL, "--size", 2, "-o", out, "--report", rep, "-q", expect=0)
        r = json.load(open(rep))
        faces = {f["face"] for f in r["faces"] if f["elements"]}
        check_file("mesh-model", fmt, out, tmp, r["nodes"], {"triangle": r["triangles"]}, faces=faces)
    names = re.findall(r'^2 (\d+) "face_(\d+)"$', open(os.path.join(tmp, "cyl.msh")).read(), re.M)
    check(len(names) == len(faces) and all(a == b for a, b in names), f"mesh-model MSH: physical names {names}")


def case_unknown(tmp):
    """Exit 2 before any work: the input does not even exist, yet the answer is about the extension."""
    PV, PT = meshes.patch(4, 4)
    src = os.path.join(tmp, "p.obj")
    meshes.write_obj(src, PV, PT)
    missing = os.path.join(tmp, "missing.obj")
    cases = [["flatten", missing, "-o", os.path.join(tmp, "f.txt")],
             ["flatten", src, "-o", os.path.join(tmp, "f.stl")],
             ["mesh", missing, "--size", 0.1, "-o", os.path.join(tmp, "m.off")],
             ["mesh", src, "--size", 0.1, "-o", os.path.join(tmp, "m.vtk"), "--domain-obj", os.path.join(tmp, "d.x3d")],
             ["batch", tmp, "-o", os.path.join(tmp, "bo"), "--format", "stl"]]
    if MODEL:
        cases += [["model", missing, "-o", os.path.join(tmp, "mo"), "--format", "step"],
                  ["mesh-model", missing, "--size", 1, "-o", os.path.join(tmp, "mm.stl")]]
    for args in cases:
        p = run(*args, expect=2)
        check("unknown" in p.stderr and ("obj" in p.stderr and "ply" in p.stderr), f"{args[0]}: message {p.stderr!r}")
    left = sorted(set(os.listdir(tmp)) - {"p.obj"})
    check(not left, f"files written: {left}")


CASES = {"flatten": case_flatten, "mesh": case_mesh, "batch": case_batch, "model": case_model,
         "mesh_model": case_mesh_model, "unknown": case_unknown}


def main():
    global MODEL
    if len(sys.argv) not in (3, 4) or sys.argv[2] not in CASES:
        print(f"usage: format_tests.py WEFM_BINARY CASE [MODEL.step]  (CASE: {', '.join(CASES)})")
        return 2
    if meshio is None or shutil.which("gmsh") is None:
        print("skipped: needs python3-meshio and gmsh")
        return 77
    cli_tests.WEFM = os.path.abspath(sys.argv[1])
    MODEL = sys.argv[3] if len(sys.argv) == 4 else None
    name = sys.argv[2]
    if name in ("model", "mesh_model") and not MODEL:
        print("skipped: no CAD model given")
        return 77
    with tempfile.TemporaryDirectory(prefix=f"wefm_formats_{name}_") as tmp:
        try:
            CASES[name](tmp)
        except Failure as e:
            print(f"FAIL {name}: {e}")
            return 1
    for row in TABLE:
        print("TABLE | " + " | ".join(row) + " |")
    print(f"ok   {name}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
