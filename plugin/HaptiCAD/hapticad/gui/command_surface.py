# SPDX-License-Identifier: GPL-3.0-or-later
"""Commands "Haptic surface" (tag the selected faces, then edit them in the task panel)
and "Edit haptic surface"."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import icon
from ..surface_object import is_haptic_surface, surface_tagging, untaggable
from .selection import face_picks

NAME = "HaptiCAD_Surface"
EDIT_NAME = "HaptiCAD_EditSurface"


def _no_dialog():
    return Gui.Control.activeDialog() is False or not Gui.Control.activeDialog()


class CommandHapticSurface:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_Surface"),
            "MenuText": "Haptic surface",
            "ToolTip": "Tag the selected faces with physical surface properties (material, roughness, "
            "friction pattern, texture) to feel them; select faces in the 3D view first",
        }

    def IsActive(self):
        # a face shown through a link too: pressed, it says why it cannot be tagged
        return App.ActiveDocument is not None and _no_dialog() and bool(face_picks())

    def Activated(self):
        picks = face_picks()
        refused = list(dict.fromkeys(r for r in (why or untaggable(o) for o, _, why in picks) if r))
        if refused:  # before any transaction: nothing is made, nothing to undo
            from PySide2 import QtWidgets

            QtWidgets.QMessageBox.warning(Gui.getMainWindow(), "Haptic surface", "\n".join(refused))
            return
        faces = []
        for obj, sub, _ in picks:
            other = surface_tagging(obj, sub)
            if other is None:
                faces.append((obj, sub))
            else:
                App.Console.PrintWarning(f"HaptiCAD: {obj.Label}.{sub} is already tagged by {other.Label}; "
                                         "it is left there (a face feels one way)\n")
                tagged_by = other
        if not faces:  # every selected face is tagged already: edit (the last) one of them
            Gui.doCommand(f"Gui.ActiveDocument.setEdit({tagged_by.Name!r}, 0)")
            return
        # by name in the active document: face_picks refused a face of another one (shown
        # through a link), whose name could be a part of this one's
        refs = ", ".join(f"(App.ActiveDocument.{obj.Name}, {sub!r})" for obj, sub in faces)
        doc = App.ActiveDocument
        # one transaction for the creation and the whole edit: the panel's OK commits it,
        # Cancel removes the new surface again
        doc.openTransaction("Haptic surface")
        # through the console, so the action is recorded in macros like any FreeCAD command
        Gui.doCommand("import HaptiCAD")
        Gui.doCommand(f"_surface = HaptiCAD.make_surface(App.ActiveDocument, [{refs}])")
        Gui.doCommand("Gui.ActiveDocument.setEdit(_surface.Name, 0)")


class CommandEditHapticSurface:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_SurfaceObject"),
            "MenuText": "Edit haptic surface",
            "ToolTip": "Edit the selected haptic surface in the task panel (or double-click it in the tree)",
        }

    def _selected(self):
        sel = Gui.Selection.getSelection()
        return sel[0] if len(sel) == 1 and is_haptic_surface(sel[0]) else None

    def IsActive(self):
        return App.ActiveDocument is not None and _no_dialog() and self._selected() is not None

    def Activated(self):
        Gui.doCommand(f"Gui.ActiveDocument.setEdit({self._selected().Name!r}, 0)")


Gui.addCommand(NAME, CommandHapticSurface())
Gui.addCommand(EDIT_NAME, CommandEditHapticSurface())
