# SPDX-License-Identifier: GPL-3.0-or-later
"""Watches a study (stiffness or similarity) and what it is felt on, for controls and
panels that show it: they follow any change, whichever way it came (an undo, the
property editor, a script)."""
import FreeCAD as App
from PySide2 import QtCore


class StudyObserver:
    """Calls back, once per event-loop turn, when the study changes by any way (an undo,
    the property editor) or its document is saved, so the controls never show a design
    that is not the study's.
    Controls that show a change they made themselves say so (``mark_shown``): the call
    due then is dropped, unless the study changed again after."""

    def __init__(self, study, callback, watch_references=False):
        self.study, self.callback, self.pending = study, callback, False
        self.watch_references = watch_references  # a similarity study's ReferenceA and B too
        self.removed = False
        self.changes = 0  # changes seen so far
        self.shown_at = None  # how many had been seen when the study was last shown (mark_shown)
        App.addDocumentObserver(self)

    def mark_shown(self):
        """Everything changed so far is shown: a call due for it is not needed (a slider step
        loaded its panel at once, then again a turn later)."""
        self.shown_at = self.changes

    def remove(self):
        """Stops watching; a call already due (a turn later) is dropped: the widgets it
        would load may be deleted by then (an undone study closes its panel)."""
        if not self.removed:
            self.removed = True
            App.removeDocumentObserver(self)

    def slotChangedObject(self, obj, prop):
        try:
            ours = obj is self.study or obj == self.study.Surface or (
                self.watch_references and obj in (self.study.ReferenceA, self.study.ReferenceB))
        except Exception:  # noqa: BLE001 (an object being deleted)
            ours = False
        if ours:
            self.changes += 1
        if ours and not self.pending:
            self.pending = True
            QtCore.QTimer.singleShot(0, self._fire)

    def slotDeletedObject(self, obj):
        self.slotChangedObject(obj, "")

    def slotFinishSaveDocument(self, doc, path):
        # saved: what is on disk changed (records no longer only in memory, a first path)
        try:
            ours = doc == self.study.Document
        except Exception:  # noqa: BLE001 (the study deleted)
            ours = False
        if ours:
            self.slotChangedObject(self.study, "")

    def _fire(self):
        self.pending = False
        if not self.removed and self.changes != self.shown_at:
            self.callback()
