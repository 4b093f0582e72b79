"""examples/python/flatten_obj.py run as a user runs it, on a closed cylinder and its seam file."""
import os
import subprocess
import sys

import numpy as np

from conftest import cylinder, seam_pairs

EXAMPLE = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples", "python",
                       "flatten_obj.py")
RINGS, SECTORS = 4, 12


def write_obj(path, xyz, tri):
    with open(path, "w") as f:
        for p in xyz:
            f.write("v %.17g %.17g %.17g\n" % tuple(p))
        for t in tri:
            f.write("f %d %d %d\n" % tuple(t + 1))


def run_example(tmp_path, closed, seam_text):
    xyz, tri = cylinder(RINGS, SECTORS, cut=not closed)
    mesh = tmp_path / "in.obj"
    write_obj(mesh, xyz, tri)
    seams = tmp_path / "in.seam"
    seams.write_text(seam_text)
    out = tmp_path / "out.obj"
    done = subprocess.run([sys.executable, EXAMPLE, str(mesh), str(out), "--seams", str(seams)],
                          capture_output=True, text=True, timeout=120)
    return done, out


def uv_count(path):
    return sum(1 for line in open(path) if line.startswith("vt "))


def test_seam_file_of_comments_only_flattens_the_face_as_it_is(tmp_path):
    # Half of the shared real faces come with a seam file holding only comments.
    done, out = run_example(tmp_path, closed=False, seam_text="# no seams on this face\n#\n")
    assert done.returncode == 0, done.stderr
    xyz, _ = cylinder(RINGS, SECTORS, cut=True)
    assert uv_count(out) == len(xyz)


def test_seam_file_cuts_the_closed_cylinder_open(tmp_path):
    pairs = seam_pairs(RINGS, SECTORS)
    text = "# the generator at angle 0\n" + "".join("%d %d\n" % tuple(p) for p in pairs)
    done, out = run_example(tmp_path, closed=True, seam_text=text)
    assert done.returncode == 0, done.stderr
    xyz, _ = cylinder(RINGS, SECTORS, cut=False)
    # Every vertex on the seam gets a second use.
    assert uv_count(out) == len(xyz) + len(np.unique(pairs))


def test_malformed_seam_line_names_the_line(tmp_path):
    done, _ = run_example(tmp_path, closed=True, seam_text="# ok\n1 2 3\n")
    assert done.returncode != 0
    assert "in.seam:2" in done.stderr
