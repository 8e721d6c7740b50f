# SPDX-License-Identifier: GPL-3.0-or-later
"""Real FreeCAD tessellations for `hapticad bench-mesh`: the example toothbrush and a
filleted block with a bore and a knob (fillets, cylinders and flats: triangles of every
size and shape, slivers included), written as STL into $HAPTICAD_CAD_MESHES (default
/tmp/hapticad-cad-meshes); and a soap bar (a box with every edge filleted: convex),
written as OFF with every digit, as the workbench hands the core its tessellations (an
STL's floats put the vertices of a flat face a rounding step off its plane, and then
no face is flat and the part no longer counts as convex).

    freecadcmd benchmarks/core/rendering/make_cad_meshes.py
"""
import os

import FreeCAD
import MeshPart
import Part

HERE = os.path.dirname(os.path.abspath(__file__)) if "__file__" in globals() else os.getcwd()
OUT = os.environ.get("HAPTICAD_CAD_MESHES", "/tmp/hapticad-cad-meshes")
TOOTHBRUSH = os.path.join(HERE, "..", "..", "..", "resources", "examples", "toothbrush.FCStd")


def write(shape, name, linear_mm, angular_rad):
    mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=linear_mm,
                                  AngularDeflection=angular_rad, Relative=False)
    path = os.path.join(OUT, name + ".stl")
    mesh.write(path)
    print(f"{path}: {mesh.CountFacets} triangles")


os.makedirs(OUT, exist_ok=True)
doc = FreeCAD.openDocument(os.path.normpath(TOOTHBRUSH))
solids = [o.Shape for o in doc.Objects if hasattr(o, "Shape") and o.Shape.Solids]
write(Part.makeCompound(solids), "toothbrush_fine", 0.02, 0.1)  # the Fine preset
block = Part.makeBox(80, 50, 30)
block = block.makeFillet(4, block.Edges)
part = block.cut(Part.makeCylinder(8, 40, FreeCAD.Vector(40, 25, -5)))
part = part.fuse(Part.makeSphere(10, FreeCAD.Vector(20, 15, 30))).removeSplitter()
write(part, "block_fine", 0.02, 0.1)
write(part, "block_superfine", 0.002, 0.05)


def write_off(shape, name, linear_mm, angular_rad):
    mesh = MeshPart.meshFromShape(Shape=shape, LinearDeflection=linear_mm,
                                  AngularDeflection=angular_rad, Relative=False)
    points, facets = mesh.Topology
    path = os.path.join(OUT, name + ".off")
    with open(path, "w") as f:
        f.write(f"OFF\n{len(points)} {len(facets)} 0\n")
        for p in points:
            f.write(f"{p.x!r} {p.y!r} {p.z!r}\n")
        for a, b, c in facets:
            f.write(f"3 {a} {b} {c}\n")
    print(f"{path}: {len(facets)} triangles")


soap = Part.makeBox(90, 55, 30)
write_off(soap.makeFillet(12, soap.Edges), "soap_fine", 0.02, 0.1)
