# SPDX-License-Identifier: GPL-3.0-or-later
"""Tells a running Feel session when the designer edits what it feels.

While a session runs, this document observer watches the session's document and calls
back once, after FreeCAD has finished the edit (the changes of one edit, and of a
recompute that reshapes several objects, are gathered into one call):

- callback(geometry=True) when a part in the session's scene changed shape (a new
  dimension, a new feature), moved (its placement, or that of a Body or App::Part
  holding it) or was deleted: the scene must be tessellated again and swapped into the
  loop (LiveSession.update_scene);
- callback(geometry=False) when only a HapticSurface, HapticVibration, StiffnessStudy or
  SimilarityStudy changed (any
  property: material, friction, roughness, pattern, texture, vibration, the faces it
  tags, a study's mechanism), or one was created or deleted, or the sketch or edge a Curve
  pattern follows was edited or moved: the surfaces are compiled again and handed to the
  loop without a new scene (LiveSession.update_surfaces).

A study's record keeping changes nothing felt and calls nothing: a stiffness study's
participants and records (recording a preference said "Surface edited"), its slider's
range, a similarity study's runs and protocol.

Either way the edit is felt without stopping the session. Changes during a recompute
wait for its end (the shapes and the face references are then all up to date), so one
recompute makes one call.
"""
import FreeCAD as App
from PySide2 import QtCore

IGNORED = frozenset(("Label", "Label2", "Visibility", "ExpressionEngine"))
# a stiffness study's property groups that change what is felt (not Customise, the slider's, or Cohort)
STIFFNESS_FELT_GROUPS = ("Study", "Beam", "Button")


class SessionEditObserver:
    def __init__(self, doc, callback, parts):
        """``parts``: a callable giving the names of the objects the session's scene
        holds (asked at each change: a new scene may hold others)."""
        self.doc = doc
        self.callback = callback
        self.parts = parts
        self.pending = False  # a call is queued
        self.dirty = False  # something changed since the last call
        self.geometry = False
        self.recomputing = False
        App.addDocumentObserver(self)

    def remove(self):
        App.removeDocumentObserver(self)

    def _ours(self, obj):
        try:
            return obj.Document is self.doc and not self.doc.Restoring
        except Exception:  # noqa: BLE001 (an object being deleted may be half gone)
            return False

    def _haptic(self, obj):
        from ..similarity_study import is_similarity_study
        from ..stiffness_study import is_stiffness_study
        from ..surface_object import is_haptic_surface
        from ..vibration_object import is_haptic_vibration

        return self._ours(obj) and (is_haptic_surface(obj) or is_haptic_vibration(obj) or is_stiffness_study(obj)
                                    or is_similarity_study(obj))

    @staticmethod
    def _felt(obj, prop):
        """False for a study's bookkeeping, with which what the face renders does not
        change: a similarity study's runs and protocol; a stiffness study's participants,
        records and slider (what it moves, its range: the parameter moved is felt). A
        stiffness study's felt properties are its surface, model and mechanism (its
        Study, Beam and Button groups)."""
        from ..similarity_study import FELT_PROPERTIES, is_similarity_study
        from ..stiffness_study import PROPERTIES, is_stiffness_study

        if is_similarity_study(obj):
            return prop in FELT_PROPERTIES
        if is_stiffness_study(obj):
            return any(name == prop and group in STIFFNESS_FELT_GROUPS for name, _, group, *_ in PROPERTIES)
        return True

    def _reshapes(self, obj, prop):
        """A change of shape or placement of a part in the scene, or of a container
        that places one (a Body, an App::Part)."""
        if prop not in ("Shape", "Placement") or not self._ours(obj):
            return False
        parts = self.parts()
        if obj.Name in parts:
            return True
        if prop != "Placement":
            return False
        for name in parts:
            part = self.doc.getObject(name)
            if part is not None and obj in part.InListRecursive:
                return True
        return False

    def _changed(self, geometry=False):
        self.dirty = True
        self.geometry = self.geometry or geometry
        if not self.recomputing:  # else once the recompute is done: it may change more
            self._later()

    def _later(self):
        if not self.pending:
            self.pending = True
            QtCore.QTimer.singleShot(0, self._fire)

    def _fire(self):
        self.pending = False
        # a long recompute lets Qt run queued calls (FreeCAD's progress bar): wait for
        # its end, when the shapes and the face references are all up to date
        if self.recomputing or not self.dirty:
            return
        geometry = self.geometry
        self.dirty = False
        self.geometry = False
        self.callback(geometry)

    def slotBeforeRecomputeDocument(self, doc):
        if doc is self.doc:
            self.recomputing = True

    def slotRecomputedDocument(self, doc):
        if doc is self.doc:
            self.recomputing = False
            if self.dirty:
                self._later()

    def _bends_a_pattern(self, obj, prop):
        """A change of shape or placement of the curve a Curve pattern follows (or of a
        container that places it)."""
        from ..surface_object import is_haptic_surface, moves_with, pattern_curve_object

        if prop not in ("Shape", "Placement") or not self._ours(obj):
            return False
        return moves_with(obj, [pattern_curve_object(s) for s in self.doc.Objects if is_haptic_surface(s)])

    def slotChangedObject(self, obj, prop):
        if self._reshapes(obj, prop):
            self._changed(geometry=True)
        elif prop not in IGNORED and ((self._haptic(obj) and self._felt(obj, prop))
                                      or self._bends_a_pattern(obj, prop)):
            self._changed()

    def slotCreatedObject(self, obj):
        if self._haptic(obj):
            self._changed()

    def slotDeletedObject(self, obj):
        if self._haptic(obj) or (self._ours(obj) and obj.Name in self.parts()):
            self._changed(geometry=True)
