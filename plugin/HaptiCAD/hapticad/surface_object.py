# SPDX-License-Identifier: GPL-3.0-or-later
"""The HapticSurface document object: physical surface properties on CAD faces.

A HapticSurface is an ``App::FeaturePython`` whose ``References`` (an
``App::PropertyLinkSubListGlobal``) name the faces it applies to, and whose other
properties say how those faces feel (seed 000 §2, seed 001 eq. 2). Units follow
FreeCAD's: lengths in mm, speeds in mm/s, the contact stiffness in N/mm; texture
parameters in the paper's normalised units. Created with :func:`make_surface`;
App-only (no GUI import), so it works in ``freecadcmd`` and from the ``hapticad`` CLI.
"""
import json
import math
import numbers

import FreeCAD as App

from .proxy_state import SchemaState, add_hidden_state, add_type_tag, is_restoring
from . import curve_references, face_picking, face_references, materials, textures

TYPE = "HaptiCAD::HapticSurface"
# 3: ReferenceState (face signatures and re-match status per reference)
# 4: ReferenceShapes, PatternCurveState, PatternAnchor, TextureScale (all added, and
#    signed from the shapes as saved, when an older document opens)
# 5: DeletedParts (added empty when an older document opens): names a deleted part
SCHEMA_VERSION = 5
PATTERNS = ["None", "Linear", "Circular", "Curve"]
FRICTION_MODELS = ["Velocity (seed 000)", "Friction cone (stick-slip)"]
INTERPOLATIONS = ["Linear (seed 000 eq. 3)", "Friction ellipse"]
CURVE_EVALUATIONS = ["Lookup table", "Exact"]
TEXTURE_SCALES = ["Device force", "Friction level"]
ROUGHNESS_MIN, ROUGHNESS_MAX = 1, 7
# keeps a typed-in zero from making a face infinitely soft; the device caps the top
STIFFNESS_MIN_N_PER_MM = 1e-3
STIFFNESS_MAX_N_PER_MM = 1e3
FRICTION_MAX = 1e3
# the lookup-table size BENCHMARKS.md justifies: below 0.1 degree on smooth sketch curves
DEFAULT_CURVE_TABLE_SIZE = 256
# degrees: a pattern angle is taken modulo a turn, but past this a float's own step is
# degrees wide (1e300 mod 360 is noise): such an angle is a slip, refused
PATTERN_ANGLE_LIMIT_DEG = 1e6
# make_surface's parameters and the properties they set: giving both is ambiguous
PARAMETER_PROPERTIES = {"roughness_category": "RoughnessCategory", "pattern": "Pattern",
                        "pattern_angle_deg": "PatternAngle", "pattern_center_mm": "PatternCenter",
                        "static_friction": "StaticFriction", "dynamic_friction": "DynamicFriction",
                        "stiffness_n_per_mm": "Stiffness"}

# name, type, group, tooltip, default, constraint (min, max, step) for numbers
PROPERTIES = [
    ("References", "App::PropertyLinkSubListGlobal", "Surface", "The faces this surface applies to", None, None),
    ("Material", "App::PropertyEnumeration", "Surface",
     "Material from the haptic database: sets the friction and stiffness below", None, None),
    ("RoughnessCategory", "App::PropertyIntegerConstraint", "Roughness",
     "Surface category 1-7 of seed 000 Table 2 (Ra range, ISO N-grades, grid size)", 3, (1, 7, 1)),
    ("FeelRoughness", "App::PropertyBool", "Roughness",
     "Render the category as a grid texture whose spacing is its ball size", True, None),
    ("RoughnessHeight", "App::PropertyFloatConstraint", "Roughness",
     "Height of the grid's balls as a share of their spacing", 0.05, (0.0, 0.5, 0.01)),
    ("RoughnessFrictionModulation", "App::PropertyFloatConstraint", "Roughness",
     "How much friction rises on the balls and falls between them (0-1)", 0.15, (0.0, 1.0, 0.05)),
    ("StaticFriction", "App::PropertyFloatConstraint", "Friction",
     "Static friction coefficient mu_s against a dry fingertip (along the stripes with a pattern)",
     0.6, (0.0, FRICTION_MAX, 0.05)),
    ("DynamicFriction", "App::PropertyFloatConstraint", "Friction",
     "Dynamic friction coefficient mu_d against a dry fingertip (along the stripes with a pattern)",
     0.5, (0.0, FRICTION_MAX, 0.05)),
    ("Stiffness", "App::PropertyFloatConstraint", "Friction",
     "Contact stiffness to render, N/mm (the device caps it at its own limit)",
     0.8, (STIFFNESS_MIN_N_PER_MM, STIFFNESS_MAX_N_PER_MM, 0.05)),
    ("Damping", "App::PropertyFloatConstraint", "Friction",
     "Viscous damping of pressing in and springing back, N s/m (a soft, lossy feel; the device caps it)",
     0.0, (0.0, 10.0, 0.05)),
    ("FrictionModel", "App::PropertyEnumeration", "Friction",
     "Velocity model of seed 000 (smooth, no stick-slip) or a friction cone on the proxy (stick-slip)",
     None, None),
    ("StickSpeed", "App::PropertyFloatConstraint", "Friction",
     "Below this sliding speed (mm/s) contact counts as static (Baraff's epsilon)", 2.0, (1e-3, 1e3, 0.5)),
    ("TransitionSpeed", "App::PropertyFloatConstraint", "Friction",
     "Width (mm/s) of the smooth step from static to dynamic friction", 2.0, (0.0, 1e3, 0.5)),
    ("StribeckSpeed", "App::PropertyFloatConstraint", "Friction",
     "Stribeck decay speed (mm/s) toward dynamic friction; 0 uses the smooth step", 0.0, (0.0, 1e3, 0.5)),
    ("Pattern", "App::PropertyEnumeration", "Pattern",
     "Anisotropic friction pattern: None, Linear, Circular or Curve", None, None),
    ("PatternAngle", "App::PropertyAngle", "Pattern",
     "Stripe direction: from the face's u direction (at its centre), counter-clockwise about its normal",
     0.0, None),
    ("PatternCenter", "App::PropertyVectorDistance", "Pattern",
     "Circular pattern: centre (mm, global coordinates; moves with the first tagged part)", None, None),
    ("PatternAxis", "App::PropertyVector", "Pattern",
     "Circular pattern: axis of the circles; zero uses the face's normal", None, None),
    ("PatternBlendRadius", "App::PropertyFloatConstraint", "Pattern",
     "Circular pattern: within this radius (mm) of the centre friction fades to isotropic",
     1.0, (1e-3, 1e3, 0.5)),
    ("PatternCurve", "App::PropertyLinkSubGlobal", "Pattern",
     "Curve pattern: the sketch or edge whose parallel copies the stripes follow", None, None),
    ("CurveEvaluation", "App::PropertyEnumeration", "Pattern",
     "Curve pattern: the paper's lookup table, or the exact curve (slower)", None, None),
    ("CurveTableSize", "App::PropertyIntegerConstraint", "Pattern",
     "Curve pattern: entries of the lookup table", DEFAULT_CURVE_TABLE_SIZE, (2, 100000, 16)),
    ("Interpolation", "App::PropertyEnumeration", "Pattern",
     "How friction varies between along and across the stripes", None, None),
    ("AcrossFriction", "App::PropertyFloatConstraint", "Pattern",
     "Friction across the stripes as a multiple of friction along them (mu_n / mu_a)", 1.5, (0.0, 100.0, 0.1)),
    ("BackwardFriction", "App::PropertyFloatConstraint", "Pattern",
     "Friction against the stripe direction as a multiple of friction with it", 1.0, (0.0, 100.0, 0.1)),
    ("Texture", "App::PropertyEnumeration", "Texture",
     "Viscous grating of seed 001 (replaces Coulomb friction): None, a paper preset, or Custom", None, None),
    ("TextureDC", "App::PropertyFloat", "Texture", "f_DC: DC friction level (1 = device's full range)", 0.5, None),
    ("TextureViscosity", "App::PropertyFloat", "Texture", "f_vis: viscous level per 400 mm/s", 0.0, None),
    ("TextureBeta", "App::PropertyFloat", "Texture", "beta_h: harmonic amplitude", 0.125, None),
    ("TextureAlpha", "App::PropertyFloat", "Texture", "alpha_h: harmonic decay exponent", 2.5, None),
    ("TextureBetaViscosity", "App::PropertyFloat", "Texture", "beta_vis: amplitude change per 400 mm/s", 0.0, None),
    ("TextureAlphaViscosity", "App::PropertyFloat", "Texture", "alpha_vis: decay change per 400 mm/s", 0.0, None),
    ("TexturePeriod", "App::PropertyFloatConstraint", "Texture", "Grating period lambda (mm)", 2.5, (1e-3, 1e3, 0.1)),
    ("TextureScale", "App::PropertyEnumeration", "Texture",
     "What level 1 stands for. Device force: a force (Full range, or the device's full range), however "
     "hard you press. Friction level: the face's static friction times how hard you press, as on the "
     "paper's TPad, whose levels set its glass's friction (seed 001 §IV)", None, None),
    ("TextureFullRange", "App::PropertyFloatConstraint", "Texture",
     "Device force: newtons that level 1 stands for; 0 = the device's full range",
     0.0, (0.0, 100.0, 0.1)),
]
# the object's own bookkeeping, JSON in hidden string properties
HIDDEN_STATE = [
    ("ReferenceState", "Per referenced face: its geometric signature and re-match status (JSON)"),
    ("ReferenceShapes", "Signatures of the tagged parts' faces at the last match (JSON)"),
    ("PatternAnchor", "The circular pattern's centre and axis in the first tagged part's frame (JSON)"),
    ("PatternCurveState", "The pattern curve's named edges: signatures and re-match status (JSON)"),
    ("DeletedParts", "The parts whose faces left References since a face was last added, name and label (JSON)"),
]
ENUMERATIONS = {
    "Pattern": PATTERNS,
    "FrictionModel": FRICTION_MODELS,
    "Interpolation": INTERPOLATIONS,
    "CurveEvaluation": CURVE_EVALUATIONS,
    "Texture": textures.CHOICES,
    "TextureScale": TEXTURE_SCALES,
}
TEXTURE_VALUES = ("TextureDC", "TextureViscosity", "TextureBeta", "TextureAlpha",
                  "TextureBetaViscosity", "TextureAlphaViscosity")


class HapticSurface(SchemaState):
    """Proxy of a HapticSurface object."""

    SCHEMA = SCHEMA_VERSION

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj, new=True)

    def setup(self, obj, new=False):
        add_type_tag(obj, TYPE)
        add_hidden_state(obj, HIDDEN_STATE)
        for name, kind, group, tip, default, constraint in PROPERTIES:
            added = name not in obj.PropertiesList
            if added:
                obj.addProperty(kind, name, group, tip)
            if name in ENUMERATIONS:
                current = getattr(obj, name) if not added else None
                setattr(obj, name, ENUMERATIONS[name])
                setattr(obj, name, current if current in ENUMERATIONS[name] else ENUMERATIONS[name][0])
            elif constraint is not None:
                # constraint ranges are not saved with the document: set on every restore
                value = default if added else getattr(obj, name)
                setattr(obj, name, (value, *constraint))
            elif added and default is not None:
                setattr(obj, name, default)
        self.refresh_material_list(obj)

    @staticmethod
    def refresh_material_list(obj):
        """Offers the current database's names; keeps the chosen one if it vanished."""
        current = obj.Material
        names = materials.default_database().names()
        if current and current not in names:
            names.append(current)
        obj.Material = names
        if current:
            obj.Material = current

    def onBeforeChange(self, obj, prop):
        # deleting a part empties its links before it goes: its label is only known here
        if prop == "References" and not is_restoring(obj):
            self._pairs_before = [(o.Name, sub, o.Label) for o, sub in reference_pairs(obj)]

    def onChanged(self, obj, prop):
        if is_restoring(obj) or getattr(self, "_applying", False):
            return
        self._applying = True
        try:
            if prop == "References":
                before = getattr(self, "_pairs_before", [])  # the setting below changes it
                pairs = reference_pairs(obj)
                if len(set((o.Name, f) for o, f in pairs)) != len(pairs):
                    obj.References = link_sub_list(pairs)  # a face listed twice is tagged once
                record_deleted_parts(obj, before)
                sync_reference_state(obj)
                # the first tagged part may be another one now: the centre stays where it is
                follow_pattern_anchor(obj)
                record_pattern_anchor(obj)
            elif prop in ("PatternCenter", "PatternAxis"):
                # the other of the two may be stale (its part moved in an App::Part
                # without a recompute): take it where the part stands now
                centre, axis = circular_centre_axis(obj)
                if prop == "PatternCenter":
                    obj.PatternAxis = axis
                else:
                    obj.PatternCenter = centre
                record_pattern_anchor(obj)
            elif prop == "Pattern" and obj.Pattern == "Circular":
                centre_circles_on_faces(obj)
            elif prop == "PatternCurve":
                _write_curve_state(obj, curve_references.sign(obj.PatternCurve))
            elif prop == "Material" and obj.Material in materials.default_database():
                material = materials.default_database().get(obj.Material)
                obj.StaticFriction = material.static_friction
                obj.DynamicFriction = material.dynamic_friction
                obj.Stiffness = material.stiffness_n_per_mm
            elif prop == "Texture" and obj.Texture in textures.PRESETS:
                for name, value in zip(TEXTURE_VALUES, textures.PRESETS[obj.Texture]):
                    setattr(obj, name, value)
            elif prop in TEXTURE_VALUES and obj.Texture in textures.PRESETS:
                # an edited preset is a custom texture
                if tuple(getattr(obj, n) for n in TEXTURE_VALUES) != textures.PRESETS[obj.Texture]:
                    obj.Texture = "Custom"
        finally:
            self._applying = False

    def onDocumentRestored(self, obj):
        self.setup(obj)
        if not obj.ReferenceState:
            # written before schema 3: the names are as good as they get, sign them now
            sync_reference_state(obj)
        elif not obj.ReferenceShapes:
            # written before the parts' faces were kept: take them now, while the shapes
            # are the ones the references were matched on
            _write_reference_shapes(obj)
        rekey_copy(obj)
        if not obj.PatternAnchor:
            record_pattern_anchor(obj)  # written before the centre moved with its part
        else:
            reanchor_copy(obj)
        if not obj.PatternCurveState and curve_references.named_edges(obj.PatternCurve):
            # written before curve edges were signed: sign them as they are now
            _write_curve_state(obj, curve_references.sign(obj.PatternCurve))
        # a document written without the GUI (freecadcmd, the CLI) has no view-provider
        # proxy to restore: give the surface its own
        attach_view_provider(obj)
        # re-applying constraints is not an edit: the object stays up to date
        obj.purgeTouched()

    def mustExecute(self, obj):
        # a Body or App::Part that moved the first tagged part recomputes only itself: run
        # to follow it (as a vibration's axis does), so PatternCenter shows what is felt
        try:
            return pattern_anchor_moved(obj)
        except Exception:  # noqa: BLE001 (an object half deleted or restored: nothing to follow)
            return False

    def execute(self, obj):
        # runs after every recompute of a referenced part (References links them)
        self._applying = True
        try:
            rematch_references(obj)
            rematch_curve(obj)
            follow_pattern_anchor(obj)
        finally:
            self._applying = False
        problems = validate(obj)
        if problems:
            App.Console.PrintError(f"{obj.Label}: {'; '.join(problems)}\n")



def validate(obj, compile_faces=True):
    """Problems with a surface's current values, as sentences (empty when fine). With
    ``compile_faces`` each tagged face is also compiled for the core, whose own checks
    (surface_compile, _core.validate_surface_properties) then speak here too."""
    problems = []
    deleted = deleted_parts(obj)
    if not obj.References and deleted:
        problems.append(f"no faces: {_and_list(deleted)}, whose faces it tagged, "
                        f"{'was' if len(deleted) == 1 else 'were'} deleted; undo the deletion or pick other faces")
    elif not obj.References:
        problems.append("no faces: pick at least one face")
    not_faces = [f"{o.Label}.{sub}" if sub else f"{o.Label} (the whole object)"
                 for o, sub in reference_pairs(obj) if not sub.startswith("Face")]
    if not_faces:
        problems.append(f"{', '.join(not_faces)}: not a face; a surface tags faces only")
    problems += list(dict.fromkeys(r for r in (untaggable(o) for o, _ in reference_pairs(obj)) if r))
    # a face the part never had (a script's typo) is not one the model lost
    signed = {(e["object"], e["face"]) for e in read_reference_state(obj) if e.get("signature") is not None}
    never = [f"{o.Label}.{sub}" for o, sub in reference_pairs(obj)
             if sub.startswith("Face") and not _has_subshape(o, sub) and (o.Name, sub) not in signed]
    if never:
        problems.append(f"no such face: {', '.join(never)}; pick a face the part has")
    broken = [f"{name}.{face_references.shown_face(face)}"
              for (name, face, status), (o, _) in zip(reference_status(obj), reference_pairs(obj))
              if status == face_references.BROKEN and face.startswith("Face") and f"{o.Label}.{face}" not in never]
    if broken:
        problems.append(f"broken face reference(s) {', '.join(broken)}: the model changed and the face "
                        "cannot be found unambiguously; pick it again")
    # in a recompute, a surface still to run has not followed its faces yet: it checks
    # against this one when its turn comes (else a renumbering edit reported a false clash)
    recomputing = "Recompute" in obj.State
    others = {(o.Name, f): surface for surface in surfaces_of(obj.Document)
              if surface is not obj and not (recomputing and "Touched" in surface.State)
              for o, f in active_reference_pairs(surface)}
    shared = [(o, f, others[(o.Name, f)]) for o, f in active_reference_pairs(obj) if (o.Name, f) in others]
    if shared:
        problems.append(", ".join(f"{o.Label}.{f} is also tagged by {other.Label}" for o, f, other in shared)
                        + ": a face feels one way; remove it from one of the surfaces")
    if obj.Pattern == "Curve" and obj.PatternCurve is None:
        problems.append(curve_references.NO_CURVE)
    elif obj.Pattern == "Curve":
        problem = curve_problem(obj)
        if problem:
            problems.append(problem)
    if obj.Texture != "None" and obj.TextureScale == "Friction level" and obj.StaticFriction == 0:
        problems.append("the texture's level 1 is the face's friction, and its static friction is 0: "
                        "it would render nothing; raise the friction, or make level 1 a device force")
    not_finite = [f"{name} = {value}" for name, value in _numbers(obj) if not math.isfinite(value)]
    if not_finite:
        problems.append(f"{', '.join(not_finite)}: not a finite number")
    if compile_faces and not problems:
        from .surface_compile import compile_surface

        placed = {}  # one copy per part: copying a big part for each of its faces took seconds
        for o, sub in active_reference_pairs(obj):
            if o.Name not in placed:
                placed[o.Name] = o.Shape.copy()
                placed[o.Name].Placement = o.getGlobalPlacement()
            try:
                compile_surface(obj, placed[o.Name].getElement(sub))
            except ValueError as exc:
                message = str(exc)
                prefix = f"{obj.Label}: "
                problems.append(message[len(prefix):] if message.startswith(prefix) else message)
                break
    return problems


def _numbers(obj):
    """(name, float) of every number among a surface's properties (vectors by component)."""
    for name, kind, *_ in PROPERTIES:
        if kind in ("App::PropertyFloat", "App::PropertyFloatConstraint", "App::PropertyAngle"):
            yield name, float(getattr(obj, name))
        elif kind in ("App::PropertyVector", "App::PropertyVectorDistance"):
            v = getattr(obj, name)
            yield from ((f"{name}.{axis}", float(getattr(v, axis))) for axis in "xyz")


def is_haptic_surface(obj):
    return getattr(obj, "HaptiCADType", None) == TYPE


def shown(value):
    """An argument as an error message names it: an object by its label, else its repr."""
    label = getattr(value, "Label", None) if isinstance(value, App.DocumentObject) else None
    return label if isinstance(label, str) else repr(value)


def require_document(doc, who):
    """Raises ValueError, naming ``who`` (the function), unless ``doc`` is a FreeCAD document."""
    if not isinstance(doc, App.Document):
        raise ValueError(f"{who}: doc = {shown(doc)} is not a FreeCAD document; pass one (App.ActiveDocument)")


def require_surface(surface, who):
    """Raises ValueError, naming ``who``, unless ``surface`` has a HapticSurface's References."""
    if not (isinstance(surface, App.DocumentObject) and hasattr(surface, "References")):
        raise ValueError(f"{who}: {shown(surface)} is not a haptic surface")


def surfaces_of(doc):
    """The HapticSurface objects of a document, in document order. Raises ValueError
    when ``doc`` is not a document."""
    require_document(doc, "surfaces_of")
    return [o for o in doc.Objects if is_haptic_surface(o)]


def surface_tagging(obj, face, besides=None):
    """The HapticSurface (other than ``besides``) that tags ``obj``'s ``face``, or None."""
    for surface in surfaces_of(obj.Document):
        if surface is not besides and (obj, face) in active_reference_pairs(surface):
            return surface
    return None


def reference_pairs(surface):
    """[(object, "FaceN"), ...] of a surface's References. Raises ValueError when
    ``surface`` is not a haptic surface."""
    require_surface(surface, "reference_pairs")
    pairs = []
    for obj, subs in surface.References:
        for sub in subs if isinstance(subs, (list, tuple)) else [subs]:
            pairs.append((obj, sub))
    return pairs


def link_sub_list(pairs):
    """[(object, ("FaceN", ...)), ...] of [(object, "FaceN"), ...], as a PropertyLinkSubList
    takes it: grouped by object in first-seen order, each face once."""
    grouped = {}
    for obj, sub in pairs:
        subs = grouped.setdefault(obj, [])
        if sub not in subs:
            subs.append(sub)
    return [(obj, tuple(subs)) for obj, subs in grouped.items()]


def pattern_curve_object(surface):
    """The object whose edges a Curve pattern follows, or None (another pattern, or no
    curve): editing or moving it changes what the surface renders."""
    link = getattr(surface, "PatternCurve", None)
    return link[0] if surface.Pattern == "Curve" and link else None


def moves_with(obj, objects):
    """True when a change of ``obj``'s shape or placement moves one of ``objects``: it is
    one, or it holds one (a Body, an App::Part)."""
    return any(obj is o or obj in o.InListRecursive for o in objects if o is not None)


def _and_list(words):
    return words[0] if len(words) == 1 else f"{', '.join(words[:-1])} and {words[-1]}"


def deleted_parts(obj):
    """Labels of the parts whose faces left this surface's References and which are no
    longer in the document: deleted (a part's links are emptied before it goes, so the
    deletion is only seen afterwards). Cleared once a face is added."""
    try:
        left = json.loads(obj.DeletedParts) if getattr(obj, "DeletedParts", "") else []
    except ValueError:
        left = []
    if not isinstance(left, list):
        return []
    return sorted({str(e.get("label")) for e in left
                   if isinstance(e, dict) and obj.Document.getObject(str(e.get("name"))) is None})


def record_deleted_parts(obj, pairs_before):
    """After References changed from ``pairs_before`` ([(name, face, label), ...]): keeps
    the parts whose faces left (deleted_parts tells which of them were deleted); forgets
    them once any face is added."""
    now = {(o.Name, sub) for o, sub in reference_pairs(obj)}
    try:
        kept = json.loads(obj.DeletedParts) if obj.DeletedParts and now <= {p[:2] for p in pairs_before} else []
    except ValueError:
        kept = []
    left = [e for e in kept if isinstance(e, dict)]
    for name, face, label in pairs_before:
        if (name, face) not in now and {"name": name, "label": label} not in left:
            left.append({"name": name, "label": label})
    text = json.dumps(left) if left else ""
    if text != obj.DeletedParts:
        obj.DeletedParts = text


def read_reference_state(obj):
    """The ReferenceState entries of a surface (see face_references)."""
    try:
        entries = json.loads(obj.ReferenceState) if obj.ReferenceState else []
    except ValueError:
        entries = []
    return entries if isinstance(entries, list) else []


def _write_reference_state(obj, entries):
    text = json.dumps(entries, sort_keys=True)
    if text != obj.ReferenceState:
        obj.ReferenceState = text


def sync_reference_state(obj):
    """Keeps one state entry per reference: known ones as they are, new ones signed from
    the face they name now (a designer just picked it)."""
    known = {(e["object"], e["face"]): e for e in read_reference_state(obj)}
    cache = {}
    entries = [known.get((o.Name, sub)) or face_references.new_entry(o, sub, cache)
               for o, sub in reference_pairs(obj)]
    _write_reference_state(obj, entries)
    _write_reference_shapes(obj)


def resign_reference(obj, part, face):
    """The designer picked ``part``'s ``face`` again for a reference that broke: the
    reference is signed afresh from the face as it is now."""
    entries = [face_references.new_entry(part, face) if (e["object"], e["face"]) == (part.Name, face) else e
               for e in read_reference_state(obj)]
    _write_reference_state(obj, entries)
    _write_reference_shapes(obj)


def _reference_shapes(obj):
    return {o.Name: getattr(o, "Shape", None) for o, _ in reference_pairs(obj)}


def _write_reference_shapes(obj, signed=None):
    """Keeps the signatures of the tagged parts' faces as they are now, for the next
    rematch (face_references.tables; ``signed``: those a rematch has just taken)."""
    text = json.dumps(face_references.tables(_reference_shapes(obj), signed), sort_keys=True)
    if text != obj.ReferenceShapes:
        obj.ReferenceShapes = text


def _read_reference_shapes(obj):
    try:
        tables = json.loads(obj.ReferenceShapes) if obj.ReferenceShapes else {}
    except ValueError:
        tables = {}
    return tables if isinstance(tables, dict) else {}


def reference_status(surface):
    """[(object name, face name, "ok" | "rematched" | "broken"), ...] per reference.
    Raises ValueError when ``surface`` is not a haptic surface."""
    require_surface(surface, "reference_status")
    known = {(e["object"], e["face"]): e["status"] for e in read_reference_state(surface)}
    return [(o.Name, sub, known.get((o.Name, sub), face_references.OK if _has_subshape(o, sub)
                                    else face_references.BROKEN))
            for o, sub in reference_pairs(surface)]


# seed 001's fastest stroke (§III: 50 to 270 mm/s); a grid a servo rate cannot follow
# that fast is said
FASTEST_STROKE_MM_S = 270.0
# The harmonics of 1/g a roughness grid's force carries, by the balls' height (RoughnessHeight,
# a share of the spacing g): along a row the balls' 1/g and, from the tilt of their normals
# (strong in the normal force for categories 1-3) and the friction they modulate, 2/g; taller
# balls tilt further and add more. Across the grid, a stroke meets rows and columns at once:
# on its diagonal every line is sqrt(2) times as fine (2 sqrt(2) / g at the default height).
# Measured (strokes at 20 kHz, 0, 30 and 45 degrees to the rows, lines of 3 % of the largest
# or more): up to 2.83 / g for heights up to 0.1, 4.47 / g up to 0.3, 6 / g at 0.5; without
# height (friction alone) 1.41 / g.
GRID_HARMONICS_BY_HEIGHT = ((0.0, 1), (0.1, 2), (0.3, 4), (0.5, 6))
# A line is felt as it is when it stays this share of half the servo rate or under: at half
# the rate its strength is what the sampling's phase leaves of it (category 1 at 1 kHz and
# 50 mm/s: a 0.041 or 0.155 N ripple for 0.161 N), and just under it, it beats with its image
# more slowly than a stroke lasts (category 3 at 106 mm/s: its diagonal's 499.7 Hz line, 96 %
# off); a tenth under it every category measured is felt as at 20 kHz, in every phase.
GRID_NYQUIST_SHARE = 0.9


def _grid_harmonics(height):
    """How many harmonics of a row a grid with balls ``height`` (share of the spacing) tall
    carries (GRID_HARMONICS_BY_HEIGHT)."""
    return next((n for top, n in GRID_HARMONICS_BY_HEIGHT if height <= top + 1e-9), GRID_HARMONICS_BY_HEIGHT[-1][1])


def _grid_fastest_mm_s(grid_mm, harmonics, rate_hz):
    """The fastest stroke (mm/s, rounded down) at which a grid of ``grid_mm`` carrying
    ``harmonics`` is felt as it is at ``rate_hz``: its finest line, harmonics sqrt(2) v / g
    across the diagonal, at GRID_NYQUIST_SHARE of half the rate."""
    fastest = GRID_NYQUIST_SHARE * grid_mm * float(rate_hz) / (2 * harmonics * math.sqrt(2))
    return math.floor(fastest) if fastest >= 10 else math.floor(10 * fastest) / 10


def _grid_beyond_rate(surface, rate_hz):
    """(category, grid mm, fastest stroke felt as it is in mm/s, harmonics) of a surface's
    roughness grid that a loop at ``rate_hz`` cannot follow at FASTEST_STROKE_MM_S, else None."""
    from . import _core

    if not surface.FeelRoughness or (surface.RoughnessHeight <= 0 and surface.RoughnessFrictionModulation <= 0):
        return None
    category = int(surface.RoughnessCategory)
    grid_mm = _core.roughness_category(category).grid_size_mm
    harmonics = _grid_harmonics(float(surface.RoughnessHeight))
    fastest = _grid_fastest_mm_s(grid_mm, harmonics, rate_hz)
    return (category, grid_mm, fastest, harmonics) if fastest < FASTEST_STROKE_MM_S else None


def _raise_rate(where):
    return f"Stroke slower, or raise the servo rate {where} (5-10 kHz for the finest categories)"


def rate_note(surface, rate_hz, where="in Preferences"):
    """What a servo loop at ``rate_hz`` makes of ``surface``'s roughness grid: "" when it is
    felt as it is up to FASTEST_STROKE_MM_S, else up to what speed: while every harmonic it
    carries stays under GRID_NYQUIST_SHARE of half the rate on every stroke direction
    (_grid_beyond_rate). Faster, a harmonic passes half the rate and is felt as a coarser
    ripple than the part has (category 1 at 1 kHz and 40 mm/s: its 800 Hz second harmonic,
    the bumps' tilt, at 200 Hz). Then texture_rate_note's sentence for its grating, if any.
    ``where`` says where the rate is set."""
    beyond = _grid_beyond_rate(surface, rate_hz)
    notes = [_grid_note(surface, beyond, rate_hz, where) if beyond else "",
             texture_rate_note(surface, rate_hz, where)]
    return " ".join(n for n in notes if n)


def _grid_note(surface, beyond, rate_hz, where):
    from .preferences import SERVO_RATE_RANGE_HZ

    category, grid_mm, fastest, harmonics = beyond
    most = SERVO_RATE_RANGE_HZ[1]
    needed = math.ceil(2 * harmonics * math.sqrt(2) * FASTEST_STROKE_MM_S / (GRID_NYQUIST_SHARE * grid_mm))
    if float(rate_hz) >= most:
        remedy = f"Stroke slower: no servo rate up to {most} Hz follows it to {FASTEST_STROKE_MM_S:.0f} mm/s"
    else:
        remedy = (f"Stroke slower, or raise the servo rate {where} "
                  + (f"({needed} Hz follows it to {FASTEST_STROKE_MM_S:.0f} mm/s)" if needed <= most else
                     f"(at {most} Hz it is felt as it is up to {_grid_fastest_mm_s(grid_mm, harmonics, most):g} mm/s)"))
    return (f"{surface.Label}: roughness category {category}'s {grid_mm:g} mm grid is felt as it is up to "
            f"{fastest:g} mm/s at the {float(rate_hz):g} Hz servo rate (there its {_ordinal(harmonics)} harmonic, "
            f"stroked across the grid's diagonal, comes within {100 * (1 - GRID_NYQUIST_SHARE):.0f} % of half the "
            f"rate); stroked faster it is felt as a coarser ripple than the part has. {remedy}")


def texture_rate_note(surface, rate_hz, where="in Preferences"):
    """What a servo loop at ``rate_hz`` makes of ``surface``'s viscous grating (seed 001
    eq. 2): "" when its highest harmonic, kViscousHarmonics v / lambda Hz, stays under half
    the rate up to FASTEST_STROKE_MM_S, else up to what speed it is felt as designed.
    Faster, the harmonics (and past lambda rate / 2, the grating itself) are sampled too
    rarely and felt at a lower, wrong pitch: a 1 mm grating at 1 kHz is felt as designed
    up to 125 mm/s, and its fundamental aliases past 500 mm/s. lambda is the finest period
    felt: on a Curve pattern, across its ridges where they lie closest (_finest_period_mm)."""
    from . import _core
    from .preferences import SERVO_RATE_RANGE_HZ

    if surface.Texture == "None":
        return ""
    period_mm = float(surface.TexturePeriod)
    felt_mm = _finest_period_mm(surface)
    harmonics = _core.VISCOUS_HARMONICS
    fastest = felt_mm * float(rate_hz) / (2 * harmonics)
    if fastest >= FASTEST_STROKE_MM_S:
        return ""
    fundamental = felt_mm * float(rate_hz) / 2
    itself = (f", and beyond {fundamental:.0f} mm/s the grating itself," if fundamental < FASTEST_STROKE_MM_S
              else "")
    needed = math.ceil(2 * harmonics * FASTEST_STROKE_MM_S / felt_mm)
    raise_to = (f"raise the servo rate {where} ({needed} Hz follows it to {FASTEST_STROKE_MM_S:.0f} mm/s)"
                if needed <= SERVO_RATE_RANGE_HZ[1] else
                f"lengthen the period (at {SERVO_RATE_RANGE_HZ[1]} Hz, "
                f"{2 * harmonics * FASTEST_STROKE_MM_S / SERVO_RATE_RANGE_HZ[1] * period_mm / felt_mm:.3g} mm "
                f"follows it to {FASTEST_STROKE_MM_S:.0f} mm/s)")
    across = (f", {felt_mm:.3g} mm across the Curve pattern's ridges where they lie closest," if felt_mm < period_mm
              else "")
    return (f"{surface.Label}: its {period_mm:g} mm texture grating{across} is felt as designed up to {fastest:.0f} "
            f"mm/s at the {float(rate_hz):g} Hz servo rate (there its {_ordinal(harmonics)} harmonic reaches half the "
            f"rate); stroked faster its harmonics{itself} are felt at a lower, wrong pitch. Stroke slower, or "
            f"{raise_to}")


def _finest_period_mm(surface):
    """The finest period (mm) ``surface``'s grating is felt at: its TexturePeriod, or, on a
    Curve pattern, that across its ridges where they lie closest, lambda times the cosine of
    the curve's largest lean over the tagged faces (surface_compile.curve_grating_periods)."""
    period = float(surface.TexturePeriod)
    if surface.Pattern != "Curve":
        return period
    from .surface_compile import curve_grating_periods

    try:
        found = [finest for _, finest, _ in curve_grating_periods(surface)]
    except ValueError:  # a curve that cannot be built: validate() says why
        return period
    return max(min([period] + found), 1e-3 * period)  # (a curve along x: ridges that all but touch)


def _ordinal(n):
    return {1: "1st", 2: "2nd", 3: "3rd"}.get(n, f"{n}th")


def rate_notes(doc, rate_hz, where="in Preferences"):
    """What a loop at ``rate_hz`` makes of doc's roughness grids: one sentence naming all
    it cannot follow (rate_note's for one); then texture_rate_note's of each grating."""
    beyond = [(s, b) for s in surfaces_of(doc) for b in [_grid_beyond_rate(s, rate_hz)] if b]
    textures = [n for n in (texture_rate_note(s, rate_hz, where) for s in surfaces_of(doc)) if n]
    if len(beyond) <= 1:
        return [_grid_note(s, b, rate_hz, where) for s, b in beyond] + textures
    each = ", ".join(f"{s.Label} (category {c}, {g:g} mm) up to {v:g} mm/s" for s, (c, g, v, _) in beyond)
    return [f"At the {float(rate_hz):g} Hz servo rate these roughness grids are felt as they are only when "
            f"stroked slowly: {each}; faster, they are felt as a coarser ripple than the part has. "
            f"{_raise_rate(where)}"] + textures


def hidden_part_notes(surface):
    """A sentence for each part the surface tags that is hidden, naming what uses it: a
    Part Fillet or Cut made after tagging hides the tagged shape, and Feel renders that
    hidden shape, not the one on screen."""
    notes = []
    for obj in dict.fromkeys(o for o, _ in reference_pairs(surface)):
        if getattr(obj, "Visibility", True):
            continue
        users = [o for o in obj.InList if hasattr(o, "Shape") and getattr(o, "Visibility", False)]
        by = f", used by {', '.join(o.Label for o in users)}" if users else ""
        instead = ""
        if users:  # a click on a Draft array made with links picks the hidden part's face again
            instead = (f"; {face_picking.link_refusal(users[0])}" if face_picking.is_link(users[0])
                       else f"; tag the faces of {users[0].Label} instead")
        notes.append(f"{obj.Label} is hidden{by}: you feel {obj.Label}'s shape, not what is shown" + instead)
    return notes


def active_reference_pairs(surface):
    """reference_pairs without the broken ones: what the scene and the overlay use."""
    status = {(o, f): s for o, f, s in reference_status(surface)}
    return [(o, sub) for o, sub in reference_pairs(surface)
            if status.get((o.Name, sub)) != face_references.BROKEN]


def rematch_references(obj):
    """Re-matches every reference to the current shapes (face_references); re-binds the
    re-matched ones and reports the ones that broke."""
    before = read_reference_state(obj)
    pairs = reference_pairs(obj)
    known = {(e["object"], e["face"]): e for e in before}
    cache = {}
    inputs = [known.get((o.Name, sub)) or face_references.new_entry(o, sub, cache) for o, sub in pairs]
    objects = {o.Name: o for o, _ in pairs}
    signed = {}
    entries = face_references.rematch(inputs, {name: getattr(o, "Shape", None) for name, o in objects.items()},
                                      _read_reference_shapes(obj), signed)
    # two references landing on one face: the one that kept its name wins, the other breaks
    holder = {}
    for i, e in enumerate(entries):
        if e["status"] == face_references.BROKEN:
            continue
        key = (e["object"], e["face"])
        j = holder.setdefault(key, i)
        if j != i:
            loser = i if entries[j]["status"] == face_references.OK else j
            entries[loser] = dict(inputs[loser], status=face_references.BROKEN)
            holder[key] = j + i - loser
    _step_aside(entries)
    was_broken = {(e["object"], e["face"]) for e in before if e.get("status") == face_references.BROKEN}
    newly_broken = [f"{e['object']}.{face_references.shown_face(e['face'])}" for e in entries
                    if e["status"] == face_references.BROKEN and (e["object"], e["face"]) not in was_broken
                    and e["face"].startswith("Face")]  # validate() names what is not a face
    if newly_broken:
        App.Console.PrintWarning(
            f"{obj.Label}: the reference{'s' if len(newly_broken) > 1 else ''} to {', '.join(newly_broken)} "
            f"{'are' if len(newly_broken) > 1 else 'is'} broken: the model changed and the face cannot be "
            "found unambiguously; left out until you pick it again\n")
    # "was" the name it had: a broken reference may be shown by the name a followed one takes
    followed = [f"{e['object']}.{e['face']}" + (f" (was {was['face']})" if was["face"] != e["face"] else "")
                for e, was in zip(entries, inputs) if e["status"] == face_references.REMATCHED]
    if followed:
        App.Console.PrintMessage(f"{obj.Label}: face references now follow {', '.join(followed)}\n")
    new_pairs = [(objects[e["object"]], e["face"]) for e in entries]
    if new_pairs != pairs:
        obj.References = link_sub_list(new_pairs)
    _write_reference_state(obj, entries)
    _write_reference_shapes(obj, signed)


def _step_aside(entries):
    """Renames, in place, each broken entry whose face name another reference holds (a
    live one re-matched onto it, or another broken one) to a name of no face ("Face6~1",
    face_references.ASIDE): References holds each name once, and the two were merged, the
    live face read as broken and its tag lost at the next edit."""
    taken = {(e["object"], e["face"]) for e in entries if e["status"] != face_references.BROKEN}
    for i, e in enumerate(entries):
        if e["status"] != face_references.BROKEN:
            continue
        key = (e["object"], e["face"])
        if key in taken:
            base, k = face_references.shown_face(e["face"]), 1
            while (e["object"], f"{base}{face_references.ASIDE}{k}") in taken:
                k += 1
            key = (e["object"], f"{base}{face_references.ASIDE}{k}")
            entries[i] = dict(e, face=key[1])
        taken.add(key)


def _vec3(v):
    return [float(v.x), float(v.y), float(v.z)]


def _global_placement(obj):
    """Where an object stands in the world (identity for one that has no placement)."""
    get = getattr(obj, "getGlobalPlacement", None)
    return get() if get is not None and hasattr(obj, "Placement") else App.Placement()


def record_pattern_anchor(obj):
    """Keeps the circular pattern's centre and axis in the frame of the first tagged
    part, so that they move with it."""
    pairs = reference_pairs(obj)
    state = ""
    if pairs:
        part = pairs[0][0]
        inverse = _global_placement(part).inverse()
        state = json.dumps({"object": part.Name, "centre": _vec3(inverse.multVec(obj.PatternCenter)),
                            "axis": _vec3(inverse.Rotation.multVec(obj.PatternAxis))}, sort_keys=True)
    if state != obj.PatternAnchor:
        obj.PatternAnchor = state


def circular_centre_axis(obj):
    """(centre mm, axis) of the circular pattern, global, where the first tagged part
    stands now (PatternCenter and PatternAxis when it has no anchor)."""
    try:
        state = json.loads(obj.PatternAnchor) if obj.PatternAnchor else None
        part = obj.Document.getObject(state["object"]) if state else None
    except (ValueError, KeyError, TypeError):
        part = None
    if part is None:
        return App.Vector(obj.PatternCenter), App.Vector(obj.PatternAxis)
    placement = _global_placement(part)
    return (placement.multVec(App.Vector(*state["centre"])),
            placement.Rotation.multVec(App.Vector(*state["axis"])))


def rekey_copy(obj):
    """A surface copied with its parts (Edit > Duplicate selection, or pasted into a
    document that already has a part of that name) tags the copies, Cut001, while its
    face signatures still name the originals, Cut: read by name, they were missing, and
    the next edit re-signed the copy's face from the already renumbered shape, moving the
    tag to a side face as "ok". Each reference's entry is in References' order, so the
    copies' names are read from there and put on the signatures."""
    pairs = reference_pairs(obj)
    entries = read_reference_state(obj)
    if len(entries) != len(pairs):
        return
    renamed = {}
    for entry, (part, face) in zip(entries, pairs):
        if entry.get("face") != face or renamed.setdefault(entry.get("object"), part.Name) != part.Name:
            return  # not these references' signatures: leave them to be signed afresh
    renamed = {old: new for old, new in renamed.items() if old != new}
    if not renamed:
        return
    _write_reference_state(obj, [dict(e, object=renamed.get(e["object"], e["object"])) for e in entries])
    tables = _read_reference_shapes(obj)
    text = json.dumps({renamed.get(name, name): table for name, table in tables.items()}, sort_keys=True)
    if text != obj.ReferenceShapes:
        obj.ReferenceShapes = text


def reanchor_copy(obj):
    """A surface copied with its part (Edit > Duplicate selection) tags the copy but is
    anchored to the original: its circles stayed on the original part and moved with
    it. The copy's frame is the original's, so the same local centre and axis are
    anchored to the copy (the first tagged part) and followed."""
    pairs = reference_pairs(obj)
    try:
        state = json.loads(obj.PatternAnchor)
        named = state["object"]
    except (ValueError, KeyError, TypeError):
        return
    if not pairs or named in {o.Name for o, _ in pairs}:
        return
    state["object"] = pairs[0][0].Name
    obj.PatternAnchor = json.dumps(state, sort_keys=True)
    follow_pattern_anchor(obj)


def faces_centre_normal(obj):
    """(centre mm, unit normal, bound box) of the faces ``obj`` tags, global: the centre
    weighted by area, the normal the faces' normals at their centres so weighted (None
    where they cancel, round a whole cylinder say); None when it tags no face."""
    from .surface_compile import global_shape

    faces = [global_shape(part).getElement(sub) for part, sub in active_reference_pairs(obj)]
    if not faces:
        return None
    area = sum(f.Area for f in faces)
    centre, normal, box = App.Vector(), App.Vector(), App.BoundBox()
    for face in faces:
        u0, u1, v0, v1 = face.ParameterRange
        centre += face.CenterOfMass * (face.Area / area)
        normal += face.normalAt(0.5 * (u0 + u1), 0.5 * (v0 + v1)) * face.Area
        box.add(face.BoundBox)
    return centre, (normal.normalize() if normal.Length > 1e-6 * area else None), box


def centre_circles_on_faces(obj):
    """A circular pattern chosen while its centre is still the default, the origin, away
    from the tagged faces: the circles are put round the faces' centre, their axis along
    the faces' normal. Left at the origin, circles 100 mm off read as straight stripes.
    A centre the designer set (anything but the origin), or an origin on the faces, stays."""
    if obj.PatternCenter.Length > 1e-9:
        return
    found = faces_centre_normal(obj)
    if found is None:
        return
    centre, normal, box = found
    box.enlarge(1e-6 * max(box.DiagonalLength, 1.0))
    if box.isInside(App.Vector()):
        return
    obj.PatternCenter = centre
    if normal is not None:
        obj.PatternAxis = normal
    record_pattern_anchor(obj)


def pattern_anchor_moved(obj):
    """Whether the part the pattern is anchored to took its centre or axis away from
    PatternCenter and PatternAxis (moved, and nothing followed it since)."""
    centre, axis = circular_centre_axis(obj)
    return (centre - obj.PatternCenter).Length > 1e-9 or (axis - obj.PatternAxis).Length > 1e-12


def follow_pattern_anchor(obj):
    """Moves PatternCenter and PatternAxis with the part they are anchored to."""
    if pattern_anchor_moved(obj):
        obj.PatternCenter, obj.PatternAxis = circular_centre_axis(obj)


def _write_curve_state(obj, state):
    text = curve_references.dumps(state) if state else ""
    if text != obj.PatternCurveState:
        obj.PatternCurveState = text


def curve_problem(obj):
    """What is wrong with the edges the pattern curve names (None when nothing is)."""
    if obj.PatternCurve is None:
        return None
    return curve_references.problem(curve_references.loads(obj.PatternCurveState), obj.PatternCurve[0].Label)


def rematch_curve(obj):
    """Looks for the pattern curve's named edges again (curve_references) and follows
    the ones that were renumbered, saying so; validate() reports the ones that broke."""
    state, names = curve_references.rematch(curve_references.loads(obj.PatternCurveState), obj.PatternCurve)
    for name, status in curve_references.status(state):
        if status == curve_references.REMATCHED:
            App.Console.PrintMessage(f"{obj.Label}: the pattern curve now follows "
                                     f"{obj.PatternCurve[0].Label}.{name}\n")
    if obj.PatternCurve is not None and names != curve_references.named_edges(obj.PatternCurve):
        obj.PatternCurve = (obj.PatternCurve[0], names)
    _write_curve_state(obj, state)


def _has_subshape(obj, sub):
    try:
        return not obj.Shape.getElement(sub).isNull()
    except Exception:
        return False


def untaggable(obj):
    """Why the faces of ``obj`` cannot be tagged, as a sentence; "" when they can. A
    surface tags a placed part's own faces: an App::Link shows another object's shape,
    placed by the link, which the scene does not follow."""
    if obj.isDerivedFrom("App::GeoFeature") and not obj.isDerivedFrom("App::Link"):
        return ""
    if face_picking.is_link(obj) and face_picking.linked_original(obj) is not None:
        # the same sentence as a click through a link (face_picking): a link array too
        return face_picking.link_refusal(obj)
    return f"{obj.Label} is not a placed part: its faces cannot be tagged"


def _normalise_references(doc, references):
    """Checks [(obj, "FaceN"), ...] and groups it as PropertyLinkSubList wants."""
    if not references:
        raise ValueError("make_surface: no faces given; pass [(object, 'FaceN'), ...]")
    pairs = []
    for item in references:
        try:
            obj, sub = item
        except (TypeError, ValueError):
            raise ValueError(f"make_surface: {item!r} is not an (object, 'FaceN') pair") from None
        if isinstance(obj, str):
            name = obj
            obj = doc.getObject(name)
            if obj is None:
                raise ValueError(f"make_surface: document {doc.Name} has no object {name!r}")
        if not isinstance(obj, App.DocumentObject):
            raise ValueError(f"make_surface: {obj!r} in references is neither an object of the document nor "
                             "its name")
        if obj.Document != doc:
            raise ValueError(f"make_surface: {obj.Name} belongs to document {obj.Document.Name}")
        if not hasattr(obj, "Shape"):
            raise ValueError(f"make_surface: {obj.Name} has no shape")
        if untaggable(obj):
            raise ValueError(f"make_surface: {untaggable(obj)}")
        if not (isinstance(sub, str) and sub.startswith("Face") and _has_subshape(obj, sub)):
            raise ValueError(f"make_surface: {obj.Name} has no face {sub!r}")
        # a PartDesign feature's face is the Body's, as the panel and the command take it
        obj, sub = face_references.owner_face(obj, sub)
        other = surface_tagging(obj, sub)
        if other is not None:
            raise ValueError(f"make_surface: {obj.Label}.{sub} is already tagged by {other.Label}; "
                             "edit that surface, or remove the face from it first")
        pairs.append((obj, sub))
    return link_sub_list(pairs)


def _check_range(label, value, low, high):
    if value is None:
        return
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"make_surface: {label} = {value!r} is not a number") from None
    if not math.isfinite(number):
        raise ValueError(f"make_surface: {label} = {value} is not a finite number")
    if not (low <= number <= high):
        raise ValueError(f"make_surface: {label} = {value} is outside {low}..{high}")


def _is_whole_number(value):
    """An int or numpy integer (what scripts compute), not a bool, nor 2.0."""
    return isinstance(value, numbers.Integral) and type(value).__name__ not in ("bool", "bool_")


def _turn_angle(label, value):
    """A pattern angle, degrees, as a float within a turn (taken modulo 360 beyond it; the
    property would clamp 400 to 360). Raises ValueError when it is not a finite number or is
    beyond PATTERN_ANGLE_LIMIT_DEG."""
    _check_range(label, value, -math.inf, math.inf)
    number = float(value)
    if abs(number) > PATTERN_ANGLE_LIMIT_DEG:
        raise ValueError(f"make_surface: {label} = {value} degrees is not a sensible angle (beyond "
                         f"±{PATTERN_ANGLE_LIMIT_DEG:g}); give degrees, a turn being 360")
    return math.fmod(number, 360.0) if abs(number) > 360.0 else number


def make_surface(doc, references, material="ABS", roughness_category=3, pattern="None",
                 pattern_angle_deg=0.0, pattern_center_mm=None, static_friction=None,
                 dynamic_friction=None, stiffness_n_per_mm=None, name="HapticSurface", **properties):
    """Creates a HapticSurface on the given faces and returns it.

    ``references`` is ``[(object_or_name, "FaceN"), ...]``. ``material`` names a row of
    the material database and sets friction and stiffness; ``static_friction``,
    ``dynamic_friction`` and ``stiffness_n_per_mm`` override them. Any other property
    can be given by its name, e.g. ``AcrossFriction=2.0, Texture="Custom"``, but not
    together with the parameter that sets it (``Stiffness`` and ``stiffness_n_per_mm``).
    An angle beyond a turn is taken modulo 360 degrees. Raises ValueError with a clear
    message on bad input, and on values validate() would report (but for a Curve pattern's
    curve, a link set once the surface is made), leaving nothing in the document.
    """
    require_document(doc, "make_surface")
    links = _normalise_references(doc, references)
    database = materials.default_database()
    if not isinstance(material, str) or material not in database:
        raise ValueError(f"make_surface: unknown material {material!r}; known: {', '.join(database.names())}")
    if not (_is_whole_number(roughness_category) and ROUGHNESS_MIN <= roughness_category <= ROUGHNESS_MAX):
        raise ValueError(f"make_surface: roughness_category must be an integer 1..7, got {roughness_category!r}")
    given = {"roughness_category": roughness_category != 3, "pattern": pattern != "None",
             "pattern_angle_deg": pattern_angle_deg != 0.0, "pattern_center_mm": pattern_center_mm is not None,
             "static_friction": static_friction is not None, "dynamic_friction": dynamic_friction is not None,
             "stiffness_n_per_mm": stiffness_n_per_mm is not None}  # a parameter at its default gives way
    for parameter, prop in PARAMETER_PROPERTIES.items():
        if given[parameter] and prop in properties:
            raise ValueError(f"make_surface: {parameter} and {prop} both set {prop}: give one of them")
    if pattern not in PATTERNS:
        raise ValueError(f"make_surface: pattern must be one of {PATTERNS}, got {pattern!r}")
    _check_range("static_friction", static_friction, 0.0, FRICTION_MAX)
    _check_range("dynamic_friction", dynamic_friction, 0.0, FRICTION_MAX)
    _check_range("stiffness_n_per_mm", stiffness_n_per_mm, STIFFNESS_MIN_N_PER_MM, STIFFNESS_MAX_N_PER_MM)
    known = {p[0]: p for p in PROPERTIES}
    for key, value in properties.items():
        if key not in known or key in ("References", "Material"):
            raise ValueError(f"make_surface: unknown property {key!r}")
        if key in ENUMERATIONS and value not in ENUMERATIONS[key]:
            raise ValueError(f"make_surface: {key} must be one of {ENUMERATIONS[key]}, got {value!r}")
        _check_kind(key, known[key][1], value)
        if known[key][5] is not None:
            _check_range(key, value, known[key][5][0], known[key][5][1])
        elif known[key][1] == "App::PropertyAngle":
            properties[key] = _turn_angle(key, value)
        elif known[key][1] == "App::PropertyFloat":
            _check_range(key, value, -math.inf, math.inf)  # any finite number
    pattern_angle_deg = _turn_angle("pattern_angle_deg", pattern_angle_deg)
    if pattern_center_mm is not None:
        _check_kind("pattern_center_mm", "App::PropertyVectorDistance", pattern_center_mm)
    if not isinstance(name, str) or not name:
        raise ValueError(f"make_surface: name must be a non-empty string, got {name!r}")
    _check_friction_level(properties, static_friction, material)

    obj = doc.addObject("App::FeaturePython", name)
    try:
        _set_up_surface(obj, links, material, roughness_category, pattern, pattern_angle_deg, pattern_center_mm,
                        static_friction, dynamic_friction, stiffness_n_per_mm, properties)
        # what only the values together say (a texture scaled by a friction of 0); the curve
        # of a Curve pattern is a link, set once the surface is made
        problems = [p for p in validate(obj) if p != curve_references.NO_CURVE]
    except Exception as exc:  # what a check above missed: nothing is left behind half made
        doc.removeObject(obj.Name)
        raise ValueError(f"make_surface: {exc}") from exc
    if problems:
        doc.removeObject(obj.Name)
        raise ValueError(f"make_surface: {'; '.join(problems)}")
    return obj


def _check_friction_level(properties, static_friction, material):
    """Refuses a texture whose level 1 is the face's static friction when that is 0 (it
    would render nothing: validate), naming the arguments that set them."""
    if properties.get("Texture", "None") == "None" or properties.get("TextureScale") != "Friction level":
        return
    for source, value in (("StaticFriction", properties.get("StaticFriction")),
                          ("static_friction", static_friction),
                          (f"material {material!r}", materials.default_database().get(material).static_friction)):
        if value is not None:
            break
    if float(value) == 0:
        raise ValueError(f"make_surface: TextureScale 'Friction level' makes the texture's level 1 the face's static "
                         f"friction, and it is 0 ({source}): the texture would render nothing; give a static "
                         "friction above 0, or TextureScale='Device force'")


def _check_kind(label, kind, value):
    """Refuses a value a property of ``kind`` cannot hold (before the object is made)."""
    # True or False, or what scripts write for them (1 and 0, numpy's booleans)
    if kind == "App::PropertyBool" and not (type(value).__name__ in ("bool", "int", "bool_") and value in (0, 1)):
        raise ValueError(f"make_surface: {label} must be True or False, got {value!r}")
    if kind == "App::PropertyIntegerConstraint" and not _is_whole_number(value):
        raise ValueError(f"make_surface: {label} must be a whole number, got {value!r}")
    if kind in ("App::PropertyVector", "App::PropertyVectorDistance"):
        try:
            components = [float(c) for c in value]
        except (TypeError, ValueError):
            components = []
        if len(components) != 3 or not all(math.isfinite(c) for c in components):
            raise ValueError(f"make_surface: {label} must be three finite numbers (x, y, z), got {value!r}")
    if kind.startswith("App::PropertyLink"):
        raise ValueError(f"make_surface: {label} is a link: set it on the surface once made")


def _set_up_surface(obj, links, material, roughness_category, pattern, pattern_angle_deg, pattern_center_mm,
                    static_friction, dynamic_friction, stiffness_n_per_mm, properties):
    HapticSurface(obj)
    obj.References = links
    obj.Material = material
    obj.RoughnessCategory = int(roughness_category)  # a numpy integer is not taken as one
    obj.Pattern = pattern
    obj.PatternAngle = pattern_angle_deg
    if pattern_center_mm is not None:  # else a circular pattern's centre is its faces' (centre_circles_on_faces)
        obj.PatternCenter = App.Vector(*pattern_center_mm)
    if static_friction is not None:
        obj.StaticFriction = float(static_friction)
    if dynamic_friction is not None:
        obj.DynamicFriction = float(dynamic_friction)
    if stiffness_n_per_mm is not None:
        obj.Stiffness = float(stiffness_n_per_mm)
    # presets first, so explicit texture values given with them win
    if "Texture" in properties:
        obj.Texture = properties["Texture"]
    for key, value in properties.items():
        if key != "Texture":
            kind = next(p[1] for p in PROPERTIES if p[0] == key)
            setattr(obj, key, App.Vector(*value) if isinstance(value, (list, tuple))
                    else bool(value) if kind == "App::PropertyBool"
                    else int(value) if kind == "App::PropertyIntegerConstraint" else value)
    sync_reference_state(obj)
    attach_view_provider(obj)


def linked_surface_problems(study, rivals, action, why_one):
    """Problems with the haptic surface a study links (``study.Surface``), as sentences:
    none linked, not a haptic surface, linked by ``rivals`` (other studies of the same
    kind) too, or its faces gone. ``action`` is what participants do ("press"),
    ``why_one`` why a surface takes one such study."""
    surface = study.Surface
    if surface is None:
        return [f"no surface: link the haptic surface whose faces the participants {action}"]
    if not is_haptic_surface(surface):
        return [f"{surface.Label} is not a haptic surface"]
    found = []
    others = [s.Label for s in rivals if s is not study and s.Surface == surface]
    if others:
        found.append(f"{surface.Label} is also studied by {', '.join(others)}: {why_one}; link another surface")
    if not active_reference_pairs(surface):
        found.append(f"{surface.Label} tags no face (its faces are gone or broken): nothing to {action}")
    return found


def attach_view_provider(obj):
    """Gives a HaptiCAD object its view provider when the GUI is up and it has none yet."""
    if not App.GuiUp or obj.ViewObject is None or obj.ViewObject.Proxy:
        return
    from .similarity_study import is_similarity_study
    from .stiffness_study import is_stiffness_study

    if is_haptic_surface(obj):
        from .gui.view_provider_surface import ViewProviderHapticSurface

        ViewProviderHapticSurface(obj.ViewObject)
    elif is_stiffness_study(obj):
        from .gui.view_provider_study import ViewProviderStiffnessStudy

        ViewProviderStiffnessStudy(obj.ViewObject)
    elif is_similarity_study(obj):
        from .gui.view_provider_similarity import ViewProviderSimilarityStudy

        ViewProviderSimilarityStudy(obj.ViewObject)
    else:
        from .gui.view_provider_vibration import ViewProviderHapticVibration

        ViewProviderHapticVibration(obj.ViewObject)
