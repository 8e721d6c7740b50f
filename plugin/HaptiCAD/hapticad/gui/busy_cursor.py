# SPDX-License-Identifier: GPL-3.0-or-later
"""The wait cursor over work that holds the GUI thread for a noticeable time (building a
scene, fitting a texture), so a designer sees FreeCAD is working rather than hung.

    with busy_cursor():
        scene = build_document_scene(doc)

Restored however the block ends (an exception included); nests.
"""
import contextlib

from PySide2 import QtCore, QtWidgets


@contextlib.contextmanager
def busy_cursor():
    QtWidgets.QApplication.setOverrideCursor(QtCore.Qt.WaitCursor)
    try:
        yield
    finally:
        QtWidgets.QApplication.restoreOverrideCursor()
