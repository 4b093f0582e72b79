"""Meshing a solved domain through the bindings (METHOD §9): quality, 3D placement, seams."""
import numpy as np

import wefm
from conftest import cylinder, flat_square, seam_pairs


def test_transfinite_square_is_exact(tmp_path):
    with wefm.Face(*flat_square(4)) as f:
        f.solve()
        with f.mesh_domain(size=0.125, type="transfinite") as dm:
            r = dm.report
            assert (r.nodes, r.elements, r.nodes_per_element) == (81, 64, 4)
            assert r.wiggle_max < 1e-20
            assert abs(r.scaled_jacobian_min - 1) < 1e-12
            # Node spacing in 3D is the requested size along both grid directions.
            el = dm.elements
            edges = np.linalg.norm(dm.xyz[el[:, 1]] - dm.xyz[el[:, 0]], axis=1)
            np.testing.assert_allclose(edges, 0.125, rtol=1e-9)
            dm.write_obj(tmp_path / "sq.obj")
            text = (tmp_path / "sq.obj").read_text().splitlines()
            assert sum(l.startswith("v ") for l in text) == 81
            assert sum(l.startswith("f ") and len(l.split()) == 5 for l in text) == 64
            # The numbers read back to the very doubles of the mesh, and each corner's v and vt agree.
            v = np.array([[float(t) for t in l.split()[1:]] for l in text if l.startswith("v ")])
            vt = np.array([[float(t) for t in l.split()[1:]] for l in text if l.startswith("vt ")])
            assert np.array_equal(v, dm.xyz) and np.array_equal(vt, dm.uv)
            corners = [c.split("/") for l in text if l.startswith("f ") for c in l.split()[1:]]
            assert all(a == b for a, b in corners)
            assert np.array_equal(np.array([int(a) - 1 for a, _ in corners]).reshape(-1, 4), el)


def test_free_mesh_nodes_lie_on_the_surface_and_map_back():
    xyz, tri = cylinder(rings=6, sectors=24, cut=True)
    with wefm.Face(xyz, tri) as f:
        f.solve(s=0.5)
        with f.mesh_domain(size=0.15) as dm:
            r = dm.report
            assert r.nodes_per_element == 3 and r.elements == dm.elements.shape[0]
            assert r.lambda_min >= 0.6 and r.lambda_mesh >= 0.9
            back = f.map_3d_to_uv(dm.xyz)
            assert back.inside.all()
            there = f.map_uv_to_3d(dm.uv)
            assert there.inside.all()
            np.testing.assert_allclose(there.points, dm.xyz, atol=1e-9)


def test_periodic_seam_nodes_match_and_edge_nodes_are_used():
    xyz, tri = cylinder(rings=6, sectors=24, cut=False)
    with wefm.Face(xyz, tri, default_edge_mode="periodic") as f:
        f.add_seams(seam_pairs(6, 24))
        f.solve(s=0.0)
        with f.mesh_domain(size=0.2) as dm:
            p = dm.xyz
            on_seam = (np.abs(p[:, 1]) < 1e-12) & (p[:, 0] > 0)
            heights, counts = np.unique(np.round(p[on_seam, 2], 9), return_counts=True)
            assert len(heights) >= 8 and (counts == 2).all()
        # The seam edge: nodes at uneven heights, given by the caller, appear in the mesh.
        seam_edge = next(e for e in range(f.edge_count()) if f.edge_is_repeated(e))
        chain = f.edge(seam_edge)
        z0, z1 = xyz[chain[0], 2], xyz[chain[-1], 2]
        zs = np.array([z0, z0 + 0.1 * (z1 - z0), z0 + 0.15 * (z1 - z0), z0 + 0.7 * (z1 - z0), z1])
        f.set_edge_nodes(seam_edge, np.column_stack([np.ones(5), np.zeros(5), zs]))
        with f.mesh_domain(size=0.2) as dm:
            p = dm.xyz
            on_seam = (np.abs(p[:, 1]) < 1e-12) & (p[:, 0] > 0)
            np.testing.assert_allclose(np.unique(np.round(p[on_seam, 2], 12)), np.sort(zs), atol=1e-12)
        f.clear_edge_nodes()


def test_bad_mesh_options_raise():
    with wefm.Face(*flat_square(3)) as f:
        f.solve()
        try:
            f.mesh_domain(size=-1.0)
        except wefm.InvalidArgumentError as e:
            assert "size" in str(e)
        else:
            raise AssertionError("negative size accepted")


def test_quad_dominant_and_all_quad_meshes(tmp_path):
    xyz, tri = cylinder(rings=6, sectors=24, cut=True)
    with wefm.Face(xyz, tri) as f:
        f.solve(s=0.5)
        with f.mesh_domain(size=0.15) as t:
            triangles = t.report.elements
        with f.mesh_domain(size=0.15, elements="quad-dominant") as dm:
            r, el = dm.report, dm.elements
            assert r.nodes_per_element == 4 and el.shape == (r.elements, 4)
            is_tri = el[:, 3] == -1
            # Pairs of the triangle mesh's triangles: the same nodes, each triangle in one element.
            assert r.quads == (~is_tri).sum() and 2 * r.quads + is_tri.sum() == triangles
            assert r.quad_area_fraction >= 0.95 and r.scaled_jacobian_min >= 0.3
            assert (el[~is_tri] >= 0).all() and (el[is_tri, :3] >= 0).all()
            dm.write_obj(tmp_path / "qd.obj")
            faces = [l.split()[1:] for l in (tmp_path / "qd.obj").read_text().splitlines() if l.startswith("f ")]
            assert sorted(len(c) for c in faces) == sorted(3 if t else 4 for t in is_tri)
        with f.mesh_domain(size=0.15, elements="quads") as dm:
            r, el = dm.report, dm.elements
            assert r.quads == r.elements and (el >= 0).all() and r.quad_area_fraction == 1.0
            # Each edge inside the face is used by two quads, each boundary edge by one.
            edges = {}
            for q in el:
                for k in range(4):
                    e = tuple(sorted((q[k], q[(k + 1) % 4])))
                    edges[e] = edges.get(e, 0) + 1
            assert set(edges.values()) == {1, 2}


def test_auto_reports_why_it_made_a_free_mesh():
    with wefm.Face(*flat_square(4)) as f:
        f.solve()
        with f.mesh_domain(size=0.125, type="auto") as dm:
            assert dm.report.transfinite == 1 and dm.report.automatic_fallback == wefm.FALLBACK_NONE
        # Corners that are not uses of the outer loop: an error, as for a transfinite mesh.
        try:
            f.mesh_domain(size=0.125, type="auto", corners=(0, 1, 2, 10 ** 6))
            raise AssertionError("bad corners accepted")
        except wefm.InvalidArgumentError:
            pass
