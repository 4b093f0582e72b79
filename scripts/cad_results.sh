#!/usr/bin/env bash
# Regenerates the "CAD models" section of docs/RESULTS.md: runs `wefm model` on every sample model in
# CAD_DIR and tabulates, per model, the faces by surface type (ok / not converged / failed, flips,
# boundary intersections, score) and every face that is not clean. Only the text between the
# cad-results markers is replaced; the rest of docs/RESULTS.md is left alone.
#
#   scripts/cad_results.sh [BUILD_DIR]        # default build/release; needs WEFM_WITH_OCCT=ON
#
# Environment: CAD_DIR (default /work/shared/data/cad), OUT (per-model outputs, default
# BUILD_DIR/cad_results), JOBS (default 2), ATLAS_MODEL (model whose atlas goes to
# docs/cad_atlas_<model>.svg, default Ball), REPEAT (runs per command in the Gmsh comparison, whose
# times are the minimum; default 5), CAD_FAILURES (if set, the input OBJ + topo.json of every
# face that is not clean are copied there as <model>_fNNN.obj / .topo.json, to reproduce them with
# `wefm flatten X.obj --topology X.topo.json`).
set -euo pipefail
ROOT="$(cd "$(dirname "$0")/.." && pwd)"
BUILD="${1:-$ROOT/build/release}"
WEFM="$BUILD/apps/wefm"
CAD_DIR="${CAD_DIR:-/work/shared/data/cad}"
OUT="${OUT:-$BUILD/cad_results}"
JOBS="${JOBS:-2}"
ATLAS_MODEL="${ATLAS_MODEL:-Ball}"
[ -x "$WEFM" ] || { echo "cad_results: no $WEFM (build first)" >&2; exit 2; }
"$WEFM" model --help >/dev/null 2>&1 || { echo "cad_results: $WEFM was built without WEFM_WITH_OCCT" >&2; exit 2; }

mkdir -p "$OUT"
for model in "$CAD_DIR"/*.step "$CAD_DIR"/*.stp "$CAD_DIR"/*.iges "$CAD_DIR"/*.igs "$CAD_DIR"/*.brep "$CAD_DIR"/*.rle; do
  [ -e "$model" ] || continue
  name="$(basename "${model%.*}")"
  rm -rf "${OUT:?}/$name"
  atlas=()
  [ "$name" = "$ATLAS_MODEL" ] && atlas=(--atlas "$ROOT/docs/cad_atlas_$name.svg")
  start=$(date +%s%N)
  rc=0
  "$WEFM" model "$model" -o "$OUT/$name" -j "$JOBS" --quiet "${atlas[@]}" >"$OUT/$name.stdout" 2>"$OUT/$name.stderr" || rc=$?
  end=$(date +%s%N)
  echo "{\"exit_code\": $rc, \"wall_ms\": $(( (end - start) / 1000000 ))}" >"$OUT/$name.run.json"
  echo "$name: exit $rc"
  # Whole-model meshing at 1/40 of the bounding-box diagonal (the size of the issue's Gmsh reference).
  rc=0
  "$WEFM" mesh-model "$model" --size-ratio 0.025 -o "$OUT/$name.msh" --report "$OUT/$name.mesh.json" -j "$JOBS" -q \
    >"$OUT/$name.mesh.stdout" 2>"$OUT/$name.mesh.stderr" || rc=$?
  echo "$name mesh-model: exit $rc"
done

# Side by side with Gmsh (bench/compare_gmsh.py) when the gmsh program is installed.
rm -f "$OUT/compare_gmsh.md"
if command -v "${GMSH:-gmsh}" >/dev/null 2>&1; then
  models=()
  for model in "$CAD_DIR"/*.step "$CAD_DIR"/*.stp "$CAD_DIR"/*.iges "$CAD_DIR"/*.igs "$CAD_DIR"/*.brep "$CAD_DIR"/*.rle; do
    [ -e "$model" ] && models+=("$model")
  done
  python3 "$ROOT/bench/compare_gmsh.py" "$WEFM" "$OUT/gmsh" "${models[@]}" --jobs "$JOBS" --gmsh "${GMSH:-gmsh}" \
    --repeat "${REPEAT:-5}" --markdown >"$OUT/compare_gmsh.md"
  echo "gmsh comparison: $OUT/compare_gmsh.md"
fi

python3 - "$OUT" "$ROOT/docs/RESULTS.md" "$CAD_DIR" "${CAD_FAILURES:-}" <<'PY'
import json, os, shutil, subprocess, sys
out, results, cad_dir, failures = sys.argv[1:5]
lines = ["## CAD models", "",
         "Produced by `scripts/cad_results.sh` (do not edit by hand): `wefm model MODEL -o OUT -j 2` with the",
         "default settings (BRepMesh linear deflection 0.1 % of the bounding-box diagonal, angular 0.5 rad;",
         "solver defaults, repeated edges `auto`) on every model of `" + cad_dir + "`.",
         "`not conv.` faces hit the rho iteration cap: their best layout is written and counted here.",
         "A face is *clean* when it is ok with 0 flipped triangles and 0 boundary intersections.", ""]
try:
    version = subprocess.run(["git", "-C", os.path.dirname(results), "rev-parse", "--short", "HEAD"],
                             capture_output=True, text=True).stdout.strip()
    dirty = subprocess.run(["git", "-C", os.path.dirname(results), "status", "--porcelain", "--", ":/core", ":/capi"],
                           capture_output=True, text=True).stdout.strip()
    lines += [f"Library built from commit `{version}`" +
              (" plus uncommitted changes in core/ or capi/ (work in progress)." if dirty else "."), ""]
except OSError:
    pass
failure_rows = []
names = sorted(d for d in os.listdir(out) if os.path.isfile(os.path.join(out, d, "index.json")))
overall = []
for name in names:
    idx = json.load(open(os.path.join(out, name, "index.json")))
    run = json.load(open(os.path.join(out, name + ".run.json")))
    faces = idx["faces"]
    tris = sum(f["triangles"] for f in faces)
    t = idx["timings"]
    lines += [f"### {os.path.basename(idx['model'])}", "",
              f"{len(faces)} faces, {idx['edges_in_model']} edges, {tris} triangles; read {t['read']:.2f} s, "
              f"BRepMesh {t['mesh']:.2f} s, import {t['import']:.3f} s, flatten {t['flatten_wall']:.2f} s "
              f"(wall, -j {t['jobs']}); exit code {run['exit_code']}.", "",
              "| surface | faces | triangles | ok | not conv. | failed | faces with flips | flipped triangles "
              "| boundary intersections | mean score | min score |",
              "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"]
    def row(label, fs):
        sc = [f["score"] for f in fs if f["score"] is not None]
        n = lambda k: sum(1 for f in fs if f["status"] == k)
        flips = [f["flipped_triangles"] or 0 for f in fs]
        inter = [f["boundary_intersections"] or 0 for f in fs]
        return (f"| {label} | {len(fs)} | {sum(f['triangles'] for f in fs)} | {n('ok')} | {n('not_converged')} | "
                f"{len(fs) - n('ok') - n('not_converged')} | {sum(1 for x in flips if x)} | {sum(flips)} | "
                f"{sum(inter)} | " + (f"{sum(sc) / len(sc):.4f} | {min(sc):.4f} |" if sc else "- | - |"))
    for st in sorted({f["surface_type"] for f in faces}):
        lines.append(row(st, [f for f in faces if f["surface_type"] == st]))
    lines.append(row("**all**", faces))
    overall += [(name, f) for f in faces]
    bad = [f for f in faces if f["status"] != "ok" or (f["flipped_triangles"] or 0) or (f["boundary_intersections"] or 0)]
    if bad:
        lines += ["", "Faces that are not clean:", "",
                  "| face | surface | triangles | seams (decision) | status | score | flips | bnd. int. | reason |",
                  "|---:|---|---:|---|---|---:|---:|---:|---|"]
        for f in bad:
            seams = ", ".join(f"{d['edge_id']}:{d['mode']}" for d in f["seam_decisions"]) or "-"
            reason = f["reason"].split(": ", 2)[-1] if f["reason"] else ""
            reason = reason.replace("|", "/")[:110]
            score = f"{f['score']:.4f}" if f["score"] is not None else "-"
            lines.append(f"| {f['face']} | {f['surface_type']} | {f['triangles']} | {seams} | {f['status']} | {score} | "
                         f"{f['flipped_triangles']} | {f['boundary_intersections']} | {reason} |")
            if failures:
                os.makedirs(failures, exist_ok=True)
                failure_rows.append(f"| {name} | {f['face']} | {f['surface_type']} | {f['triangles']} | {seams} | {f['status']} | "
                                    f"{score} | {f['flipped_triangles']} | {f['boundary_intersections']} | {reason} | "
                                    f"`wefm flatten {name}_{f['name']}.obj --topology {name}_{f['name']}.topo.json -o out.obj` |")
                for key, ext in (("input_obj", ".obj"), ("input_topology", ".topo.json")):
                    if key in f["files"]:
                        shutil.copy(os.path.join(out, name, f["files"][key]), os.path.join(failures, f"{name}_{f['name']}{ext}"))
    lines.append("")
mesh_rows = []
for name in names:
    p = os.path.join(out, name + ".mesh.json")
    if not os.path.exists(p):
        continue
    r = json.load(open(p))
    c, t = r["conformity"], r["timings"]
    bad = [f"{f['face']} ({f['status']})" for f in r["faces"] if f["status"] != "ok"]
    mesh_rows.append(f"| {name} | {r['size']:.4g} | {r['triangles']} | {r['lambda_mesh']:.4f} | {r['lambda_min']:.4f} | "
                     f"{100 * r['fraction_below_0_6']:.1f} % | {c['open_edges']} | {c['non_manifold_edges']} | "
                     f"{', '.join(bad) or '-'} | {t['total']:.2f} s |")
if mesh_rows:
    lines += ["### Whole-model meshes (`wefm mesh-model`)", "",
              "`wefm mesh-model MODEL --size-ratio 0.025 -o MODEL.msh -j 2`: every model edge discretised once at",
              "h = 1/40 of the bounding-box diagonal (faces narrower than h at their width, at least h/4, and edges",
              "graded towards shorter neighbours: the local size of apps/README.md), each face flattened, meshed free",
              "in its domain (frontal-Delaunay at the 3D size, graded from short boundary segments) and mapped back,",
              "the face meshes welded on their shared edge nodes. Lo's lambda on the 3D triangles; `open` = edges used",
              "by one triangle, `non-manifold` = by more than two (a closed solid must have 0 and 0). Faces listed",
              "as not ok were still meshed from the flattener's best layout (`not_converged`).", "",
              "| model | h | triangles | lambda_mesh | min lambda | below 0.6 | open edges | non-manifold edges "
              "| faces not ok | time |",
              "|---|---:|---:|---:|---:|---:|---:|---:|---|---:|"] + mesh_rows + [
              ""]
cmp = os.path.join(out, "compare_gmsh.md")
if os.path.exists(cmp) and os.path.getsize(cmp) > 0:
    gv = subprocess.run(["gmsh", "--version"], capture_output=True, text=True)
    lines += ["### Side by side with Gmsh", "",
              "`bench/compare_gmsh.py`: `wefm mesh-model --size-ratio 0.025` against `gmsh MODEL -2 -clmax h -format msh41`",
              f"(Gmsh {(gv.stdout or gv.stderr).strip()}, OCC kernel, default Frontal-Delaunay and thread settings) at the same h. Both",
              "meshes are read back from their MSH files and measured by the same code; times are the wall and CPU",
              "(user + sys) times of each whole command (read, tessellate or import, mesh, write) on this shared",
              "2-core machine, the smallest of `REPEAT` runs (default 5).", ""]
    lines += open(cmp).read().rstrip("\n").split("\n") + [""]
clean = sum(1 for _, f in overall if f["status"] == "ok" and not f["flipped_triangles"] and not f["boundary_intersections"])
lines += [f"All models: {len(overall)} faces, {clean} clean, "
          f"{sum(1 for _, f in overall if f['status'] == 'not_converged')} not converged, "
          f"{sum(1 for _, f in overall if f['status'] not in ('ok', 'not_converged'))} failed, "
          f"{sum(1 for _, f in overall if f['flipped_triangles'])} with flipped triangles.", ""]
atlases = sorted(p for p in os.listdir(os.path.join(os.path.dirname(results))) if p.startswith("cad_atlas_"))
for a in atlases:
    lines += [f"Atlas of every domain of one model ({a}; colour = area distortion, black = flipped, green = seams):", "",
              f"![atlas]({a})", ""]
if failures and failure_rows:
    with open(os.path.join(failures, "README.md"), "w") as fh:
        fh.write("# CAD faces that are not clean (from scripts/cad_results.sh)\n\n"
                 "| model | face | surface | triangles | seams (decision) | status | score | flips | bnd. int. | reason | reproduce |\n"
                 "|---|---:|---|---:|---|---|---:|---:|---:|---|---|\n" + "\n".join(failure_rows) + "\n")
section = "<!-- cad-results:begin -->\n" + "\n".join(lines) + "<!-- cad-results:end -->\n"
text = open(results).read() if os.path.exists(results) else "# Results\n\n"
b, e = text.find("<!-- cad-results:begin -->"), text.find("<!-- cad-results:end -->")
if b >= 0 and e > b:
    text = text[:b] + section + text[e + len("<!-- cad-results:end -->\n"):]
else:
    text = text.rstrip("\n") + "\n\n" + section
open(results, "w").write(text)
print(f"wrote the CAD section of {results}")
PY
