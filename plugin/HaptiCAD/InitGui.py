# SPDX-License-Identifier: GPL-3.0-or-later
# FreeCAD runs this file at GUI start-up (exec'd: no __file__, no module globals).


class HaptiCADWorkbench(Workbench):  # noqa: F821 (FreeCAD injects Workbench)
    MenuText = "HaptiCAD"
    ToolTip = "Tag faces with physical surface properties and feel them through a haptic device"

    def __init__(self):
        import hapticad

        self.__class__.Icon = hapticad.icon("HaptiCAD")

    def Initialize(self):
        try:
            from hapticad import _core  # noqa: F401
        except ImportError as exc:
            # e.g. installed by the Addon Manager, which cannot compile
            App.Console.PrintError(  # noqa: F821
                f"HaptiCAD: its compiled module is missing ({exc}). Install the hapticad .deb, or build "
                "it with packaging/setup.sh from a checkout (see README.md)\n")
            return
        # commands are imported on activation only, as freecad.gears does
        from hapticad.gui import commands

        self.appendToolbar("HaptiCAD", commands.TOOLBAR)
        self.appendMenu("&HaptiCAD", commands.MENU)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


Gui.addWorkbench(HaptiCADWorkbench())  # noqa: F821


def _add_preferences_page():
    # at start-up, so Edit > Preferences shows the page before the workbench is opened;
    # the group's icon is found by name (preferences-hapticad.svg) in the icon path
    import hapticad
    from hapticad.gui.preferences_page import PreferencesPage

    Gui.addIconPath(hapticad.ICONS_DIR)  # noqa: F821
    Gui.addPreferencePage(PreferencesPage, "HaptiCAD")  # noqa: F821


_add_preferences_page()
