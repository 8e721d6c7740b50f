# SPDX-License-Identifier: GPL-3.0-or-later
"""A live Feel session: the one place the workbench drives the C++ servo loop live.

The servo loop runs in its own C++ thread (devices/, issue 5) with a device: the
simulated hand, whose target the GUI sets from the mouse (lock-free, any thread), or a
HID device. Python only builds the scene, starts and stops the loop, sets the hand's
target, and drains the trace for display (the GUI polls at most 60 times a second).
Nothing here runs per servo tick, and there is no servo loop in Python.

This is a thin adapter over the binding's contract, so that a change in the device
layer's Python API is absorbed here only:

    _core.SimulatedHand(limits)            .set_target(p_w)   (world m; identity mapping)
    _core.ServoLoop(device, renderer, rate_hz, trace_capacity)
        .start() .stop() .drain_trace() .stats .running .set_mapping(mapping)
    _core.list_devices()                   HID devices (optional)
    _core.open_device(path)                a HID device by path (optional)

``missing_bindings()`` says what the compiled module lacks; a session refuses to start
with that message rather than pretend. Units: SI (m, N) in the loop, mm in the
document. No GUI.
"""
from dataclasses import dataclass

import numpy as np

from . import _core, preferences

MM = 1e-3
SIMULATED = preferences.SIMULATED_DEVICE
WORKSPACE_MARGIN_M = 0.05  # around the parts: the simulated hand can lift off and come back
TRACE_SECONDS = 4.0  # ring capacity between two drains, at the servo rate


class BindingsMissing(RuntimeError):
    """The compiled module lacks what a live session needs."""


def missing_bindings():
    """Names the compiled module lacks for a live session with the simulated hand."""
    missing = [f"_core.{name}" for name in ("SimulatedHand", "ServoLoop", "ForceRenderer")
               if not hasattr(_core, name)]
    loop = getattr(_core, "ServoLoop", None)
    for method in ("start", "stop", "drain_trace"):
        if loop is not None and not hasattr(loop, method):
            missing.append(f"_core.ServoLoop.{method}")
    return missing


def missing_message():
    missing = missing_bindings()
    if not missing:
        return ""
    return ("a live Feel session needs the device layer's live servo loop, which this build of "
            f"HaptiCAD's compiled module does not have yet ({', '.join(missing)})")


@dataclass(frozen=True)
class DeviceChoice:
    label: str
    path: str  # "simulated" or what opens it again (e.g. /dev/hidraw3)

    @property
    def simulated(self):
        return self.path == SIMULATED


def device_choices():
    """The simulated probe first, then every HID device the core finds now."""
    choices = [DeviceChoice("Simulated probe (mouse)", SIMULATED)]
    lister = getattr(_core, "list_devices", None)
    if lister is not None:
        try:
            for info in lister():
                # a dict per device (issue 5's binding), or an object with the same fields
                field = info.get if isinstance(info, dict) else (lambda key, default=None: getattr(info, key, default))
                path, kind = field("path", "") or "", field("kind", "hid") or "hid"
                if path and kind != "sim":
                    choices.append(DeviceChoice(f"{field('name', 'HID device')} ({path})", path))
        except Exception:  # a device that fails to enumerate must not hide the simulated one
            pass
    return choices


def _limits_workspace(limits, low_m, high_m):
    """Sets a DeviceLimits' workspace box, whatever the binding names it."""
    for low, high in (("workspace_min_d", "workspace_max_d"), ("workspace_min_w", "workspace_max_w")):
        if hasattr(limits, low):
            setattr(limits, low, np.asarray(low_m, float))
            setattr(limits, high, np.asarray(high_m, float))
            return


def scene_box_m(doc_scene):
    """(min, max) corners of the parts in the scene, world metres."""
    low, high = np.full(3, np.inf), np.full(3, -np.inf)
    for shape in doc_scene.shapes.values():
        box = shape.BoundBox
        low = np.minimum(low, [box.XMin, box.YMin, box.ZMin])
        high = np.maximum(high, [box.XMax, box.YMax, box.ZMax])
    return low * MM, high * MM


class LiveSession:
    """One Feel session on a document scene. Raises BindingsMissing, or RuntimeError /
    ValueError with the device layer's message when the device cannot be opened."""

    def __init__(self, doc_scene, device=SIMULATED, prefs=None):
        message = missing_message()
        if message:
            raise BindingsMissing(message)
        prefs = prefs or preferences.load()
        self.doc_scene = doc_scene
        self.simulated = device == SIMULATED
        self.rate_hz = float(prefs.servo_rate_hz)
        low, high = scene_box_m(doc_scene)
        if self.simulated:
            limits = _core.simulated_hand_limits() if hasattr(_core, "simulated_hand_limits") \
                else _core.simulated_probe_limits()
            limits.max_force_n = min(limits.max_force_n, prefs.force_limit_n)
            _limits_workspace(limits, low - WORKSPACE_MARGIN_M, high + WORKSPACE_MARGIN_M)
            self.device = _core.SimulatedHand(limits)
            mapping = None  # identity: the hand's frame is the world
        else:
            opener = getattr(_core, "open_device", None)
            if opener is None:
                raise BindingsMissing("opening a HID device needs _core.open_device, which this build lacks")
            self.device = opener(device)
            limits = self.device.info.limits
            mapping = self._mapping(limits, low, high, prefs)
        self.limits = limits
        if mapping is not None and hasattr(_core, "render_limits_for"):
            render = _core.render_limits_for(limits, mapping)
        else:
            render = _core.RenderLimits()
            render.max_stiffness_n_per_m = limits.max_stiffness_n_per_m
            render.max_force_n = limits.max_force_n
        render.max_force_n = min(render.max_force_n, prefs.force_limit_n)
        self.renderer = _core.ForceRenderer(doc_scene.scene, doc_scene.surfaces, render)
        self.loop = _core.ServoLoop(self.device, self.renderer, rate_hz=self.rate_hz,
                                    trace_capacity=int(self.rate_hz * TRACE_SECONDS) + 1024)
        if mapping is not None:
            self.loop.set_mapping(mapping)

    @staticmethod
    def _mapping(limits, low, high, prefs):
        if prefs.workspace_mapping == "Fit part" and hasattr(_core, "fit_workspace"):
            return _core.fit_workspace(limits, low, high)
        mapping = _core.WorkspaceMapping()
        mapping.scale = prefs.workspace_scale
        centre_d = 0.5 * (np.asarray(limits.workspace_min_d) + np.asarray(limits.workspace_max_d))
        mapping.offset_w = 0.5 * (low + high) - prefs.workspace_scale * centre_d
        return mapping

    # --- control (GUI thread) --------------------------------------------------------

    def start(self, target_w=None):
        """Starts the loop; the simulated hand begins at rest at ``target_w`` (m)."""
        if self.simulated and target_w is not None:
            self.set_target(target_w)
        self.loop.start()

    def stop(self):
        if self.loop.running:
            self.loop.stop()

    def set_target(self, target_w):
        """Where the simulated hand aims, world metres (lock-free in the device)."""
        if self.simulated:
            self.device.set_target(np.asarray(target_w, float))

    def drain(self):
        """Trace samples since the last drain (a NumPy structured array)."""
        return self.loop.drain_trace()

    @property
    def running(self):
        return bool(self.loop.running)

    @property
    def stats(self):
        return self.loop.stats

    @property
    def end_message(self):
        return getattr(self.loop, "fault_message", "") or ""

    def achieved_rate_hz(self):
        stats = self.loop.stats
        rate = getattr(stats, "achieved_rate_hz", 0.0)
        if not rate and stats.elapsed_s > 0:
            rate = stats.ticks / stats.elapsed_s
        return float(rate)

    def describe_face(self, cad_face):
        """"Object.FaceN: surface (material, mu_s, mu_d, roughness)" of a face, or ""."""
        if cad_face is None or cad_face < 0 or cad_face >= len(self.doc_scene.face_names):
            return ""
        name = self.doc_scene.face_names[cad_face]
        surface = self.doc_scene.face_surface.get(name)
        props = self.doc_scene.surface_properties(cad_face)
        friction = props.friction
        what = f"{self.doc_scene.face_material.get(name)}" if surface else "untagged"
        return (f"{name}: {surface or 'no surface'} ({what}, μs {friction.static_coefficient:.2f}, "
                f"μd {friction.dynamic_coefficient:.2f}, {props.stiffness_n_per_m * MM:.2f} N/mm)")
