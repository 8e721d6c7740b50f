# SPDX-License-Identifier: GPL-3.0-or-later
"""Builds resources/examples/toothbrush.FCStd: a manual toothbrush with tagged faces.

Run in FreeCAD's GUI (so the document keeps its view: colours, visibility, camera),
with the HaptiCAD workbench installed, e.g. from the build tree:
    XDG_DATA_HOME=build/test-home/data xvfb-run -a freecad \
        resources/examples/make_toothbrush.py
Dimensions in mm; x runs along the brush, z is up (bristles on +z of the head).
"""
import os

import FreeCAD as App
import FreeCADGui as Gui
import Part

import HaptiCAD

V = App.Vector
OUT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "toothbrush.FCStd")


def rounded_box(length, width, height, origin, radius):
    box = Part.makeBox(length, width, height, origin)
    vertical = [e for e in box.Edges if abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) > 1e-6]
    return box.makeFillet(radius, vertical)


def face_at(shape, point, normal):
    """The planar face of `shape` through `point` with outward `normal`."""
    for i, face in enumerate(shape.Faces):
        if face.Surface.__class__.__name__ != "Plane":
            continue
        u, v = face.Surface.parameter(point)
        if face.normalAt(u, v).getAngle(normal) < 1e-6 and face.isInside(point, 1e-6, True):
            return f"Face{i + 1}"
    raise RuntimeError(f"no face through {point} facing {normal}")


def build():
    handle = rounded_box(115, 18, 12, V(0, -9, 0), 6)
    grip = rounded_box(46, 12, 1.5, V(22, -6, 12), 4)  # soft-touch thumb pad on top
    neck = Part.makeBox(42, 7, 6, V(110, -3.5, 4))
    # the head sits 1 mm lower than the neck, as on most brushes (and so its faces
    # stay separate from the neck's)
    head = rounded_box(30, 12, 6, V(150, -6, 3), 3)
    shape = handle.fuse([grip, neck, head]).removeSplitter()

    doc = App.newDocument("Toothbrush")
    body = doc.addObject("Part::Feature", "Toothbrush")
    body.Shape = shape
    body.ViewObject.ShapeColor = (0.36, 0.62, 0.85)  # a blue handle
    doc.recompute()

    up, down = V(0, 0, 1), V(0, 0, -1)
    HaptiCAD.make_surface(doc, [(body, face_at(shape, V(45, 0, 13.5), up))],
                          material="TPE soft-touch", roughness_category=4, name="ThumbGrip")
    HaptiCAD.make_surface(doc, [(body, face_at(shape, V(8, 0, 12), up)),
                                (body, face_at(shape, V(60, 0, 0), down))],
                          material="PP", roughness_category=2, name="Handle")
    HaptiCAD.make_surface(doc, [(body, face_at(shape, V(130, 0, 10), up))],
                          material="PP", roughness_category=1, name="Neck")
    HaptiCAD.make_surface(doc, [(body, face_at(shape, V(165, 0, 3), down))],
                          material="Rubber", roughness_category=6, name="TongueCleaner")
    doc.recompute()
    view = Gui.getDocument(doc.Name).ActiveView
    view.viewIsometric()
    view.fitAll()
    doc.saveAs(OUT)
    App.closeDocument(doc.Name)
    print(f"wrote {OUT}")


try:
    build()
finally:
    os._exit(0)
