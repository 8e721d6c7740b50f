# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD's page in FreeCAD's real preferences dialog (Xvfb): it is there, shows the
stored values, and stores what the user sets. Run by gui_test_runner.py."""
import os
import sys
import unittest

import FreeCADGui as Gui
from PySide2 import QtCore, QtWidgets

from hapticad import preferences

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402


class PreferencesPageTest(unittest.TestCase):
    def setUp(self):
        preferences.save(preferences.Preferences(servo_rate_hz=2000, accuracy="Fine", force_limit_n=2.5))

    def tearDown(self):
        preferences.save(preferences.Preferences())

    def test_the_page_is_in_freecads_preferences_dialog_and_stores_values(self):
        seen = {}

        def use_dialog():
            dialog = QtWidgets.QApplication.activeModalWidget()
            try:
                seen["dialog"] = dialog is not None
                rate = dialog.findChild(QtWidgets.QSpinBox, "servoRate")
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

        QtCore.QTimer.singleShot(800, use_dialog)
        Gui.showPreferences("HaptiCAD", 0)  # modal: returns when the dialog closes
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

        def in_dialog():
            dialog = QtWidgets.QApplication.activeModalWidget()
            try:
                use(dialog, seen)
                dialog.findChild(QtWidgets.QDialogButtonBox).button(QtWidgets.QDialogButtonBox.Ok).click()
            except Exception as exc:  # report in the test, never leave the modal dialog open
                seen["error"] = repr(exc)
                dialog.reject()

        QtCore.QTimer.singleShot(800, in_dialog)
        Gui.showPreferences("HaptiCAD", 0)
        self.assertNotIn("error", seen, seen)
        return seen

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
