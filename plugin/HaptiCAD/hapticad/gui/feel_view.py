# SPDX-License-Identifier: GPL-3.0-or-later
"""What a Feel session draws in the 3D view, and how the mouse steers the probe.

Drawn in its own Coin node added to the view (unpickable, so picking still sees the
part): the probe (where the device, or the simulated hand, is) as a blue sphere, the
proxy (the point held on the surface) as a green sphere, and the force on the hand as
a red arrow from the proxy. With the simulated probe, moving the mouse over a part aims
the hand at the point under the cursor, pressed ``depth_mm`` into the surface; the wheel
sets that depth (and is not passed on to zoom while the session runs).
"""
import numpy as np

import FreeCAD as App

MM = 1e-3
ARROW_MM_PER_N = 8.0  # force arrow length per newton
LIFT_MM = 5.0  # where the hand goes when the cursor leaves the part: lifted off along the normal
HOVER_MM = 5.0  # coming to a face it is not on: this far off it, along its normal, first
CLEAR_MM = 10.0  # above the parts' top, where a hand crosses to a face that looks up
ARRIVED_MM = 1.0  # near enough the hover point to come down
APPROACH_TIMEOUT_S = 1.0  # comes down then anyway (a hand held back by something)
# How the hand comes down from there: a target stepped onto the face landed at 1.45 N
# on ABS pressed to 0.40 N, a knock on every first touch. At 150 mm/s to 4 mm above the
# face, then slowing as it nears (the distance left / 0.1 s, 30 to 10 mm/s), it lands
# at 1.16x / 1.10x / 1.03x what it then presses at 1 / 1.5 / 3 mm, in 0.4-0.6 s from
# 10 mm above (the hand lags a fast target by some 3 mm: slow down before the face)
DESCENT_FAST_MM_S = 150.0
DESCENT_SLOW_ZONE_MM = 4.0
DESCENT_TIME_S = 0.1
DESCENT_MM_S = (10.0, 30.0)
STEP_MM = 2.0  # a face under the cursor this much (beyond the press) above the hand: a step up, lifted over


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
        graph = self.view.getSceneGraph()
        if graph.findChild(self.root) >= 0:
            graph.removeChild(self.root)


class MouseSteering:
    """Turns mouse moves and the wheel in the 3D view into the simulated hand's target.

    On the part, the hand presses ``depth_mm`` into the face under the cursor; off it,
    it lifts LIFT_MM off the face it was on. Coming to the part (the session's first
    touch, the cursor back on it, or a face that stands above the hand: a step up), the
    hand does not go straight for the face, which would drag it through whatever stands
    between (a grip's side wall caught it and held it there): it goes to a point
    HOVER_MM off the face along its normal (for a face that looks up, at least CLEAR_MM
    above the parts' top), and once ``tool_w()`` says it is there comes down, slowing
    over the last DESCENT_SLOW_ZONE_MM, as a hand lowers a finger, not in one step
    that lands with a knock."""

    def __init__(self, view, doc_scene, set_target, depth_changed, tool_w=None, top_mm=None):
        from pivy import coin
        from PySide2 import QtCore

        self.view = view
        self.doc_scene = doc_scene
        self.set_target = set_target  # callable(target_w in m)
        self.depth_changed = depth_changed  # callable(step), from the wheel
        self.tool_w = tool_w  # callable() -> the tool's position in m, or None: no approach
        self.top_mm = top_mm  # the parts' highest z, mm
        self.depth_mm = 1.0
        self.last_surface = None  # (point_mm, normal) under the cursor last
        self.landed = False  # the hand is on the part (not lifted, not coming down)
        self.approach = None  # (hover_w, press_w) while coming to the part
        self.descent_left_mm = None  # while coming down from the hover point: how far is left
        self._approach_time = 0.0
        self._approach_timer = QtCore.QTimer()
        self._approach_timer.setInterval(20)
        self._approach_timer.timeout.connect(self._check_approach)
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

    def _on_move(self, event_callback):
        event = event_callback.getEvent()
        x, y = event.getPosition().getValue()
        self.moves += 1
        self.aim_at_pixel(int(x), int(y))

    def aim_again(self):
        """Aims at the face it was on with the current depth (the wheel or the slider
        changed it): felt at once, not at the next mouse move; coming down, it lands at
        the new depth."""
        if self.last_surface is None:
            return
        point_mm, normal = self.last_surface
        press_w = (point_mm - self.depth_mm * normal) * MM
        if self.landed:
            self.set_target(press_w)
        elif self.approach is not None:
            self.approach = (self.approach[0], press_w)

    def aim_at_pixel(self, x, y):
        """Aims the hand at the part under view pixel (x, y) (Coin's: y up)."""
        info = self.view.getObjectInfo((x, y))
        on_part = bool(info) and "x" in info
        if on_part:
            point_mm = np.array([info["x"], info["y"], info["z"]], float)
            sample = self.doc_scene.scene.calc_closest_point(point_mm * MM)
            self.last_surface = (point_mm, np.asarray(sample.normal_w, float))
        if self.last_surface is None:
            return
        point_mm, normal = self.last_surface
        if not on_part:
            self.landed = False
            self.approach = self.descent_left_mm = None
            self.set_target((point_mm + LIFT_MM * normal) * MM)
            return
        press_w = (point_mm - self.depth_mm * normal) * MM
        if self.landed and self.tool_w is not None and self._below(point_mm, normal):
            self.landed = False  # a step up under the cursor: over it, as a hand would, not into its wall
        if self.landed or self.tool_w is None:
            self.set_target(press_w)
            return
        hover_mm = point_mm + HOVER_MM * normal
        if self.top_mm is not None and normal[2] > 0.5:
            hover_mm[2] = max(hover_mm[2], self.top_mm + CLEAR_MM)
        if self.approach is None:
            self._approach_time = 0.0
            self._approach_timer.start()
        self.approach = (hover_mm * MM, press_w)
        self.set_target(self._descending_target())

    def _below(self, point_mm, normal):
        """True when the hand is under the face at ``point_mm`` by more than it presses."""
        return float(np.dot(self.tool_w() / MM - point_mm, normal)) < -(self.depth_mm + STEP_MM)

    def _descending_target(self):
        """The approach's target: the hover point, or on the way down from it to the press
        point (the cursor moved while coming down: as far down over the new point)."""
        hover_w, press_w = self.approach
        if self.descent_left_mm is None:
            return hover_w
        way = hover_w - press_w
        length_mm = float(np.linalg.norm(way)) / MM
        return press_w + way * min(1.0, self.descent_left_mm / length_mm) if length_mm > 0 else press_w

    def _check_approach(self):
        """While coming to the part: once the hand hovers over it, down onto the face."""
        if self.approach is None:
            self._approach_timer.stop()
            return
        step_s = self._approach_timer.interval() / 1000.0
        if self.descent_left_mm is None:
            hover_w, press_w = self.approach
            self._approach_time += step_s
            there = np.linalg.norm(self.tool_w() - hover_w) < ARRIVED_MM * MM
            if there or self._approach_time >= APPROACH_TIMEOUT_S:
                self.descent_left_mm = float(np.linalg.norm(hover_w - press_w)) / MM
            return
        above_mm = self.descent_left_mm - self.depth_mm  # the face is depth_mm up the way
        if above_mm > DESCENT_SLOW_ZONE_MM:
            self.descent_left_mm = max(self.depth_mm + DESCENT_SLOW_ZONE_MM,
                                       self.descent_left_mm - DESCENT_FAST_MM_S * step_s)
        else:
            self.descent_left_mm -= float(np.clip(above_mm / DESCENT_TIME_S, *DESCENT_MM_S)) * step_s
        if self.descent_left_mm > 0:
            self.set_target(self._descending_target())
            return
        press_w = self.approach[1]
        self._approach_timer.stop()
        self.approach = self.descent_left_mm = None
        self.landed = True
        self.set_target(press_w)

    def halt(self):
        """No more aiming: a hand coming down stops where it is."""
        self._approach_timer.stop()
        self.approach = self.descent_left_mm = None

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
