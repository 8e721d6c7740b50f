# SPDX-License-Identifier: GPL-3.0-or-later
"""The StiffnessStudy document object: how a product gives under the finger, and what
participants prefer (seed 000 §3).

A study links the HapticSurface whose faces the participants press (a toothbrush's
head, a button's top) and models the mechanism behind them:

* Bending beam: the head sits on a neck clamped at the handle, a rectangular section
  b x h bent across h over length L, of a material's Young's modulus E:
  k = 3 E I / L^3, I = b h^3 / 12 (field notes: PP, 5 x 4 mm over 60 mm, 0.56 N/mm).
  The head gives k; the plastic's own give is far stiffer and left out.
* Push button: a tactile switch that rises to its operating force at the pretravel,
  snaps down by the snap ratio, and bottoms out on its housing (HousingStiffness), felt
  as stiff as it is up to the device's stiffness; a device softer than the click
  stretches the click's travel, never for the housing (force_travel.h).

While a study holds, its law replaces the surface's contact stiffness in the Feel
session (surface_compile), so a slider moving one design parameter (``Adjust``, between
``AdjustMin`` and ``AdjustMax``) is felt at the next servo tick. When a participant
finds the design right, :func:`record_preference` keeps their personal data and the
value they chose (cohort.Record), saved with the document, and written to disk as it
comes until the document is saved (study_journal). App-only.
"""
import json
import math
import numbers
import re
from datetime import datetime

import FreeCAD as App
import numpy as np

from . import _core, cohort, materials, study_journal
from .proxy_state import SchemaState, add_hidden_state, add_properties, add_type_tag, is_restoring

TYPE = "HaptiCAD::StiffnessStudy"
# 2: HousingStiffness (the button bottomed out on the surface's stiffness before: an
#    older document's buttons get a plastic housing's 50 N/mm)
SCHEMA_VERSION = 2
MM = 1e-3
BEAM, BUTTON = "Bending beam", "Push button"
MODELS = [BEAM, BUTTON]
# (name, kind, group, tooltip, default, (min, max, step) of a constrained float)
PROPERTIES = [
    ("Surface", "App::PropertyLink", "Study", "The haptic surface whose faces the participants press", None, None),
    ("Model", "App::PropertyEnumeration", "Study", "The mechanism behind the pressed faces", None, None),
    ("BeamMaterial", "App::PropertyEnumeration", "Beam", "Material of the neck: sets its Young's modulus", None, None),
    ("YoungsModulus", "App::PropertyFloatConstraint", "Beam", "Young's modulus E of the neck, GPa", 1.5,
     (0.001, 1000.0, 0.1)),
    ("BeamWidth", "App::PropertyFloatConstraint", "Beam", "Width b of the neck's section, mm", 5.0, (0.1, 200.0, 0.5)),
    ("BeamThickness", "App::PropertyFloatConstraint", "Beam", "Thickness h of the neck's section, bent across it, mm",
     4.0, (0.1, 200.0, 0.25)),
    ("BeamLength", "App::PropertyFloatConstraint", "Beam", "Length L from the clamp to where the finger presses, mm",
     60.0, (1.0, 2000.0, 5.0)),
    ("BendingStiffness", "App::PropertyFloat", "Beam", "k = 3 E I / L^3, N/mm (computed)", 0.0, None),
    ("OperatingForce", "App::PropertyFloatConstraint", "Button", "Force at the operating point, N", 1.47,
     (0.05, 50.0, 0.1)),
    ("Pretravel", "App::PropertyFloatConstraint", "Button", "Travel to the operating point, mm", 0.25,
     (0.01, 20.0, 0.05)),
    ("SnapRatio", "App::PropertyFloatConstraint", "Button", "(F_op - F_return) / F_op: how far the force drops",
     0.5, (0.01, 0.99, 0.05)),
    ("SnapTravel", "App::PropertyFloatConstraint", "Button", "Travel over which the force drops, mm", 0.1,
     (0.01, 20.0, 0.05)),
    ("TotalTravel", "App::PropertyFloatConstraint", "Button", "Travel where the button bottoms out, mm", 0.6,
     (0.02, 50.0, 0.1)),
    ("HousingStiffness", "App::PropertyFloatConstraint", "Button",
     "Stiffness of the housing the button bottoms out on, N/mm (felt up to the device's stiffness)", 50.0,
     (0.05, 1e4, 1.0)),
    ("Adjust", "App::PropertyEnumeration", "Customise", "The design parameter the Feel panel's slider moves",
     None, None),
    ("AdjustMin", "App::PropertyFloat", "Customise", "The slider's low end, in the parameter's unit", 2.0, None),
    ("AdjustMax", "App::PropertyFloat", "Customise", "The slider's high end, in the parameter's unit", 8.0, None),
    ("Participants", "App::PropertyInteger", "Cohort", "Participants with a preference kept (one person's records "
     "count once): those of another unit (what the slider moved before, or the other model) too, which the panel "
     "does not compare", 0, None),
]
HIDDEN_STATE = [("Cohort", "The participants' records (JSON)"),
                ("AdjustRanges", "The slider's range over each parameter it moved before (JSON), given back when "
                 "it moves that one again")]
# what a slider can move, per model: property -> (label, unit, default range)
ADJUSTABLE = {
    BEAM: {"BeamThickness": ("thickness h", "mm", (2.0, 8.0)), "BeamWidth": ("width b", "mm", (2.0, 12.0)),
           "BeamLength": ("length L", "mm", (30.0, 120.0)), "YoungsModulus": ("Young's modulus E", "GPa", (0.5, 5.0))},
    BUTTON: {"OperatingForce": ("operating force", "N", (0.5, 5.0)), "SnapRatio": ("snap ratio", "", (0.2, 0.8))},
}
ALL_ADJUSTABLE = [name for model in MODELS for name in ADJUSTABLE[model]]
# what the slider's low and high ends do to the design: a longer neck is softer, a larger
# snap ratio drops the force further (a crisper click)
SLIDER_ENDS = {"BeamThickness": ("softer", "stiffer"), "BeamWidth": ("softer", "stiffer"),
               "YoungsModulus": ("softer", "stiffer"), "BeamLength": ("stiffer", "softer"),
               "OperatingForce": ("lighter", "heavier"), "SnapRatio": ("less snap", "more snap")}
# what a preference in each unit is the value of, and the model that records it (design_value)
UNIT_SOURCES = {"N/mm": ("bending stiffness", BEAM), "N": ("operating force", BUTTON),
                "snap ratio": ("snap ratio", BUTTON)}


def _material_names():
    return [m.name for m in materials.default_database()]


class StiffnessStudy(SchemaState):
    """Proxy of a StiffnessStudy object."""

    SCHEMA = SCHEMA_VERSION

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj, new=True)

    def setup(self, obj, new=False):
        study_journal.watch_saves()  # records written to disk until a save holds them
        add_type_tag(obj, TYPE)
        add_properties(obj, PROPERTIES)
        add_hidden_state(obj, HIDDEN_STATE, "Cohort")
        if study_journal.REMOVED not in obj.PropertiesList:
            # the records removed on purpose since the document was opened (study_journal):
            # not saved (NoPersist), taken back and brought again with the removal by Undo and Redo
            obj.addProperty("App::PropertyString", study_journal.REMOVED, "Cohort",
                            "The participants' records removed on purpose since the document was opened (JSON, "
                            "not saved): never offered back as lost", 32)
            obj.setEditorMode(study_journal.REMOVED, 2)
        obj.setEditorMode("BendingStiffness", 1)
        obj.setEditorMode("Participants", 1)
        if new:
            obj.Adjust = ALL_ADJUSTABLE  # before Model: its change looks at Adjust
            obj.Adjust = "BeamThickness"
            obj.Model = MODELS
            names = _material_names()
            obj.BeamMaterial = names
            if "PP" in names:
                obj.BeamMaterial = "PP"
            obj.Cohort = "[]"
        _update_stiffness(obj)

    def onBeforeChange(self, obj, prop):
        if prop == "Adjust" and "Adjust" in obj.PropertiesList:
            try:  # onChanged resets the range only on a real change
                self._adjust_before = obj.Adjust
            except Exception:  # noqa: BLE001 (an enumeration not listed yet)
                self._adjust_before = None

    def onChanged(self, obj, prop):
        if prop in ("Cohort", study_journal.REMOVED) and not ("Restore" in obj.State or obj.Document.Restoring):
            # written to disk until the document is saved, an Undo or Redo too (study_journal)
            study_journal.cohort_changed(obj)
        if is_restoring(obj):
            return
        if prop == "BeamMaterial" and obj.BeamMaterial in materials.default_database():
            obj.YoungsModulus = materials.default_database().get(obj.BeamMaterial).youngs_modulus_gpa
        elif prop == "Model" and "Adjust" in obj.PropertiesList and obj.Adjust not in ADJUSTABLE[obj.Model]:
            obj.Adjust = next(iter(ADJUSTABLE[obj.Model]))  # its range follows (below)
        elif prop == "Adjust" and {"AdjustMin", "AdjustMax"} <= set(obj.PropertiesList):
            # the slider moves another parameter: its range is that one's, whoever chose it (the
            # panel, the property editor, a script); not on an undo or a restore (returned above)
            before = getattr(self, "_adjust_before", None)
            self._adjust_before = None
            if obj.Adjust != before:
                switch_adjust_range(obj, before)
        if prop in ("YoungsModulus", "BeamWidth", "BeamThickness", "BeamLength"):
            _update_stiffness(obj)

    def onDocumentRestored(self, obj):
        study_journal.opened(obj)  # first: what the file holds is what is saved
        self.setup(obj)
        try:  # documents saved before it counted people counted records
            obj.Participants = cohort.count_participants(records(obj))
        except (ValueError, TypeError, AttributeError):
            pass  # an unreadable cohort: the panel says so when opened
        from .surface_object import attach_view_provider

        attach_view_provider(obj)
        obj.purgeTouched()

    def execute(self, obj):
        _update_stiffness(obj)
        found = validate(obj)
        if found:
            App.Console.PrintError(f"{obj.Label}: {'; '.join(found)}\n")


def reset_adjust_range(study):
    """Sets the slider's range to the default of the parameter it moves (ADJUSTABLE)."""
    for model in MODELS:
        if study.Adjust in ADJUSTABLE[model]:
            low, high = ADJUSTABLE[model][study.Adjust][2]
            if (study.AdjustMin, study.AdjustMax) != (low, high):
                study.AdjustMin, study.AdjustMax = low, high
            return


def remembered_ranges(study):
    """{parameter: (low, high)} the slider had over each parameter it moved before."""
    try:
        data = json.loads(getattr(study, "AdjustRanges", "") or "{}")
    except ValueError:  # edited by hand: the defaults serve
        return {}
    kept = {}
    for name, pair in (data.items() if isinstance(data, dict) else ()):
        try:
            low, high = (float(v) for v in pair)
        except (TypeError, ValueError):
            continue
        if name in ALL_ADJUSTABLE and math.isfinite(low) and math.isfinite(high):
            kept[name] = (low, high)
    return kept


def switch_adjust_range(study, before):
    """The slider now moves ``study.Adjust``, not ``before``: the range it had over
    ``before`` is kept (AdjustRanges), and the new parameter's is the one it had last,
    else its default (reset_adjust_range). Switching away and back lost a range of one's
    own (3-5 mm) to the default (2-8)."""
    ranges = remembered_ranges(study)
    if before in ALL_ADJUSTABLE:
        ranges[before] = (float(study.AdjustMin), float(study.AdjustMax))
        kept = json.dumps({name: list(pair) for name, pair in ranges.items()})
        if study.AdjustRanges != kept:
            study.AdjustRanges = kept
    if study.Adjust in ranges:
        low, high = ranges[study.Adjust]
        if (study.AdjustMin, study.AdjustMax) != (low, high):
            study.AdjustMin, study.AdjustMax = low, high
    else:
        reset_adjust_range(study)


def _update_stiffness(obj):
    if not {"YoungsModulus", "BeamWidth", "BeamThickness", "BeamLength", "BendingStiffness"} <= set(
            obj.PropertiesList):
        return  # still being set up
    try:
        k = _core.cantilever_stiffness(obj.YoungsModulus * 1e9, obj.BeamWidth * MM, obj.BeamThickness * MM,
                                       obj.BeamLength * MM) * MM
    except ValueError:
        k = 0.0
    if abs(obj.BendingStiffness - k) > 1e-12:
        obj.BendingStiffness = k


def is_stiffness_study(obj):
    return getattr(obj, "HaptiCADType", None) == TYPE


def studies_of(doc):
    """The StiffnessStudy objects of a document. Raises ValueError when ``doc`` is not one."""
    from .surface_object import require_document

    require_document(doc, "studies_of")
    return [o for o in doc.Objects if is_stiffness_study(o)]


def study_of(surface):
    """The study whose law the surface's faces feel, or None."""
    found = [s for s in studies_of(surface.Document) if s.Surface == surface]
    return found[0] if found else None


def force_travel(study):
    """The study's force-travel law (_core.ForceTravel). Raises ValueError saying what
    is wrong with the study's values."""
    if study.Model == BEAM:
        k = _core.cantilever_stiffness(study.YoungsModulus * 1e9, study.BeamWidth * MM, study.BeamThickness * MM,
                                       study.BeamLength * MM)
        return _core.make_linear_force_travel(k)
    params = _core.PushButtonParams()
    params.operating_force_n = study.OperatingForce
    params.pretravel_m = study.Pretravel * MM
    params.snap_ratio = study.SnapRatio
    params.snap_travel_m = study.SnapTravel * MM
    params.total_travel_m = study.TotalTravel * MM
    params.bottom_stiffness_n_per_m = study.HousingStiffness / MM
    return _core.make_push_button(params)


def force_travel_of(surface):
    """The law a surface's faces feel, or None when no study holds it or its law cannot
    be made (law_problems says why). Problems of the slider alone do not drop the law."""
    study = study_of(surface)
    if study is None or law_problems(study):
        return None
    return force_travel(study)


def device_note(study, max_stiffness_n_per_m):
    """A sentence when the study's law is steeper than a device renders stably (it then
    feels softer there: the renderer clamps the slope), else "". Both are felt at the
    handle, in N per m of its travel: the renderer presses the law by the handle's depth
    whatever the workspace scale, and ``max_stiffness_n_per_m`` is the device's own limit
    (device_stiffness_n_per_m, LiveSession.render_limits)."""
    try:
        steepest = force_travel(study).stretch_slope()  # the click: no stretch is made for the housing
    except ValueError:
        return ""
    if steepest <= max_stiffness_n_per_m:
        return ""
    limit = f"({max_stiffness_n_per_m * MM:.3g} N/mm)"
    if study.Model == BEAM:
        return (f"the neck's stiffness, {steepest * MM:.3g} N/mm, is more than the device renders stably "
                f"{limit}: it is felt at the handle as {max_stiffness_n_per_m * MM:.3g} N/mm, and stiffer necks alike")
    return (f"the button's steepest slope, {steepest * MM:.3g} N/mm, is more than the device renders stably "
            f"{limit}: its forces are kept, over a handle travel {steepest / max_stiffness_n_per_m:.2g} x longer")


def force_note(study, max_force_n):
    """A sentence when a button's operating force is above the force the session renders
    (the force limit: the force stops there and the click never comes), else "". Forces
    are felt at the handle as designed, whatever the workspace scale (the mapping scales
    travel, not force), so both are the handle's newtons."""
    if study.Model != BUTTON or float(study.OperatingForce) <= max_force_n:
        return ""
    return (f"the operating force, {float(study.OperatingForce):.3g} N, is above the force limit, "
            f"{max_force_n:.3g} N: the force stops there and the click is never felt; raise the force "
            "limit in HaptiCAD's Preferences (as far as the device gives)")


# seed 000 §1 (after Lee and Cheng): a trigger should need under 2 kg with one finger and
# under 4 kg with two. The field notes read "2 kg" as a likely slip for the widely cited
# 2 lb (0.9 kg, 8.9 N) for one finger; both are said.
ONE_FINGER_TRIGGER_N = 2 * 0.45359237 * 9.80665  # 2 lb
PAPER_ONE_FINGER_N, PAPER_TWO_FINGER_N = 2 * 9.80665, 4 * 9.80665  # 2 kg, 4 kg


def ergonomic_note(study):
    """A sentence when a button needs more force than a trigger pressed again and again
    should (seed 000 §1), else "": a design note, nothing is clamped."""
    force = float(study.OperatingForce)
    if study.Model != BUTTON or force <= ONE_FINGER_TRIGGER_N:
        return ""
    paper = ("also above seed 000's 2 kg (19.6 N) for one finger" if force > PAPER_ONE_FINGER_N
             else "under seed 000's 2 kg (19.6 N), which the field notes take for a slip for 2 lb")
    two = f"; above even the 4 kg ({PAPER_TWO_FINGER_N:.1f} N) it allows two fingers" if force > PAPER_TWO_FINGER_N \
        else ""
    return (f"the operating force, {force:.3g} N, is above the widely cited one-finger trigger limit of 2 lb "
            f"({ONE_FINGER_TRIGGER_N:.1f} N), {paper}{two}: pressed again and again it tires the finger")


def device_stiffness_n_per_m(doc, prefs=None):
    """The stable stiffness a Feel session on ``doc`` renders with the preferences' device
    and workspace mapping, felt at the handle (N per m of its travel): the device's own
    limit, whatever the mapping's scale (the renderer presses a study's law by the handle's
    depth, and keeps it under this), as _core.render_limits_for gives it and
    LiveSession.render_limits holds it, so a record made in the study's panel keeps the
    stiffness and mark the Feel panel's would. The simulated hand's when the preferences
    choose it, or a device that is not connected now."""
    return device_render_limits(doc, prefs)[0].max_stiffness_n_per_m


def device_render_limits(doc, prefs=None):
    """(limits, known): the _core.RenderLimits a Feel session on ``doc`` renders with the
    preferences' device and workspace mapping (device_stiffness_n_per_m's), before the
    preferences' force limit, and whether they are that device's: False for a device not
    connected now, whose limits are not known (the simulated hand's stand in). Probes the
    HID devices: ask once, and rendered_force_limit_n as the preference changes."""
    from . import feel_session, preferences

    prefs = prefs or preferences.load()
    if prefs.device != feel_session.SIMULATED:
        limits = _listed_limits(prefs.device)
        if limits is not None:
            try:
                low, high = _parts_box_m(doc)
            except ValueError:  # nothing tagged: the mapping a session would fit is unknown
                low, high = np.zeros(3), np.full(3, 0.1)
            mapping = feel_session.workspace_mapping(limits, low, high, prefs)
            return _core.render_limits_for(limits, mapping), True
        return _core.render_limits_for(_core.simulated_hand_limits(), _core.WorkspaceMapping()), False
    return _core.render_limits_for(_core.simulated_hand_limits(), _core.WorkspaceMapping()), True


def rendered_force_limit_n(device_limits, force_limit_n):
    """The largest force a Feel session renders (N), as LiveSession.render_limits holds it:
    the preferences' ``force_limit_n`` under the device's own limit (``device_limits``:
    device_render_limits'), the preference alone when the device's limit is not known. A
    preference above what the device gives is not what is felt: the device's limit is."""
    limits, known = device_limits
    return min(float(limits.max_force_n), float(force_limit_n)) if known else float(force_limit_n)


def _listed_limits(path):
    """The _core.DeviceLimits of the device at ``path`` as listed now, or None."""
    try:
        listed = [info for info in _core.list_devices() if info["path"] == path and info["limits"]]
    except RuntimeError:  # a device that fails to enumerate
        return None
    if not listed:
        return None
    limits = _core.DeviceLimits()
    for name, value in listed[0]["limits"].items():
        if hasattr(limits, name):
            setattr(limits, name, np.asarray(value, float) if isinstance(value, (list, tuple)) else value)
    return limits


def _parts_box_m(doc):
    """(min, max) corners, world m, of the parts a Feel session on ``doc`` would hold
    (feel_session.scene_box_m of its scene, without tessellating it)."""
    from .document_scene import global_shape, tagged_objects
    from .feel_session import shapes_box_m

    objects = tagged_objects(doc)
    if not objects:
        raise ValueError("no part")
    return shapes_box_m(global_shape(o) for o in objects)


def design_value(study):
    """(value, unit) a participant's preference is recorded as: the bending stiffness
    (N/mm) of a beam, whatever the slider moves; of a button, what the slider moves (its
    operating force in N, its snap ratio)."""
    if study.Model == BEAM:
        return study.BendingStiffness, "N/mm"
    if study.Adjust == "SnapRatio":
        return study.SnapRatio, "snap ratio"
    return study.OperatingForce, "N"


def material_override(study):
    """A beam's Young's modulus edited away from its material's, as a sentence ("E 1.8 GPa,
    not PP's 1.5 GPa"), or "" (the material's, or a push button)."""
    database = materials.default_database()
    if study.Model != BEAM or study.BeamMaterial not in database:
        return ""
    listed = database.get(study.BeamMaterial).youngs_modulus_gpa
    if abs(listed - study.YoungsModulus) <= 1e-9 * listed:
        return ""
    return f"E {study.YoungsModulus:g} GPa, not {study.BeamMaterial}'s {listed:g} GPa"


def design(study):
    """The study's model parameters now, by property name."""
    names = (["YoungsModulus", "BeamWidth", "BeamThickness", "BeamLength", "BendingStiffness"] if study.Model == BEAM
             else ["OperatingForce", "Pretravel", "SnapRatio", "SnapTravel", "TotalTravel", "HousingStiffness"])
    return {name: float(getattr(study, name)) for name in names}


def law_problems(study):
    """Problems that keep the study's law off its surface's faces, as sentences."""
    from .surface_object import is_haptic_surface, linked_surface_problems

    found = linked_surface_problems(study, studies_of(study.Document), "press", "a face gives one way")
    try:
        if study.Surface is None or is_haptic_surface(study.Surface):
            force_travel(study)
    except ValueError as exc:
        found.append(str(exc))
    return found


def validate(study):
    """Problems with a study's current values, as sentences (empty when fine): its law's
    (law_problems), its slider's (slider_problems), and a design the slider cannot reach
    (outside_slider)."""
    return [*law_problems(study), *slider_problems(study), *filter(None, [outside_slider(study)])]


def slider_problems(study):
    """What keeps the slider from working, as sentences: record_preference refuses then."""
    found = []
    if study.Adjust not in ADJUSTABLE[study.Model]:
        found.append(f"the slider moves {study.Adjust}, which the {study.Model.lower()} model does not use")
    elif not study.AdjustMin < study.AdjustMax:
        found.append(f"the slider's range {study.AdjustMin:g}..{study.AdjustMax:g} is empty")
    else:
        prop = next(p for p in PROPERTIES if p[0] == study.Adjust)
        low, high = prop[5][0], prop[5][1]
        if study.AdjustMin < low or study.AdjustMax > high:
            found.append(f"the slider's range {study.AdjustMin:g}..{study.AdjustMax:g} leaves {low:g}..{high:g}, "
                         f"what {study.Adjust} allows")
    return found


def outside_slider(study):
    """A sentence when the parameter the slider moves is set outside the slider's range (h
    8 mm with a range of 3-5: set in the Mechanism box, the property editor or a script),
    else "": a participant could not have chosen it, and the slider, pinned at its end,
    jumps back into the range when touched. Said, not refused: a researcher may record a
    design set by hand (Table 3's 4.5 N/mm needs h 8.03 mm, past the default 2-8)."""
    if study.Adjust not in ADJUSTABLE[study.Model] or not study.AdjustMin < study.AdjustMax:
        return ""  # slider_problems says what is wrong
    value = float(getattr(study, study.Adjust))
    slack = 1e-9 * (study.AdjustMax - study.AdjustMin)  # the slider's own end, low + (high - low) * 200/200
    if study.AdjustMin - slack <= value <= study.AdjustMax + slack:
        return ""
    label, unit = adjust_info(study)
    unit = f" {unit}" if unit else ""
    return (f"the {label}, {value:g}{unit}, is outside the slider's range {study.AdjustMin:g}..{study.AdjustMax:g}"
            f"{unit}: move the slider, or widen its range")


def range_note(study, max_force_n):
    """A sentence when the slider moves a button's operating force past the force limit
    (``max_force_n``, N: force_note's), else "": there the force stops and the click is
    never felt, so a preference chosen there is marked (cohort.beyond_force_limit)."""
    if study.Model != BUTTON or study.Adjust != "OperatingForce" or not max_force_n:
        return ""
    low, high = float(study.AdjustMin), float(study.AdjustMax)
    if high <= max_force_n:
        return ""
    if low >= max_force_n:
        return f"the whole range is above {max_force_n:.3g} N, the force limit: the click is never felt"
    return f"past {max_force_n:.3g} N, the force limit, the click is never felt (the slider goes to {high:g} N)"


def _stored(study):
    """The study's stored cohort as the list of JSON records it holds; ValueError naming the
    study when it is not readable JSON or not a list."""
    try:
        data = json.loads(study.Cohort or "[]")
    except ValueError:
        raise ValueError(f"{study.Label}: the stored cohort is not readable JSON") from None
    if not isinstance(data, list):
        raise ValueError(f"{study.Label}: the stored cohort is not a list of records but {type(data).__name__} "
                         f"{str(data)[:40]!r}")
    return data


def _read(study, data):
    """[(index in ``data``, cohort.Record or None)], and a sentence for each stored record
    that cannot be read, naming the study, which record and what is wrong."""
    found, unread = [], []
    for index, entry in enumerate(data):
        try:
            found.append((index, cohort.from_dict(entry)))
        except ValueError as exc:
            name = entry.get("name") if isinstance(entry, dict) else None
            who = f" ({name})" if isinstance(name, str) and name.strip() else ""
            found.append((index, None))
            unread.append(f"{study.Label}: stored record {index + 1} of {len(data)}{who} cannot be read: "
                          f"{str(exc).removeprefix('not a participant record: ')}")
    return found, unread


def records(study):
    """The participants' records (cohort.Record), oldest first. Raises ValueError, naming
    the study, the record and what is wrong, when one cannot be read (a hand-edited
    document): what is written back from these must lose none (readable_records reads
    the others)."""
    found, unread = _read(study, _stored(study))
    if unread:
        raise ValueError(unread[0] + (f" (and {len(unread) - 1} more)" if len(unread) > 1 else ""))
    return [r for _, r in found]


def readable_records(study):
    """(the records that can be read, oldest first; a sentence naming each stored record
    that cannot, left out): for summarising a cohort a hand-edited record broke. Raises
    ValueError naming the study when the stored cohort is not readable at all."""
    found, unread = _read(study, _stored(study))
    return [r for _, r in found if r is not None], unread


def _write_records(study, kept):
    study.Cohort = json.dumps([r.as_dict() for r in kept])
    study.Participants = cohort.count_participants(kept)


def comparable_records(study):
    """The records in the unit the study records in now (a study switched from a beam
    to a button keeps its beam records, but they are not compared with button ones).
    A stored record that cannot be read is left out (readable_records names it)."""
    _, unit = design_value(study)
    return [r for _, r in _read(study, _stored(study))[0] if r is not None and r.unit == unit]


def comparable_indices(study):
    """Where comparable_records lie among all the records (for remove_record)."""
    _, unit = design_value(study)
    return [i for i, r in _read(study, _stored(study))[0] if r is not None and r.unit == unit]


def record_preference(study, name, gender, age_band, weight_kg, height_mm, device_max_stiffness_n_per_m=None,
                      force_limit_n=None):
    """Keeps a participant's preference for the design as it is now. With the device's
    stable stiffness, a design beyond it is marked (the participant felt less than it);
    with the session's force limit (N), a button whose operating force is above it is
    marked (its click was never felt: cohort.beyond_force_limit), and the limit kept. Each
    limit is None when not known, else a finite number > 0. Raises ValueError, keeping
    nothing, if the record, a limit or the study is not valid (a design outside the
    slider's range is not refused: outside_slider)."""
    if not isinstance(name, str):
        raise ValueError(f"{study.Label}: name must be text (the participant's name or alias), got {name!r}")
    for label, limit, unit in (("device_max_stiffness_n_per_m", device_max_stiffness_n_per_m, "N/m"),
                               ("force_limit_n", force_limit_n, "N")):
        # a NaN or negative limit was kept, starred, and printed as "(nan N, -1 N)"
        if limit is not None and not (isinstance(limit, numbers.Real) and type(limit).__name__ not in
                                      ("bool", "bool_") and math.isfinite(limit) and limit > 0):
            raise ValueError(f"{study.Label}: {label} = {limit!r} must be a finite number > 0 ({unit}), or None "
                             "when not known")
    wrong = law_problems(study) + slider_problems(study)
    if wrong:
        raise ValueError(f"{study.Label}: {'; '.join(wrong)}")
    value, unit = design_value(study)
    kept = design(study)
    if device_max_stiffness_n_per_m is not None:
        kept["DeviceStiffness"] = float(device_max_stiffness_n_per_m) * MM  # N/mm
        kept["BeyondDevice"] = float(bool(device_note(study, device_max_stiffness_n_per_m)))
    if force_limit_n is not None:  # as the stiffness limit is kept: what the session rendered at most
        kept["ForceLimit"] = float(force_limit_n)  # N
        kept["BeyondForceLimit"] = float(bool(force_note(study, force_limit_n)))
    given = [None if v is None else float(v) for v in (weight_kg, height_mm)]  # None: not given
    record = cohort.Record(name.strip(), gender, age_band, *given, float(value), unit,
                           study.Model, kept, datetime.now().isoformat(timespec="seconds"))
    wrong = cohort.problems(record)
    if wrong:
        raise ValueError("; ".join(wrong))
    _write_records(study, [*records(study), record])
    return record


def remove_record(study, index):
    """Removes the record at ``index`` (of records) on purpose: the journal never offers it
    back as lost (study_journal.removing; an Undo of the removal holds it again). Raises
    ValueError if there is none."""
    kept = records(study)
    if not 0 <= index < len(kept):
        raise ValueError(f"{study.Label}: no participant {index + 1} (it has {len(kept)})")
    study_journal.removing(study, kept.pop(index))
    _write_records(study, kept)


def add_records(study, more):
    """Adds ``more`` (cohort.Record) after the study's records, as they are: records made
    before (put back from study_journal.lost), not judged again. Raises ValueError, adding
    none, if the stored cohort cannot be read."""
    _write_records(study, [*records(study), *more])


def others_note(study):
    """What the records not compared now (comparable_records) are, naming what differs,
    as a sentence without its full stop, or "": "4 recorded while the slider moved the
    operating force (N) are kept but not compared ...", "3 made with the bending beam
    model (N/mm) ..."."""
    held, _ = readable_records(study)  # what is summarised beside it
    _, unit = design_value(study)
    counts = {}
    for r in held:
        if r.unit != unit:
            counts[r.unit] = counts.get(r.unit, 0) + 1
    if not counts:
        return ""
    parts = []
    for other, count in counts.items():
        label, model = UNIT_SOURCES.get(other, (other, None))
        if model == study.Model:  # the same mechanism: the slider moved another parameter
            parts.append(f"{count} recorded while the slider moved the {label}" + (f" ({other})" if other != label
                                                                                 else ""))
        elif model is not None:
            parts.append(f"{count} made with the {model.lower()} model ({other})")
        else:
            parts.append(f"{count} in {other}")
    total = sum(counts.values())
    return (f"{', '.join(parts)} {'is' if total == 1 else 'are'} kept but not compared with the "
            f"{UNIT_SOURCES[unit][0]}; the study's Participants ({study.Participants}) counts everyone with a "
            "record, of any unit")


class Imported(tuple):
    """What import_records did: the tuple (added, already held, repeated in the file), and
    ``retimed``, how many of the held were recognised by their time to the precision the
    file gives it (a spreadsheet's re-save rewrites "2026-11-24T15:17:03" as "2026-11-24
    15:17"), and ``read_as``, how the file was read ("" for commas, else "semicolon-
    separated, with decimal commas": cohort.read_csv_as_read)."""

    def __new__(cls, added, held, repeated, retimed=0, read_as=""):
        made = super().__new__(cls, (added, held, repeated))
        made.retimed, made.read_as = retimed, read_as
        return made


def import_records(study, path):
    """Adds the records of a cohort CSV that the study does not hold yet (cohort.same_record:
    every field alike, the time to the precision the file gives), each once; returns
    Imported: (added, already held, repeated in the file), with how many held were
    recognised by a rewritten time and how the file was read. Records in a unit the study
    does not compare now are kept as its own are (others_note): those its model records
    (a button's operating force or snap ratio) or that it holds already (made before its
    model changed), so its own export comes back whole. Raises ValueError, adding none, on
    a bad line, on records of a unit this study neither records nor holds (a beam's cohort
    into a button study), or on stiffnesses that read as N/m given as N/mm (per_m_problem)."""
    read, read_as = cohort.read_csv_as_read(path)
    held = records(study)
    _, unit = design_value(study)
    known = {u for u, (_, model) in UNIT_SOURCES.items() if model == study.Model} | {r.unit for r in held}
    other = [r for r in read if r.unit not in known]
    if other:
        label, model = UNIT_SOURCES.get(other[0].unit, (None, None))
        of = f" (a {model.lower()}'s {label})" if model else ""
        raise ValueError(f"{path}: {len(other)} record(s) are in {other[0].unit}{of}, this study's preferences "
                         f"in {unit}")
    per_m = per_m_problem(study, [r for r in read if not any(cohort.same_record(r, h) for h in held)])
    if per_m:
        raise ValueError(f"{path}: {per_m}")

    def key(r):  # same_record compares within these (numbers with a tolerance, times to a precision)
        return r.name, r.unit

    held_by_key, seen_by_key = {}, {}
    for r in held:
        held_by_key.setdefault(key(r), []).append(r)
    added, repeated, retimed = [], 0, 0
    for r in read:
        seen = seen_by_key.setdefault(key(r), [])
        same = [h for h in held_by_key.get(key(r), ()) if cohort.same_record(r, h)]
        if any(cohort.same_record(r, s) for s in seen):  # a row listed twice (a merged file): one
            repeated += 1
        elif not same:
            added.append(r)
        elif all(h.recorded != r.recorded for h in same):  # held, its time as a spreadsheet rewrote it
            retimed += 1
        seen.append(r)
    _write_records(study, [*held, *added])
    return Imported(len(added), len(read) - len(added) - repeated, repeated, retimed, read_as)


# A stiffness written in N/m under an N/mm unit reads 1000 times too stiff, and up to 1000
# (a 1 N/mm neck) passes cohort.PREFERENCE_RANGES. Such a value is told from a stiffness of
# the study's product by how far it lies above the stiffest design the study makes (its
# slider's range, its design now, what it holds): 30 times, the middle on a log scale of
# the factor 1000 (sqrt(1000) = 32). A cohort of the product in N/mm lies within the
# slider's reach give or take what another setup of it makes (seed 000 Table 3's necks,
# 3.5-4.5 N/mm, and the field notes' toothbrush, 0.56 N/mm, are a factor 8 apart), far
# under 30 times its stiffest; the stiffest device of the field notes renders 3 N/mm. One
# in N/m lies 1000 times above its own values, so above 30 times the stiffest for each
# value over 1/33 of it: a toothbrush slider over h 2-8 mm makes 0.069-4.4 N/mm, so every
# N/m value of 0.13 N/mm and up is told (400 and 800 for 0.4 and 0.8). A stiffer product's
# cohort is not refused for good: a slider widened to reach it takes it. Records whose
# design holds the value as its BendingStiffness were computed by a study (an export):
# they are what they say.
PER_M_FACTOR = 30.0


def design_reach(study):
    """(lowest, highest) bending stiffness, N/mm, a beam study's slider makes over its
    range, the other parameters as they are now, with the design now; None for a button,
    or when the law cannot be made."""
    if study.Model != BEAM:
        return None
    values = {name: float(getattr(study, name)) for name in ("YoungsModulus", "BeamWidth", "BeamThickness",
                                                              "BeamLength")}
    found = [float(study.BendingStiffness)]
    if study.Adjust in values and float(study.AdjustMin) < float(study.AdjustMax):
        for end in (float(study.AdjustMin), float(study.AdjustMax)):
            at = {**values, study.Adjust: end}
            try:
                found.append(_core.cantilever_stiffness(at["YoungsModulus"] * 1e9, at["BeamWidth"] * MM,
                                                        at["BeamThickness"] * MM, at["BeamLength"] * MM) * MM)
            except ValueError:  # an end the law refuses (a length of 0): slider_problems says so
                pass
    found = [k for k in found if math.isfinite(k) and k > 0]
    return (min(found), max(found)) if found else None


def per_m_problem(study, read):
    """A sentence when stiffnesses among ``read`` (cohort.Record, given as N/mm) read as
    N/m (PER_M_FACTOR times the stiffest the study makes or holds, and their design does
    not hold them as its BendingStiffness), else ""."""
    reach = design_reach(study)
    if reach is None:
        return ""
    held = [r.value for r in records(study) if r.unit == "N/mm" and isinstance(r.value, (int, float))
            and math.isfinite(r.value)]
    stiffest = max([reach[1], *held])
    suspect = [r for r in read if r.unit == "N/mm" and r.value > PER_M_FACTOR * stiffest
               and not _computed_by_a_study(r)]
    if not suspect:
        return ""
    label, unit = adjust_info(study)
    shown = ", ".join(f"{r.name} {r.value:g}" for r in suspect[:5]) + (f" and {len(suspect) - 5} more"
                                                                      if len(suspect) > 5 else "")
    as_n_per_mm = ", ".join(f"{r.value / 1000:.3g}" for r in suspect[:5]) + (", ..." if len(suspect) > 5 else "")
    many = len(suspect) != 1
    they, are = ("they", "are") if many else ("it", "is")
    return (f"{cohort.plural(len(suspect), 'preference')} given in N/mm ({shown}) {are} over {PER_M_FACTOR:g} "
            f"times the stiffest this study makes or holds ({stiffest:.3g} N/mm; its slider over the {label} "
            f"{study.AdjustMin:g}-{study.AdjustMax:g} {unit} makes {reach[0]:.3g}-{reach[1]:.3g} N/mm): {are} "
            f"{they} in N/m? As N/mm {they} {are} {as_n_per_mm}: divide the value column by 1000 and import again "
            f"(if {they} {are} N/mm, widen the slider's range to reach {'them' if many else 'it'})")


def _computed_by_a_study(record):
    """Whether a record's design holds its value as the BendingStiffness a study computed."""
    try:
        return math.isclose(float(record.design.get("BendingStiffness")), record.value, rel_tol=1e-9)
    except (TypeError, ValueError):
        return False


# the unit each constrained property is in (its tooltip's), for what is typed into it
UNITS = {"YoungsModulus": "GPa", "BeamWidth": "mm", "BeamThickness": "mm", "BeamLength": "mm", "OperatingForce": "N",
         "Pretravel": "mm", "SnapRatio": "", "SnapTravel": "mm", "TotalTravel": "mm", "HousingStiffness": "N/mm"}
# gram- and kilogram-force, as switch datasheets give operating forces (Omron B3F: 100 gf)
_FORCE_UNITS = ((re.compile(r"(?<![A-Za-z])kgf\b"), "*9.80665 N"), (re.compile(r"(?<![A-Za-z])gf\b"), "*9.80665 mN"))


def typed_value(name, text, label=None):
    """What ``text`` typed for the property ``name`` (or the slider's range over it) is,
    in the property's unit (UNITS), read as FreeCAD reads a quantity: "6 cm" is 60 mm,
    "1500 MPa" 1.5 GPa, "4,5" 4.5 (a decimal comma), a number alone in the property's
    unit; "150 gf" is 1.47 N. Raises ValueError with a sentence when it is not a value of
    that kind or is outside the property's range: nothing is to be set then."""
    from .quantity_text import read_quantity

    unit = UNITS[name]
    label = label or name

    def force_units(typed):  # units FreeCAD does not know, for a force
        for pattern, replacement in _FORCE_UNITS:
            typed = pattern.sub(replacement, typed)
        return typed

    value = read_quantity(text, unit, label, rewrite=force_units if unit == "N" else None)
    low, high = next(p[5][:2] for p in PROPERTIES if p[0] == name)
    if not low <= value <= high:
        hint = ""
        alone = App.Units.Quantity(" ".join(text.split())).Unit == App.Units.Quantity(1.0).Unit
        if name == "YoungsModulus" and low <= value / 1000 <= high and alone:
            hint = f": in MPa? give {value:g} MPa"  # a number alone is in GPa
        raise ValueError(f"{label}: {value:g}{' ' + unit if unit else ''} is outside {low:g}..{high:g}"
                         f"{' ' + unit if unit else ''}{hint}")
    return value


def slider_ends(study):
    """(low end, high end): what moving the slider that way does to the design."""
    return SLIDER_ENDS.get(study.Adjust, ("", ""))


def adjust_info(study):
    """(label, unit) of the parameter the slider moves."""
    label, unit, _ = ADJUSTABLE[study.Model].get(study.Adjust, (study.Adjust, "", None))
    return label, unit


def expression_of(obj, prop):
    """The expression bound to ``obj``'s property ``prop`` (``"Spreadsheet.h"``), or None.
    Nothing but the expression can set a bound property: the next recompute sets it back."""
    return next((expression for path, expression in obj.ExpressionEngine if path.lstrip(".") == prop), None)


def adjust_expression(study):
    """The expression bound to the parameter the slider moves, or None."""
    return expression_of(study, study.Adjust)


# what setting a property sets of others (StiffnessStudy.onChanged), in the order make_study
# sets them, each before what it sets, so that every value given stays as given: the model
# the slider's parameter (Adjust) when it does not use it, and with it the slider's range;
# the material the modulus; the slider's parameter its range (AdjustMin, AdjustMax)
SETS_OTHERS = ("Model", "BeamMaterial", "Adjust")
# what make_study does not take as a property, and why
NOT_GIVEN = {"Surface": "give the surface as make_study's second argument",
             "BendingStiffness": "it is computed from YoungsModulus, BeamWidth, BeamThickness and BeamLength",
             "Participants": "it counts the participants recorded"}


def make_study(doc, surface, model=None, name="StiffnessStudy", **properties):
    """A study of how ``surface`` (a haptic surface, or its name or label) gives, of
    ``model`` (MODELS; a bending beam when not given; ``Model=`` is the same). Properties
    may be given by name, in their units (PROPERTIES' tooltips), in any order: each ends
    up as given (SETS_OTHERS are set first). Raises ValueError on bad input (an unknown or
    computed property, a value outside a property's range, a slider parameter the model
    does not use), adding nothing."""
    from .surface_object import attach_view_provider, is_haptic_surface

    if isinstance(surface, str):
        surface = doc.getObject(surface) or next(iter(doc.getObjectsByLabel(surface)), None)
    if surface is None or not is_haptic_surface(surface) or surface.Document != doc:
        raise ValueError("make_study: give a haptic surface of this document")
    properties = dict(properties)
    if "Model" in properties:
        if model is not None and model != properties["Model"]:
            raise ValueError(f"make_study: model {model!r} and Model {properties['Model']!r} differ: give one")
        model = properties.pop("Model")
    model = BEAM if model is None else model
    if model not in MODELS:
        raise ValueError(f"make_study: model {model!r} is not one of {', '.join(MODELS)}")
    existing = study_of(surface)
    if existing is not None:
        raise ValueError(f"make_study: {surface.Label} is already studied by {existing.Label}")
    unknown = [k for k in properties if k not in {p[0] for p in PROPERTIES}]
    if unknown:
        raise ValueError(f"make_study: unknown properties {', '.join(unknown)}")
    computed = [f"{k} ({why})" for k, why in NOT_GIVEN.items() if k in properties]
    if computed:
        raise ValueError(f"make_study: not to be given: {'; '.join(computed)}")
    wrong = _given_problems(model, properties)
    if wrong:
        raise ValueError(f"make_study: {'; '.join(wrong)}")
    obj = doc.addObject("App::FeaturePython", name)
    StiffnessStudy(obj)
    obj.Surface = surface
    obj.Model = model
    try:
        # what sets others first, in SETS_OTHERS' order; the rest as given (a stable sort)
        for key, value in sorted(properties.items(), key=lambda item: SETS_OTHERS.index(item[0])
                                 if item[0] in SETS_OTHERS else len(SETS_OTHERS)):
            setattr(obj, key, value)
        changed = [f"{key} {value!r} became {getattr(obj, key)!r}" for key, value in properties.items()
                   if not _holds(getattr(obj, key), value)]
        if changed:  # the order above keeps them all: a safety net, never silent
            raise ValueError(", ".join(changed))
    except Exception as exc:  # a value the property refuses: no half-made study
        doc.removeObject(obj.Name)
        raise ValueError(f"make_study: {exc}") from None
    attach_view_provider(obj)
    obj.recompute()
    return obj


def _given_problems(model, properties):
    """What is wrong with values given to make_study, as sentences: a number that is not
    finite or is outside its property's range (FreeCAD would clamp it, unsaid), a slider
    parameter the model does not use."""
    found = []
    for name, _, _, _, _, constraint in PROPERTIES:
        if name not in properties or not isinstance(properties[name], (int, float)):
            continue  # not given, or not a number: the property refuses it when set
        value = float(properties[name])
        unit = f" {UNITS[name]}" if UNITS.get(name) else ""
        if not math.isfinite(value):
            found.append(f"{name} {value} is not a finite number")
        elif constraint is not None and not constraint[0] <= value <= constraint[1]:
            found.append(f"{name} {value:g}{unit} is outside {constraint[0]:g}..{constraint[1]:g}{unit}")
    adjust = properties.get("Adjust")
    if adjust is not None and adjust not in ADJUSTABLE[model]:
        found.append(f"the {model.lower()} model's slider moves {', '.join(ADJUSTABLE[model])}, not {adjust!r}")
    return found


def _holds(now, given):
    """Whether a property reads back as given (numbers to a relative 1e-12)."""
    if isinstance(given, (int, float)) and isinstance(now, (int, float)):
        return math.isclose(float(now), float(given), rel_tol=1e-12, abs_tol=1e-300)
    return now == given
