# SPDX-License-Identifier: GPL-3.0-or-later
"""The live Feel session adapter, headless: with the device layer's live bindings it
runs the real C++ servo loop with the simulated hand (the hand aims into the top face
and is held at its surface); without them it refuses to start, naming what is missing.
Run by freecadcmd."""
import time
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad import _core, feel_session, preferences
from hapticad.document_scene import build_document_scene

MM = 1e-3


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

    def test_device_choices_start_with_the_simulated_probe(self):
        choices = feel_session.device_choices()
        self.assertEqual(choices[0].path, "simulated")
        self.assertTrue(choices[0].simulated)
        self.assertEqual(len({c.path for c in choices}), len(choices))

    def test_listed_hid_devices_follow_the_simulated_probe(self):
        # the binding lists dicts (issue 5); simulated entries are not HID choices
        listed = [{"kind": "sim", "name": "Simulated hand", "path": "sim:hand", "limits": None},
                  {"kind": "hid", "name": "Prototype", "path": "/dev/hidraw7", "limits": None}]
        saved = getattr(_core, "list_devices", None)
        _core.list_devices = lambda: listed
        try:
            choices = feel_session.device_choices()
        finally:
            if saved is None:
                del _core.list_devices
            else:
                _core.list_devices = saved
        self.assertEqual([c.path for c in choices], ["simulated", "/dev/hidraw7"])
        self.assertEqual(choices[1].label, "Prototype (/dev/hidraw7)")

    def test_the_hand_is_held_at_the_surface(self):
        prefs = preferences.Preferences(servo_rate_hz=1000, force_limit_n=3.0)
        session = feel_session.LiveSession(self.scene, prefs=prefs)
        above = np.array([20, 15, 30]) * MM
        session.start(above)
        try:
            time.sleep(0.3)
            free = session.drain()
            session.set_target(np.array([20, 15, 18]) * MM)  # 2 mm into the top face
            time.sleep(0.6)
            pressed = session.drain()
        finally:
            session.stop()
        self.assertFalse(session.running)
        self.assertGreater(len(free), 100)
        self.assertGreater(len(pressed), 300)
        self.assertGreater(session.achieved_rate_hz(), 500.0)
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


if __name__ == "__main__":
    unittest.main()
