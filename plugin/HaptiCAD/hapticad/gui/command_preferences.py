# SPDX-License-Identifier: GPL-3.0-or-later
"""Command "Preferences": opens FreeCAD's preferences at HaptiCAD's page."""
import FreeCADGui as Gui

from .. import icon

NAME = "HaptiCAD_Preferences"


class CommandPreferences:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_Preferences"),
            "MenuText": "Preferences...",
            "ToolTip": "HaptiCAD preferences: device, servo rate, accuracy, force limit, workspace mapping",
        }

    def IsActive(self):
        return True

    def Activated(self):
        Gui.showPreferences("HaptiCAD", 0)


Gui.addCommand(NAME, CommandPreferences())
