#!/usr/bin/python3
"""Every face of a CAD model meshed by Gmsh (OCC kernel, isotropic, size RATIO x the bounding-box
diagonal), written like the real sample: OUT/fNNN/face.obj (seam sides merged, as Gmsh shares seam
nodes) and face.seam (facet edges along the curves the face uses twice). Needs Gmsh's Python API
(Debian: python3-gmsh, for /usr/bin/python3).

  make_gmsh_faces.py MODEL OUT RATIO"""
import sys, os, gmsh
model, out, ratio = sys.argv[1], sys.argv[2], float(sys.argv[3])
gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0)
gmsh.open(model)
xmin, ymin, zmin, xmax, ymax, zmax = gmsh.model.getBoundingBox(-1, -1)
diag = ((xmax-xmin)**2 + (ymax-ymin)**2 + (zmax-zmin)**2) ** 0.5
gmsh.option.setNumber("Mesh.MeshSizeMax", ratio * diag)
gmsh.option.setNumber("Mesh.MeshSizeMin", 0)
gmsh.model.mesh.generate(2)
os.makedirs(out, exist_ok=True)
for dim, tag in gmsh.model.getEntities(2):
    types, etags, enodes = gmsh.model.mesh.getElements(2, tag)
    tris = []
    for t, nodes in zip(types, enodes):
        if t == 2:
            tris += [tuple(int(x) for x in nodes[i:i+3]) for i in range(0, len(nodes), 3)]
    if not tris: continue
    used = sorted({n for t in tris for n in t}); idx = {n: i for i, n in enumerate(used)}
    ntags, coords, _ = gmsh.model.mesh.getNodes(-1, -1, includeBoundary=True)
    pos = {int(t): coords[3*i:3*i+3] for i, t in enumerate(ntags)}
    # Gmsh orients each surface's triangles consistently; which side is outward does not matter here.
    bnd = gmsh.model.getBoundary([(2, tag)], combined=False, oriented=True, recursive=False)
    count = {}
    for d, c in bnd: count[abs(c)] = count.get(abs(c), 0) + 1
    seams = [c for c, k in count.items() if k >= 2]
    edges = set()
    for a, b, c in tris:
        for u, v in ((a, b), (b, c), (c, a)): edges.add((min(u, v), max(u, v)))
    seam_pairs = []
    for c in seams:
        # The curve's line elements are its facet edges.
        etypes, _, en = gmsh.model.mesh.getElements(1, c)
        for t, nodes in zip(etypes, en):
            if t == 1:
                for i in range(0, len(nodes), 2):
                    u, v = int(nodes[i]), int(nodes[i+1])
                    if u in idx and v in idx and (min(u, v), max(u, v)) in edges: seam_pairs.append((idx[u], idx[v]))
    d = os.path.join(out, f"f{tag:03d}")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "face.obj"), "w") as f:
        for n in used: f.write("v %.17g %.17g %.17g\n" % tuple(pos[n]))
        for t in tris: f.write("f %d %d %d\n" % tuple(idx[n] + 1 for n in t))
    with open(os.path.join(d, "face.seam"), "w") as f:
        f.write(f"# seams: {seams}\n")
        for a, b in seam_pairs: f.write(f"{a} {b}\n")
gmsh.finalize()
