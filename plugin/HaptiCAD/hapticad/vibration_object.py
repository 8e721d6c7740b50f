# SPDX-License-Identifier: GPL-3.0-or-later
"""The HapticVibration document object: a part that vibrates when powered.

Seed 000 lets a designer "feel the vibration while an electronic razor is powered on".
A HapticVibration links one part (``App::PropertyLinkGlobal``) and holds its
``Frequency`` (Hz), ``Amplitude`` (N), ``Axis`` and ``Powered``; while the probe touches
any face of that part, the force carries amplitude * sin(2 pi f t) along the axis.
Created with :func:`make_vibration`. App-only.

The axis belongs to the part, as a circular pattern's centre does to its surface's part
(surface_object.record_pattern_anchor): ``Axis`` is shown in global coordinates, and the
hidden ``AxisAnchor`` keeps it in the part's own frame, so that it turns with the part
(its own placement, or that of a Body or App::Part holding it). A razor head shaking
along its blade shakes along it wherever the assembly turns it.

Deleting the part empties ``Part`` before the part goes (FreeCAD breaks the links to
it); the hidden ``DeletedPart`` keeps its name and label, so the vibration can say which
part it lost and how to mend it (undo the deletion, link another part, or delete it),
also after saving and reopening. The vibration stays, as a surface on a deleted part
does: Std_Delete lists it as "might break", and Undo brings the link back.
"""
import json
import math
import numbers

import FreeCAD as App

from .proxy_state import SchemaState, add_hidden_state, add_type_tag, is_restoring

TYPE = "HaptiCAD::HapticVibration"
# 2: DeletedPart (added empty when an older document opens)
# 3: AxisAnchor (recorded from the Axis as saved when an older document opens: felt as
#    before, and from then on turning with the part)
SCHEMA_VERSION = 3
FREQUENCY_RANGE_HZ = (1.0, 1000.0)  # what a servo loop up to 10 kHz can render
AMPLITUDE_RANGE_N = (0.0, 10.0)  # up to what a strong device renders: force_note says what a weaker one does
# How hard a hand feeling a part presses it, N: a firm touch. The vibration rides on this
# push, and the two together must stay within the session's force limit (force_note).
TYPICAL_PUSH_N = 1.0
ZERO_AXIS = "the vibration axis cannot be zero; kept +Z"
AXIS_TIP = ("Direction of the vibration, in global coordinates where the part stands now: it turns with the "
            "part (its placement, its Body's or App::Part's)")


class HapticVibration(SchemaState):
    """Proxy of a HapticVibration object."""

    SCHEMA = SCHEMA_VERSION

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj, new=True)

    def setup(self, obj, new=False):
        def add(kind, name, group, tip):
            if name not in obj.PropertiesList:
                obj.addProperty(kind, name, group, tip)
                return True
            return False

        add_type_tag(obj, TYPE)
        add_hidden_state(obj, [("DeletedPart", "The part that vibrated and was deleted, name and label (JSON)"),
                               ("AxisAnchor", "The axis in the frame of the part it turns with, and its name (JSON)")])
        add("App::PropertyLinkGlobal", "Part", "Vibration", "The part that vibrates")
        add("App::PropertyBool", "Powered", "Vibration", "Whether the part is switched on")
        if add("App::PropertyFloatConstraint", "Frequency", "Vibration", "Vibration frequency, Hz"):
            obj.Frequency = 100.0
        if add("App::PropertyFloatConstraint", "Amplitude", "Vibration", "Force amplitude, N"):
            obj.Amplitude = 0.3
        if add("App::PropertyVector", "Axis", "Vibration", AXIS_TIP):
            obj.Axis = App.Vector(0, 0, 1)
        obj.setDocumentationOfProperty("Axis", AXIS_TIP)  # a document keeps the tooltip it was saved with
        if new:
            obj.Powered = True
        obj.Frequency = (obj.Frequency, *FREQUENCY_RANGE_HZ, 10.0)
        obj.Amplitude = (obj.Amplitude, *AMPLITUDE_RANGE_N, 0.05)

    def onBeforeChange(self, obj, prop):
        # deleting a part empties Part before the part goes: its label is only known here
        if prop == "Part" and not is_restoring(obj):
            self._part_before = (obj.Part.Name, obj.Part.Label) if obj.Part is not None else None

    def onChanged(self, obj, prop):
        if prop == "Part" and "DeletedPart" in obj.PropertiesList and not is_restoring(obj):
            before, self._part_before = getattr(self, "_part_before", None), None
            if obj.Part is None and before is not None:
                text = json.dumps({"name": before[0], "label": before[1]})
            else:
                text = ""  # linked to a part again (or never linked): nothing lost
            if text != obj.DeletedPart:
                obj.DeletedPart = text
        if prop == "Part" and "AxisAnchor" in obj.PropertiesList and not is_restoring(obj):
            # another part (or none): the axis stays where it was felt, then turns with this one
            follow_axis_anchor(obj)
            record_axis_anchor(obj)
        if prop == "Axis" and "Restore" not in obj.State and obj.Axis.Length == 0:
            App.Console.PrintError(f"{obj.Label}: {ZERO_AXIS}\n")
            obj.Axis = App.Vector(0, 0, 1)
        elif (prop == "Axis" and "AxisAnchor" in obj.PropertiesList and not is_restoring(obj)
              and _differs(obj.Axis, axis_where_felt(obj))):
            record_axis_anchor(obj)  # an axis given, not the one the part's turn gave it

    def onDocumentRestored(self, obj):
        self.setup(obj)
        if not obj.AxisAnchor:
            # saved before the axis turned with its part: anchored as saved, so felt as before
            record_axis_anchor(obj)
        else:
            reanchor_copy(obj)
        from .surface_object import attach_view_provider

        attach_view_provider(obj)
        obj.purgeTouched()

    def mustExecute(self, obj):
        # a Body or App::Part that turned the part recomputes only itself: run to follow it
        try:
            return _differs(axis_where_felt(obj), obj.Axis)
        except Exception:  # noqa: BLE001 (an object half deleted or restored: nothing to follow)
            return False

    def execute(self, obj):
        follow_axis_anchor(obj)
        problems = validate(obj)
        if problems:
            App.Console.PrintError(f"{obj.Label}: {'; '.join(problems)}\n")


def _differs(a, b):
    """Two axes apart by more than rounding (of any length: the property editor takes any)."""
    return (a - b).Length > 1e-12 * max(1.0, b.Length)


def _anchor(obj):
    """(part, axis in its frame) that ``obj``'s AxisAnchor names, or None (no anchor, or
    its part is gone)."""
    try:
        state = json.loads(obj.AxisAnchor) if getattr(obj, "AxisAnchor", "") else None
        part = obj.Document.getObject(state["object"]) if state else None
        axis = App.Vector(*(float(a) for a in state["axis"])) if part is not None else None
    except (ValueError, KeyError, TypeError):
        return None
    return (part, axis) if part is not None else None


def record_axis_anchor(obj):
    """Keeps ``obj``'s Axis in its part's frame, so that it turns with the part."""
    from .surface_object import _global_placement

    state = ""
    if obj.Part is not None:
        local = _global_placement(obj.Part).Rotation.inverted().multVec(obj.Axis)
        state = json.dumps({"object": obj.Part.Name, "axis": [local.x, local.y, local.z]}, sort_keys=True)
    if state != obj.AxisAnchor:
        obj.AxisAnchor = state


def axis_where_felt(obj):
    """``obj``'s axis, global, where its part stands now: what the probe feels (Axis
    when it has no anchor). Axis lags behind it while nothing recomputes the vibration."""
    from .surface_object import _global_placement

    anchored = _anchor(obj)
    if anchored is None:
        return App.Vector(obj.Axis)
    part, local = anchored
    return _global_placement(part).Rotation.multVec(local)


def follow_axis_anchor(obj):
    """Turns Axis with the part it is anchored to."""
    axis = axis_where_felt(obj)
    if _differs(axis, obj.Axis):
        obj.Axis = axis


def reanchor_copy(obj):
    """A vibration copied with its part (Edit > Duplicate selection) shakes the copy but
    was anchored to the original, and turned with it. The copy's frame is the original's:
    the same axis in it is anchored to the copy."""
    try:
        state = json.loads(obj.AxisAnchor)
        named = state["object"]
    except (ValueError, KeyError, TypeError):
        return
    if obj.Part is None or named == obj.Part.Name:
        return
    state["object"] = obj.Part.Name
    obj.AxisAnchor = json.dumps(state, sort_keys=True)
    follow_axis_anchor(obj)


def faceless_note(part):
    """"" when ``part`` has faces the scene feels, else why a vibration on it is felt
    nowhere: it has no faces, or it is a link (the scene holds the parts themselves, not
    links to them; a surface cannot tag a link's faces either)."""
    linked = part.getLinkedObject(True) if part.isDerivedFrom("App::Link") else None
    if linked is not None and linked is not part:
        return (f"{part.Label} is a link to {linked.Label}: a link cannot vibrate yet (Feel holds the parts "
                f"themselves, not links to them); make {linked.Label} vibrate")
    if part.Shape.Faces:
        return ""
    return (f"{part.Label} has no faces, so the probe touches nothing of it: make a solid or a surface "
            "vibrate")


def deleted_part(obj):
    """Label of the part ``obj`` vibrated until it was deleted, or "" (it has its part,
    was never linked, or the part is in the document still: only unlinked)."""
    try:
        entry = json.loads(obj.DeletedPart) if getattr(obj, "DeletedPart", "") else {}
    except ValueError:
        entry = {}
    if not isinstance(entry, dict) or obj.Part is not None:
        return ""
    if obj.Document.getObject(str(entry.get("name"))) is not None:
        return ""
    return str(entry.get("label", ""))


def no_part_note(obj):
    """Why ``obj`` vibrates nothing, naming the deleted part and the ways to mend it; ""
    while it has a part."""
    if obj.Part is not None:
        return ""
    mend = f"link a part in its Part property (Data tab) or delete {obj.Label}"
    deleted = deleted_part(obj)
    if deleted:
        return f"no part to vibrate: {deleted}, which it vibrated, was deleted; undo the deletion, {mend}"
    return f"no part to vibrate: {mend}"


def validate(obj):
    """Problems with a vibration's current values, as sentences (empty when fine)."""
    problems = []
    if obj.Part is None:
        problems.append(no_part_note(obj))
    elif not hasattr(obj.Part, "Shape") or obj.Part.Shape.isNull():
        problems.append(f"{obj.Part.Label} has no shape to vibrate")
    elif faceless_note(obj.Part):
        problems.append(faceless_note(obj.Part))
    axis = [obj.Axis.x, obj.Axis.y, obj.Axis.z]
    if not all(math.isfinite(a) for a in axis):
        problems.append(f"the axis {tuple(axis)} is not three finite numbers")
    if obj.Part is not None and any(v is not obj and v.Part == obj.Part for v in vibrations_of(obj.Document)):
        problems.append(f"{obj.Part.Label} has another vibration: a part vibrates one way (delete one)")
    return problems


def vibration_of(part):
    """The HapticVibration that makes ``part`` vibrate, or None."""
    for v in vibrations_of(part.Document):
        if v.Part == part:
            return v
    return None


def is_haptic_vibration(obj):
    return getattr(obj, "HaptiCADType", None) == TYPE


def vibrations_of(doc):
    """The HapticVibration objects of a document. Raises ValueError when ``doc`` is not one."""
    from .surface_object import require_document

    require_document(doc, "vibrations_of")
    return [o for o in doc.Objects if is_haptic_vibration(o)]


# under this share of the servo rate a vibration's samples meet its peaks every cycle: the
# largest sample of each cycle stays within 5 % of the amplitude up to a quarter of the
# rate (0.955 at 250 Hz under 1 kHz), and falls to 0.82 at 300 Hz and 0.32 at 450 Hz
EVEN_SHARE = 0.25


def rate_note(vibration, rate_hz, where="in Preferences"):
    """What a servo loop at ``rate_hz`` makes of ``vibration``'s frequency: "" when it
    renders it evenly (under EVEN_SHARE of the rate), else what is felt. From a quarter to
    half the rate its few samples a cycle meet its peaks in some cycles and miss them in
    others: at 1 kHz a 450 Hz vibration's size beats at 100 Hz. At or above half the rate
    the force's samples alias: at 1 kHz a 0.5 N vibration at 700 Hz was felt at 300 Hz, at
    500 or 1000 Hz not at all (sampled at its zero crossings, or once a cycle). ``where``
    says where the rate is set."""
    f = float(vibration.Frequency)
    if f < EVEN_SHARE * rate_hz or not vibration.Powered:
        return ""
    if f < 0.5 * rate_hz:  # rendered, but with few samples a cycle its peaks are hit or missed
        return (f"{vibration.Label}: {f:g} Hz gets {rate_hz / f:.2g} samples a cycle at the {rate_hz:g} Hz servo "
                f"rate, so its size swings from cycle to cycle (a beat, not an even buzz); keep it under "
                f"{EVEN_SHARE * rate_hz:g} Hz or raise the servo rate {where}")
    alias = abs(f - rate_hz * round(f / rate_hz))
    felt = (f"felt at {alias:.0f} Hz instead" if 0 < alias < 0.5 * rate_hz
            else "not felt at all")
    return (f"{vibration.Label}: {f:g} Hz is {felt} at the {rate_hz:g} Hz servo rate; keep it under "
            f"{0.5 * rate_hz:g} Hz (half the rate) or raise the servo rate {where}")


def rate_notes(doc, rate_hz, where="in Preferences"):
    """rate_note of every vibration of doc that a loop at ``rate_hz`` cannot render."""
    return [n for n in (rate_note(v, rate_hz, where) for v in vibrations_of(doc)) if n]


def force_note(vibration, force_limit_n):
    """What a session's force limit (``force_limit_n``, N) makes of ``vibration``: "" when
    its amplitude on a typical push (TYPICAL_PUSH_N) stays within the limit, else what is
    felt instead. Not a problem with the vibration: a stronger device, or a higher limit,
    renders it. The force is cut at the limit as a whole, so the vibration's peaks are
    flattened and, once it alone reaches the limit, it is a square wave at the limit in
    which the part's push is no longer felt. A face only pushes: where the vibration
    would pull the probe into the part, nothing is felt (force_renderer.h)."""
    amplitude, limit = float(vibration.Amplitude), float(force_limit_n)
    if not vibration.Powered or amplitude <= 0 or amplitude + TYPICAL_PUSH_N <= limit:
        return ""
    if amplitude >= limit:
        felt = (f"alone it reaches the {limit:g} N force limit: it is felt as a square wave at the limit and "
                "the part's push is lost in it")
    else:
        felt = (f"on a typical {TYPICAL_PUSH_N:g} N push it passes the {limit:g} N force limit, which cuts "
                "its peaks")
    room = limit - TYPICAL_PUSH_N
    keep = f"keep the amplitude under {room:g} N or raise" if room > 0 else "raise"
    return (f"{vibration.Label}: {amplitude:g} N {felt}; {keep} the force limit in HaptiCAD's Preferences "
            "(as far as the device gives)")


def force_notes(doc, force_limit_n):
    """force_note of every vibration of doc that a session limited to ``force_limit_n``
    (N) cuts."""
    return [n for n in (force_note(v, force_limit_n) for v in vibrations_of(doc)) if n]


def _is_number(value):
    """A real number (numpy's too), not a bool nor a string."""
    return isinstance(value, numbers.Real) and type(value).__name__ not in ("bool", "bool_")


def _part_argument(doc, part):
    """The part ``part`` names (an object of ``doc`` or its name) whose faces can vibrate.
    Raises ValueError naming what it is instead."""
    from .surface_object import is_haptic_surface, reference_pairs, shown

    if isinstance(part, str):
        found = doc.getObject(part)
        if found is None:
            raise ValueError(f"make_vibration: document {doc.Name} has no object {part!r}")
        part = found
    if not isinstance(part, App.DocumentObject):
        raise ValueError(f"make_vibration: part = {part!r} is neither a part of document {doc.Name} nor its name")
    if is_haptic_surface(part):
        tagged = ", ".join(dict.fromkeys(o.Label for o, _ in reference_pairs(part)))
        raise ValueError(f"make_vibration: part {part.Label} is a haptic surface, not a part: give the part "
                         f"whose faces vibrate{f' ({tagged})' if tagged else ''}")
    if getattr(part, "HaptiCADType", None):
        raise ValueError(f"make_vibration: part {shown(part)} is a HaptiCAD {part.HaptiCADType.split('::')[-1]}, "
                         "not a part")
    if part.Document != doc or not hasattr(part, "Shape"):
        raise ValueError(f"make_vibration: {part.Name} is not a part of document {doc.Name}")
    if faceless_note(part):
        raise ValueError(f"make_vibration: {faceless_note(part)}")
    return part


def _unit_axis(axis):
    """``axis`` (three finite numbers, not all 0) as a unit App.Vector: hypot neither
    overflows on (1e200, 1e200, 0) nor underflows on (1e-300, 0, 0). Raises ValueError."""
    try:
        components = list(axis)
    except TypeError:
        components = []
    if not (len(components) == 3 and all(_is_number(a) and math.isfinite(a) for a in components)):
        raise ValueError(f"make_vibration: axis must be three finite numbers (x, y, z), got {axis!r}")
    length = math.hypot(*(float(a) for a in components))
    if length == 0:
        raise ValueError(f"make_vibration: axis {axis!r} must be a non-zero vector")
    return App.Vector(*(float(a) / length for a in components))


def make_vibration(doc, part, frequency_hz=100.0, amplitude_n=0.3, axis=(0.0, 0.0, 1.0), powered=True,
                   name="HapticVibration"):
    """Makes ``part`` (an object of ``doc`` with faces, or its name) vibrate when touched
    and powered: ``frequency_hz`` within FREQUENCY_RANGE_HZ, ``amplitude_n`` within
    AMPLITUDE_RANGE_N, along ``axis`` (three numbers; kept as a unit vector). Raises
    ValueError naming the argument on bad input, before anything is added."""
    from .surface_object import attach_view_provider, require_document

    require_document(doc, "make_vibration")
    part = _part_argument(doc, part)
    for label, value, (low, high), unit in (("frequency_hz", frequency_hz, FREQUENCY_RANGE_HZ, "Hz"),
                                            ("amplitude_n", amplitude_n, AMPLITUDE_RANGE_N, "N")):
        if not _is_number(value):
            raise ValueError(f"make_vibration: {label} must be a number ({unit}), got {value!r}")
        if not low <= value <= high:
            raise ValueError(f"make_vibration: {label} = {value!r} is outside {low}..{high} {unit}")
    unit_axis = _unit_axis(axis)
    # True or False, or what scripts write for them (1 and 0, numpy's booleans)
    if not (type(powered).__name__ in ("bool", "int", "bool_") and powered in (0, 1)):
        raise ValueError(f"make_vibration: powered must be True or False, got {powered!r}")
    if not isinstance(name, str) or not name:
        raise ValueError(f"make_vibration: name must be a non-empty string, got {name!r}")
    if vibration_of(part) is not None:
        raise ValueError(f"make_vibration: {part.Label} vibrates already ({vibration_of(part).Label}); "
                         "edit that one")
    obj = doc.addObject("App::FeaturePython", name)
    try:
        HapticVibration(obj)
        obj.Part = part
        obj.Frequency = float(frequency_hz)
        obj.Amplitude = float(amplitude_n)
        obj.Axis = unit_axis
        obj.Powered = bool(powered)
        attach_view_provider(obj)
    except Exception as exc:  # what a check above missed: nothing is left behind half made
        doc.removeObject(obj.Name)
        raise ValueError(f"make_vibration: {exc}") from exc
    return obj
