#!/usr/bin/python3
"""Flattens every ROOT/*/f*/face.obj with its face.seam (the evaluation's `wefm flatten face.obj
--seams face.seam`) at several s and checks each layout with uvcheck.py; one line per run, BAD for
anything but exit 0 with 0 flips and 0 boundary overlaps, and a summary.

  run_faces.py WEFM ROOT [S_VALUES, default 1,0.3,2] [UVCHECK, default /work/shared/tools/uvcheck.py]"""
import sys, glob, os, subprocess, json, time
B, root = sys.argv[1], sys.argv[2]
svals = (sys.argv[3] if len(sys.argv) > 3 else "1,0.3,2").split(",")
uvcheck = sys.argv[4] if len(sys.argv) > 4 else "/work/shared/tools/uvcheck.py"
bad = []; n = 0
for d in sorted(glob.glob(os.path.join(root, "*", "f*"))):
    obj = os.path.join(d, "face.obj"); seam = os.path.join(d, "face.seam")
    has = any(l.strip() and not l.startswith("#") for l in open(seam))
    for s in svals:
        n += 1
        o = os.path.join(d, f"uv_s{s}.obj"); rj = os.path.join(d, f"r_s{s}.json")
        args = [B, "flatten", obj, "-o", o, "--report", rj, "-q", "--s", s] + (["--seams", seam] if has else [])
        t0 = time.time()
        try:
            p = subprocess.run(args, capture_output=True, text=True, timeout=120); rc = p.returncode; err = p.stderr.strip()[:160]
        except subprocess.TimeoutExpired:
            rc = -9; err = "timeout"
        dt = time.time() - t0
        fl = bi = sc = None
        if os.path.exists(o) and rc in (0, 5):
            try:
                u = json.loads(subprocess.run(["/usr/bin/python3", uvcheck, o, "--json"], capture_output=True, text=True, timeout=60).stdout)
                fl, bi, sc = u["flips"], u["boundary_intersections"], u["paper_score"]
            except Exception as ex:
                err += f" uvcheck failed {ex}"
        ok = rc == 0 and fl == 0 and bi == 0
        tris = sum(1 for l in open(obj) if l.startswith("f "))
        line = f"{os.path.relpath(d, root)} tris={tris} seam={int(has)} s={s} rc={rc} t={dt:.2f} flips={fl} bi={bi} score={sc if sc is None else round(sc,3)} {err}"
        print(("OK  " if ok else "BAD ") + line, flush=True)
        if not ok: bad.append(line)
print(f"== {n} runs, {len(bad)} bad")
for b in bad: print("BAD", b)
