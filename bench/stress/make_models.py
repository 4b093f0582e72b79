#!/usr/bin/python3
"""Writes a set of small CAD models with Gmsh's Open CASCADE kernel (needs python3-gmsh): the shapes
real faces come from, each with seams, poles, apexes or thin parts. OUT/<name>.brep, one per model.

  make_models.py OUT"""
import os, sys, gmsh

out = sys.argv[1]
os.makedirs(out, exist_ok=True)

def model(name, build):
    gmsh.initialize(); gmsh.option.setNumber("General.Terminal", 0)
    gmsh.model.add(name)
    build(gmsh.model.occ)
    gmsh.model.occ.synchronize()
    gmsh.write(os.path.join(out, name + ".brep"))
    gmsh.finalize()


def sphere(o): o.addSphere(0, 0, 0, 1)
def cone_apex(o): o.addCone(0, 0, 0, 0, 0, 2, 1, 0)
def torus(o): o.addTorus(0, 0, 0, 2, 0.5)
def thin_torus(o): o.addTorus(0, 0, 0, 3, 0.08)
def ellipsoid(o):
    s = o.addSphere(0, 0, 0, 1); o.dilate([(3, s)], 0, 0, 0, 2.5, 1, 0.4)
def filleted_box(o):
    b = o.addBox(0, 0, 0, 3, 2, 1); o.synchronize()
    o.fillet([b], [e[1] for e in gmsh.model.getEntities(1)], [0.3])
def box_minus_cylinder(o):
    b = o.addBox(-2, -2, 0, 4, 4, 1); c = o.addCylinder(0, 0, -1, 0, 0, 3, 0.7)
    o.cut([(3, b)], [(3, c)])
def cylinder_on_box(o):
    b = o.addBox(-2, -2, 0, 4, 4, 1); c = o.addCylinder(0.5, 0, 1, 0, 0, 2, 0.4)
    o.fuse([(3, b)], [(3, c)])
def sphere_cut_by_box(o):
    s = o.addSphere(0, 0, 0, 1); b = o.addBox(-2, -2, 0.6, 4, 4, 4)
    o.cut([(3, s)], [(3, b)])
def pipe_elbow(o):
    t = o.addTorus(0, 0, 0, 2, 0.4, angle=3.14159265 / 2)
def wedge_cone(o):
    o.addCone(0, 0, 0, 0, 0, 3, 1.5, 0.2, angle=4.0)
def spheres_fused(o):
    a = o.addSphere(0, 0, 0, 1); b = o.addSphere(1.2, 0, 0, 0.8)
    o.fuse([(3, a)], [(3, b)])


for f in [sphere, cone_apex, torus, thin_torus, ellipsoid, filleted_box, box_minus_cylinder, cylinder_on_box,
          sphere_cut_by_box, pipe_elbow, wedge_cone, spheres_fused]:
    try:
        model(f.__name__, f)
        print(f.__name__, "ok")
    except Exception as e:
        print(f.__name__, "failed:", e)
