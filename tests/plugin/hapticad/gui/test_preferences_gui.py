# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD's page in FreeCAD's real preferences dialog (Xvfb): it is there, shows the
stored values, and stores what the user sets. Run by gui_test_runner.py."""
import os
import sys
import unittest

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtCore, QtWidgets

from hapticad import preferences

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402


def when_open(use):
    """Calls ``use(dialog)`` once FreeCAD's preferences dialog shows HaptiCAD's page: polled,
    since a slow host opens it later than any fixed delay (a callback finding no dialog yet
    left the modal dialog open until the runner's timeout). Keep the timer returned."""
    timer = QtCore.QTimer()
    timer.setInterval(50)

    def poll():
        dialog = QtWidgets.QApplication.activeModalWidget()
        if dialog is None or dialog.findChild(QtWidgets.QAbstractSpinBox, "servoRate") is None:
            return  # not open yet
        timer.stop()
        use(dialog)

    timer.timeout.connect(poll)
    timer.start()
    return timer


class PreferencesPageTest(unittest.TestCase):
    def setUp(self):
        preferences.save(preferences.Preferences(servo_rate_hz=2000, accuracy="Fine", force_limit_n=2.5))

    def tearDown(self):
        preferences.save(preferences.Preferences())
        # the dialog's OK wrote user.cfg with the test's values (a custom refinement of 0.25 mm
        # that a later module sharing the config then built 4 million triangles from): reset it
        App.saveParameter()

    def test_the_page_is_in_freecads_preferences_dialog_and_stores_values(self):
        seen = {}

        def use_dialog(dialog):
            try:
                seen["dialog"] = dialog is not None
                rate = dialog.findChild(QtWidgets.QAbstractSpinBox, "servoRate")
                seen["rate"] = rate.value()
                seen["accuracy"] = dialog.findChild(QtWidgets.QComboBox, "accuracy").currentText()
                seen["device"] = dialog.findChild(QtWidgets.QComboBox, "device").currentData()
                rate.setValue(1500)
                mapping = dialog.findChild(QtWidgets.QComboBox, "workspaceMapping")
                scale = dialog.findChild(QtWidgets.QDoubleSpinBox, "workspaceScale")
                mapping.setCurrentText("Fixed scale")
                scale.setValue(0.5)
                # the simulated probe moves in the part's own space: no mapping to set for it
                seen["mapping enabled"] = (mapping.isEnabled(), scale.isEnabled())
                hint = dialog.findChild(QtWidgets.QLabel, "workspaceHint")
                seen["hint"] = (hint.isVisible(), hint.text())
                h.grab_screen("preferences_page.png")
                buttons = dialog.findChild(QtWidgets.QDialogButtonBox)
                buttons.button(QtWidgets.QDialogButtonBox.Ok).click()
            except Exception as exc:  # report in the test, never leave the modal dialog open
                seen["error"] = repr(exc)
                dialog.reject()

        timer = when_open(use_dialog)
        Gui.showPreferences("HaptiCAD", 0)  # modal: returns when the dialog closes
        timer.stop()
        self.assertNotIn("error", seen, seen)
        self.assertEqual((seen["rate"], seen["accuracy"], seen["device"]), (2000, "Fine", "simulated"))
        prefs = preferences.load()
        self.assertEqual((prefs.servo_rate_hz, prefs.workspace_mapping, prefs.workspace_scale),
                         (1500, "Fixed scale", 0.5))
        self.assertEqual(prefs.force_limit_n, 2.5)  # untouched values stay
        self.assertEqual(seen["mapping enabled"], (False, False))
        # greyed, and why is said (it was not: the fields looked broken)
        self.assertTrue(seen["hint"][0])
        self.assertIn("The simulated probe moves in the part's own space", seen["hint"][1])

    def _run_dialog(self, use):
        """Opens FreeCAD's preferences at HaptiCAD's page, runs use(dialog, seen), OK."""
        seen = {}

        def in_dialog(dialog):
            try:
                use(dialog, seen)
                dialog.findChild(QtWidgets.QDialogButtonBox).button(QtWidgets.QDialogButtonBox.Ok).click()
            except Exception as exc:  # report in the test, never leave the modal dialog open
                seen["error"] = repr(exc)
                dialog.reject()

        timer = when_open(in_dialog)
        Gui.showPreferences("HaptiCAD", 0)
        timer.stop()
        self.assertNotIn("error", seen, seen)
        return seen

    def test_values_typed_are_taken_as_typed_or_refused_saying_the_range(self):
        # a spin box bounded by its range dropped keys, unsaid: 20000 Hz was stored as 2000,
        # 0,05 mm as 5 mm, 200 degrees as 20, and a refinement of 0.005 mm as off
        preferences.update(servo_rate_hz=1000)

        def typed(dialog, seen, name, text, finish="leave"):
            spin = dialog.findChild(QtWidgets.QAbstractSpinBox, name)
            h.type_into(spin, text, finish)
            message = dialog.findChild(QtWidgets.QLabel, "preferencesMessage")
            seen[name, text] = (spin.lineEdit().text(), message.text() if message is not None else "")

        def odd_values(dialog, seen):
            dialog.findChild(QtWidgets.QComboBox, "accuracy").setCurrentText("Custom")
            typed(dialog, seen, "servoRate", "20000")
            typed(dialog, seen, "linearDeflection", "0,05")
            typed(dialog, seen, "angularDeflection", "200")
            typed(dialog, seen, "refineEdge", "0.005")
            h.grab_screen("preferences_refused.png")
            typed(dialog, seen, "forceLimit", "0", finish=None)  # and OK pressed while still in the field

        with h.MessageBoxes() as boxes:
            seen = self._run_dialog(odd_values)
        # beyond the range: every digit kept, refused saying the range, the field back to what is kept
        self.assertEqual(seen["servoRate", "20000"][0], "1000 Hz")
        self.assertIn("Not set: Servo rate: 20000 Hz is outside 400..10000 Hz", seen["servoRate", "20000"][1])
        # a decimal comma is a decimal point
        self.assertEqual(seen["linearDeflection", "0,05"][0], "0.05 mm")
        self.assertEqual(seen["angularDeflection", "200"][0], "5.7296 \u00b0")
        self.assertIn("Not set: Angular deflection: 200 \u00b0 is outside 0.573..85.9436 \u00b0",
                      seen["angularDeflection", "200"][1])
        # finer than the field's old step: refused, not rounded to off unsaid
        self.assertEqual(seen["refineEdge", "0.005"][0], "off")
        self.assertIn("Not set: Refine edges over: 0.005 mm is neither 0 (off) nor in 0.01..100 mm",
                      seen["refineEdge", "0.005"][1])
        # OK says what was not saved, the last typed just before it included
        self.assertEqual(len(boxes.seen), 1, boxes.seen)
        said = boxes.seen[0][1]
        for problem in ("Servo rate: 20000 Hz is outside 400..10000 Hz",
                        "Angular deflection: 200 \u00b0 is outside 0.573..85.9436 \u00b0",
                        "Refine edges over: 0.005 mm is neither 0 (off) nor in 0.01..100 mm",
                        "Force limit: 0 N is outside 0.1..50 N"):
            self.assertIn(problem, said)
        self.assertNotIn("Linear deflection", said)
        prefs = preferences.load()
        self.assertEqual((prefs.servo_rate_hz, prefs.accuracy, prefs.custom_linear_deflection_mm,
                          prefs.custom_angular_deflection_deg, prefs.custom_refine_edge_mm, prefs.force_limit_n),
                         (1000, "Custom", 0.05, preferences.DEFAULTS.custom_angular_deflection_deg, 0.0, 2.5))

        def with_units(dialog, seen):
            typed(dialog, seen, "servoRate", "1500.5")
            typed(dialog, seen, "servoRate", "1,500")
            typed(dialog, seen, "servoRate", "2,5 kHz")
            typed(dialog, seen, "angularDeflection", "0,5 rad")
            typed(dialog, seen, "refineEdge", "0,25")
            typed(dialog, seen, "linearDeflection", "5 kg")
            typed(dialog, seen, "linearDeflection", "0.1 cm")

        with h.MessageBoxes() as boxes:
            seen = self._run_dialog(with_units)
        self.assertIn("Servo rate: 1500.5 Hz is not a whole number of Hz", seen["servoRate", "1500.5"][1])
        self.assertIn("Servo rate: is '1,500' 1500 or 1.500? give it without the comma", seen["servoRate", "1,500"][1])
        self.assertEqual(seen["servoRate", "2,5 kHz"], ("2500 Hz", ""))  # taken: the refusals gone
        self.assertEqual(seen["angularDeflection", "0,5 rad"][0], "28.64789 \u00b0")
        self.assertEqual(seen["refineEdge", "0,25"][0], "0.25 mm")
        self.assertIn("Linear deflection: '5 kg' is a mass, not a length", seen["linearDeflection", "5 kg"][1])
        self.assertEqual(seen["linearDeflection", "0.1 cm"], ("1 mm", ""))
        self.assertEqual(boxes.seen, [])
        prefs = preferences.load()
        self.assertEqual((prefs.servo_rate_hz, prefs.custom_linear_deflection_mm, prefs.custom_refine_edge_mm),
                         (2500, 1.0, 0.25))
        self.assertAlmostEqual(prefs.custom_angular_deflection_deg, 28.64789, places=6)

    def test_a_custom_accuracy_is_set_on_the_page_and_a_presets_values_are_shown(self):
        def fields(dialog):
            spin = {name: dialog.findChild(QtWidgets.QDoubleSpinBox, name)
                    for name in ("linearDeflection", "angularDeflection", "refineEdge")}
            shading = dialog.findChild(QtWidgets.QCheckBox, "forceShading")
            hint = dialog.findChild(QtWidgets.QLabel, "accuracyHint")
            values = (spin["linearDeflection"].value(), round(spin["angularDeflection"].value(), 2),
                      shading.isChecked(), spin["refineEdge"].value())
            enabled = all(w.isEnabled() for w in (*spin.values(), shading))
            return spin, shading, values, enabled, (hint.isVisible(), hint.text())

        def set_custom(dialog, seen):
            accuracy = dialog.findChild(QtWidgets.QComboBox, "accuracy")
            seen["items"] = [accuracy.itemText(i) for i in range(accuracy.count())]
            seen["fine"] = fields(dialog)[2:]
            accuracy.setCurrentText("Custom")
            spin, shading, values, enabled, _ = fields(dialog)
            seen["custom"] = (values, enabled)
            spin["linearDeflection"].setValue(0.25)
            spin["angularDeflection"].setValue(15.0)
            shading.setChecked(False)
            spin["refineEdge"].setValue(3.0)
            accuracy.setCurrentText("Draft")
            seen["draft"] = fields(dialog)[2:]
            accuracy.setCurrentText("Custom")  # the edits are still there
            seen["back"] = fields(dialog)[2:4]
            h.grab_screen("preferences_custom_accuracy.png")

        seen = self._run_dialog(set_custom)
        self.assertEqual(seen["items"], ["Draft", "Normal", "Fine", "Custom"])
        # Fine's own values, greyed, and why
        self.assertEqual(seen["fine"][0], (0.02, 5.73, True, 0.0))
        self.assertFalse(seen["fine"][1])
        self.assertEqual(seen["fine"][2], (True, "Fine's values; choose Custom to set your own."))
        # Custom starts from its stored values (the default's) and can be edited
        self.assertEqual(seen["custom"], ((0.02, 5.73, True, 0.0), True))
        self.assertEqual(seen["draft"][0], (0.5, 28.65, True, 0.0))
        self.assertFalse(seen["draft"][1])
        self.assertEqual(seen["back"], ((0.25, 15.0, False, 3.0), True))
        prefs = preferences.load()
        self.assertEqual((prefs.accuracy, prefs.custom_linear_deflection_mm, prefs.custom_angular_deflection_deg,
                          prefs.custom_force_shading, prefs.custom_refine_edge_mm),
                         ("Custom", 0.25, 15.0, False, 3.0))
        self.assertEqual(preferences.scene_accuracy(prefs).refine_edge_mm, 3.0)

        # a preset chosen later keeps the custom values for the next time
        seen = self._run_dialog(lambda dialog, seen: dialog.findChild(QtWidgets.QComboBox, "accuracy")
                                .setCurrentText("Normal"))
        prefs = preferences.load()
        self.assertEqual((prefs.accuracy, prefs.custom_linear_deflection_mm, prefs.custom_refine_edge_mm),
                         ("Normal", 0.25, 3.0))

        # values set from Python, finer than the fields show, survive the page untouched:
        # shown, switched to and from, and OK'd (they were rounded to the fields' decimals)
        fine_grained = prefs.replace(accuracy="Custom", custom_linear_deflection_mm=0.012345,
                                     custom_angular_deflection_deg=0.5730001)
        preferences.save(fine_grained)

        def flick(dialog, seen):
            accuracy = dialog.findChild(QtWidgets.QComboBox, "accuracy")
            for name in ("Fine", "Custom", "Draft", "Custom"):
                accuracy.setCurrentText(name)

        self._run_dialog(flick)
        self.assertEqual(preferences.load(), fine_grained)


if __name__ == "__main__":
    unittest.main()
