# SPDX-License-Identifier: GPL-3.0-or-later
"""Calls back once when a given document is being closed.

A task panel that works on one document (Feel runs a servo loop on its parts) must stop
before the document and its 3D view are gone; FreeCAD leaves an open task dialog
behind when its document closes. Remove the observer when the panel closes."""
import FreeCAD as App


class DocumentClosingObserver:
    def __init__(self, doc, callback):
        self.doc_name = doc.Name
        self.callback = callback
        App.addDocumentObserver(self)

    def remove(self):
        App.removeDocumentObserver(self)

    def slotDeletedDocument(self, doc):
        if doc.Name == self.doc_name:
            self.remove()
            self.callback()
