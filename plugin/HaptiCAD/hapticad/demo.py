# SPDX-License-Identifier: GPL-3.0-or-later
"""``hapticad demo``: open the example toothbrush and feel it.

Both work on a copy of the example in the output folder (the shipped one stays as
shipped; a copy saved there before is used again, once checked: a damaged one is named,
with how to get a fresh one). With a display, FreeCAD opens with the HaptiCAD workbench
and the copy. Headless, the simulated probe strokes every tagged face of the copy and
the traces and plots are written to the output folder, whose location is printed, with
what the Feel panel would say of the copy (feel_notes).
"""
import os
import shutil
import subprocess

from . import EXAMPLES_DIR

EXAMPLE = os.path.join(EXAMPLES_DIR, "toothbrush.FCStd")
GUI_STARTUP = os.path.join(os.path.dirname(os.path.abspath(__file__)), "gui", "demo_startup.py")


def working_copy(out_dir, example=EXAMPLE):
    """The example's copy in ``out_dir`` that the GUI demo opens: the shipped example
    stays as shipped (Save would overwrite it, or fail where it is installed read-only),
    and a copy saved there before is opened again, not replaced. Returns (path, new)."""
    path = os.path.join(os.path.abspath(out_dir), os.path.basename(example))
    if os.path.exists(path):
        return path, False
    os.makedirs(os.path.dirname(path), exist_ok=True)
    shutil.copyfile(example, path)
    return path, True


def damaged_copy(exc):
    """ValueError of document_file's ``exc`` on the demo's working copy, saying how to get a
    fresh one: working_copy opens a copy already there as it is, so each demo would fail on it."""
    return ValueError(f"{exc}. It is the demo's copy of the example: move it away and run hapticad demo again, "
                      "which copies the example there afresh")


def launch_gui(out_dir):
    from .document_file import document_xml

    freecad = shutil.which("freecad")
    if freecad is None:
        raise RuntimeError("FreeCAD's GUI ('freecad') is not installed")
    document, new = working_copy(out_dir)
    try:
        document_xml(document)  # FreeCAD opens a damaged one without a word, its faces looking gone
    except ValueError as exc:
        raise damaged_copy(exc) from None
    env = dict(os.environ)
    if os.geteuid() == 0:
        env.setdefault("QTWEBENGINE_DISABLE_SANDBOX", "1")  # else the Start page kills FreeCAD
    subprocess.Popen([freecad, document, GUI_STARTUP], env=env, start_new_session=True)
    return {"gui": True, "document": document, "copied": new}


def off_ball_rows(surface, face, p0, p1):
    """The stroke p0 -> p1 (mm) moved sideways, along the face, to run a quarter of the
    spacing off a row of the roughness grid's balls when it runs along one of the grid's
    axes. Along a row the mean friction is some 5 % above the material's, midway between
    rows 5 % below (measured at mu 0.4: 0.423 and 0.380); a quarter of the spacing off a
    row it is the material's (0.402), as over the whole face, so the plot's mean Ft/Fn
    can be read against mu_d."""
    import numpy as np

    from . import _core
    from .surface_compile import face_frame

    if not surface.FeelRoughness:
        return p0, p1
    origin, e1, e2, _ = face_frame(face, float(surface.PatternAngle))
    start, end = np.asarray(p0, float), np.asarray(p1, float)
    along = (end - start) / np.linalg.norm(end - start)
    across = e2 if abs(along @ e1) > 0.99 else e1 if abs(along @ e2) > 0.99 else None
    if across is None:
        return p0, p1
    g = _core.roughness_category(int(surface.RoughnessCategory)).grid_size_mm
    offset = float((start - np.asarray(origin) / 1e-3) @ across) % g
    shift = (g / 4 - offset) * across  # a quarter of the spacing off a row of ball centres
    return tuple(start + shift), tuple(end + shift)


RATE_HZ = 5000.0  # the finest roughness (0.1 mm balls) at 50 mm/s is 500 Hz: 1 kHz would alias it
RATE_OPTION = "with hapticad feel --rate"  # the demo's own rate is fixed: where a stroke's rate is set


def run_headless(out_dir, document=None, speed_mm_s=50.0, depth_mm=1.0, rate_hz=RATE_HZ):
    """Strokes every tagged face of ``document``: by default the example's copy in
    ``out_dir`` (working_copy), the one the GUI demo opens, so what the designer changed
    and saved there is what is stroked. Returns the strokes' summaries (feel.summarize,
    each with its own ``notes``) and ``notes``, what the Feel panel would say of the
    document (feel_notes.stroke_notes; a broken face is said as its stroke, skipped).
    Raises ValueError when the document is damaged (document_file), for the working copy
    saying how to get a fresh one."""
    import FreeCAD as App

    from . import feel_notes
    from .document_file import open_document
    from .document_scene import build_document_scene
    from .face_strokes import plan_face_stroke, vector_tuple
    from . import preferences
    from .feel import Stroke, feel_document, probe_limits, study_labels
    from .face_references import shown_face
    from .surface_object import active_reference_pairs, reference_pairs, surfaces_of

    copy = document is None
    if copy:
        document, _ = working_copy(out_dir)
    try:
        doc = open_document(App, document)
    except ValueError as exc:
        raise (damaged_copy(exc) if copy else exc) from None
    try:
        doc_scene = build_document_scene(doc)
        limits = probe_limits(preferences.load())  # the force limit the Feel panel renders with
        notes = feel_notes.stroke_notes(doc, rate_hz, limits.max_force_n, RATE_OPTION, broken=False)
        studies = study_labels(doc, doc_scene)
        strokes = []
        for surface in surfaces_of(doc):
            active = active_reference_pairs(surface)
            for obj, sub in reference_pairs(surface):
                name = f"{obj.Name}.{sub}"
                if (obj, sub) not in active:  # a model edit took its face: the scene has it untagged
                    strokes.append({"face": f"{obj.Name}.{shown_face(sub)}",
                                    "skipped": f"{surface.Label}'s face {shown_face(sub)} is broken by a model edit: "
                                               "pick it again in the surface's panel"})
                    continue
                ends = plan_face_stroke(doc_scene.face_shape(name))
                if ends is None:
                    strokes.append({"face": name, "skipped": "no straight stroke fits on this face"})
                    continue
                p0, p1 = off_ball_rows(surface, doc_scene.face_shape(name), vector_tuple(ends[0]),
                                           vector_tuple(ends[1]))
                stroke = Stroke(p0, p1, speed_mm_s, depth_mm, rate_hz)
                title = (f"{surface.Label} on {name}: {surface.Material}, roughness category "
                         f"{surface.RoughnessCategory}; stroked at {speed_mm_s:g} mm/s, {depth_mm:g} mm deep, "
                         f"{rate_hz / 1000:g} kHz")
                summary = feel_document(doc_scene, stroke, os.path.join(out_dir, name), title, limits, studies)
                summary["face"] = name
                strokes.append(summary)
    finally:
        App.closeDocument(doc.Name)
    return {"gui": False, "document": document, "out_dir": os.path.abspath(out_dir), "notes": notes,
            "strokes": strokes}
