# SPDX-License-Identifier: GPL-3.0-or-later
"""Which part's face a click in the 3D view picked, or why it cannot be tagged.

A click names a path from a top-level object of the view's document down to the face:
"Body.Pad.Face6", "Assembly.Body.Pad.Face6", "KnobLink.Pad.Face6". FreeCAD's resolved
selection keeps only the deepest object, which through an App::Link, a link array or a
Draft array made with links is the original: shown elsewhere, perhaps in another
document. A surface tags a part's own faces, felt where the part itself is, so a path
through a link is refused, saying which link and what to tag instead."""
import os

from . import face_references

LINK_EXTENSION = "App::LinkBaseExtension"


def element(path):
    """The element a selection path ends in: "Face6" of "Body.Pad.Face6"."""
    return path.rsplit(".", 1)[-1] if path else ""


def is_link(obj):
    """Shows another object's shape where it places it: an App::Link, a link array and its
    elements, a link group, a Draft array made with links."""
    return obj.hasExtension(LINK_EXTENSION)


def linked_original(link):
    """The object ``link`` shows (what a Draft link array repeats is its Base), or None
    (a link group shows several)."""
    target = link.getLinkedObject(True)
    if target is not None and target != link:
        return target
    # a link array answers itself; its elements and a Draft link array name the original
    target = getattr(link, "LinkedObject", None) or getattr(link, "Base", None)
    return target if target != link else None


def document_file(doc):
    """How a user knows a document: its file's name, or its label when never saved."""
    return os.path.basename(doc.FileName) if doc.FileName else doc.Label


def link_refusal(link, shown=None):
    """Why a face shown through ``link`` cannot be tagged, and what to tag instead.
    ``shown``: the part whose face it is (inside the original when that is an App::Part);
    the original itself when not given."""
    original = linked_original(link) or shown
    if original is None:
        return f"{link.Label} is a link to nothing: it has no faces of its own to tag"
    shown = shown or original
    if not link.isDerivedFrom("App::Link") and not link.isDerivedFrom("App::LinkElement") \
            and hasattr(link, "Base"):
        # a Draft array made with links: a click names Base's face, not the array's
        return (f"{link.Label} is an array made with links to {original.Label}: its faces are "
                f"{original.Label}'s, shown where the array places them, and cannot be tagged there; "
                f"make the array without links (Draft's Link array option off) and tag its faces")
    what = "a link array of" if getattr(link, "ElementCount", 0) else "a link to"
    if link.isDerivedFrom("App::LinkGroup"):
        what = "a link group showing"
    where = original.Label
    if original.Document != link.Document:
        where += f" in {document_file(original.Document)}"
    instead = f"tag {shown.Label}'s faces"
    if shown != original:
        instead += f" in {original.Label}"
    if shown.Document != link.Document:  # the scene holds only its own document's parts
        instead += f" in {document_file(shown.Document)} itself, and feel them there"
    return f"{link.Label} is {what} {where}: a link's faces cannot be tagged yet; {instead}"


def picked_face(root, path):
    """(object, "FaceN", "") for the face a click picked at ``path`` under ``root`` (a
    top-level object of the view's document), as a reference holds it (a PartDesign
    feature's face as its Body's: face_references.owner_face); (None, "", why) for a face
    shown through a link, or from another document."""
    chain = root.getSubObjectList(path) if path else [root]
    face = element(path)
    if not chain or chain[-1] is None or not face.startswith("Face"):
        return None, "", f"{root.Label}.{path} is not a face"
    leaf = chain[-1]
    for obj in chain:
        if is_link(obj):
            shown = None if is_link(leaf) else face_references.owner_face(leaf, face)[0]
            return None, "", link_refusal(obj, shown)
    if leaf.Document != root.Document:  # no link in between: never seen, but never tagged
        return None, "", (f"{leaf.Label}.{face} is in {document_file(leaf.Document)}, shown by "
                          f"{root.Label}: tag it in its own document")
    obj, face = face_references.owner_face(leaf, face)
    return obj, face, ""
