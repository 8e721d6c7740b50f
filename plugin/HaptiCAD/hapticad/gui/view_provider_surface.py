# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of HapticSurface objects: icon and tree presence."""
from .. import icon


class ViewProviderHapticSurface:
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object
        from pivy import coin

        # a surface draws nothing of its own yet; FreeCAD needs one display mode
        self._root = coin.SoSeparator()
        vobj.addDisplayMode(self._root, "Default")

    def getDisplayModes(self, vobj):
        return ["Default"]

    def getDefaultDisplayMode(self):
        return "Default"

    def getIcon(self):
        return icon("HaptiCAD_Surface")

    def dumps(self):
        return None

    def loads(self, state):
        return None

    def __getstate__(self):
        return None

    def __setstate__(self, state):
        return None
