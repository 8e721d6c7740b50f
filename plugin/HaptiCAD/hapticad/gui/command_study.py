# SPDX-License-Identifier: GPL-3.0-or-later
"""Command "Stiffness study": study how the selected haptic surface gives under the
finger (a toothbrush's neck, a push button), then edit it in the task panel."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import icon
from ..stiffness_study import study_of
from ..surface_object import is_haptic_surface, surface_tagging
from .selection import selected_faces

NAME = "HaptiCAD_Study"


def selected_surface():
    """The haptic surface selected in the tree, or tagging a face selected in the view."""
    for obj in Gui.Selection.getSelection():
        if is_haptic_surface(obj):
            return obj
    for obj, sub in selected_faces():
        surface = surface_tagging(obj, sub)
        if surface is not None:
            return surface
    return None


class CommandStiffnessStudy:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_Study"),
            "MenuText": "Stiffness study",
            "ToolTip": "Study how the selected haptic surface gives under the finger (a toothbrush's bending "
            "neck, a push button's snap) and record what participants prefer; select a haptic surface, or "
            "one of its faces, first",
        }

    def IsActive(self):
        return App.ActiveDocument is not None and not Gui.Control.activeDialog() and selected_surface() is not None

    def Activated(self):
        surface = selected_surface()
        study = study_of(surface)
        if study is None:
            # its own undo step (the panel has only Close, and commits nothing)
            App.ActiveDocument.openTransaction("Stiffness study")
            Gui.doCommand("import HaptiCAD")
            Gui.doCommand(f"_study = HaptiCAD.make_study(App.ActiveDocument, App.ActiveDocument.{surface.Name})")
            App.ActiveDocument.commitTransaction()
            Gui.doCommand("Gui.ActiveDocument.setEdit(_study.Name, 0)")
        else:
            Gui.doCommand(f"Gui.ActiveDocument.setEdit({study.Name!r}, 0)")


Gui.addCommand(NAME, CommandStiffnessStudy())
