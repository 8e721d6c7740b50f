# SPDX-License-Identifier: GPL-3.0-or-later
"""Command "Similarity study": study which textures feel alike on the selected haptic
surface (seed 001 §IV), then edit it in the task panel."""
import FreeCAD as App
import FreeCADGui as Gui

from .. import icon
from ..similarity_study import similarity_studies_of
from .command_study import selected_surface

NAME = "HaptiCAD_SimilarityStudy"


class CommandSimilarityStudy:
    def GetResources(self):
        return {
            "Pixmap": icon("HaptiCAD_SimilarityStudy"),
            "MenuText": "Similarity study",
            "ToolTip": "Study which textures feel alike on the selected haptic surface: participants rate pairs "
            "of gratings (the paper's nine by default) and class them against two references, and the study "
            "maps them into a perceptual space; select a haptic surface, or one of its faces, first",
        }

    def IsActive(self):
        return App.ActiveDocument is not None and not Gui.Control.activeDialog() and selected_surface() is not None

    def Activated(self):
        surface = selected_surface()
        existing = [s for s in similarity_studies_of(surface.Document) if s.Surface == surface]
        if existing:
            Gui.doCommand(f"Gui.ActiveDocument.setEdit({existing[0].Name!r}, 0)")
            return
        # its own undo step (the panel has only Close, and commits nothing)
        App.ActiveDocument.openTransaction("Similarity study")
        Gui.doCommand("import HaptiCAD")
        Gui.doCommand("_study = HaptiCAD.make_similarity_study(App.ActiveDocument, "
                      f"App.ActiveDocument.{surface.Name})")
        App.ActiveDocument.commitTransaction()
        Gui.doCommand("Gui.ActiveDocument.setEdit(_study.Name, 0)")


Gui.addCommand(NAME, CommandSimilarityStudy())
