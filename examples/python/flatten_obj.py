#!/usr/bin/env python3
"""Flatten a triangulated face and write it as OBJ with UVs (vt per vertex use).

    python3 examples/python/flatten_obj.py IN.obj OUT.obj [--seams FILE] [--s 1.0]

FILE lists facet edges to cut along, one "i j" pair of 0-based vertex indices a line ('#' comments),
as /work/shared/data/cylinder_open.seam. Needs the wefm package importable and its library found
(e.g. PYTHONPATH=bindings/python WEFM_LIBRARY=build/capi/libwefm.so).
"""
import argparse
import sys

import wefm


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input")
    parser.add_argument("output")
    parser.add_argument("--seams", help="file of 0-based vertex pairs to cut along")
    parser.add_argument("--s", type=float, default=1.0, help="roll-out exponent in [0, 2]")
    args = parser.parse_args(argv)

    vertices, triangles, info = wefm.read_mesh(args.input)
    print("%s: %d vertices, %d triangles, %d boundary loop(s), genus %d"
          % (args.input, info.vertices, info.triangles, info.boundary_loops, info.genus))
    try:
        with wefm.Face(vertices, triangles) as face:
            if args.seams:
                face.add_seams(wefm.read_seams(args.seams))
            report = face.solve(s=args.s, strict=False)
            face.write_obj(args.output)
    except (wefm.WefmError, ValueError) as err:  # ValueError: a malformed seam line
        print("wefm: %s" % err, file=sys.stderr)
        return 1
    print("wrote %s: score %.6f, angle distortion max %.6f, %d flipped triangle(s), %.3f s"
          % (args.output, report.score, report.angle_distortion_max, report.flipped_triangles,
             report.time_total))
    return 0


if __name__ == "__main__":
    sys.exit(main())
