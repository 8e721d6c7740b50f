# SPDX-License-Identifier: GPL-3.0-or-later
"""An assembly shown through every kind of link, for the GUI tests that click faces on
it (test_workbench_gui, test_task_panel). Seen from the top, each face clicked is a top
at z = 10 mm (the plate's at 4 mm)."""
import os
import tempfile

import FreeCAD as App
import FreeCADGui as Gui
import Part
import Sketcher

import gui_helpers as h


def body_box(doc, name, length, width, height):
    """A PartDesign Body padded from a rectangle at the origin."""
    body = doc.addObject("PartDesign::Body", name)
    sketch = body.newObject("Sketcher::SketchObject", "Sketch")
    sketch.Support = (body.Origin.OriginFeatures[3], [""])
    sketch.MapMode = "FlatFace"
    corners = [App.Vector(0, 0, 0), App.Vector(length, 0, 0), App.Vector(length, width, 0), App.Vector(0, width, 0)]
    for i in range(4):
        sketch.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
    for i in range(4):
        sketch.addConstraint(Sketcher.Constraint("Coincident", i, 2, (i + 1) % 4, 1))
    pad = body.newObject("PartDesign::Pad", "Pad")
    pad.Profile = sketch
    pad.Length = height
    doc.recompute()
    sketch.ViewObject.Visibility = False
    return body


class LinkedAssembly:
    """Two saved documents: "Knob" (its Body "Body", 10 x 10 x 6 mm) and "Assembly", the
    active one, with its own plate Body, also "Body" (80 x 40 x 4 mm), and:

    - KnobLink, an App::Link to the knob's Body, placed at (50, 15, 4);
    - BoxLink, an App::Link to the box Src, 20 mm right of it;
    - PartLink, an App::Link to the App::Part Holder (a cylinder Dial in it), 30 mm right;
    - Array, a Draft ortho array of ArrBase made with links, three along x every 20 mm;
    - LinkArr, an App::Link array of Src, its second element 20 mm right of the first.

    ``clicks``: (what is clicked, the 3D point on it, the words its refusal has)."""

    def __init__(self):
        import Draft

        self.folder = tempfile.TemporaryDirectory()
        self.knob_doc = App.newDocument("Knob")
        self.knob = body_box(self.knob_doc, "Body", 10, 10, 6)
        self.knob_doc.saveAs(os.path.join(self.folder.name, "knob.FCStd"))
        self.doc = App.newDocument("Assembly")
        self.doc.saveAs(os.path.join(self.folder.name, "assembly.FCStd"))
        doc = self.doc
        self.plate = body_box(doc, "Body", 80, 40, 4)
        knob_link = doc.addObject("App::Link", "KnobLink")
        knob_link.LinkedObject = self.knob
        knob_link.Placement.Base = App.Vector(50, 15, 4)
        src = doc.addObject("Part::Box", "Src")
        src.Placement.Base = App.Vector(0, 60, 0)
        box_link = doc.addObject("App::Link", "BoxLink")
        box_link.LinkedObject = src
        box_link.Placement.Base = App.Vector(20, 60, 0)
        holder = doc.addObject("App::Part", "Holder")
        dial = doc.addObject("Part::Cylinder", "Dial")
        dial.Radius = 3
        holder.addObject(dial)
        holder.Placement.Base = App.Vector(3, 100, 0)
        part_link = doc.addObject("App::Link", "PartLink")
        part_link.LinkedObject = holder
        part_link.Placement.Base = App.Vector(33, 100, 0)
        base = doc.addObject("Part::Box", "ArrBase")
        base.Placement.Base = App.Vector(0, 130, 0)
        doc.recompute()
        array = Draft.make_ortho_array(base, App.Vector(20, 0, 0), App.Vector(0, 20, 0), App.Vector(0, 0, 20),
                                       3, 1, 1, use_link=True)
        link_array = doc.addObject("App::Link", "LinkArr")
        link_array.LinkedObject = src
        link_array.ElementCount = 2
        link_array.Placement.Base = App.Vector(0, 160, 0)
        doc.recompute()
        link_array.ElementList[1].Placement.Base = App.Vector(20, 0, 0)
        doc.recompute()
        self.clicks = [
            ("the knob through KnobLink", (55, 20, 10), "KnobLink is a link to Body in knob.FCStd"),
            ("BoxLink", (25, 65, 10), "BoxLink is a link to Src"),
            ("the dial through PartLink", (33, 100, 10), "PartLink is a link to Holder"),
            ("the third element of the Draft link array", (45, 135, 10),
             f"{array.Label} is an array made with links to ArrBase"),
            ("the second element of LinkArr", (25, 165, 10), "LinkArr is a link array of Src"),
        ]
        App.setActiveDocument(doc.Name)
        Gui.ActiveDocument = Gui.getDocument(doc.Name)
        view = Gui.ActiveDocument.ActiveView
        view.viewTop()
        view.fitAll()
        h.process_events()

    def surfaces(self):
        from hapticad.surface_object import surfaces_of

        return surfaces_of(self.doc) + surfaces_of(self.knob_doc)

    def close(self):
        for doc in (self.doc, self.knob_doc):
            App.closeDocument(doc.Name)
        self.folder.cleanup()
