# SPDX-License-Identifier: GPL-3.0-or-later
"""What is selected in the 3D view, as HaptiCAD wants it."""
import FreeCADGui as Gui

from ..face_picking import element, picked_curve, picked_face


def face_picks():
    """Every selected face, in selection order, as face_picking.picked_face gives it:
    (object, "FaceN", "") for a face of the part under the cursor (a PartDesign feature's as
    its Body's), (None, "", why) for a face shown through a link. Read from the unresolved
    selection: the resolved one names a link's original, shown elsewhere or in another
    document, as if it had been clicked."""
    picks = []
    for sel in Gui.Selection.getSelectionEx("", 0):
        for path in sel.SubElementNames:
            if element(path).startswith("Face"):
                pick = picked_face(sel.Object, path)
                if pick not in picks:
                    picks.append(pick)
    return picks


def selected_faces():
    """[(object, "FaceN"), ...] for every selected face that can be tagged where it is
    shown (face_picks without those shown through a link), in selection order."""
    return [(obj, face) for obj, face, why in face_picks() if not why]


def selected_curve():
    """((object, [edge names]), "") for a curve pattern: selected edges of one object, or a
    whole selected sketch ([] = all its edges); (None, why) for edges shown through a link
    (face_picking.picked_curve), (None, "") if nothing fits. Read from the unresolved
    selection, as face_picks: the resolved one names the link's original, elsewhere."""
    return picked_curve([(sel.Object, list(sel.SubElementNames)) for sel in Gui.Selection.getSelectionEx("", 0)])


def selected_parts():
    """Selected objects with a solid shape (for a vibration)."""
    return [sel.Object for sel in Gui.Selection.getSelectionEx()
            if hasattr(sel.Object, "Shape") and not sel.Object.Shape.isNull() and sel.Object.Shape.Faces]
