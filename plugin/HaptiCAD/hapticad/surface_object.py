# SPDX-License-Identifier: GPL-3.0-or-later
"""The HapticSurface document object: physical surface properties on CAD faces.

A HapticSurface is an ``App::FeaturePython`` whose ``References`` (an
``App::PropertyLinkSubListGlobal``) name the faces it applies to, and whose other
properties say how those faces feel. Units follow FreeCAD's: lengths in mm, the
contact stiffness in N/mm. Created with :func:`make_surface`; App-only (no GUI
import), so it works in ``freecadcmd`` and from the ``hapticad`` CLI.
"""
import FreeCAD as App

from . import materials

TYPE = "HaptiCAD::HapticSurface"
SCHEMA_VERSION = 1
PATTERNS = ["None", "Linear", "Circular", "Curve"]
ROUGHNESS_MIN, ROUGHNESS_MAX = 1, 7
# keeps a typed-in zero from making a face infinitely soft; the device caps the top
STIFFNESS_MIN_N_PER_MM = 1e-3
STIFFNESS_MAX_N_PER_MM = 1e3
FRICTION_MAX = 1e3


def _add(obj, kind, name, group, doc):
    if name not in obj.PropertiesList:
        obj.addProperty(kind, name, group, doc)


def _apply_constraints(obj):
    # constraint ranges are not saved with the document: set them on creation and on
    # every restore
    obj.RoughnessCategory = (obj.RoughnessCategory or 3, ROUGHNESS_MIN, ROUGHNESS_MAX, 1)
    obj.StaticFriction = (obj.StaticFriction, 0.0, FRICTION_MAX, 0.05)
    obj.DynamicFriction = (obj.DynamicFriction, 0.0, FRICTION_MAX, 0.05)
    obj.Stiffness = (
        max(obj.Stiffness, STIFFNESS_MIN_N_PER_MM),
        STIFFNESS_MIN_N_PER_MM,
        STIFFNESS_MAX_N_PER_MM,
        0.05,
    )


def _is_restoring(obj):
    return "Restore" in obj.State or obj.Document.Restoring


class HapticSurface:
    """Proxy of a HapticSurface object."""

    def __init__(self, obj):
        obj.Proxy = self
        self.setup(obj)

    def setup(self, obj):
        _add(obj, "App::PropertyString", "HaptiCADType", "Base", "Type tag of HaptiCAD objects")
        obj.HaptiCADType = TYPE
        obj.setEditorMode("HaptiCADType", 2)  # hidden
        _add(obj, "App::PropertyLinkSubListGlobal", "References", "Surface",
             "The faces this surface applies to")
        _add(obj, "App::PropertyEnumeration", "Material", "Surface",
             "Material from the haptic database: sets the friction and stiffness below")
        _add(obj, "App::PropertyIntegerConstraint", "RoughnessCategory", "Surface",
             "Surface category 1-7 of seed 000 Table 2 (Ra range, ISO N-grades, grid size)")
        _add(obj, "App::PropertyEnumeration", "Pattern", "Pattern",
             "Anisotropic friction pattern: None, Linear, Circular or Curve")
        _add(obj, "App::PropertyAngle", "PatternAngle", "Pattern",
             "Linear pattern: stripe direction, measured in the face's frame")
        _add(obj, "App::PropertyVectorDistance", "PatternCenter", "Pattern",
             "Circular pattern: centre (mm, global coordinates)")
        _add(obj, "App::PropertyFloatConstraint", "StaticFriction", "Friction",
             "Static friction coefficient mu_s against a dry fingertip")
        _add(obj, "App::PropertyFloatConstraint", "DynamicFriction", "Friction",
             "Dynamic friction coefficient mu_d against a dry fingertip")
        _add(obj, "App::PropertyFloatConstraint", "Stiffness", "Friction",
             "Contact stiffness to render, N/mm (the device caps it at its own limit)")
        if not obj.Pattern:
            obj.Pattern = PATTERNS
            obj.Pattern = "None"
        self.refresh_material_list(obj)
        _apply_constraints(obj)

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

    def onChanged(self, obj, prop):
        if prop == "Material" and not _is_restoring(obj) and obj.Material:
            database = materials.default_database()
            if obj.Material in database:
                material = database.get(obj.Material)
                obj.StaticFriction = material.static_friction
                obj.DynamicFriction = material.dynamic_friction
                obj.Stiffness = material.stiffness_n_per_mm

    def onDocumentRestored(self, obj):
        self.setup(obj)
        # a document written without the GUI (freecadcmd, the CLI) has no view-provider
        # proxy to restore: give the surface its own
        attach_view_provider(obj)
        # re-applying constraints is not an edit: the object stays up to date
        obj.purgeTouched()

    def execute(self, obj):
        broken = [f"{o.Name}.{sub}" for o, sub in reference_pairs(obj) if not _has_subshape(o, sub)]
        if broken:
            App.Console.PrintWarning(f"{obj.Label}: face(s) no longer exist: {', '.join(broken)}\n")

    # FreeCAD 0.20 with Python 3.11 pickles proxies through both protocols
    def dumps(self):
        return {"schema": SCHEMA_VERSION}

    def loads(self, state):
        self.schema = (state or {}).get("schema", SCHEMA_VERSION)

    def __getstate__(self):
        return self.dumps()

    def __setstate__(self, state):
        self.loads(state)


def is_haptic_surface(obj):
    return getattr(obj, "HaptiCADType", None) == TYPE


def surfaces_of(doc):
    """The HapticSurface objects of a document, in document order."""
    return [o for o in doc.Objects if is_haptic_surface(o)]


def reference_pairs(surface):
    """[(object, "FaceN"), ...] of a surface's References."""
    pairs = []
    for obj, subs in surface.References:
        for sub in subs if isinstance(subs, (list, tuple)) else [subs]:
            pairs.append((obj, sub))
    return pairs


def _has_subshape(obj, sub):
    try:
        return not obj.Shape.getElement(sub).isNull()
    except Exception:
        return False


def _normalise_references(doc, references):
    """Checks [(obj, "FaceN"), ...] and groups it as PropertyLinkSubList wants."""
    if not references:
        raise ValueError("make_surface: no faces given; pass [(object, 'FaceN'), ...]")
    grouped = {}
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
        if obj.Document != doc:
            raise ValueError(f"make_surface: {obj.Name} belongs to document {obj.Document.Name}")
        if not hasattr(obj, "Shape"):
            raise ValueError(f"make_surface: {obj.Name} has no shape")
        if not (isinstance(sub, str) and sub.startswith("Face") and _has_subshape(obj, sub)):
            raise ValueError(f"make_surface: {obj.Name} has no face {sub!r}")
        grouped.setdefault(obj, [])
        if sub not in grouped[obj]:
            grouped[obj].append(sub)
    return [(obj, tuple(subs)) for obj, subs in grouped.items()]


def make_surface(doc, references, material="ABS", roughness_category=3, pattern="None",
                 pattern_angle_deg=0.0, pattern_center_mm=(0.0, 0.0, 0.0), static_friction=None,
                 dynamic_friction=None, stiffness_n_per_mm=None, name="HapticSurface"):
    """Creates a HapticSurface on the given faces and returns it.

    ``references`` is ``[(object_or_name, "FaceN"), ...]``. ``material`` names a row of
    the material database and sets friction and stiffness; ``static_friction``,
    ``dynamic_friction`` and ``stiffness_n_per_mm`` override them. Raises ValueError
    with a clear message on bad input, before anything is added to the document.
    """
    links = _normalise_references(doc, references)
    database = materials.default_database()
    if material not in database:
        raise ValueError(f"make_surface: unknown material {material!r}; known: {', '.join(database.names())}")
    if not (isinstance(roughness_category, int) and ROUGHNESS_MIN <= roughness_category <= ROUGHNESS_MAX):
        raise ValueError(f"make_surface: roughness_category must be an integer 1..7, got {roughness_category!r}")
    if pattern not in PATTERNS:
        raise ValueError(f"make_surface: pattern must be one of {PATTERNS}, got {pattern!r}")
    for label, value, low, high in (
        ("static_friction", static_friction, 0.0, FRICTION_MAX),
        ("dynamic_friction", dynamic_friction, 0.0, FRICTION_MAX),
        ("stiffness_n_per_mm", stiffness_n_per_mm, STIFFNESS_MIN_N_PER_MM, STIFFNESS_MAX_N_PER_MM),
    ):
        if value is not None and not (low <= float(value) <= high):
            raise ValueError(f"make_surface: {label} = {value} is outside {low}..{high}")

    obj = doc.addObject("App::FeaturePython", name)
    HapticSurface(obj)
    obj.References = links
    obj.Material = material
    obj.RoughnessCategory = roughness_category
    obj.Pattern = pattern
    obj.PatternAngle = pattern_angle_deg
    obj.PatternCenter = App.Vector(*pattern_center_mm)
    if static_friction is not None:
        obj.StaticFriction = float(static_friction)
    if dynamic_friction is not None:
        obj.DynamicFriction = float(dynamic_friction)
    if stiffness_n_per_mm is not None:
        obj.Stiffness = float(stiffness_n_per_mm)
    attach_view_provider(obj)
    return obj


def attach_view_provider(obj):
    """Gives a surface its view provider when the GUI is up and it has none yet."""
    if not App.GuiUp or obj.ViewObject is None or obj.ViewObject.Proxy:
        return
    from .gui.view_provider_surface import ViewProviderHapticSurface

    ViewProviderHapticSurface(obj.ViewObject)
