"""Developable faces flatten without distortion (METHOD: isometric when one exists)."""
import numpy as np

import wefm
from conftest import cylinder, flat_square

EXACT = 1 + 1e-8


def uv_edge_lengths(uv, triangle_uses):
    corners = uv[triangle_uses]                      # (m, 3, 2)
    return np.linalg.norm(corners - np.roll(corners, -1, axis=1), axis=2).ravel()


def xyz_edge_lengths(xyz, triangles):
    corners = xyz[triangles]
    return np.linalg.norm(corners - np.roll(corners, -1, axis=1), axis=2).ravel()


def test_flat_square_has_no_distortion():
    xyz, tri = flat_square()
    r = wefm.flatten(xyz, tri)
    assert r.report.angle_distortion_max < EXACT
    assert r.report.flipped_triangles == 0
    assert r.uv.shape == (len(xyz), 2)
    assert r.triangle_uses.shape == tri.shape
    # Isometric up to one global scale.
    ratio = uv_edge_lengths(r.uv, r.triangle_uses) / xyz_edge_lengths(xyz, tri)
    assert np.ptp(ratio) < 1e-9 * ratio.mean()


def test_cut_open_cylinder_has_no_distortion():
    xyz, tri = cylinder(cut=True)
    r = wefm.flatten(xyz, tri)
    assert r.report.angle_distortion_max < EXACT
    assert r.report.flipped_triangles == 0
    ratio = uv_edge_lengths(r.uv, r.triangle_uses) / xyz_edge_lengths(xyz, tri)
    assert np.ptp(ratio) < 1e-9 * ratio.mean()


def test_int64_triangles_and_fortran_order_give_the_same_result():
    xyz, tri = cylinder(cut=True)
    a = wefm.flatten(xyz, tri)
    b = wefm.flatten(np.asfortranarray(xyz), np.asfortranarray(tri.astype(np.int64)))
    np.testing.assert_array_equal(a.uv, b.uv)


def test_pyramid_cut_from_apex_to_base_corner_is_equilateral(pyramid_path):
    xyz, tri, info = wefm.read_mesh(pyramid_path)
    assert (info.vertices, info.triangles, info.boundary_loops) == (6, 5, 1)
    apex, corner = 0, 3                              # the apex is interior with 240 degrees
    with wefm.Face() as f:
        f.set_mesh(xyz, tri)
        f.add_seams([(apex, corner)])
        report = f.solve()
        lengths = uv_edge_lengths(f.uv, f.triangle_uses)
        # A slit from the boundary to an interior vertex doubles every vertex but its tip.
        assert len(f.vertex_uses(apex)) == 1 and len(f.vertex_uses(corner)) == 2
        assert f.use_count() == 7
    assert report.flipped_triangles == 0
    # The file stores coordinates to 12 digits, hence the tolerance.
    assert lengths.max() / lengths.min() - 1 < 1e-9
