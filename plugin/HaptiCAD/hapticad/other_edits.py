# SPDX-License-Identifier: GPL-3.0-or-later
"""What the designer did to a document outside a task panel's own objects while it was
open: properties set (in the property editor, a spreadsheet, the Python console),
objects added or deleted.

FreeCAD puts every change made while a transaction is open into it, so a panel's Cancel
(abortTransaction) takes those with it: a box lengthened while the surface panel was
open came back short. A panel keeps an OtherEdits while it is open and asks before its
Cancel takes them (``describe``). Changes made by a recompute (a part's Shape, a
sketch's solved geometry) follow what was set and are not counted; nor is Visibility,
which FreeCAD keeps out of undo. App-only."""
import FreeCAD as App

IGNORED_PROPERTIES = {"Visibility"}
# a part's shape follows its other properties (a Part primitive remakes it as a property is
# set, before any recompute): the property set is the edit
RESULT_TYPES = {"Part::PropertyPartShape"}


class OtherEdits:
    """Listens to ``doc`` from now until ``remove()``; ``in_scope(obj)`` says which
    objects are the panel's own (their changes, creation and deletion are not counted).
    Judged when asked: an object being made is set up before it can be told apart."""

    def __init__(self, doc, in_scope):
        self.doc = doc
        self.doc_name = doc.Name
        self.in_scope = in_scope
        self.changed = {}  # object Name -> [property, ...] in the order first set
        self.created = []  # object Names added since
        self.deleted = {}  # object Name -> Label, of those not in scope and not added since
        self.recomputing = 0
        App.addDocumentObserver(self)

    def remove(self):
        App.removeDocumentObserver(self)

    def forget(self):
        """Starts afresh: an Undo or a Redo took the transaction these were made in, so a
        Cancel can no longer take them (nor what the Undo itself changed)."""
        self.changed, self.created, self.deleted = {}, [], {}

    def _ours(self, obj):
        return getattr(obj, "Document", None) is not None and obj.Document.Name == self.doc_name

    # --- FreeCAD's document observer ---------------------------------------------------

    def slotBeforeRecomputeDocument(self, doc):
        if doc.Name == self.doc_name:
            self.recomputing += 1

    def slotRecomputedDocument(self, doc):
        if doc.Name == self.doc_name:
            self.recomputing = max(0, self.recomputing - 1)

    def slotChangedObject(self, obj, prop):
        if self.recomputing or prop in IGNORED_PROPERTIES or not self._ours(obj):
            return
        try:
            if obj.getTypeIdOfProperty(prop) in RESULT_TYPES:
                return
        except (AttributeError, ValueError):
            return
        props = self.changed.setdefault(obj.Name, [])
        if prop not in props:
            props.append(prop)

    def slotCreatedObject(self, obj):
        if self._ours(obj):
            self.created.append(obj.Name)

    def slotDeletedObject(self, obj):
        if not self._ours(obj):
            return
        if obj.Name in self.created:
            self.created.remove(obj.Name)
        elif not self.in_scope(obj):
            self.deleted[obj.Name] = obj.Label
        self.changed.pop(obj.Name, None)

    # --- what it saw --------------------------------------------------------------------

    def _counted(self, name):
        obj = self.doc.getObject(name)
        return obj is not None and not self.in_scope(obj)

    def describe(self):
        """"changed Box (Length, Width) and Pad (Length); added Sketch001; deleted Fillet",
        or "" when nothing outside the panel's objects was done. Objects by the labels they
        have now; the changes of an object added since are its adding."""
        changed = [(self.doc.getObject(n).Label, props) for n, props in self.changed.items()
                   if n not in self.created and self._counted(n)]
        created = [self.doc.getObject(n).Label for n in self.created if self._counted(n)]
        parts = []
        if changed:
            parts.append("changed " + " and ".join(f"{label} ({', '.join(props)})" for label, props in changed))
        if created:
            parts.append("added " + ", ".join(created))
        if self.deleted:
            parts.append("deleted " + ", ".join(self.deleted.values()))
        return "; ".join(parts)

    def any(self):
        return bool(self.describe())
