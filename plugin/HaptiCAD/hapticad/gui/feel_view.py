# SPDX-License-Identifier: GPL-3.0-or-later
"""What a Feel session draws in the 3D view, and how the mouse steers the probe.

Drawn in its own Coin node added to the view (unpickable, so picking still sees the
part): the probe (where the device, or the simulated hand, is) as a blue sphere, the
proxy (the point held on the surface) as a green sphere, and the force on the hand as
an amber arrow from the proxy. With the simulated probe, moving the mouse over a part aims
the hand at the point under the cursor, pressed ``depth_mm`` into the surface (how it
comes there: hand_approach.py); the wheel sets that depth (and is not passed on to zoom
while the session runs). A hidden part is felt but not picked by the view: where the
view's pick finds nothing, the line of sight through the cursor is cast against the
felt surface (hand_approach.cast_ray), so the mouse reaches a hidden part too. A scene
swapped in (a part edited or moved) is picked again under the cursor: a proxy it left on
the far side of the part is let go of, and the hand re-lands (HandApproach.scene_changed).
"""
import numpy as np

import FreeCAD as App

from ..feel_session import scene_box_m
from ..hand_approach import MM, HandApproach, cast_ray

ARROW_MM_PER_N = 8.0  # force arrow length per newton


class FeelView:
    def __init__(self, view, probe_radius_mm):
        from pivy import coin

        self.view = view
        self.root = coin.SoSeparator()
        self.root.setName("HaptiCAD_Feel")
        # on top of the part: the probe is inside it whenever it presses
        on_top = coin.SoAnnotation()
        self.root.addChild(on_top)
        pick = coin.SoPickStyle()
        pick.style = coin.SoPickStyle.UNPICKABLE
        on_top.addChild(pick)
        self.probe = self._sphere((0.15, 0.4, 0.9), probe_radius_mm)
        self.proxy = self._sphere((0.1, 0.75, 0.2), probe_radius_mm * 0.8)
        on_top.addChild(self.probe[0])
        on_top.addChild(self.proxy[0])
        arrow = coin.SoSeparator()
        colour = coin.SoBaseColor()
        colour.rgb.setValue(1.0, 0.75, 0.0)
        style = coin.SoDrawStyle()
        style.lineWidth = 4
        self.arrow_coords = coin.SoCoordinate3()
        self.arrow_coords.point.setValues(0, 5, [(0, 0, 0)] * 5)
        lines = coin.SoLineSet()
        lines.numVertices.setValues(0, 3, [2, 2, 1])
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR
        for node in (light, colour, style, self.arrow_coords, lines):
            arrow.addChild(node)
        on_top.addChild(arrow)
        self.radius_mm = probe_radius_mm
        view.getSceneGraph().addChild(self.root)

    @staticmethod
    def _sphere(rgb, radius):
        from pivy import coin

        sep = coin.SoSeparator()
        move = coin.SoTranslation()
        material = coin.SoMaterial()
        material.diffuseColor.setValue(*rgb)
        material.emissiveColor.setValue(*(0.3 * c for c in rgb))
        sphere = coin.SoSphere()
        sphere.radius = radius
        for node in (move, material, sphere):
            sep.addChild(node)
        return sep, move

    def show(self, device_m, proxy_m, force_n):
        """Moves the probe, proxy and arrow (world metres and newtons)."""
        device_mm = np.asarray(device_m, float) / MM
        proxy_mm = np.asarray(proxy_m, float) / MM
        self.probe[1].translation.setValue(*device_mm)
        self.proxy[1].translation.setValue(*proxy_mm)
        force = np.asarray(force_n, float)
        tip = proxy_mm + force * ARROW_MM_PER_N
        magnitude = np.linalg.norm(force)
        if magnitude > 1e-6:
            back = -force / magnitude * min(2.0 * self.radius_mm, 0.3 * magnitude * ARROW_MM_PER_N)
            side = np.cross(force / magnitude, [0, 0, 1.0])
            if np.linalg.norm(side) < 1e-6:
                side = np.cross(force / magnitude, [1.0, 0, 0])
            side = side / np.linalg.norm(side) * 0.5 * np.linalg.norm(back)
            head = [tip + back + side, tip, tip + back - side]
        else:
            head = [tip, tip, tip]
        points = [proxy_mm, tip, head[0], head[1], head[2]]
        self.arrow_coords.point.setValues(0, 5, [tuple(map(float, p)) for p in points])

    def remove(self):
        try:
            graph = self.view.getSceneGraph()
        except RuntimeError:  # the view was closed (the document still open in another)
            return  # its scene graph, with the probe's nodes, went with it
        if graph.findChild(self.root) >= 0:
            graph.removeChild(self.root)


class MouseSteering:
    """Turns mouse moves and the wheel in the 3D view into the simulated hand's target:
    the face under the cursor goes to a HandApproach (hand_approach.py says where the
    hand goes and how it comes to the part), which a timer ticks every TICK_MS."""

    TICK_MS = 20

    def __init__(self, view, doc_scene, set_target, depth_changed, tool_w=None, proxy_w=None, top_mm=None,
                 clutch=None):
        from pivy import coin
        from PySide2 import QtCore

        self.view = view
        self.doc_scene = doc_scene
        self.depth_changed = depth_changed  # callable(step), from the wheel
        self.hand = HandApproach(set_target, tool_w, proxy_w, top_mm, clutch)
        self.pixel = None  # the view pixel the mouse was at last (Coin's: y up)
        self._timer = QtCore.QTimer()
        self._timer.setInterval(self.TICK_MS)
        self._timer.timeout.connect(lambda: self.hand.step(self.TICK_MS / 1000.0))
        if tool_w is not None:
            self._timer.start()
        self.moves = 0
        self._move_type = coin.SoLocation2Event.getClassTypeId()
        self._move_callback = view.addEventCallbackPivy(self._move_type, self._on_move)

        class WheelFilter(QtCore.QObject):
            # the wheel sets the pressing depth, and does not zoom, while the session runs
            def eventFilter(filter_self, obj, event):
                if event.type() == QtCore.QEvent.Wheel:
                    delta = event.angleDelta().y()  # 120 per notch; touchpads send less
                    if delta:
                        self.depth_changed(int(round(delta / 120)) or (1 if delta > 0 else -1))
                    return True
                return False

        self._wheel_filter = WheelFilter()
        self._viewport = view.graphicsView().viewport() if hasattr(view, "graphicsView") else None
        if self._viewport is not None:
            self._viewport.installEventFilter(self._wheel_filter)

    @property
    def depth_mm(self):
        return self.hand.depth_mm

    @depth_mm.setter
    def depth_mm(self, value):
        self.hand.depth_mm = value

    def _on_move(self, event_callback):
        event = event_callback.getEvent()
        x, y = event.getPosition().getValue()
        self.moves += 1
        self.aim_at_pixel(int(x), int(y))

    def aim_again(self):
        self.hand.aim_again()

    def aim_at_pixel(self, x, y):
        """Aims the hand at the part under view pixel (x, y) (Coin's: y up)."""
        self.pixel = (x, y)
        self.hand.aim(self.surface_at(x, y))

    def surface_at(self, x, y):
        """(point_mm, normal) of the part under view pixel (x, y) (Coin's: y up), or None."""
        info = self.view.getObjectInfo((x, y))
        if info and "x" in info:
            point_mm = np.array([info["x"], info["y"], info["z"]], float)
        else:  # nothing drawn there: a hidden part may be, and it is felt
            point_mm = self.hidden_point(x, y)
        if point_mm is None:
            return None
        sample = self.doc_scene.scene.calc_closest_point(point_mm * MM)
        return point_mm, np.asarray(sample.normal_w, float)

    def scene_changed(self, doc_scene):
        """A new scene swapped into the loop (the parts changed shape or moved): aimed from
        now on, and the hand told what the cursor is over now (HandApproach.scene_changed:
        a hand whose proxy the swap left on the far side of the part re-lands)."""
        self.doc_scene = doc_scene
        top_mm = scene_box_m(doc_scene)[1][2] / MM
        if self.pixel is None:  # the mouse has not steered yet
            self.hand.top_mm = top_mm
            return
        self.hand.scene_changed(self.surface_at(*self.pixel), top_mm)

    def hidden_point(self, x, y):
        """Where the line of sight through view pixel (x, y) (Coin's: y up) first meets the
        felt surface (mm), or None: the scene's parts, drawn or not."""
        box = None
        for shape in self.doc_scene.shapes.values():
            if box is None:
                box = App.BoundBox(shape.BoundBox)
            else:
                box.add(shape.BoundBox)
        if box is None or not box.isValid():
            return None
        on_plane = np.array(tuple(self.view.getPoint(x, y)), float)  # on the focal plane
        if self.view.getCameraType() == "Perspective":
            eye = np.array(self.view.getCameraNode().position.getValue().getValue(), float)
            direction = on_plane - eye
            behind_eye = -float(np.linalg.norm(direction))
        else:
            direction = np.array(tuple(self.view.getViewDirection()), float)
            behind_eye = -np.inf
        direction /= np.linalg.norm(direction)
        centre = np.array([box.Center.x, box.Center.y, box.Center.z])
        radius = 0.5 * box.DiagonalLength + 1.0
        # from in front of the parts' bounding sphere (never behind the eye) to behind it
        along = float(np.dot(centre - on_plane, direction))
        start = max(along - radius, behind_eye)
        scene = self.doc_scene.scene

        def distance_mm(p):
            return scene.calc_closest_point(p * MM).distance_m / MM

        return cast_ray(distance_mm, on_plane + start * direction, direction, along + radius - start)

    def halt(self):
        """No more aiming: a hand on its way stops where it is."""
        self._timer.stop()
        self.hand.halt()

    def remove(self):
        self.halt()
        try:
            self.view.removeEventCallbackPivy(self._move_type, self._move_callback)
        except Exception:  # the view is already gone
            App.Console.PrintLog("HaptiCAD: Feel mouse callback outlived its view\n")
        if self._viewport is not None:
            try:
                self._viewport.removeEventFilter(self._wheel_filter)
            except RuntimeError:
                pass
