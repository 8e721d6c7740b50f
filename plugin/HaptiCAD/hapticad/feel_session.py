# SPDX-License-Identifier: GPL-3.0-or-later
"""A live Feel session: the one place the workbench drives the C++ servo loop live.

The servo loop runs in its own C++ thread (devices/, issue 5) with a device: the
simulated hand, whose target the GUI sets from the mouse (lock-free, any thread), or a
HID device. Python only builds the scene, starts and stops the loop, sets the hand's
target, and drains the trace for display (the GUI polls at most 60 times a second).
Nothing here runs per servo tick, and there is no servo loop in Python.

The binding's contract (devices/README.md):

    _core.SimulatedHand(limits)            .set_target(p_w)   (world m; identity mapping)
    _core.ServoLoop(device, renderer, rate_hz, trace_capacity)
        .start() .stop() .drain_trace() .calc_stats() .ticks .running .set_mapping(mapping)
    _core.ForceRenderer(scene, surfaces, limits) .set_surfaces(surfaces)
    loop.set_renderer(renderer)            (a new scene, taken at the next tick)
    loop.release_replaced_renderers()      (frees a scene the loop moved past)
    _core.list_devices(), _core.open_device(path)   (device_opening.py: off the GUI thread)

Units: SI (m, N) in the loop, mm in the document. No GUI.
"""
from dataclasses import dataclass

import numpy as np

from . import _core, preferences

MM = 1e-3
SIMULATED = preferences.SIMULATED_DEVICE
WORKSPACE_MARGIN_M = 0.05  # around the parts: the simulated hand can lift off and come back
TRACE_SECONDS = 4.0  # ring capacity between two drains, at the servo rate


@dataclass(frozen=True)
class DeviceChoice:
    label: str
    path: str  # "simulated" or what opens it again (e.g. /dev/hidraw3)
    problem: str = ""  # why it cannot be used (an unsupported protocol, say), as the core lists it

    @property
    def simulated(self):
        return self.path == SIMULATED


def device_choices():
    """The simulated probe first, then every HID device the core finds now; one that
    cannot be used says so in its label and ``problem`` (it used to be offered as if it
    could, and refused only at Start)."""
    choices = [DeviceChoice("Simulated probe (mouse)", SIMULATED)]
    try:
        for info in _core.list_devices():
            if info["kind"] != "sim" and info["path"]:
                problem = info.get("error") or ""
                choices.append(DeviceChoice(f"{info['name'] or 'HID device'} ({info['path']})"
                                            + (": unusable" if problem else ""), info["path"], problem))
    except RuntimeError:  # a device that fails to enumerate must not hide the simulated one
        pass
    return choices


def _limits_workspace(limits, low_m, high_m):
    """Sets a DeviceLimits' workspace box (device frame = world for the simulated hand)."""
    limits.workspace_min_d = np.asarray(low_m, float)
    limits.workspace_max_d = np.asarray(high_m, float)


def scene_box_m(doc_scene):
    """(min, max) corners of the parts in the scene, world metres."""
    return shapes_box_m(doc_scene.shapes.values())


def workspace_mapping(limits, low, high, prefs):
    """The device-to-world mapping the preferences choose for a device of ``limits`` and
    parts between ``low`` and ``high`` (world m): fitted to the parts, or a fixed scale
    centred on them."""
    if prefs.workspace_mapping == "Fit part":
        return _core.fit_workspace(limits, low, high)
    mapping = _core.WorkspaceMapping()
    mapping.scale = prefs.workspace_scale
    centre_d = 0.5 * (np.asarray(limits.workspace_min_d) + np.asarray(limits.workspace_max_d))
    mapping.offset_w = 0.5 * (low + high) - prefs.workspace_scale * centre_d
    return mapping


def shapes_box_m(shapes):
    """(min, max) corners of Part shapes placed in the world (mm), world metres."""
    low, high = np.full(3, np.inf), np.full(3, -np.inf)
    for shape in shapes:
        box = shape.BoundBox
        low = np.minimum(low, [box.XMin, box.YMin, box.ZMin])
        high = np.maximum(high, [box.XMax, box.YMax, box.ZMax])
    return low * MM, high * MM


def beyond_reach(limits, mapping, low_m, high_m):
    """A sentence when the box (world m) of the parts does not fit in the device's
    workspace (limits) as ``mapping`` places it in the world, else None."""
    low_d, high_d = np.asarray(limits.workspace_min_d, float), np.asarray(limits.workspace_max_d, float)
    tolerance = 1e-9 * max(float(np.max(high_d - low_d)), 1e-3)
    corners_w = [np.array([x, y, z]) for x in (low_m[0], high_m[0]) for y in (low_m[1], high_m[1])
                 for z in (low_m[2], high_m[2])]
    for corner in corners_w:
        p_d = np.asarray(mapping.world_to_device(corner), float)
        if (p_d < low_d - tolerance).any() or (p_d > high_d + tolerance).any():
            return ("the parts reach beyond the device's workspace as it is mapped now: use the clutch to "
                    "reach the rest, or start the session again to fit them")
    return None


class LiveSession:
    """One Feel session on a document scene. ``device``: SIMULATED (the simulated probe),
    a device path, opened here with ``_core.open_device`` on the calling thread (which it
    may block for seconds with a device that does not answer: the GUI opens it with
    device_opening.DeviceOpening instead), or a device opened already (a _core.Device,
    which the session then owns). Raises RuntimeError / ValueError with the device
    layer's message when the device cannot be opened."""

    def __init__(self, doc_scene, device=SIMULATED, prefs=None):
        prefs = prefs or preferences.load()
        self.doc_scene = doc_scene
        self.simulated = isinstance(device, str) and device == SIMULATED
        self.rate_hz = float(prefs.servo_rate_hz)
        low, high = scene_box_m(doc_scene)
        self.reach_m = None  # the world box the probe reaches, where the session knows it
        if self.simulated:
            limits = _core.simulated_hand_limits()
            limits.max_force_n = min(limits.max_force_n, prefs.force_limit_n)
            self.reach_m = (low - WORKSPACE_MARGIN_M, high + WORKSPACE_MARGIN_M)
            _limits_workspace(limits, *self.reach_m)
            self.device = _core.SimulatedHand(limits)
            mapping = None  # identity: the hand's frame is the world
        else:
            self.device = _core.open_device(device) if isinstance(device, str) else device
            limits = self.device.info.limits
            mapping = workspace_mapping(limits, low, high, prefs)
        self.limits = limits
        render = _core.render_limits_for(limits, mapping or _core.WorkspaceMapping())
        render.max_force_n = min(render.max_force_n, prefs.force_limit_n)
        self.render_limits = render
        self.renderer = _core.ForceRenderer(doc_scene.scene, doc_scene.surfaces, render,
                                            doc_scene.contact_options())
        self.loop = _core.ServoLoop(self.device, self.renderer, rate_hz=self.rate_hz,
                                    trace_capacity=int(self.rate_hz * TRACE_SECONDS) + 1024)
        if mapping is not None:
            self.loop.set_mapping(mapping)
        self.mapping = mapping or _core.WorkspaceMapping()  # the loop takes it at its first tick
        # a device's reach: the simulated hand's is the parts' box and a margin
        self.reach_note = None if self.simulated else beyond_reach(limits, self.mapping, low, high)

    # --- control (GUI thread) --------------------------------------------------------

    def start(self, target_w=None):
        """Starts the loop; the simulated hand begins at rest at ``target_w`` (m)."""
        if self.simulated and target_w is not None:
            self.set_target(target_w)
        self.loop.start()

    def stop(self):
        if self.loop.running:
            self.loop.stop()

    def update_surfaces(self, doc):
        """Compiles doc's surfaces again and hands them to the loop: a property edit is
        felt from the next tick on, the scene is not rebuilt and the session goes on.
        Raises ValueError (naming the surface) when the edit cannot be compiled, and
        document_scene.NeedsNewScene when it needs a new scene (update_scene); the loop
        then keeps what it had."""
        from .document_scene import recompile_surfaces  # FreeCAD's: only when used

        doc_scene = recompile_surfaces(doc, self.doc_scene)
        self.renderer.set_surfaces(doc_scene.surfaces)
        self.doc_scene = doc_scene

    def update_scene(self, doc):
        """Tessellates doc's tagged parts again, at the session's accuracy, and swaps the
        new scene into the loop: a change of shape is felt from the next tick on, the
        session goes on. The loop takes the new renderer at its next tick (built here,
        never on the servo thread); the proxy restarts where it was, or on the nearest
        face if the part grew over it, and the force goes over 0.2 s from the old one to
        the new (at once to zero if the hand touches nothing now). Raises ValueError
        (naming the part or surface) when the new shape cannot be felt (a tagged face
        gone, nothing left to touch, parts beyond the simulated probe's workspace, which
        was set at the start); the loop then keeps the old scene. With a device, parts
        grown beyond its mapped workspace are felt where it reaches, and ``reach_note``
        says so (the clutch reaches the rest)."""
        from .document_scene import build_document_scene  # FreeCAD's: only when used

        doc_scene = build_document_scene(doc, self.doc_scene.accuracy)
        if self.reach_m is not None:
            low, high = scene_box_m(doc_scene)
            if (low < self.reach_m[0]).any() or (high > self.reach_m[1]).any():
                raise ValueError("the parts now reach beyond the simulated probe's workspace, "
                                 "which was set when the session started: start it again")
        renderer = _core.ForceRenderer(doc_scene.scene, doc_scene.surfaces, self.render_limits,
                                       doc_scene.contact_options())
        self.loop.set_renderer(renderer)
        self.renderer = renderer
        self.doc_scene = doc_scene
        if not self.simulated:  # the device's mapping was fitted to the parts as they were
            # the mapping in effect, clutch offsets included, once the loop has ticked
            mapping = self.loop.mapping if self.loop.ticks > 0 else self.mapping
            self.reach_note = beyond_reach(self.limits, mapping, *scene_box_m(doc_scene))

    def apply_edit(self, doc, geometry):
        """What the Feel panel calls after the designer edits doc: with ``geometry``
        (a part changed shape) the scene is built again (update_scene); otherwise the
        surfaces are recompiled (update_surfaces), and if the edit tags a part or face
        the scene does not hold, the scene is built again after all. Returns "scene" or
        "surfaces", what was handed to the loop. Raises ValueError as those do; the loop
        then keeps what it had."""
        from .document_scene import NeedsNewScene

        if not geometry:
            try:
                self.update_surfaces(doc)
                return "surfaces"
            except NeedsNewScene:
                pass
        self.update_scene(doc)
        return "scene"

    def set_target(self, target_w):
        """Where the simulated hand aims, world metres (lock-free in the device)."""
        if self.simulated:
            self.device.set_target(np.asarray(target_w, float))

    def let_go(self):
        """The simulated hand lets go of the proxy (the clutch held): the force stops at
        once and the hand moves freely, while the loop's tool stays where it was. With
        ``take_hold`` the hand steering frees a proxy caught on the far side of a part
        (hand_approach.py); a real device's user moves the handle out instead."""
        if self.simulated:
            self.loop.set_clutch(True)

    def take_hold(self):
        """After ``let_go``: the proxy restarts at the hand, as at the start of a session
        (the hand's identity mapping given again: it drops the clutch's offset), and the
        force ramps in from zero. The mapping first, so that the tick that sees the clutch
        released restarts the proxy at the hand, never at the tool let go of."""
        if self.simulated:
            self.loop.set_mapping(self.mapping)
            self.loop.set_clutch(False)

    def hand_w(self):
        """Where the simulated hand holds the handle now, world metres (its frame is the
        world), let go of or not."""
        return np.asarray(self.device.true_state.position_d, float)

    def tool_w(self):
        """Where the device's tool was at the loop's last tick, world metres."""
        return np.asarray(self.loop.latest()["device_m"], float)

    def proxy_w(self):
        """Where the proxy was held at the loop's last tick, world metres."""
        return np.asarray(self.loop.latest()["proxy_m"], float)

    def drain(self):
        """Trace samples since the last drain (a NumPy structured array). Also frees a
        scene the loop has swapped out (the GUI polls this)."""
        self.loop.release_replaced_renderers()
        return self.loop.drain_trace()

    @property
    def running(self):
        return bool(self.loop.running)

    @property
    def ticks(self):
        """Ticks the loop ran so far (cheap: one atomic read)."""
        return int(self.loop.ticks)

    @property
    def end_message(self):
        return getattr(self.loop, "fault_message", "") or ""

    def achieved_rate_hz(self):
        """The rate the loop kept, (ticks - 1) over its wall time (the loop computes its
        statistics for this: call it at display rate, not in a tight loop)."""
        return float(self.loop.calc_stats().achieved_rate_hz)

    def vibration_notes(self, doc):
        """What this session makes of doc's vibrations, as sentences (empty when each is
        felt as set): what its servo rate keeps from being felt (vibration_object.rate_note)
        and what its force limit cuts (vibration_object.force_note, with the session's
        limit, render_limits.max_force_n)."""
        from . import vibration_object  # FreeCAD's: only when used

        return (vibration_object.rate_notes(doc, self.rate_hz)
                + vibration_object.force_notes(doc, self.render_limits.max_force_n))

    def roughness_notes(self, doc):
        """The roughness grids and texture gratings of doc's surfaces this session's servo
        rate cannot follow at a brisk stroke (surface_object.rate_notes), as sentences."""
        from . import surface_object  # FreeCAD's: only when used

        return surface_object.rate_notes(doc, self.rate_hz)

    def describe_face(self, cad_face):
        """"Object.FaceN: surface label (material, mu_s, mu_d, stiffness) of a face, or ""."""
        if cad_face is None or cad_face < 0 or cad_face >= len(self.doc_scene.face_names):
            return ""
        name = self.doc_scene.face_names[cad_face]
        surface = self.doc_scene.face_surface_label.get(name)  # as the tree shows it
        props = self.doc_scene.surface_properties(cad_face)
        friction = props.friction
        what = f"{self.doc_scene.face_material.get(name)}" if surface else "untagged"
        law = props.force_travel
        # what is felt: the renderer holds stiffness and damping to the device's (render_limits)
        k_most, b_most = self.render_limits.max_stiffness_n_per_m, self.render_limits.max_damping_n_s_per_m
        k_set, b_set = props.stiffness_n_per_m, props.damping_n_s_per_m
        # a stiffness study's mechanism gives instead of the material: say which
        give = (f"{min(k_set, k_most) * MM:.2f} N/mm" if law is None else
                f"{law.max_slope() * MM:.2f} N/mm bending" if law.points == 1 else
                f"button, operating force {law.force_n[0]:.2f} N")
        if law is None and k_set > k_most:
            give += f", the device's most ({k_set * MM:.2f} set)"
        if b_set > 0:
            give += f", damping {min(b_set, b_most):.2f} N s/m"
            if b_set > b_most:
                give += f", the device's most ({b_set:.2f} set)"
        return (f"{name}: {surface or 'no surface'} ({what}, μs {friction.static_coefficient:.2f}, "
                f"μd {friction.dynamic_coefficient:.2f}, {give})")
