# SPDX-License-Identifier: GPL-3.0-or-later
"""What the studies' task panels share: boxes with the study's icon, a status line, and
only a Close button (edits are undo steps of their own, so nothing waits for an OK);
the panel closes with its document."""
import FreeCADGui as Gui
from PySide2 import QtGui, QtWidgets

from .. import icon
from .document_closing import DocumentClosingObserver


class CloseOnlyPanel:
    """Base of a study's panel. Subclasses set ICON and call ``watch_closing`` once built;
    ``observers`` are removed when the panel is left."""

    ICON = "HaptiCAD"

    def watch_closing(self, doc, *observers):
        self.doc = doc
        self.observers = observers
        self.closing = DocumentClosingObserver(doc, self.document_closing)

    def _box(self, title):
        box = QtWidgets.QWidget()
        box.setWindowTitle(title)
        box.setWindowIcon(QtGui.QIcon(icon(self.ICON)))
        return box

    def _status_box(self, title, object_name):
        """A box holding one wrapped status label, ``self.status``."""
        box = self._box(title)
        layout = QtWidgets.QVBoxLayout(box)
        self.status = QtWidgets.QLabel()
        self.status.setObjectName(object_name)
        self.status.setWordWrap(True)
        layout.addWidget(self.status)
        return box

    def document_closing(self):
        self.document_gone = True
        Gui.Control.closeDialog()

    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Close)

    def _leave(self):
        self._left = True  # closed: what it shows is no longer the document's
        for observer in self.observers:
            observer.remove()
        self.closing.remove()
        if not getattr(self, "document_gone", False):
            gui_doc = Gui.getDocument(self.doc.Name)
            if gui_doc is not None and gui_doc.getInEdit() is not None:
                gui_doc.resetEdit()
        return True

    def reject(self):
        return self._leave()

    def accept(self):
        return self._leave()
