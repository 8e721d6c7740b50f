# SPDX-License-Identifier: GPL-3.0-or-later
"""A Feel session in FreeCAD's real GUI (Xvfb) with the simulated probe, driven by
synthetic mouse events: the probe follows the mouse across the tagged face, the wheel
presses harder, the strip chart receives the forces, the status names the face, Stop
ends it. The servo loop is the C++ one. Run by gui_test_runner.py."""
import os
import sys
import time
import unittest

import numpy as np

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtGui, QtWidgets

import HaptiCAD
from hapticad import preferences

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402

MM = 1e-3


class FeelGuiTest(unittest.TestCase):
    def setUp(self):
        preferences.update(device="simulated", servo_rate_hz=1000)
        self.doc = App.newDocument("FeelGui")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", pattern="Linear")
        self.doc.recompute()
        h.show_workbench()

    def tearDown(self):
        if Gui.Control.activeDialog():
            h.press_task_button("Close")
        if self.doc is not None:
            App.closeDocument(self.doc.Name)

    def open_feel(self):
        """Opens Feel on the document; returns the panel, its session running."""
        from hapticad.gui import task_panel_feel

        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        panel = task_panel_feel.active_panel()
        self.assertTrue(panel.session is not None, h.widget(QtWidgets.QLabel, "feelMessage").text())
        return panel

    def start_feeling(self):
        """Opens Feel, steers the probe onto the top face; returns the panel."""
        panel = self.open_feel()
        h.mouse("move", h.screen_pos(np.array([20.0, 15.0, 20.0])))
        self.wait_touching("Box.Face6")
        return panel

    def wait_touching(self, face):
        """Until the probe touches ``face`` (it comes down at 150 mm/s, then slows near the
        face: a loaded host draws that later), has landed and presses steadily."""
        label = h.widget(QtWidgets.QLabel, "feelFace")
        h.wait_for(lambda: face in label.text(), f"touching {face}: {label.text()}")
        h.wait_settled(h.widget(QtWidgets.QWidget, "stripChart"), f"resting on {face}")

    def test_closing_the_document_while_feeling_stops_the_session_and_closes_the_panel(self):
        from hapticad.gui import task_panel_feel

        panel = self.start_feeling()
        session = panel.session
        App.closeDocument(self.doc.Name)  # asked the 3D view for its scene graph: a crash
        self.doc = None
        h.wait(0.3)
        self.assertFalse(session.running)
        self.assertIsNone(panel.session)
        self.assertFalse(panel.timer.isActive())
        self.assertFalse(Gui.Control.activeDialog())
        self.assertIsNone(task_panel_feel.active_panel())
        # a new document and a new session work as before
        self.setUp()
        self.start_feeling()
        h.widget(QtWidgets.QPushButton, "feelStop").click()
        h.process_events()

    def test_a_panel_closed_without_close_does_not_leave_the_loop_running(self):
        panel = self.start_feeling()
        session = panel.session
        Gui.Control.closeDialog()  # the display timer then drew on deleted widgets forever
        h.wait(0.3)
        self.assertFalse(session.running)
        self.assertFalse(panel.timer.isActive())
        self.assertIsNone(panel.session)

    def test_feel_runs_in_the_3d_view_when_a_spreadsheet_is_active_and_says_when_there_is_none(self):
        from hapticad.gui import task_panel_feel

        sheet = self.doc.addObject("Spreadsheet::Sheet", "Params")
        self.doc.recompute()
        sheet.ViewObject.doubleClicked()  # its view active: Feel raised AttributeError (getSceneGraph)
        h.process_events()
        gui_doc = Gui.getDocument(self.doc.Name)
        self.assertFalse(hasattr(gui_doc.ActiveView, "getSceneGraph"))
        panel = self.open_feel()
        self.assertTrue(hasattr(gui_doc.ActiveView, "getSceneGraph"))  # brought to the front
        self.assertTrue(panel.session.running)
        h.press_task_button("Close")
        h.process_events()
        # the 3D view closed, the spreadsheet's left: said, nothing built
        for window in Gui.getMainWindow().findChild(QtWidgets.QMdiArea).subWindowList():
            if "3D" in window.windowTitle() or "FeelGui : 1" in window.windowTitle():
                window.close()
        h.process_events()
        self.assertFalse(gui_doc.mdiViewsOfType("Gui::View3DInventor"))
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        panel = task_panel_feel.active_panel()
        self.assertIsNone(panel.session)
        self.assertIn("Feel draws the probe in a 3D view of FeelGui, and it has none open",
                      h.widget(QtWidgets.QLabel, "feelMessage").text())

    def test_closing_the_view_feel_runs_in_leaves_a_panel_that_stops_and_closes(self):
        from hapticad.gui import task_panel_feel

        Gui.runCommand("Std_ViewCreate")  # a second 3D view of the document, active
        h.process_events()
        panel = self.start_feeling()
        session = panel.session
        Gui.getMainWindow().findChild(QtWidgets.QMdiArea).activeSubWindow().close()
        h.process_events()
        h.widget(QtWidgets.QPushButton, "feelStop").click()  # raised: its scene graph was deleted
        h.process_events()
        self.assertFalse(session.running)
        self.assertIsNone(panel.session)
        self.assertTrue(h.widget(QtWidgets.QPushButton, "feelStart").isEnabled())
        h.press_task_button("Close")
        h.process_events()
        self.assertIsNone(task_panel_feel.active_panel())
        self.assertFalse(Gui.Control.activeDialog())

    def test_a_simulated_session_follows_the_mouse_and_charts_the_forces(self):
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        self.assertTrue(Gui.Control.activeDialog())
        stop = h.widget(QtWidgets.QPushButton, "feelStop")
        self.assertTrue(stop.isEnabled(), h.widget(QtWidgets.QLabel, "feelMessage").text())
        chart = h.widget(QtWidgets.QWidget, "stripChart")
        depth = h.widget(QtWidgets.QSlider, "feelDepth")
        # slide the mouse across the top face, left to right, for about a second
        path = [np.array([6.0 + 28.0 * i / 40, 15.0, 20.0]) for i in range(41)]
        h.mouse("move", h.screen_pos(path[0]))
        h.wait(0.4)
        start_depth = depth.value()
        h.wheel(h.screen_pos(path[0]), 2)  # press harder
        self.assertEqual(depth.value(), start_depth + 2)
        devices = []
        for point in path:
            h.mouse("move", h.screen_pos(point))
            h.wait(0.025)
            devices.append(probe_mm())
        h.wait(0.3)
        h.widen_panel()
        h.wait(0.1)
        h.grab_screen("feel_session.png")
        h.save_view("feel_session_view.png", "Current")
        h.wait_for(lambda: chart.sample_count > 800, "800 samples charted")  # about 1.5 s at 1 kHz
        normal = chart.values["normal_force_n"]
        self.assertGreater(float(normal[-200:].mean()), 0.2)  # pressing on the face
        self.assertGreater(float(np.abs(chart.values["friction_force_n"][-600:]).max()), 0.05)
        face = h.widget(QtWidgets.QLabel, "feelFace").text()
        self.assertIn("Box.Face6", face)
        self.assertIn("ABS", face)
        self.assertIn("Hz", h.widget(QtWidgets.QLabel, "feelRate").text())
        # the probe followed the mouse along x, on (a little into) the top face
        self.assertGreater(devices[-1][0] - devices[0][0], 15.0)
        self.assertLess(abs(devices[-1][2] - 20.0), 2.0)
        stop.click()
        h.process_events()
        self.assertFalse(stop.isEnabled())
        self.assertIn("stopped", h.widget(QtWidgets.QLabel, "feelRate").text())
        # nothing is touched now: the face the probe was on is no longer said
        self.assertEqual(h.widget(QtWidgets.QLabel, "feelFace").text(), "Face: -")
        graph = Gui.ActiveDocument.ActiveView.getSceneGraph()
        names = [graph.getChild(i).getName().getString() for i in range(graph.getNumChildren())]
        self.assertNotIn("HaptiCAD_Feel", names)
        h.press_task_button("Close")

    def test_feel_builds_the_scene_with_the_custom_accuracy_chosen_in_the_preferences(self):
        preferences.update(accuracy="Custom", custom_linear_deflection_mm=0.4, custom_angular_deflection_deg=25.0,
                           custom_force_shading=False)
        try:
            panel = self.open_feel()
            built = panel.doc_scene.accuracy
            self.assertEqual((built.name, built.linear_deflection_mm, built.force_shading), ("Custom", 0.4, False))
            self.assertAlmostEqual(built.angular_deflection_rad, np.radians(25.0), places=12)
            h.press_task_button("Close")
        finally:
            preferences.update(accuracy="Fine")

    def test_preferences_changed_during_a_session_are_said_to_apply_at_the_next_start(self):
        # the session keeps the servo rate and force limit it started with, and nothing said
        # so: the panel went on talking of its rate as if the new one were in use
        kept = preferences.load()
        self.addCleanup(preferences.save, kept)
        panel = self.open_feel()
        note = h.widget(QtWidgets.QLabel, "feelPreferencesNote")
        self.assertFalse(note.isVisible())
        preferences.update(overlay_colour_by="Roughness")  # nothing the session uses
        h.wait(0.6)
        self.assertFalse(note.isVisible())
        self.assertEqual(note.text(), "")
        said = []
        set_text = note.setText
        note.setText = lambda text: (said.append(text), set_text(text))
        preferences.update(servo_rate_hz=2000, force_limit_n=2.0)  # as the Preferences dialog's OK saves them
        h.wait_for(lambda: note.isVisible(), "the note on the preferences")
        h.widen_panel()
        h.grab_screen("feel_preferences_changed.png")
        self.assertIn("Preferences changed (servo rate, force limit): they apply when you press Stop and Start again",
                      note.text())
        self.assertEqual((panel.session.rate_hz, panel.session.render_limits.max_force_n), (1000.0, 3.0))
        h.wait(0.8)
        self.assertEqual(len(said), 1)  # said once, not at every look
        # Stop and Start: the session takes them, and the note goes
        h.widget(QtWidgets.QPushButton, "feelStop").click()
        h.process_events()
        self.assertFalse(note.isVisible())
        h.widget(QtWidgets.QPushButton, "feelStart").click()
        h.process_events()
        self.assertEqual((panel.session.rate_hz, panel.session.render_limits.max_force_n), (2000.0, 2.0))
        h.wait(0.6)
        self.assertFalse(note.isVisible())
        # changed, and changed back to the session's: the note comes and goes
        preferences.update(servo_rate_hz=1000)
        h.wait_for(lambda: note.isVisible(), "the note on the servo rate")
        self.assertIn("(servo rate)", note.text())
        preferences.update(servo_rate_hz=2000)
        h.wait_for(lambda: not note.isVisible(), "the note gone")

    def press_on_the_top(self):
        """Starts a session and presses the probe well into the middle of the top face;
        the panel's Stop button and strip chart."""
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        stop = h.widget(QtWidgets.QPushButton, "feelStop")
        self.assertTrue(stop.isEnabled(), h.widget(QtWidgets.QLabel, "feelMessage").text())
        chart = h.widget(QtWidgets.QWidget, "stripChart")
        h.mouse("move", h.screen_pos(np.array([20.0, 15.0, 20.0])))
        h.wait_settled(chart, "landed on the top")
        h.wheel(h.screen_pos(np.array([20.0, 15.0, 20.0])), 4)
        h.wait_settled(chart, "pressing 2 mm in")
        return stop, chart

    def test_a_vibration_the_servo_rate_cannot_render_is_said_when_feeling_starts(self):
        HaptiCAD.make_vibration(self.doc, self.box, frequency_hz=700.0, amplitude_n=0.5)
        self.open_feel()  # at 1000 Hz (setUp's preference)
        self.assertIn("700 Hz is felt at 300 Hz instead", h.widget(QtWidgets.QLabel, "feelMessage").text())

    def test_a_vibration_beyond_the_force_limit_is_said_when_feeling_starts(self):
        vibration = HaptiCAD.make_vibration(self.doc, self.box, frequency_hz=150.0, amplitude_n=10.0)
        panel = self.open_feel()
        limit = panel.session.render_limits.max_force_n
        self.assertLess(limit, 10.0)
        self.assertIn(f"{vibration.Label}: 10 N alone it reaches the {limit:g} N force limit",
                      h.widget(QtWidgets.QLabel, "feelMessage").text())

    def test_a_study_is_judged_by_the_devices_force_limit_after_stop_too(self):
        # the simulated hand renders 8.9 N at most: with 20 N in the Preferences a 12 N click is never felt,
        # while the session runs and after Stop (the panel then judged by the preference alone, and a
        # participant recorded after Stop kept 20 N and no mark)
        from hapticad import _core, stiffness_study

        hand = _core.simulated_hand_limits().max_force_n
        self.addCleanup(preferences.update, force_limit_n=preferences.load().force_limit_n)
        preferences.update(force_limit_n=20.0)
        study = HaptiCAD.make_study(self.doc, HaptiCAD.surfaces_of(self.doc)[0], model="Push button",
                                    OperatingForce=12.0)
        panel = self.open_feel()
        said = f"the operating force, 12 N, is above the force limit, {hand:.3g} N"
        self.assertIn(said, h.widget(QtWidgets.QLabel, "studyValue").text())
        h.widget(QtWidgets.QPushButton, "feelStop").click()
        h.process_events()
        self.assertIsNone(panel.session)
        self.assertEqual(panel.force_limit(), hand)
        self.assertIn(said, h.widget(QtWidgets.QLabel, "studyValue").text())
        h.widget(QtWidgets.QLineEdit, "participantName").setText("Ann")
        h.widget(QtWidgets.QComboBox, "participantGender").setCurrentText("F")
        h.widget(QtWidgets.QComboBox, "participantAge").setCurrentText("26-40")
        h.widget(QtWidgets.QPushButton, "recordPreference").click()
        h.process_events()
        ann = stiffness_study.records(study)[-1]
        self.assertEqual((ann.design["ForceLimit"], ann.design["BeyondForceLimit"]), (hand, 1.0))
        # a preference under the device's is the limit, as before
        preferences.update(force_limit_n=3.0)
        self.assertEqual(panel.force_limit(), 3.0)

    def test_a_vibration_along_the_face_is_drawn_in_the_chart_while_touching(self):
        HaptiCAD.make_vibration(self.doc, self.box, frequency_hz=150.0, amplitude_n=0.3, axis=(1.0, 0.0, 0.0))
        _, chart = self.press_on_the_top()
        vibration = np.asarray(chart.values["vibration_force_n"][-300:], float)
        self.assertAlmostEqual(float(vibration.max()), 0.3, delta=0.03)
        self.assertIn("vibration_force_n", chart.drawn())
        h.widen_panel()
        h.grab_screen("feel_vibration.png")

    def test_the_first_touch_lands_without_a_knock(self):
        # the hand comes from above the part's top and is lowered onto the face: landing
        # in one step it knocked at 1.45 N where it then pressed 0.27 N
        self.open_feel()
        chart = h.widget(QtWidgets.QWidget, "stripChart")
        h.mouse("move", h.screen_pos(np.array([20.0, 15.0, 20.0])))
        h.wait_settled(chart, "landed")
        self.assertIn("Box.Face6", h.widget(QtWidgets.QLabel, "feelFace").text())
        normal = np.asarray(chart.values["normal_force_n"], float)
        pressed = float(normal[-200:].mean())
        self.assertGreater(pressed, 0.2)
        self.assertLess(float(normal.max()), 1.3 * pressed)

    def test_a_hidden_part_is_felt_where_the_mouse_points_as_the_note_says(self):
        # the note said "Box is hidden: you feel Box's shape", but the view's pick skips
        # hidden parts: the probe never touched it
        self.box.ViewObject.Visibility = False
        h.process_events()
        self.open_feel()
        self.assertIn("Box is hidden", h.widget(QtWidgets.QLabel, "feelMessage").text())
        view = Gui.ActiveDocument.ActiveView
        for camera, point in (("Orthographic", (10.0, 8.0, 20.0)), ("Perspective", (30.0, 22.0, 20.0))):
            view.setCameraType(camera)
            h.process_events()
            h.mouse("move", h.screen_pos(np.array(point)))
            h.wait_for(lambda: np.linalg.norm(probe_mm("proxy_m")[:2] - point[:2]) < 1.0
                       and "Box.Face6" in h.widget(QtWidgets.QLabel, "feelFace").text(),
                       f"{camera}: the proxy on the hidden top face at {point}: {probe_mm('proxy_m')}")
            self.assertAlmostEqual(float(probe_mm("proxy_m")[2]), 20.0, delta=0.1)
        h.grab_screen("feel_hidden_part.png")
        # off the part the hand lifts off, as over a part that is shown
        h.mouse("move", h.screen_pos(np.array([90.0, -60.0, 0.0])))
        h.wait_for(lambda: "not touching" in h.widget(QtWidgets.QLabel, "feelFace").text(), "lifted off")

    def test_a_vibration_whose_part_was_deleted_is_said_when_feeling_starts(self):
        motor = self.doc.addObject("Part::Box", "Motor")
        motor.Placement.Base = App.Vector(60, 0, 0)
        self.doc.recompute()
        vibration = HaptiCAD.make_vibration(self.doc, motor)
        self.doc.removeObject("Motor")
        self.doc.recompute()
        self.open_feel()
        self.assertIn(f"Note: {vibration.Label}: no part to vibrate: Motor, which it vibrated, was deleted; undo "
                      "the deletion", h.widget(QtWidgets.QLabel, "feelMessage").text())

    def test_the_wheel_turned_while_coming_down_sets_where_it_lands(self):
        panel = self.open_feel()
        chart = h.widget(QtWidgets.QWidget, "stripChart")
        point = h.screen_pos(np.array([20.0, 15.0, 20.0]))
        h.mouse("move", point)
        h.wheel(point, 6)  # 1 -> 2.5 mm before it has landed
        self.assertFalse(panel.steering.hand.landed)
        h.wait_settled(chart, "landed")
        self.assertEqual(panel.depth_mm(), 2.5)
        # grip (0.4 N/mm) in series with the face (0.8 N/mm): 0.67 N at 2.5 mm, 0.27 at 1
        self.assertGreater(float(np.asarray(chart.values["normal_force_n"][-200:]).mean()), 0.55)

    def feel_a_stepped_part(self):
        """Feel on a 60 x 30 x 10 mm base with a 5 mm block standing on it at x 30..50,
        both tops tagged; returns the panel."""
        App.closeDocument(self.doc.Name)
        self.doc = App.newDocument("FeelStep")
        base = self.doc.addObject("Part::Box", "Base")
        base.Length, base.Width, base.Height = 60, 30, 10
        block = self.doc.addObject("Part::Box", "Block")
        block.Length, block.Width, block.Height = 20, 30, 5
        block.Placement.Base = App.Vector(30, 0, 10)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(base, "Face6"), (block, "Face6")], material="ABS")
        self.doc.recompute()
        Gui.SendMsgToActiveView("ViewFit")
        return self.open_feel()

    def test_a_jump_of_the_cursor_across_the_part_comes_over_it_not_through(self):
        # the cursor jumps from the base right of the block to the base left of it in one
        # move. Straight there, the hand was dragged through the block: the proxy stayed
        # caught on its wall, the hand tens of mm away, pulled at the force limit (a
        # reviewer's toothbrush: 101 mm, 3 N)
        panel = self.feel_a_stepped_part()
        h.mouse("move", h.screen_pos(np.array([56.0, 15.0, 10.0])))
        self.wait_touching("Base.Face6")
        h.mouse("move", h.screen_pos(np.array([10.0, 15.0, 10.0])))  # one move, across the block
        h.wait_for(lambda: abs(probe_mm("proxy_m")[0] - 10.0) < 1.0 and abs(probe_mm("proxy_m")[2] - 10.0) < 0.1,
                   f"the proxy on the base at x 10: {probe_mm('proxy_m')}")
        h.wait_settled(h.widget(QtWidgets.QWidget, "stripChart"), "landed on the base")
        self.assertIn("Base.Face6", h.widget(QtWidgets.QLabel, "feelFace").text())
        apart = np.linalg.norm(probe_mm("proxy_m") - probe_mm())
        self.assertLess(apart, 2.0)  # pressing 1 mm, not held anywhere else
        self.assertLess(float(np.linalg.norm(panel.last_sample["force_n"])), 1.0)

    def test_the_probe_comes_down_onto_the_face_under_the_cursor_and_over_a_step_not_into_its_wall(self):
        panel = self.feel_a_stepped_part()
        # first touch right of the block: the hand starts above the middle (over the
        # block); straight for the face it would land on the block's top and stay there
        h.mouse("move", h.screen_pos(np.array([56.0, 15.0, 10.0])))
        self.wait_touching("Base.Face6")
        self.assertAlmostEqual(float(panel.last_sample["proxy_m"][2]) * 1e3, 10.0, delta=0.1)
        # slide left onto the block: over its 5 mm step, onto its top, not pressed into its wall
        for x in np.linspace(56.0, 40.0, 17):
            h.mouse("move", h.screen_pos(np.array([x, 15.0, 10.0 if x > 50 else 15.0])))
            h.wait(0.03)
        self.wait_touching("Block.Face6")
        proxy_mm = np.asarray(panel.last_sample["proxy_m"]) * 1e3
        self.assertAlmostEqual(float(proxy_mm[2]), 15.0, delta=0.1)
        self.assertLess(abs(float(proxy_mm[0]) - 40.0), 2.0)
        # the wheel presses harder at once, the mouse held still: 1 -> 2.5 mm aimed, the
        # hand's grip (0.4 N/mm) in series with the face (0.8 N/mm): 0.27 -> 0.67 N
        chart = h.widget(QtWidgets.QWidget, "stripChart")
        pressed = float(chart.values["normal_force_n"][-200:].mean())
        h.wheel(h.screen_pos(np.array([40.0, 15.0, 15.0])), 6)
        h.wait_settled(chart, "pressing 2.5 mm in")
        self.assertEqual(panel.depth_mm(), 2.5)
        self.assertGreater(float(chart.values["normal_force_n"][-200:].mean()), 1.8 * pressed)
        # aimed 2.5 mm in, the probe goes in less: the panel says how far, 0.67 N / 0.8 N/mm
        self.assertRegex(h.widget(QtWidgets.QLabel, "feelFace").text(), r"the probe 0\.[6-9]\d mm in")

    def test_the_chart_draws_friction_and_texture_as_felt_when_the_force_was_clamped(self):
        from hapticad import _core
        from hapticad.gui.strip_chart import StripChart

        trace = np.zeros(3, dtype=[("time_s", float), ("flags", np.uint32), ("normal_force_n", float),
                                   ("tangential_force_n", float), ("friction_force_n", float),
                                   ("texture_force_n", float)])
        trace["time_s"] = [0.0, 0.001, 0.002]
        trace["normal_force_n"] = [1.0, 2.0, 2.0]
        # rendered 0.6 N of friction (sent as is), then 7 N and 5 N of texture, sent at the 2.2 N limit
        trace["friction_force_n"] = [0.6, 0.0, 0.0]
        trace["texture_force_n"] = [0.0, 7.0, 5.0]
        trace["tangential_force_n"] = [0.6, 0.9, 0.9]
        trace["flags"] = [0, _core.FLAG_FORCE_CLAMPED, _core.FLAG_FORCE_CLAMPED]
        chart = StripChart()
        chart.append(trace)
        np.testing.assert_allclose(chart.values["friction_force_n"], [0.6, 0.0, 0.0])
        np.testing.assert_allclose(chart.values["texture_force_n"], [0.0, 0.9, 0.9])
        np.testing.assert_allclose(chart.values["normal_force_n"], [1.0, 2.0, 2.0])
        # no vibration: not drawn, not in the legend (most parts never vibrate)
        self.assertEqual(chart.drawn(), ["normal_force_n", "friction_force_n", "texture_force_n"])

    def test_the_chart_draws_a_vibration_whatever_its_axis(self):
        # a vibration along the face moves none of the other series: it showed nowhere
        from hapticad.gui.strip_chart import StripChart

        names = ("normal_force_n", "tangential_force_n", "friction_force_n", "texture_force_n", "vibration_force_n")
        trace = np.zeros(4, dtype=[("time_s", float), ("flags", np.uint32), *((n, float) for n in names)])
        trace["time_s"] = [0.0, 0.001, 0.002, 0.003]
        trace["normal_force_n"] = 0.8
        trace["vibration_force_n"] = [0.0, 0.3, 0.0, -0.3]
        chart = StripChart()
        chart.append(trace)
        np.testing.assert_allclose(chart.values["vibration_force_n"], [0.0, 0.3, 0.0, 0.3])
        self.assertIn("vibration_force_n", chart.drawn())
        chart.resize(400, 150)
        image = chart.grab().toImage()
        purple = sum(1 for x in range(image.width()) for y in range(image.height())
                     if QtGui.QColor(image.pixel(x, y)).name() == "#9467bd")
        self.assertGreater(purple, 20)  # its legend and its trace

    def test_a_double_click_on_a_surface_while_feeling_says_where_to_edit_it(self):
        self.open_feel()
        surface = self.doc.getObject("HapticSurface")
        handled = surface.ViewObject.Proxy.doubleClicked(surface.ViewObject)  # what the tree calls
        h.process_events()
        self.assertTrue(handled)
        self.assertIn(f"While you feel, edit {surface.Label} in the property editor",
                      h.widget(QtWidgets.QLabel, "feelMessage").text())
        from hapticad.gui import task_panel_feel

        self.assertIsNotNone(task_panel_feel.active_panel())  # Feel goes on, not replaced
        self.assertTrue(Gui.Control.activeDialog())

    def test_editing_the_surface_during_a_session_is_felt_at_once(self):
        stop, chart = self.press_on_the_top()
        abs_normal = float(chart.values["normal_force_n"][-200:].mean())
        # the designer softens the face in the property editor while feeling it
        surface = self.doc.getObject("HapticSurface")
        surface.Stiffness = 0.03  # N/mm
        self.doc.recompute()
        h.wait(0.8)
        soft_normal = float(chart.values["normal_force_n"][-200:].mean())
        message = h.widget(QtWidgets.QLabel, "feelMessage").text()
        h.grab_screen("feel_surface_edit.png")
        self.assertTrue(stop.isEnabled())  # the session went on
        self.assertIn("Surface edited", message)
        self.assertGreater(abs_normal, 0.2)
        self.assertLess(soft_normal, 0.5 * abs_normal)
        # an edit that cannot be compiled: named, and the soft face stays
        surface.Pattern = "Curve"
        self.doc.recompute()
        h.wait(0.3)
        self.assertIn("the Curve pattern needs a sketch or edge to follow",
                      h.widget(QtWidgets.QLabel, "feelMessage").text())
        self.assertTrue(stop.isEnabled())
        # an error of another kind (OCC's, the core's) is shown too, not lost to Qt
        from hapticad.gui import task_panel_feel

        session = task_panel_feel.active_panel().session

        def fails(doc, geometry):
            raise RuntimeError("the kernel said no")

        session.apply_edit = fails
        surface.Stiffness = 0.04
        self.doc.recompute()
        h.wait(0.3)
        self.assertIn("the kernel said no", h.widget(QtWidgets.QLabel, "feelMessage").text())
        self.assertTrue(stop.isEnabled())
        stop.click()
        h.process_events()
        # once stopped, edits no longer reach the closed session
        surface.Pattern = "None"
        self.doc.recompute()
        h.process_events()
        self.assertNotIn("Surface edited", h.widget(QtWidgets.QLabel, "feelMessage").text())
        h.press_task_button("Close")


    def test_editing_the_sketch_a_curve_pattern_follows_is_felt_at_once(self):
        import Part
        from hapticad.feel import Stroke, run_stroke_in_servo_loop, summarize

        sketch = self.doc.addObject("Sketcher::SketchObject", "Guide")
        sketch.Placement.Base = App.Vector(0, 0, 20)
        sketch.addGeometry(Part.LineSegment(App.Vector(20, 0, 0), App.Vector(20, 30, 0)))  # along y
        self.doc.recompute()
        surface = HaptiCAD.surfaces_of(self.doc)[0]
        surface.Pattern, surface.PatternCurve, surface.AcrossFriction = "Curve", (sketch, []), 2.0
        surface.FeelRoughness = False  # the friction alone
        self.doc.recompute()
        panel = self.open_feel()

        def along_x():
            """Ft/Fn of a stroke along x through what the session renders now."""
            summary = summarize(run_stroke_in_servo_loop(panel.doc_scene, Stroke((5, 15, 20), (35, 15, 20), 50, 1.0)),
                                panel.doc_scene)
            return summary["faces"]["Box.Face6"]["mean_ft_over_fn"]

        self.assertAlmostEqual(along_x(), 1.0, delta=0.05)  # across the line: ABS's 0.5 doubled
        sketch.movePoint(0, 1, App.Vector(5, 15, 0))  # the line turned to run along x
        sketch.movePoint(0, 2, App.Vector(35, 15, 0))
        self.doc.recompute()
        h.wait(0.3)
        self.assertIn("you feel the change now", h.widget(QtWidgets.QLabel, "feelMessage").text())
        self.assertAlmostEqual(along_x(), 0.5, delta=0.05)  # along it now

    def test_reshaping_the_part_during_a_session_is_felt_at_once(self):
        stop, chart = self.press_on_the_top()
        self.assertAlmostEqual(probe_mm("proxy_m")[2], 20.0, delta=0.05)
        before = float(chart.values["normal_force_n"][-200:].mean())
        # the designer makes the box 3 mm taller while resting on its top: the probe is
        # now inside the part, and the new top pushes it out
        self.box.Height = 23
        self.doc.recompute()
        h.wait(0.8)
        message = h.widget(QtWidgets.QLabel, "feelMessage").text()
        h.grab_screen("feel_geometry_edit.png")
        self.assertTrue(stop.isEnabled())  # the session went on
        self.assertIn("Geometry edited", message)
        self.assertAlmostEqual(probe_mm("proxy_m")[2], 23.0, delta=0.05)
        after = float(chart.values["normal_force_n"][-200:].mean())
        self.assertGreater(before, 0.2)
        self.assertGreater(after, 1.5 * before)
        # moved up 2 mm (its placement only: no new shape), then made 1 mm taller: one
        # rebuild each
        from hapticad.gui import task_panel_feel

        panel = task_panel_feel.active_panel()
        edits = panel.edits
        calls = []
        handler = edits.callback
        edits.callback = lambda geometry: (calls.append(geometry), handler(geometry))
        # what the panel shows while the part is built again
        shown = []
        apply_edit = panel.session.apply_edit
        panel.session.apply_edit = lambda doc, geometry: (shown.append(panel.message.text()),
                                                          apply_edit(doc, geometry))[1]
        self.box.Placement.Base = App.Vector(0, 0, 2)
        self.doc.recompute()
        h.wait(0.8)
        self.assertEqual(calls, [True])
        self.assertIn("building it again", shown[0])
        self.assertAlmostEqual(probe_mm("proxy_m")[2], 25.0, delta=0.05)
        self.box.Height = 24
        self.doc.recompute()
        h.wait(0.8)
        self.assertEqual(calls, [True, True])
        self.assertAlmostEqual(probe_mm("proxy_m")[2], 26.0, delta=0.05)
        # a second part, tagged while feeling: the scene is built again to hold it
        other = self.doc.addObject("Part::Box", "Other")
        other.Placement.Base = App.Vector(60, 0, 0)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(other, "Face6")], material="Steel")
        self.doc.recompute()
        h.wait(0.3)
        self.assertIn("built again", h.widget(QtWidgets.QLabel, "feelMessage").text())
        self.assertIn("Other", task_panel_feel_scene().shapes)
        # deleted while feeling: said as such, not as an edit of its shape
        self.doc.removeObject("Other")
        self.doc.recompute()
        h.wait(0.5)
        self.assertIn("Other left the scene (deleted, or no longer tagged)",
                      h.widget(QtWidgets.QLabel, "feelMessage").text())
        self.assertNotIn("Other", task_panel_feel_scene().shapes)
        self.assertTrue(stop.isEnabled())
        stop.click()
        h.process_events()
        h.press_task_button("Close")

    def move_the_part_up_under_the_resting_probe(self, before_the_move=None):
        """A 10 mm box felt resting on its top, then moved 7 mm up under the probe (after
        ``before_the_move(panel)``), the swap done: (the panel, its face label)."""
        self.box.Height = 10
        self.doc.recompute()
        h.show_workbench()
        panel = self.open_feel()
        label = h.widget(QtWidgets.QLabel, "feelFace")
        h.mouse("move", h.screen_pos(np.array([20.0, 15.0, 10.0])))
        self.wait_touching("Box.Face6")
        if before_the_move:
            before_the_move(panel)
        self.box.Placement.Base = App.Vector(0, 0, 7)
        self.doc.recompute()
        h.wait_for(lambda: "Geometry edited" in h.widget(QtWidgets.QLabel, "feelMessage").text(), "the swap")
        return panel, label

    def test_a_part_moved_up_over_the_resting_probe_lets_it_come_back_onto_its_top(self):
        # a 10 mm box moved 7 mm up under the probe resting on its top: the proxy restarts on
        # its bottom face (2 mm away, the top 8), and every way the hand took to the new top,
        # or off the part, went up through it: held under it at the force limit, "the probe
        # 10.38 mm in", until Stop and Start
        panel, label = self.move_the_part_up_under_the_resting_probe()

        def on_the_top():
            return abs(probe_mm("proxy_m")[2] - 17.0) < 0.1 and "Box.Face6" in label.text()

        # the mouse held still: it re-lands on the top face under the cursor, as at the first touch
        wait_probe(on_the_top, "the proxy on the new top")
        h.widen_panel()
        h.grab_screen("feel_part_moved_up.png")
        self.assertLess(np.linalg.norm(probe_mm("proxy_m") - probe_mm()), 2.0)  # pressing 1 mm, held nowhere else
        # off the part it lifts off; back on the top it lands there again
        h.mouse("move", h.screen_pos(np.array([90.0, -60.0, 0.0])))
        wait_probe(lambda: "not touching" in label.text(), "lifted off")
        h.mouse("move", h.screen_pos(np.array([22.0, 16.0, 17.0])))
        wait_probe(on_the_top, "back on the top")
        self.assertTrue(panel.session.running)

    def test_a_proxy_left_under_the_part_is_freed_by_moving_off_it(self):
        # the same trap, the hand aimed at the new top before the panel could tell (a
        # steering that does not re-land at the swap): off the part it lifts off all the same
        panel, label = self.move_the_part_up_under_the_resting_probe(
            lambda panel: setattr(panel.steering.hand, "scene_changed", lambda surface, top_mm=None: None))
        wait_probe(lambda: "Box.Face5" in label.text(), "the proxy under the bottom face")
        h.mouse("move", h.screen_pos(np.array([90.0, -60.0, 0.0])))
        wait_probe(lambda: "not touching" in label.text(), "lifted off")
        h.mouse("move", h.screen_pos(np.array([20.0, 15.0, 17.0])))
        wait_probe(lambda: abs(probe_mm("proxy_m")[2] - 17.0) < 0.1 and "Box.Face6" in label.text(),
                   "on the new top")

    def test_a_slow_recompute_of_two_parts_rebuilds_once_after_it(self):
        # two parts whose recompute takes 0.3 s each: FreeCAD's progress bar runs Qt's
        # queued events in the middle; a rebuild then would see one part new, one old
        parts = []
        for i in range(2):
            part = self.doc.addObject("Part::FeaturePython", f"Slow{i}")
            SlowBox(part, 50.0 * i)
            parts.append(part)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(parts[0], "Face6"), (parts[1], "Face6")], material="ABS")
        self.doc.recompute()
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        from hapticad.gui import task_panel_feel

        panel = task_panel_feel.active_panel()
        self.assertTrue(panel.session is not None, h.widget(QtWidgets.QLabel, "feelMessage").text())
        h.wait(0.2)
        calls = []
        handler = panel.edits.callback

        def counted(geometry):
            tops = [task_panel_feel_scene().shapes[p.Name].BoundBox.ZMax for p in parts]
            calls.append(geometry)
            handler(geometry)
            calls.append(tops)

        panel.edits.callback = counted
        for part in parts:
            part.Height = 15.0
            part.touch()
        self.doc.recompute()
        h.wait(0.5)
        self.assertEqual(len(calls), 2, calls)
        self.assertTrue(calls[0])
        tops = [task_panel_feel_scene().shapes[p.Name].BoundBox.ZMax for p in parts]
        self.assertEqual(tops, [15.0, 15.0])
        h.widget(QtWidgets.QPushButton, "feelStop").click()
        h.process_events()
        h.press_task_button("Close")


class SlowBox:
    """A FeaturePython box 10 x 10 x Height mm at x = `x`, whose recompute takes 0.3 s."""

    def __init__(self, obj, x):
        obj.addProperty("App::PropertyLength", "Height").Height = 10.0
        obj.addProperty("App::PropertyFloat", "X").X = x
        obj.Proxy = self

    def execute(self, obj):
        import Part

        time.sleep(0.3)
        obj.Shape = Part.makeBox(10.0, 10.0, float(obj.Height), App.Vector(obj.X, 0.0, 0.0))


def task_panel_feel_scene():
    """The document scene the open Feel panel's session feels."""
    from hapticad.gui import task_panel_feel

    return task_panel_feel.active_panel().session.doc_scene


def wait_probe(condition, what, dead_after_s=20.0):
    """h.wait_for, whose failure says where the probe and the proxy were then and the face the
    panel named (not as they were when the wait began)."""
    try:
        h.wait_for(condition, what, dead_after_s)
    except AssertionError as exc:
        raise AssertionError(f"{exc}: probe {probe_mm()}, proxy {probe_mm('proxy_m')} mm; "
                             f"{h.widget(QtWidgets.QLabel, 'feelFace').text()}") from None


def probe_mm(field="device_m"):
    """The probe position (mm; or the proxy's, field "proxy_m") in the Feel panel's last
    displayed sample."""
    from hapticad.gui import task_panel_feel

    sample = task_panel_feel.active_panel().last_sample
    return np.asarray(sample[field], float) / MM if sample is not None else np.full(3, np.nan)


if __name__ == "__main__":
    unittest.main()
