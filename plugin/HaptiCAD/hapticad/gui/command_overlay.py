# SPDX-License-Identifier: GPL-3.0-or-later
"""Commands that control the overlay: show/hide it, colour it by roughness."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import icon, preferences
from ..surface_object import surfaces_of

NAME = "HaptiCAD_ToggleOverlay"
COLOUR_NAME = "HaptiCAD_OverlayByRoughness"


def refresh_all():
    """Redraws every surface's overlay and legend in every open document, and shows the
    stored state in the two check boxes (the preferences page may have changed it)."""
    from . import overlay_legend

    prefs = preferences.load()
    for name, checked in ((NAME, prefs.overlay_visible), (COLOUR_NAME, prefs.overlay_colour_by == "Roughness")):
        command = Gui.Command.get(name)
        actions = command.getAction() if command is not None else []
        for action in actions:
            if action.isCheckable() and action.isChecked() != checked:
                action.blockSignals(True)
                action.setChecked(checked)
                action.blockSignals(False)

    for doc in App.listDocuments().values():
        for surface in surfaces_of(doc):
            proxy = getattr(surface.ViewObject, "Proxy", None) if surface.ViewObject else None
            if proxy is not None and hasattr(proxy, "refresh"):
                proxy.refresh()
        overlay_legend.refresh(doc)


class CommandToggleOverlay:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_Overlay"),
            "MenuText": "Show haptic overlay",
            "ToolTip": "Show or hide the colours and friction stripes drawn over tagged faces, and their "
            "legend (the part keeps its own colours)",
            "Checkable": preferences.load().overlay_visible,
        }

    def IsActive(self):
        return App.ActiveDocument is not None

    def Activated(self, checked=None):
        visible = (not preferences.load().overlay_visible) if checked is None else bool(checked)
        preferences.update(overlay_visible=visible)
        refresh_all()


class CommandOverlayByRoughness:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_ColourByRoughness"),
            "MenuText": "Colour overlay by roughness",
            "ToolTip": "Colour tagged faces by their roughness category instead of their material",
            "Checkable": preferences.load().overlay_colour_by == "Roughness",
        }

    def IsActive(self):
        return App.ActiveDocument is not None

    def Activated(self, checked=None):
        by_roughness = (preferences.load().overlay_colour_by != "Roughness") if checked is None else bool(checked)
        preferences.update(overlay_colour_by="Roughness" if by_roughness else "Material")
        refresh_all()


Gui.addCommand(NAME, CommandToggleOverlay())
Gui.addCommand(COLOUR_NAME, CommandOverlayByRoughness())
