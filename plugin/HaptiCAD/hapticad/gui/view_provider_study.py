# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of StiffnessStudy objects: its icon, and its task panel on a double
click; a study draws nothing of its own (its surface's faces are drawn by the surface)."""
from .. import icon
from ..proxy_state import NoState


class ViewProviderStiffnessStudy(NoState):
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        from pivy import coin

        self.Object = vobj.Object
        vobj.addDisplayMode(coin.SoSeparator(), "Default")  # FreeCAD needs one display mode

    def getDisplayModes(self, vobj):
        return ["Default"]

    def getDefaultDisplayMode(self):
        return "Default"

    def getIcon(self):
        return icon("HaptiCAD_Study")

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        import FreeCADGui as Gui

        from .task_panel_study import StudyTaskPanel

        Gui.Control.showDialog(StudyTaskPanel(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        import FreeCADGui as Gui

        Gui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        import FreeCADGui as Gui

        if Gui.Control.activeDialog():
            return False
        vobj.Document.setEdit(vobj.Object.Name, 0)
        return True
