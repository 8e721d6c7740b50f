# SPDX-License-Identifier: GPL-3.0-or-later
"""Calls back after each Undo or Redo of one document, once FreeCAD has applied it.

A task panel that edits inside its own transaction (the surface panel) loses it to an
Undo or a Redo pressed while it is open: Undo commits the pending transaction and undoes
it. The panel then shows values the object no longer has, and its Cancel and OK act on
no transaction. It listens with this, shows the object again, and opens a transaction at
its next edit. App-only (FreeCAD's document observer)."""
import FreeCAD as App


class UndoRedoObserver:
    """``callback()`` after each Undo or Redo of ``doc``, until ``remove()``."""

    def __init__(self, doc, callback):
        self.doc_name = doc.Name
        self.callback = callback
        App.addDocumentObserver(self)

    def remove(self):
        App.removeDocumentObserver(self)

    def slotUndoDocument(self, doc):
        if doc.Name == self.doc_name:
            self.callback()

    def slotRedoDocument(self, doc):
        if doc.Name == self.doc_name:
            self.callback()
