# SPDX-License-Identifier: GPL-3.0-or-later
"""Which part's face (or edge, or point) a click in the 3D view picked, or why it cannot
be tagged (followed by a curve pattern, or be a circular pattern's centre).

A click names a path from a top-level object of the view's document down to the face:
"Body.Pad.Face6", "Assembly.Body.Pad.Face6", "KnobLink.Pad.Face6". FreeCAD's resolved
selection keeps only the deepest object, which through an App::Link, a link array or a
Draft array made with links is the original: shown elsewhere, perhaps in another
document. A surface tags a part's own faces, felt where the part itself is, so a path
through a link is refused, saying which link and what to tag instead; so are a curve
pattern's edges (it would follow the original's, elsewhere) and a circular pattern's centre
clicked on a link (where the link shows the original, away from the faces felt)."""
import os

from . import face_references

LINK_EXTENSION = "App::LinkBaseExtension"
# what is refused through a link: (its elements, what cannot be done to them, what to do instead)
FACES = ("faces", "tagged", "tag")
EDGES = ("edges", "followed by a curve pattern", "pick")


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


def _is_draft_link_array(link):
    return not link.isDerivedFrom("App::Link") and not link.isDerivedFrom("App::LinkElement") \
        and hasattr(link, "Base")


def _what_link_is(link, original):
    """ "BoxLink is a link to Box", "... in knob.FCStd", "LinkArr is a link array of Box"."""
    if _is_draft_link_array(link):
        return f"{link.Label} is an array made with links to {original.Label}"
    what = "a link array of" if getattr(link, "ElementCount", 0) else "a link to"
    if link.isDerivedFrom("App::LinkGroup"):
        what = "a link group showing"
    where = original.Label
    if original.Document != link.Document:
        where += f" in {document_file(original.Document)}"
    return f"{link.Label} is {what} {where}"


def link_refusal(link, shown=None, kind=FACES):
    """Why a face (``kind`` EDGES: an edge) shown through ``link`` cannot be tagged (followed
    by a curve pattern), and what to tag (pick) instead. ``shown``: the part whose face it is
    (inside the original when that is an App::Part); the original itself when not given."""
    elements, cannot, do = kind
    original = linked_original(link) or shown
    if original is None:
        return f"{link.Label} is a link to nothing: it has no {elements} of its own to {do}"
    shown = shown or original
    if _is_draft_link_array(link):
        # a Draft array made with links: a click names Base's face, not the array's
        return (f"{_what_link_is(link, original)}: its {elements} are {original.Label}'s, shown where the array "
                f"places them, and cannot be {cannot} there; make the array without links (Draft's Link array "
                f"option off) and {do} its {elements}")
    instead = f"{do} {shown.Label}'s {elements}"
    if shown != original:
        instead += f" in {original.Label}"
    if shown.Document != link.Document:  # the scene holds only its own document's parts
        instead += f" in {document_file(shown.Document)} itself, and feel them there"
    return f"{_what_link_is(link, original)}: a link's {elements} cannot be {cannot} yet; {instead}"


def _refusal(root, chain, name, shown, kind):
    """Why element ``name`` ("": the whole object) picked along ``chain`` (from ``root``
    down) cannot be taken, or "": it is shown through a link, or is of another document.
    ``shown``: the part whose element it is, for the link's refusal (None: the link's
    original)."""
    link = next((o for o in chain if is_link(o)), None)
    if link is not None:
        return link_refusal(link, shown, kind)
    leaf = chain[-1]
    if leaf.Document != root.Document:  # no link in between: never seen, but never taken
        return (f"{leaf.Label}{'.' + name if name else ''} is in {document_file(leaf.Document)}, shown by "
                f"{root.Label}: {kind[2]} it in its own document")
    return ""


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
    obj, owned = (None, "") if is_link(leaf) else face_references.owner_face(leaf, face)
    why = _refusal(root, chain, face, obj, FACES)
    return (None, "", why) if why else (obj, owned, "")


def _has_edges_only(obj):
    shape = getattr(obj, "Shape", None)
    return shape is not None and not shape.isNull() and bool(shape.Edges) and not shape.Faces


def picked_curve(selection):
    """The curve a curve pattern is to follow, from ``selection``: [(top-level object,
    [paths])] as the unresolved selection gives it ("Sketch.Edge2"; "Body.Sketch." or no
    path for a whole object). ((object, [edge names]), "") for the first object selected
    with edges, or whole with edges and no faces (a sketch: [] for all its edges), and the
    edges selected of it; (None, why) when any edge selected, or that whole object, is shown
    through a link, or is of another document: the pattern would follow the original's
    edges, elsewhere; (None, "") when nothing fits."""
    chosen, edges = None, []
    for root, paths in selection:
        for path in paths or [""]:
            name = element(path)
            if name and not name.startswith("Edge"):
                continue
            chain = root.getSubObjectList(path) if path else [root]
            if not chain or chain[-1] is None:
                continue
            leaf = chain[-1]
            if not name:  # a whole object: a link to a sketch has no shape of its own, what it shows decides
                shown = linked_original(leaf) if is_link(leaf) else leaf
                if chosen is not None or shown is None or not _has_edges_only(shown):
                    continue
            # any edge through a link: it may be meant as the same curve, shown elsewhere
            why = _refusal(root, chain, name, None if is_link(leaf) else leaf, EDGES)
            if why:
                return None, why
            if chosen is not None and leaf != chosen:
                continue  # edges of a second object: the pattern follows one
            chosen = leaf
            if name and name not in edges:
                edges.append(name)
    return ((chosen, edges), "") if chosen is not None else (None, "")


def link_on_path(root, path):
    """The first link a click at ``path`` under ``root`` went through, or None."""
    chain = root.getSubObjectList(path) if path else [root]
    return next((o for o in chain if o is not None and is_link(o)), None)


def centre_refusal(link, parts):
    """Why a point clicked on what ``link`` shows cannot be a circular pattern's centre:
    it lies where the link shows its original, not on ``parts`` (the parts whose faces
    the circles are felt on, by label)."""
    original = linked_original(link)
    if original is None:
        said, where = f"{link.Label} is a link to nothing", "the point clicked lies on it"
    else:
        said, where = _what_link_is(link, original), f"the point clicked lies where it shows {original.Label}"
    on = ", ".join(parts[:-1]) + f" or {parts[-1]}" if len(parts) > 1 else (parts[0] if parts else "the tagged part")
    return f"{said}: {where}, away from the faces the circles are felt on; click the centre on {on} itself"
