# SPDX-License-Identifier: GPL-3.0-or-later
"""The live Feel session adapter, headless: with the device layer's live bindings it
runs the real C++ servo loop with the simulated hand (the hand aims into the top face
and is held at its surface); without them it refuses to start, naming what is missing.
The simulated hand waits for a late tick (it lives on the loop's clock), so no trace
here may show the watchdog's fault, whatever the host does. Run by freecadcmd."""
import time
import unittest

import numpy as np

import FreeCAD as App
import Part

import HaptiCAD
from hapticad import _core, feel_session, preferences
from hapticad.document_scene import NeedsNewScene, build_document_scene


MM = 1e-3


def drain(session):
    """All the session's samples since the last drain; none may show a watchdog fault."""
    trace = session.drain()
    if (trace["flags"] & _core.FLAG_FAULT_WATCHDOG).any():
        raise AssertionError("a watchdog fault in a simulated session: its clock must wait for the host")
    return trace


def drain_ticks(session, count, dead_after_s=20.0):
    """The session's next ``count`` or more samples, however long the host takes to tick
    them (the limit is only for a loop that died); checked as drain."""
    parts, got = [], 0
    end = time.monotonic() + dead_after_s
    while got < count:
        if time.monotonic() > end:
            raise AssertionError(f"the loop gave {got} of {count} samples in {dead_after_s} s")
        time.sleep(0.02)
        parts.append(drain(session))
        got += len(parts[-1])
    return np.concatenate(parts)


class FeelSessionTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("FeelSession")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel")
        self.scene = build_document_scene(self.doc)

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def press_on_the_top(self):
        """A running session whose hand came down from above and now presses 2 mm into
        the top face, and the last 50 samples of that."""
        prefs = preferences.Preferences(servo_rate_hz=1000, force_limit_n=3.0)
        session = feel_session.LiveSession(self.scene, prefs=prefs)
        session.start(np.array([20, 15, 30]) * MM)
        try:
            drain_ticks(session, 300)  # the hand starts above the part
            session.set_target(np.array([20, 15, 18]) * MM)
            return session, drain_ticks(session, 600)[-50:]
        except BaseException:
            session.stop()
            raise

    def test_the_face_line_says_what_is_felt_where_the_device_holds_it(self):
        # the simulated hand renders at most 3 N/mm and 0.5 N s/m: a face set stiffer or
        # more damped is felt at those, and the line under the view says so
        surface = self.doc.getObject("HapticSurface")
        surface.Label = "Chrome trim"
        face = self.scene.face_id("Box.Face6")
        prefs = preferences.Preferences(servo_rate_hz=1000, force_limit_n=3.0)
        within = feel_session.LiveSession(self.scene, prefs=prefs).describe_face(face)
        self.assertIn(f"{surface.Stiffness:.2f} N/mm)", within)
        self.assertNotIn("damping", within)  # none set
        surface.Stiffness, surface.Damping = 8.0, 5.0
        self.doc.recompute()
        scene = build_document_scene(self.doc)
        session = feel_session.LiveSession(scene, prefs=prefs)
        self.assertEqual(session.render_limits.max_stiffness_n_per_m, 3000.0)
        self.assertEqual(session.render_limits.max_damping_n_s_per_m, 0.5)
        self.assertIn("3.00 N/mm, the device's most (8.00 set), damping 0.50 N s/m, the device's most (5.00 set)",
                      session.describe_face(face))
        self.assertTrue(session.describe_face(face).startswith("Box.Face6: Chrome trim (Steel"))  # as the tree names it
        surface.Damping = 0.2
        self.doc.recompute()
        self.assertIn("damping 0.20 N s/m)",
                      feel_session.LiveSession(build_document_scene(self.doc), prefs=prefs).describe_face(face))

    def test_device_choices_start_with_the_simulated_probe(self):
        choices = feel_session.device_choices()
        self.assertEqual(choices[0].path, "simulated")
        self.assertTrue(choices[0].simulated)
        self.assertEqual(len({c.path for c in choices}), len(choices))

    def test_listed_hid_devices_follow_the_simulated_probe(self):
        # the binding lists dicts (issue 5); simulated entries are not HID choices
        listed = [{"kind": "sim", "name": "Simulated hand", "path": "sim:hand", "limits": None},
                  {"kind": "hid", "name": "Prototype", "path": "/dev/hidraw7", "limits": None, "error": None},
                  {"kind": "hid", "name": "Old arm", "path": "/dev/hidraw8", "limits": None,
                   "error": "speaks HaptiCAD HID protocol 2.0-2.1; this HaptiCAD speaks 1.x"}]
        saved = getattr(_core, "list_devices", None)
        _core.list_devices = lambda: listed
        try:
            choices = feel_session.device_choices()
        finally:
            if saved is None:
                del _core.list_devices
            else:
                _core.list_devices = saved
        self.assertEqual([c.path for c in choices], ["simulated", "/dev/hidraw7", "/dev/hidraw8"])
        self.assertEqual((choices[1].label, choices[1].problem), ("Prototype (/dev/hidraw7)", ""))
        # one that cannot be used is listed as such, with why, not offered as if it could
        self.assertEqual(choices[2].label, "Old arm (/dev/hidraw8): unusable")
        self.assertIn("protocol 2.0-2.1", choices[2].problem)

    def test_the_sessions_notes_say_what_its_rate_and_force_limit_make_of_a_vibration(self):
        from hapticad import vibration_object

        v = HaptiCAD.make_vibration(self.doc, self.box, frequency_hz=100.0, amplitude_n=2.5)
        scene = build_document_scene(self.doc)

        def notes(force_limit_n):
            session = feel_session.LiveSession(scene, prefs=preferences.Preferences(force_limit_n=force_limit_n))
            try:
                return session.vibration_notes(self.doc)
            finally:
                session.stop()

        # 2.5 N on a firm 1 N push passes the preferences' 3 N: said, not refused
        self.assertEqual(notes(3.0), [vibration_object.force_note(v, 3.0)])
        self.assertIn("passes the 3 N force limit", notes(3.0)[0])
        # the session's limit, not the preferences' alone: the simulated hand's 8.9 N under a 20 N preference
        self.assertEqual(notes(20.0), [])
        v.Amplitude = 10.0
        self.assertIn("10 N alone it reaches the 8.9 N force limit", notes(20.0)[0])
        # and what the servo rate keeps from being felt, as before
        v.Amplitude, v.Frequency = 0.3, 700.0
        self.assertEqual(notes(3.0), [vibration_object.rate_note(v, 1000)])
        self.assertIn("felt at 300 Hz instead", notes(3.0)[0])

    def test_the_sessions_notes_say_which_roughness_grids_its_rate_cannot_follow(self):
        from hapticad import surface_object

        s = HaptiCAD.make_surface(self.doc, [(self.box, "Face5")], material="ABS", roughness_category=1)
        self.assertIn("up to 15 mm/s", surface_object.rate_note(s, 1000))
        scene = build_document_scene(self.doc)
        # at 1 kHz the Steel top's category 3 too (up to 95 mm/s), at 8 kHz category 1's alone (up to 127)
        self.assertIn("up to 95 mm/s", surface_object.rate_notes(self.doc, 1000)[0])
        for rate, expected in ((1000, surface_object.rate_notes(self.doc, 1000)),
                               (8000, [surface_object.rate_note(s, 8000)])):
            session = feel_session.LiveSession(scene, prefs=preferences.Preferences(servo_rate_hz=rate))
            try:
                self.assertEqual(session.roughness_notes(self.doc), expected, rate)
            finally:
                session.stop()

    def test_the_hand_is_held_at_the_surface(self):
        prefs = preferences.Preferences(servo_rate_hz=1000, force_limit_n=3.0)
        session = feel_session.LiveSession(self.scene, prefs=prefs)
        above = np.array([20, 15, 30]) * MM
        session.start(above)
        try:
            free = drain_ticks(session, 300)
            session.set_target(np.array([20, 15, 18]) * MM)  # 2 mm into the top face
            pressed = drain_ticks(session, 600)
        finally:
            session.stop()
        self.assertFalse(session.running)
        self.assertFalse((free["flags"] & _core.FLAG_CONTACT).any())  # above the part: nothing touched
        # the rate the panel shows: the loop's own count over its run, never above what was asked
        self.assertGreater(session.achieved_rate_hz(), 0.0)
        self.assertLessEqual(session.achieved_rate_hz(), 1000 * 1.02)
        last = pressed[-50:]
        contact = (last["flags"] & _core.FLAG_CONTACT) != 0
        self.assertTrue(contact.all())
        self.assertTrue((last["cad_face"] == self.scene.face_id("Box.Face6")).all())
        # the proxy stays on the surface, the force pushes up, within the force limit
        self.assertTrue(np.allclose(last["proxy_m"][:, 2], 20 * MM, atol=0.05 * MM))
        self.assertTrue((last["force_n"][:, 2] > 0.1).all())
        self.assertLessEqual(float(np.linalg.norm(last["force_n"], axis=1).max()), 3.0 + 1e-9)
        self.assertIn("Box.Face6", session.describe_face(int(last["cad_face"][-1])))
        self.assertIn("Steel", session.describe_face(int(last["cad_face"][-1])))

    def test_a_property_edit_is_felt_in_the_running_session_without_a_rebuild(self):
        surface = self.doc.getObject("HapticSurface")
        session, steel = self.press_on_the_top()
        scene_before = session.doc_scene.scene
        try:
            # a much softer face, while the loop runs
            surface.Stiffness = 0.05  # N/mm
            self.doc.recompute()
            session.update_surfaces(self.doc)
            softening = drain_ticks(session, 600)
            soft = softening[-50:]
            # an edit that cannot be compiled is refused with its name; the loop keeps the soft face
            surface.Pattern = "Curve"  # with no curve to follow
            with self.assertRaises(ValueError) as raised:
                session.update_surfaces(self.doc)
            self.assertIn(surface.Label, str(raised.exception))
            still_soft = drain_ticks(session, 100)[-50:]
            running = session.running
        finally:
            session.stop()
        self.assertTrue(running)
        self.assertIs(session.doc_scene.scene, scene_before)  # nothing was rebuilt
        f_steel = float(np.median(steel["force_n"][:, 2]))
        f_soft = float(np.median(soft["force_n"][:, 2]))
        self.assertTrue((soft["flags"] & _core.FLAG_CONTACT).all())
        # the hand's grip and the face's spring in series: 50 N/m is felt much softer
        self.assertGreater(f_steel, 0.3)
        self.assertLess(f_soft, 0.5 * f_steel)
        self.assertAlmostEqual(float(np.median(still_soft["force_n"][:, 2])), f_soft, delta=0.02)
        # under the pressing hand the face gave way over the edit's 0.2 s ramp, not in
        # one tick: the largest change from one tick to the next is the encoder's
        # 0.055 mm step on the still stiff face (0.04 N), not the drop
        blending = (softening["flags"] & _core.FLAG_EDIT_BLENDING) != 0
        self.assertGreater(int(blending.sum()), 150)
        self.assertLess(int(blending.sum()), 250)
        steps = np.abs(np.diff(softening["force_n"][:, 2]))
        self.assertLess(float(steps.max()), 0.25 * (f_steel - f_soft), steps.max())
        self.assertAlmostEqual(session.doc_scene.surfaces.surface(self.scene.face_id("Box.Face6")).stiffness_n_per_m,
                               50.0)

    def test_a_geometry_edit_is_felt_in_the_running_session(self):
        session, before = self.press_on_the_top()
        scene_before = session.doc_scene.scene
        try:
            # the box grows 5 mm while the hand rests on its top: hand and proxy are now
            # inside the part, and the new top pushes the hand out of it
            self.box.Height = 25
            self.doc.recompute()
            session.update_scene(self.doc)
            after = drain_ticks(session, 600)[-50:]
            running = session.running
        finally:
            session.stop()
        self.assertTrue(running)
        self.assertIsNot(session.doc_scene.scene, scene_before)
        for trace, top in ((before, 20), (after, 25)):
            self.assertTrue((trace["flags"] & _core.FLAG_CONTACT).all(), top)
            self.assertTrue((trace["cad_face"] == session.doc_scene.face_id("Box.Face6")).all(), top)
            self.assertTrue(np.allclose(trace["proxy_m"][:, 2], top * MM, atol=0.05 * MM), top)
        # the hand still aims at 18 mm: 7 mm under the new top instead of 2, so it is
        # pushed up harder (the grip and the face in series), within the force limit
        f_before = float(np.median(before["force_n"][:, 2]))
        f_after = float(np.median(after["force_n"][:, 2]))
        self.assertGreater(f_before, 0.3)
        self.assertGreater(f_after, 2.0 * f_before)
        self.assertLessEqual(float(np.linalg.norm(after["force_n"], axis=1).max()), 3.0 + 1e-9)

    def test_a_hand_let_go_of_its_proxy_caught_under_the_part_takes_hold_again_in_the_open(self):
        # the box moved 14 mm up over the resting hand: the proxy restarts on its bottom
        # (6 mm away, the top 14), and pulls the hand aiming up through the part back down
        session, _ = self.press_on_the_top()
        try:
            self.box.Placement.Base = App.Vector(0, 0, 14)
            self.doc.recompute()
            session.update_scene(self.doc)
            session.set_target(np.array([20, 15, 44]) * MM)  # 10 mm over the new top
            caught = drain_ticks(session, 600)[-50:]
            session.let_go()  # the force stops, the hand goes up freely
            let_go = drain_ticks(session, 600)
            hand_mm = session.hand_w() / MM
            session.take_hold()  # the proxy restarts at the hand, in the open
            held = drain_ticks(session, 300)[-50:]
            session.set_target(np.array([20, 15, 32]) * MM)  # 2 mm into the new top
            pressed = drain_ticks(session, 600)[-50:]
            running = session.running
        finally:
            session.stop()
        self.assertTrue(running)
        bottom, top = session.doc_scene.face_id("Box.Face5"), session.doc_scene.face_id("Box.Face6")
        self.assertTrue((caught["cad_face"] == bottom).all())
        self.assertTrue(np.allclose(caught["proxy_m"][:, 2], 14 * MM, atol=0.05 * MM))
        self.assertLess(float(caught["device_m"][-1, 2]), 40 * MM)  # held down by the force
        # let go: no force, the loop's tool stays, the hand rises to its target
        self.assertTrue((let_go["flags"][-300:] & _core.FLAG_CLUTCHED).all())
        self.assertEqual(float(np.abs(let_go["force_n"][-300:]).max()), 0.0)
        np.testing.assert_allclose(hand_mm, [20, 15, 44], atol=0.5)
        # taken hold again: the proxy at the hand over the part, touching nothing
        self.assertFalse((held["flags"] & (_core.FLAG_CONTACT | _core.FLAG_CLUTCHED)).any())
        np.testing.assert_allclose(held["proxy_m"], held["device_m"], atol=1e-9)
        self.assertGreater(float(held["proxy_m"][-1, 2]), 43 * MM)
        # and the hand comes down onto the new top
        self.assertTrue((pressed["cad_face"] == top).all())
        self.assertTrue(np.allclose(pressed["proxy_m"][:, 2], 34 * MM, atol=0.05 * MM))

    def test_a_geometry_edit_that_cannot_be_felt_leaves_the_old_scene_running(self):
        self.doc.removeObject("HapticSurface")  # the plate's surface is the only one
        part = self.doc.addObject("Part::Feature", "Plate")
        part.Shape = self.box.Shape.copy()
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(part, "Face3")], material="Steel")
        scene = build_document_scene(self.doc)
        session = feel_session.LiveSession(scene)
        session.start(np.array([20, 15, 30]) * MM)
        try:
            # the plate becomes a ball: one face, its tagged Face3 gone, nothing to feel
            part.Shape = Part.makeSphere(5)
            self.doc.recompute()
            with self.assertRaises(ValueError) as raised:
                session.update_scene(self.doc)
            time.sleep(0.1)
            running = session.running
        finally:
            session.stop()
        self.assertTrue(running)
        self.assertIn("broken", str(raised.exception))
        self.assertIs(session.doc_scene, scene)

    def test_tagging_a_part_outside_the_scene_builds_a_new_scene(self):
        session = feel_session.LiveSession(self.scene)
        other = self.doc.addObject("Part::Box", "Other")
        other.Placement.Base = App.Vector(45, 0, 0)  # within the probe's reach (to x = 90 mm)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(other, "Face1")], material="Steel")
        # recompiling the surfaces alone cannot take it
        with self.assertRaises(NeedsNewScene) as raised:
            session.update_surfaces(self.doc)
        self.assertIn("not in the scene being felt", str(raised.exception))
        self.assertIs(session.doc_scene, self.scene)
        # the panel's edit handler builds the scene again instead
        self.assertEqual(session.apply_edit(self.doc, geometry=False), "scene")
        self.assertIn("Other", session.doc_scene.shapes)
        face = session.doc_scene.face_id("Other.Face1")
        self.assertEqual(session.doc_scene.surfaces.surface(face).stiffness_n_per_m,
                         session.doc_scene.surfaces.surface(session.doc_scene.face_id("Box.Face6")).stiffness_n_per_m)
        # a plain property edit is still only a recompile
        self.doc.getObject("HapticSurface").Stiffness = 0.05
        self.doc.recompute()
        scene = session.doc_scene.scene
        self.assertEqual(session.apply_edit(self.doc, geometry=False), "surfaces")
        self.assertIs(session.doc_scene.scene, scene)
        # deleting the tagged part: the scene is built without it
        self.doc.removeObject("Other")
        self.doc.recompute()
        with self.assertRaises(NeedsNewScene):
            session.update_surfaces(self.doc)
        self.assertEqual(session.apply_edit(self.doc, geometry=False), "scene")
        self.assertEqual(sorted(session.doc_scene.shapes), ["Box"])

    def test_a_part_grown_beyond_the_simulated_probes_reach_asks_for_a_new_session(self):
        session = feel_session.LiveSession(self.scene)
        self.box.Height = 200  # the workspace was set to 50 mm round the 20 mm box
        self.doc.recompute()
        with self.assertRaises(ValueError) as raised:
            session.update_scene(self.doc)
        self.assertIn("workspace", str(raised.exception))
        self.assertIs(session.doc_scene, self.scene)


if __name__ == "__main__":
    unittest.main()
