# SPDX-License-Identifier: GPL-3.0-or-later
"""HapticSurface objects: creation through the API, validation, save and reopen.
Run by freecadcmd (see tests/plugin/CMakeLists.txt)."""
import os
import tempfile
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad import _core, materials, surface_object


class MakeSurfaceTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("MakeSurfaceTest")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_creates_a_surface_with_the_materials_values(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", roughness_category=3)
        abs_ = materials.default_database().get("ABS")
        self.assertTrue(HaptiCAD.is_haptic_surface(s))
        self.assertEqual(HaptiCAD.reference_pairs(s), [(self.box, "Face6")])
        self.assertEqual(s.References[0][0], self.box)
        self.assertEqual(s.Material, "ABS")
        self.assertEqual(s.RoughnessCategory, 3)
        self.assertEqual(s.Pattern, "None")
        self.assertAlmostEqual(s.StaticFriction, abs_.static_friction)
        self.assertAlmostEqual(s.DynamicFriction, abs_.dynamic_friction)
        self.assertAlmostEqual(s.Stiffness, abs_.stiffness_n_per_mm)
        self.assertEqual(s.TypeId, "App::FeaturePython")
        self.assertIn("PropertyLinkSubListGlobal", s.getTypeIdOfProperty("References"))
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [s])

    def test_groups_faces_of_one_object_and_accepts_names(self):
        s = HaptiCAD.make_surface(self.doc, [("Box", "Face1"), (self.box, "Face2"), (self.box, "Face1")])
        self.assertEqual(s.References, [(self.box, ("Face1", "Face2"))])

    def test_link_sub_list_groups_by_object_in_first_seen_order_each_face_once(self):
        from hapticad.surface_object import link_sub_list

        other = self.doc.addObject("Part::Cylinder", "Other")
        pairs = [(self.box, "Face3"), (other, "Face1"), (self.box, "Face1"), (self.box, "Face3"), (other, "Face2")]
        self.assertEqual(link_sub_list(pairs), [(self.box, ("Face3", "Face1")), (other, ("Face1", "Face2"))])
        self.assertEqual(link_sub_list(iter([])), [])

    def test_overrides_take_precedence_over_the_material(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel",
                                  static_friction=0.9, dynamic_friction=0.7, stiffness_n_per_mm=0.25)
        self.assertEqual((s.StaticFriction, s.DynamicFriction, s.Stiffness), (0.9, 0.7, 0.25))

    def test_choosing_another_material_sets_its_values(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel")
        s.Material = "Rubber"
        rubber = materials.default_database().get("Rubber")
        self.assertEqual((s.StaticFriction, s.DynamicFriction), (rubber.static_friction, rubber.dynamic_friction))

    def test_undo_and_redo_bring_back_every_value_as_it_was(self):
        from hapticad import textures

        self.doc.UndoMode = 1
        self.doc.openTransaction("tag")
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        self.doc.commitTransaction()
        self.doc.openTransaction("override")
        s.StaticFriction = 0.93
        self.doc.commitTransaction()
        self.doc.openTransaction("material")
        s.Material = "PP"
        self.doc.commitTransaction()
        pp = materials.default_database().get("PP").static_friction
        self.assertEqual(s.StaticFriction, pp)
        self.doc.undo()  # re-applied ABS's database values over the restored override
        self.assertEqual((s.Material, s.StaticFriction), ("ABS", 0.93))
        self.doc.redo()
        self.assertEqual((s.Material, s.StaticFriction), ("PP", pp))
        preset = list(textures.PRESETS)[0]
        self.doc.openTransaction("texture")
        s.Texture = preset
        self.doc.commitTransaction()
        self.doc.openTransaction("texture edit")
        s.TextureBeta = 0.3
        self.doc.commitTransaction()
        self.assertEqual(s.Texture, "Custom")
        self.doc.undo()
        self.assertEqual((s.Texture, s.TextureBeta), (preset, textures.PRESETS[preset][2]))
        self.doc.redo()
        self.assertEqual((s.Texture, s.TextureBeta), ("Custom", 0.3))

    def test_constraints_keep_values_in_range(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        s.RoughnessCategory = 9
        self.assertEqual(s.RoughnessCategory, 7)
        s.RoughnessCategory = 0
        self.assertEqual(s.RoughnessCategory, 1)
        s.DynamicFriction = -1.0
        self.assertEqual(s.DynamicFriction, 0.0)
        s.Stiffness = 0.0
        self.assertGreater(s.Stiffness, 0.0)

    def test_bad_input_raises_a_clear_error_and_adds_nothing(self):
        cases = [
            ([], {}, "no faces"),
            ([(self.box, "Face7")], {}, "no face 'Face7'"),
            ([(self.box, "Edge1")], {}, "no face 'Edge1'"),
            ([("Nothing", "Face1")], {}, "no object 'Nothing'"),
            ([self.box], {}, "not an (object, 'FaceN') pair"),
            ([(self.box, "Face1")], {"material": "Unobtainium"}, "unknown material"),
            ([(self.box, "Face1")], {"roughness_category": 8}, "roughness_category"),
            ([(self.box, "Face1")], {"roughness_category": 2.5}, "roughness_category"),
            ([(self.box, "Face1")], {"pattern": "Spiral"}, "pattern"),
            ([(self.box, "Face1")], {"static_friction": -0.1}, "static_friction"),
            ([(self.box, "Face1")], {"stiffness_n_per_mm": 0}, "stiffness_n_per_mm"),
            ([(self.box, "Face1")], {"TextureDC": float("nan")}, "TextureDC = nan is not a finite number"),
            ([(self.box, "Face1")], {"TextureAlpha": float("inf")}, "TextureAlpha = inf is not a finite number"),
            ([(self.box, "Face1")], {"static_friction": float("nan")}, "static_friction = nan is not a finite"),
            # these were set on an object already added: FreeCAD's own error, and a surface
            # left tagging the face, so the corrected call was refused as a second tag
            ([(self.box, "Face1")], {"pattern_angle_deg": "thirty"}, "pattern_angle_deg = 'thirty' is not a number"),
            ([(self.box, "Face1")], {"pattern_angle_deg": float("nan")}, "pattern_angle_deg = nan is not a finite"),
            ([(self.box, "Face1")], {"pattern_center_mm": (1, 2, 3, 4)}, "pattern_center_mm must be three finite"),
            ([(self.box, "Face1")], {"PatternAxis": "z"}, "PatternAxis must be three finite numbers (x, y, z)"),
            ([(self.box, "Face1")], {"PatternAngle": float("inf")}, "PatternAngle = inf is not a finite number"),
            ([(self.box, "Face1")], {"FeelRoughness": "no"}, "FeelRoughness must be True or False"),
            ([(self.box, "Face1")], {"CurveTableSize": 2.5}, "CurveTableSize must be a whole number"),
            ([(self.box, "Face1")], {"PatternCurve": (self.box, ["Edge1"])}, "PatternCurve is a link"),
            # these gave AttributeError, or were taken as something else: 1e300 degrees as 360,
            # Stiffness=5 over stiffness_n_per_mm=2 silently, and a texture that renders
            # nothing made a surface validate() reports
            ([(5, "Face1")], {}, "5 in references is neither an object of the document nor its name"),
            ([(None, "Face1")], {}, "None in references is neither an object of the document nor its name"),
            ([(self.box, "Face1")], {"roughness_category": True}, "roughness_category must be an integer 1..7"),
            ([(self.box, "Face1")], {"pattern_angle_deg": 1e300},
             "pattern_angle_deg = 1e+300 degrees is not a sensible angle"),
            ([(self.box, "Face1")], {"PatternAngle": -1e7}, "PatternAngle = -10000000.0 degrees is not a sensible"),
            ([(self.box, "Face1")], {"Stiffness": 5, "stiffness_n_per_mm": 2},
             "stiffness_n_per_mm and Stiffness both set Stiffness: give one of them"),
            ([(self.box, "Face1")], {"StaticFriction": 0.5, "static_friction": 0.4},
             "static_friction and StaticFriction both set StaticFriction: give one of them"),
            ([(self.box, "Face1")], {"Pattern": "Linear", "pattern": "Circular"},
             "pattern and Pattern both set Pattern: give one of them"),
            ([(self.box, "Face1")], {"Texture": "Custom", "TextureScale": "Friction level", "static_friction": 0},
             "TextureScale 'Friction level' makes the texture's level 1 the face's static friction, and it is 0 "
             "(static_friction)"),
            ([(self.box, "Face1")], {"Texture": "Custom", "TextureScale": "Friction level", "StaticFriction": 0.0},
             "and it is 0 (StaticFriction)"),
            ([(self.box, "Face1")], {"name": None}, "name must be a non-empty string, got None"),
        ]
        for refs, kwargs, message in cases:
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as caught:
                    HaptiCAD.make_surface(self.doc, refs, **kwargs)
                self.assertIn(message, str(caught.exception))
                self.assertTrue(str(caught.exception).startswith("make_surface: "))
                self.assertEqual([o.Name for o in self.doc.Objects], ["Box"])
                self.assertFalse(self.doc.HasPendingTransaction)
        for doc in (None, "MakeSurfaceTest"):
            with self.assertRaisesRegex(ValueError, r"^make_surface: doc = .* is not a FreeCAD document"):
                HaptiCAD.make_surface(doc, [(self.box, "Face1")])
        self.assertEqual([o.Name for o in self.doc.Objects], ["Box"])
        # good values of those kinds, as a script gives them
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face1")], pattern_center_mm=App.Vector(1, 2, 3),
                                  PatternAxis=(0, 0, 1), FeelRoughness=0, CurveTableSize=64)
        self.assertEqual((s.PatternCenter, s.PatternAxis), (App.Vector(1, 2, 3), App.Vector(0, 0, 1)))
        self.assertIs(s.FeelRoughness, False)  # 0, as scripts write it, is False
        # numpy's integers are whole numbers (2 was refused as "must be an integer 1..7, got 2"),
        # an angle beyond a turn is taken modulo 360 (400 was clamped to 360), and a
        # parameter left at its default gives way to its property
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face2")], roughness_category=np.int64(2),
                                  CurveTableSize=np.int32(64), pattern_angle_deg=400)
        self.assertEqual((s.RoughnessCategory, s.CurveTableSize, float(s.PatternAngle)), (2, 64, 40.0))
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face3")], RoughnessCategory=5, PatternAngle=-400.0)
        self.assertEqual((s.RoughnessCategory, float(s.PatternAngle)), (5, -40.0))
        self.assertEqual([surface_object.validate(o) for o in HaptiCAD.surfaces_of(self.doc)], [[], [], []])

    def test_the_queries_refuse_what_is_not_a_document_or_a_surface(self):
        # these gave a bare AttributeError ("'NoneType' object has no attribute 'Objects'")
        for shown, doc in (("None", None), ("a name", "MakeSurfaceTest"), ("a part", self.box)):
            with self.subTest(doc=shown):
                with self.assertRaisesRegex(ValueError, r"^surfaces_of: doc = .* is not a FreeCAD document"):
                    HaptiCAD.surfaces_of(doc)
        for surface, shown in ((None, "None"), ("HapticSurface", "'HapticSurface'"), (self.box, "Box")):
            with self.subTest(surface=shown):
                for query in (HaptiCAD.reference_status, HaptiCAD.reference_pairs):
                    with self.assertRaises(ValueError) as caught:
                        query(surface)
                    self.assertEqual(str(caught.exception), f"{query.__name__}: {shown} is not a haptic surface")
        self.assertEqual([o.Name for o in self.doc.Objects], ["Box"])

    def test_validation_names_the_property_or_reference_that_is_wrong(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        self.doc.recompute()
        self.assertEqual(surface_object.validate(s), [])
        nan = float("nan")
        for name in ("PatternBlendRadius", "PatternAngle", "TextureBeta"):  # used or not
            with self.subTest(name=name):
                old = getattr(s, name)
                setattr(s, name, nan)
                problems = surface_object.validate(s)
                self.assertEqual(problems, [f"{name} = nan: not a finite number"])
                setattr(s, name, old)
        s.PatternCenter = App.Vector(0, float("inf"), 0)
        self.assertEqual(surface_object.validate(s), ["PatternCenter.y = inf: not a finite number"])
        s.PatternCenter = App.Vector()
        s.Texture, s.TextureScale, s.StaticFriction = "Custom", "Friction level", 0.0
        self.assertEqual(len(surface_object.validate(s)), 1)
        self.assertIn("would render nothing", surface_object.validate(s)[0])
        s.TextureScale = "Device force"
        self.assertEqual(surface_object.validate(s), [])
        s.References = [(self.box, ("Face6", "Edge1"))]  # was: "the model changed"
        self.doc.recompute()
        self.assertEqual(surface_object.validate(s), ["Box.Edge1: not a face; a surface tags faces only"])
        s.References = [(self.box, ("Face6", "Face99"))]  # was: "the model changed" too
        self.doc.recompute()
        self.assertEqual(surface_object.validate(s), ["no such face: Box.Face99; pick a face the part has"])
        # a face listed twice is tagged once (both were marked broken: the surface tagged nothing)
        s.References = [(self.box, ("Face6", "Face6"))]
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(s), [("Box", "Face6", "ok")])
        self.assertEqual(surface_object.validate(s), [])

    def test_a_face_tagged_by_another_surface_is_refused_or_reported(self):
        first = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel")
        with self.assertRaisesRegex(ValueError, r"Box\.Face6 is already tagged by HapticSurface"):
            HaptiCAD.make_surface(self.doc, [(self.box, "Face1"), (self.box, "Face6")])
        self.assertEqual(len(HaptiCAD.surfaces_of(self.doc)), 1)
        # a script that adds it to a second surface directly is told, and so is the first
        second = HaptiCAD.make_surface(self.doc, [(self.box, "Face1")])
        second.References = [(self.box, ("Face1", "Face6"))]
        self.doc.recompute()
        for surface, other in ((second, first), (first, second)):
            problems = surface_object.validate(surface)
            self.assertTrue(any(f"Box.Face6 is also tagged by {other.Label}" in p for p in problems), problems)
        second.References = [(self.box, ("Face1",))]
        self.assertEqual(surface_object.validate(second), [])

    def test_a_tagged_part_hidden_behind_a_later_feature_is_said(self):
        # a Part Fillet (here a Refine) made on a tagged cut hides it: Feel renders the
        # hidden shape, so the panels say so and name what to tag instead
        from hapticad.surface_object import hidden_part_notes

        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        self.assertEqual(hidden_part_notes(s), [])
        refined = self.doc.addObject("Part::Refine", "Refined")
        refined.Source = self.box
        self.doc.recompute()
        self.box.Visibility = False  # what the GUI does when the feature is made
        self.assertEqual(hidden_part_notes(s), [f"{self.box.Label} is hidden, used by Refined: you feel "
                                                f"{self.box.Label}'s shape, not what is shown; tag the faces of "
                                                f"Refined instead"])

    def test_a_tagged_part_hidden_by_a_draft_array_made_with_links_says_to_make_it_without(self):
        # it said "tag the faces of Array instead", which no click can do: a click on such
        # an array picks the hidden part's face again
        import Draft
        from hapticad.surface_object import hidden_part_notes

        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        array = Draft.make_ortho_array(self.box, App.Vector(20, 0, 0), App.Vector(0, 20, 0), App.Vector(0, 0, 20),
                                       3, 1, 1, use_link=True)
        self.doc.recompute()
        self.box.Visibility = False
        (note,) = hidden_part_notes(s)
        self.assertNotIn(f"tag the faces of {array.Label} instead", note)
        self.assertEqual(note, f"{self.box.Label} is hidden, used by {array.Label}: you feel {self.box.Label}'s "
                               f"shape, not what is shown; {array.Label} is an array made with links to "
                               f"{self.box.Label}: its faces are {self.box.Label}'s, shown where the array places "
                               "them, and cannot be tagged there; make the array without links (Draft's Link array "
                               "option off) and tag its faces")

    def test_a_deleted_part_is_named_until_faces_are_picked_again(self):
        # deleting a part empties the surface's links before the part goes; it used to
        # say "no faces: pick at least one face", as if nothing had ever been tagged
        cyl = self.doc.addObject("Part::Cylinder", "Cylinder")
        cyl.Label = "Grip"
        self.box.Label = "Handle"
        self.doc.recompute()
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6"), (self.box, "Face2"), (cyl, "Face1")])
        self.doc.recompute()
        s.References = [(self.box, ("Face6",)), (cyl, ("Face1",))]  # a face removed: no part went
        self.assertEqual(surface_object.deleted_parts(s), [])
        self.doc.openTransaction("delete")
        self.doc.removeObject("Cylinder")
        self.doc.commitTransaction()
        self.doc.recompute()
        self.assertEqual(surface_object.deleted_parts(s), ["Grip"])
        self.assertEqual(surface_object.validate(s, compile_faces=False), [])  # Face6 still feels
        self.doc.removeObject("Box")
        self.doc.recompute()
        self.assertEqual(surface_object.validate(s), [
            "no faces: Grip and Handle, whose faces it tagged, were deleted; undo the deletion or pick "
            "other faces"])
        # kept through save and reopen
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "deleted.FCStd")
            self.doc.saveCopy(path)
            reopened = App.openDocument(path)
            try:
                self.assertIn("Grip and Handle", surface_object.validate(reopened.getObject(s.Name))[0])
            finally:
                App.closeDocument(reopened.Name)
        # faces picked again: the note goes
        other = self.doc.addObject("Part::Box", "Other")
        self.doc.recompute()
        s.References = [(other, ("Face1",))]
        self.doc.recompute()
        self.assertEqual(surface_object.deleted_parts(s), [])
        self.assertEqual(surface_object.validate(s), [])
        s.References = []
        self.assertEqual(surface_object.validate(s), ["no faces: pick at least one face"])

    def test_undoing_a_part_deletion_brings_its_faces_back_and_no_note(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        self.doc.UndoMode = 1
        self.doc.recompute()
        self.doc.openTransaction("delete")
        self.doc.removeObject("Box")
        self.doc.commitTransaction()
        self.assertEqual(surface_object.deleted_parts(s), ["Box"])
        self.doc.undo()
        self.doc.recompute()
        self.assertEqual([(o.Name, f) for o, f in HaptiCAD.reference_pairs(s)], [("Box", "Face6")])
        self.assertEqual(surface_object.deleted_parts(s), [])
        self.assertEqual(surface_object.validate(s), [])

    def test_a_grid_the_servo_rate_cannot_follow_says_up_to_what_speed_it_is_felt(self):
        # category 1's 0.1 mm grid at 1 kHz and 120 mm/s is 1.2 kHz, past half the rate:
        # the probe felt a 200 Hz ripple, and nothing said so. The speed said counts the
        # harmonics the grid carries, as the grating's does: its balls' tilt doubles 1/g, and
        # a stroke across the grid's diagonal meets lines sqrt(2) finer (the 50 and 150 mm/s
        # once said were half the rate for 1/g alone: test_a_grid_is_felt_as_it_is_...)
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", roughness_category=1)
        s.Label = "Lid"
        note = surface_object.rate_note(s, 1000)
        self.assertIn("Lid: roughness category 1's 0.1 mm grid is felt as it is up to 15 mm/s at the 1000 Hz "
                      "servo rate (there its 2nd harmonic, stroked across the grid's diagonal, comes within 10 % of "
                      "half the rate)", note)
        self.assertIn("raise the servo rate in Preferences (at 10000 Hz it is felt as it is up to 159 mm/s)", note)
        self.assertEqual(surface_object.rate_notes(self.doc, 1000), [note])
        s.RoughnessCategory = 2
        self.assertIn("up to 47 mm/s", surface_object.rate_note(s, 1000))
        self.assertIn("(5657 Hz follows it to 270 mm/s)", surface_object.rate_note(s, 1000))
        self.assertEqual(surface_object.rate_note(s, 5657), "")  # 270 mm/s: the paper's fastest stroke
        self.assertIn("up to 269 mm/s", surface_object.rate_note(s, 5656))
        s.RoughnessCategory = 3
        self.assertIn("up to 95 mm/s", surface_object.rate_note(s, 1000))
        s.RoughnessCategory = 6
        self.assertIn("up to 238 mm/s", surface_object.rate_note(s, 1000))
        s.RoughnessCategory = 7
        self.assertEqual(surface_object.rate_note(s, 1000), "")  # 477 mm/s
        s.RoughnessCategory = 1  # no servo rate HaptiCAD runs follows it to 270 mm/s
        self.assertIn("up to 159 mm/s at the 10000 Hz servo rate", surface_object.rate_note(s, 10000))
        self.assertIn("Stroke slower: no servo rate up to 10000 Hz follows it to 270 mm/s",
                      surface_object.rate_note(s, 10000))
        # taller balls tilt further and carry more harmonics; friction alone, only the balls' own
        s.RoughnessHeight = 0.2
        self.assertIn("up to 7.9 mm/s at the 1000 Hz servo rate (there its 4th harmonic",
                      surface_object.rate_note(s, 1000))
        s.RoughnessHeight = 0.0
        self.assertIn("up to 31 mm/s at the 1000 Hz servo rate (there its 1st harmonic",
                      surface_object.rate_note(s, 1000))
        s.RoughnessHeight = 0.05
        s.FeelRoughness = False  # nothing rendered: nothing to say
        self.assertEqual(surface_object.rate_note(s, 1000), "")
        # two grids: one sentence naming both, in the tree's order
        s.FeelRoughness = True
        other = HaptiCAD.make_surface(self.doc, [(self.box, "Face1")], material="ABS", roughness_category=2)
        other.Label = "Grip"
        self.assertEqual(len(surface_object.rate_notes(self.doc, 1000)), 1)
        self.assertIn("Lid (category 1, 0.1 mm) up to 15 mm/s, Grip (category 2, 0.3 mm) up to 47 mm/s",
                      surface_object.rate_notes(self.doc, 1000)[0])

    def test_a_grid_is_felt_as_it_is_at_the_speed_its_note_says(self):
        # reviewer (roughness_nyquist.py): "category 1's grid is felt as it is up to 50 mm/s" at 1 kHz was not
        # true: at 50 mm/s the lateral ripple was 0.041 or 0.155 N peak to peak by where the stroke started (0.161
        # N at 10 kHz), and at 40 mm/s the normal force carried a 200 Hz line, the 800 Hz second harmonic's alias.
        # At the speed the note says, along a row and across the grid's diagonal, from any start, every line of
        # the force sampled at 1 kHz is the grid's own at 10 kHz, as strong, and the ripple as large
        import math
        import re

        from hapticad.document_scene import build_document_scene

        self.box.Length, self.box.Width, self.box.Height = 100, 100, 10
        self.doc.recompute()
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", static_friction=0.5,
                                  dynamic_friction=0.4, stiffness_n_per_mm=0.5, roughness_category=1)
        scene = build_document_scene(self.doc)
        limits = _core.RenderLimits()
        limits.max_force_n, limits.max_stiffness_n_per_m = 10.0, 1e4

        def stroke(degrees, start_mm, speed, rate):
            """(normal, lateral) force of a stroke 1 mm deep from start_mm (x, y on the top) along
            degrees, past its first 20 ms; the probe set down there first."""
            direction = np.array([math.cos(math.radians(degrees)), math.sin(math.radians(degrees)), 0.0])
            start = np.array([*start_mm, 9.0]) * 1e-3
            ticks = int(round(0.35 * rate))
            path = np.vstack([np.tile(start + [0, 0, 0.003], (5, 1)), np.tile(start, (int(0.1 * rate), 1)),
                              start + np.outer(np.arange(1, ticks + 1) * speed * 1e-3 / rate, direction)])
            velocity = np.zeros_like(path)
            velocity[-ticks:] = direction * speed * 1e-3
            renderer = _core.ForceRenderer(scene.scene, scene.surfaces, limits, scene.contact_options())
            force = np.asarray(_core.run_stroke(renderer, path, velocity, list(np.arange(len(path)) / rate))["force_w"])
            force = force[-ticks + int(0.02 * rate):]
            return force[:, 2], -(force @ direction)

        def lines(signal, rate):
            """{Hz: amplitude} of the spectrum's peaks of 3 % of its largest or more."""
            signal = signal - signal.mean()
            window = np.hanning(len(signal))
            spectrum = np.abs(np.fft.rfft(signal * window, 8 * len(signal))) * 2 / window.sum()
            hz = np.fft.rfftfreq(8 * len(signal), 1 / rate)
            peaks = [i for i in range(1, len(spectrum) - 1) if spectrum[i - 1] < spectrum[i] >= spectrum[i + 1]]
            return {hz[i]: spectrum[i] for i in peaks if spectrum[i] >= 0.03 * max(spectrum[peaks])}

        fastest = float(re.search(r"up to ([0-9.]+) mm/s", surface_object.rate_note(s, 1000)).group(1))
        for degrees in (0.0, 45.0):
            for start in ((30.0, 50.0), (30.025, 50.0)):
                felt, reference = stroke(degrees, start, fastest, 1000.0), stroke(degrees, start, fastest, 10000.0)
                for name, at_1k, at_10k in zip(("normal", "lateral"), felt, reference):
                    with self.subTest(degrees=degrees, start=start, force=name):
                        own = lines(at_10k, 10000.0)
                        self.assertLess(max(own), 0.95 * 500.0)  # every line of the grid under half the rate
                        for hz, amplitude in lines(at_1k, 1000.0).items():
                            nearest = min(own, key=lambda f: abs(f - hz))
                            self.assertLess(abs(nearest - hz), 3.0, f"{hz:.0f} Hz is not the grid's: {sorted(own)}")
                            if amplitude > 0.1 * max(own.values()):
                                self.assertAlmostEqual(amplitude / own[nearest], 1.0, delta=0.03)
                        self.assertAlmostEqual(np.ptp(at_1k) / np.ptp(at_10k), 1.0, delta=0.03)
        # what the old note said: at 40 mm/s the normal force's strongest line is 200 Hz, not the grid's 800
        normal = lines(stroke(0.0, (30.0, 50.0), 40.0, 1000.0)[0], 1000.0)
        self.assertAlmostEqual(max(normal, key=normal.get), 200.0, delta=3.0)
        # and at 50 mm/s the ripple is what the start leaves of it
        ripple = [np.ptp(stroke(0.0, start, 50.0, 1000.0)[1]) for start in ((30.0, 50.0), (30.025, 50.0))]
        self.assertLess(min(ripple), 0.5 * max(ripple))

    def test_a_grating_the_servo_rate_cannot_follow_says_up_to_what_speed_it_is_felt_as_designed(self):
        # the paper's 2.5 mm grating at 1 kHz: its 4th harmonic stays under 500 Hz up to 312 mm/s, said nothing
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", FeelRoughness=False,
                                  Texture="Custom")
        s.Label = "Grip"
        self.assertEqual(surface_object.rate_note(s, 1000), "")
        s.TexturePeriod = 1.0
        note = surface_object.rate_note(s, 1000)
        self.assertEqual(note, "Grip: its 1 mm texture grating is felt as designed up to 125 mm/s at the 1000 Hz servo "
                               "rate (there its 4th harmonic reaches half the rate); stroked faster its harmonics are "
                               "felt at a lower, wrong pitch. Stroke slower, or raise the servo rate in Preferences "
                               "(2160 Hz follows it to 270 mm/s)")
        self.assertEqual(surface_object.rate_notes(self.doc, 1000), [note])
        self.assertEqual(surface_object.rate_note(s, 2160), "")
        s.TexturePeriod = 0.4  # the grating itself aliases past 200 mm/s
        self.assertIn("up to 50 mm/s", surface_object.rate_note(s, 1000))
        self.assertIn("its harmonics, and beyond 200 mm/s the grating itself, are felt",
                      surface_object.rate_note(s, 1000))
        self.assertIn("(5400 Hz follows it", surface_object.rate_note(s, 1000, where="with --rate"))
        s.TexturePeriod = 0.1  # no servo rate in Preferences follows it: the period must change
        self.assertIn("or lengthen the period (at 10000 Hz, 0.216 mm follows it to 270 mm/s)",
                      surface_object.rate_note(s, 1000))
        s.Texture = "None"
        self.assertEqual(surface_object.rate_note(s, 1000), "")
        # both a grid and a grating: both said
        s.Texture, s.TexturePeriod, s.FeelRoughness, s.RoughnessCategory = "Custom", 1.0, True, 1
        both = surface_object.rate_note(s, 1000)
        self.assertIn("Grip: roughness category 1's 0.1 mm grid", both)
        self.assertIn("Grip: its 1 mm texture grating", both)
        self.assertEqual(len(surface_object.rate_notes(self.doc, 1000)), 2)

    def test_a_grating_past_half_the_servo_rate_is_felt_at_its_alias(self):
        # what texture_rate_note says, measured: a 0.4 mm grating stroked at 250 mm/s is 625 Hz; the 1 kHz loop
        # renders it at 1000 - 625 = 375 Hz, the 5 kHz loop at 625 Hz
        import numpy as np
        from hapticad.document_scene import build_document_scene
        from hapticad.feel import Stroke, run_stroke_in_servo_loop

        self.box.Length, self.box.Width, self.box.Height = 40, 100, 10
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", FeelRoughness=False,
                              Texture="Custom", TexturePeriod=0.4, TextureDC=0.5, TextureBeta=0.4, TextureAlpha=3.0,
                              TextureFullRange=2.0)
        scene = build_document_scene(self.doc)
        peaks = {}
        for rate in (1000, 5000):
            # across the grating: its coordinate runs along the face frame's e2, +y on this face
            stroke = Stroke((20, 10, 10), (20, 90, 10), speed_mm_s=250.0, depth_mm=1.0, rate_hz=rate)
            result = run_stroke_in_servo_loop(scene, stroke)
            trace = result.trace
            slide = (trace["time_s"] > result.plan.slide_start_s + 0.02) & (trace["time_s"] < result.plan.slide_end_s)
            lateral = np.linalg.norm(np.asarray(trace["force_n"])[slide][:, :2], axis=1)
            times = np.asarray(trace["time_s"])[slide]
            self.assertGreater(len(times), 0.25 * rate)
            # evenly resampled at the loop's own period (a late tick shifts a sample, not the tone)
            grid = np.arange(times[0], times[-1], 1.0 / rate)
            samples = np.interp(grid, times, lateral)
            spectrum = np.abs(np.fft.rfft((samples - samples.mean()) * np.hanning(len(samples))))
            peaks[rate] = float(np.fft.rfftfreq(len(samples), 1.0 / rate)[np.argmax(spectrum)])
        self.assertAlmostEqual(peaks[5000], 625.0, delta=10.0)
        self.assertAlmostEqual(peaks[1000], 375.0, delta=10.0)
        self.assertIn("beyond 200 mm/s the grating itself", surface_object.rate_note(HaptiCAD.surfaces_of(self.doc)[0],
                                                                                     1000))

    def test_a_circular_pattern_copied_with_its_part_is_centred_on_the_copy(self):
        # Edit > Duplicate selection with the part: the copy's circles stayed on the
        # original part's hole and moved with the original
        cylinder = self.doc.addObject("Part::Cylinder", "Hole")
        cylinder.Radius, cylinder.Height = 5, 30
        cylinder.Placement.Base = App.Vector(65, 20, -5)
        self.box.Length, self.box.Width, self.box.Height = 80, 40, 20
        cut = self.doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = self.box, cylinder
        self.doc.recompute()
        s = HaptiCAD.make_surface(self.doc, [(cut, "Face3")], material="ABS", Pattern="Circular",
                                  PatternCenter=(65, 20, 20))
        self.doc.recompute()
        copy = next(o for o in self.doc.copyObject([s], True) if HaptiCAD.is_haptic_surface(o))
        self.doc.recompute()
        (part, _), = HaptiCAD.reference_pairs(copy)
        self.assertIsNot(part, cut)
        part.Placement.Base = App.Vector(0, 100, 0)
        self.doc.recompute()
        self.assertEqual(tuple(copy.PatternCenter), (65, 120, 20))  # on the copy's hole
        cut.Placement.Base = App.Vector(200, 0, 0)
        self.doc.recompute()
        self.assertEqual(tuple(copy.PatternCenter), (65, 120, 20))  # not moved by the original
        self.assertEqual(tuple(s.PatternCenter), (265, 20, 20))

    def test_a_circular_pattern_chosen_is_centred_on_its_faces(self):
        # a part away from the origin: circles round (0, 0, 0) crossed its face as stripes
        self.box.Placement.Base = App.Vector(100, 0, 0)
        self.box.Length, self.box.Width, self.box.Height = 40, 20, 10
        self.doc.recompute()
        top = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        top.Pattern = "Circular"  # as the task panel sets it
        self.assertEqual(tuple(top.PatternCenter), (120, 10, 10))
        self.assertEqual(tuple(top.PatternAxis), (0, 0, 1))
        # a side face: round its centre, about its normal
        side = HaptiCAD.make_surface(self.doc, [(self.box, "Face2")], material="ABS", pattern="Circular")
        self.assertEqual(tuple(side.PatternCenter), (140, 10, 5))
        self.assertEqual(tuple(side.PatternAxis), (1, 0, 0))
        # two faces: weighted by area (the top 800 mm², the side 200 mm²)
        both = HaptiCAD.make_surface(self.doc, [(self.box, "Face1")], material="ABS")
        both.References = [(self.box, ("Face1", "Face5"))]
        both.Pattern = "Circular"
        expected = (App.Vector(100, 10, 5) * 200 + App.Vector(120, 10, 0) * 800) * (1 / 1000)
        self.assertLess((both.PatternCenter - expected).Length, 1e-9)
        # a centre the designer set stays, switched away and back
        top.PatternCenter = App.Vector(130, 5, 10)
        top.Pattern = "Linear"
        top.Pattern = "Circular"
        self.assertEqual(tuple(top.PatternCenter), (130, 5, 10))
        # so does the origin where it lies on the faces
        plate = self.doc.addObject("Part::Box", "Plate")
        plate.Length, plate.Width = 40, 20
        plate.Placement.Base = App.Vector(-20, -10, -10)  # its top face round the origin
        self.doc.recompute()
        on = HaptiCAD.make_surface(self.doc, [(plate, "Face6")], material="ABS", pattern="Circular",
                                   pattern_center_mm=(0, 0, 0))
        on.Pattern = "Linear"
        on.Pattern = "Circular"
        self.assertEqual(tuple(on.PatternCenter), (0, 0, 0))

    def test_a_circular_pattern_is_shown_where_a_container_turning_its_part_took_it(self):
        # reviewer: the App::Part holding the part turned 90 degrees about Y, and PatternCenter
        # still read (10, 5, 10) where (10, 5, -10) was felt: the App::Part recomputes only itself
        from hapticad.surface_object import circular_centre_axis

        def assertVector(vector, expected):
            self.assertLess((App.Vector(vector) - App.Vector(*expected)).Length, 1e-9, f"{vector} != {expected}")

        assembly = self.doc.addObject("App::Part", "Assembly")
        self.box.Length, self.box.Width, self.box.Height = 60, 10, 10
        assembly.addObject(self.box)
        self.doc.recompute()
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], pattern="Circular", pattern_center_mm=(10, 5, 10))
        self.doc.recompute()
        turn = App.Rotation(App.Vector(0, 1, 0), 90)
        assembly.Placement = App.Placement(App.Vector(), turn)
        self.doc.recompute()
        assertVector(s.PatternCenter, (10, 5, -10))
        assertVector(s.PatternAxis, (1, 0, 0))  # the top's normal, turned with it
        self.assertEqual(circular_centre_axis(s), (s.PatternCenter, s.PatternAxis))  # shown is felt
        self.assertNotIn("Touched", s.State)
        # a Body in an App::Part: the surface links the Body, which nothing recomputes either
        body = self.doc.addObject("PartDesign::Body", "Body")
        knob = body.newObject("PartDesign::AdditiveBox", "Knob")
        assembly.addObject(body)
        self.doc.recompute()
        on_body = HaptiCAD.make_surface(self.doc, [(knob, "Face6")], pattern="Circular",
                                        pattern_center_mm=(5, 5, 10))
        self.doc.recompute()
        assembly.Placement = App.Placement(App.Vector(0, 0, 20), turn)  # lifted 20 mm
        self.doc.recompute()
        assertVector(on_body.PatternCenter, (5, 5, 30))
        assertVector(s.PatternCenter, (10, 5, 10))
        # and saved as shown
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "turned.FCStd")
            self.doc.saveCopy(path)
            reopened = App.openDocument(path)
            try:
                assertVector(reopened.getObject(s.Name).PatternCenter, (10, 5, 10))
            finally:
                App.closeDocument(reopened.Name)

    def test_a_face_from_another_document_is_refused(self):
        other = App.newDocument("Other")
        try:
            cyl = other.addObject("Part::Cylinder", "Cylinder")
            other.recompute()
            with self.assertRaises(ValueError):
                HaptiCAD.make_surface(self.doc, [(cyl, "Face1")])
        finally:
            App.closeDocument(other.Name)


class PersistenceTest(unittest.TestCase):
    """Every property survives save and reopen, twice, without touching the object."""

    PROPERTIES = [p[0] for p in surface_object.PROPERTIES if p[0] not in ("References", "PatternCurve")]

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.dir.name, "persist.FCStd")

    def tearDown(self):
        for name in list(App.listDocuments()):
            if name.startswith("persist"):
                App.closeDocument(name)
        self.dir.cleanup()

    def snapshot(self, s):
        values = {p: getattr(s, p) for p in self.PROPERTIES}
        values["PatternAngle"] = float(values["PatternAngle"])
        values["PatternCenter"] = tuple(values["PatternCenter"])
        values["PatternAxis"] = tuple(values["PatternAxis"])
        values["References"] = [(o.Name, tuple(subs)) for o, subs in s.References]
        values["PatternCurve"] = (s.PatternCurve[0].Name, tuple(s.PatternCurve[1]))
        values["MaterialChoices"] = s.getEnumerationsOfProperty("Material")
        return values

    def test_round_trip_of_every_property(self):
        doc = App.newDocument("persist")
        doc.addObject("Part::Box", "Box")
        doc.addObject("Part::Cylinder", "Cylinder")
        doc.recompute()
        # a value off its default for every property
        s = HaptiCAD.make_surface(doc, [(doc.Box, "Face6"), (doc.Box, "Face2"), (doc.Cylinder, "Face1")],
                                  material="TPE soft-touch", roughness_category=6, pattern="Circular",
                                  pattern_angle_deg=37.5, pattern_center_mm=(1.5, -2.0, 30.0),
                                  static_friction=1.7, dynamic_friction=1.3, stiffness_n_per_mm=0.35,
                                  FeelRoughness=False, RoughnessHeight=0.12, RoughnessFrictionModulation=0.4,
                                  FrictionModel="Friction cone (stick-slip)", StickSpeed=3.5,
                                  TransitionSpeed=1.5, StribeckSpeed=7.0, PatternAxis=App.Vector(0, 1, 1),
                                  PatternBlendRadius=2.5, CurveEvaluation="Exact", CurveTableSize=100,
                                  Interpolation="Friction ellipse", AcrossFriction=2.5, BackwardFriction=0.7,
                                  Texture="Custom", TextureDC=0.4, TextureViscosity=-0.1, TextureBeta=0.2,
                                  TextureAlpha=1.5, TextureBetaViscosity=0.05, TextureAlphaViscosity=-0.3,
                                  TexturePeriod=3.25, TextureFullRange=1.5, Damping=0.35)
        s.PatternCurve = (doc.Box, ["Edge3"])
        doc.recompute()
        defaults = {p[0]: p[4] for p in surface_object.PROPERTIES}
        for name in self.PROPERTIES:
            if defaults.get(name) is not None:
                self.assertNotEqual(getattr(s, name), defaults[name], name)
        before = self.snapshot(s)
        doc.saveAs(self.path)
        App.closeDocument(doc.Name)
        for _ in range(2):
            doc = App.openDocument(self.path)
            s = doc.getObject("HapticSurface")
            self.assertIsInstance(s.Proxy, surface_object.HapticSurface)
            self.assertEqual(self.snapshot(s), before)
            self.assertNotIn("Touched", s.State)
            # constraints are back after reopening
            s.RoughnessCategory = 42
            self.assertEqual(s.RoughnessCategory, 7)
            s.RoughnessCategory = 6
            doc.save()
            App.closeDocument(doc.Name)


class MigrationTest(unittest.TestCase):
    def test_a_schema_1_document_gains_the_new_properties_and_keeps_its_values(self):
        path = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data", "schema1_toothbrush.FCStd")
        doc = App.openDocument(path)
        try:
            grip = doc.getObject("ThumbGrip")
            self.assertEqual((grip.Material, grip.RoughnessCategory), ("TPE soft-touch", 4))
            self.assertEqual(grip.DynamicFriction, 1.2)
            for name, _, _, _, default, _ in surface_object.PROPERTIES:
                self.assertIn(name, grip.PropertiesList)
                if default is not None and name not in ("RoughnessCategory", "StaticFriction",
                                                        "DynamicFriction", "Stiffness"):
                    self.assertEqual(getattr(grip, name), default, name)
            self.assertEqual(grip.Texture, "None")
            self.assertEqual(grip.DeletedParts, "")
            self.assertEqual(surface_object.deleted_parts(grip), [])
            self.assertNotIn("Touched", grip.State)
        finally:
            App.closeDocument(doc.Name)


class TexturePresetTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("TexturePreset")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_a_preset_fills_the_values_and_an_edit_makes_it_custom(self):
        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], Texture="Paper f_DC 0.325 f_vis -0.2")
        self.assertEqual((s.TextureDC, s.TextureViscosity, s.TextureBeta, s.TextureAlpha), (0.325, -0.2, 0.125, 2.5))
        s.TextureDC = 0.4
        self.assertEqual(s.Texture, "Custom")
        self.assertEqual(s.TextureDC, 0.4)
        s.Texture = "Paper f_DC 0.675 f_vis +0.2"
        self.assertEqual((s.TextureDC, s.TextureViscosity), (0.675, 0.2))

    def test_unknown_properties_and_choices_are_refused(self):
        with self.assertRaisesRegex(ValueError, "unknown property 'Colour'"):
            HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], Colour="red")
        with self.assertRaisesRegex(ValueError, "Texture must be one of"):
            HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], Texture="Velvet")
        with self.assertRaisesRegex(ValueError, "AcrossFriction"):
            HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], AcrossFriction=-1)
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [])


if __name__ == "__main__":
    unittest.main()
