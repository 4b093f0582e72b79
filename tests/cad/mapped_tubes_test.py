#!/usr/bin/env python3
"""`wefm mesh-model` meshes a thin tube as a mapped strip on the shared edge nodes (issue 28 items 2 and
4, issue 32 item 2): a tube narrower than the element size, one seam and two ends with as many
segments, gets the end circles' segments round and elements twice as long along its axis.

pin_plate.brep (tests/cad/data): a pin of radius 0.2 and length 15 standing on a 10 x 10 x 2 plate, one
solid; made with Gmsh 4.8 (OpenCASCADE factory):
    Box(1) = {0, 0, 0, 10, 10, 2}; Cylinder(2) = {5, 5, 2, 0, 0, 15, 0.2};
    BooleanUnion{ Volume{1}; Delete; }{ Volume{2}; Delete; }  Save "pin_plate.brep";

Checked, at 1/40 of the diagonal (h about 0.48, the pin 2.6 h round):
- by default the pin's side is meshed transfinite, its triangles are the quads of a grid split in two
  (N nodes round each of M + 1 rings, 2 N M triangles), Lo's lambda on it at least 0.6, and
  it has fewer than half the triangles a free mesh of it has (--no-mapped-tubes, which meshes it free);
- both runs exit 0 and write a closed mesh (every edge of the MSH used by exactly two triangles);
- a face named with --transfinite that cannot be mapped (the plate's top, which has a hole) is meshed
  free on the same edge nodes: exit 0, the mesh still closed, the report and stderr say why.

usage: mapped_tubes_test.py WEFM MODEL.brep
"""
import sys
import tempfile
from collections import Counter

from model_mesh_test import mesh_model, read_msh_faces


def run(wefm, model, tmp, name, *extra):
    """mesh-model, and the written mesh closed: every edge of the MSH used by exactly two triangles."""
    report, msh, err = mesh_model(wefm, model, tmp, name, *extra)
    faces, _ = read_msh_faces(msh)
    uses = Counter(tuple(sorted((t[i], t[(i + 1) % 3]))) for tris in faces.values() for t in tris for i in range(3))
    assert set(uses.values()) == {2}, f"{name}: open or non-manifold edges: {Counter(uses.values())}"
    return report, faces, err


def main():
    wefm, model = sys.argv[1:3]
    with tempfile.TemporaryDirectory() as tmp:
        r, faces, _ = run(wefm, model, tmp, "mapped")
        tubes = [f for f in r["faces"] if f["surface_type"] == "cylinder"]
        assert len(tubes) == 1, tubes
        tube = tubes[0]
        assert tube["type"] == "transfinite" and tube["mapped_refused"] is None, tube
        assert tube["lambda_min"] >= 0.6, tube
        # A grid of quads split in two: N nodes round each of its M + 1 rings, 2 N M triangles.
        tris = faces[tube["face"]]
        assert len(tris) == tube["elements"], (len(tris), tube["elements"])
        edges = Counter(tuple(sorted((t[i], t[(i + 1) % 3]))) for t in tris for i in range(3))
        rim = {v for e, n in edges.items() if n == 1 for v in e}
        nodes = {v for t in tris for v in t}
        round_ = len(rim) // 2
        assert round_ >= 3 and len(nodes) % round_ == 0, (len(rim), len(nodes))
        along = len(nodes) // round_ - 1
        assert len(tris) == 2 * round_ * along, (len(tris), round_, along)

        free, _, _ = run(wefm, model, tmp, "free", "--no-mapped-tubes")
        free_tube = next(f for f in free["faces"] if f["face"] == tube["face"])
        assert free_tube["type"] == "free", free_tube
        assert 2 * tube["elements"] < free_tube["elements"], (tube["elements"], free_tube["elements"])

        # The plate's top has a hole (the pin's foot): no transfinite mesh of it.
        top = max((f for f in r["faces"] if f["surface_type"] == "plane"), key=lambda f: f["elements"])["face"]
        asked, _, err = run(wefm, model, tmp, "asked", "--transfinite", str(top))
        face = next(f for f in asked["faces"] if f["face"] == top)
        assert face["type"] == "free" and face["mapped_refused"] and "hole" in face["mapped_refused"], face
        assert f"face {top} " in err and "meshed free, not transfinite" in err, err
    print("mapped tubes: ok")


if __name__ == "__main__":
    main()
