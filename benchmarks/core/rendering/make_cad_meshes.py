# SPDX-License-Identifier: GPL-3.0-or-later
"""Real FreeCAD tessellations for `hapticad bench-mesh`: the example toothbrush and a
filleted block with a bore and a knob (fillets, cylinders and flats: triangles of every
size and shape, slivers included), written as STL into $HAPTICAD_CAD_MESHES (default
/tmp/hapticad-cad-meshes).

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
