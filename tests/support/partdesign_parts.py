# SPDX-License-Identifier: GPL-3.0-or-later
"""A PartDesign Body for tests of documents read outside FreeCAD's GUI: a 30 x 20 mm
rectangle padded 10 mm (its top face at z = 10), the Body's top face tagged."""


def make_padded_body(App, HaptiCAD, doc, name="Body"):
    """Adds the Body and a HapticSurface on its top face to ``doc``; returns (body, surface)."""
    import Part
    import Sketcher  # noqa: F401  (registers Sketcher::SketchObject)

    body = doc.addObject("PartDesign::Body", name)
    sketch = body.newObject("Sketcher::SketchObject", f"{name}Sketch")
    corners = [App.Vector(0, 0, 0), App.Vector(30, 0, 0), App.Vector(30, 20, 0), App.Vector(0, 20, 0)]
    for a, b in zip(corners, corners[1:] + corners[:1]):
        sketch.addGeometry(Part.LineSegment(a, b))
    pad = body.newObject("PartDesign::Pad", f"{name}Pad")
    pad.Profile = sketch
    pad.Length = 10
    doc.recompute()
    top = next(f"Face{i + 1}" for i, face in enumerate(body.Shape.Faces)
               if abs(face.CenterOfMass.z - 10) < 1e-6 and abs(face.normalAt(0, 0).z - 1) < 1e-9)
    surface = HaptiCAD.make_surface(doc, [(body, top)], material="ABS", FeelRoughness=False, TextureFullRange=2.0)
    doc.recompute()
    return body, surface
