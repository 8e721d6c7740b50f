# SPDX-License-Identifier: GPL-3.0-or-later
"""What the overlay draws, computed without the GUI: stripe coordinates constant along
the direction of lowest friction, colours, legend, broken faces left out. freecadcmd."""
import math
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad import overlay
from hapticad.surface_compile import face_frame


class OverlayGeometryTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("OverlayGeometry")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.box.Placement.Base = App.Vector(100, 0, 0)
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_linear_stripes_are_constant_along_the_low_friction_direction(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], pattern="Linear", pattern_angle_deg=30,
                                  AcrossFriction=2.0)
        (face,) = overlay.overlay_faces(s)
        self.assertEqual(face.name, "Box.Face6")
        self.assertTrue(np.allclose(face.points[:, 2], 20.0))
        self.assertGreaterEqual(face.points[:, 0].min(), 100.0 - 1e-9)  # global: placement applied
        top = self.box.Shape.getElement("Face6")
        _, e1, e2, _ = face_frame(top, 30.0)
        values, _ = overlay.stripe_coordinates(s, top, face.points)
        # a linear function of position whose gradient is e2: constant along e1
        gradient, *_ = np.linalg.lstsq(np.c_[face.points, np.ones(len(face.points))], values, rcond=None)
        self.assertAlmostEqual(abs(np.dot(gradient[:3], e1)), 0.0, places=9)
        self.assertAlmostEqual(abs(np.dot(gradient[:3], e2)), 1.0, places=9)
        # about ten stripe pairs over the face
        self.assertAlmostEqual(face.stripes.max() - face.stripes.min(), overlay.STRIPES_PER_FACE, places=6)
        # friction lower across: the stripes turn
        s.AcrossFriction = 0.5
        values, _ = overlay.stripe_coordinates(s, top, face.points)
        gradient, *_ = np.linalg.lstsq(np.c_[face.points, np.ones(len(face.points))], values, rcond=None)
        self.assertAlmostEqual(abs(np.dot(gradient[:3], e1)), 1.0, places=9)

    def test_linear_stripes_run_round_a_cylinder_as_they_are_felt(self):
        # angle 0 on a handle: rings round it, so the stripe coordinate is the length along
        # the axis wherever the point is round it; turned 45 degrees, helices: constant along
        # the line that winds round at 45 degrees (on the tangent plane they were ellipses)
        handle = self.doc.addObject("Part::Cylinder", "Handle")
        handle.Radius, handle.Height = 20, 80
        self.doc.recompute()
        face = handle.Shape.getElement("Face1")
        s = HaptiCAD.make_surface(self.doc, [(handle, "Face1")], pattern="Linear", AcrossFriction=2.0,
                                  FeelRoughness=False)
        angles = np.radians(np.arange(0, 360, 10.0))
        ring = np.c_[20 * np.cos(angles), 20 * np.sin(angles), np.full(len(angles), 30.0)]
        values, kind = overlay.stripe_coordinates(s, face, ring)
        self.assertEqual(kind, "length")
        np.testing.assert_allclose(values, values[0], atol=1e-9)  # one ring round the handle
        higher, _ = overlay.stripe_coordinates(s, face, ring + [0, 0, 5])
        np.testing.assert_allclose(np.abs(higher - values), 5.0, atol=1e-9)
        s.PatternAngle = 45
        self.doc.recompute()
        start = math.atan2(*reversed(face_frame(face, 45.0)[0][:2]))  # round from the face's centre
        turn = np.radians(np.arange(-150, 151, 10.0))
        along = 20 * turn  # as far along the axis as round it: the 45 degree helix
        # (which way it winds is the face's: try both, one must hold the coordinate)
        spreads = []
        for hand in (1, -1):
            helix = np.c_[20 * np.cos(start + turn), 20 * np.sin(start + turn), 40 + hand * along]
            values, _ = overlay.stripe_coordinates(s, face, helix)
            spreads.append(np.ptp(values))
        self.assertLess(min(spreads), 1e-6, spreads)
        self.assertGreater(max(spreads), 100.0, spreads)

    def test_circular_rings_are_distances_from_the_axis(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], pattern="Circular",
                                  pattern_center_mm=(120, 15, 20))
        (face,) = overlay.overlay_faces(s)
        self.assertGreater(len(face.points), 100)  # interior vertices, so rings interpolate
        values, kind = overlay.stripe_coordinates(s, self.box.Shape.getElement("Face6"), face.points)
        r = np.linalg.norm(face.points[:, :2] - [120, 15], axis=1)
        self.assertEqual(kind, "length")
        self.assertTrue(np.allclose(values, r))

    def test_no_pattern_no_stripes_and_colours_by_material_or_roughness(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Rubber", roughness_category=7)
        (face,) = overlay.overlay_faces(s, "Material")
        self.assertIsNone(face.stripes)
        self.assertEqual(face.colour, overlay.material_colour("Rubber"))
        self.assertNotEqual(overlay.material_colour("Rubber"), overlay.material_colour("Steel"))
        (face,) = overlay.overlay_faces(s, "Roughness")
        self.assertEqual(face.colour, overlay.ROUGHNESS_COLOURS[6])

    def test_friction_edited_off_the_material_shades_its_colour_and_says_so(self):
        # PP at mu_s 0.90 and PP as listed had one swatch: two feels, one colour
        listed = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="PP")
        grippy = HaptiCAD.make_surface(self.doc, [(self.box, "Face1")], material="PP")
        slick = HaptiCAD.make_surface(self.doc, [(self.box, "Face2")], material="PP")
        grippy.StaticFriction, grippy.DynamicFriction = 0.90, 0.80
        slick.DynamicFriction = 0.38  # a touch under the listed 0.40: still shaded visibly
        pp = overlay.material_colour("PP")
        self.assertEqual(overlay.surface_colour(listed, "Material"), pp)
        darker, lighter = overlay.surface_colour(grippy, "Material"), overlay.surface_colour(slick, "Material")
        self.assertLess(sum(darker), sum(pp) - 0.3)  # twice the listed mu_d: the full 45 % darker
        self.assertGreater(sum(lighter), sum(pp) + 0.1)
        rows = overlay.legend_entries([listed, grippy, slick], "Material")
        self.assertEqual(len({rgb for rgb, _ in rows}), 3)
        self.assertEqual([label.endswith("(edited: more friction than listed)") for _, label in rows],
                         [False, True, False])
        self.assertIn("(edited: less friction than listed)", rows[2][1])
        (face,) = overlay.overlay_faces(grippy, "Material")
        self.assertEqual(face.colour, darker)  # the faces are drawn as the legend says
        # no friction at all: the palest, and said (it had the listed swatch, unmarked)
        slick.StaticFriction = slick.DynamicFriction = 0.0
        self.assertEqual(overlay.friction_shade(slick), -1.0)
        self.assertTrue(overlay.legend_entries([slick], "Material")[0][1].endswith(
            "(edited: less friction than listed)"))
        # a material missing from the database is not a grey beside the table's own grey
        self.assertNotEqual(overlay.material_colour("Birch ply"), (0.6, 0.6, 0.6))
        self.assertGreater(max(overlay.material_colour("Birch ply")) - min(overlay.material_colour("Birch ply")), 0.2)

    def test_legend_has_one_entry_per_colour_and_the_stripe_key(self):
        a = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel", pattern="Linear")
        b = HaptiCAD.make_surface(self.doc, [(self.box, "Face1")], material="Steel")
        c = HaptiCAD.make_surface(self.doc, [(self.box, "Face2")], material="ABS", roughness_category=5)
        rows = overlay.legend_entries([a, b, c], "Material")
        self.assertEqual([label.split(":")[0] for _, label in rows], ["Steel", "ABS", "Stripes"])
        self.assertIsNone(rows[-1][0])
        rows = overlay.legend_entries([a, b, c], "Roughness")
        self.assertEqual(rows[0][1], overlay.roughness_label(3))
        self.assertIn("Ra", rows[0][1])
        self.assertTrue(all(label.isascii() for _, label in rows))
        # a Curve pattern whose sketch is deleted draws no stripes: the key goes with them
        import Part

        guide = self.doc.addObject("Sketcher::SketchObject", "Guide")
        guide.addGeometry(Part.LineSegment(App.Vector(0, 0, 0), App.Vector(10, 0, 0)))
        a.Pattern, a.PatternCurve = "Curve", (guide, [])
        self.doc.recompute()
        self.assertEqual(overlay.legend_entries([a, b], "Material")[-1][1], "Stripes: direction of lowest friction")
        self.doc.removeObject(guide.Name)
        self.doc.recompute()
        self.assertEqual([label.split(":")[0] for _, label in overlay.legend_entries([a, b], "Material")], ["Steel"])
        self.assertIsNone(overlay.overlay_faces(a)[0].stripes)

    def test_faces_of_a_hidden_part_are_not_drawn_nor_in_the_legend(self):
        lid = self.doc.addObject("Part::Box", "Lid")
        assembly = self.doc.addObject("App::Part", "Assembly")
        assembly.addObject(lid)
        self.doc.recompute()
        a = HaptiCAD.make_surface(self.doc, [(self.box, "Face6"), (lid, "Face6")], material="Steel")
        b = HaptiCAD.make_surface(self.doc, [(lid, "Face1")], material="ABS", pattern="Linear")
        self.doc.recompute()
        self.assertEqual(len(overlay.overlay_faces(a)), 2)
        self.assertEqual([label.split(":")[0] for _, label in overlay.legend_entries([a, b], "Material")],
                         ["Steel", "ABS", "Stripes"])
        # the App::Part hidden: its child keeps Visibility on but is not drawn
        assembly.Visibility = False
        self.assertTrue(lid.Visibility)
        self.assertEqual([f.name for f in overlay.overlay_faces(a)], ["Box.Face6"])
        self.assertEqual(overlay.overlay_faces(b), [])
        self.assertEqual([label.split(":")[0] for _, label in overlay.legend_entries([a, b], "Material")],
                         ["Steel"])
        self.box.Visibility = False
        self.assertEqual(overlay.legend_entries([a, b], "Material"), [])
        self.box.Visibility = assembly.Visibility = True
        self.assertEqual(len(overlay.legend_entries([a, b], "Roughness")), 2)  # one category and the stripes

    def _bore_tagged_in_a_cut(self):
        """(the Cut of a hole through the box, its bore's face names, a surface tagging the
        first bore face and Face1)."""
        hole = self.doc.addObject("Part::Cylinder", "Hole")
        hole.Placement.Base = App.Vector(110, 10, -5)
        hole.Height = 30
        cut = self.doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = self.box, hole
        self.doc.recompute()
        bore = [f"Face{i + 1}" for i, f in enumerate(cut.Shape.Faces) if type(f.Surface).__name__ == "Cylinder"]
        s = HaptiCAD.make_surface(self.doc, [(cut, bore[0]), (cut, "Face1")])
        self.doc.recompute()
        return cut, bore, s

    def test_broken_references_are_not_drawn(self):
        cut, bore, s = self._bore_tagged_in_a_cut()
        self.assertEqual(len(overlay.overlay_faces(s)), 2)
        cut.Tool = self.doc.addObject("Part::Sphere", "Ball")
        self.doc.recompute()
        self.assertEqual([st for _, _, st in HaptiCAD.reference_status(s)][0], "broken")
        self.assertEqual([f.name for f in overlay.overlay_faces(s)], [f"Cut.{HaptiCAD.reference_status(s)[1][1]}"])

    def test_a_face_gone_before_the_surface_recomputes_is_left_out_without_a_warning(self):
        # the part's recompute redraws the overlay before the surface has matched its
        # faces again: "HapticSurface: cannot draw Cut.Face7: Index out of bound" came
        # before the surface's own "reference ... is broken"
        cut, bore, s = self._bore_tagged_in_a_cut()
        self.assertGreater(int(bore[0][4:]), 6)  # a number the plain box has not
        warnings = []
        original = App.Console.PrintWarning
        App.Console.PrintWarning = warnings.append
        try:
            cut.Tool.Placement.Base = App.Vector(300, 10, -5)  # the hole leaves the part
            cut.Tool.recompute()
            cut.recompute()  # the part only: the surface has not followed yet
            self.assertEqual([f.name for f in overlay.overlay_faces(s)], ["Cut.Face1"])
        finally:
            App.Console.PrintWarning = original
        self.assertEqual(warnings, [])


if __name__ == "__main__":
    unittest.main()
