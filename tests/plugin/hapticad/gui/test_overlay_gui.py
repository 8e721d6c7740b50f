# SPDX-License-Identifier: GPL-3.0-or-later
"""The overlay in FreeCAD's real GUI (Xvfb), checked in screenshots: tagged faces are
coloured by material or roughness, black and white stripes run along the direction of
lowest friction, the part keeps its own colours, one command hides it all, and a legend
explains it. Pixel checks sample the tagged face's region. Run by gui_test_runner.py."""
import os
import sys
import unittest

import numpy as np

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtGui, QtWidgets

import HaptiCAD
from hapticad import overlay, preferences
from hapticad.surface_compile import face_frame

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402

MM = 1e-3


def bands(flags, gap=3):
    """(first, last) index of each run of True, runs at most ``gap`` apart taken as one
    (a line of text and the underscores below it)."""
    found, start = [], None
    for i, flag in enumerate(list(flags) + [False]):
        if flag and start is None:
            start = i
        elif not flag and start is not None:
            if found and start - found[-1][1] <= gap + 1:
                start = found.pop()[0]
            found.append((start, i - 1))
            start = None
    return found


class OverlayTest(unittest.TestCase):
    def setUp(self):
        preferences.update(overlay_visible=True, overlay_colour_by="Material")
        self.doc = App.newDocument("OverlayTest")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.doc.recompute()
        self.part_colours = (tuple(self.box.ViewObject.ShapeColor), list(self.box.ViewObject.DiffuseColor))
        self.top = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel", pattern="Linear",
                                         AcrossFriction=1.5)
        self.side = HaptiCAD.make_surface(self.doc, [(self.box, "Face2")], material="Rubber")
        self.doc.recompute()
        h.show_workbench()

    def tearDown(self):
        preferences.update(overlay_visible=True, overlay_colour_by="Material")
        App.closeDocument(self.doc.Name)

    def stripe_axes(self):
        """Unit vectors on the top face along e1 (the pattern's direction) and e2, mm."""
        _, e1, e2, _ = face_frame(self.box.Shape.getElement("Face6"), float(self.top.PatternAngle))
        return np.asarray(e1), np.asarray(e2)

    def scan_top(self, image, direction):
        """Pixel classes along a 24 mm segment through the top face's centre."""
        centre = np.array([20.31, 15.37, 20.0])  # off the texel edges the centre lies on
        p0, p1 = centre - 12 * direction, centre + 12 * direction
        return h.scan(image, h.image_pos(p0, image), h.image_pos(p1, image))

    def test_stripes_run_along_the_lowest_friction_direction(self):
        _, image = h.save_view("overlay_linear.png")
        e1, e2 = self.stripe_axes()
        across, along = self.scan_top(image, e2), self.scan_top(image, e1)
        # across the stripes: many alternating black and white bands; along one: none
        self.assertGreaterEqual(h.runs(across), 8, across)
        self.assertIn("black", across)
        self.assertIn("white", across)
        self.assertLessEqual(h.runs(along), 2, along)
        # friction lower across the pattern's direction: the stripes turn by 90 degrees
        self.top.AcrossFriction = 0.5
        h.process_events()
        _, image = h.save_view("overlay_linear_turned.png")
        self.assertGreaterEqual(h.runs(self.scan_top(image, e1)), 8)
        self.assertLessEqual(h.runs(self.scan_top(image, e2)), 2)

    def test_colours_by_material_and_roughness_and_the_part_keeps_its_own(self):
        _, image = h.save_view("overlay_material.png")
        rubber = overlay.material_colour("Rubber")
        r, g, b = h.pixel(image, *h.image_pos((40, 15, 10), image))  # centre of the tagged side face
        self.assertEqual(np.argmax((r, g, b)), int(np.argmax(rubber)), (r, g, b))
        self.assertGreater(r - max(g, b), 60, (r, g, b))
        front = h.scan(image, h.image_pos((5, 0, 10), image), h.image_pos((35, 0, 10), image))
        self.assertEqual(h.runs(front), 0)  # the untagged front face: no stripes
        fr, fg, fb = h.pixel(image, *h.image_pos((20, 0, 10), image))
        self.assertLess(max(fr, fg, fb) - min(fr, fg, fb), 12, (fr, fg, fb))  # FreeCAD's own grey
        self.assertEqual((tuple(self.box.ViewObject.ShapeColor), list(self.box.ViewObject.DiffuseColor)),
                         self.part_colours)

        Gui.runCommand("HaptiCAD_OverlayByRoughness", 1)
        h.process_events()
        self.assertEqual(preferences.load().overlay_colour_by, "Roughness")
        _, image = h.save_view("overlay_roughness.png")
        expected = np.array(overlay.roughness_colour(self.side.RoughnessCategory)) * 255
        got = np.array(h.pixel(image, *h.image_pos((40, 15, 10), image)), dtype=float)
        # shading scales the colour: compare chromaticity
        self.assertLess(np.abs(got / got.sum() - expected / expected.sum()).max(), 0.06, (got, expected))

    def test_the_legend_forgets_a_surface_undone_or_cancelled(self):
        from hapticad.gui import overlay_legend

        h.process_events()
        before = overlay_legend.shown_labels(self.doc)
        self.assertEqual(len(before), 3, before)  # Steel, Rubber, the stripes
        self.doc.UndoMode = 1
        self.doc.openTransaction("Glass lid")
        HaptiCAD.make_surface(self.doc, [(self.box, "Face1")], material="Glass")
        self.doc.commitTransaction()
        self.doc.recompute()
        h.process_events()
        self.assertTrue(any("Glass" in label for label in overlay_legend.shown_labels(self.doc)))
        self.doc.undo()
        h.process_events()
        self.assertEqual(overlay_legend.shown_labels(self.doc), before)
        # a new surface's panel cancelled: gone from the legend with it
        Gui.Selection.addSelection(self.box, "Face3")
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        h.widget(QtWidgets.QComboBox, "Material").setCurrentText("Glass")
        h.process_events()
        self.assertTrue(any("Glass" in label for label in overlay_legend.shown_labels(self.doc)))
        h.press_task_button("Cancel")
        h.process_events()
        self.assertEqual(overlay_legend.shown_labels(self.doc), before)

    def test_each_swatch_sits_beside_its_own_label_at_any_view_size(self):
        # laid out in fractions of the view, each swatch sat a row below its own label in
        # a 400 pixel high view (the README's picture paired the grip's colour with PP)
        from hapticad.gui import overlay_legend as legend

        for size in (None, (640, 400), (1600, 1200)):
            path = os.path.join(h.SHOTS, f"overlay_legend_{size[1] if size else 'view'}.png")
            view = Gui.ActiveDocument.ActiveView
            width, height = size or view.getSize()
            view.saveImage(path, width, height, "White")
            image = QtGui.QImage(path)
            x = legend.LEFT_PX + legend.SWATCH_PX // 2
            text_x = range(legend.LEFT_PX + legend.SWATCH_PX + 6, 120)  # left of the part
            rows = range(0, legend.TOP_PX + 4 * legend.ROW_PX)
            swatch = [h.classify(h.pixel(image, x, y)) != "white" for y in rows]
            text = [any(h.classify(h.pixel(image, tx, y)) == "black" for tx in text_x) for y in rows]
            swatches, labels = bands(swatch), bands(text)
            self.assertEqual(len(swatches), len(legend.shown_labels(self.doc)), (size, swatches))
            self.assertEqual(len(labels), len(swatches), (size, labels))
            for (s0, s1), (t0, t1) in zip(swatches, labels):
                self.assertLessEqual(abs((s0 + s1) / 2 - (t0 + t1) / 2), 3, (size, swatches, labels))

    def test_one_command_hides_and_shows_overlay_and_legend(self):
        _, shown = h.save_view("overlay_shown.png")
        e1, e2 = self.stripe_axes()
        self.assertGreater(h.non_white_fraction(shown, 0.0, 0.0, 0.35, 0.12), 0.02)  # the legend
        Gui.runCommand("HaptiCAD_ToggleOverlay", 0)
        h.process_events()
        _, hidden = h.save_view("overlay_hidden.png")
        self.assertEqual(h.runs(self.scan_top(hidden, e2)), 0)
        self.assertLess(h.non_white_fraction(hidden, 0.0, 0.0, 0.35, 0.12), 0.002)
        action = Gui.Command.get("HaptiCAD_ToggleOverlay").getAction()[0]
        self.assertFalse(action.isChecked())
        Gui.runCommand("HaptiCAD_ToggleOverlay", 1)
        h.process_events()
        self.assertTrue(action.isChecked())
        # a change made elsewhere (the preferences page) shows in the check box too
        preferences.update(overlay_visible=False)
        from hapticad.gui.command_overlay import refresh_all

        refresh_all()
        self.assertFalse(action.isChecked())
        preferences.update(overlay_visible=True)
        refresh_all()
        _, again = h.save_view("overlay_shown_again.png")
        self.assertGreaterEqual(h.runs(self.scan_top(again, e2)), 8)

    def test_a_hidden_part_takes_its_overlay_and_legend_entries_with_it(self):
        from hapticad.gui import overlay_legend

        lid = self.doc.addObject("Part::Box", "Lid")
        lid.Placement.Base = App.Vector(60, 0, 0)
        self.doc.recompute()
        glass = HaptiCAD.make_surface(self.doc, [(lid, "Face6")], material="Glass")
        self.doc.recompute()
        h.process_events()
        self.assertTrue(any(label.startswith("Glass") for label in overlay_legend.shown_labels(self.doc)))
        self.assertEqual(glass.ViewObject.Proxy.overlay_face_count(), 1)
        Gui.getDocument(self.doc.Name).getObject("Lid").Visibility = False  # as the space bar does
        h.process_events()
        self.assertEqual(glass.ViewObject.Proxy.overlay_face_count(), 0)
        self.assertFalse(any(label.startswith("Glass") for label in overlay_legend.shown_labels(self.doc)))
        self.assertEqual(len(overlay_legend.shown_labels(self.doc)), 3)  # Steel, Rubber, the stripes
        # the box hidden too: nothing tagged in view, no legend
        self.box.ViewObject.Visibility = False
        h.process_events()
        self.assertEqual(overlay_legend.shown_labels(self.doc), [])
        _, image = h.save_view("overlay_parts_hidden.png")
        self.assertLess(h.non_white_fraction(image, 0.0, 0.0, 0.35, 0.12), 0.002)
        lid.ViewObject.Visibility = True
        h.process_events()
        self.assertEqual([label.split(":")[0] for label in overlay_legend.shown_labels(self.doc)], ["Glass"])
        self.assertEqual(glass.ViewObject.Proxy.overlay_face_count(), 1)

    def test_circular_pattern_draws_rings_and_clicks_still_reach_the_part(self):
        self.top.Pattern = "Circular"
        self.top.PatternCenter = App.Vector(20, 15, 20)
        h.process_events()
        path, image = h.save_view("overlay_circular.png")
        # from the centre outward in two directions: rings cross both
        for direction in ((1, 0, 0), (0, 1, 0)):
            p1 = np.array([20, 15, 20]) + 14 * np.array(direction)
            classes = h.scan(image, h.image_pos((20, 15, 20), image), h.image_pos(p1, image))
            self.assertGreaterEqual(h.runs(classes), 6, (direction, classes))
        # the overlay is unpickable: the part's face is what the view reports
        info = Gui.ActiveDocument.ActiveView.getObjectInfo(
            Gui.ActiveDocument.ActiveView.getPointOnScreen(App.Vector(20, 15, 20)))
        self.assertEqual((info["Object"], info["Component"]), ("Box", "Face6"))

    def test_curve_stripes_follow_an_edited_sketch(self):
        import Part

        sketch = self.doc.addObject("Sketcher::SketchObject", "Guide")
        sketch.Placement.Base = App.Vector(0, 0, 20)
        sketch.addGeometry(Part.LineSegment(App.Vector(20, 0, 0), App.Vector(20, 30, 0)))  # along y
        self.doc.recompute()
        self.top.Pattern = "Curve"
        self.top.PatternCurve = (sketch, [])
        self.doc.recompute()
        h.process_events()
        x, y = np.array([1.0, 0, 0]), np.array([0, 1.0, 0])
        _, image = h.save_view("overlay_curve.png")
        self.assertLessEqual(h.runs(self.scan_top(image, y)), 2)  # stripes along the line
        self.assertGreaterEqual(h.runs(self.scan_top(image, x)), 8)
        # the designer turns the line to run along x: the stripes turn with it (they
        # stayed as drawn until something else redrew them)
        sketch.movePoint(0, 1, App.Vector(5, 15, 0))
        sketch.movePoint(0, 2, App.Vector(35, 15, 0))
        self.doc.recompute()
        h.process_events()
        _, image = h.save_view("overlay_curve_edited.png")
        self.assertLessEqual(h.runs(self.scan_top(image, x)), 2)
        self.assertGreaterEqual(h.runs(self.scan_top(image, y)), 8)
        # the sketch deleted: no stripes, and the legend no longer explains them
        from hapticad.gui import overlay_legend

        self.assertIn("Stripes: direction of lowest friction", overlay_legend.shown_labels(self.doc))
        self.doc.removeObject(sketch.Name)
        self.doc.recompute()
        h.process_events()
        _, image = h.save_view("overlay_curve_deleted.png")
        self.assertEqual(h.runs(self.scan_top(image, y)), 0)
        self.assertNotIn("Stripes: direction of lowest friction", overlay_legend.shown_labels(self.doc))

    def test_the_overlay_follows_a_moved_part_and_a_moved_app_part(self):
        def top_points():
            node = self.top.ViewObject.Proxy._faces.getChild(0)
            coords = [node.getChild(i) for i in range(node.getNumChildren())
                      if node.getChild(i).getTypeId().getName().getString() == "Coordinate3"][0]
            return np.array([tuple(p.getValue()) for p in coords.point.getValues()])

        self.assertAlmostEqual(top_points()[:, 2].max(), 20.0, places=6)
        self.box.Placement.Base = App.Vector(0, 0, 7)
        self.doc.recompute()
        self.assertAlmostEqual(top_points()[:, 2].max(), 27.0, places=6)
        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(self.box)
        container.Placement.Base = App.Vector(0, 0, 100)
        self.doc.recompute()
        self.assertAlmostEqual(top_points()[:, 2].max(), 127.0, places=6)

    def test_the_overlay_comes_back_after_reopening(self):
        import tempfile

        self.top.PatternAngle = 45
        before = {s.Name: (s.Material, float(s.PatternAngle), s.ReferenceState) for s in HaptiCAD.surfaces_of(self.doc)}
        top_name = self.top.Name
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "overlay.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            h.process_events()
            after = {s.Name: (s.Material, float(s.PatternAngle), s.ReferenceState)
                     for s in HaptiCAD.surfaces_of(self.doc)}
            self.assertEqual(after, before)
            for surface in HaptiCAD.surfaces_of(self.doc):
                self.assertEqual(surface.ViewObject.Proxy.overlay_face_count(), 1)
                self.assertNotIn("Touched", surface.State)
            view = Gui.ActiveDocument.ActiveView
            view.viewIsometric()
            view.fitAll()
            _, image = h.save_view("overlay_reopened.png")
            self.top = self.doc.getObject(top_name)
            self.box = self.doc.getObject("Box")
            _, e2 = self.stripe_axes()
            self.assertGreaterEqual(h.runs(self.scan_top(image, e2)), 8)
            self.assertGreater(h.non_white_fraction(image, 0.0, 0.0, 0.35, 0.12), 0.02)

    def test_documentation_screenshot(self):
        """The README's overlay picture: several materials, a linear and a circular pattern."""
        cyl = self.doc.addObject("Part::Cylinder", "Knob")
        cyl.Radius, cyl.Height = 9, 8
        cyl.Placement.Base = App.Vector(20, 15, 20)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(cyl, "Face3")], material="TPE soft-touch", pattern="Circular",
                              pattern_center_mm=(20, 15, 28), roughness_category=5)
        HaptiCAD.make_surface(self.doc, [(self.box, "Face3")], material="Aluminium", roughness_category=2)
        self.top.PatternAngle = 30
        self.doc.recompute()
        view = Gui.ActiveDocument.ActiveView
        view.viewIsometric()
        view.fitAll()
        h.process_events()
        path, image = h.save_view("overlay_stripes.png", "Current")
        self.assertGreater(h.non_white_fraction(image), 0.5)


if __name__ == "__main__":
    unittest.main()
