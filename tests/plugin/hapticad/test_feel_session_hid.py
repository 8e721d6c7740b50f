# SPDX-License-Identifier: GPL-3.0-or-later
"""A Feel session on a HID device (the hidapi emulator preloaded in front of libhidapi,
emu:0), given its path or the device opened already: its workspace mapping fits the
parts when it starts, and a part that then grows beyond it is still felt where the
device reaches, with a note that says so. The loop is not started: the mapping and the
scene swap are what is tested. Run by freecadcmd."""
import unittest

import numpy as np

import FreeCAD as App

import HaptiCAD
from hapticad import _core, feel_session, preferences
from hapticad.document_scene import build_document_scene


class ReachTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("FeelHid")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="Steel")

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def session(self, **prefs):
        return feel_session.LiveSession(build_document_scene(self.doc), device="emu:0",
                                        prefs=preferences.Preferences(**prefs))

    def test_a_part_grown_beyond_the_fitted_workspace_is_felt_with_a_note(self):
        session = self.session(workspace_mapping="Fit part")
        self.assertIsNone(session.reach_note)
        self.box.Length = 400  # ten times longer: far beyond the mapping fitted to 40 mm
        self.doc.recompute()
        session.update_scene(self.doc)  # swapped in, not refused
        self.assertEqual(session.doc_scene.shapes["Box"].BoundBox.XLength, 400)
        self.assertIn("beyond the device's workspace", session.reach_note)
        self.box.Length = 40
        self.doc.recompute()
        session.update_scene(self.doc)
        self.assertIsNone(session.reach_note)

    def test_a_large_part_fitted_to_the_workspace_is_within_reach(self):
        # the note at the start used the loop's mapping before its first tick: identity
        self.box.Length, self.box.Width, self.box.Height = 1000, 600, 300
        self.doc.recompute()
        session = self.session(workspace_mapping="Fit part")
        self.assertGreater(session.mapping.scale, 5.0)
        self.assertIsNone(session.reach_note)
        session.update_scene(self.doc)
        self.assertIsNone(session.reach_note)

    def test_a_session_takes_a_device_opened_already_as_it_takes_its_path(self):
        # the Feel panel opens the device off the GUI thread (device_opening) and hands it over
        device = _core.open_device("emu:0")
        session = feel_session.LiveSession(build_document_scene(self.doc), device=device,
                                           prefs=preferences.Preferences(workspace_mapping="Fit part"))
        self.assertIs(session.device, device)
        self.assertFalse(session.simulated)
        by_path = self.session(workspace_mapping="Fit part")
        self.assertEqual(session.device.info.name, by_path.device.info.name)
        self.assertEqual(session.mapping.scale, by_path.mapping.scale)
        np.testing.assert_allclose(session.mapping.offset_w, by_path.mapping.offset_w)
        self.assertEqual(session.render_limits.max_force_n, by_path.render_limits.max_force_n)

    def test_a_fixed_scale_that_cannot_hold_the_part_is_noted_at_the_start(self):
        limits = _core.open_device("emu:0").info.limits
        span_mm = float(np.max(np.asarray(limits.workspace_max_d) - np.asarray(limits.workspace_min_d))) * 1e3
        self.box.Length = 2 * span_mm
        self.doc.recompute()
        self.assertIn("clutch", self.session(workspace_mapping="Fixed scale", workspace_scale=1.0).reach_note)

    def test_beyond_reach_checks_every_corner_through_the_mapping(self):
        limits = _core.simulated_hand_limits()
        limits.workspace_min_d = np.array([-0.1, -0.1, -0.1])
        limits.workspace_max_d = np.array([0.1, 0.1, 0.1])
        mapping = _core.WorkspaceMapping()
        inside = (np.array([-0.05, -0.05, 0.0]), np.array([0.05, 0.05, 0.09]))
        self.assertIsNone(feel_session.beyond_reach(limits, mapping, *inside))
        mapping.scale = 0.5  # the device's 0.2 m covers 0.1 m of the world
        self.assertIsNotNone(feel_session.beyond_reach(limits, mapping, *inside))
        mapping.scale = 1.0
        mapping.offset_w = np.array([0.0, 0.0, 0.05])  # the device's box spans z -0.05..0.15 m
        self.assertIsNone(feel_session.beyond_reach(limits, mapping, inside[0], inside[1] + [0, 0, 0.05]))
        self.assertIsNotNone(feel_session.beyond_reach(limits, mapping, inside[0], inside[1] + [0, 0, 0.07]))
        self.assertIsNotNone(feel_session.beyond_reach(limits, mapping, inside[0] - [0, 0, 0.06], inside[1]))


if __name__ == "__main__":
    unittest.main()
