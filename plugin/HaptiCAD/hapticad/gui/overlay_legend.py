# SPDX-License-Identifier: GPL-3.0-or-later
"""The overlay's legend: colour swatches and labels in the top-left of each 3D view.

One legend per document, drawn in screen space (its own orthographic camera, on top
of everything, unpickable, outside the view's bounding box so "fit all" ignores it),
rebuilt whenever a surface changes. Hidden with the overlay.

Laid out in pixels, as its text is: the camera's units are kept at one pixel at every
render (the view can be resized). Laid out in fractions of the view, the swatches drifted
off their labels: in a 400 pixel high view each sat a row below its own.
"""
import FreeCAD as App

from .. import overlay, preferences

NODE_NAME = "HaptiCAD_Legend"
FONT_PX = 14
ROW_PX = 20  # baseline to baseline
SWATCH_PX = 12
CHAR_PX = 10  # the width of a character of the 14 px font, measured on screenshots
LEFT_PX, TOP_PX = 10, 10  # the first row's top, from the view's top-left corner
_FITTERS = {}  # the render callbacks' Python functions, kept alive with their legend


def _views(doc):
    import FreeCADGui as Gui

    gui_doc = Gui.getDocument(doc.Name) if doc.Name in App.listDocuments() else None
    if gui_doc is None:
        return []
    try:
        return gui_doc.mdiViewsOfType("Gui::View3DInventor")
    except Exception:
        return [gui_doc.ActiveView] if gui_doc.ActiveView else []


def _new_root():
    """(node to insert in a view, separator to fill). The scene graph owns the nodes."""
    from pivy import coin

    kind = coin.SoType.fromName("SoSkipBoundingGroup")  # FreeCAD's: ignored by "fit all"
    if kind.isBad():
        root = coin.SoSeparator()
        inner = root
    else:
        root = coin.cast(kind.createInstance(), "SoGroup")
        inner = coin.SoSeparator()
        root.addChild(inner)
    root.setName(NODE_NAME)
    return root, inner


def _remove_legends(graph):
    for i in reversed(range(graph.getNumChildren())):
        if graph.getChild(i).getName().getString() == NODE_NAME:
            graph.removeChild(i)


def shown_labels(doc):
    """The labels the legend shows now in ``doc``'s first 3D view ([] with none)."""
    from pivy import coin

    for view in _views(doc)[:1]:
        graph = view.getSceneGraph()
        for i in range(graph.getNumChildren()):
            if graph.getChild(i).getName().getString() != NODE_NAME:
                continue
            search = coin.SoSearchAction()
            search.setType(coin.SoText2.getClassTypeId())
            search.setInterest(coin.SoSearchAction.ALL)
            search.apply(graph.getChild(i))
            paths = search.getPaths()
            return [paths[k].getTail().string.getValues()[0] for k in range(paths.getLength())]
    return []


def visible_surfaces(doc, exclude=None):
    from ..surface_object import surfaces_of

    return [s for s in surfaces_of(doc)
            if s is not exclude and s.ViewObject is not None and s.ViewObject.Visibility]


def entries(doc, exclude=None):
    prefs = preferences.load()
    if not prefs.overlay_visible:
        return []
    return overlay.legend_entries(visible_surfaces(doc, exclude), prefs.overlay_colour_by)


def refresh(doc, exclude=None):
    """Rebuilds the legend of ``doc`` and shows it in each of its 3D views (or removes it
    when there is nothing to explain)."""
    from pivy import coin

    if doc.Restoring:
        # a surface restored so far may lack its later properties (a part's Visibility
        # comes back before them): each surface's overlay draws the legend once it is open
        return []
    rows = entries(doc, exclude)
    for view in _views(doc):
        _remove_legends(view.getSceneGraph())
    if not rows:
        return []
    root, content = _new_root()
    annotation = coin.SoAnnotation()  # drawn last, without depth test
    content.addChild(annotation)
    fit, camera = _pixel_camera()
    _FITTERS[doc.Name] = fit
    pick = coin.SoPickStyle()
    pick.style = coin.SoPickStyle.UNPICKABLE
    light = coin.SoLightModel()
    light.model = coin.SoLightModel.BASE_COLOR
    font = coin.SoFont()
    font.size = FONT_PX
    for node in (fit, camera, pick, light, font):
        annotation.addChild(node)
    # a white card under it: black text is unreadable on FreeCAD's dark blue background
    width = SWATCH_PX + 6 + CHAR_PX * max(len(label) for _, label in rows) + 8
    annotation.addChild(_quad(LEFT_PX - 4, -(TOP_PX - 4), LEFT_PX + width, -(TOP_PX + len(rows) * ROW_PX),
                              (1.0, 1.0, 1.0)))
    for i, (colour, label) in enumerate(rows):
        top = -(TOP_PX + i * ROW_PX)  # y grows up: rows go down from the top edge
        annotation.addChild(_swatch(colour, LEFT_PX, top))
        # the text's baseline level with the swatch's bottom, as a row of text sits on it
        annotation.addChild(_label(label, LEFT_PX + SWATCH_PX + 6, top - SWATCH_PX))
    for view in _views(doc):
        view.getSceneGraph().addChild(root)
    return rows


def _pixel_camera():
    """(callback node, camera): the camera's units are the view's pixels, x from the left
    edge, y up from the top edge; the callback sets it so at each render, before the
    camera is used, and only when the view's size changed (setting a field redraws)."""
    from pivy import coin

    camera = coin.SoOrthographicCamera()
    camera.viewportMapping = coin.SoCamera.LEAVE_ALONE
    camera.nearDistance = 1.0
    camera.farDistance = 10.0

    def fit(_data, action):
        if not action.isOfType(coin.SoGLRenderAction.getClassTypeId()):
            return
        region = coin.cast(action, "SoGLRenderAction").getViewportRegion()
        width, height = region.getViewportSizePixels().getValue()
        if (camera.height.getValue(), camera.position.getValue()[0]) != (height, width / 2):
            camera.height = height
            camera.aspectRatio = width / height  # left alone, the view stretches x to its width
            camera.position.setValue(width / 2, -height / 2, 5)

    node = coin.SoCallback()
    node.setCallback(fit)
    return node, camera


def _quad(x0, y0, x1, y1, colour):
    from pivy import coin

    sep = coin.SoSeparator()
    mat = coin.SoBaseColor()
    mat.rgb.setValue(*colour)
    coords = coin.SoCoordinate3()
    coords.point.setValues(0, 4, [(x0, y0, 0), (x1, y0, 0), (x1, y1, 0), (x0, y1, 0)])
    faces = coin.SoFaceSet()
    faces.numVertices.setValue(4)
    for node in (mat, coords, faces):
        sep.addChild(node)
    return sep


def _swatch(colour, x, top):
    """A filled square, its top-left corner at (x, top); for the stripes key, black and
    white bars."""
    from pivy import coin

    sep = coin.SoSeparator()
    w = h = SWATCH_PX
    if colour is None:
        for k in range(4):
            sep.addChild(_quad(x + k * w / 4, top - h, x + (k + 1) * w / 4, top,
                               (0.0, 0.0, 0.0) if k % 2 == 0 else (1.0, 1.0, 1.0)))
    else:
        sep.addChild(_quad(x, top - h, x + w, top, colour))
    return sep


def _label(text, x, y):
    from pivy import coin

    sep = coin.SoSeparator()
    colour = coin.SoBaseColor()
    colour.rgb.setValue(0.0, 0.0, 0.0)
    move = coin.SoTranslation()
    move.translation.setValue(x, y, 0)
    label = coin.SoText2()
    label.string.setValue(text)
    for node in (colour, move, label):
        sep.addChild(node)
    return sep
