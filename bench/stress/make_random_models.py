#!/usr/bin/python3
"""Random whole CAD models, for stress runs beyond the public ones (shared/data/cad-more): each a
solid of one to four primitives (box, cylinder, sphere, cone to a point, torus, wedge, ellipsoid,
partial cylinders, spheres and tori, a B-spline solid lofted through closed splines) at sizes from a
twentieth to twice the model's, joined by unions, differences and intersections, a third of them
then filleted and some chamfered. Seams, poles, cone apexes, thin walls, slivers and blends come out
of these the way they do out of real modelling, and so do the kernel's failures (a fillet that leaves
an invalid solid); a model Gmsh cannot write, or that comes out empty, is skipped.

Needs the gmsh command (Open CASCADE kernel; scripts/install-deps.sh installs it): each model is
written as OUT/gNNNN.geo and turned into OUT/gNNNN.step by `gmsh gNNNN.geo -0 -o gNNNN.step`. The same
seed gives the same models.

  make_random_models.py OUT COUNT [FIRST_SEED]

then, for instance:

  bench/stress/run_models.py build/release/apps/wefm OUT2 OUT/*.step --ratios 0.025,0.1 --no-gmsh
"""
import math
import os
import random
import subprocess
import sys


def primitive(r, tag):
    """One Open CASCADE primitive as .geo text, volume `tag`."""
    kind = r.choice(["box", "cylinder", "sphere", "cone", "torus", "wedge", "ellipsoid", "loft", "part_cylinder",
                     "part_sphere"])
    x, y, z = (r.uniform(-1, 1) for _ in range(3))
    s = math.exp(r.uniform(math.log(0.05), math.log(2.0)))
    if kind == "box":
        return f"Box({tag}) = {{{x},{y},{z}, {s * r.uniform(0.2, 2)},{s * r.uniform(0.2, 2)},{s * r.uniform(0.05, 2)}}};"
    if kind == "cylinder":
        return f"Cylinder({tag}) = {{{x},{y},{z}, {r.uniform(-1, 1)},{r.uniform(-1, 1)},{r.uniform(0.2, 2)}, {s * 0.5}}};"
    if kind == "part_cylinder":
        return f"Cylinder({tag}) = {{{x},{y},{z}, 0,0,{r.uniform(0.2, 2)}, {s * 0.5}, {r.uniform(0.5, 6.0)}}};"
    if kind == "sphere":
        return f"Sphere({tag}) = {{{x},{y},{z}, {s * 0.6}}};"
    if kind == "part_sphere":
        return f"Sphere({tag}) = {{{x},{y},{z}, {s * 0.6}, {r.uniform(-1.5, 0)}, {r.uniform(0, 1.5)}, {r.uniform(1, 6.28)}}};"
    if kind == "cone":
        tip = r.choice([0, s * r.uniform(0.05, 0.5)])
        return f"Cone({tag}) = {{{x},{y},{z}, {r.uniform(-1, 1)},{r.uniform(-1, 1)},{r.uniform(0.3, 2)}, {s * 0.6}, {tip}}};"
    if kind == "torus":
        angle = f", {r.uniform(1, 6.2)}" if r.random() < 0.4 else ""
        return f"Torus({tag}) = {{{x},{y},{z}, {s * 0.8}, {s * 0.8 * r.uniform(0.05, 0.45)}{angle}}};"
    if kind == "wedge":
        return f"Wedge({tag}) = {{{x},{y},{z}, {s * r.uniform(0.3, 2)},{s * r.uniform(0.3, 2)},{s * r.uniform(0.3, 2)}, {s * r.uniform(0, 0.5)}}};"
    if kind == "ellipsoid":
        return (f"Sphere({tag}) = {{{x},{y},{z}, {s * 0.5}}};\n"
                f"Dilate {{{{{x},{y},{z}}}, {{{r.uniform(0.3, 3)},{r.uniform(0.3, 3)},{r.uniform(0.1, 1)}}}}} {{ Volume{{{tag}}}; }}")
    lines, wires = [], []  # loft: closed splines at two to four heights
    for j in range(r.randint(2, 4)):
        points = []
        m = r.randint(5, 8)
        for i in range(m):
            a, radius, p = 2 * math.pi * i / m, s * r.uniform(0.3, 0.7), tag * 1000 + j * 20 + i
            lines.append(f"Point({p}) = {{{x + radius * math.cos(a)},{y + radius * math.sin(a)},{z + j * s * r.uniform(0.3, 0.8)}}};")
            points.append(p)
        c = tag * 1000 + j * 20 + 19
        lines.append(f"Spline({c}) = {{{','.join(map(str, points + [points[0]]))}}};")
        lines.append(f"Curve Loop({c}) = {{{c}}};")
        wires.append(c)
    lines.append(f"ThruSections({tag}) = {{{','.join(map(str, wires))}}};")
    return "\n".join(lines)


def script(r):
    """A whole model as .geo text."""
    lines = ['SetFactory("OpenCASCADE");', "Geometry.OCCBooleanPreserveNumbering = 0;"]
    count = r.randint(1, 4)
    for t in range(1, count + 1):
        lines.append(primitive(r, t))
    current = 1
    for t in range(2, count + 1):
        op = r.choice(["BooleanUnion", "BooleanUnion", "BooleanDifference", "BooleanDifference", "BooleanIntersection"])
        lines.append(f"{op}({100 + t}) = {{ Volume{{{current}}}; Delete; }}{{ Volume{{{t}}}; Delete; }};")
        current = 100 + t
    lines.append("v() = Volume{:};")
    blend = r.random()
    if blend < 0.5:
        lines.append("s() = Abs(Boundary{ Volume{v(0)}; });")
        lines.append("e() = Unique(Abs(Boundary{ Surface{s()}; }));")
    if blend < 0.35:
        k = r.randint(1, 4)
        lines.append(f"If (#e() >= {k})")
        lines.append(f"  Fillet{{v(0)}}{{{','.join('e(%d)' % i for i in range(k))}}}{{{r.uniform(0.01, 0.2)}}}")
        lines.append("EndIf")
    elif blend < 0.5:
        lines.append("If (#e() >= 2)")
        lines.append(f"  Chamfer{{v(0)}}{{e(0),e(1)}}{{s(0),s(0)}}{{{r.uniform(0.01, 0.1)}}}")
        lines.append("EndIf")
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) < 3:
        print(__doc__)
        return 2
    out, count = sys.argv[1], int(sys.argv[2])
    seed = int(sys.argv[3]) if len(sys.argv) > 3 else 0
    os.makedirs(out, exist_ok=True)
    made = 0
    while made < count:
        r = random.Random(seed)
        name = f"g{seed:04d}"
        seed += 1
        geo, step = os.path.join(out, name + ".geo"), os.path.join(out, name + ".step")
        with open(geo, "w") as f:
            f.write(script(r))
        try:
            p = subprocess.run(["gmsh", geo, "-0", "-o", step], capture_output=True, text=True, timeout=60)
            ok = p.returncode == 0 and "Error" not in p.stdout + p.stderr and os.path.exists(step) and os.path.getsize(step) >= 2000
        except FileNotFoundError:
            print("make_random_models.py: no gmsh command (scripts/install-deps.sh installs it)", file=sys.stderr)
            return 1
        except subprocess.TimeoutExpired:
            ok = False
        if not ok:
            for f in (geo, step):
                if os.path.exists(f):
                    os.remove(f)
            continue
        made += 1
        print(name, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
