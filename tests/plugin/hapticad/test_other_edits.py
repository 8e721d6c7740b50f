# SPDX-License-Identifier: GPL-3.0-or-later
"""OtherEdits: what was done to a document outside a panel's own objects while it was
open, in real FreeCAD (freecadcmd)."""
import unittest

import FreeCAD as App

import HaptiCAD
from hapticad.other_edits import OtherEdits
from hapticad.vibration_object import is_haptic_vibration


class OtherEditsTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("OtherEdits")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.cyl = self.doc.addObject("Part::Cylinder", "Cylinder")
        self.doc.recompute()
        self.surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        self.doc.recompute()
        self.edits = OtherEdits(self.doc, lambda o: o == self.surface or is_haptic_vibration(o))
        self.addCleanup(self.edits.remove)

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_the_panels_own_objects_and_a_recompute_are_not_counted(self):
        self.surface.Material = "Rubber"
        self.surface.StaticFriction = 0.9
        vibration = HaptiCAD.make_vibration(self.doc, self.box)
        vibration.Frequency = 120.0
        self.doc.removeObject(vibration.Name)
        self.box.touch()
        self.doc.recompute()  # sets every part's Shape: follows what was set, not an edit
        self.box.Visibility = False  # FreeCAD keeps it out of undo
        self.assertFalse(self.edits.any())
        self.assertEqual(self.edits.describe(), "")

    def test_edits_to_other_objects_are_named_with_their_properties(self):
        self.box.Length = 25
        self.doc.recompute()
        self.box.Width = 12
        self.box.Length = 30  # said once
        self.cyl.Radius = 4
        self.box.Label = "Lid"
        self.assertTrue(self.edits.any())
        self.assertEqual(self.edits.describe(), "changed Lid (Length, Width, Label) and Cylinder (Radius)")

    def test_objects_added_and_deleted_are_named_once(self):
        sketch = self.doc.addObject("Sketcher::SketchObject", "Sketch")
        sketch.Label = "Outline"  # changes of an object added here are its adding
        self.doc.recompute()
        self.doc.removeObject(self.cyl.Name)
        scratch = self.doc.addObject("Part::Sphere", "Scratch")
        self.doc.removeObject(scratch.Name)  # added and deleted while open: nothing to lose
        self.assertEqual(self.edits.describe(), "added Outline; deleted Cylinder")

    def test_another_documents_edits_are_not_counted(self):
        other = App.newDocument("OtherEditsElsewhere")
        self.addCleanup(App.closeDocument, other.Name)
        box = other.addObject("Part::Box", "Box")
        box.Length = 3
        other.recompute()
        self.assertFalse(self.edits.any())
