# SPDX-License-Identifier: GPL-3.0-or-later
"""A Curve pattern's named edges survive sketch edits, or say they broke: never a silent
move onto another curve, never a traceback that locks the surface. Run by freecadcmd."""
import json
import os
import tempfile
import unittest

import numpy as np

import FreeCAD as App
import Part

import HaptiCAD
from hapticad import curve_references
from hapticad.surface_compile import compile_surface
from hapticad.surface_object import validate

V = App.Vector


class SketchEditsTest(unittest.TestCase):
    """A sketch holding two splines, one running along x and one along y."""

    def setUp(self):
        self.doc = App.newDocument("CurveEdits")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 60, 40, 10
        self.sketch = self.doc.addObject("Sketcher::SketchObject", "Sketch")
        self.sketch.Placement = App.Placement(V(0, 0, 10), App.Rotation())
        self.along_x = Part.BSplineCurve([V(5, 5, 0), V(20, 8, 0), V(40, 4, 0), V(55, 6, 0)])
        self.along_y = Part.BSplineCurve([V(30, 2, 0), V(33, 15, 0), V(28, 25, 0), V(31, 38, 0)])
        self.sketch.addGeometry(self.along_x, False)
        self.sketch.addGeometry(self.along_y, False)
        self.doc.recompute()
        self.surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", Pattern="Curve")

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def pick(self, edge):
        self.surface.PatternCurve = (self.sketch, [edge])
        self.doc.recompute()

    def stripe_at_centre(self):
        frame = compile_surface(self.surface, self.box.Shape.Faces[5]).pattern.evaluate([0.03, 0.02, 0.01],
                                                                                         [0, 0, 1])
        return np.abs(frame.stripe)

    def state(self):
        return curve_references.status(curve_references.loads(self.surface.PatternCurveState))

    def test_deleting_the_picked_spline_breaks_the_pattern_instead_of_moving_it_to_the_other(self):
        self.pick("Edge1")
        self.assertGreater(self.stripe_at_centre()[0], 0.9)  # along x
        self.sketch.delGeometry(0)  # the x spline goes; "Edge1" now names the y spline
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "broken")])
        problems = validate(self.surface)
        self.assertTrue(any("Sketch.Edge1" in p and "pick the curve again" in p for p in problems), problems)
        with self.assertRaisesRegex(ValueError, "pick the curve again"):
            compile_surface(self.surface, self.box.Shape.Faces[5])
        # undoing the edit (the spline back as the first edge) brings it back
        self.sketch.Geometry = [self.along_x, self.along_y]
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "ok")])
        self.assertGreater(self.stripe_at_centre()[0], 0.9)

    def test_a_renumbered_spline_is_followed(self):
        self.pick("Edge2")
        self.assertGreater(self.stripe_at_centre()[1], 0.9)  # along y
        self.sketch.delGeometry(0)
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "rematched")])
        self.assertEqual(list(self.surface.PatternCurve[1]), ["Edge1"])
        self.assertEqual(validate(self.surface), [])
        self.assertGreater(self.stripe_at_centre()[1], 0.9)

    def test_the_picked_spline_deleted_as_the_other_is_nudged_breaks_the_pattern(self):
        # one Sketcher session: "Edge1" now names the other spline, changed too; it was
        # taken for the picked one, reshaped
        self.pick("Edge1")
        nudged = Part.BSplineCurve([V(30, 2, 0), V(34, 15, 0), V(28, 25, 0), V(31, 38, 0)])
        self.sketch.Geometry = [nudged]
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "broken")])

    def test_a_reshaped_spline_keeps_the_pattern(self):
        self.pick("Edge1")
        reshaped = Part.BSplineCurve([V(5, 5, 0), V(20, 12, 0), V(40, 0, 0), V(55, 6, 0)])
        self.sketch.Geometry = [reshaped, self.along_y]
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "ok")])
        self.assertEqual(validate(self.surface), [])
        # the signature follows the new shape: deleting the other spline now changes nothing
        self.sketch.delGeometry(1)
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "ok")])

    def test_an_edge_that_is_gone_is_a_clear_problem_not_a_traceback(self):
        self.pick("Edge2")
        self.sketch.delGeometry(1)
        self.doc.recompute()  # would raise Part.OCCError ("Index out of bound") from execute
        self.assertEqual(self.state(), [("Edge2", "broken")])
        self.assertTrue(any("pick the curve again" in p for p in validate(self.surface)))
        # without the signed state, compiling still names the missing edge
        self.surface.PatternCurveState = ""
        with self.assertRaisesRegex(ValueError, r"Sketch\.Edge2, which Sketch no longer has \(it has 1 edges\)"):
            compile_surface(self.surface, self.box.Shape.Faces[5])

    def test_a_broken_edge_is_not_revived_by_a_new_curve_in_its_place(self):
        self.pick("Edge2")
        self.sketch.delGeometry(1)
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge2", "broken")])
        # a new spline drawn later takes the name Edge2: it is not the curve picked
        self.sketch.addGeometry(Part.BSplineCurve([V(40, 2, 0), V(43, 15, 0), V(38, 25, 0), V(41, 38, 0)]), False)
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge2", "broken")])
        # the picked spline itself back (an undo): followed again
        self.sketch.Geometry = [self.along_x, self.along_y]
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge2", "ok")])

    def test_a_document_written_without_curve_state_signs_it_when_it_opens(self):
        self.pick("Edge1")
        self.surface.PatternCurveState = ""
        name = self.surface.Name
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "curves.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
        self.surface = self.doc.getObject(name)
        self.sketch = self.doc.getObject("Sketch")
        self.box = self.doc.getObject("Box")
        self.assertEqual(self.state(), [("Edge1", "ok")])
        self.assertEqual(len(json.loads(self.surface.PatternCurveState)["others"]), 1)
        self.sketch.delGeometry(0)
        self.doc.recompute()
        self.assertEqual(self.state(), [("Edge1", "broken")])

    def test_a_whole_sketch_needs_no_state(self):
        self.surface.PatternCurve = (self.sketch, [])
        self.doc.recompute()
        self.assertEqual(self.surface.PatternCurveState, "")


if __name__ == "__main__":
    unittest.main()
