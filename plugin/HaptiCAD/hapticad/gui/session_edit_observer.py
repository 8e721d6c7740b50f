# SPDX-License-Identifier: GPL-3.0-or-later
"""Tells a running Feel session when the designer edits what it feels.

While a session runs, this document observer watches the session's document and calls
back once, after FreeCAD has finished the edit (the changes of one edit, and of a
recompute that reshapes several objects, are gathered into one call):

- callback(geometry=True) when a part in the session's scene changed shape (a new
  dimension, a new feature, a moved placement): the scene must be tessellated again
  and swapped into the loop (LiveSession.update_scene);
- callback(geometry=False) when only a HapticSurface or HapticVibration changed (any
  property: material, friction, roughness, pattern, texture, vibration, the faces it
  tags), or one was created or deleted: the surfaces are compiled again and handed to
  the loop without a new scene (LiveSession.update_surfaces).

Either way the edit is felt without stopping the session.
"""
import FreeCAD as App
from PySide2 import QtCore

IGNORED = frozenset(("Label", "Label2", "Visibility", "ExpressionEngine"))


class SessionEditObserver:
    def __init__(self, doc, callback, parts):
        """``parts``: a callable giving the names of the objects the session's scene
        holds (asked at each change: a new scene may hold others)."""
        self.doc = doc
        self.callback = callback
        self.parts = parts
        self.pending = False
        self.geometry = False
        App.addDocumentObserver(self)

    def remove(self):
        App.removeDocumentObserver(self)

    def _ours(self, obj):
        try:
            return obj.Document is self.doc and not self.doc.Restoring
        except Exception:  # noqa: BLE001 (an object being deleted may be half gone)
            return False

    def _haptic(self, obj):
        from ..surface_object import is_haptic_surface
        from ..vibration_object import is_haptic_vibration

        return self._ours(obj) and (is_haptic_surface(obj) or is_haptic_vibration(obj))

    def _later(self):
        if not self.pending:
            self.pending = True
            QtCore.QTimer.singleShot(0, self._fire)

    def _fire(self):
        geometry = self.geometry
        self.pending = False
        self.geometry = False
        self.callback(geometry)

    def slotChangedObject(self, obj, prop):
        if prop == "Shape" and self._ours(obj) and obj.Name in self.parts():
            self.geometry = True
            self._later()
        elif prop not in IGNORED and self._haptic(obj):
            self._later()

    def slotCreatedObject(self, obj):
        if self._haptic(obj):
            self._later()

    def slotDeletedObject(self, obj):
        if self._haptic(obj):
            self._later()
