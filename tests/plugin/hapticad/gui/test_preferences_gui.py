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


if __name__ == "__main__":
    unittest.main()
