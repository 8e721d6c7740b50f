# SPDX-License-Identifier: GPL-3.0-or-later
"""Strokes: planning (approach, depth, slide, retreat) and clear errors."""
import re
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad.document_scene import build_document_scene
from hapticad import _core, feel
from hapticad.feel import Stroke, plan_stroke, run_stroke_in_servo_loop, summarize


class FeelTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.doc = App.newDocument("FeelTest")
        box = cls.doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 60, 40, 20
        cls.doc.recompute()
        HaptiCAD.make_surface(cls.doc, [(box, "Face6")], material="Rubber", stiffness_n_per_mm=0.5,
                              FeelRoughness=False)
        cls.scene = build_document_scene(cls.doc)

    @classmethod
    def tearDownClass(cls):
        App.closeDocument(cls.doc.Name)

    def test_force_shading_off_pushes_along_the_facets_on_a_coarse_cylinder(self):
        # the accuracy's force shading reaches the renderer: on, the push on a coarse
        # tessellation of a cylinder's side is radial; off, it is the facet's normal
        import math

        from hapticad import accuracy

        doc = App.newDocument("FeelShading")
        try:
            can = doc.addObject("Part::Cylinder", "Can")
            can.Radius, can.Height = 20, 30
            doc.recompute()
            HaptiCAD.make_surface(doc, [(can, "Face1")], material="Rubber", static_friction=0.0,
                                  dynamic_friction=0.0, FeelRoughness=False)
            worst = {}
            for shading in (True, False):
                scene = build_document_scene(doc, accuracy.custom(0.5, math.radians(30), force_shading=shading))
                self.assertEqual(scene.contact_options().force_shading, shading)
                angles = []
                for degrees in (3.0, 7.0, 11.0, 17.0):
                    a = math.radians(degrees)
                    radial = np.array([math.cos(a), math.sin(a), 0.0])
                    start, end = 20 * radial + [0, 0, 8], 20 * radial + [0, 0, 22]
                    trace = run_stroke_in_servo_loop(scene, Stroke(start, end, speed_mm_s=60, depth_mm=1)).trace
                    # the simulated hand waits for a late tick: no force is zeroed by a stall
                    self.assertFalse((trace["flags"] & _core.FLAG_DEVICE_FAULT).any())
                    contact = np.asarray(trace["normal_force_n"]) > 0.05
                    force = np.asarray(trace["force_n"])[contact]
                    self.assertGreater(len(force), 100)
                    horizontal = force[:, :2] / np.linalg.norm(force[:, :2], axis=1)[:, None]
                    angles.append(float(np.degrees(np.arccos(np.clip(horizontal @ radial[:2], -1, 1))).max()))
                worst[shading] = max(angles)
            self.assertLess(worst[True], 1.0, worst)
            self.assertGreater(worst[False], 4.0, worst)
        finally:
            App.closeDocument(doc.Name)

    def test_plan_goes_depth_below_the_surface_along_the_inward_normal(self):
        plan = plan_stroke(self.scene, Stroke((10, 20, 20), (50, 20, 20), speed_mm_s=40, depth_mm=2))
        np.testing.assert_allclose(plan.outward_normal, [0, 0, 1], atol=1e-12)
        np.testing.assert_allclose(plan.positions_m[0], [0.010, 0.020, 0.025], atol=1e-12)
        np.testing.assert_allclose(plan.positions_m[3], [0.010, 0.020, 0.018], atol=1e-12)
        np.testing.assert_allclose(plan.positions_m[4], [0.050, 0.020, 0.018], atol=1e-12)
        self.assertAlmostEqual(plan.slide_end_s - plan.slide_start_s, 1.0)  # 40 mm at 40 mm/s
        self.assertEqual(self.scene.face_names[plan.start_face], "Box.Face6")
        self.assertTrue((np.diff(plan.times_s) > 0).all())

    def test_bad_strokes_are_refused_with_a_reason(self):
        cases = [
            (Stroke((10, 20, 35), (50, 20, 35)), "stroke: P0 is 15.000 mm from the nearest surface"),
            # a mistyped end: the slide would run 10 mm into the part, or off it into the air
            (Stroke((10, 20, 20), (50, 20, 10)), "stroke: P1 is 10.000 mm from the nearest surface"),
            (Stroke((10, 20, 20), (50, 20, 30)), "stroke: P1 is 10.000 mm from the nearest surface"),
            (Stroke((10, 20, 20), (10, 20, 20)), "coincide"),
            (Stroke((10, 20, 20), (50, 20, 20), speed_mm_s=0), "speed"),
            (Stroke((10, 20, 20), (50, 20, 20), depth_mm=-1), "depth"),
            (Stroke((10, 20, 20), (50, 20, 20), rate_hz=1e6), "rate"),
            (Stroke((10, 20, 20), (50, 20, 20), rate_hz=200), "the loop's watchdog would cut the force"),
            (Stroke((10, float("nan"), 20), (50, 20, 20)), "finite"),
        ]
        for stroke, message in cases:
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as caught:
                    plan_stroke(self.scene, stroke)
                self.assertIn(message, str(caught.exception))

    def test_a_stroke_feels_k_depth_and_mu_d(self):
        result = run_stroke_in_servo_loop(self.scene, Stroke((10, 20, 20), (50, 20, 20), speed_mm_s=80, depth_mm=1.5))
        summary = summarize(result, self.scene)
        face = summary["faces"]["Box.Face6"]
        self.assertGreater(face["sliding_ticks"], 300)
        self.assertAlmostEqual(face["mean_normal_force_n"], 0.5 * 1.5, delta=1e-5)
        self.assertAlmostEqual(face["mean_ft_over_fn"], 1.0, delta=1e-6)
        self.assertEqual(summary["ticks"] + summary["skipped_ticks"],
                         int(round(result.plan.times_s[-1] * 1000)) + 1)


    def test_a_surface_stiffer_than_the_device_is_said_and_its_label_given(self):
        # 5 N/mm on a 3 N/mm probe: felt at 3 N/mm (1.5 N at 0.5 mm, not 2.5 N), and nothing said it
        doc = App.newDocument("FeelStiff")
        try:
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 40, 20, 10
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="Steel", stiffness_n_per_mm=5.0,
                                            FeelRoughness=False)
            surface.Label = "Grïp 面"
            scene = build_document_scene(doc)
            result = run_stroke_in_servo_loop(scene, Stroke((5, 10, 10), (35, 10, 10), depth_mm=0.5))
            summary = summarize(result, scene)
            face = summary["faces"]["Box.Face6"]
            self.assertEqual((face["surface"], face["surface_name"]), ("Grïp 面", surface.Name))
            most = result.limits.max_stiffness_n_per_m * 1e-3
            self.assertEqual(summary["max_stiffness_n_per_mm"], most)
            self.assertLess(most, 5.0)
            self.assertEqual((face["stiffness_n_per_mm"], face["surface_stiffness_n_per_mm"],
                              face["stiffness_above_device"]), (most, 5.0, True))
            self.assertAlmostEqual(face["mean_normal_force_n"], most * 0.5, delta=1e-4)
            self.assertEqual(summary["notes"], [
                f"Box.Face6 (Grïp 面) is 5 N/mm stiff, above the {most:g} N/mm the device renders stably: it was "
                f"felt at {most:g} N/mm (0.5 mm deep it pushes back with {most * 0.5:.3g} N, not 2.5 N)"])
        finally:
            App.closeDocument(doc.Name)
        # one the device renders: nothing said
        result = run_stroke_in_servo_loop(self.scene, Stroke((10, 20, 20), (50, 20, 20), depth_mm=1))
        summary = summarize(result, self.scene)
        self.assertEqual((summary["notes"], summary["faces"]["Box.Face6"]["stiffness_above_device"]), ([], False))

    def test_a_stiffness_studys_law_is_reported_as_felt_and_said(self):
        # the summary gave the surface's 0.8 N/mm as felt, with no note, while the probe felt
        # the study's neck: 2.77 N of a 4.44 N/mm neck (held to the device's 3), 1.08 N of a 1.09 one
        doc = App.newDocument("FeelStudy")
        try:
            box = doc.addObject("Part::Box", "Head")
            box.Length, box.Width, box.Height = 40, 20, 10
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="PP", stiffness_n_per_mm=0.8,
                                            FeelRoughness=False)
            surface.Label = "Brush head"
            study = HaptiCAD.make_study(doc, surface, YoungsModulus=1.5, BeamWidth=5, BeamThickness=8,
                                        BeamLength=60)
            study.Label = "Neck study"
            doc.recompute()
            scene = build_document_scene(doc)
            result = run_stroke_in_servo_loop(scene, Stroke((5, 10, 10), (35, 10, 10), depth_mm=0.5))
            most = result.limits.max_stiffness_n_per_m * 1e-3
            self.assertLess(most, study.BendingStiffness)  # 4.44 N/mm on the 3 N/mm probe
            face = summarize(result, scene)["faces"]["Head.Face6"]
            self.assertEqual((face["stiffness_n_per_mm"], face["surface_stiffness_n_per_mm"],
                              face["stiffness_above_device"]), (most, 0.8, True))
            self.assertAlmostEqual(face["mean_normal_force_n"], most * 0.5, delta=1e-3)  # what it says is felt
            self.assertAlmostEqual(face["study_stiffness_n_per_mm"], study.BendingStiffness, places=9)
            # named by the study that governs the face (feel.study_labels, as `hapticad feel` passes them)
            self.assertEqual(feel.study_labels(doc, scene), {"Head.Face6": "Neck study"})
            summary = summarize(result, scene, feel.study_labels(doc, scene))
            self.assertEqual(summary["faces"]["Head.Face6"]["stiffness_study"], "Neck study")
            self.assertEqual(summary["notes"], [
                f"Head.Face6 (Brush head): Neck study's bending beam (4.44 N/mm) replaces the surface's 0.8 N/mm; "
                f"it is above the {most:g} N/mm the device renders stably: it was felt at {most:g} N/mm (0.5 mm deep "
                f"it pushes back with {most * 0.5:.3g} N, not 2.22 N)"])

            study.BeamThickness = 4.0  # 0.56 N/mm: under the device's, felt as designed
            doc.recompute()
            scene = build_document_scene(doc)
            result = run_stroke_in_servo_loop(scene, Stroke((5, 10, 10), (35, 10, 10), depth_mm=1.0))
            summary = summarize(result, scene, feel.study_labels(doc, scene))
            face = summary["faces"]["Head.Face6"]
            self.assertAlmostEqual(face["stiffness_n_per_mm"], study.BendingStiffness, places=9)
            self.assertFalse(face["stiffness_above_device"])
            self.assertAlmostEqual(face["mean_normal_force_n"], study.BendingStiffness, delta=1e-3)
            self.assertEqual(summary["notes"], [
                "Head.Face6 (Brush head): Neck study's bending beam (0.556 N/mm) replaces the surface's 0.8 N/mm"])

            # a push button: its click (0.8 N at 0.4 mm: 2 N/mm, under the device's) felt as designed
            study.Model = "Push button"
            study.OperatingForce, study.Pretravel, study.SnapRatio = 0.8, 0.4, 0.5
            study.SnapTravel, study.TotalTravel = 0.2, 1.0
            doc.recompute()
            scene = build_document_scene(doc)
            result = run_stroke_in_servo_loop(scene, Stroke((5, 10, 10), (35, 10, 10), depth_mm=0.5))
            summary = summarize(result, scene, feel.study_labels(doc, scene))
            face = summary["faces"]["Head.Face6"]
            self.assertAlmostEqual(face["stiffness_n_per_mm"], 2.0, places=9)
            self.assertFalse(face["stiffness_above_device"])
            self.assertEqual(summary["notes"], [
                "Head.Face6 (Brush head): Neck study's push button (operating force 0.8 N at 0.4 mm) replaces the "
                "surface's 0.8 N/mm"])
            study.Pretravel = 0.2  # 4 N/mm to its click: stretched to the device's 3, its forces kept
            doc.recompute()
            scene = build_document_scene(doc)
            result = run_stroke_in_servo_loop(scene, Stroke((5, 10, 10), (35, 10, 10), depth_mm=0.5))
            summary = summarize(result, scene, feel.study_labels(doc, scene))
            face = summary["faces"]["Head.Face6"]
            self.assertEqual((face["stiffness_n_per_mm"], face["stiffness_above_device"]), (most, True))
            self.assertIn("Neck study's push button (operating force 0.8 N at 0.2 mm) replaces the surface's 0.8 "
                          f"N/mm; its steepest slope, 4 N/mm, is above the {most:g} N/mm the device renders stably: "
                          "its forces are kept over a travel 1.3 x longer", summary["notes"][0])
        finally:
            App.closeDocument(doc.Name)

    def test_what_the_feel_panel_says_is_said_for_a_stroke_too(self):
        # `hapticad feel` said nothing of a tagged part hidden behind a Cut (the Feel panel
        # did), nor of a texture clipped at its full range (the surface panel did)
        from hapticad import feel_notes

        doc = App.newDocument("FeelNotes")
        try:
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 40, 20, 10
            hole = doc.addObject("Part::Cylinder", "Hole")
            hole.Radius, hole.Height = 5, 30
            hole.Placement.Base = App.Vector(20, 10, -5)
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False)
            cut = doc.addObject("Part::Cut", "Cut")
            cut.Base, cut.Tool = box, hole
            doc.recompute()
            self.assertEqual(feel_notes.stroke_notes(doc, 1000.0, 3.0, "with --rate"), [])
            box.Visibility = hole.Visibility = False  # as FreeCAD's Cut leaves them
            surface.Texture, surface.TextureDC = "Custom", 1e6
            hidden = "Box is hidden, used by Cut: you feel Box's shape, not what is shown; tag the faces of Cut instead"
            # the Feel panel's: and a texture at its full range all over leaves no force to press with
            limited = (f"{surface.Label}: the texture drags up to 3.00 N at 50-270 mm/s (level 1.00 of the device's "
                       "full range, the 3 N force limit), as much as the 3 N force limit or more")
            session = feel_notes.session_notes(doc, 1000.0, 3.0)
            self.assertEqual(session[1:], [hidden])
            self.assertTrue(session[0].startswith(limited), session[0])
            notes = feel_notes.stroke_notes(doc, 1000.0, 3.0, "with --rate")
            self.assertEqual(notes[:2], session)  # said once
            self.assertEqual(sum(n.startswith(limited) for n in notes), 1)
            self.assertIn(f"{surface.Label}: the texture is at level 1 or more all over at 50-270 mm/s: felt as a "
                          "flat drag at the full range, its ridges clipped", notes)
        finally:
            App.closeDocument(doc.Name)

    def grating_document(self):
        """A 300 mm box whose top carries the paper's f_DC 0.675 f_vis +0.2 on ABS (0.8 N/mm),
        its level 1 the force limit; its scene and the probe's limits under the default 3 N."""
        doc = App.newDocument("FeelTextureHeld")
        self.addCleanup(App.closeDocument, doc.Name)
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 300, 300, 10
        doc.recompute()
        surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False,
                                        Texture="Paper f_DC 0.675 f_vis +0.2")
        surface.Label = "Grating"
        limits = _core.simulated_probe_limits()
        limits.max_force_n = 3.0  # the Preferences' default, as `hapticad feel` holds it (feel.probe_limits)
        return doc, build_document_scene(doc), limits

    def test_a_texture_whose_drag_with_the_press_passed_the_force_limit_is_said_with_what_fits(self):
        # reviewer (make_texture_doc.py, hapticad feel, analyze_cli_grating.py): the paper's f_DC 0.675 f_vis +0.2
        # on ABS under the 3 N limit, pressed 2 mm at 270 mm/s: 41 % of the ticks held to 3 N, the press down to
        # 1.49 N from 1.6, eq. 2's ridges distorted, and "notes": []
        from hapticad import feel_notes

        doc, scene, limits = self.grating_document()
        # said before feeling it, by the Feel panel and `hapticad feel` alike, at the session's limit
        (said,) = feel_notes.session_notes(doc, 1000.0, 3.0)
        self.assertTrue(said.startswith("Grating: the texture drags up to 2.80 N at 50-270 mm/s (level 0.93 of the "
                                        "device's full range, the 3 N force limit), which leaves 1.07 N"), said)
        self.assertEqual([n for n in feel_notes.stroke_notes(doc, 1000.0, 3.0, "with --rate") if "drags" in n],
                         [said])
        result = run_stroke_in_servo_loop(scene, Stroke((150, 20, 10), (150, 100, 10), speed_mm_s=270.0,
                                                        depth_mm=2.0), limits)
        (note,) = summarize(result, scene)["notes"]
        held = re.match(r"Box\.Face6 \(Grating\): (\d+) % of the slide was held to the 3 N force limit: the "
                        r"texture's drag \(up to 2\.80 N\) and the 1\.60 N press passed it together and the whole "
                        r"force was scaled down, the press to as little as 1\.(\d\d) N and the grating's ridges "
                        r"with it; pressed at most 1\.07 N it fits \(or give the texture a smaller Full range\)$",
                        note)
        self.assertIsNotNone(held, note)
        self.assertAlmostEqual(int(held.group(1)), 41, delta=3)
        self.assertAlmostEqual(int(held.group(2)), 49, delta=2)

    def test_a_texture_whose_drag_with_the_press_fits_the_force_limit_says_nothing_of_it(self):
        _, scene, limits = self.grating_document()
        # pressed 1 mm (0.8 N, under the 1.07 N said) it fits: nothing held, nothing said
        result = run_stroke_in_servo_loop(scene, Stroke((150, 20, 10), (150, 100, 10), speed_mm_s=270.0,
                                                        depth_mm=1.0), limits)
        self.assertEqual(summarize(result, scene)["notes"], [])

    def test_a_study_whose_law_is_not_felt_is_said_as_its_controls_say_it(self):
        # a duplicated study (two on one surface) dropped the neck's 0.556 N/mm for the
        # surface's 0.8 N/mm: `hapticad feel` said nothing, the study controls "Not felt: ..."
        from hapticad import feel_notes, stiffness_study

        doc = App.newDocument("FeelStudyNotFelt")
        try:
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 40, 20, 10
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="PP", stiffness_n_per_mm=0.8,
                                            FeelRoughness=False)
            surface.Label = "Head"
            study = HaptiCAD.make_study(doc, surface, YoungsModulus=1.5, BeamWidth=5, BeamThickness=4,
                                        BeamLength=60)
            study.Label = "Neck"
            doc.recompute()
            self.assertEqual(feel_notes.stroke_notes(doc, 1000.0, 3.0, "with --rate"), [])
            copy = doc.copyObject(study, False)  # Edit > Duplicate selection
            doc.recompute()
            self.assertIsNone(stiffness_study.force_travel_of(surface))  # felt at the surface's 0.8 N/mm
            said = [f"{s.Label} is not felt (Head is felt at its own stiffness): "
                    f"{'; '.join(stiffness_study.law_problems(s))}" for s in (study, copy)]
            self.assertEqual(said[0], "Neck is not felt (Head is felt at its own stiffness): Head is also studied by "
                                      f"{copy.Label}: a face gives one way; link another surface")
            self.assertEqual(feel_notes.study_notes(doc), said)
            self.assertEqual(feel_notes.stroke_notes(doc, 1000.0, 3.0, "with --rate"), said)
            self.assertEqual(feel_notes.session_notes(doc, 1000.0, 3.0), [])  # the panel's study controls say it
            doc.removeObject(copy.Name)
            study.Surface = None  # nothing pressed: no surface is felt in its place
            doc.recompute()
            self.assertEqual(feel_notes.study_notes(doc), [
                "Neck is not felt: no surface: link the haptic surface whose faces the participants press"])
        finally:
            App.closeDocument(doc.Name)

    def test_a_surface_whose_part_was_deleted_is_named_with_why(self):
        doc = App.newDocument("FeelDeleted")
        try:
            box = doc.addObject("Part::Box", "Box")
            can = doc.addObject("Part::Cylinder", "Can")
            can.Placement.Base = App.Vector(100, 0, 0)
            doc.recompute()
            HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False)
            grip = HaptiCAD.make_surface(doc, [(can, "Face1")], material="Rubber", FeelRoughness=False)
            grip.Label = "Grip"
            self.assertEqual(feel.skipped_surface_notes(doc), [])
            can.Label = "Handle"
            doc.removeObject("Can")
            doc.recompute()
            self.assertEqual(feel.skipped_surface_notes(doc), [
                "Grip is not felt on Handle, which was deleted: undo the deletion or tag the faces of another part"])
            self.assertEqual(list(build_document_scene(doc).shapes), ["Box"])  # the rest is still felt
        finally:
            App.closeDocument(doc.Name)


if __name__ == "__main__":
    unittest.main()
