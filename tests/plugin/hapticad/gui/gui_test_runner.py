# SPDX-License-Identifier: GPL-3.0-or-later
"""Runs a GUI test module inside FreeCAD's GUI, then exits with its status.

    xvfb-run -a freecad tests/plugin/hapticad/gui/gui_test_runner.py
with HAPTICAD_GUI_TEST=<module name> and HAPTICAD_GUI_TEST_DIR=<its folder> in the
environment. The tests start once the main window is up (a Qt timer), and the
process exits with 0 only if every test passed.
"""
import os
import sys
import traceback
import unittest

from PySide2 import QtCore


def _run():
    status = 1
    try:
        sys.path.insert(0, os.environ["HAPTICAD_GUI_TEST_DIR"])
        suite = unittest.defaultTestLoader.loadTestsFromName(os.environ["HAPTICAD_GUI_TEST"])
        # FreeCAD routes sys.stderr to its report view: write to the process stderr
        result = unittest.TextTestRunner(stream=sys.__stderr__, verbosity=2).run(suite)
        status = 0 if result.wasSuccessful() and result.testsRun > 0 else 1
    except Exception:
        traceback.print_exc(file=sys.__stderr__)
    finally:
        sys.__stderr__.flush()
        sys.__stdout__.flush()
        os._exit(status)


QtCore.QTimer.singleShot(200, _run)
