#!/usr/bin/env python3
"""`wefm mesh-model` merges faces far narrower than the element size with a neighbour for meshing
(virtual topology, issue 28 item 4: a quality floor on narrow faces), at 1/40 of the diagonal.

fillet_chamfer_box.brep (tests/cad/data): a 10 x 6 x 4 box with one edge rounded at radius 0.003 and
another chamfered at 0.0007, about h / 70 and h / 300 wide at h = 1/40 of the diagonal (both are
merged: the chamfer keeps slivers on its own, the fillet refines its neighbours); made with Gmsh 4.8
(OpenCASCADE factory):
    Box(1) = {0, 0, 0, 10, 6, 4}; f() = Fillet{1}{1}{0.003}; c() = Chamfer{f(0)}{12}{6}{0.0007};
    Save "fillet_chamfer_box.brep";
fillet_chamfer_box_twice.brep: the same box held twice at the same place (Gmsh:
    d() = Translate{0, 0, 0}{ Duplicata{ Volume{c(0)}; } }; before the Save), every face lying on its
copy. The chamfers (narrower than h / 100) are still merged, alike in both copies; the fillets, which
mesh well enough on their own, are kept so that a face and its copy stay meshed alike.

Checked: with --no-merge-faces --no-local-size the narrow faces keep slivers (min Lo lambda below 0.3:
the model does exercise the property; with local sizes alone they are sized by their width, as any
needle face: min lambda 0.59 with 45k triangles, against 0.80 with 8k when merged); by default the run exits 0, min lambda is at least 0.3, the mesh is closed
(every edge of the written MSH used by exactly two triangles, as a closed solid's are), every
triangle is in the group of a face of the model, and the report names each merge (the face, the face
it was merged into, the shared model edges, why) on both the merge list and the receiving face.

step_box.brep: a 10 x 6 x 4 box whose top steps up by 0.0007 over half its length (h / 440 at 1/40 of
the diagonal): the step is a needle at right angles to both its neighbours (Gmsh 4.8, OpenCASCADE):
    Box(1) = {0, 0, 0, 10, 6, 4}; Box(2) = {0, 0, 0, 5, 6, 4.0007};
    BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; } Save "step_box.brep";
A face under h / 300 wide merges across any edge short of a fold back (a triangle across it leaves the
surface by at most its width): the step is merged into a top face across 90 degrees, the model is meshed closed with
min lambda at least 0.3 and far fewer triangles than with the step meshed on its own (sized by its
width), where the ends of the merged step meet the side walls' corners.

usage: merge_faces_test.py WEFM MODEL.brep TWICE.brep STEP.brep
"""
import sys
import tempfile
from collections import Counter

from model_mesh_test import mesh_model, read_msh_faces


def run(wefm, model, tmp, name, *extra):
    report, msh, _ = mesh_model(wefm, model, tmp, name, *extra)
    return report, msh


def assert_closed(report, msh):
    """No defect in the report, and every edge of the written MSH used by exactly two triangles (a closed
    solid's mesh). Returns the MSH's triangles per face."""
    c = report["conformity"]
    assert c["unexplained_open_edges"] == 0 and c["unexplained_non_manifold_edges"] == 0 and c["zero_area_triangles"] == 0, c
    faces, _ = read_msh_faces(msh)
    uses = Counter(tuple(sorted((t[i], t[(i + 1) % 3]))) for tris in faces.values() for t in tris for i in range(3))
    assert set(uses.values()) == {2}, f"open or non-manifold edges: {Counter(uses.values())}"
    return faces


def check_twice(wefm, model, tmp):
    r, msh = run(wefm, model, tmp, "twice")
    c = r["conformity"]
    assert c["unexplained_open_edges"] == 0 and c["unexplained_non_manifold_edges"] == 0, c
    h = r["size"]
    merged = {m["face"]: m for m in r["merged_faces"]}
    needles = [m for m in merged.values() if m["width"] < h / 100]
    wider = [m for m in merged.values() if h / 100 <= m["width"] < h / 30]
    assert len(needles) == 2 and len(wider) == 2, merged
    for m in needles:
        assert m["merged_into"], m
    for m in wider:
        assert m["merged_into"] is None and "lies on face" in m["reason"], m
        other = int(m["reason"].split("lies on face ")[1].split(",")[0])
        assert other in merged and other != m["face"] and f"lies on face {m['face']}," in merged[other]["reason"], (m, merged[other])
    faces, _ = read_msh_faces(msh)
    copies = [f for f in r["faces"] if f["mesh_of_face"]]
    assert len(copies) == len(r["faces"]) // 2, [(f["face"], f["mesh_of_face"]) for f in r["faces"]]
    for f in copies:
        assert len(faces[f["face"]]) == len(faces[f["mesh_of_face"]]), f
    print(f"twice: min lambda {r['lambda_min']:.3f}; needles merged in both copies, "
          + ", ".join(f"f{m['face']} kept" for m in wider))


def check_step(wefm, model, tmp):
    alone, _ = run(wefm, model, tmp, "step-alone", "--no-merge-faces")
    r, msh = run(wefm, model, tmp, "step")
    h = r["size"]
    merges = [m for m in r["merged_faces"] if m["merged_into"]]
    assert len(merges) == 1 and merges[0]["width"] < h / 100 and merges[0]["dihedral_degrees"] > 80, r["merged_faces"]
    assert_closed(r, msh)
    assert r["lambda_min"] >= 0.3, r["lambda_min"]
    assert 4 * r["triangles"] < alone["triangles"], (r["triangles"], alone["triangles"])
    print(f"step: merged f{merges[0]['face']} into f{merges[0]['merged_into']} across {merges[0]['dihedral_degrees']:.0f} deg; "
          f"{alone['triangles']} triangles (min {alone['lambda_min']:.3f}) -> {r['triangles']} (min {r['lambda_min']:.3f})")


def main():
    wefm, model, twice, step = sys.argv[1:5]
    with tempfile.TemporaryDirectory() as tmp:
        strict, _ = run(wefm, model, tmp, "strict", "--no-merge-faces", "--no-local-size")
        assert strict["merged_faces"] == [], strict["merged_faces"]
        assert strict["lambda_min"] < 0.3, f"the narrow faces mesh well on their own (min {strict['lambda_min']}): no test"
        all_faces = {f["face"] for f in strict["faces"]}

        r, msh = run(wefm, model, tmp, "merged")
        assert r["lambda_min"] >= 0.3, f"min lambda {r['lambda_min']} with merging"
        faces = assert_closed(r, msh)
        assert set(faces) <= all_faces, f"triangles in groups that are no face: {set(faces) - all_faces}"

        merges = [m for m in r["merged_faces"] if m["merged_into"]]
        assert merges, f"expected the chamfer merged: {merges}"
        kept = {f["face"]: f for f in r["faces"]}
        for m in merges:
            assert m["face"] in all_faces and m["merged_into"] in kept and m["face"] not in kept, m
            assert m["shared_edges"] and m["reason"].startswith("narrow") and m["dihedral_degrees"] <= 50, m
            assert m["face"] in kept[m["merged_into"]]["merged_faces"], (m, kept[m["merged_into"]])
        print(f"min lambda {strict['lambda_min']:.3f} -> {r['lambda_min']:.3f}; merged "
              + ", ".join(f"f{m['face']} into f{m['merged_into']} ({m['dihedral_degrees']:.0f} deg)" for m in merges))
        assert len(merges) == 2, f"expected the fillet and the chamfer merged: {merges}"
        check_twice(wefm, twice, tmp)
        check_step(wefm, step, tmp)
    return 0


if __name__ == "__main__":
    sys.exit(main())
