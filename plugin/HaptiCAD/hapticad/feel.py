# SPDX-License-Identifier: GPL-3.0-or-later
"""Feel a stroke over a document's tagged faces with the simulated probe.

A stroke is a segment P0 -> P1 on the part's surface (mm, global coordinates). The
probe starts ``clearance_mm`` above P0 along the outward normal, descends to ``depth_mm``
below the surface, dwells, slides to P1 at ``speed_mm_s`` (the segment shifted into
the part along the inward normal at P0), dwells and retreats. The C++ servo loop runs
it in real time at ``rate_hz`` and returns the trace. No GUI.
"""
import csv
import math
import os
from dataclasses import dataclass

import numpy as np

from . import _core

MM = 1e-3
APPROACH_SPEED_MM_S = 25.0  # descent and retreat: slow enough to meet the surface gently
DWELL_S = 0.1  # at depth before sliding, so the slide starts from rest
MAX_START_DISTANCE_MM = 1.0  # P0 must lie on (or this close to) the surface
MAX_STROKE_S = 600.0  # a slide longer than ten minutes is a typo (and a trace of millions of samples)


@dataclass
class Stroke:
    p0_mm: tuple
    p1_mm: tuple
    speed_mm_s: float = 50.0
    depth_mm: float = 1.0
    rate_hz: float = 1000.0
    clearance_mm: float = 5.0

    def validate(self):
        p0, p1 = np.asarray(self.p0_mm, float), np.asarray(self.p1_mm, float)
        if p0.shape != (3,) or p1.shape != (3,) or not (np.isfinite(p0).all() and np.isfinite(p1).all()):
            raise ValueError("stroke: P0 and P1 must be three finite coordinates each")
        if np.linalg.norm(p1 - p0) <= 0:
            raise ValueError("stroke: P0 and P1 coincide")
        if not (0 < self.speed_mm_s <= 2000):
            raise ValueError(f"stroke: speed {self.speed_mm_s} mm/s is outside 0..2000")
        if not (0 < self.depth_mm <= 20):
            raise ValueError(f"stroke: depth {self.depth_mm} mm is outside 0..20")
        seconds = float(np.linalg.norm(p1 - p0)) / self.speed_mm_s
        if seconds > MAX_STROKE_S:  # run in real time, its trace kept whole
            raise ValueError(f"stroke: {np.linalg.norm(p1 - p0):g} mm at {self.speed_mm_s:g} mm/s takes "
                             f"{seconds:.3g} s; strokes run in real time: give one under {MAX_STROKE_S:g} s")
        slowest = _core.min_servo_rate_hz()  # what the loop's watchdog allows
        if not (slowest <= self.rate_hz <= 10000):
            raise ValueError(f"stroke: rate {self.rate_hz} Hz is outside {slowest:g}..10000 "
                             "(slower, the loop's watchdog would cut the force)")


@dataclass
class StrokePlan:
    times_s: np.ndarray
    positions_m: np.ndarray  # waypoints, world metres
    outward_normal: np.ndarray
    start_face: int
    slide_start_s: float
    slide_end_s: float
    p0_m: np.ndarray
    p1_m: np.ndarray


def _closest_on_surface(doc_scene, point_m, name, fix):
    """The scene's closest point to a stroke's end ``name`` ("P0", "P1"); raises
    ValueError saying ``fix`` when it is farther than MAX_START_DISTANCE_MM."""
    closest = doc_scene.scene.calc_closest_point(point_m)
    if closest.distance_m > MAX_START_DISTANCE_MM * MM:
        raise ValueError(
            f"stroke: {name} is {closest.distance_m / MM:.3f} mm from the nearest surface of the "
            f"tagged parts (closest point {np.round(np.asarray(closest.point_w) / MM, 3).tolist()} mm "
            f"on {doc_scene.face_names[closest.cad_face]}); {fix}"
        )
    return closest


def plan_stroke(doc_scene, stroke):
    """Waypoints of the scripted probe for a stroke. Raises ValueError if P0 or P1 is off
    the surface: the slide runs from P0 to P1 pressed in by the depth, so a P1 off it (a
    mistyped coordinate) would drive the probe deep into the part or off it into the air."""
    stroke.validate()
    p0 = np.asarray(stroke.p0_mm, float) * MM
    p1 = np.asarray(stroke.p1_mm, float) * MM
    start = _closest_on_surface(doc_scene, p0, "P0", "start the stroke on the surface")
    _closest_on_surface(doc_scene, p1, "P1", "end the stroke on the surface")
    n = np.asarray(start.normal_w, float)
    clearance = stroke.clearance_mm * MM
    depth = stroke.depth_mm * MM
    approach = (clearance + depth) / (min(stroke.speed_mm_s, APPROACH_SPEED_MM_S) * MM)
    slide = np.linalg.norm(p1 - p0) / (stroke.speed_mm_s * MM)
    times = np.cumsum([0.0, 0.05, approach, DWELL_S, slide, 0.05, approach])
    positions = np.array([
        p0 + clearance * n,
        p0 + clearance * n,
        p0 - depth * n,
        p0 - depth * n,
        p1 - depth * n,
        p1 - depth * n,
        p1 + clearance * n,
    ])
    return StrokePlan(times, positions, n, start.cad_face, times[3], times[4], p0, p1)


@dataclass
class FeelResult:
    trace: np.ndarray  # structured: _core TraceSample fields
    plan: StrokePlan
    stroke: Stroke
    stats: object  # _core.ServoStats
    limits: object  # _core.DeviceLimits


def probe_limits(prefs):
    """The simulated probe's limits as a Feel session with ``prefs`` (preferences.Preferences)
    renders them: its force held to the Preferences' force limit, as the Feel panel holds the
    simulated hand's, so a scripted stroke presses as hard as the designer would feel."""
    limits = _core.simulated_probe_limits()
    limits.max_force_n = min(limits.max_force_n, prefs.force_limit_n)
    return limits


def run_stroke_in_servo_loop(doc_scene, stroke, limits=None):
    """Plans ``stroke`` (plan_stroke: approach, dwell, slide, retreat) and runs it in real
    time through the real servo loop, the simulated probe following the plan; returns a
    FeelResult with the loop's trace. Takes as long as the stroke (seconds). Not
    _core.run_stroke, which renders a given path tick by tick straight through a
    ForceRenderer, with no loop, device or real time, to time each tick."""
    plan = plan_stroke(doc_scene, stroke)
    limits = limits or _core.simulated_probe_limits()
    device = _core.SimulatedDevice(list(plan.times_s), plan.positions_m, limits)
    render_limits = _core.RenderLimits()
    render_limits.max_force_n = limits.max_force_n
    render_limits.max_stiffness_n_per_m = limits.max_stiffness_n_per_m
    renderer = _core.ForceRenderer(doc_scene.scene, doc_scene.surfaces, render_limits,
                                   doc_scene.contact_options())
    loop = _core.ServoLoop(device, renderer, stroke.rate_hz,
                           trace_capacity=int(stroke.rate_hz * (plan.times_s[-1] + 1)) + 1024)
    trace = loop.run_for(float(plan.times_s[-1]))
    return FeelResult(trace, plan, stroke, loop.calc_stats(), limits)


def _contact(trace):
    return (trace["flags"] & _core.FLAG_CONTACT) != 0


def sliding_mask(result, doc_scene):
    """Contact ticks of the slide phase where the tangential speed is past the face's
    static band and transition (friction is mu_d there)."""
    trace = result.trace
    contact = _contact(trace)
    normal = np.asarray(trace["proxy_m"]) - np.asarray(trace["device_m"])
    length = np.linalg.norm(normal, axis=1, keepdims=True)
    normal = np.divide(normal, length, out=np.zeros_like(normal), where=length > 0)
    velocity = np.asarray(trace["velocity_mps"])
    v_t = velocity - (velocity * normal).sum(axis=1, keepdims=True) * normal
    speed = np.linalg.norm(v_t, axis=1)
    threshold = np.array([
        _dynamic_speed(doc_scene, face) if face >= 0 else np.inf for face in trace["cad_face"]
    ])
    in_slide = (trace["time_s"] > result.plan.slide_start_s) & (trace["time_s"] < result.plan.slide_end_s)
    return contact & in_slide & (speed >= threshold)


def _dynamic_speed(doc_scene, face):
    f = doc_scene.surface_properties(face).friction
    return f.stick_speed_mps + f.transition_speed_mps


def effective_stiffness_n_per_mm(doc_scene, face, limits):
    """The face's stiffness as the device renders it, N/mm: the surface's, or, while a
    stiffness study holds it, its law's steepest slope (the mechanism replaces the
    surface's contact stiffness: a bending beam's stiffness, a button's click; its housing
    stop aside, as stiffness_study.device_note leaves it), held to the device's stable most
    (limits.max_stiffness_n_per_m) as the renderer holds it."""
    props = doc_scene.surface_properties(face)
    k = props.stiffness_n_per_m if props.force_travel is None else props.force_travel.stretch_slope()
    return min(k, limits.max_stiffness_n_per_m) * MM


def stiffer_than_device(doc_scene, face, limits):
    """Whether what the face pushes back with is steeper than the device's stable most, so
    it is felt softer: the surface's own stiffness (felt at the device's most), or its
    stiffness study's law's steepest slope (the law is stretched to the device, its forces
    kept), as stiffness_study.device_note judges it."""
    props = doc_scene.surface_properties(face)
    k = props.stiffness_n_per_m if props.force_travel is None else props.force_travel.stretch_slope()
    return k > limits.max_stiffness_n_per_m


def _face_named(doc_scene, face):
    """"Object.FaceN (surface label)" of a face, as the notes name it."""
    name = doc_scene.face_names[face]
    surface = doc_scene.face_surface_label.get(name)
    return f"{name}{f' ({surface})' if surface else ''}"


def law_note(doc_scene, face, limits, depth_mm, study=""):
    """A sentence when a stiffness study's law governs the face (its mechanism replaces the
    surface's contact stiffness), naming the study (``study``: its Label; "" for "a
    stiffness study"), the law and the surface stiffness it replaces; then, when the law is
    steeper than the device renders stably, what the stroke felt at ``depth_mm`` instead.
    "" when no law governs the face."""
    props = doc_scene.surface_properties(face)
    law = props.force_travel
    if law is None:
        return ""
    whose = f"{study}'s" if study else "a stiffness study's"
    steepest = law.stretch_slope() * MM  # N/mm
    k_most = limits.max_stiffness_n_per_m * MM
    if law.points == 1:  # a straight law: the bending beam's stiffness
        mechanism = f"bending beam ({steepest:.3g} N/mm)"
        beyond = f"it is above the {k_most:g} N/mm the device renders stably: it was felt at {k_most:g} N/mm"
    else:
        mechanism = f"push button (operating force {law.force_n[0]:.3g} N at {law.travel_m[0] / MM:.3g} mm)"
        beyond = (f"its steepest slope, {steepest:.3g} N/mm, is above the {k_most:g} N/mm the device renders stably: "
                  f"its forces are kept over a travel {steepest / k_most:.2g} x longer")
    said = (f"{_face_named(doc_scene, face)}: {whose} {mechanism} replaces the surface's "
            f"{props.stiffness_n_per_m * MM:g} N/mm")
    if not stiffer_than_device(doc_scene, face, limits):
        return said
    felt, designed = law.force_clamped(depth_mm * MM, limits.max_stiffness_n_per_m), law.force(depth_mm * MM)
    return f"{said}; {beyond} ({depth_mm:g} mm deep it pushes back with {felt:.3g} N, not {designed:.3g} N)"


def stiffness_note(doc_scene, face, limits, depth_mm, study=""):
    """A sentence on the face's stiffness as the stroke felt it at ``depth_mm``: law_note's
    when a stiffness study governs it (``study``: its Label); else, when the surface is
    stiffer_than_device, what was felt instead (held at the device's most); else ""."""
    if doc_scene.surface_properties(face).force_travel is not None:
        return law_note(doc_scene, face, limits, depth_mm, study)
    if not stiffer_than_device(doc_scene, face, limits):
        return ""
    k_set = doc_scene.surface_properties(face).stiffness_n_per_m * MM
    k_most = limits.max_stiffness_n_per_m * MM
    return (f"{_face_named(doc_scene, face)} is {k_set:g} N/mm stiff, above the {k_most:g} N/mm the "
            f"device renders stably: it was felt at {k_most:g} N/mm ({depth_mm:g} mm deep it pushes back with "
            f"{k_most * depth_mm:.3g} N, not {k_set * depth_mm:.3g} N)")


CLAMPED_NOTE_SHARE = 0.01  # of a textured face's slide held to the force limit: said


def texture_clip_note(result, doc_scene, face):
    """A sentence when the stroke's slide over textured ``face`` was held to the force limit
    (FLAG_FORCE_CLAMPED) on CLAMPED_NOTE_SHARE of its ticks or more while the press alone
    fits under it: the texture's drag and the press passed the limit together and the
    renderer scaled the whole force down (the press felt lighter, eq. 2's ridges cut). It
    says how much, how light the press fell, and the press that fits with the strongest drag
    felt (the trace's texture force, before the scaling); "" otherwise."""
    props = doc_scene.surface_properties(face)
    limit = float(result.limits.max_force_n)
    depth = result.stroke.depth_mm
    pressed = expected_normal_force_n(doc_scene, face, result.limits, depth)
    if props.texture is None or pressed >= limit:  # a press past the limit is said as such
        return ""
    trace = result.trace
    slide = (_contact(trace) & (trace["cad_face"] == face) & (trace["time_s"] > result.plan.slide_start_s)
             & (trace["time_s"] < result.plan.slide_end_s) & (trace["texture_force_n"] > 0))
    held = slide & ((trace["flags"] & _core.FLAG_FORCE_CLAMPED) != 0)
    if not slide.any() or held.sum() < CLAMPED_NOTE_SHARE * slide.sum():
        return ""
    if props.texture.scale == _core.TextureScale.FRICTION_LEVEL:  # the drag grows with the press
        ratio = float((trace["tangential_force_n"][held] / np.maximum(trace["normal_force_n"][held], 1e-12)).max())
        fits = limit / math.sqrt(1.0 + ratio ** 2)
    else:
        fits = math.sqrt(max(limit ** 2 - float(trace["texture_force_n"][slide].max()) ** 2, 0.0))
    return (f"{_face_named(doc_scene, face)}: {100 * held.sum() / slide.sum():.0f} % of the slide was held to the "
            f"{limit:g} N force limit: the texture's drag (up to {float(trace['texture_force_n'][slide].max()):.2f} "
            f"N) and the {pressed:.2f} N press passed it together and the whole force was scaled down, the press to "
            f"as little as {float(trace['normal_force_n'][held].min()):.2f} N and the grating's ridges with it; "
            f"pressed at most {fits:.2f} N it fits (or give the texture a smaller Full range)")


def expected_normal_force_n(doc_scene, face, limits, depth_mm):
    """What the face pushes back with at ``depth_mm`` on this device: its stiffness
    study's law (stretched to the device as the renderer does), else k x depth."""
    law = doc_scene.surface_properties(face).force_travel
    if law is not None:
        return law.force_clamped(depth_mm * MM, limits.max_stiffness_n_per_m)
    return effective_stiffness_n_per_mm(doc_scene, face, limits) * depth_mm


def study_labels(doc, doc_scene):
    """{"Object.FaceN": Label of the stiffness study whose law the face feels} for the faces
    of ``doc_scene`` (built from ``doc``) that feel one: how summarize names the study."""
    from .stiffness_study import study_of

    labels = {}
    for name, surface_name in doc_scene.face_surface.items():
        surface = doc.getObject(surface_name)
        study = study_of(surface) if surface is not None else None
        if study is not None and doc_scene.surface_properties(doc_scene.face_id(name)).force_travel is not None:
            labels[name] = study.Label
    return labels


def summarize(result, doc_scene, studies=None):
    """The JSON-ready summary of a stroke: per face felt, its surface (Label, and Name as
    surface_name), material, friction, its stiffness as felt and as set, and the stiffness
    study governing it (``studies``: study_labels; its law's steepest slope as
    study_stiffness_n_per_mm, null for none); the device's limits; and ``notes``, sentences
    on what was felt otherwise than set (a study's law in place of the surface's stiffness,
    a face stiffer than the device renders stably: stiffness_note; a texture whose drag with
    the press passed the force limit: texture_clip_note)."""
    studies = studies or {}
    trace = result.trace
    contact = _contact(trace)
    sliding = sliding_mask(result, doc_scene)
    faces = {}
    for face in sorted(set(int(f) for f in trace["cad_face"][contact])):
        name = doc_scene.face_names[face]
        on_face = trace["cad_face"] == face
        # a vibration may take the push away on some ticks (a face only pushes): no ratio there
        slide = sliding & on_face & (trace["normal_force_n"] > 0)
        props = doc_scene.surface_properties(face)
        law = props.force_travel
        fn = trace["normal_force_n"][slide]
        ft = trace["tangential_force_n"][slide]
        faces[name] = {
            # the Label, as the tree shows it and cohort, similarity and fit-texture name it; the Name beside it
            "surface": doc_scene.face_surface_label.get(name),
            "surface_name": doc_scene.face_surface.get(name),
            "material": doc_scene.face_material.get(name),
            "mu_static": props.friction.static_coefficient,
            "mu_dynamic": props.friction.dynamic_coefficient,
            "stiffness_n_per_mm": effective_stiffness_n_per_mm(doc_scene, face, result.limits),  # as felt
            "surface_stiffness_n_per_mm": props.stiffness_n_per_m * MM,  # as set on the surface
            "stiffness_above_device": stiffer_than_device(doc_scene, face, result.limits),
            "stiffness_study": studies.get(name),  # its Label, when a study's law replaces the surface's stiffness
            "study_stiffness_n_per_mm": law.stretch_slope() * MM if law is not None else None,  # as designed
            "contact_ticks": int((contact & on_face).sum()),
            "sliding_ticks": int(slide.sum()),
            "mean_normal_force_n": float(fn.mean()) if len(fn) else None,
            "mean_ft_over_fn": float((ft / fn).mean()) if len(fn) else None,
        }
    tick_us = trace["tick_us"]
    contact_us = tick_us[contact]
    start_face = result.plan.start_face
    return {
        "ticks": int(len(trace)),
        "contact_ticks": int(contact.sum()),
        "max_normal_force_n": float(trace["normal_force_n"].max()) if len(trace) else 0.0,
        "expected_normal_force_n": expected_normal_force_n(doc_scene, start_face, result.limits,
                                                           result.stroke.depth_mm),
        "faces": faces,
        "tick_us": _percentiles(tick_us),
        "contact_tick_us": _percentiles(contact_us),
        "rate_hz": result.stroke.rate_hz,
        "force_limit_n": float(result.limits.max_force_n),
        "max_stiffness_n_per_mm": float(result.limits.max_stiffness_n_per_m * MM),  # the device's, stable
        # what the stroke felt otherwise than the document sets it, as sentences (`hapticad feel` says them)
        "notes": [note for face in sorted(set(int(f) for f in trace["cad_face"][contact]))
                  for note in (stiffness_note(doc_scene, face, result.limits, result.stroke.depth_mm,
                                              studies.get(doc_scene.face_names[face], "")),
                               texture_clip_note(result, doc_scene, face)) if note],
        "accuracy": _accuracy_summary(doc_scene),
        "overruns": int(result.stats.overruns),
        "skipped_ticks": int(result.stats.skipped_ticks),
        "stroke": {
            "p0_mm": list(map(float, result.stroke.p0_mm)),
            "p1_mm": list(map(float, result.stroke.p1_mm)),
            "speed_mm_s": result.stroke.speed_mm_s,
            "depth_mm": result.stroke.depth_mm,
            "start_face": doc_scene.face_names[start_face],
        },
    }


def _accuracy_summary(doc_scene):
    accuracy = doc_scene.accuracy
    described = {"triangles": int(doc_scene.scene.num_triangles)}
    if accuracy is not None:
        described.update(name=accuracy.name, linear_deflection_mm=accuracy.linear_deflection_mm,
                         angular_deflection_deg=round(math.degrees(accuracy.angular_deflection_rad), 4),
                         force_shading=accuracy.force_shading, refine_edge_mm=accuracy.refine_edge_mm)
    return described


def _percentiles(values):
    if len(values) == 0:
        return {"p50": None, "p99": None, "max": None}
    return {
        "p50": float(np.percentile(values, 50)),
        "p99": float(np.percentile(values, 99)),
        "max": float(np.max(values)),
    }


def skipped_surface_notes(doc, broken=True):
    """A sentence for each HapticSurface of ``doc`` that tags faces a stroke cannot feel,
    naming it and why: its part was deleted, a face reference broke (the model changed;
    left out unless ``broken``), or it tags no face. The scene leaves those faces out
    (document_scene)."""
    from . import face_references
    from .surface_object import deleted_parts, reference_status, surfaces_of

    notes = []
    for surface in surfaces_of(doc):
        deleted = deleted_parts(surface)
        if deleted:
            were = "was" if len(deleted) == 1 else "were"
            notes.append(f"{surface.Label} is not felt on {', '.join(deleted)}, which {were} deleted: undo the "
                         "deletion or tag the faces of another part")
        gone = [f"{name}.{face_references.shown_face(face)}" for name, face, status in reference_status(surface)
                if status == face_references.BROKEN]
        if gone and broken:
            notes.append(f"{surface.Label} is not felt on {', '.join(gone)}: the face reference broke when the "
                         "model changed; pick the face again")
        if not surface.References and not deleted:
            notes.append(f"{surface.Label} tags no face: pick faces for it")
    return notes


def write_trace_csv(path, result, doc_scene):
    """One row per tick: time, device, proxy (mm), force (N), face, flags."""
    trace = result.trace
    with open(path, "w", newline="") as handle:
        out = csv.writer(handle)
        out.writerow([
            "time_s", "device_x_mm", "device_y_mm", "device_z_mm", "proxy_x_mm", "proxy_y_mm",
            "proxy_z_mm", "force_x_n", "force_y_n", "force_z_n", "normal_force_n",
            "tangential_force_n", "face", "contact",
        ])
        contact = _contact(trace)
        for i, s in enumerate(trace):
            face = int(s["cad_face"])
            out.writerow([
                f"{s['time_s']:.6f}",
                *(f"{x / MM:.6f}" for x in s["device_m"]),
                *(f"{x / MM:.6f}" for x in s["proxy_m"]),
                *(f"{x:.6f}" for x in s["force_n"]),
                f"{s['normal_force_n']:.6f}",
                f"{s['tangential_force_n']:.6f}",
                doc_scene.face_names[face] if face >= 0 else "",
                int(contact[i]),
            ])


def distance_along_stroke_mm(result):
    """Device position projected on P0 -> P1, mm from P0."""
    direction = result.plan.p1_m - result.plan.p0_m
    direction /= np.linalg.norm(direction)
    return (np.asarray(result.trace["device_m"]) - result.plan.p0_m) @ direction / MM


def feel_document(doc_scene, stroke, out_dir, title="", limits=None, studies=None):
    """Runs a stroke with the probe's ``limits`` (probe_limits; by default the simulated
    probe's own), writes out_dir/trace.csv and out_dir/trace.png, returns the summary
    (``studies``: study_labels, naming the stiffness studies it felt)."""
    from .trace_plot import plot_trace

    os.makedirs(out_dir, exist_ok=True)
    result = run_stroke_in_servo_loop(doc_scene, stroke, limits)
    summary = summarize(result, doc_scene, studies)
    csv_path = os.path.join(out_dir, "trace.csv")
    png_path = os.path.join(out_dir, "trace.png")
    write_trace_csv(csv_path, result, doc_scene)
    plot_trace(png_path, result, doc_scene, summary, title)
    summary["trace_csv"] = os.path.abspath(csv_path)
    summary["trace_png"] = os.path.abspath(png_path)
    return summary
