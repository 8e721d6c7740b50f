# SPDX-License-Identifier: GPL-3.0-or-later
"""Command "Haptic surface": tag the selected faces with a HapticSurface."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import icon
from .selection import selected_faces

NAME = "HaptiCAD_Surface"


class CommandHapticSurface:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_Surface"),
            "MenuText": "Haptic surface",
            "ToolTip": "Tag the selected faces with physical surface properties "
            "(material, roughness, friction pattern) to feel them",
        }

    def IsActive(self):
        return App.ActiveDocument is not None and bool(selected_faces())

    def Activated(self):
        faces = selected_faces()
        refs = ", ".join(f"(App.ActiveDocument.{obj.Name}, {sub!r})" for obj, sub in faces)
        doc = App.ActiveDocument
        doc.openTransaction("Haptic surface")
        # through the console, so the action is recorded in macros like any FreeCAD command
        Gui.doCommand("import HaptiCAD")
        Gui.doCommand(f"_surface = HaptiCAD.make_surface(App.ActiveDocument, [{refs}])")
        Gui.doCommand("App.ActiveDocument.recompute()")
        doc.commitTransaction()


Gui.addCommand(NAME, CommandHapticSurface())
