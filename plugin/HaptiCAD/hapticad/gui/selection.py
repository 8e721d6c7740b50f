# SPDX-License-Identifier: GPL-3.0-or-later
"""What is selected in the 3D view, as HaptiCAD wants it."""
import FreeCADGui as Gui

from ..face_references import owner_face


def selected_faces():
    """[(object, "FaceN"), ...] for every selected face, in selection order; a face of a
    PartDesign feature is given as the Body's face (face_references.owner_face)."""
    faces = []
    for sel in Gui.Selection.getSelectionEx():
        for sub in sel.SubElementNames:
            if sub.startswith("Face"):
                pair = owner_face(sel.Object, sub)
                if pair not in faces:
                    faces.append(pair)
    return faces


def selected_curve():
    """(object, [edge names]) for a curve pattern: selected edges of one object, or a
    whole selected sketch ([] = all its edges); None if nothing fits."""
    for sel in Gui.Selection.getSelectionEx():
        edges = [s for s in sel.SubElementNames if s.startswith("Edge")]
        if edges:
            return sel.Object, edges
        if not sel.SubElementNames and hasattr(sel.Object, "Shape") and sel.Object.Shape.Edges \
                and not sel.Object.Shape.Faces:
            return sel.Object, []
    return None


def selected_parts():
    """Selected objects with a solid shape (for a vibration)."""
    return [sel.Object for sel in Gui.Selection.getSelectionEx()
            if hasattr(sel.Object, "Shape") and not sel.Object.Shape.isNull() and sel.Object.Shape.Faces]
