#!/usr/bin/env bash
# Regenerates the "Real CAD faces" section of docs/RESULTS.md: flattens every face of the real sample
# (REAL_DIR, default /work/shared/data/real: single CAD faces as a mesher receives them, see its
# README) the way the evaluation does, `wefm flatten face.obj --seams face.seam`, at s = 0.3, 1 and 2,
# and checks every layout with the independent checker (UVCHECK, default
# /work/shared/tools/uvcheck.py; needs numpy for /usr/bin/python3). Only the text between the
# real-sample markers is replaced.
#
#   scripts/real_sample.sh [BUILD_DIR]      # default build/release
#
# Environment: REAL_DIR, UVCHECK, OUT (layouts and reports, default BUILD_DIR/real_sample),
# S_VALUES (default "0.3 1 2").
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build/release}"
WEFM="$BUILD/apps/wefm"
REAL_DIR="${REAL_DIR:-/work/shared/data/real}"
UVCHECK="${UVCHECK:-/work/shared/tools/uvcheck.py}"
OUT="${OUT:-$BUILD/real_sample}"
S_VALUES="${S_VALUES:-0.3 1 2}"
[ -x "$WEFM" ] || { echo "real_sample: no $WEFM (build first)" >&2; exit 2; }
[ -d "$REAL_DIR" ] || { echo "real_sample: no $REAL_DIR" >&2; exit 2; }
mkdir -p "$OUT"
/usr/bin/python3 - "$WEFM" "$REAL_DIR" "$UVCHECK" "$OUT" "$ROOT/docs/RESULTS.md" "$S_VALUES" <<'PY'
import json, os, subprocess, sys, time
wefm, real, uvcheck, out, results, svalues = sys.argv[1:7]
svalues = svalues.split()
rows, totals = [], {s: [0, 0] for s in svalues}
for name in sorted(os.listdir(real)):
    d = os.path.join(real, name)
    if not os.path.isfile(os.path.join(d, "face.obj")):
        continue
    topo = json.load(open(os.path.join(d, "topo.json")))
    seam = os.path.join(d, "face.seam")
    has_seam = any(l.strip() and not l.startswith("#") for l in open(seam))
    tris = sum(1 for l in open(os.path.join(d, "face.obj")) if l.startswith("f "))
    cells = [name, topo.get("surface_type", "?"), str(tris), "yes" if has_seam else "-"]
    for s in svalues:
        uv, rep = os.path.join(out, f"{name}.s{s}.obj"), os.path.join(out, f"{name}.s{s}.json")
        cmd = [wefm, "flatten", os.path.join(d, "face.obj"), "--s", s, "-o", uv, "--report", rep, "-q"]
        if has_seam:
            cmd += ["--seams", seam]
        t0 = time.time()
        rc = subprocess.run(cmd, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL).returncode
        wall = time.time() - t0
        try:
            u = json.loads(subprocess.run(["/usr/bin/python3", uvcheck, uv, "--json"], capture_output=True, text=True).stdout)
            valid = u["flips"] == 0 and u["boundary_intersections"] == 0
            r = json.load(open(rep))
            cell = f"{u['paper_score']:.3f}" + ("" if valid else f" ({u['flips']} flips, {u['boundary_intersections']} overlaps)")
            if abs(r.get("s", float(s)) - float(s)) > 1e-9:
                cell += f" at s = {r['s']:g}"
            if rc != 0:
                cell += f", exit {rc}"
        except Exception:
            valid, cell = False, f"failed (exit {rc})"
        totals[s][0] += 1
        totals[s][1] += 1 if valid and rc == 0 else 0
        cells.append(f"{cell}, {wall:.2f} s")
    rows.append("| " + " | ".join(cells) + " |")
head = ["face", "surface", "triangles", "seam"] + [f"s = {s}: score, time" for s in svalues]
summary = ", ".join(f"s = {s}: {v[1]}/{v[0]} valid with exit 0" for s, v in totals.items())
lines = ["## Real CAD faces", "",
         "Produced by `scripts/real_sample.sh` (do not edit by hand): every face of the real sample",
         f"(`{real}`, single faces of real CAD models as a mesher receives them) flattened the way the",
         "evaluation does, `wefm flatten face.obj --seams face.seam --s S` with default options, and each",
         "layout checked by the independent `uvcheck.py` (its paper score; flips and boundary overlaps are",
         "named when not 0). Times are wall seconds of the whole command on the 2-core reference machine.",
         "", f"{summary}.", "",
         "| " + " | ".join(head) + " |", "|" + "|".join(["---"] * 2 + ["--:"] * 2 + ["--:"] * len(svalues)) + "|"] + rows
text = open(results).read() if os.path.exists(results) else "# Results\n"
begin, end = "<!-- real-sample:begin -->", "<!-- real-sample:end -->"
block = begin + "\n" + "\n".join(lines) + "\n" + end
if begin in text:
    text = text[:text.index(begin)] + block + text[text.index(end) + len(end):]
else:
    text = text.rstrip("\n") + "\n\n" + block + "\n"
open(results, "w").write(text)
print(summary)
PY
