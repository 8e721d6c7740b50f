# SPDX-License-Identifier: GPL-3.0-or-later
"""Tells a running Feel session when the designer edits a surface.

While a session runs, this document observer watches the session's document: a change
to a HapticSurface or HapticVibration (any property: material, friction, roughness,
pattern, texture, vibration, the faces it tags), or one created or deleted, calls back
once, after FreeCAD has finished the edit (the changes of one edit, and of an edit that
sets several properties, are gathered into one call). The callback recompiles the
surfaces and hands them to the servo loop (LiveSession.update_surfaces): the edit is
felt without stopping the session.
"""
import FreeCAD as App
from PySide2 import QtCore

IGNORED = frozenset(("Label", "Label2", "Visibility", "ExpressionEngine"))


class SurfaceEditObserver:
    def __init__(self, doc, callback):
        self.doc = doc
        self.callback = callback
        self.pending = False
        App.addDocumentObserver(self)

    def remove(self):
        App.removeDocumentObserver(self)

    def _haptic(self, obj):
        from ..surface_object import is_haptic_surface
        from ..vibration_object import is_haptic_vibration

        try:
            if obj.Document is not self.doc or self.doc.Restoring:
                return False
        except Exception:  # noqa: BLE001 (an object being deleted may be half gone)
            return False
        return is_haptic_surface(obj) or is_haptic_vibration(obj)

    def _later(self):
        if not self.pending:
            self.pending = True
            QtCore.QTimer.singleShot(0, self._fire)

    def _fire(self):
        self.pending = False
        self.callback()

    def slotChangedObject(self, obj, prop):
        if prop not in IGNORED and self._haptic(obj):
            self._later()

    def slotCreatedObject(self, obj):
        if self._haptic(obj):
            self._later()

    def slotDeletedObject(self, obj):
        if self._haptic(obj):
            self._later()
