# SPDX-License-Identifier: GPL-3.0-or-later
"""HapticVibration: a part that vibrates when powered; validation and persistence."""
import os
import tempfile
import unittest

import FreeCAD as App

import HaptiCAD
from hapticad import _core, vibration_object
from hapticad.document_scene import build_document_scene

from test_feel_session import drain_ticks  # noqa: E402

MM = 1e-3
TURN_Z = App.Rotation(App.Vector(0, 0, 1), 90)
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def shake_amplitudes(trace, frequency_hz):
    """Amplitude, N, of the force at ``frequency_hz`` along x, y and z over ``trace``."""
    import numpy as np

    phase = np.exp(-2j * np.pi * frequency_hz * np.asarray(trace["time_s"]))
    force = np.asarray(trace["force_n"])
    return 2 * np.abs(((force - force.mean(axis=0)) * phase[:, None]).mean(axis=0))


class VibrationTest(unittest.TestCase):
    def test_a_part_without_faces_is_refused_and_one_that_loses_them_is_said(self):
        import Part

        wire = self.doc.addObject("Part::Feature", "Wire")
        wire.Shape = Part.makePolygon([App.Vector(0, 0, 0), App.Vector(10, 0, 0), App.Vector(10, 10, 0)])
        self.doc.recompute()
        with self.assertRaisesRegex(ValueError, "Wire has no faces, so the probe touches nothing of it"):
            HaptiCAD.make_vibration(self.doc, wire)
        self.assertEqual(vibration_object.vibrations_of(self.doc), [])
        # a part that had faces and lost them in an edit
        plate = self.doc.addObject("Part::Feature", "Plate")
        plate.Shape = Part.makeBox(10, 10, 1)
        self.doc.recompute()
        v = HaptiCAD.make_vibration(self.doc, plate)
        plate.Shape = wire.Shape.copy()
        self.doc.recompute()
        self.assertIn("Plate has no faces", " ".join(vibration_object.validate(v)))
        with self.assertRaisesRegex(ValueError, f"{v.Label}: Plate has no faces.*or delete {v.Label}"):
            build_document_scene(self.doc)

    def setUp(self):
        self.doc = App.newDocument("VibrationTest")
        self.razor = self.doc.addObject("Part::Box", "Razor")
        self.doc.recompute()

    def tearDown(self):
        for name in list(App.listDocuments()):
            App.closeDocument(name)

    def test_make_vibration_sets_the_values(self):
        v = HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=120.0, amplitude_n=0.4, axis=(1, 0, 0))
        self.assertTrue(HaptiCAD.is_haptic_vibration(v))
        self.assertEqual((v.Part, v.Frequency, v.Amplitude, v.Powered), (self.razor, 120.0, 0.4, True))
        self.assertEqual(tuple(v.Axis), (1.0, 0.0, 0.0))
        self.assertEqual(HaptiCAD.vibrations_of(self.doc), [v])

    def test_bad_values_raise_and_add_nothing(self):
        for kwargs, message in (({"frequency_hz": 0.0}, "frequency_hz"), ({"amplitude_n": -1.0}, "amplitude_n"),
                                ({"axis": (0, 0, 0)}, "axis"), ({"frequency_hz": "fast"}, "frequency_hz")):
            with self.assertRaisesRegex(ValueError, message):
                HaptiCAD.make_vibration(self.doc, self.razor, **kwargs)
        with self.assertRaisesRegex(ValueError, "no object"):
            HaptiCAD.make_vibration(self.doc, "Shaver")
        self.assertEqual(len(self.doc.Objects), 1)

    def test_every_bad_argument_is_refused_by_name_before_anything_is_added(self):
        neck = HaptiCAD.make_surface(self.doc, [(self.razor, "Face6")])
        before = [o.Name for o in self.doc.Objects]
        # a four-number axis was refused by FreeCAD after the vibration was added (150 Hz,
        # along Z, powered, saved with the document), and the corrected call then refused
        # as "Razor vibrates already"; the others gave bare TypeError, OverflowError,
        # AttributeError, or took True for 1 Hz
        for args, kwargs, message in (
                ((self.doc, self.razor), {"frequency_hz": 150, "axis": (1, 0, 0, 0)},
                 "axis must be three finite numbers (x, y, z), got (1, 0, 0, 0)"),
                ((self.doc, self.razor), {"axis": "xyz"}, "axis must be three finite numbers (x, y, z), got 'xyz'"),
                ((self.doc, self.razor), {"axis": None}, "axis must be three finite numbers (x, y, z), got None"),
                ((self.doc, self.razor), {"axis": (0, float("inf"), 1)}, "axis must be three finite numbers"),
                ((self.doc, 5), {}, "part = 5 is neither a part of document VibrationTest nor its name"),
                ((self.doc, None), {}, "part = None is neither a part of document VibrationTest nor its name"),
                ((self.doc, neck), {}, "part HapticSurface is a haptic surface, not a part: give the part whose "
                                       "faces vibrate (Razor)"),
                ((None, self.razor), {}, "doc = None is not a FreeCAD document"),
                ((self.doc, self.razor), {"frequency_hz": "100"}, "frequency_hz must be a number (Hz), got '100'"),
                ((self.doc, self.razor), {"frequency_hz": True}, "frequency_hz must be a number (Hz), got True"),
                ((self.doc, self.razor), {"amplitude_n": None}, "amplitude_n must be a number (N), got None"),
                ((self.doc, self.razor), {"powered": "no"}, "powered must be True or False, got 'no'"),
                ((self.doc, self.razor), {"name": 7}, "name must be a non-empty string, got 7")):
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as caught:
                    HaptiCAD.make_vibration(*args, **kwargs)
                self.assertIn(f"make_vibration: {message}", str(caught.exception))
                self.assertEqual([o.Name for o in self.doc.Objects], before)
                self.assertFalse(self.doc.HasPendingTransaction)
        # the corrected call is taken; an axis of any finite size is kept as its direction
        v = HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=150, axis=(1e200, 1e200, 0))
        self.assertEqual(HaptiCAD.vibrations_of(self.doc), [v])
        self.assertAlmostEqual(v.Axis.x, 0.5 ** 0.5)
        self.assertAlmostEqual(v.Axis.y, 0.5 ** 0.5)
        self.assertEqual(vibration_object.validate(v), [])
        for doc in (None, "VibrationTest"):
            with self.assertRaisesRegex(ValueError, "^vibrations_of: doc = .* is not a FreeCAD document"):
                HaptiCAD.vibrations_of(doc)

    def test_a_part_vibrates_one_way_and_an_axis_must_be_finite(self):
        v = HaptiCAD.make_vibration(self.doc, self.razor)
        with self.assertRaisesRegex(ValueError, "Razor vibrates already"):
            HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=200.0)
        self.assertEqual(HaptiCAD.vibrations_of(self.doc), [v])
        self.assertEqual(vibration_object.validate(v), [])
        # a second one made anyway (the property editor, a script): said, by name
        other = self.doc.addObject("App::FeaturePython", "Other")
        vibration_object.HapticVibration(other)
        other.Part = self.razor
        self.assertIn("Razor has another vibration", vibration_object.validate(v)[0])
        self.doc.removeObject("Other")
        v.Axis = App.Vector(float("nan"), 0, 1)
        self.assertEqual(len(vibration_object.validate(v)), 1)
        self.assertIn("not three finite numbers", vibration_object.validate(v)[0])
        # and Feel says which vibration it is, not "vibration 0"
        HaptiCAD.make_surface(self.doc, [(self.razor, "Face6")])
        with self.assertRaises(ValueError) as caught:
            build_document_scene(self.doc)
        self.assertIn(f"{v.Label}: the axis (nan, 0.0, 1.0) is not three finite numbers", str(caught.exception))

    def test_a_zero_axis_typed_in_is_refused(self):
        v = HaptiCAD.make_vibration(self.doc, self.razor)
        v.Axis = App.Vector(0, 0, 0)
        self.assertEqual(tuple(v.Axis), (0.0, 0.0, 1.0))

    def test_every_face_of_the_part_carries_the_vibration(self):
        HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=150.0, powered=False)
        scene = build_document_scene(self.doc)
        self.assertEqual(len(scene.face_names), 6)
        for face in range(6):
            self.assertEqual(scene.surfaces.surface(face).vibration, 0)

    def test_a_frequency_the_servo_rate_cannot_render_is_said_as_it_would_be_felt(self):
        import numpy as np
        from hapticad.feel import Stroke, run_stroke_in_servo_loop

        self.razor.Length, self.razor.Width, self.razor.Height = 80, 40, 20
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.razor, "Face6")], FeelRoughness=False, static_friction=0.0,
                              dynamic_friction=0.0)
        v = HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=100.0, amplitude_n=0.5, axis=(0, 0, 1))

        def felt(rate_hz):
            """(strongest frequency, its amplitude) of the normal force while sliding."""
            scene = build_document_scene(self.doc)
            stroke = Stroke((10, 20, 20), (70, 20, 20), 50, 1.0, rate_hz=rate_hz)
            result = run_stroke_in_servo_loop(scene, stroke)
            t = result.trace
            sliding = (t["time_s"] > result.plan.slide_start_s) & (t["time_s"] < result.plan.slide_end_s)
            fz = np.asarray(t["force_n"])[sliding, 2]
            spectrum = np.abs(np.fft.rfft(fz - fz.mean())) * 2 / len(fz)
            k = int(spectrum.argmax())
            return np.fft.rfftfreq(len(fz), 1.0 / rate_hz)[k], spectrum[k]

        self.assertEqual(vibration_object.rate_note(v, 1000), "")
        frequency, amplitude = felt(1000)
        self.assertAlmostEqual(frequency, 100, delta=2)
        self.assertGreater(amplitude, 0.4)
        v.Frequency = 700
        self.assertIn("700 Hz is felt at 300 Hz instead at the 1000 Hz servo rate", vibration_object.rate_note(v, 1000))
        self.assertIn("under 500 Hz", vibration_object.rate_note(v, 1000))
        frequency, amplitude = felt(1000)  # what the note says: 300 Hz
        self.assertAlmostEqual(frequency, 300, delta=2)
        # at 2 kHz it is no longer aliased, but with 2.9 samples a cycle not even either
        self.assertNotIn("instead", vibration_object.rate_note(v, 2000))
        self.assertIn("700 Hz gets 2.9 samples a cycle", vibration_object.rate_note(v, 2000))
        self.assertEqual(vibration_object.rate_note(v, 4000), "")
        v.Frequency = 1000
        self.assertIn("not felt at all", vibration_object.rate_note(v, 1000))
        self.assertLess(felt(1000)[1], 0.05)
        self.assertEqual(vibration_object.rate_notes(self.doc, 1000), [vibration_object.rate_note(v, 1000)])
        v.Powered = False
        self.assertEqual(vibration_object.rate_notes(self.doc, 1000), [])
        v.Powered = True

        def weakest_cycle_peak(rate_hz):
            """The smallest of the largest shake in each cycle's samples, as a share of
            the amplitude: 1 when every cycle's peak is felt."""
            scene = build_document_scene(self.doc)
            stroke = Stroke((10, 20, 20), (40, 20, 20), 50, 1.0, rate_hz=rate_hz)
            result = run_stroke_in_servo_loop(scene, stroke)
            t = result.trace
            sliding = (t["time_s"] > result.plan.slide_start_s) & (t["time_s"] < result.plan.slide_end_s)
            shake = np.abs(np.asarray(t["vibration_force_n"])[sliding])
            w = int(np.ceil(rate_hz / float(v.Frequency)))
            return min(shake[i:i + w].max() for i in range(len(shake) - w)) / float(v.Amplitude)

        # a quarter to half the rate: rendered, but its size swings from cycle to cycle
        v.Frequency = 450
        self.assertIn("450 Hz gets 2.2 samples a cycle at the 1000 Hz servo rate, so its size swings",
                      vibration_object.rate_note(v, 1000))
        self.assertIn("keep it under 250 Hz", vibration_object.rate_note(v, 1000))
        self.assertLess(weakest_cycle_peak(1000), 0.5)
        v.Frequency = 200  # under a quarter: even, and not said
        self.assertEqual(vibration_object.rate_note(v, 1000), "")
        self.assertGreater(weakest_cycle_peak(1000), 0.9)

    def test_an_amplitude_beyond_the_force_limit_is_said_and_a_vibration_never_pulls_the_probe_in(self):
        import numpy as np
        from hapticad.feel import Stroke, run_stroke_in_servo_loop

        self.razor.Length, self.razor.Width, self.razor.Height = 80, 40, 20
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.razor, "Face6")], FeelRoughness=False, static_friction=0.0,
                              dynamic_friction=0.0, stiffness_n_per_mm=0.4)
        # a phone's buzz, 0.3 N, on a touch of 0.25 mm (0.1 N): more than the push
        v = HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=200.0, amplitude_n=0.3, axis=(0, 0, 1))
        scene = build_document_scene(self.doc)
        result = run_stroke_in_servo_loop(scene, Stroke((10, 20, 20), (70, 20, 20), 50, 0.25, rate_hz=1000))
        t = result.trace
        sliding = (t["time_s"] > result.plan.slide_start_s) & (t["time_s"] < result.plan.slide_end_s)
        fz = np.asarray(t["force_n"])[sliding, 2]
        # the face only pushes: the push's half-wave, from nothing (it pulled to -0.185 N) to 0.1 N and the
        # vibration's highest sample at 1 kHz, 0.3 N sin 72 degrees
        self.assertGreaterEqual(float(fz.min()), 0.0)
        self.assertLess(float(fz.min()), 1e-9)
        self.assertAlmostEqual(float(fz.max()), 0.1 + 0.3 * np.sin(np.radians(72)), delta=0.005)
        # a firm 1 N push and 0.3 N fit under the 3 N force limit: nothing to say
        self.assertEqual(vibration_object.force_note(v, 3.0), "")
        # 10 N is accepted (a strong device renders it) but said: under 3 N it is a square wave at the limit
        v.Amplitude = 10.0
        self.assertEqual(v.Amplitude, 10.0)
        self.assertEqual(vibration_object.validate(v), [])
        note = vibration_object.force_note(v, 3.0)
        self.assertIn(f"{v.Label}: 10 N alone it reaches the 3 N force limit", note)
        self.assertIn("square wave", note)
        self.assertIn("keep the amplitude under 2 N or raise the force limit", note)
        # 2.5 N fits alone, not on a 1 N push: its peaks are cut
        v.Amplitude = 2.5
        self.assertIn("2.5 N on a typical 1 N push it passes the 3 N force limit, which cuts its peaks",
                      vibration_object.force_note(v, 3.0))
        self.assertEqual(vibration_object.force_note(v, 3.5), "")  # a limit that holds both
        self.assertIn("raise the force limit", vibration_object.force_note(v, 0.5))
        self.assertNotIn("keep the amplitude", vibration_object.force_note(v, 0.5))  # no room left under 0.5 N
        self.assertEqual(vibration_object.force_notes(self.doc, 3.0), [vibration_object.force_note(v, 3.0)])
        v.Powered = False
        self.assertEqual(vibration_object.force_notes(self.doc, 3.0), [])

    def test_a_deleted_part_is_named_with_the_ways_to_mend_it_through_undo_and_reopening(self):
        # deleting the part left "no part to vibrate", naming nothing, for good
        v = HaptiCAD.make_vibration(self.doc, self.razor)
        self.razor.Label = "Shaver head"
        self.doc.UndoMode = 1
        self.doc.recompute()
        self.doc.openTransaction("delete")
        self.doc.removeObject("Razor")
        self.doc.commitTransaction()
        self.doc.recompute()
        said = ("no part to vibrate: Shaver head, which it vibrated, was deleted; undo the deletion, link a part "
                f"in its Part property (Data tab) or delete {v.Label}")
        self.assertIsNone(v.Part)
        self.assertEqual(vibration_object.validate(v), [said])
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "orphan.FCStd")
            self.doc.saveCopy(path)
            reopened = App.openDocument(path)
            try:
                self.assertEqual(vibration_object.validate(reopened.getObject(v.Name)), [said])
            finally:
                App.closeDocument(reopened.Name)
        self.doc.undo()  # the part and the link come back, the note goes
        self.doc.recompute()
        self.assertEqual((v.Part.Name, vibration_object.deleted_part(v)), ("Razor", ""))
        self.assertEqual(vibration_object.validate(v), [])
        # unlinked without a deletion, or linked to another part: nothing was deleted
        v.Part = None
        self.assertEqual(vibration_object.validate(v), [f"no part to vibrate: link a part in its Part property "
                                                         f"(Data tab) or delete {v.Label}"])
        self.doc.removeObject("Razor")
        other = self.doc.addObject("Part::Box", "Other")
        self.doc.recompute()
        v.Part = other
        self.assertEqual((vibration_object.deleted_part(v), vibration_object.validate(v)), ("", []))

    def test_round_trip(self):
        v = HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=167.0, amplitude_n=0.25,
                                    axis=(0, 1, 0), powered=False)
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "razor.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            doc = App.openDocument(path)
            v = doc.getObject("HapticVibration")
            self.assertEqual((v.Part.Name, v.Frequency, v.Amplitude, v.Powered), ("Razor", 167.0, 0.25, False))
            self.assertEqual(tuple(v.Axis), (0.0, 1.0, 0.0))
            self.assertNotIn("Touched", v.State)
            v.Frequency = 5000.0  # constraint restored on reopening
            self.assertEqual(v.Frequency, 1000.0)
            self.doc = doc


    def assertAxis(self, axis, expected, msg=None):
        self.assertLess((App.Vector(axis) - App.Vector(*expected)).Length, 1e-9, msg or f"{axis} != {expected}")

    def head_in_an_assembly(self):
        """The razor's head, 60 mm long in x, in an App::Part, shaking at 120 Hz along
        its blade (x), and the App::Part."""
        assembly = self.doc.addObject("App::Part", "Assembly")
        self.razor.Length, self.razor.Width, self.razor.Height = 60, 10, 10
        assembly.addObject(self.razor)
        self.doc.recompute()
        v = HaptiCAD.make_vibration(self.doc, self.razor, frequency_hz=120.0, amplitude_n=0.3, axis=(1, 0, 0))
        self.doc.recompute()
        self.assertNotIn("Touched", v.State)
        return v, assembly

    def test_the_axis_turns_with_its_part_and_is_shown_where_it_is_felt(self):
        # the App::Part turned 90 degrees about Z: the head's blade runs along +Y, and the
        # shake stayed along X, across the blade
        from hapticad.surface_compile import compile_vibration

        v, assembly = self.head_in_an_assembly()
        assembly.Placement = App.Placement(App.Vector(5, 0, 0), TURN_Z)
        # felt turned at once, before anything recomputes the vibration
        self.assertAxis(App.Vector(*compile_vibration(v).axis_w), (0, 1, 0))
        # and shown: the App::Part's recompute alone runs the vibration, which follows
        self.doc.recompute()
        self.assertAxis(v.Axis, (0, 1, 0))
        self.assertNotIn("Touched", v.State)
        self.assertIn("turns with the part", v.getDocumentationOfProperty("Axis"))
        # the head turned itself too (its own placement, 90 degrees about Y): x to -z
        self.razor.Placement = App.Placement(App.Vector(), App.Rotation(App.Vector(0, 1, 0), 90))
        self.doc.recompute()
        self.assertAxis(v.Axis, (0, 0, -1))
        self.assertAxis(App.Vector(*compile_vibration(v).axis_w), (0, 0, -1))
        # an axis given while turned is felt as given, and turns from there on
        v.Axis = App.Vector(0, 1, 0)
        self.assertAxis(App.Vector(*compile_vibration(v).axis_w), (0, 1, 0))
        assembly.Placement = App.Placement()
        self.doc.recompute()
        self.assertAxis(v.Axis, (1, 0, 0))
        # linked to another part: the axis stays where it was felt, then turns with that part
        other = self.doc.addObject("Part::Box", "Other")
        self.doc.recompute()
        v.Part = other
        self.assertAxis(v.Axis, (1, 0, 0))
        self.razor.Placement = App.Placement()
        other.Placement = App.Placement(App.Vector(), TURN_Z)
        self.doc.recompute()
        self.assertAxis(v.Axis, (0, 1, 0))
        self.assertEqual(vibration_object.validate(v), [])

    def test_the_axis_turns_with_a_body_that_holds_its_part(self):
        # a feature of a PartDesign Body: turning the Body recomputes the Body only
        body = self.doc.addObject("PartDesign::Body", "Body")
        handle = body.newObject("PartDesign::AdditiveBox", "Handle")
        handle.Length, handle.Width, handle.Height = 60, 10, 10
        self.doc.recompute()
        v = HaptiCAD.make_vibration(self.doc, handle, axis=(1, 0, 0))
        self.doc.recompute()
        body.Placement = App.Placement(App.Vector(0, 0, 20), TURN_Z)
        self.doc.recompute()
        self.assertAxis(v.Axis, (0, 1, 0))
        scene = build_document_scene(self.doc)  # the handle's faces where the Body put them
        self.assertEqual(scene.surfaces.surface(scene.face_id("Handle.Face1")).vibration, 0)
        # the Body itself vibrating turns with it as well
        self.doc.removeObject(v.Name)
        w = HaptiCAD.make_vibration(self.doc, body, axis=(0, 1, 0))
        self.doc.recompute()
        body.Placement = App.Placement()
        self.doc.recompute()
        self.assertAxis(w.Axis, (1, 0, 0))

    def test_a_document_saved_before_the_axis_turned_with_its_part_is_felt_as_saved(self):
        # written by HaptiCAD with vibration schema 2: the head in an App::Part turned 90
        # degrees about Z, its vibration's Axis (0, 1, 0) global, along the turned blade
        from hapticad.surface_compile import compile_vibration

        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "razor.FCStd")
            with open(os.path.join(DATA, "schema2_razor.FCStd"), "rb") as src, open(path, "wb") as dst:
                dst.write(src.read())
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
        v = self.doc.getObject("HapticVibration")
        self.assertEqual(v.Proxy.schema, 2)
        self.assertAxis(v.Axis, (0, 1, 0))  # felt as saved while nothing moved
        self.assertAxis(App.Vector(*compile_vibration(v).axis_w), (0, 1, 0))
        self.assertNotIn("Touched", v.State)
        self.assertIn("turns with the part", v.getDocumentationOfProperty("Axis"))
        # and from now on along the blade: the assembly turned back, the blade along x
        self.doc.getObject("Razor").Placement = App.Placement()
        self.doc.recompute()
        self.assertAxis(v.Axis, (1, 0, 0))
        self.assertAxis(App.Vector(*compile_vibration(v).axis_w), (1, 0, 0))

    def test_the_anchor_is_saved_and_a_copy_with_its_part_turns_with_the_copy(self):
        v, assembly = self.head_in_an_assembly()
        assembly.Placement = App.Placement(App.Vector(), TURN_Z)
        self.doc.recompute()
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "razor.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
        v, assembly = self.doc.getObject("HapticVibration"), self.doc.getObject("Assembly")
        self.assertAxis(v.Axis, (0, 1, 0))
        assembly.Placement = App.Placement()
        self.doc.recompute()
        self.assertAxis(v.Axis, (1, 0, 0))
        # Edit > Duplicate selection with the part: the copy's shake turned with the original
        copy = next(o for o in self.doc.copyObject([v], True) if HaptiCAD.is_haptic_vibration(o))
        self.doc.recompute()
        self.assertIsNot(copy.Part, v.Part)
        copy.Part.Placement = App.Placement(App.Vector(0, 50, 0), TURN_Z)
        self.doc.recompute()
        self.assertAxis(copy.Axis, (0, 1, 0))
        self.assertAxis(v.Axis, (1, 0, 0))
        v.Part.Placement = App.Placement(App.Vector(), App.Rotation(App.Vector(0, 1, 0), 90))
        self.doc.recompute()
        self.assertAxis(copy.Axis, (0, 1, 0))  # not turned by the original
        self.assertAxis(v.Axis, (0, 0, -1))

    def test_a_link_is_refused_by_name(self):
        # a vibration on an App::Link was made, and Feel then failed with "'App.DocumentObject'
        # object has no attribute 'getGlobalPlacement'"
        link = self.doc.addObject("App::Link", "Link")
        link.LinkedObject = self.razor
        self.doc.recompute()
        said = "Link is a link to Razor: a link cannot vibrate yet"
        with self.assertRaisesRegex(ValueError, f"make_vibration: {said}"):
            HaptiCAD.make_vibration(self.doc, link)
        self.assertEqual(vibration_object.vibrations_of(self.doc), [])
        v = HaptiCAD.make_vibration(self.doc, self.razor)
        v.Part = link  # the property editor takes one
        self.assertIn(said, " ".join(vibration_object.validate(v)))
        with self.assertRaisesRegex(ValueError, f"{v.Label}: {said}.*make Razor vibrate"):
            build_document_scene(self.doc)

    def test_a_running_session_feels_the_shake_turn_with_its_part(self):
        # the Feel panel's live path: SessionEditObserver gives geometry=True for a
        # placement of a part in the scene or of a container holding it, a property edit
        # geometry=False; LiveSession.apply_edit hands the loop what they change
        import numpy as np
        from hapticad import feel_session, preferences

        v, assembly = self.head_in_an_assembly()
        session = feel_session.LiveSession(build_document_scene(self.doc),
                                           prefs=preferences.Preferences(servo_rate_hz=1000, force_limit_n=3.0))
        session.start(np.array([30, 5, 30]) * MM)  # over the head's centre, which the turn keeps

        def felt(settle):
            """The shake's amplitude along x, y, z over 30 of its cycles, after ``settle`` ticks."""
            trace = drain_ticks(session, settle + 250)[-250:]
            self.assertTrue((trace["flags"] & _core.FLAG_CONTACT).all())
            return shake_amplitudes(trace, v.Frequency)

        try:
            drain_ticks(session, 300)
            session.set_target(np.array([30, 5, 8]) * MM)  # 2 mm into the top, held there
            along_x = felt(300)
            assembly.Placement = App.Placement(App.Vector(), TURN_Z, App.Vector(30, 5, 0))
            self.doc.recompute()
            self.assertEqual(session.apply_edit(self.doc, geometry=True), "scene")
            along_y = felt(250)  # the new scene's force ramps in over 0.2 s
            v.Axis = App.Vector(0, 0, 1)  # typed in the property editor: the surfaces are compiled again
            self.assertEqual(session.apply_edit(self.doc, geometry=False), "surfaces")
            along_z = felt(50)
            running = session.running
        finally:
            session.stop()
        self.assertTrue(running)
        for felt, axis in ((along_x, 0), (along_y, 1), (along_z, 2)):
            self.assertGreater(felt[axis], 0.25, (axis, felt))
            self.assertLess(np.delete(felt, axis).max(), 0.03, (axis, felt))


if __name__ == "__main__":
    unittest.main()
