#!/usr/bin/python3
"""Where wefm stands against CGAL's surface parameterizations on hard faces.

    bench/compare_peers.py [--build build/release] [--repeat 3] [--faces a,b] [--no-write]

Runs `wefm flatten` (s = 1, 0 and 2) and every method of `wefm-peer-cgal` (CGAL 5.5's LSCM, ARAP,
discrete conformal map and mean-value coordinates, see bench/cgal_peer.cpp) on

  * the synthetic hard faces of /work/shared/data: a helical strip of two turns, a sphere with a
    small hole, an open cylinder with its seam, a saddle, a curved plate with two holes;
  * the 12 real CAD faces of /work/shared/data/real (wefm: face.obj --seams face.seam, as the
    evaluation runs it; CGAL: face_cut.obj, the same face cut open along its seams);

checks every layout with the independent checker (/work/shared/tools/uvcheck.py --json: flips,
boundary intersections, distortion, paper score) and writes a Markdown table between the markers
`<!-- peers:begin -->` / `<!-- peers:end -->` of docs/RESULTS.md (nothing else in the file changes).
Layouts, reports and every measured number go to BUILD/peers/ (peers.json).

CGAL needs a topological disk, so it is given the cut-open face: face_cut.obj for the real faces,
and for cylinder_open.obj a copy cut along cylinder_open.seam by `cut_along_seams` below (each seam
vertex is split into one copy per fan of triangles between seam edges). Faces with several boundary
loops are still given to CGAL (its package does not check); the cell says the face is outside
CGAL's precondition.

Needs: a Release build with the benchmarks and CGAL (`apt-get install -y libcgal-dev`, Debian 12:
CGAL 5.5, header-only; `cmake --preset release -DWEFM_BUILD_BENCH=ON && cmake --build build/release
-j2 --target wefm_cli wefm-peer-cgal`), numpy for /usr/bin/python3 (uvcheck.py).
"""
import argparse
import json
import os
import subprocess
import sys
import time
from collections import defaultdict

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BEGIN, END = "<!-- peers:begin -->", "<!-- peers:end -->"
CGAL_METHODS = [("lscm", "CGAL LSCM"), ("arap", "CGAL ARAP"), ("dcm", "CGAL DCM (circle)"), ("mvc", "CGAL MVC (circle)")]
SHORT = {"lscm": "LSCM", "arap": "ARAP", "dcm": "DCM", "mvc": "MVC"}
WEFM_S = ["1", "0", "2"]


# ------------------------------------------------------------------------------------------------
# Faces
# ------------------------------------------------------------------------------------------------

def read_obj(path):
    V, F = [], []
    with open(path) as f:
        for line in f:
            p = line.split()
            if not p:
                continue
            if p[0] == "v":
                V.append(line.split(None, 1)[1].strip())
            elif p[0] == "f":
                F.append([int(q.split("/")[0]) - 1 for q in p[1:]])
    return V, F


def read_seam(path):
    edges = []
    with open(path) as f:
        for line in f:
            line = line.split("#", 1)[0].split()
            if len(line) == 2:
                edges.append((int(line[0]), int(line[1])))
    return edges


def cut_along_seams(V, F, seam):
    """Cut a triangle mesh open along seam edges (0-based vertex pairs). Every vertex on the seam is
    split into one vertex per fan of its triangles that can be walked around it without crossing a
    seam edge; the first fan keeps the original index, the others get copies appended (as
    face_cut.obj of the real sample does). Returns (V, F) of the cut mesh."""
    edge_tris = defaultdict(list)
    for t, tri in enumerate(F):
        for k in range(3):
            edge_tris[frozenset((tri[k], tri[(k + 1) % 3]))].append(t)
    cut = set()
    for a, b in seam:
        e = frozenset((a, b))
        if len(edge_tris.get(e, ())) != 2:
            raise ValueError(f"seam edge {a} {b} is not an interior edge of the mesh")
        cut.add(e)
    around = defaultdict(list)
    for t, tri in enumerate(F):
        for v in tri:
            around[v].append(t)
    V, F = list(V), [list(t) for t in F]
    for v in sorted({v for e in cut for v in e}):
        fan = around[v]
        parent = {t: t for t in fan}

        def find(t):
            while parent[t] != t:
                parent[t] = parent[parent[t]]
                t = parent[t]
            return t

        for t in fan:
            for w in F[t]:
                e = frozenset((v, w))
                if w == v or e in cut:
                    continue
                for t2 in edge_tris[e]:
                    if t2 != t:
                        parent[find(t2)] = find(t)
        groups = defaultdict(list)
        for t in fan:
            groups[find(t)].append(t)
        for g in sorted(groups.values(), key=min)[1:]:
            V.append(V[v])
            for t in g:
                F[t] = [len(V) - 1 if x == v else x for x in F[t]]
    return V, F


def write_obj(path, V, F):
    with open(path, "w") as f:
        f.write("# cut open by bench/compare_peers.py\n")
        f.writelines(f"v {v}\n" for v in V)
        f.writelines(f"f {a + 1} {b + 1} {c + 1}\n" for a, b, c in F)


def faces(data, real, out):
    """(name, kind, wefm input, seam file or None, CGAL input); builds the cut cylinder."""
    cyl_cut = os.path.join(out, "cylinder_open_cut.obj")
    V, F = read_obj(os.path.join(data, "cylinder_open.obj"))
    write_obj(cyl_cut, *cut_along_seams(V, F, read_seam(os.path.join(data, "cylinder_open.seam"))))
    out_faces = [
        ("helix_strip_2turns", "helical strip, 2 turns", os.path.join(data, "helix_strip_2turns.obj"), None, None),
        ("sphere_small_hole", "sphere, small hole", os.path.join(data, "sphere_small_hole.obj"), None, None),
        ("cylinder_open", "open cylinder", os.path.join(data, "cylinder_open.obj"),
         os.path.join(data, "cylinder_open.seam"), cyl_cut),
        ("cylinder_open_uncut", "the same cylinder, no seam (annulus)", os.path.join(data, "cylinder_open.obj"), None,
         None),
        ("saddle", "saddle", os.path.join(data, "saddle.obj"), None, None),
        ("plate_holes", "curved plate, 2 holes", os.path.join(data, "plate_holes.obj"), None, None),
    ]
    for name in sorted(os.listdir(real)):
        d = os.path.join(real, name)
        if not os.path.isfile(os.path.join(d, "face.obj")):
            continue
        seam = os.path.join(d, "face.seam")
        has_seam = os.path.isfile(seam) and bool(read_seam(seam))
        try:
            kind = json.load(open(os.path.join(d, "topo.json"))).get("surface_type", "real")
        except (OSError, ValueError):
            kind = "real"
        cgal_in = os.path.join(d, "face_cut.obj")
        out_faces.append((name, f"real: {kind}", os.path.join(d, "face.obj"), seam if has_seam else None,
                          cgal_in if os.path.isfile(cgal_in) else None))
    return out_faces


# ------------------------------------------------------------------------------------------------
# Runs
# ------------------------------------------------------------------------------------------------

def run(cmd, timeout):
    """Runs a command; returns (exit code or None on timeout, stdout, stderr, wall, CPU of the child)."""
    t0 = time.monotonic()
    r0 = os.times()
    try:
        p = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        rc, so, se = p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        rc, so, se = None, e.stdout or "", e.stderr or ""
        so = so.decode() if isinstance(so, bytes) else so
        se = se.decode() if isinstance(se, bytes) else se
    r1 = os.times()
    return rc, so, se, time.monotonic() - t0, (r1.children_user - r0.children_user) + (r1.children_system - r0.children_system)


def uvcheck(uvcheck_py, path):
    if not path or not os.path.isfile(path):
        return None, "no layout written"
    p = subprocess.run(["/usr/bin/python3", uvcheck_py, path, "--json"], capture_output=True, text=True)
    if p.returncode != 0:
        return None, "uvcheck failed: " + (p.stderr.strip().splitlines() or ["?"])[-1]
    return json.loads(p.stdout), ""


def run_wefm(wefm, face, s, out, repeat, timeout, checker):
    name, _, inp, seam, _ = face
    uv, rep = os.path.join(out, f"{name}.wefm_s{s}.obj"), os.path.join(out, f"{name}.wefm_s{s}.json")
    cmd = [wefm, "flatten", inp, "-o", uv, "--s", s, "--report", rep, "-q"] + (["--seams", seam] if seam else [])
    res = {"method": f"wefm_s{s}", "command": cmd, "runs": []}
    for _ in range(repeat):
        for f in (uv, rep):
            if os.path.exists(f):
                os.remove(f)
        rc, _, se, wall, cpu = run(cmd, timeout)
        r = {"exit_code": rc, "process_wall": wall, "process_cpu": cpu, "stderr": se.strip()[-500:]}
        try:
            report = json.load(open(rep))
            r["solve"] = report["timings"]["wall_solve"]
            r["report"] = {k: report.get(k) for k in ("status", "message", "score", "s", "converged", "via_s",
                                                      "boundary_unwind", "min_beta_raised", "edge_decisions")}
        except (OSError, ValueError, KeyError, TypeError):
            r["solve"] = None
        res["runs"].append(r)
        if rc is None:
            break
    res["output"] = uv
    res["check"], res["check_error"] = uvcheck(checker, uv)
    return res


def run_cgal(peer, face, method, out, repeat, timeout, checker):
    name, _, _, _, cgal_in = face
    prefix = os.path.join(out, name)
    inp = cgal_in or face[2]
    cmd = [peer, inp, "-o", prefix, "--method", method]
    res = {"method": method, "command": cmd, "runs": []}
    uv = f"{prefix}.{method}.obj"
    for _ in range(repeat):
        if os.path.exists(uv):
            os.remove(uv)
        rc, so, se, wall, cpu = run(cmd, timeout)
        r = {"exit_code": rc, "process_wall": wall, "process_cpu": cpu, "stderr": se.strip()[-500:]}
        try:
            j = json.loads(so.strip().splitlines()[-1])
            r["peer"] = j
            r["solve"] = j.get("time_parameterize")
        except (ValueError, IndexError):
            r["peer"], r["solve"] = None, None
        res["runs"].append(r)
        if rc is None or rc < 0:
            break
    res["output"] = uv
    res["check"], res["check_error"] = uvcheck(checker, uv)
    return res


# ------------------------------------------------------------------------------------------------
# Table
# ------------------------------------------------------------------------------------------------

def best_time(res):
    times = [r["solve"] for r in res["runs"] if r.get("solve") is not None]
    return min(times) if times else None


def fmt_time(t):
    if t is None:
        return "–"
    return f"{t:.2f} s" if t >= 0.1 else (f"{t * 1000:.0f} ms" if t >= 0.01 else f"{t * 1000:.1f} ms")


def fmt_angle(a):
    return f"{a:.2f}" if a < 100 else f"{a:.2g}"


def plural(n, word):
    return f"{n} {word}" + ("" if n == 1 else "s")


def valid(res):
    c = res.get("check")
    return bool(c) and c["flips"] == 0 and c["boundary_intersections"] == 0


def cell(res):
    last = res["runs"][-1]
    c = res.get("check")
    notes = []
    if res["method"].startswith("wefm"):
        rc = last["exit_code"]
        if rc is None:
            return f"timed out ({last['process_wall']:.0f} s)"
        rep = last.get("report") or {}
        if rc not in (0, 5) or not c:
            msg = (rep.get("message") or last["stderr"] or "").splitlines()
            return f"failed, exit {rc}" + (f": {msg[-1][:80]}" if msg else "")
        if rc == 5:
            notes.append("not converged (exit 5)")
        if rep.get("s") is not None and abs(rep["s"] - float(res["method"][6:])) > 1e-9:
            notes.append(f"at s = {rep['s']:g}")
    else:
        j = last.get("peer") or {}
        rc = last["exit_code"]
        if rc is None:
            return f"timed out ({last['process_wall']:.0f} s)"
        if rc < 0:
            return f"crashed (signal {-rc})"
        st = j.get("status", "no output")
        if st == "bad input":
            return f"not run: {j.get('message', '')}"
        if st == "non-finite uv":
            ok = "CGAL returned OK, but " if not j.get("message") else ""
            return f"**failed**: {ok}{j['non_finite_uv']} of {j.get('vertices', '?')} UVs are NaN"
        if st != "ok":
            notes.append(f"{st}: {j.get('message', '')}" if j.get("message") else st)
        if not c:
            return "; ".join(notes + [res.get("check_error") or "no layout"])
    text = (f"{c['paper_score']:.3f} ({c['flips']} / {c['boundary_intersections']}), ∠{fmt_angle(c['angle_dist_mean'])}, "
            f"{fmt_time(best_time(res))}")
    if not valid(res):
        text = f"**{text}**"
    return text + "".join(f"; {n}" for n in notes)


def seam_note(face, results):
    if not face[3]:
        return ""
    modes = set()
    for r in results:
        if r["method"].startswith("wefm"):
            for d in ((r["runs"][-1].get("report") or {}).get("edge_decisions") or []):
                modes.add(d.get("mode"))
    return f"wefm seam: {', '.join(sorted(m for m in modes if m)) or '?'}"


def table(rows, cmdline, build_commit, repeat, cgal_version):
    methods = [(f"wefm_s{s}", f"wefm s = {s}") for s in WEFM_S] + CGAL_METHODS
    head = ["face", "what", "triangles", "loops (CGAL input)"] + [m[1] for m in methods] + ["best"]
    lines = ["## Against other flatteners: CGAL on hard faces", "",
             "Produced by `bench/compare_peers.py` (do not edit by hand; one command, below). Each face is",
             "flattened by `wefm flatten FACE --s S` (s = 1, 0 and 2: altitude preserving, conformal, authalic;",
             "default options; the seam file where the face has one, as the evaluation runs it) and by four",
             "methods of CGAL "
             f"{cgal_version}'s Surface_mesh_parameterization",
             "through `wefm-peer-cgal` (bench/cgal_peer.cpp), each with CGAL's defaults and Eigen solvers:",
             "*LSCM* (free border, CGAL's two-point pinning: the extreme vertices along the longest",
             "bounding-box axis), *ARAP* (Liu et al. 2008, lambda 1000, at most 50 local/global iterations from",
             "LSCM, MVC post-processing when not one-to-one), and two fixed-border maps, *DCM* (discrete",
             "conformal, Eck et al.) and *MVC* (Floater's mean-value coordinates), both with the longest",
             "border on a circle by arc length. CGAL needs a topological disk, so it gets the face cut open",
             "along its seams (real faces: `face_cut.obj`; the cylinder: cut along `cylinder_open.seam` by the",
             "script). A face with several boundary loops (\"not a disk\") is outside CGAL's precondition; it is",
             "still given to CGAL, which does not check, to show what comes out (LSCM and ARAP leave the holes",
             "free; the fixed-border maps treat the vertices of the inner loops as interior ones).",
             "`cylinder_open_uncut` is the cylinder without its seam, an annulus, for every method.",
             "libigl and Boundary First Flattening are not measured.",
             "",
             "Every layout is checked by the independent `uvcheck.py`. A cell is **paper score (flipped",
             "triangles / boundary intersections), ∠ angle distortion, time**; bold = not a valid layout",
             "(flips or overlaps). The paper score is the area-weighted mean of min(r, 1/r)² (r = UV/3D area",
             "after scaling to the 3D area), minus 1 with any flip and minus 2 with any boundary",
             "intersection: it measures area distortion only, so it favours authalic maps (wefm s = 2, ARAP)",
             "over conformal ones (LSCM, DCM, wefm s = 0), whose angle distortion ∠ (uvcheck's",
             "`angle_dist_mean`, area-weighted mean of σmax/σmin, 1 = conformal) is the lower. Time is the wall",
             "time of the solve call alone (wefm: the report's `wall_solve`, the `wefm_face_solve` call;",
             "CGAL: the `parameterize` call), " + ("the smallest of " + str(repeat) + " runs" if repeat > 1 else "one run") +
             ", on the shared 2-core reference machine; reading, setup and writing",
             "are not included (whole-process times are in `BUILD/peers/peers.json`). Both run on one thread.",
             "*best* names the method with the highest score among the valid layouts of the face.", "",
             "    apt-get install -y libcgal-dev      # benchmark only; the library never links CGAL",
             "    cmake --preset release -DWEFM_BUILD_BENCH=ON && cmake --build build/release -j2 --target wefm_cli wefm-peer-cgal",
             f"    {cmdline}", "",
             f"Run at commit `{build_commit}`, {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}, load average "
             f"{os.getloadavg()[0]:.1f} at the end.", ""]
    lines += ["| " + " | ".join(head) + " |", "|" + "|".join(["---"] * 2 + ["--:"] * 2 + ["---"] * (len(methods) + 1)) + "|"]
    counts = {m: [0, 0, 0] for m, _ in methods}
    for face, info, results in rows:
        by = {r["method"]: r for r in results}
        loops = info.get("cgal_loops")
        what = face[1] + (f"; {seam_note(face, results)}" if face[3] else "")
        loops_text = "?" if loops is None else (f"{loops}: not a disk" if loops > 1 else str(loops))
        cells = [face[0], what, str(info.get("triangles", "?")), loops_text]
        for m, _ in methods:
            r = by.get(m)
            if r is None:
                cells.append("–")
                continue
            cells.append(cell(r))
            counts[m][0] += 1
            counts[m][1] += 1 if valid(r) else 0
        scored = [(by[m]["check"]["paper_score"], m) for m, _ in methods if m in by and valid(by[m])]
        top = max((sc for sc, _ in scored), default=None)
        best = [m for sc, m in scored if top is not None and sc >= top - 5e-4]
        for m in best:
            counts[m][2] += 1
        cells.append(", ".join(SHORT.get(m, m.replace("wefm_s", "wefm ")) for m in best) if best else "none valid")
        lines.append("| " + " | ".join(cells) + " |")
    lines.append("| **valid layouts** | | | | " + " | ".join(f"**{counts[m][1]} / {counts[m][0]}**" for m, _ in methods) + " | |")
    lines.append("| **best (within 0.0005)** | | | | " + " | ".join(f"{counts[m][2]}" for m, _ in methods) + " | |")
    return lines + [""] + findings(rows, methods)


def findings(rows, methods):
    """Sentences read off the table (so they stay true when it is regenerated)."""
    out = []
    for m, name in methods:
        bad = []
        for face, _, results in rows:
            r = next((x for x in results if x["method"] == m), None)
            if r is None or valid(r):
                continue
            c = r.get("check")
            if c:
                what = [plural(c["flips"], "flipped triangle") if c["flips"] else "",
                        plural(c["boundary_intersections"], "boundary intersection") if c["boundary_intersections"] else ""]
                bad.append(f"{face[0]} ({', '.join(w for w in what if w)})")
            else:
                bad.append(f"{face[0]} ({cell(r).replace('**', '')})")
        out.append(f"- {name}: {len(rows) - len(bad)} of {len(rows)} layouts valid" +
                   (f"; not valid: {'; '.join(bad)}." if bad else "."))
    beaten = []
    for face, _, results in rows:
        by = {r["method"]: r for r in results}
        wefm_best = max((by[m]["check"]["paper_score"] for m, _ in methods if m.startswith("wefm") and m in by
                         and valid(by[m])), default=None)
        for m, name in methods:
            if m.startswith("wefm") or m not in by or not valid(by[m]):
                continue
            sc = by[m]["check"]["paper_score"]
            if wefm_best is None or sc > wefm_best + 5e-4:
                beaten.append(f"{face[0]} ({name} {sc:.3f}, best wefm " +
                              ("none valid" if wefm_best is None else f"{wefm_best:.3f}") + ")")
    out.append("- A CGAL layout scores above every wefm layout of the same face on: " +
               ("; ".join(beaten) if beaten else "no face") + ".")
    return out


def write_section(results_md, lines):
    text = open(results_md).read() if os.path.exists(results_md) else "# Results\n"
    block = BEGIN + "\n" + "\n".join(lines) + "\n" + END
    if BEGIN in text and END in text:
        text = text[:text.index(BEGIN)] + block + text[text.index(END) + len(END):]
    else:
        text = text.rstrip("\n") + "\n\n" + block + "\n"
    open(results_md, "w").write(text)


# ------------------------------------------------------------------------------------------------

def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter, epilog=__doc__)
    ap.add_argument("--build", default=os.path.join(ROOT, "build", "release"), help="build tree [build/release]")
    ap.add_argument("--data", default="/work/shared/data", help="synthetic faces [/work/shared/data]")
    ap.add_argument("--real", default=None, help="real faces [DATA/real]")
    ap.add_argument("--uvcheck", default="/work/shared/tools/uvcheck.py")
    ap.add_argument("--out", default=None, help="layouts and peers.json [BUILD/peers]")
    ap.add_argument("--results", default=os.path.join(ROOT, "docs", "RESULTS.md"))
    ap.add_argument("--repeat", type=int, default=3, help="runs per method, the smallest time is reported [3]")
    ap.add_argument("--timeout", type=float, default=900.0, help="seconds per run [900]")
    ap.add_argument("--faces", default="", help="comma-separated face names (default: all); implies --no-write")
    ap.add_argument("--no-write", action="store_true", help="print the table, leave docs/RESULTS.md alone")
    a = ap.parse_args()
    real = a.real or os.path.join(a.data, "real")
    out = a.out or os.path.join(a.build, "peers")
    wefm = os.path.join(a.build, "apps", "wefm")
    peer = os.path.join(a.build, "bench", "wefm-peer-cgal")
    for path, what in ((wefm, "the wefm tool (cmake --build BUILD --target wefm_cli)"),
                       (peer, "wefm-peer-cgal (needs CGAL and -DWEFM_BUILD_BENCH=ON)"), (a.uvcheck, "uvcheck.py")):
        if not os.path.isfile(path):
            print(f"compare_peers: no {path}: {what}", file=sys.stderr)
            return 2
    for d in (a.data, real):
        if not os.path.isdir(d):
            print(f"compare_peers: no directory {d}", file=sys.stderr)
            return 2
    if a.repeat < 1:
        print("compare_peers: --repeat wants at least 1", file=sys.stderr)
        return 2
    os.makedirs(out, exist_ok=True)
    try:
        face_list = faces(a.data, real, out)
    except (OSError, ValueError) as e:
        print(f"compare_peers: {e}", file=sys.stderr)
        return 2
    if a.faces:
        want = set(a.faces.split(","))
        unknown = want - {f[0] for f in face_list}
        if unknown:
            print(f"compare_peers: unknown faces {', '.join(sorted(unknown))}", file=sys.stderr)
            return 2
        face_list = [f for f in face_list if f[0] in want]
    try:
        commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                                text=True).stdout.strip() or "?"
    except OSError:
        commit = "?"
    rows, dump = [], []
    cgal_version = "?"
    for face in face_list:
        info = {}
        try:
            _, F = read_obj(face[2])
            info["triangles"] = len(F)
        except OSError:
            pass
        results = [run_wefm(wefm, face, s, out, a.repeat, a.timeout, a.uvcheck) for s in WEFM_S]
        for m, _ in CGAL_METHODS:
            r = run_cgal(peer, face, m, out, a.repeat, a.timeout, a.uvcheck)
            j = r["runs"][-1].get("peer") or {}
            info.setdefault("cgal_loops", j.get("boundary_loops"))
            cgal_version = j.get("cgal_version", cgal_version)
            results.append(r)
        rows.append((face, info, results))
        dump.append({"face": face[0], "what": face[1], "wefm_input": face[2], "seam": face[3],
                     "cgal_input": face[4] or face[2], **info, "results": results})
        summary = ", ".join(f"{r['method']} " + (f"{r['check']['paper_score']:.3f}/{r['check']['flips']}/"
                                                 f"{r['check']['boundary_intersections']}" if r.get("check") else "-")
                            for r in results)
        print(f"{face[0]}: {summary}", file=sys.stderr)
    json.dump({"date": time.strftime("%Y-%m-%d %H:%M UTC", time.gmtime()), "commit": commit,
               "load_average": os.getloadavg(), "faces": dump}, open(os.path.join(out, "peers.json"), "w"), indent=1)
    cmdline = "bench/compare_peers.py" + (f" --repeat {a.repeat}" if a.repeat != 3 else "")
    lines = table(rows, cmdline, commit, a.repeat, cgal_version)
    if a.no_write or a.faces:
        print("\n".join(lines))
    else:
        write_section(a.results, lines)
        print(f"compare_peers: wrote the peers section of {a.results}; layouts and peers.json in {out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
