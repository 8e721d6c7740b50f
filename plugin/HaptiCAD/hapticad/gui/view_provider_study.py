# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of StiffnessStudy objects: its icon; a study draws nothing of its own
(its surface's faces are drawn by the surface)."""
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
