"""Reading meshes and writing flattened OBJ files."""
import numpy as np

import wefm
from conftest import requires


def test_read_mesh_returns_arrays_and_info(pyramid_path):
    xyz, tri, info = wefm.read_mesh(pyramid_path)
    assert xyz.shape == (6, 3) and xyz.dtype == np.float64
    assert tri.shape == (5, 3) and tri.dtype == np.int32
    assert info.components == 1 and info.genus == 0 and info.non_manifold_edges == 0
    np.testing.assert_allclose(info.area, 5 * np.sqrt(3) / 4, rtol=1e-9)


def test_load_into_face_equals_arrays(pyramid_path):
    xyz, tri, _ = wefm.read_mesh(pyramid_path)
    with wefm.Face() as a, wefm.Face(xyz, tri) as b:
        a.load(pyramid_path)
        np.testing.assert_array_equal(a.solve() and a.uv, b.solve() and b.uv)


def test_mesh_from_arrays_round_trips(pyramid_path):
    xyz, tri, _ = wefm.read_mesh(pyramid_path)
    with wefm.Mesh.from_arrays(xyz, tri) as m:
        np.testing.assert_array_equal(m.vertices, xyz)
        np.testing.assert_array_equal(m.triangles, tri)


def test_write_obj_has_one_vt_per_use(tmp_path, pyramid_path):
    out = tmp_path / "flat.obj"
    with wefm.Face() as f:
        f.load(pyramid_path)
        f.add_seams([(0, 3)])
        f.solve()
        f.write_obj(out)
        n_uses = f.use_count()
    lines = out.read_text().splitlines()
    assert sum(l.startswith("vt ") for l in lines) == n_uses
    assert sum(l.startswith("f ") for l in lines) == 5


@requires("face_map_3d_to_uv")
def test_mapping_vertices_round_trips():
    from conftest import flat_square
    xyz, tri = flat_square(3)
    with wefm.Face(xyz, tri) as f:
        f.solve()
        uv = f.uv
        back = f.map_3d_to_uv(xyz)
        assert back.inside.all()
        np.testing.assert_allclose(back.points, uv[np.argsort(f.use_vertex)], atol=1e-12)
        there = f.map_uv_to_3d(uv)
        np.testing.assert_allclose(there.points, xyz[f.use_vertex], atol=1e-12)
        outside = f.map_uv_to_3d(uv.max(axis=0, keepdims=True) + 10)
        assert outside.status[0] == 16 and outside.triangle[0] == -1


@requires("face_mesh_domain")
def test_mesh_domain_returns_a_domain_mesh():
    from conftest import flat_square
    with wefm.Face(*flat_square(3)) as f:
        f.solve()
        with f.mesh_domain(size=0.2) as dm:
            r = dm.report
            assert dm.uv.shape == (r.nodes, 2) and dm.xyz.shape == (r.nodes, 3)
            assert dm.elements.shape == (r.elements, r.nodes_per_element)
