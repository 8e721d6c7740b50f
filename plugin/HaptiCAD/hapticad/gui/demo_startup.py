# SPDX-License-Identifier: GPL-3.0-or-later
# Run by FreeCAD after it opens the demo document: switch to the HaptiCAD workbench
# and show the part.
import FreeCADGui as Gui

Gui.activateWorkbench("HaptiCADWorkbench")
if Gui.ActiveDocument is not None:
    Gui.ActiveDocument.ActiveView.viewIsometric()
    Gui.SendMsgToActiveView("ViewFit")
