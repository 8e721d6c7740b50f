# SPDX-License-Identifier: GPL-3.0-or-later
"""Stiffness studies (seed 000 §3): a bending neck and a push button felt through the
real servo loop, participants' preferences kept with the document, clear errors."""
import csv
import dataclasses
import json
import os
import re
import tempfile
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad import cohort, stiffness_study, study_journal
from hapticad.document_scene import build_document_scene, recompile_surfaces
from hapticad import _core
from hapticad.feel import Stroke, expected_normal_force_n, run_stroke_in_servo_loop


PARTICIPANT = ("Steven", "M", "26-40", 70, 1700)


def pressed_normal_force(doc, depth_mm, start=(20, 20, 10)):
    """Mean normal force while the simulated probe holds ``depth_mm`` deep at a point."""
    scene = build_document_scene(doc)
    p0 = np.asarray(start, float)
    stroke = Stroke(tuple(p0), tuple(p0 + [0.01, 0, 0]), speed_mm_s=25.0, depth_mm=depth_mm, rate_hz=1000)
    result = run_stroke_in_servo_loop(scene, stroke)
    trace, plan = result.trace, result.plan
    held = (trace["time_s"] > plan.slide_start_s - 0.05) & (trace["time_s"] < plan.slide_start_s)
    return float(np.mean(trace["normal_force_n"][held]))


class StudyTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("StudyTest")
        self.box = self.doc.addObject("Part::Box", "Head")
        self.box.Length, self.box.Width, self.box.Height = 40, 40, 10
        self.doc.recompute()
        self.head = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="PP", FeelRoughness=False)

    def tearDown(self):
        # records left unsaved are journaled in the test's home, and written again as the document closes
        paths = {study_journal.path_for(s) for s in HaptiCAD.studies_of(self.doc)} - {None}
        App.closeDocument(self.doc.Name)
        for path in paths:
            if os.path.exists(path):
                os.remove(path)

    def test_a_toothbrush_neck_gives_its_bending_stiffness(self):
        study = HaptiCAD.make_study(self.doc, self.head, YoungsModulus=1.5, BeamWidth=5, BeamThickness=4,
                                    BeamLength=60)
        self.assertAlmostEqual(study.BendingStiffness, 0.5556, places=4)  # the field notes' toothbrush
        self.assertEqual(stiffness_study.validate(study), [])
        # pressed 1 mm, the head pushes back with the neck's 0.56 N, not the plastic's 0.8
        self.assertAlmostEqual(pressed_normal_force(self.doc, 1.0), 0.5556, delta=0.01)
        # and `hapticad feel`'s summary expects what the neck gives, not the plastic
        scene = build_document_scene(self.doc)
        face = scene.face_id("Head.Face6")
        self.assertAlmostEqual(expected_normal_force_n(scene, face, _core.simulated_probe_limits(), 1.0), 0.5556,
                               places=3)
        study.BeamThickness = 6  # k goes with h^3
        self.doc.recompute()
        self.assertAlmostEqual(study.BendingStiffness, 27 / 8 * 0.5556, places=3)
        self.assertAlmostEqual(pressed_normal_force(self.doc, 0.5), 0.5 * 27 / 8 * 0.5556, delta=0.02)
        self.assertEqual(stiffness_study.device_note(study, 3000.0), "")
        # 8 mm: 4.4 N/mm, more than the simulated probe's 3 N/mm: felt at the device's limit, and said so
        study.BeamThickness = 8
        self.doc.recompute()
        self.assertAlmostEqual(pressed_normal_force(self.doc, 0.5), 0.5 * 3.0, delta=0.02)
        self.assertIn("4.44 N/mm, is more than the device renders stably (3 N/mm)",
                      stiffness_study.device_note(study, 3000.0))

    def test_the_beams_material_sets_its_modulus(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        study.BeamMaterial = "ABS"
        self.assertAlmostEqual(study.YoungsModulus, 2.3)
        self.assertAlmostEqual(study.BendingStiffness, 0.5556 * 2.3 / 1.5, places=3)
        self.assertEqual(stiffness_study.material_override(study), "")
        # a modulus typed in by hand: the material's name stays, and the study says it no longer holds
        study.YoungsModulus = 1.8
        self.assertEqual(stiffness_study.material_override(study), "E 1.8 GPa, not ABS's 2.3 GPa")
        study.BeamMaterial = "PP"  # choosing a material again sets its modulus
        self.assertEqual(stiffness_study.material_override(study), "")

    def test_a_push_button_snaps_and_bottoms_out_on_its_housing(self):
        # slopes the simulated probe renders (2 N/mm, under its 3): 0.8 N at 0.4 mm, halved by 0.6 mm
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button", OperatingForce=0.8, Pretravel=0.4,
                                    SnapRatio=0.5, SnapTravel=0.2, TotalTravel=1.0)
        self.assertEqual(study.Adjust, "OperatingForce")  # the slider follows the model
        scene = build_document_scene(self.doc)
        law = scene.surface_properties(scene.face_id("Head.Face6")).force_travel
        self.assertAlmostEqual(law.force(0.4e-3), 0.8)
        self.assertAlmostEqual(law.force(0.6e-3), 0.4)
        # the housing, 50 N/mm, not the face's material (0.8 N/mm: after the click, mush)
        self.assertAlmostEqual(law.force(1.0e-3 + 1e-4) - law.force(1.0e-3), 50.0 * 1e3 * 1e-4)
        self.assertAlmostEqual(law.stretch_slope(), 2000.0)  # what a soft device stretches: the click
        # on the way down to 1.5 mm, the probe felt the operating force, then the snap
        stroke = Stroke((20, 20, 10), (20.01, 20, 10), speed_mm_s=5.0, depth_mm=1.5)
        result = run_stroke_in_servo_loop(scene, stroke)
        fn = result.trace["normal_force_n"][result.trace["time_s"] < result.plan.slide_start_s]
        highest = np.maximum.accumulate(fn)
        snap = int(np.argmax(highest - fn > 0.2))  # the first tick 0.2 N below the highest so far
        self.assertGreater(snap, 0, "the force never dropped")
        self.assertAlmostEqual(highest[snap], 0.8, delta=0.03)  # the operating force, then the drop
        self.assertLess(fn[snap:].min(), 0.45)
        # bottomed out: 0.5 mm on the housing, at the probe's 3 N/mm (its stable stiffness)
        self.assertAlmostEqual(fn[-1], 0.8 + 3.0 * 0.5, delta=0.03)
        self.assertEqual(stiffness_study.device_note(study, 3000.0), "")  # the housing stretches nothing
        study.HousingStiffness = 0.8  # a soft housing is felt as soft as it is
        scene = build_document_scene(self.doc)
        result = run_stroke_in_servo_loop(scene, stroke)
        self.assertAlmostEqual(result.trace["normal_force_n"][result.trace["time_s"] < result.plan.slide_start_s][-1],
                               0.8 + 0.8 * 0.5, delta=0.03)
        study.OperatingForce = 1.47  # Omron B3F's: 5.9 N/mm to the operating point
        self.assertIn("the button's steepest slope", stiffness_study.device_note(study, 3000.0))

    def test_a_button_whose_click_lies_above_the_force_limit_says_so(self):
        # the preferences' 3 N limit against a 4.5 N button: the force stops at 3 N and the
        # click never comes, though the slider offers up to 5 N
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button", OperatingForce=4.5)
        note = stiffness_study.force_note(study, 3.0)
        self.assertIn("the operating force, 4.5 N, is above the force limit, 3 N", note)
        self.assertIn("raise the force limit", note)
        self.assertEqual(stiffness_study.force_note(study, 5.0), "")
        study.OperatingForce = 2.55
        self.assertEqual(stiffness_study.force_note(study, 3.0), "")
        study.Model = "Bending beam"  # a neck's force is the hand's press, not the design's
        self.assertEqual(stiffness_study.force_note(study, 0.1), "")

    def test_a_button_heavier_than_a_one_finger_trigger_should_be_says_so(self):
        # seed 000 §1: under 2 kg for one finger, 4 kg for two; the field notes: 2 lb likely
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button", OperatingForce=4.9)  # B3F's heaviest
        self.assertEqual(stiffness_study.ergonomic_note(study), "")
        study.OperatingForce = 12.0
        note = stiffness_study.ergonomic_note(study)
        self.assertIn("12 N, is above the widely cited one-finger trigger limit of 2 lb (8.9 N)", note)
        self.assertIn("under seed 000's 2 kg (19.6 N)", note)
        study.OperatingForce = 45.0
        self.assertIn("above even the 4 kg (39.2 N)", stiffness_study.ergonomic_note(study))
        study.Model = "Bending beam"  # a neck is not a trigger
        self.assertEqual(stiffness_study.ergonomic_note(study), "")

    def test_a_study_that_cannot_hold_says_why_and_the_face_keeps_its_stiffness(self):
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button")
        study.TotalTravel = 0.3  # less than pretravel and snap
        self.assertIn("push button: total travel must exceed pretravel plus snap travel",
                      stiffness_study.validate(study))
        self.assertIsNone(stiffness_study.force_travel_of(self.head))
        self.assertAlmostEqual(pressed_normal_force(self.doc, 1.0), 0.8, delta=0.02)  # PP's 0.8 N/mm
        with self.assertRaises(ValueError) as caught:
            HaptiCAD.make_study(self.doc, self.head)
        self.assertIn("already studied by", str(caught.exception))
        other = self.doc.addObject("App::FeaturePython", "Other")
        stiffness_study.StiffnessStudy(other)
        other.Surface = self.head
        self.assertTrue(any("also studied by" in p for p in stiffness_study.validate(other)))
        other.Surface = self.box
        self.assertIn("Head is not a haptic surface", stiffness_study.validate(other))
        with self.assertRaises(ValueError):
            HaptiCAD.make_study(self.doc, self.box)

    def test_the_expression_bound_to_the_sliders_parameter_is_told(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        self.assertIsNone(stiffness_study.adjust_expression(study))
        study.setExpression("BeamThickness", "BeamWidth - 1")
        self.doc.recompute()
        self.assertEqual(stiffness_study.adjust_expression(study), "BeamWidth - 1")
        self.assertAlmostEqual(study.BeamThickness, study.BeamWidth - 1)
        study.Adjust = "BeamLength"  # another parameter, not bound
        self.assertIsNone(stiffness_study.adjust_expression(study))
        self.assertEqual(stiffness_study.expression_of(study, "BeamThickness"), "BeamWidth - 1")

    def test_a_slider_problem_does_not_take_the_law_off_the_face(self):
        study = HaptiCAD.make_study(self.doc, self.head, YoungsModulus=1.5, BeamThickness=4)
        study.AdjustMin, study.AdjustMax = 8.0, 2.0
        self.assertIn("the slider's range 8..2 is empty", stiffness_study.validate(study))
        self.assertEqual(stiffness_study.law_problems(study), [])
        self.assertAlmostEqual(stiffness_study.force_travel_of(self.head).max_slope(), 555.6, delta=0.1)
        with self.assertRaises(ValueError):  # but nobody records on a study that is not right
            HaptiCAD.record_preference(study, *PARTICIPANT)
        # a surface whose faces are gone leaves nothing to press: said, and no law
        self.head.References = []
        self.assertTrue(any("tags no face" in p for p in stiffness_study.law_problems(study)))
        self.assertIsNone(stiffness_study.force_travel_of(self.head))

    def test_preferences_are_kept_with_the_document(self):
        study = HaptiCAD.make_study(self.doc, self.head, YoungsModulus=1.5, BeamThickness=4)
        record = HaptiCAD.record_preference(study, *PARTICIPANT)
        self.assertAlmostEqual(record.value, study.BendingStiffness)
        self.assertEqual((record.unit, record.design["BeamThickness"]), ("N/mm", 4.0))
        study.BeamThickness = 6
        HaptiCAD.record_preference(study, "Zhang", "F", "26-40", 52, 1650)
        with self.assertRaises(ValueError) as caught:
            HaptiCAD.record_preference(study, "Yang", "M", "41-60", 5, 1680)
        self.assertIn("weight 5", str(caught.exception))
        self.assertEqual(study.Participants, 2)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "study.FCStd")
            self.doc.saveAs(path)
            name = self.doc.Name
            App.closeDocument(name)
            self.doc = App.openDocument(path)
            (study,) = HaptiCAD.studies_of(self.doc)
            kept = stiffness_study.records(study)
            self.assertEqual([r.name for r in kept], ["Steven", "Zhang"])
            # the document does not save the ranges: restored, they hold again
            study.BeamThickness = -3
            study.BeamLength = 0
            self.assertGreater(study.BeamThickness, 0)
            self.assertGreater(study.BeamLength, 0)
            study.BeamThickness = 6
            self.assertAlmostEqual(kept[1].value, 0.5556 * 27 / 8, places=3)
            self.assertEqual(study.Participants, 2)
            # exported and imported into another study of the same kind
            csv_path = os.path.join(tmp, "cohort.csv")
            cohort.write_csv(csv_path, kept)
            stiffness_study.remove_record(study, 0)
            self.assertEqual([r.name for r in stiffness_study.records(study)], ["Zhang"])
            # Zhang is held already: only Steven comes back, once
            self.assertEqual(stiffness_study.import_records(study, csv_path), (1, 1, 0))
            self.assertEqual([r.name for r in stiffness_study.records(study)], ["Zhang", "Steven"])
            self.assertEqual(study.Participants, 2)
            study.Model = "Push button"
            # its own beam records come back as held: nothing added, nothing refused
            self.assertEqual(stiffness_study.import_records(study, csv_path), (0, 2, 0))
            self.assertEqual(study.Participants, 2)
            # but a beam's cohort into a button study holding none is another study's: refused
            button = HaptiCAD.make_study(self.doc, HaptiCAD.make_surface(
                self.doc, [(self.doc.getObject("Head"), "Face1")]), model="Push button")
            with self.assertRaises(ValueError) as caught:
                stiffness_study.import_records(button, csv_path)
            self.assertIn("2 record(s) are in N/mm (a bending beam's bending stiffness), this study's preferences "
                          "in N", str(caught.exception))
            self.assertEqual(button.Participants, 0)
            # the beam's records stay, but a button's preferences are not compared with them
            self.assertEqual(stiffness_study.comparable_records(study), [])
            HaptiCAD.record_preference(study, "Yang", "M", "41-60", 60, 1680)
            self.assertEqual([r.unit for r in stiffness_study.comparable_records(study)], ["N"])
            study.Adjust = "SnapRatio"  # a button whose snap the participants choose records the snap
            self.assertEqual(stiffness_study.design_value(study), (study.SnapRatio, "snap ratio"))

    def test_one_persons_second_session_is_one_participant_and_old_documents_are_recounted(self):
        study = HaptiCAD.make_study(self.doc, self.head, BeamThickness=4)
        HaptiCAD.record_preference(study, *PARTICIPANT)
        first = study.BendingStiffness
        study.BeamThickness = 6
        HaptiCAD.record_preference(study, "Zhang", "F", "26-40", 52, 1650)
        HaptiCAD.record_preference(study, "steven", "M", "26-40", 71, 1700)  # his second session
        self.assertEqual(study.Participants, 2)
        (everyone, *_) = cohort.statistics(stiffness_study.comparable_records(study))
        self.assertEqual((everyone["n"], everyone["records"]), (2, 3))
        self.assertAlmostEqual(everyone["mean"], ((first + study.BendingStiffness) / 2 + study.BendingStiffness) / 2)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "study.FCStd")
            study.Participants = 3  # what a document saved when it counted records holds
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            (study,) = HaptiCAD.studies_of(self.doc)
            self.assertEqual(study.Participants, 2)

    def test_the_cohorts_preference_ranges_hold_what_the_button_model_can_record(self):
        # cohort cannot import the model (it is imported by it): the ranges are checked here
        ranges = {p[0]: p[5][:2] for p in stiffness_study.PROPERTIES if p[5]}
        self.assertEqual(cohort.PREFERENCE_RANGES["N"], ranges["OperatingForce"])
        self.assertEqual(cohort.PREFERENCE_RANGES["snap ratio"], ranges["SnapRatio"])
        # the field notes' toothbrush and Table 3's 4.5 N/mm are plausible beams
        low, high = cohort.PREFERENCE_RANGES["N/mm"]
        self.assertTrue(low < 0.5556 < 4.5 < high)

    def test_reimporting_the_own_export_adds_nobody_and_a_repeated_row_is_taken_once(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        for name in ("=1+1", "-Neg", "+plus", "@at", "Ann"):
            HaptiCAD.record_preference(study, name, "F", "18-25", None, None, 3000.0)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cohort.csv")
            cohort.write_csv(path, stiffness_study.records(study))
            self.assertEqual(stiffness_study.import_records(study, path), (0, 5, 0))
            self.assertEqual(study.Participants, 5)
            # into another study: the design comes back as numbers, so nobody is starred beyond the device
            other_doc = App.newDocument("StudyTestOther")
            try:
                box = other_doc.addObject("Part::Box", "Head")
                other_doc.recompute()
                other = HaptiCAD.make_study(other_doc, HaptiCAD.make_surface(other_doc, [(box, "Face6")]))
                self.assertEqual(stiffness_study.import_records(other, path), (5, 0, 0))
                self.assertEqual([r.design for r in stiffness_study.records(other)],
                                 [r.design for r in stiffness_study.records(study)])
                self.assertEqual([cohort.beyond_device(r) for r in stiffness_study.records(other)], [False] * 5)
            finally:
                App.closeDocument(other_doc.Name)
            # a file listing a row twice: one participant, and said
            with open(path) as handle:
                lines = handle.readlines()
            with open(path, "w") as handle:
                handle.writelines(lines + lines[-1:])
            stiffness_study.remove_record(study, 4)  # Ann
            self.assertEqual(stiffness_study.import_records(study, path), (1, 4, 1))
            self.assertEqual([r.name for r in stiffness_study.records(study)], ["=1+1", "-Neg", "+plus", "@at", "Ann"])
            # a bad line adds nothing
            with open(path, "a") as handle:
                handle.write("Zed,M,18-25,70,1700,1e308,N/mm,Bending beam,,\n")
            with self.assertRaises(ValueError) as caught:
                stiffness_study.import_records(study, path)
            self.assertIn("line 8, column value (F): the preferred value 1e+308 N/mm is outside", str(caught.exception))
            self.assertEqual(study.Participants, 5)

    def test_an_import_keeps_namesakes_apart_and_a_spreadsheets_save_adds_nobody(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        with tempfile.TemporaryDirectory() as tmp:
            # two people of one name and one preferred value: two participants, not one
            two = os.path.join(tmp, "two_wangs.csv")
            with open(two, "w") as handle:
                handle.write("name,gender,age_band,weight_kg,height_mm,value,unit\n"
                             "Wang,M,26-40,70,1750,3.5,N/mm\nWang,F,41-60,55,1600,3.5,N/mm\n"
                             "Wang,F,41-60,55,,3.5,N/mm\nLi,F,18-25,50,1620,2.5,N/mm\n")
            self.assertEqual(stiffness_study.import_records(study, two), (4, 0, 0))
            self.assertEqual([(r.gender, r.height_mm) for r in stiffness_study.records(study)],
                             [("M", 1750.0), ("F", 1600.0), ("F", None), ("F", 1620.0)])
            self.assertEqual(stiffness_study.import_records(study, two), (0, 4, 0))
            # an export saved back by a spreadsheet, its numbers rounded to 15 significant digits
            for i, h in enumerate((3.0, 3.7, 4.1, 5.3, 6.2)):
                study.BeamThickness = h
                HaptiCAD.record_preference(study, f"P{i}", "F", "18-25", 60.7, 1650)
            exported = os.path.join(tmp, "cohort.csv")
            cohort.write_csv(exported, stiffness_study.records(study))
            with open(exported, newline="") as handle:
                rows = list(csv.DictReader(handle))
            self.assertTrue(any(len(r["value"].replace(".", "").lstrip("0")) > 15 for r in rows))  # 16 digits
            saved = os.path.join(tmp, "sheet.csv")
            with open(saved, "w", newline="") as handle:
                out = csv.DictWriter(handle, fieldnames=list(rows[0]))
                out.writeheader()
                for r in rows:
                    out.writerow(dict(r, value=f"{float(r['value']):.15g}", weight_kg=r["weight_kg"] and
                                      f"{float(r['weight_kg']):.15g}"))
            self.assertEqual(stiffness_study.import_records(study, saved), (0, 9, 0))
            # nine records of eight people: the Wang F 41-60 without a height is her second session
            self.assertEqual((len(stiffness_study.records(study)), study.Participants), (9, 8))

    def test_a_button_whose_slider_moved_another_parameter_keeps_says_and_round_trips_its_records(self):
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button")
        for i, force in enumerate((1.0, 1.5, 2.5)):
            study.OperatingForce = force
            HaptiCAD.record_preference(study, f"Op{i}", "M", "26-40", None, None)
        self.assertEqual(stiffness_study.others_note(study), "")
        study.Adjust = "SnapRatio"
        HaptiCAD.record_preference(study, "Snap0", "F", "26-40", None, None)
        self.assertEqual(len(stiffness_study.comparable_records(study)), 1)
        # what differs is the slider's parameter, not the model; and Participants counts all four
        self.assertEqual(stiffness_study.others_note(study),
                         "3 recorded while the slider moved the operating force (N) are kept but not compared with "
                         "the snap ratio; the study's Participants (4) counts everyone with a record, of any unit")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "export.csv")
            cohort.write_csv(path, stiffness_study.records(study))  # what Export CSV... writes
            self.assertEqual(stiffness_study.import_records(study, path), (0, 4, 0))
            self.assertEqual(study.Participants, 4)
            other_doc = App.newDocument("StudyTestButton")
            try:
                box = other_doc.addObject("Part::Box", "Cap")
                other_doc.recompute()
                other = HaptiCAD.make_study(other_doc, HaptiCAD.make_surface(other_doc, [(box, "Face6")]),
                                            model="Push button")
                self.assertEqual(stiffness_study.import_records(other, path), (4, 0, 0))
                self.assertEqual(len(stiffness_study.comparable_records(other)), 3)  # by operating force
                self.assertIn("1 recorded while the slider moved the snap ratio is kept",
                              stiffness_study.others_note(other))
            finally:
                App.closeDocument(other_doc.Name)
        study.Model = "Bending beam"
        self.assertEqual(stiffness_study.others_note(study),
                         "3 made with the push button model (N), 1 made with the push button model (snap ratio) are "
                         "kept but not compared with the bending stiffness; the study's Participants (4) counts "
                         "everyone with a record, of any unit")

    def test_the_slider_takes_the_range_of_what_it_moves_however_that_is_chosen(self):
        self.doc.UndoMode = 1
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button")
        study.Adjust = "SnapRatio"  # a script, or the property editor
        self.assertEqual((study.AdjustMin, study.AdjustMax), (0.2, 0.8))
        study.AdjustMin, study.AdjustMax = 0.3, 0.6  # a range of one's own
        study.Adjust = "SnapRatio"  # chosen again: kept
        self.assertEqual((study.AdjustMin, study.AdjustMax), (0.3, 0.6))
        self.doc.openTransaction("slider")
        study.Adjust = "OperatingForce"
        self.doc.commitTransaction()
        self.assertEqual((study.AdjustMin, study.AdjustMax), (0.5, 5.0))
        self.assertEqual(stiffness_study.validate(study), [])
        self.doc.undo()  # the range comes back with what the slider moved, not reset by the undo
        self.assertEqual((study.Adjust, study.AdjustMin, study.AdjustMax), ("SnapRatio", 0.3, 0.6))
        study.Model = "Bending beam"
        self.assertEqual((study.Adjust, study.AdjustMin, study.AdjustMax), ("BeamThickness", 2.0, 8.0))
        # made with a range of its own, in any order of the keywords
        made = HaptiCAD.make_study(self.doc, HaptiCAD.make_surface(self.doc, [(self.box, "Face1")]),
                                   AdjustMin=40.0, AdjustMax=100.0, Adjust="BeamLength")
        self.assertEqual((made.Adjust, made.AdjustMin, made.AdjustMax), ("BeamLength", 40.0, 100.0))
        with tempfile.TemporaryDirectory() as tmp:  # a reopened document keeps its range
            path, name = os.path.join(tmp, "range.FCStd"), made.Name
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            made = self.doc.getObject(name)
            self.assertEqual((made.Adjust, made.AdjustMin, made.AdjustMax), ("BeamLength", 40.0, 100.0))

    def test_make_study_keeps_every_value_given_in_any_order(self):
        # the model set after the slider's range gave the slider another parameter and reset its range to that
        # one's default (AdjustMin 1 became 0.5); the material set after the modulus reset the modulus to its own
        import itertools

        cases = [{"AdjustMin": 1.0, "AdjustMax": 3.0, "Model": stiffness_study.BUTTON},
                 {"YoungsModulus": 2.0, "BeamMaterial": "ABS"},
                 {"AdjustMin": 0.3, "AdjustMax": 0.6, "Adjust": "SnapRatio", "Model": stiffness_study.BUTTON},
                 {"AdjustMin": 3.0, "AdjustMax": 5.0, "Adjust": "BeamThickness", "BeamMaterial": "ABS",
                  "YoungsModulus": 1.8}]
        for case in cases:
            for order in itertools.permutations(case):
                given = {key: case[key] for key in order}
                study = HaptiCAD.make_study(self.doc, self.head, **given)
                self.assertEqual({key: getattr(study, key) for key in given}, given, f"given in the order {order}")
                self.doc.removeObject(study.Name)
        study = HaptiCAD.make_study(self.doc, self.head, model=stiffness_study.BUTTON, AdjustMin=1.0, AdjustMax=3.0)
        self.assertEqual((study.Adjust, study.AdjustMin, study.AdjustMax), ("OperatingForce", 1.0, 3.0))
        self.doc.removeObject(study.Name)
        # what cannot be as given is refused, saying why, and nothing is added (FreeCAD clamped 5000 GPa to
        # 1000 unsaid; the computed stiffness was overwritten unsaid; a slider parameter the model does not use
        # was replaced by the model's first)
        for given, said in (({"YoungsModulus": 5000.0}, "YoungsModulus 5000 GPa is outside 0.001..1000 GPa"),
                            ({"BeamThickness": float("nan")}, "BeamThickness nan is not a finite number"),
                            ({"BendingStiffness": 3.0}, "not to be given: BendingStiffness (it is computed from"),
                            ({"Participants": 3}, "Participants (it counts the participants recorded)"),
                            ({"Surface": self.head}, "give the surface as make_study's second argument"),
                            ({"Adjust": "BeamLength", "Model": stiffness_study.BUTTON},
                             "the push button model's slider moves OperatingForce, SnapRatio, not 'BeamLength'"),
                            ({"model": stiffness_study.BEAM, "Model": stiffness_study.BUTTON},
                             "model 'Bending beam' and Model 'Push button' differ: give one")):
            with self.assertRaises(ValueError) as caught:
                HaptiCAD.make_study(self.doc, self.head, **given)
            self.assertIn(said, str(caught.exception))
            self.assertEqual(HaptiCAD.studies_of(self.doc), [])

    def test_stiffnesses_in_n_per_m_given_as_n_per_mm_are_refused_and_the_products_own_are_not(self):
        # 400 and 800 (N/m: 0.4 and 0.8 N/mm) under N/mm passed, 1000 N/mm being the plausible top; the toothbrush's
        # slider over h 2-8 mm makes 0.0694-4.44 N/mm
        def cohort_file(name, *values, design=None):
            path = os.path.join(tmp, name)
            cohort.write_csv(path, [cohort.Record(who, "F", "26-40", None, None, value, "N/mm", stiffness_study.BEAM,
                                                  dict(design or {}), f"2026-11-24T10:0{i}:00")
                                    for i, (who, value) in enumerate(zip(("Ann", "Bo", "Cy"), values))])
            return path

        def fresh_study():
            for made in HaptiCAD.studies_of(self.doc):
                self.doc.removeObject(made.Name)
            return HaptiCAD.make_study(self.doc, self.head)

        with tempfile.TemporaryDirectory() as tmp:
            study = fresh_study()
            with self.assertRaises(ValueError) as caught:
                stiffness_study.import_records(study, cohort_file("per_m.csv", 400.0, 800.0))
            self.assertIn("per_m.csv: 2 preferences given in N/mm (Ann 400, Bo 800) are over 30 times the stiffest "
                          "this study makes or holds (4.44 N/mm; its slider over the thickness h 2-8 mm makes "
                          "0.0694-4.44 N/mm): are they in N/m? As N/mm they are 0.4, 0.8: divide the value column by "
                          "1000 and import again (if they are N/mm, widen the slider's range to reach them)",
                          str(caught.exception))
            self.assertEqual((stiffness_study.records(study), study.Participants), ([], 0))
            with self.assertRaises(ValueError) as caught:
                stiffness_study.import_records(study, cohort_file("one.csv", 4.5, 500.0))
            self.assertIn("1 preference given in N/mm (Bo 500) is over 30 times", str(caught.exception))
            self.assertIn("is it in N/m? As N/mm it is 0.5: divide", str(caught.exception))
            self.assertEqual(stiffness_study.records(study), [])  # not Ann's 4.5 either
            self.assertEqual(stiffness_study.import_records(study, cohort_file("per_mm.csv", 0.4, 0.8)), (2, 0, 0))
            # the product's own cohorts are not refused: typed by hand, 22 times the slider's stiffest (and Table
            # 3's 4.5 N/mm); exported by a study of a design set beyond the slider (h 30 mm: 234 N/mm), its design
            # holding the value it computed
            study = fresh_study()
            self.assertEqual(stiffness_study.import_records(study, cohort_file("stiff.csv", 100.0, 4.5)), (2, 0, 0))
            study = fresh_study()
            study.BeamThickness = 30.0
            HaptiCAD.record_preference(study, "Dan", "M", "26-40", None, None)
            self.assertAlmostEqual(stiffness_study.records(study)[0].value, 0.5556 * 7.5 ** 3, delta=0.1)
            export = os.path.join(tmp, "export.csv")
            cohort.write_csv(export, stiffness_study.records(study))
            study = fresh_study()
            self.assertEqual(stiffness_study.import_records(study, export), (1, 0, 0))
            # and a slider widened to reach a stiffer product takes its cohort (h 2-20 mm: up to 69.4 N/mm)
            study = fresh_study()
            study.AdjustMax = 20.0
            self.assertEqual(stiffness_study.import_records(study, cohort_file("per_m.csv", 400.0, 800.0)), (2, 0, 0))

    def test_the_slider_ends_say_what_they_do_to_the_design(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        for adjust, ends in (("BeamThickness", ("softer", "stiffer")), ("BeamLength", ("stiffer", "softer"))):
            study.Adjust = adjust
            self.assertEqual(stiffness_study.slider_ends(study), ends)
        study.Model = "Push button"
        self.assertEqual(stiffness_study.slider_ends(study), ("lighter", "heavier"))
        study.Adjust = "SnapRatio"
        self.assertEqual(stiffness_study.slider_ends(study), ("less snap", "more snap"))

    def test_a_value_typed_is_read_with_its_unit_and_refused_outside_its_range(self):
        for name, text, value in (("BeamLength", "6 cm", 60.0), ("BeamLength", "60", 60.0),
                                  ("BeamThickness", "4,5", 4.5), ("BeamThickness", "4.5 mm", 4.5),
                                  ("YoungsModulus", "1500 MPa", 1.5), ("YoungsModulus", "2", 2.0),
                                  ("OperatingForce", "150 gf", 1.4709975), ("OperatingForce", "0.1 kgf", 0.980665),
                                  ("OperatingForce", "1 lbf", 4.44822), ("SnapRatio", "0.7", 0.7)):
            with self.subTest(name=name, text=text):
                self.assertAlmostEqual(stiffness_study.typed_value(name, text), value)
        for name, text, message in (
                ("YoungsModulus", "1500", "E: 1500 GPa is outside 0.001..1000 GPa: in MPa? give 1500 MPa"),
                ("BeamLength", "3 m", "L: 3000 mm is outside 1..2000 mm"),
                ("BeamLength", "5 kg", "L: '5 kg' is a mass, not a length"),
                ("BeamLength", "1,000", "is '1,000' 1000 or 1.000?"),
                ("BeamLength", "abc", "'abc' is not a value FreeCAD reads"),
                ("BeamLength", " ", "give a value in mm"),
                ("SnapRatio", "1.5", "ratio: 1.5 is outside 0.01..0.99"),
                ("SnapRatio", "5 mm", "'5 mm' is a length, not a plain number")):
            with self.subTest(name=name, text=text):
                with self.assertRaises(ValueError) as caught:
                    stiffness_study.typed_value(name, text, {"YoungsModulus": "E", "BeamLength": "L",
                                                             "SnapRatio": "ratio"}[name])
                self.assertIn(message, str(caught.exception))

    def test_the_study_judges_by_the_stiffness_a_feel_session_renders(self):
        from hapticad import feel_session, preferences

        study = HaptiCAD.make_study(self.doc, self.head, model="Push button", OperatingForce=0.8, Pretravel=0.4,
                                    SnapRatio=0.5, SnapTravel=0.2, TotalTravel=1.0)
        self.doc.recompute()
        scene = build_document_scene(self.doc)
        base = preferences.load()
        # a device through the workspace mapping (2 model mm per device mm, or fitted): what it renders is felt at
        # the handle, as a session holds it
        for prefs in (dataclasses.replace(base, **{"device": "simulated"}),
                      dataclasses.replace(base, **{"device": "sim:hand",
                                                 "workspace_mapping": "Fixed scale", "workspace_scale": 2.0}),
                      dataclasses.replace(base, **{"device": "sim:hand",
                                                 "workspace_mapping": "Fit part"})):
            with self.subTest(device=prefs.device, mapping=prefs.workspace_mapping):
                session = feel_session.LiveSession(scene, device=prefs.device, prefs=prefs)
                try:
                    rendered = session.render_limits.max_stiffness_n_per_m
                finally:
                    session.stop()
                self.assertAlmostEqual(stiffness_study.device_stiffness_n_per_m(self.doc, prefs), rendered)
        scaled = dataclasses.replace(base, **{"device": "sim:hand", "workspace_mapping": "Fixed scale",
                                            "workspace_scale": 2.0})
        k = stiffness_study.device_stiffness_n_per_m(self.doc, scaled)
        # the scale stretches the part, not what is felt: the device's own 3 N/mm at the handle
        self.assertAlmostEqual(k, _core.simulated_hand_limits().max_stiffness_n_per_m)
        # 2 N/mm to the operating point: within the 3 N/mm felt at the handle whatever the scale: not marked
        record = HaptiCAD.record_preference(study, *PARTICIPANT, k)
        self.assertEqual((record.design["DeviceStiffness"], cohort.beyond_device(record)), (k * 1e-3, False))
        self.assertEqual(stiffness_study.device_note(study, _core.simulated_hand_limits().max_stiffness_n_per_m), "")
        # a device of 1.5 N/mm does not hold it: marked so
        record = HaptiCAD.record_preference(study, "Yang", "F", "41-60", 60, 1600, k / 2)
        self.assertEqual((record.design["DeviceStiffness"], cohort.beyond_device(record)), (k / 2 * 1e-3, True))

    def test_the_study_judges_by_the_force_a_feel_session_renders(self):
        from hapticad import feel_session, preferences

        HaptiCAD.make_study(self.doc, self.head, model="Push button")
        self.doc.recompute()
        scene = build_document_scene(self.doc)
        base = preferences.load()
        hand = _core.simulated_hand_limits().max_force_n  # 8.9 N
        # the Preferences' limit under the device's own, as a session renders it: 20 N in the Preferences is the
        # hand's 8.9 N, 3 N is 3 N, through the workspace mapping too (it scales travel, not force)
        for device, mapping in (("simulated", "Fit part"), ("sim:hand", "Fixed scale"), ("sim:hand", "Fit part")):
            for limit in (3.0, 20.0):
                prefs = dataclasses.replace(base, device=device, workspace_mapping=mapping, workspace_scale=2.0,
                                            force_limit_n=limit)
                with self.subTest(device=device, mapping=mapping, limit=limit):
                    session = feel_session.LiveSession(scene, device=device, prefs=prefs)
                    try:
                        rendered = session.render_limits.max_force_n
                    finally:
                        session.stop()
                    limits = stiffness_study.device_render_limits(self.doc, prefs)
                    self.assertTrue(limits[1])
                    self.assertEqual(stiffness_study.rendered_force_limit_n(limits, limit), rendered)
                    self.assertAlmostEqual(rendered, min(hand, limit))
                    self.assertEqual(limits[0].max_stiffness_n_per_m,
                                     stiffness_study.device_stiffness_n_per_m(self.doc, prefs))
        # a device not connected now: its limit is not known, the Preferences' alone is said (its stiffness the
        # simulated hand's, as before)
        absent = dataclasses.replace(base, device="hid:not-connected", force_limit_n=20.0)
        limits = stiffness_study.device_render_limits(self.doc, absent)
        self.assertFalse(limits[1])
        self.assertEqual(stiffness_study.rendered_force_limit_n(limits, 20.0), 20.0)
        self.assertEqual(stiffness_study.device_stiffness_n_per_m(self.doc, absent),
                         _core.simulated_hand_limits().max_stiffness_n_per_m)

    def test_a_stored_implausible_preference_is_still_summarised(self):
        # saved before the range was checked: the study still gives its statistics (the CLI, the panel)
        study = HaptiCAD.make_study(self.doc, self.head)
        HaptiCAD.record_preference(study, *PARTICIPANT)
        data = json.loads(study.Cohort)
        data.append(dict(data[0], name="Zed", value=1e308))
        data.append(dict(data[0], name="Yan", value=1.5e308))
        study.Cohort = json.dumps(data)
        held = stiffness_study.comparable_records(study)
        self.assertEqual(cohort.statistics(held)[0]["n"], 3)
        self.assertIn("of the 3 participants", cohort.place_design(1.0, held)[1])
        self.assertIn("outside the plausible", cohort.problems(held[1])[0])

    def test_a_stored_record_that_cannot_be_read_is_named_and_left_out_of_the_summary(self):
        # a hand-edited record lacking its gender: "Record.__init__() missing 1 required positional argument"
        # without the study or the record, and the study could not be summarised at all
        study = HaptiCAD.make_study(self.doc, self.head)
        study.Label = "Neck"
        HaptiCAD.record_preference(study, *PARTICIPANT)
        HaptiCAD.record_preference(study, "Zoë", "F", "26-40", 52, 1650)
        data = json.loads(study.Cohort)
        del data[1]["gender"]
        data.append(dict(data[0], name="Nan", value=float("nan")))
        study.Cohort = json.dumps(data)
        read, unread = stiffness_study.readable_records(study)
        self.assertEqual([r.name for r in read], ["Steven", "Nan"])
        self.assertEqual(unread, ["Neck: stored record 2 of 3 (Zoë) cannot be read: it lacks gender"])
        self.assertEqual([r.name for r in stiffness_study.comparable_records(study)], ["Steven", "Nan"])
        self.assertEqual(stiffness_study.comparable_indices(study), [0, 2])
        self.assertEqual(cohort.statistics(stiffness_study.comparable_records(study))[0]["n"], 1)
        self.assertEqual(stiffness_study.others_note(study), "")
        # what writes the cohort back refuses, naming it, rather than drop the record
        for write in (lambda: stiffness_study.remove_record(study, 0),
                      lambda: HaptiCAD.record_preference(study, "Ann", "F", "18-25", None, None)):
            with self.assertRaises(ValueError) as caught:
                write()
            self.assertEqual(str(caught.exception), unread[0])
        self.assertEqual(json.loads(study.Cohort.replace("NaN", "null")), json.loads(json.dumps(data).replace(
            "NaN", "null")))
        study.Cohort = '{"a": 1}'
        with self.assertRaisesRegex(ValueError, r"^Neck: the stored cohort is not a list of records but dict"):
            stiffness_study.readable_records(study)

    def test_a_scaled_workspace_feels_the_design_at_the_handle(self):
        from types import SimpleNamespace

        from hapticad import preferences

        # seed 000's toothbrush neck, 0.556 N/mm, through a device whose workspace is scaled 1.8 x into the model
        # (a 180 mm toothbrush fitted into a 100 mm workspace): the neck was felt as 1.0 N/mm at the handle
        study = HaptiCAD.make_study(self.doc, self.head, YoungsModulus=1.5, BeamWidth=5, BeamThickness=4,
                                    BeamLength=60)
        self.doc.recompute()
        scene = build_document_scene(self.doc)
        limits = _core.simulated_probe_limits()  # 3 N/mm

        def held_force(scale, handle_depth_m):
            """Mean normal force while a scripted handle holds ``handle_depth_m`` below the top, live loop."""
            mapping = _core.WorkspaceMapping()
            mapping.scale = scale
            mapping.offset_w = np.array([20.0, 20.0, 10.0]) * 1e-3  # the handle's origin on the top's middle
            path = np.array([[0, 0, 0.01], [0, 0, 0.01], [0, 0, -handle_depth_m], [0, 0, -handle_depth_m]])

            def run():
                device = _core.SimulatedDevice([0.0, 0.1, 0.4, 0.8], path, limits)
                renderer = _core.ForceRenderer(scene.scene, scene.surfaces, _core.render_limits_for(limits, mapping))
                loop = _core.ServoLoop(device, renderer, 1000.0, trace_capacity=2000)
                loop.set_mapping(mapping)
                return SimpleNamespace(trace=loop.run_for(0.8))

            trace = run().trace
            held = trace["time_s"] > 0.6  # down at 0.4 s, the mapping's ramp-in long over
            self.assertTrue((trace["flags"][held] & _core.FLAG_CONTACT).all())
            return float(np.mean(trace["normal_force_n"][held]))

        # pressed 1 mm at the handle (1.8 mm into the model): the design's 0.556 N, as at scale 1. The proxy rests
        # 1e-9 of the part's size off the face (micronewtons): 1e-4 N is far inside the 0.44 N the old 1.8 x gave
        for scale in (1.0, 1.8):
            with self.subTest(scale=scale):
                self.assertAlmostEqual(held_force(scale, 1e-3), study.BendingStiffness * 1.0, delta=1e-4)
        # 8 mm: 4.44 N/mm, beyond the device: felt at its 3 N/mm at the handle, what the note and the record say
        study.BeamThickness = 8
        self.doc.recompute()
        scene = build_document_scene(self.doc)
        fitted = dataclasses.replace(preferences.load(), **{"device": "sim:hand", "workspace_mapping": "Fixed scale",
                                                           "workspace_scale": 1.8})
        k = stiffness_study.device_stiffness_n_per_m(self.doc, fitted)
        self.assertAlmostEqual(k, 3000.0)
        self.assertIn("it is felt at the handle as 3 N/mm", stiffness_study.device_note(study, k))
        self.assertAlmostEqual(held_force(1.8, 0.5e-3), k * 0.5e-3, delta=1e-4)

    def test_a_live_edit_of_the_study_recompiles_the_faces_law(self):
        study = HaptiCAD.make_study(self.doc, self.head, YoungsModulus=1.5, BeamThickness=4)
        scene = build_document_scene(self.doc)
        face = scene.face_id("Head.Face6")
        self.assertAlmostEqual(scene.surface_properties(face).force_travel.max_slope(), 555.6, delta=0.1)
        study.BeamLength = 30  # 1/L^3: 8 x
        scene = recompile_surfaces(self.doc, scene)
        self.assertAlmostEqual(scene.surface_properties(face).force_travel.max_slope(), 8 * 555.6, delta=1)

    def test_a_preference_above_the_force_limit_keeps_the_limit_and_is_left_out_of_the_statistics(self):
        # the preferences' 3 N: a 3.48 N button stops at 3 N and its click never comes
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button")
        for name, force in (("Ann", 1.5), ("Bo", 2.5), ("Cy", 3.48)):
            study.OperatingForce = force
            HaptiCAD.record_preference(study, name, "F", "26-40", None, None, 3000.0, 3.0)
        ann, bo, cy = stiffness_study.records(study)
        # the limit kept, as the stiffness limit is
        self.assertEqual((cy.design["ForceLimit"], cy.design["BeyondForceLimit"]), (3.0, 1.0))
        self.assertEqual((ann.design["ForceLimit"], ann.design["BeyondForceLimit"]), (3.0, 0.0))
        self.assertEqual([cohort.mark(r) for r in (ann, bo, cy)], [" *", " *", " †"])
        held = stiffness_study.comparable_records(study)
        self.assertEqual(cohort.statistics(held)[0]["n"], 2)
        self.assertIn("† 1 preference above the force limit (3 N): the force stopped there and the click was never "
                      "felt; left out of the statistics", cohort.beyond_device_note(held))
        self.assertIn("* 2 preferences steeper than the device", cohort.beyond_device_note(held))
        self.assertEqual(study.Participants, 3)  # kept all the same
        # without a force limit given (a script), nothing is claimed either way
        self.assertNotIn("ForceLimit", HaptiCAD.record_preference(study, "Di", "F", "26-40", None, None).design)
        # a neck keeps the limit too; its force is the hand's press, never beyond it
        study.Model = "Bending beam"
        neck = HaptiCAD.record_preference(study, "Ed", "M", "26-40", None, None, 3000.0, 0.5)
        self.assertEqual((neck.design["ForceLimit"], cohort.beyond_force_limit(neck)), (0.5, False))

    def test_a_limit_or_name_that_is_not_valid_is_refused_keeping_nothing(self):
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button")
        HaptiCAD.record_preference(study, "Ann", "F", "26-40", None, None, 3000.0, 3.0)
        before = (study.Cohort, study.Participants, [o.Name for o in self.doc.Objects])
        # a NaN or negative limit was kept, starred †, stored as NaN and printed as
        # "above the force limit (nan N, -1 N)"; a name not text gave an AttributeError
        nan, inf = float("nan"), float("inf")
        for args, message in (((None, None, nan), "device_max_stiffness_n_per_m = nan must be a finite number > 0"),
                              ((None, None, inf), "device_max_stiffness_n_per_m = inf must be a finite number > 0"),
                              ((None, None, -3000.0), "device_max_stiffness_n_per_m = -3000.0 must be a finite"),
                              ((None, None, 3000.0, -1), "force_limit_n = -1 must be a finite number > 0 (N)"),
                              ((None, None, 3000.0, nan), "force_limit_n = nan must be a finite number > 0 (N)"),
                              ((None, None, 3000.0, 0.0), "force_limit_n = 0.0 must be a finite number > 0 (N)"),
                              ((None, None, 3000.0, True), "force_limit_n = True must be a finite number > 0 (N)")):
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as caught:
                    HaptiCAD.record_preference(study, "Bo", "F", "26-40", *args)
                self.assertIn(f"{study.Label}: {message}", str(caught.exception))
                self.assertEqual((study.Cohort, study.Participants, [o.Name for o in self.doc.Objects]), before)
        for name in (None, 5):
            with self.subTest(name=name):
                with self.assertRaises(ValueError) as caught:
                    HaptiCAD.record_preference(study, name, "F", "26-40", None, None)
                self.assertEqual(str(caught.exception),
                                 f"{study.Label}: name must be text (the participant's name or alias), got {name!r}")
                self.assertEqual((study.Cohort, study.Participants, [o.Name for o in self.doc.Objects]), before)
        self.assertEqual([r.name for r in stiffness_study.records(study)], ["Ann"])
        for doc in (None, "StudyTest"):
            with self.assertRaisesRegex(ValueError, "^studies_of: doc = .* is not a FreeCAD document"):
                HaptiCAD.studies_of(doc)

    def test_the_sliders_range_says_when_it_runs_past_the_force_limit(self):
        study = HaptiCAD.make_study(self.doc, self.head, model="Push button")  # 0.5-5 N
        self.assertEqual(stiffness_study.range_note(study, 3.0),
                         "past 3 N, the force limit, the click is never felt (the slider goes to 5 N)")
        self.assertEqual(stiffness_study.range_note(study, 5.0), "")
        self.assertEqual(stiffness_study.range_note(study, None), "")  # no limit known: nothing claimed
        study.AdjustMin, study.AdjustMax = 3.5, 4.5
        self.assertEqual(stiffness_study.range_note(study, 3.0),
                         "the whole range is above 3 N, the force limit: the click is never felt")
        study.Adjust = "SnapRatio"  # its range is no force
        self.assertEqual(stiffness_study.range_note(study, 0.1), "")
        study.Model = "Bending beam"
        self.assertEqual(stiffness_study.range_note(study, 0.1), "")

    def test_switching_what_the_slider_moves_and_back_keeps_a_range_of_ones_own(self):
        self.doc.UndoMode = 1
        study = HaptiCAD.make_study(self.doc, self.head)
        study.AdjustMin, study.AdjustMax = 3.0, 5.0  # narrowed mid-study
        study.Adjust = "BeamLength"
        self.assertEqual((study.AdjustMin, study.AdjustMax), (30.0, 120.0))  # never narrowed: its default
        study.AdjustMin = 40.0
        study.Adjust = "BeamThickness"
        self.assertEqual((study.AdjustMin, study.AdjustMax), (3.0, 5.0))  # not reset to 2-8
        study.Adjust = "BeamLength"
        self.assertEqual((study.AdjustMin, study.AdjustMax), (40.0, 120.0))
        study.Model = "Push button"  # another model and back: the same
        self.assertEqual((study.Adjust, study.AdjustMin, study.AdjustMax), ("OperatingForce", 0.5, 5.0))
        study.Model = "Bending beam"
        self.assertEqual((study.Adjust, study.AdjustMin, study.AdjustMax), ("BeamThickness", 3.0, 5.0))
        # an undo of a switch brings back the range with what the slider moved, and the ones kept
        self.doc.openTransaction("slider")
        study.Adjust = "YoungsModulus"
        self.doc.commitTransaction()
        self.assertEqual((study.AdjustMin, study.AdjustMax), (0.5, 5.0))
        self.doc.undo()
        self.assertEqual((study.Adjust, study.AdjustMin, study.AdjustMax), ("BeamThickness", 3.0, 5.0))
        with tempfile.TemporaryDirectory() as tmp:  # and a reopened document remembers them
            path, name = os.path.join(tmp, "ranges.FCStd"), study.Name
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            study = self.doc.getObject(name)
            study.Adjust = "BeamLength"
            self.assertEqual((study.AdjustMin, study.AdjustMax), (40.0, 120.0))
        # kept ranges edited into nonsense: the defaults serve
        study.AdjustRanges = "{not json"
        study.Adjust = "BeamWidth"
        self.assertEqual((study.AdjustMin, study.AdjustMax), (2.0, 12.0))

    def test_a_design_outside_the_sliders_range_is_said_and_still_recorded(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        study.AdjustMin, study.AdjustMax = 3.0, 5.0
        self.assertEqual(stiffness_study.validate(study), [])
        study.BeamThickness = 8.0  # the Mechanism box, the property editor, a script
        self.assertIn("the thickness h, 8 mm, is outside the slider's range 3..5 mm: move the slider, or widen its "
                      "range", stiffness_study.validate(study))
        self.assertEqual(stiffness_study.law_problems(study), [])  # still felt
        # a researcher's design set by hand is recorded (Table 3's 4.5 N/mm needs h 8.03, past 2-8)
        HaptiCAD.record_preference(study, *PARTICIPANT)
        self.assertEqual(study.Participants, 1)
        # the slider's own ends are inside, whatever the float sum gives (0.3 + (0.9 - 0.3) is 0.9000000000000001)
        study.Model = "Push button"
        study.Adjust = "SnapRatio"
        study.AdjustMin, study.AdjustMax = 0.3, 0.9
        for position in (0, 200):
            study.SnapRatio = study.AdjustMin + (study.AdjustMax - study.AdjustMin) * position / 200
            self.assertEqual(stiffness_study.validate(study), [])
        self.assertGreater(study.SnapRatio, 0.9)
        study.SnapRatio = 0.95
        self.assertIn("the snap ratio, 0.95, is outside the slider's range 0.3..0.9",
                      stiffness_study.validate(study)[0])

    def test_a_spreadsheets_resave_of_the_export_adds_nobody_and_says_how_it_was_known(self):
        study = HaptiCAD.make_study(self.doc, self.head)
        for i, h in enumerate((3.0, 4.1, 5.3)):
            study.BeamThickness = h
            HaptiCAD.record_preference(study, f"P{i}", "F", "18-25", 60.7, 1650)
        with tempfile.TemporaryDirectory() as tmp:
            exported = os.path.join(tmp, "cohort.csv")
            cohort.write_csv(exported, stiffness_study.records(study))
            with open(exported, newline="") as handle:
                rows = list(csv.DictReader(handle))
            # as LibreOffice or Excel saves it back: a BOM, CRLF, the time to the minute, an empty row
            sheet = os.path.join(tmp, "sheet.csv")
            with open(sheet, "w", newline="", encoding="utf-8-sig") as handle:
                out = csv.DictWriter(handle, fieldnames=list(rows[0]), lineterminator="\r\n")
                out.writeheader()
                for r in rows:
                    out.writerow(dict(r, recorded=r["recorded"].replace("T", " ")[:16]))
                handle.write(",,,,,,,,,\r\n")
            result = stiffness_study.import_records(study, sheet)
            self.assertEqual(result, (0, 3, 0))
            self.assertEqual((result.retimed, result.read_as), (3, ""))
            self.assertEqual(study.Participants, 3)
            # European: ';' and decimal commas, the time day first
            european = os.path.join(tmp, "european.csv")
            with open(european, "w", newline="", encoding="utf-8-sig") as handle:
                out = csv.DictWriter(handle, fieldnames=list(rows[0]), delimiter=";", lineterminator="\r\n")
                out.writeheader()
                for r in rows:
                    day, clock = r["recorded"].split("T")
                    out.writerow(dict(r, value=r["value"].replace(".", ","), weight_kg="60,7",
                                      recorded=".".join(reversed(day.split("-"))) + " " + clock[:5]))
            result = stiffness_study.import_records(study, european)
            self.assertEqual((result, result.retimed, result.read_as),
                             ((0, 3, 0), 3, "semicolon-separated, with decimal commas"))
            # the same file two minutes off (neither cut nor rounded from the time kept) is another session: added
            with open(sheet, newline="", encoding="utf-8-sig") as handle:
                text = handle.read()
            later = os.path.join(tmp, "later.csv")
            with open(later, "w", newline="") as handle:
                handle.write(re.sub(r":(\d\d)\r\n", lambda m: f":{(int(m[1]) + 2) % 60:02d}\r\n", text))
            self.assertEqual(stiffness_study.import_records(study, later), (3, 0, 0))
            # six records: the three people's second sessions
            self.assertEqual((len(stiffness_study.records(study)), study.Participants), (6, 3))


if __name__ == "__main__":
    unittest.main()
