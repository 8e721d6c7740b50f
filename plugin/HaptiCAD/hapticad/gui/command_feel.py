# SPDX-License-Identifier: GPL-3.0-or-later
"""Command "Feel": starts a Feel session on the active document's tagged faces."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import icon
from ..surface_object import surfaces_of
from ..vibration_object import vibrations_of

NAME = "HaptiCAD_Feel"


class CommandFeel:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_Feel"),
            "MenuText": "Feel",
            "ToolTip": "Feel the tagged faces: the simulated probe follows the mouse (the wheel presses), or "
            "a haptic device drives it; a live chart shows the forces",
        }

    def IsActive(self):
        doc = App.ActiveDocument
        return (doc is not None and not Gui.Control.activeDialog()
                and bool(surfaces_of(doc) or vibrations_of(doc)))

    def Activated(self):
        from .task_panel_feel import FeelTaskPanel

        panel = FeelTaskPanel(App.ActiveDocument)
        Gui.Control.showDialog(panel)
        panel.start()


Gui.addCommand(NAME, CommandFeel())
