# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of HapticSurface objects: the overlay, the tree icon, editing.

The overlay is this view provider's own Coin scene graph, drawn over the user's part
(pulled toward the camera with a polygon offset, unpickable so clicks still reach the
part): each tagged face in its material or roughness colour, with black and white
stripes along the direction of lowest friction (hapticad.overlay computes them). The
part keeps its own colours. Broken references show in the tree icon. Double-click
opens the task panel.
"""
from .. import icon, overlay, preferences
from ..face_references import BROKEN
from ..proxy_state import NoState
from .view_provider_base import EditsInTaskPanel

# stripe texture: black, face colour, white, face colour (one stripe pair per period)
_STRIPE_TEXELS = 4


class ViewProviderHapticSurface(EditsInTaskPanel, NoState):
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        from pivy import coin

        self.Object = vobj.Object
        self.ViewObject = vobj
        self._root = coin.SoSeparator()
        self._switch = coin.SoSwitch()
        self._faces = coin.SoSeparator()
        offset = coin.SoPolygonOffset()  # in front of the part's own faces
        offset.factor = -2.0
        offset.units = -4.0
        pick = coin.SoPickStyle()
        pick.style = coin.SoPickStyle.UNPICKABLE  # clicks go to the part's faces
        hints = coin.SoShapeHints()
        hints.vertexOrdering = coin.SoShapeHints.UNKNOWN_ORDERING  # lit from both sides
        self._overlay = coin.SoSeparator()
        for node in (pick, offset, hints, self._faces):
            self._overlay.addChild(node)
        self._switch.addChild(self._overlay)
        self._switch.whichChild = coin.SO_SWITCH_ALL
        self._root.addChild(self._switch)
        self._highlight = coin.SoSeparator()  # outlines of the faces picked in the task panel
        self._root.addChild(self._highlight)
        self._highlighted = []
        vobj.addDisplayMode(self._root, "Overlay")
        from . import overlay_observer

        overlay_observer.install()  # redraws when a tagged part (or its container) moves
        self.refresh()

    def getDisplayModes(self, vobj):
        return ["Overlay"]

    def getDefaultDisplayMode(self):
        return "Overlay"

    def setDisplayMode(self, mode):
        return mode

    def getIcon(self):
        obj = getattr(self, "Object", None)
        if obj is not None and self.has_broken_references():
            return icon("HaptiCAD_SurfaceBroken")
        return icon("HaptiCAD_SurfaceObject")

    def has_broken_references(self):
        from ..surface_object import reference_status

        try:
            return any(s == BROKEN for _, _, s in reference_status(self.Object))
        except Exception:
            return False

    def updateData(self, obj, prop):
        if prop in ("Proxy", "HaptiCADType", "Label"):
            return
        if prop == "ReferenceState":
            self.ViewObject.signalChangeIcon()
        self.refresh()

    def onChanged(self, vobj, prop):
        if prop == "Visibility":
            from . import overlay_legend

            overlay_legend.refresh(vobj.Object.Document)

    # --- the overlay ---------------------------------------------------------------------

    def refresh(self):
        """Rebuilds the overlay from the object's current faces and values."""
        if not hasattr(self, "_faces"):
            return
        obj = self.Object
        if obj.Document.Restoring or "Restore" in obj.State:
            # the referenced parts may not be there yet: draw once the document is open
            if not getattr(self, "_refresh_pending", False):
                from PySide2 import QtCore

                self._refresh_pending = True
                QtCore.QTimer.singleShot(0, self._deferred_refresh)
            return
        from ..surface_object import is_haptic_surface

        if not is_haptic_surface(obj):  # a vibration saved with this class by version 0.1
            return
        from pivy import coin

        prefs = preferences.load()
        self._switch.whichChild = coin.SO_SWITCH_ALL if prefs.overlay_visible else coin.SO_SWITCH_NONE
        self._faces.removeAllChildren()
        for face in overlay.overlay_faces(obj, prefs.overlay_colour_by):
            self._faces.addChild(_face_node(face))
        from . import overlay_legend

        overlay_legend.refresh(obj.Document)

    def set_highlight(self, names):
        """Outlines faces ("Object.FaceN") on top of everything, for the task panel."""
        from pivy import coin

        self._highlighted = list(names)
        self._highlight.removeAllChildren()
        if not names:
            return
        annotation = coin.SoAnnotation()
        style = coin.SoDrawStyle()
        style.lineWidth = 4
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        colour = coin.SoBaseColor()
        colour.rgb.setValue(1.0, 0.85, 0.0)
        pick = coin.SoPickStyle()
        pick.style = coin.SoPickStyle.UNPICKABLE
        for node in (pick, style, light, colour):
            annotation.addChild(node)
        for name in names:
            obj_name, sub = name.split(".", 1)
            part = self.Object.Document.getObject(obj_name)
            if part is None:
                continue
            for points in overlay.face_outline(part, sub):
                coords = coin.SoCoordinate3()
                coords.point.setValues(0, len(points), points)
                lines = coin.SoLineSet()
                lines.numVertices.setValue(len(points))
                annotation.addChild(coords)
                annotation.addChild(lines)
        self._highlight.addChild(annotation)

    def _deferred_refresh(self):
        self._refresh_pending = False
        try:
            self.Object.Name
        except Exception:  # closed before the document finished opening
            return
        self.refresh()

    def overlay_face_count(self):
        return self._faces.getNumChildren() if hasattr(self, "_faces") else 0

    # --- editing ----------------------------------------------------------------------

    def task_panel(self, obj):
        from .task_panel_surface import SurfaceTaskPanel

        return SurfaceTaskPanel(obj)

    def setupContextMenu(self, vobj, menu):
        from PySide2 import QtGui

        action = menu.addAction(QtGui.QIcon(icon("HaptiCAD_Surface")), "Edit haptic surface")
        action.triggered.connect(lambda: vobj.Document.setEdit(vobj.Object.Name, 0))

    def onDelete(self, vobj, subelements):
        from . import overlay_legend

        overlay_legend.refresh(vobj.Object.Document, exclude=vobj.Object)
        return True



def _face_node(face):
    """Coin nodes of one OverlayFace."""
    from pivy import coin

    node = coin.SoSeparator()
    material = coin.SoMaterial()
    if face.stripes is None:
        material.diffuseColor.setValue(*face.colour)
    else:
        material.diffuseColor.setValue(1.0, 1.0, 1.0)  # the texture carries the colour
        # some light of its own, so shading never turns the white stripes grey
        material.emissiveColor.setValue(0.35, 0.35, 0.35)
        node.addChild(_stripe_texture(face.colour))
    material.ambientColor.setValue(*(0.3 * c for c in face.colour))
    material.specularColor.setValue(0.05, 0.05, 0.05)
    node.addChild(material)
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, len(face.points), face.points.tolist())
    node.addChild(coords)
    normals = coin.SoNormal()
    normals.vector.setValues(0, len(face.normals), face.normals.tolist())
    node.addChild(normals)
    binding = coin.SoNormalBinding()
    binding.value = coin.SoNormalBinding.PER_VERTEX_INDEXED
    node.addChild(binding)
    if face.stripes is not None:
        tex = coin.SoTextureCoordinate2()
        tex.point.setValues(0, len(face.stripes), [(float(s), 0.5) for s in face.stripes])
        node.addChild(tex)
        tex_binding = coin.SoTextureCoordinateBinding()
        tex_binding.value = coin.SoTextureCoordinateBinding.PER_VERTEX_INDEXED
        node.addChild(tex_binding)
    faces = coin.SoIndexedFaceSet()
    index = []
    for a, b, c in face.triangles.tolist():
        index.extend((a, b, c, -1))
    faces.coordIndex.setValues(0, len(index), index)
    faces.normalIndex.setValues(0, len(index), index)
    if face.stripes is not None:
        faces.textureCoordIndex.setValues(0, len(index), index)
    node.addChild(faces)
    return node


def _stripe_texture(colour):
    """A group: crisp (nearest) repeating texture black | colour | white | colour."""
    from pivy import coin

    group = coin.SoGroup()
    complexity = coin.SoComplexity()
    complexity.textureQuality = 0.01  # nearest-texel sampling: sharp stripe edges
    group.addChild(complexity)
    texture = coin.SoTexture2()
    c = bytes(int(round(255 * v)) for v in colour)
    row = b"\x00\x00\x00" + c + b"\xff\xff\xff" + c
    texture.image.setValue(coin.SbVec2s(_STRIPE_TEXELS, 2), 3, row + row)
    texture.wrapS = coin.SoTexture2.REPEAT
    texture.wrapT = coin.SoTexture2.REPEAT
    texture.model = coin.SoTexture2.MODULATE
    group.addChild(texture)
    return group
