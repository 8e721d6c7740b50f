# SPDX-License-Identifier: GPL-3.0-or-later
"""Keeps overlays on their faces when parts move.

A surface's overlay is drawn in global coordinates. Moving a tagged part, or the
App::Part or Body holding it, changes where its faces are without changing anything
of the surface itself, so this document observer redraws the overlays of the surfaces
whose parts (or their containers) changed placement or shape; and of those whose
Curve pattern follows a sketch or edge that was edited or moved. A part (or its
container) hidden or shown again takes its faces' overlay, and their legend entries, with
it. Installed once, by the first surface view provider.
"""
import FreeCAD as App

WATCHED = frozenset(("Placement", "Shape", "Visibility"))
_OBSERVER = []


class _Observer:
    def slotChangedObject(self, obj, prop):
        if prop not in WATCHED:
            return
        try:
            doc = obj.Document
        except Exception:
            return
        if doc.Restoring:
            return
        from ..surface_object import is_haptic_surface, moves_with, pattern_curve_object, reference_pairs

        for surface in doc.Objects:
            if not is_haptic_surface(surface) or surface is obj:
                continue
            # its parts, and the curve its stripes follow (a sketch edited or moved)
            placing = {o for o, _ in reference_pairs(surface)} | {pattern_curve_object(surface)}
            if moves_with(obj, placing):
                proxy = getattr(surface.ViewObject, "Proxy", None) if surface.ViewObject else None
                if proxy is not None and hasattr(proxy, "refresh"):
                    proxy.refresh()


    def slotDeletedObject(self, obj):
        # a surface gone by an undo or a cancelled creation (no view provider onDelete
        # then): the legend must not go on explaining it
        from ..surface_object import is_haptic_surface

        try:
            doc = obj.Document
            ours = is_haptic_surface(obj)
        except Exception:
            return
        if ours and not doc.Restoring:
            from . import overlay_legend

            overlay_legend.refresh(doc, exclude=obj)


def install():
    if not _OBSERVER:
        _OBSERVER.append(_Observer())
        App.addDocumentObserver(_OBSERVER[0])
