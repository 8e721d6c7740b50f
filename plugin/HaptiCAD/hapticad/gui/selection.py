# SPDX-License-Identifier: GPL-3.0-or-later
"""Faces in the current 3D selection."""
import FreeCADGui as Gui


def selected_faces():
    """[(object, "FaceN"), ...] for every selected face, in selection order."""
    faces = []
    for sel in Gui.Selection.getSelectionEx():
        for sub in sel.SubElementNames:
            if sub.startswith("Face"):
                faces.append((sel.Object, sub))
    return faces
