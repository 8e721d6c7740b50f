# SPDX-License-Identifier: GPL-3.0-or-later
"""The surface task panel, driven through its widgets in FreeCAD's real GUI (Xvfb):
create and edit as one undo step, Cancel reverts, faces picked with synthetic clicks in
the 3D view, live validation, curve and circular-centre picking, vibration, broken
references shown. Run through gui_test_runner.py."""
import json
import os
import sys
import tempfile
import unittest
from unittest import mock

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtCore, QtGui, QtWidgets

import HaptiCAD
from hapticad import materials

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402


class TaskPanelTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("PanelTest")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.doc.recompute()
        self.doc.UndoMode = 1
        Gui.Selection.clearSelection()
        h.show_workbench()

    def tearDown(self):
        if Gui.Control.activeDialog():
            with h.MessageBoxes(press="Undo those too"):  # a test that failed with other edits made: no hang
                h.press_task_button("Cancel")
        Gui.Selection.clearSelection()
        App.closeDocument(self.doc.Name)

    def open_new_surface(self, face="Face6"):
        Gui.Selection.addSelection(self.box, face)
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        self.assertTrue(Gui.Control.activeDialog())
        (surface,) = HaptiCAD.surfaces_of(self.doc)
        return surface

    def test_create_and_edit_through_the_widgets_is_one_undo_step(self):
        surface = self.open_new_surface()
        self.assertEqual(h.widget(QtWidgets.QListWidget, "faces").count(), 1)
        h.widget(QtWidgets.QComboBox, "Material").setCurrentText("Steel")
        steel = materials.default_database().get("Steel")
        self.assertEqual(surface.Material, "Steel")
        self.assertAlmostEqual(h.widget(QtWidgets.QDoubleSpinBox, "StaticFriction").value(), steel.static_friction)
        self.assertNotIn("overridden", h.widget(QtWidgets.QLabel, "materialInfo").text())
        h.widget(QtWidgets.QDoubleSpinBox, "StaticFriction").setValue(0.95)  # override the database
        self.assertAlmostEqual(surface.StaticFriction, 0.95)
        self.assertIn("overridden", h.widget(QtWidgets.QLabel, "materialInfo").text())
        h.widget(QtWidgets.QComboBox, "RoughnessCategory").setCurrentIndex(5)
        self.assertEqual(surface.RoughnessCategory, 6)
        info = h.widget(QtWidgets.QLabel, "roughnessInfo").text()
        # category 6: 1.5 mm balls, rendered 5 % of that high; Table 2's Ra band for real surfaces beside it
        self.assertIn("Grid of 1.5 mm balls, felt 75 µm high", info)
        self.assertIn("real surfaces: Ra 12.5–50 µm (N11, N12)", info)
        # pattern-specific widgets appear with their pattern
        self.assertFalse(h.widget(QtWidgets.QDoubleSpinBox, "AcrossFriction").isVisible())
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Linear")
        self.assertTrue(h.widget(QtWidgets.QDoubleSpinBox, "AcrossFriction").isVisible())
        h.widget(QtWidgets.QDoubleSpinBox, "PatternAngle").setValue(30.0)
        self.assertAlmostEqual(float(surface.PatternAngle), 30.0)
        preset = "Paper f_DC 0.325 f_vis -0.2"
        h.widget(QtWidgets.QComboBox, "Texture").setCurrentText(preset)
        self.assertAlmostEqual(h.widget(QtWidgets.QDoubleSpinBox, "TextureDC").value(), 0.325)
        h.widget(QtWidgets.QDoubleSpinBox, "Stiffness").setValue(0.45)
        self.assertAlmostEqual(surface.Stiffness, 0.45)
        h.widget(QtWidgets.QCheckBox, "vibrates").setChecked(True)
        (vibration,) = HaptiCAD.vibrations_of(self.doc)
        self.assertEqual(vibration.Part, self.box)
        h.widget(QtWidgets.QDoubleSpinBox, "VibrationFrequency").setValue(167.0)
        self.assertEqual(vibration.Frequency, 167.0)
        h.widen_panel()
        h.grab_screen("task_panel.png")
        pattern = h.widget(QtWidgets.QComboBox, "Pattern")
        for area in Gui.getMainWindow().findChildren(QtWidgets.QScrollArea):
            if area.isVisible() and area.widget() is not None and area.widget().isAncestorOf(pattern):
                area.ensureWidgetVisible(h.widget(QtWidgets.QCheckBox, "vibrates"), 0, 0)
        h.grab_screen("task_panel_pattern.png")

        h.press_task_button("OK")
        self.assertFalse(Gui.Control.activeDialog())
        self.assertEqual((surface.Material, surface.StaticFriction, surface.Pattern), ("Steel", 0.95, "Linear"))
        self.assertNotIn("Touched", surface.State)
        # the whole creation and edit is one step
        self.assertEqual(self.doc.UndoCount, 1, self.doc.UndoNames)
        self.doc.undo()
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [])
        self.assertEqual(HaptiCAD.vibrations_of(self.doc), [])

    def test_the_vibrations_part_box_greyed_for_one_part_says_why(self):
        self.open_new_surface()
        part = h.widget(QtWidgets.QComboBox, "vibrationPart")
        self.assertFalse(part.isEnabled())
        self.assertEqual(part.toolTip(), "This surface's faces are all on Box: the vibration below is Box's")

    def test_a_surface_on_two_parts_sets_each_parts_vibration(self):
        lid = self.doc.addObject("Part::Box", "Lid")
        lid.Placement.Base = App.Vector(0, 0, 30)
        self.doc.recompute()
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6"), (lid, "Face6"), (self.box, "Face5")])
        self.doc.recompute()
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        part = h.widget(QtWidgets.QComboBox, "vibrationPart")
        vibrates = h.widget(QtWidgets.QCheckBox, "vibrates")
        self.assertEqual([part.itemText(i) for i in range(part.count())], ["Box", "Lid"])
        self.assertTrue(part.isEnabled())
        # the lid vibrates, the box does not
        part.setCurrentIndex(1)
        self.assertFalse(vibrates.isChecked())
        vibrates.setChecked(True)
        h.widget(QtWidgets.QDoubleSpinBox, "VibrationFrequency").setValue(240.0)
        (vibration,) = HaptiCAD.vibrations_of(self.doc)
        self.assertEqual((vibration.Part, vibration.Frequency), (lid, 240.0))
        self.assertEqual(part.currentText(), "Lid (vibrates)")
        part.setCurrentIndex(0)
        self.assertFalse(vibrates.isChecked())
        self.assertFalse(h.widget(QtWidgets.QDoubleSpinBox, "VibrationFrequency").isEnabled())
        vibrates.setChecked(True)
        self.assertEqual({v.Part.Name: v.Frequency for v in HaptiCAD.vibrations_of(self.doc)},
                         {"Box": 100.0, "Lid": 240.0})
        # one component edited: the others stay as they are (a -1..1 range clamped (2, 0, 1))
        box_vibration = next(v for v in HaptiCAD.vibrations_of(self.doc) if v.Part == self.box)
        box_vibration.Axis = App.Vector(2, 0, 1.23456789)
        part.setCurrentIndex(1)
        part.setCurrentIndex(0)
        h.widget(QtWidgets.QDoubleSpinBox, "VibrationAxis.y").setValue(0.1)
        self.assertEqual(box_vibration.Axis, App.Vector(2, 0.1, 1.23456789))
        h.widen_panel()
        h.scroll_to(part)
        h.grab_screen("task_panel_vibration_parts.png")
        h.press_task_button("OK")
        self.assertEqual(len(HaptiCAD.vibrations_of(self.doc)), 2)

    def test_an_edit_that_stops_pooling_a_similarity_studys_runs_is_said(self):
        from hapticad import similarity_study as ss

        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        study = HaptiCAD.make_similarity_study(self.doc, surface, WarmUps=0)
        run = ss.Run(study, "Ada", seed=1)
        while not run.done:
            run.present_each()
            run.answer(4)
        ss.record_run(study, run)
        self.doc.recompute()
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        status = h.widget(QtWidgets.QLabel, "status")
        self.assertNotIn("no longer pooled", status.text())
        h.widget(QtWidgets.QDoubleSpinBox, "StaticFriction").setValue(0.9)  # not felt with a Device force texture
        self.assertNotIn("no longer pooled", status.text())
        h.widget(QtWidgets.QDoubleSpinBox, "StickSpeed").setValue(5.0)  # what Ada felt changed
        self.assertIn("SimilarityStudy: 1 run felt on the surface as it was is no longer pooled", status.text())
        h.widget(QtWidgets.QDoubleSpinBox, "StickSpeed").setValue(2.0)  # as Ada felt it
        self.assertAlmostEqual(surface.StickSpeed, 2.0)
        self.assertNotIn("no longer pooled", status.text())  # back as it was: pooled again

    def test_the_texture_is_fitted_to_recordings_and_cancel_reverts_it(self):
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "support"))
        from texture_recordings import write_rig_csv

        from hapticad import _core, texture_fit

        surface = self.open_new_surface()
        folder = tempfile.mkdtemp()
        rig, bad = os.path.join(folder, "rig.csv"), os.path.join(folder, "bad.csv")
        write_rig_csv(_core, rig, speeds_mm_s=(50.0, 120.0), f_dc=0.4, f_vis=0.2, full_range_n=2.0)
        with open(bad, "w") as handle:
            handle.write("t,x,force <N>\n0,0,0\n")  # its header is said back as written, not read as markup
        chosen = []
        cursors = []
        fit_files = texture_fit.fit_files

        def watched(*args, **kwargs):
            cursors.append(QtWidgets.QApplication.overrideCursor().shape())
            return fit_files(*args, **kwargs)

        original = QtWidgets.QFileDialog.getOpenFileNames
        QtWidgets.QFileDialog.getOpenFileNames = staticmethod(lambda *a, **k: (chosen, "CSV recordings (*.csv)"))
        try:
            info = h.widget(QtWidgets.QLabel, "fitInfo")
            self.assertFalse(h.widget(QtWidgets.QPushButton, "fitPlot").isEnabled())  # nothing fitted yet
            h.widget(QtWidgets.QLineEdit, "fitSpeeds").setText("50, fast")
            chosen[:] = [rig]
            h.widget(QtWidgets.QPushButton, "fitTexture").click()
            self.assertIn("Recorded speeds: '50, fast' is not a list of speeds in mm/s", info.text())
            self.assertEqual(surface.Texture, "None")
            h.widget(QtWidgets.QLineEdit, "fitSpeeds").setText("50; 120")
            chosen[:] = [bad]
            h.widget(QtWidgets.QPushButton, "fitTexture").click()
            self.assertIn("Not fitted, nothing changed", info.text())
            self.assertIn("needs the columns time_s, position_mm, lateral_force_n", info.text())
            shown = QtGui.QTextDocument()
            shown.setHtml(info.text())
            self.assertIn("its header is t,x,force <N>", shown.toPlainText())
            self.assertEqual(surface.Texture, "None")
            self.assertIsNone(QtWidgets.QApplication.overrideCursor())  # an error left no wait cursor behind
            # the fit holds the GUI thread: the wait cursor shows while it runs, and goes after
            texture_fit.fit_files = watched
            chosen[:] = [rig]
            h.widget(QtWidgets.QPushButton, "fitTexture").click()
        finally:
            QtWidgets.QFileDialog.getOpenFileNames = original
            texture_fit.fit_files = fit_files
        self.assertEqual(cursors, [QtCore.Qt.WaitCursor])
        self.assertIsNone(QtWidgets.QApplication.overrideCursor())
        self.assertIn("Fitted to 4 sections at 50, 120 mm/s", info.text())
        # the fit's plot, as the CLI's --plot draws it, from the panel
        plot = h.widget(QtWidgets.QPushButton, "fitPlot")
        self.assertTrue(plot.isEnabled())
        picture = os.path.join(folder, "fit.png")
        with mock.patch.object(QtWidgets.QFileDialog, "getSaveFileName", return_value=(picture, "PNG pictures (*.png)")):
            plot.click()
        with open(picture, "rb") as handle:
            self.assertEqual(handle.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertIn(f"Plot saved to {picture}", info.text())
        self.assertEqual(surface.Texture, "Custom")
        self.assertEqual(h.widget(QtWidgets.QComboBox, "Texture").currentText(), "Custom")
        # the recorded newtons, whatever level 1 became
        self.assertAlmostEqual(surface.TextureDC * surface.TextureFullRange, 0.8, delta=0.01)
        self.assertAlmostEqual(surface.TextureViscosity * surface.TextureFullRange, 0.4, delta=0.02)
        self.assertAlmostEqual(h.widget(QtWidgets.QDoubleSpinBox, "TextureDC").value(), surface.TextureDC, places=4)
        self.assertIn("Full range set to", info.text())
        h.widen_panel()
        h.scroll_to(info)
        h.grab_screen("task_panel_texture_fit.png")
        h.widget(QtWidgets.QDoubleSpinBox, "TexturePeriod").setValue(3.0)
        self.assertEqual(info.text(), "")  # the fit's message named 2.5 mm
        h.press_task_button("Cancel")
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [])

    def test_the_fits_options_are_set_in_the_panel_and_said_with_the_fit(self):
        # a rig that ran 4 % fast: the paper's 2.5 % tolerance finds no section at 50 and
        # 120 mm/s; the panel's options (as the CLI's) widen it, and say so with the fit
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "..", "support"))
        from texture_recordings import write_rig_csv

        from hapticad import _core, texture_fit

        surface = self.open_new_surface()
        used = []
        fit_files = texture_fit.fit_files

        def watched(*args, **kwargs):
            try:
                report = fit_files(*args, **kwargs)
            except ValueError:
                options = _core.TextureFitOptions()  # what the failed fit was asked for, as the core reads it
                options.speed_tolerance, options.lowpass_hz, options.harmonics, options.min_periods = (
                    kwargs["tolerance_percent"] / 100.0, kwargs["lowpass_hz"], kwargs["harmonics"],
                    kwargs["min_periods"])
                used.append(options)
                raise
            used.append(report.options)
            return report

        self.addCleanup(setattr, texture_fit, "fit_files", fit_files)
        texture_fit.fit_files = watched
        rig = os.path.join(tempfile.mkdtemp(), "fast_rig.csv")
        write_rig_csv(_core, rig, speeds_mm_s=(52.0, 124.8), f_dc=0.4, f_vis=0.2, full_range_n=2.0)
        toggle = h.widget(QtWidgets.QToolButton, "fitOptionsToggle")
        tolerance = h.widget(QtWidgets.QDoubleSpinBox, "fitTolerance")
        harmonics = h.widget(QtWidgets.QSpinBox, "fitHarmonics")
        self.assertFalse(tolerance.isVisibleTo(Gui.getMainWindow()))  # folded away
        self.assertEqual((tolerance.value(), h.widget(QtWidgets.QDoubleSpinBox, "fitLowpass").value(),
                          harmonics.value(), h.widget(QtWidgets.QSpinBox, "fitMinPeriods").value()),
                         (2.5, 1000.0, 3, 6))
        info = h.widget(QtWidgets.QLabel, "fitInfo")
        h.widget(QtWidgets.QLineEdit, "fitSpeeds").setText("50, 120")
        with mock.patch.object(QtWidgets.QFileDialog, "getOpenFileNames", return_value=([rig], "")):
            h.widget(QtWidgets.QPushButton, "fitTexture").click()
            self.assertIn("Not fitted, nothing changed", info.text())
            self.assertEqual(surface.Texture, "None")
            toggle.click()
            self.assertTrue(tolerance.isVisibleTo(Gui.getMainWindow()))
            tolerance.setValue(5.0)
            harmonics.setValue(4)
            h.widget(QtWidgets.QPushButton, "fitTexture").click()
        self.assertIn("Fitted to 4 sections at 52, 125 mm/s", info.text())
        self.assertIn("With speed tolerance 5 %, 4 harmonics.", info.text())
        # the fit was run with them: its options, as the core read them
        self.assertEqual([(o.harmonics, round(o.speed_tolerance, 9), o.lowpass_hz, o.min_periods) for o in used],
                         [(3, 0.025, 1000.0, 6), (4, 0.05, 1000.0, 6)])
        self.assertAlmostEqual(surface.TextureDC * surface.TextureFullRange, 0.8, delta=0.02)
        h.widen_panel()
        h.scroll_to(info)
        h.grab_screen("task_panel_fit_options.png")
        h.press_task_button("Cancel")

    def test_the_panel_names_its_surface_and_shows_what_applies(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", FeelRoughness=False)
        surface.Label = "ThumbGrip"
        # the face tagged already: the command opens the surface that tags it, by name
        Gui.Selection.addSelection(self.box, "Face6")
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        self.assertEqual(h.widget(QtWidgets.QLabel, "surfaceName").text(), "<b>ThumbGrip</b>")
        angle = h.widget(QtWidgets.QDoubleSpinBox, "PatternAngle")
        self.assertFalse(angle.isVisibleTo(Gui.getMainWindow()))  # no stripes, no grid: it turns nothing
        h.widget(QtWidgets.QCheckBox, "FeelRoughness").setChecked(True)
        self.assertTrue(angle.isVisibleTo(Gui.getMainWindow()))  # it turns the roughness grid
        h.widget(QtWidgets.QCheckBox, "FeelRoughness").setChecked(False)
        h.widget(QtWidgets.QComboBox, "Texture").setCurrentIndex(1)  # it turns the grating too
        self.assertTrue(angle.isVisibleTo(Gui.getMainWindow()))
        h.widget(QtWidgets.QComboBox, "Texture").setCurrentText("None")
        self.assertFalse(angle.isVisibleTo(Gui.getMainWindow()))
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Linear")
        self.assertTrue(angle.isVisibleTo(Gui.getMainWindow()))
        # no texture yet: the fit to recordings is offered, and the period it reads is shown
        self.assertEqual(surface.Texture, "None")
        self.assertTrue(h.widget(QtWidgets.QPushButton, "fitTexture").isVisibleTo(Gui.getMainWindow()))
        # the speeds read from their start in a narrow panel ("0, 80, 120" hid the 5 of 50)
        self.assertEqual(h.widget(QtWidgets.QLineEdit, "fitSpeeds").cursorPosition(), 0)
        self.assertTrue(h.widget(QtWidgets.QDoubleSpinBox, "TexturePeriod").isVisibleTo(Gui.getMainWindow()))
        self.assertFalse(h.widget(QtWidgets.QDoubleSpinBox, "TextureDC").isVisibleTo(Gui.getMainWindow()))
        h.press_task_button("Cancel")

    def test_a_grating_finer_than_the_servo_rate_follows_is_said_in_the_status(self):
        from hapticad import preferences

        self.addCleanup(preferences.update, servo_rate_hz=preferences.load().servo_rate_hz)
        preferences.update(servo_rate_hz=1000)
        surface = self.open_new_surface()
        surface.Label = "Grip"
        h.widget(QtWidgets.QCheckBox, "FeelRoughness").setChecked(False)
        h.widget(QtWidgets.QComboBox, "Texture").setCurrentText("Custom")
        h.process_events()
        status = h.widget(QtWidgets.QLabel, "status")
        self.assertNotIn("texture grating", status.text())  # the paper's 2.5 mm: followed to 312 mm/s
        h.widget(QtWidgets.QDoubleSpinBox, "TexturePeriod").setValue(1.0)
        h.process_events()
        self.assertIn("Note: Grip: its 1 mm texture grating is felt as designed up to 125 mm/s at the 1000 Hz servo "
                      "rate", status.text())
        h.widen_panel()
        h.grab_screen("task_panel_grating_rate.png")
        h.widget(QtWidgets.QDoubleSpinBox, "TexturePeriod").setValue(2.5)
        h.process_events()
        self.assertNotIn("texture grating", status.text())
        h.press_task_button("Cancel")

    def test_a_texture_past_the_force_limit_and_a_grating_finer_across_a_curves_ridges_are_noted(self):
        # reviewer: the paper's strongest preset, level 1 the default 3 N force limit, was clipped under a 1.6 N
        # press, and a grating on a leaning Curve pattern felt finer across its ridges: the panel said neither
        import math

        import Part

        arc = self.doc.addObject("Part::Feature", "Arc")
        arc.Shape = Part.ArcOfCircle(Part.Circle(App.Vector(0, 15, 20), App.Vector(0, 0, 1), 30),
                                     -math.pi / 4, math.pi / 4).toShape()
        self.doc.recompute()
        self.open_new_surface()
        h.widget(QtWidgets.QCheckBox, "FeelRoughness").setChecked(False)
        h.widget(QtWidgets.QComboBox, "Material").setCurrentText("ABS")
        h.widget(QtWidgets.QComboBox, "Texture").setCurrentText("Paper f_DC 0.675 f_vis +0.2")
        h.process_events()
        status = h.widget(QtWidgets.QLabel, "status")
        self.assertIn("Note: the texture drags up to 2.80 N at 50-270 mm/s (level 0.93 of the device's full range, "
                      "the 3 N force limit), which leaves 1.07 N of the 3 N force limit for the press", status.text())
        self.assertIn("give Full range 2.78 N or less to press up to 1.5 N.", status.text())
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Curve")
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(arc, "Edge1")
        h.widget(QtWidgets.QPushButton, "useCurve").click()
        h.process_events()
        # the face spans the arc where it leans 30 degrees at most (45 at its ends, beyond the face)
        self.assertIn("Note: Box.Face6: the 2.5 mm texture grating is felt as fine as 2.17 mm across its ridges, "
                      "where Arc leans 30° from the line between its ends", status.text())
        self.assertNotIn("⚠", status.text())
        h.widen_panel()
        h.scroll_to(status)
        h.grab_screen("task_panel_texture_notes.png")
        h.press_task_button("Cancel")

    def test_cancel_on_a_new_surface_removes_it(self):
        self.open_new_surface()
        h.press_task_button("Cancel")
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [])

    def test_cancel_reverts_every_edit(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        self.doc.recompute()
        before = (surface.Material, surface.StaticFriction, surface.RoughnessCategory, surface.Pattern)
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        h.widget(QtWidgets.QComboBox, "Material").setCurrentText("Rubber")
        h.widget(QtWidgets.QComboBox, "RoughnessCategory").setCurrentIndex(0)
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Circular")
        self.assertEqual(surface.Material, "Rubber")
        h.press_task_button("Cancel")
        self.assertEqual((surface.Material, surface.StaticFriction, surface.RoughnessCategory, surface.Pattern),
                         before)
        # the values it was recomputed with are back: it is not left waiting for a recompute
        self.assertNotIn("Touched", surface.State)
        self.assertNotIn("Touched", self.box.State)

    def test_cancel_asks_before_it_undoes_what_was_done_elsewhere_meanwhile(self):
        # FreeCAD puts every change made while the panel is open into its transaction: Cancel took the box's new
        # length (set in the property editor meanwhile) with the surface's edits, and said nothing
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        other = self.doc.addObject("Part::Cylinder", "Handle")
        self.doc.recompute()
        motor = HaptiCAD.make_vibration(self.doc, other)
        motor.Label = "Motor"
        self.doc.recompute()
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        h.widget(QtWidgets.QCheckBox, "vibrates").setChecked(True)  # the panel's own: its part's vibration
        h.widget(QtWidgets.QComboBox, "Material").setCurrentText("Rubber")
        self.box.Length = 55  # as the property editor sets it
        motor.Frequency = 90.0  # another part's vibration: not the panel's
        self.doc.recompute()
        with h.MessageBoxes() as boxes:  # Keep editing: the panel stays, nothing is undone
            h.press_task_button("Cancel")
        self.assertEqual(len(boxes.seen), 1)
        self.assertEqual(boxes.seen[0], ("Cancel the surface's edits", "While this panel was open you also changed Box "
                                         "(Length) and Motor (Frequency).\n\nCancel undoes everything done since "
                                         "the panel opened: those too."))
        self.assertTrue(Gui.Control.activeDialog())
        self.assertEqual((surface.Material, float(self.box.Length)), ("Rubber", 55.0))
        h.widen_panel()
        with h.MessageBoxes(press="Undo those too") as boxes:
            h.press_task_button("Cancel")
        self.assertEqual(len(boxes.seen), 1)
        self.assertFalse(Gui.Control.activeDialog())
        self.assertEqual((surface.Material, float(self.box.Length), motor.Frequency), ("ABS", 40.0, 100.0))
        self.assertEqual(HaptiCAD.vibrations_of(self.doc), [motor])  # the box's, made in the panel, undone
        # nothing else done: Cancel asks nothing, as before
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        h.widget(QtWidgets.QComboBox, "Material").setCurrentText("Rubber")
        with h.MessageBoxes() as boxes:
            h.press_task_button("Cancel")
        self.assertEqual(boxes.seen, [])
        self.assertEqual(surface.Material, "ABS")

    def test_undo_and_redo_while_editing_show_the_surface_and_edits_after_them_stay_one_step(self):
        # Edit > Undo while the panel was open took back its edits (FreeCAD commits the open
        # transaction and undoes it) but the widgets still showed them; later edits were in no
        # transaction, so Cancel left them and OK made no undo step
        self.doc.openTransaction("Tag")
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        self.doc.commitTransaction()
        self.doc.recompute()
        abs_k, steel_k = surface.Stiffness, materials.default_database().get("Steel").stiffness_n_per_mm
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        material = h.widget(QtWidgets.QComboBox, "Material")
        stiffness = h.widget(QtWidgets.QDoubleSpinBox, "Stiffness")
        material.setCurrentText("Steel")
        self.assertEqual(surface.Material, "Steel")
        Gui.runCommand("Std_Undo")
        h.process_events()
        self.assertEqual(surface.Material, "ABS")
        self.assertEqual(material.currentText(), "ABS")  # the panel shows what the Undo left
        self.assertAlmostEqual(stiffness.value(), abs_k, places=3)
        stiffness.setValue(0.33)
        self.assertAlmostEqual(surface.Stiffness, 0.33)
        self.assertTrue(self.doc.HasPendingTransaction)
        h.press_task_button("Cancel")  # reverts the edit made after the Undo; the tag stays
        self.assertAlmostEqual(surface.Stiffness, abs_k)
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [surface])
        # Redo brings the edits back into view; an edit after it is one undo step of its own
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        material = h.widget(QtWidgets.QComboBox, "Material")
        stiffness = h.widget(QtWidgets.QDoubleSpinBox, "Stiffness")
        material.setCurrentText("Steel")
        Gui.runCommand("Std_Undo")
        h.process_events()
        Gui.runCommand("Std_Redo")  # the Redo list was kept: the panel opened no transaction at the Undo
        h.process_events()
        self.assertEqual((surface.Material, material.currentText()), ("Steel", "Steel"))
        self.assertAlmostEqual(stiffness.value(), steel_k, places=3)
        stiffness.setValue(0.33)
        h.press_task_button("OK")
        self.assertFalse(Gui.Control.activeDialog())
        self.doc.undo()  # the edit after the Redo
        self.assertEqual(surface.Material, "Steel")
        self.assertAlmostEqual(surface.Stiffness, steel_k)
        self.doc.undo()  # the Steel edit
        self.assertEqual(surface.Material, "ABS")
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [surface])  # the tag is a step of its own

    def test_a_full_range_of_0_reads_as_the_devices(self):
        # it read "0.0000 N", a texture of no force, where 0 stands for the device's full range
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS")
        surface.Texture = surface.getEnumerationsOfProperty("Texture")[1]
        self.doc.recompute()
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        full_range = h.widget(QtWidgets.QDoubleSpinBox, "TextureFullRange")
        self.assertTrue(full_range.isVisible())
        self.assertEqual(full_range.lineEdit().text(), "device's full range")
        h.widen_panel()
        h.scroll_to(full_range)
        h.grab_screen("task_panel_full_range.png")
        full_range.setValue(0.7)
        self.assertEqual((surface.TextureFullRange, full_range.lineEdit().text()), (0.7, "0.7000 N"))
        h.press_task_button("Cancel")
        self.assertEqual(surface.TextureFullRange, 0.0)

    def test_faces_are_picked_in_the_3d_view_listed_highlighted_and_removed(self):
        surface = self.open_new_surface()
        h.widget(QtWidgets.QPushButton, "addFaces").setChecked(True)
        # the front face (y = 0), clicked at its centre
        h.click_at((20, 0, 10))
        faces = h.widget(QtWidgets.QListWidget, "faces")
        self.assertEqual(HaptiCAD.reference_pairs(surface), [(self.box, "Face6"), (self.box, "Face3")])
        self.assertEqual(faces.count(), 2)
        # a click on a face already tagged adds nothing
        h.click_at((20, 15, 20))
        self.assertEqual(faces.count(), 2)
        # selecting it in the list highlights it: outlined in the overlay, selected in the view
        faces.setCurrentRow(1)
        h.process_events()
        self.assertEqual(surface.ViewObject.Proxy._highlighted, ["Box.Face3"])
        self.assertIn("Face3", Gui.Selection.getSelectionEx()[0].SubElementNames)
        h.widget(QtWidgets.QPushButton, "removeFaces").click()
        self.assertEqual(HaptiCAD.reference_pairs(surface), [(self.box, "Face6")])
        h.press_task_button("OK")

    def test_a_face_another_surface_tags_is_not_added_and_the_command_edits_that_surface(self):
        first = self.open_new_surface()  # Face6, the top
        h.press_task_button("OK")
        # the command on the tagged top face opens its surface instead of a second one
        Gui.Selection.addSelection(self.box, "Face6")
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [first])
        self.assertTrue(Gui.Control.activeDialog())
        self.assertEqual(Gui.ActiveDocument.getInEdit().Object, first)
        h.press_task_button("Cancel")
        # the top and the front selected: the new surface takes only the front
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(self.box, "Face6")
        Gui.Selection.addSelection(self.box, "Face3")
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        second = [s for s in HaptiCAD.surfaces_of(self.doc) if s is not first][0]
        self.assertEqual(HaptiCAD.reference_pairs(second), [(self.box, "Face3")])
        # a click on the top face in the panel adds nothing, and says why
        Gui.Selection.clearSelection()
        h.widget(QtWidgets.QPushButton, "addFaces").setChecked(True)
        h.click_at((20, 15, 20))
        self.assertEqual(HaptiCAD.reference_pairs(second), [(self.box, "Face3")])
        self.assertIn(f"already tagged by {first.Label}", h.widget(QtWidgets.QLabel, "status").text())
        h.press_task_button("OK")
        self.assertEqual(HaptiCAD.reference_pairs(first), [(self.box, "Face6")])

    def test_a_face_clicked_through_any_link_is_not_added_and_the_panel_says_why(self):
        # Add took a Draft link array's element as its hidden base ArrBase (felt 35 mm from
        # the click), a link to an App::Part's cylinder as the original, and ignored a knob
        # shown by a link to another file without a word
        from link_scenes import LinkedAssembly

        scene = LinkedAssembly()
        try:
            side = [f"Face{i + 1}" for i, f in enumerate(scene.plate.Shape.Faces) if abs(f.CenterOfMass.y) < 1e-6][0]
            surface = HaptiCAD.make_surface(scene.doc, [(scene.plate, side)])
            Gui.ActiveDocument.setEdit(surface.Name, 0)
            h.process_events()
            h.widget(QtWidgets.QPushButton, "addFaces").setChecked(True)
            h.widen_panel()
            Gui.SendMsgToActiveView("ViewFit")
            status = h.widget(QtWidgets.QLabel, "status")
            for what, point, refusal in scene.clicks:
                with self.subTest(what):
                    Gui.Selection.clearSelection()
                    h.click_at(point)
                    self.assertTrue(Gui.Selection.getSelectionEx("", 0), f"the click missed {what}")
                    added = HaptiCAD.reference_pairs(surface)
                    if added != [(scene.plate, side)]:  # taken back, for the next click
                        surface.References = [(scene.plate, (side,))]
                    self.assertEqual(added, [(scene.plate, side)])
                    self.assertIn(refusal, status.text())
                    self.assertIn("cannot be tagged", status.text())
                    if what == scene.clicks[0][0]:
                        h.grab_screen("panel_link_refused.png")
            # the plate's own top is added, as the assembly's plate
            Gui.Selection.clearSelection()
            h.click_at((20, 20, 4))
            ((part, top),) = [p for p in HaptiCAD.reference_pairs(surface) if p != (scene.plate, side)]
            self.assertEqual((part.Document.Name, part.Name), ("Assembly", "Body"))
            self.assertAlmostEqual(part.Shape.getElement(top).CenterOfMass.z, 4.0)
            # a click in another document's view is said too, and adds nothing
            Gui.getDocument(scene.knob_doc.Name).ActiveView.viewTop()  # in a window of its own
            Gui.ActiveDocument = Gui.getDocument(scene.knob_doc.Name)
            Gui.SendMsgToActiveView("ViewFit")
            h.process_events()
            h.click_at((5, 5, 6))
            self.assertEqual(len(HaptiCAD.reference_pairs(surface)), 2)
            self.assertIn(f"that click was in knob.FCStd: {surface.Label} tags faces of assembly.FCStd", status.text())
            h.press_task_button("OK")
            self.assertEqual([s.Document.Name for s in scene.surfaces()], ["Assembly"])
        finally:
            if Gui.Control.activeDialog():
                h.press_task_button("Cancel")
            Gui.Selection.clearSelection()
            scene.close()

    def test_labels_with_angle_brackets_are_shown_as_typed(self):
        # "Lid <rev B>" lost "<rev B>": the panel read the label as markup
        self.box.Label = "Lid <rev B>"
        first = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        first.Label = "Top <A&B>"
        Gui.Selection.addSelection(self.box, "Face1")
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        (surface,) = [s for s in HaptiCAD.surfaces_of(self.doc) if s is not first]
        surface.References = [(self.box, ("Face1", "Face6"))]  # a clash, as a script makes it
        h.widget(QtWidgets.QDoubleSpinBox, "StaticFriction").setValue(0.7)  # a live check
        h.process_events()
        shown = QtGui.QTextDocument()
        shown.setHtml(h.widget(QtWidgets.QLabel, "status").text())
        self.assertIn("Lid <rev B>.Face6 is also tagged by Top <A&B>", shown.toPlainText())

    def test_a_circular_centre_is_edited_where_its_moved_app_part_took_it(self):
        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(self.box)
        self.doc.recompute()
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], pattern="Circular",
                                        pattern_center_mm=(10, 10, 20))
        self.doc.recompute()
        container.Placement.Base = App.Vector(50, 0, 0)  # the surface is not recomputed
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        self.assertEqual([h.widget(QtWidgets.QDoubleSpinBox, f"PatternCenter.{a}").value() for a in "xyz"],
                         [60.0, 10.0, 20.0])
        h.widget(QtWidgets.QDoubleSpinBox, "PatternCenter.y").setValue(15.0)  # it jumped back 50 mm
        h.process_events()
        from hapticad.surface_object import circular_centre_axis

        centre, _ = circular_centre_axis(surface)
        self.assertEqual((centre.x, centre.y, centre.z), (60.0, 15.0, 20.0))
        h.press_task_button("OK")

    def test_a_vibration_axis_is_shown_and_edited_where_its_turned_app_part_took_it(self):
        # the boxes showed Axis, (1, 0, 0), after the App::Part turned the blade 90 degrees
        # about Z, and editing z saved (1, 0, 0.5): across the blade
        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(self.box)
        self.doc.recompute()
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        vibration = HaptiCAD.make_vibration(self.doc, self.box, axis=(1, 0, 0))
        self.doc.recompute()
        container.Placement = App.Placement(App.Vector(), App.Rotation(App.Vector(0, 0, 1), 90))  # no recompute
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        boxes = [h.widget(QtWidgets.QDoubleSpinBox, f"VibrationAxis.{a}") for a in "xyz"]
        self.assertEqual([b.value() for b in boxes], [0.0, 1.0, 0.0])
        boxes[2].setValue(0.5)
        h.process_events()
        self.assertLess((vibration.Axis - App.Vector(0, 1, 0.5)).Length, 1e-9, vibration.Axis)
        h.press_task_button("OK")

    def test_a_pattern_and_a_vibration_turned_while_the_panel_is_open_are_edited_where_they_are_felt(self):
        # the App::Part turned in the property editor with the panel open: an edit of one box
        # kept the others as they were before the turn
        from hapticad.surface_object import circular_centre_axis
        from hapticad.vibration_object import axis_where_felt

        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(self.box)
        self.doc.recompute()
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], pattern="Circular",
                                        pattern_center_mm=(10, 10, 20))
        vibration = HaptiCAD.make_vibration(self.doc, self.box, axis=(1, 0, 0))
        self.doc.recompute()
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        container.Placement = App.Placement(App.Vector(), App.Rotation(App.Vector(0, 0, 1), 90))
        h.widget(QtWidgets.QDoubleSpinBox, "PatternCenter.z").setValue(25.0)
        h.process_events()
        centre, axis = circular_centre_axis(surface)
        self.assertLess((centre - App.Vector(-10, 10, 25)).Length, 1e-9, centre)
        self.assertLess((axis - App.Vector(0, 0, 1)).Length, 1e-9, axis)
        self.assertEqual([round(h.widget(QtWidgets.QDoubleSpinBox, f"PatternCenter.{a}").value(), 3) for a in "xyz"],
                         [-10.0, 10.0, 25.0])
        container.Placement = App.Placement()
        h.widget(QtWidgets.QDoubleSpinBox, "VibrationAxis.z").setValue(0.5)
        h.process_events()
        self.assertLess((axis_where_felt(vibration) - App.Vector(1, 0, 0.5)).Length, 1e-9, vibration.Axis)
        self.assertEqual([round(h.widget(QtWidgets.QDoubleSpinBox, f"PatternCenter.{a}").value(), 3) for a in "xyz"],
                         [10.0, 10.0, 25.0])  # the load after the edit shows the pattern turned back too
        h.press_task_button("OK")

    def test_closing_the_document_under_the_panel_closes_it_and_stops_its_picking(self):
        from hapticad.gui.task_panel_surface import SurfaceTaskPanel

        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        panel = SurfaceTaskPanel(surface)
        Gui.Control.showDialog(panel)
        h.process_events()
        picks = []
        panel.picked = lambda *args: picks.append(args)
        App.closeDocument(self.doc.Name)  # its clicks then asked the deleted surface its name
        h.process_events()
        self.assertFalse(Gui.Control.activeDialog())
        other = App.newDocument("AfterClose")
        try:
            box = other.addObject("Part::Box", "Box")
            other.recompute()
            Gui.Selection.addSelection(box, "Face1")
            h.process_events()
            self.assertEqual(picks, [])
        finally:
            Gui.Selection.clearSelection()
            App.closeDocument(other.Name)
            self.doc = App.newDocument("PanelTest")  # for tearDown

    def test_a_material_this_machine_does_not_know_keeps_the_documents_values(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        # as a document made with a colleague's own material card opens here
        surface.Material = surface.getEnumerationsOfProperty("Material") + ["MyFoam"]
        surface.Material = "MyFoam"
        surface.StaticFriction = 0.9
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        reset = h.widget(QtWidgets.QPushButton, "resetMaterial")
        self.assertFalse(reset.isEnabled())
        self.assertIn("MyFoam is not in the material database", h.widget(QtWidgets.QLabel, "materialInfo").text())
        reset.setEnabled(True)  # pressed anyway (a shortcut): a message, not a KeyError
        reset.click()
        h.process_events()
        self.assertIn("MyFoam is not in the material database", h.widget(QtWidgets.QLabel, "status").text())
        self.assertEqual(surface.StaticFriction, 0.9)
        h.press_task_button("OK")

    def test_values_are_validated_live_and_ok_is_refused_while_wrong(self):
        import Part

        sketch_line = self.doc.addObject("Part::Feature", "Guide")
        sketch_line.Shape = Part.makeLine(App.Vector(0, 5, 20), App.Vector(40, 25, 20))
        self.doc.recompute()
        surface = self.open_new_surface()
        status = h.widget(QtWidgets.QLabel, "status")
        self.assertIn("1 face", status.text())
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Curve")
        self.assertIn("needs a sketch or edge", status.text())
        h.press_task_button("OK")
        self.assertTrue(Gui.Control.activeDialog(), "OK must be refused while the curve is missing")
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(sketch_line, "Edge1")
        h.widget(QtWidgets.QPushButton, "useCurve").click()
        self.assertEqual(surface.PatternCurve[0], sketch_line)
        self.assertNotIn("⚠", status.text())
        self.assertIn("Guide", h.widget(QtWidgets.QLabel, "curveLabel").text())
        self.assertNotIn("lies beyond the ends", status.text())
        # a stub of a curve: the face beyond its ends feels straight stripes, and the panel says so
        stub = self.doc.addObject("Part::Feature", "Stub")
        stub.Shape = Part.makeLine(App.Vector(18, 0, 20), App.Vector(18, 6, 20))
        self.doc.recompute()
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(stub, "Edge1")
        h.widget(QtWidgets.QPushButton, "useCurve").click()
        self.assertIn("Note: Box.Face6: 80 % of it lies beyond the ends of Stub", status.text())
        self.assertNotIn("⚠", status.text())  # a note: it is felt, and OK is allowed
        h.grab_screen("task_panel_curve_note.png")
        # the core's own check speaks through the panel: no stick speed below the minimum exists,
        # so remove the only face instead
        faces = h.widget(QtWidgets.QListWidget, "faces")
        faces.setCurrentRow(0)
        h.widget(QtWidgets.QPushButton, "removeFaces").click()
        self.assertIn("no faces", status.text())
        h.press_task_button("OK")
        self.assertTrue(Gui.Control.activeDialog())
        # Guide was made before the panel opened, Stub while it was: Cancel takes Stub with it, and asks
        with h.MessageBoxes(press="Undo those too") as boxes:
            h.press_task_button("Cancel")
        self.assertEqual([text.split(".")[0] for _, text in boxes.seen],
                         ["While this panel was open you also added Stub"])
        self.assertIsNone(self.doc.getObject("Stub"))
        self.assertIsNotNone(self.doc.getObject("Guide"))

    def test_the_circular_centre_is_picked_in_the_3d_view(self):
        surface = self.open_new_surface()
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Circular")
        h.widget(QtWidgets.QPushButton, "pickCenter").click()
        h.click_at((10, 20, 20))
        c = surface.PatternCenter
        self.assertAlmostEqual(c.z, 20.0, places=3)
        self.assertLess(abs(c.x - 10) + abs(c.y - 20), 1.0, c)  # within a pixel or two
        self.assertAlmostEqual(h.widget(QtWidgets.QDoubleSpinBox, "PatternCenter.x").value(), c.x, places=2)
        # the pick did not add the face a second time
        self.assertEqual(len(HaptiCAD.reference_pairs(surface)), 1)
        h.press_task_button("OK")

    def test_a_curve_and_a_centre_picked_through_a_link_are_refused_and_the_panel_says_why(self):
        # Use selection took a link's edges as the original's, shown 30 mm away, and Pick took
        # a point on a link's copy of the box, 60 mm from the faces the circles are felt on
        import Part

        guide = self.doc.addObject("Part::Feature", "Guide")
        guide.Shape = Part.makeLine(App.Vector(0, 5, 20), App.Vector(40, 25, 20))
        guide_link = self.doc.addObject("App::Link", "GuideLink")
        guide_link.LinkedObject = guide
        guide_link.Placement.Base = App.Vector(0, 0, 30)
        box_link = self.doc.addObject("App::Link", "BoxLink")
        box_link.LinkedObject = self.box
        box_link.Placement.Base = App.Vector(60, 0, 0)
        self.doc.recompute()
        surface = self.open_new_surface()
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Curve")
        status = h.widget(QtWidgets.QLabel, "status")
        refused = ("GuideLink is a link to Guide: a link's edges cannot be followed by a curve pattern yet; pick "
                   "Guide's edges")
        for what, select in [("its edge in the 3D view", lambda: Gui.Selection.addSelection(
                                  self.doc.Name, guide_link.Name, "Edge1")),
                             ("the link in the tree", lambda: Gui.Selection.addSelection(guide_link))]:
            with self.subTest(what):
                Gui.Selection.clearSelection()
                select()
                h.widget(QtWidgets.QPushButton, "useCurve").click()
                self.assertIsNone(surface.PatternCurve)
                self.assertIn(refused, status.text())
        h.widen_panel()
        h.scroll_to(status)
        h.grab_screen("panel_link_curve_refused.png")
        Gui.Selection.clearSelection()
        Gui.Selection.addSelection(guide, "Edge1")
        h.widget(QtWidgets.QPushButton, "useCurve").click()
        self.assertEqual(surface.PatternCurve, (guide, ["Edge1"]))
        # the centre: a click on BoxLink's top is refused and Pick waits for another click
        h.widget(QtWidgets.QComboBox, "Pattern").setCurrentText("Circular")
        before = App.Vector(surface.PatternCenter)
        Gui.ActiveDocument.ActiveView.viewTop()
        Gui.SendMsgToActiveView("ViewFit")
        h.process_events()
        h.widget(QtWidgets.QPushButton, "pickCenter").click()
        Gui.Selection.clearSelection()
        h.click_at((80, 15, 20))
        self.assertTrue(Gui.Selection.getSelectionEx("", 0), "the click missed BoxLink")
        self.assertEqual(surface.PatternCenter, before)
        self.assertIn("BoxLink is a link to Box: the point clicked lies where it shows Box, away from the faces the "
                      "circles are felt on; click the centre on Box itself", status.text())
        h.scroll_to(status)
        h.grab_screen("panel_link_centre_refused.png")
        Gui.Selection.clearSelection()
        h.click_at((30, 5, 20))  # the box's own top, off the guide and its link above it
        c = surface.PatternCenter
        self.assertLess(abs(c.x - 30) + abs(c.y - 5) + abs(c.z - 20), 1.0, c)
        h.press_task_button("OK")

    def test_faces_of_a_partdesign_body_and_of_a_part_in_an_app_part(self):
        import Part
        import Sketcher

        body = self.doc.addObject("PartDesign::Body", "Body")
        sketch = body.newObject("Sketcher::SketchObject", "Sketch")
        sketch.Support = (self.doc.getObject("XY_Plane"), [""])
        sketch.MapMode = "FlatFace"
        corners = [App.Vector(60, 0, 0), App.Vector(90, 0, 0), App.Vector(90, 20, 0), App.Vector(60, 20, 0)]
        for i in range(4):
            sketch.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
        for i in range(4):
            sketch.addConstraint(Sketcher.Constraint("Coincident", i, 2, (i + 1) % 4, 1))
        pad = body.newObject("PartDesign::Pad", "Pad")
        pad.Profile = sketch
        pad.Length = 10
        container = self.doc.addObject("App::Part", "Assembly")
        inner = self.doc.addObject("Part::Box", "Inner")
        inner.Placement.Base = App.Vector(0, 60, 0)
        container.addObject(inner)
        self.doc.recompute()
        pad_top = [f"Face{i + 1}" for i, f in enumerate(pad.Shape.Faces)
                   if abs(f.CenterOfMass.z - 10) < 1e-6 and type(f.Surface).__name__ == "Plane"][0]
        # as the 3D view selects them: through the Body and through the App::Part
        Gui.Selection.addSelection(self.doc.Name, body.Name, f"{pad.Name}.{pad_top}")
        Gui.Selection.addSelection(self.doc.Name, container.Name, f"{inner.Name}.Face6")
        Gui.runCommand("HaptiCAD_Surface")
        h.process_events()
        (surface,) = HaptiCAD.surfaces_of(self.doc)
        pairs = HaptiCAD.reference_pairs(surface)
        self.assertEqual([o.Name for o, _ in pairs], ["Body", "Inner"])  # the Body owns the pad's face
        self.assertAlmostEqual(body.Shape.getElement(pairs[0][1]).CenterOfMass.z, 10.0)
        h.press_task_button("OK")
        self.assertEqual(surface.ViewObject.Proxy.overlay_face_count(), 2)

    def test_a_broken_reference_shows_in_the_panel_and_the_tree(self):
        cyl = self.doc.addObject("Part::Cylinder", "Hole")
        cyl.Radius, cyl.Height = 3, 30
        cyl.Placement.Base = App.Vector(10, 10, -5)
        cut = self.doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = self.box, cyl
        self.doc.recompute()
        bore = [f"Face{i + 1}" for i, f in enumerate(cut.Shape.Faces) if type(f.Surface).__name__ == "Cylinder"][0]
        surface = HaptiCAD.make_surface(self.doc, [(cut, bore)])
        self.doc.recompute()
        self.assertTrue(surface.ViewObject.Proxy.getIcon().endswith("HaptiCAD_SurfaceObject.svg"))
        square = self.doc.addObject("Part::Box", "Square")
        square.Length = square.Width = 4
        square.Height = 30
        square.Placement.Base = App.Vector(8, 8, -5)
        cut.Tool = square
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface)[0][2], "broken")
        self.assertTrue(surface.ViewObject.Proxy.getIcon().endswith("HaptiCAD_SurfaceBroken.svg"))
        Gui.ActiveDocument.setEdit(surface.Name, 0)
        h.process_events()
        item = h.widget(QtWidgets.QListWidget, "faces").item(0)
        self.assertIn("broken", item.text())
        self.assertIn("broken face reference", h.widget(QtWidgets.QLabel, "status").text())
        h.press_task_button("Cancel")
        # a broken reference stepped aside for a face FreeCAD renamed onto its name: shown
        # by the name it had, selected without a highlight of a face it is not
        top = [f"Face{i + 1}" for i, f in enumerate(cut.Shape.Faces) if abs(f.CenterOfMass.z - 20) < 1e-6][0]
        other = HaptiCAD.make_surface(self.doc, [(cut, top)], material="Steel")
        other.References = [(cut, (top, f"{top}~1"))]
        other.ReferenceState = json.dumps([dict(e, face=f"{top}~1", status="broken") if i else e for i, e in
                                           enumerate(json.loads(other.ReferenceState) * 2)])
        Gui.ActiveDocument.setEdit(other.Name, 0)
        h.process_events()
        faces = h.widget(QtWidgets.QListWidget, "faces")
        self.assertEqual([faces.item(i).text() for i in range(faces.count())],
                         [f"Cut.{top}", f"Cut.{top}  (broken)"])
        faces.item(1).setSelected(True)
        self.assertEqual(Gui.Selection.getSelectionEx(), [])
        # picked again: chosen in the list, the face clicked takes its place (it names no face
        # to click, and a click used to add the face beside it, the broken one left)
        self.assertIn("put it in its place", faces.item(1).toolTip())
        h.widget(QtWidgets.QPushButton, "addFaces").setChecked(True)
        h.click_at((20, 0, 10))  # the front face
        front = [f"Face{i + 1}" for i, f in enumerate(cut.Shape.Faces) if abs(f.CenterOfMass.y) < 1e-6][0]
        self.assertEqual(HaptiCAD.reference_pairs(other), [(cut, top), (cut, front)])
        self.assertEqual([state for _, _, state in HaptiCAD.reference_status(other)], ["ok", "ok"])
        faces = h.widget(QtWidgets.QListWidget, "faces")
        self.assertEqual([faces.item(i).text() for i in range(faces.count())], [f"Cut.{top}", f"Cut.{front}"])
        h.press_task_button("Cancel")
        # the list is older than the surface (a reference taken out from the console): the
        # broken one chosen there is gone, and a pick adds its face, not nothing
        other.References = [(cut, (top, f"{top}~1"))]
        other.ReferenceState = json.dumps([dict(e, face=f"{top}~1", status="broken") if i else e for i, e in
                                           enumerate(json.loads(other.ReferenceState)[:1] * 2)])
        Gui.ActiveDocument.setEdit(other.Name, 0)
        h.process_events()
        h.widget(QtWidgets.QListWidget, "faces").item(1).setSelected(True)
        other.References = [(cut, top)]
        h.widget(QtWidgets.QPushButton, "addFaces").setChecked(True)
        h.click_at((20, 0, 10))
        self.assertEqual(HaptiCAD.reference_pairs(other), [(cut, top), (cut, front)])
        h.press_task_button("Cancel")


if __name__ == "__main__":
    unittest.main()
