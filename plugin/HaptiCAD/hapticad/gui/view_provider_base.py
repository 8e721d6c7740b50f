# SPDX-License-Identifier: GPL-3.0-or-later
"""What HaptiCAD's view providers share: drawing nothing of their own, and editing the
object in a task panel on a double click."""
from .. import icon
from ..proxy_state import NoState


class DrawsNothing(NoState):
    """A view provider whose object draws nothing (FreeCAD still needs one display
    mode); its tree icon is ``ICON``."""

    ICON = "HaptiCAD"

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        from pivy import coin

        self.Object = vobj.Object
        vobj.addDisplayMode(coin.SoSeparator(), "Default")

    def getDisplayModes(self, vobj):
        return ["Default"]

    def getDefaultDisplayMode(self):
        return "Default"

    def getIcon(self):
        return icon(self.ICON)


class EditsInTaskPanel:
    """setEdit shows ``task_panel(obj)``; a double click edits, or, with a dialog open,
    says what to do instead."""

    def task_panel(self, obj):
        raise NotImplementedError

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None
        import FreeCADGui as Gui

        Gui.Control.showDialog(self.task_panel(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        import FreeCADGui as Gui

        Gui.Control.closeDialog()
        return True

    def doubleClicked(self, vobj):
        import FreeCADGui as Gui

        if Gui.Control.activeDialog():
            # FreeCAD shows one task panel at a time: say so, rather than nothing happening
            from . import task_panel_feel

            label = vobj.Object.Label
            feel = task_panel_feel.active_panel()
            if feel is not None:
                feel.show_message(f"While you feel, edit {label} in the property editor (its Data tab): "
                                  "every change is felt at once. Close Feel to edit it in its panel.")
            else:
                Gui.getMainWindow().statusBar().showMessage(
                    f"Close the open task panel first to edit {label}.", 10000)
            return True
        vobj.Document.setEdit(vobj.Object.Name, 0)
        return True
