# SPDX-License-Identifier: GPL-3.0-or-later
"""Compile a HapticSurface on one B-rep face into the core's SurfaceProperties.

The face gives the geometry the effects need, in world metres: a tangent frame at its
centre (e1 = dS/du turned by PatternAngle about the outward normal, e2 = n x e1), the
circular pattern's axis, and the plane of a curve pattern. Document units (mm, mm/s,
N/mm) become SI here. No GUI.
"""
import math

import numpy as np

from . import _core, curve_references
from .similarity_study import rendered_texture
from .stiffness_study import force_travel_of
from .surface_object import TEXTURE_VALUES, circular_centre_axis

MM = 1e-3


def point_on_face(face):
    """(u, v) of a point on the face near its centre (not in a hole): the point nearest
    its centre of mass, or where that is no point (a whole cylinder's centre lies on its
    axis, a sphere's at its centre: every point is as near, and which one the projection
    gave was rounding, another 1 km off the origin) the middle of its parameters."""
    centre = face.CenterOfMass
    u0, u1, v0, v1 = face.ParameterRange
    u, v = face.Surface.parameter(centre)
    middle = 0.5 * (u0 + u1), 0.5 * (v0 + v1)
    nearest = face.valueAt(u, v).distanceToPoint(centre)
    if face.valueAt(*middle).distanceToPoint(centre) <= nearest + 1e-9 * max(face.BoundBox.DiagonalLength, 1e-300):
        u, v = middle
    if face.isInside(face.valueAt(u, v), 1e-6, True):
        return u, v
    grid = sorted(((i, j) for i in range(1, 10) for j in range(1, 10)),
                  key=lambda ij: abs(ij[0] - 5) + abs(ij[1] - 5))
    for i, j in grid:
        u, v = u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10
        if face.isInside(face.valueAt(u, v), 1e-6, True):
            return u, v
    return 0.5 * (u0 + u1), 0.5 * (v0 + v1)


def _vec(v, scale=1.0):
    return np.array([v.x, v.y, v.z], dtype=float) * scale


def _cross(a, b):
    """a x b of two 3-vectors (numpy's cross costs 60 us a call: most of a frame)."""
    return np.array([a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]])


def face_frame(face, angle_deg, uv=None):
    """(origin m, e1, e2, n) at the face's centre; e1 is the u direction turned by angle.
    ``uv``: point_on_face(face) when already known (it costs most of the frame)."""
    u, v = uv if uv is not None else point_on_face(face)
    origin = _vec(face.valueAt(u, v), MM)
    n = _vec(face.normalAt(u, v))
    du = _vec(face.derivative1At(u, v)[0])
    e1 = du - du.dot(n) * n
    if np.linalg.norm(e1) < 1e-12:  # degenerate parametrisation at the centre: any tangent
        e1 = _cross(n, [1.0, 0, 0] if abs(n[0]) < 0.9 else [0, 1.0, 0])
    e1 /= np.linalg.norm(e1)
    a = math.radians(angle_deg)
    e1 = math.cos(a) * e1 + math.sin(a) * _cross(n, e1)
    e2 = _cross(n, e1)
    return origin, e1, e2, n


def global_shape(obj):
    """obj's shape placed where it sits in the document (App::Part parents included)."""
    shape = obj.Shape.copy()
    shape.Placement = obj.getGlobalPlacement()
    return shape


def _curve_edges(link):
    """The edges a PatternCurve link names: a whole sketch, or chosen edges, where they
    sit in the document (App::Part parents included: the faces are read there too, and a
    sketch read in its container's own frame ran turned with the container). Raises
    ValueError naming an edge the object does not have."""
    obj, _ = link
    shape = global_shape(obj)
    names = curve_references.named_edges(link)
    if not names:
        return list(shape.Edges)
    edges = shape.Edges
    missing = [n for n in names if not (n.startswith("Edge") and n[4:].isdigit() and 1 <= int(n[4:]) <= len(edges))]
    if missing:
        raise ValueError(f"PatternCurve names {', '.join(f'{obj.Label}.{n}' for n in missing)}, which "
                         f"{obj.Label} no longer has (it has {len(edges)} edges): pick the curve again")
    return [edges[int(n[4:]) - 1] for n in names]


def _as_bspline(edges):
    if len(edges) == 1:
        # exact: an arc or an ellipse becomes a rational quadratic, not a degree-9 fit
        e = edges[0].toNurbs().Edges[0]
        curve = e.Curve
        if (e.FirstParameter, e.LastParameter) != (curve.FirstParameter, curve.LastParameter):
            curve = curve.copy()
            curve.segment(e.FirstParameter, e.LastParameter)
        return curve
    import Part

    pieces = Part.sortEdges(edges)  # groups of connected edges
    if len(pieces) > 1:  # a wire of them would keep the first piece and drop the rest
        raise ValueError(f"the pattern curve is {len(pieces)} separate pieces: a Curve pattern follows one "
                         f"connected curve; join them, or pick the edges of one")
    wire = Part.Wire(pieces[0])
    return wire.approximate(1e-7, 1e-4, 200, 7)


def curve_pattern(surface, frame):
    """The core CurvePattern of a surface: the curve, in a plane through the face frame's
    origin, the lookup axis y along the curve's chord. Raises ValueError clearly."""
    curve, x, y = _pattern_curve_in_plane(surface, frame)
    origin = frame[0]
    poles = np.array([[(p - origin).dot(x), (p - origin).dot(y)]
                      for p in (_vec(q, MM) for q in curve.getPoles())])
    knots = [k for k, m in zip(curve.getKnots(), curve.getMultiplicities()) for _ in range(m)]
    evaluation = (_core.CurveEvaluation.EXACT if surface.CurveEvaluation == "Exact"
                  else _core.CurveEvaluation.LOOKUP_TABLE)
    try:
        return _core.CurvePattern.build(_core.PatternPlane(origin, x, y), curve.Degree, knots, poles,
                                        list(curve.getWeights()), surface.CurveTableSize, evaluation)
    except ValueError as exc:
        raise ValueError(f"{surface.Label}: {exc}") from None


def _pattern_curve_in_plane(surface, frame):
    """(B-spline curve, x, y) of a Curve pattern on a face frame: the family's translation
    axis x and the lookup axis y, along the curve's chord in the face's plane."""
    if surface.PatternCurve is None:
        raise ValueError(f"{surface.Label}: {curve_references.NO_CURVE}")
    problem = curve_references.problem(curve_references.loads(getattr(surface, "PatternCurveState", "")),
                                       surface.PatternCurve[0].Label)
    if problem:
        raise ValueError(f"{surface.Label}: {problem}")
    try:
        edges = _curve_edges(surface.PatternCurve)
    except ValueError as exc:
        raise ValueError(f"{surface.Label}: {exc}") from None
    if not edges:
        raise ValueError(f"{surface.Label}: PatternCurve {surface.PatternCurve[0].Label} has no edges")
    try:
        curve = _as_bspline(edges)
    except ValueError as exc:
        raise ValueError(f"{surface.Label}: {surface.PatternCurve[0].Label}: {exc}") from None
    if curve.isPeriodic():
        curve = curve.copy()
        curve.setNotPeriodic()
    origin, _, _, n = frame
    start, end = _vec(curve.value(curve.FirstParameter), MM), _vec(curve.value(curve.LastParameter), MM)
    chord = end - start
    y = chord - chord.dot(n) * n
    if np.linalg.norm(y) < 1e-12:
        raise ValueError(f"{surface.Label}: the pattern curve is closed or normal to the face")
    y /= np.linalg.norm(y)
    return curve, np.cross(y, n), y


CURVE_BEYOND_NOTE = 0.25  # of a face's extent along the curve: more beyond its ends is said


def curve_notes(surface):
    """Faces a Curve pattern mostly misses, as sentences. The stripes are the curve's
    copies slid across it (seed 000 Fig. 7); beyond the curve's ends, along its chord,
    its end directions run on straight, so a face lying there feels straight stripes,
    not the curve's shape. Problems with the curve itself are validate()'s."""
    if surface.Pattern != "Curve" or surface.PatternCurve is None:
        return []
    from .surface_object import active_reference_pairs

    notes = []
    for obj, sub in active_reference_pairs(surface):
        face = global_shape(obj).getElement(sub)
        frame = face_frame(face, float(surface.PatternAngle))
        try:
            curve, _, y = _pattern_curve_in_plane(surface, frame)
        except ValueError:
            return []
        ends = [(_vec(curve.value(t), MM) - frame[0]).dot(y) for t in (curve.FirstParameter, curve.LastParameter)]
        lo, hi = _extent_along(face, frame[0], y)
        if hi - lo < 1e-9:
            continue
        beyond = (max(0.0, min(ends) - lo) + max(0.0, hi - max(ends))) / (hi - lo)
        if beyond > CURVE_BEYOND_NOTE:
            where = "all of it" if beyond >= 1.0 else f"{100 * min(beyond, 1.0):.0f} % of it"
            notes.append(f"{obj.Label}.{sub}: {where} lies beyond the ends of {surface.PatternCurve[0].Label} "
                         f"(along the curve), where the stripes run straight on in its end directions: "
                         f"draw the curve across the face to feel its shape there")
    return notes


def _extent_along(face, origin, direction):
    """(lowest, highest) m of ``face`` along the unit ``direction`` from ``origin``: its
    boundary, sampled (its edges bound it)."""
    heights = [(_vec(p, MM) - origin).dot(direction) for edge in face.Edges for p in edge.discretize(Number=33)]
    return min(heights), max(heights)


CURVE_PERIOD_NOTE = 0.95  # a grating felt this much finer across a Curve pattern's ridges, or more, is said
CURVE_PERIOD_SAMPLES = 257  # heights over a face at which the curve's lean is read


def curve_grating_periods(surface):
    """[(Object.FaceN, finest period felt mm, largest lean deg)] over the tagged faces of a
    Curve pattern that carries a texture. The ridges are the curve slid along the family's
    translation axis x (seed 000 Fig. 7; the grating's coordinate is the member's offset
    along x, CurvePattern::MemberOffset), so where the curve leans by an angle a from the
    lookup axis y, along its chord, neighbouring ridges lie lambda cos a apart across them:
    on a 90 degree arc 1.77 mm for 2.5 mm at its ends. Inherent in a translated family (no
    coordinate constant along every member has a constant gradient). Read from the core's
    pattern at the heights the face spans (beyond the curve's ends its end directions run on,
    as the renderer has them). [] for other patterns, no texture, or a curve that cannot be
    built (validate() says why)."""
    if surface.Pattern != "Curve" or surface.Texture == "None" or surface.PatternCurve is None:
        return []
    from .surface_object import active_reference_pairs

    period = float(surface.TexturePeriod)
    found = []
    for obj, sub in active_reference_pairs(surface):
        face = global_shape(obj).getElement(sub)
        frame = face_frame(face, float(surface.PatternAngle))
        try:
            _, _, y = _pattern_curve_in_plane(surface, frame)
            family = curve_pattern(surface, frame)
        except ValueError:
            return []
        lo, hi = _extent_along(face, frame[0], y)
        # the tangent's angle from x: |sin| of it is the cosine of its lean from y
        across = min(abs(math.sin(family.exact_angle(h))) for h in np.linspace(lo, hi, CURVE_PERIOD_SAMPLES))
        found.append((f"{obj.Label}.{sub}", period * across, math.degrees(math.acos(min(across, 1.0)))))
    return found


def curve_grating_notes(surface):
    """A sentence for each face on which a Curve pattern's grating is felt CURVE_PERIOD_NOTE
    finer across its ridges than its TexturePeriod, or more (curve_grating_periods), with why
    and the period that gives TexturePeriod there."""
    period = float(surface.TexturePeriod) if surface.Texture != "None" else 0.0
    notes = []
    for name, finest, lean in curve_grating_periods(surface):
        if finest >= CURVE_PERIOD_NOTE * period:
            continue
        curve = surface.PatternCurve[0].Label
        fits = (f"; a TexturePeriod of {period * period / finest:.3g} mm is felt {period:g} mm there (coarser where "
                f"it leans less)" if finest > 1e-3 * period else "")
        notes.append(f"{name}: the {period:g} mm texture grating is felt as fine as {finest:.3g} mm across its ridges, "
                     f"where {curve} leans {lean:.0f}° from the line between its ends: the ridges are copies of "
                     f"{curve} slid across that line (seed 000 Fig. 7), so where it leans by an angle a they lie "
                     f"{period:g} mm × cos a apart{fits}")
    return notes


def viscous_params(texture):
    """Eq. 2's parameters of a texture given as {surface property: value} (the core's
    ViscousTextureParams, SI)."""
    params = _core.ViscousTextureParams()
    params.f_dc = texture["TextureDC"]
    params.f_vis = texture["TextureViscosity"]
    params.beta_h = texture["TextureBeta"]
    params.alpha_h = texture["TextureAlpha"]
    params.beta_vis = texture["TextureBetaViscosity"]
    params.alpha_vis = texture["TextureAlphaViscosity"]
    params.period_m = texture["TexturePeriod"] * MM
    return params


TYPICAL_SPEEDS_MPS = (0.05, 0.12, 0.27)  # the paper's slowest, middle and fastest strokes
LEVEL_SAMPLES = 64  # over a period


def friction_notes(surface):
    """What is unusual in a surface's friction without being an error, as sentences: a
    dynamic coefficient above the static one (eq. 1's mu_s is the peak a finger must
    overcome to start sliding; mu_d above it is felt as typed, but is most often the two
    boxes swapped)."""
    mu_s, mu_d = float(surface.StaticFriction), float(surface.DynamicFriction)
    notes = []
    if mu_d > mu_s:
        notes.append(f"dynamic friction μd {mu_d:g} is above static friction μs {mu_s:g}: sliding feels stickier "
                     f"than starting to slide, which few materials do (were the two swapped?)")
    return notes + _degenerate_ellipse_notes(surface)


def _degenerate_ellipse_notes(surface):
    """The friction ellipse with a zero axis (AcrossFriction or BackwardFriction 0) has
    friction only exactly on its other axis and none a hair off it: as a hand strokes,
    none. Eq. 3 (Linear) goes to 0 over the quarter turn instead."""
    if surface.Pattern == "None" or surface.Interpolation != "Friction ellipse" or float(surface.StaticFriction) <= 0:
        return []
    zero = [(name, what) for name, what in (("AcrossFriction", "across the stripes"),
                                            ("BackwardFriction", "against the stripe direction"))
            if float(getattr(surface, name)) == 0]
    return [f"the friction ellipse with no friction {what} ({name} 0) has friction only exactly "
            f"{'along the stripes' if name == 'AcrossFriction' else 'across them'}, and none the least bit off: "
            f"a hand's stroke slides freely; choose Linear interpolation, which fades it over the quarter turn, or "
            f"give {name} above 0" for name, what in zero]


def _texture_values(surface):
    """{property: value} of a surface's own texture (eq. 2's values and its period), or None
    without one or with values that are not finite (validate() says so)."""
    if surface.Texture == "None":
        return None
    texture = {k: getattr(surface, k) for k in (*TEXTURE_VALUES, "TexturePeriod")}
    return texture if all(math.isfinite(v) for v in texture.values()) else None


def _texture_levels(texture):
    """Eq. 2's levels (unclipped) over a period at TYPICAL_SPEEDS_MPS."""
    params = viscous_params(texture)
    xs = np.arange(LEVEL_SAMPLES) * params.period_m / LEVEL_SAMPLES
    return np.array([_core.viscous_texture_level(params, x, v) for v in TYPICAL_SPEEDS_MPS for x in xs])


def texture_notes(surface, force_limit_n=None):
    """What a designer should know about a surface's texture that is not an error, as
    sentences, as the surface panel shows them: texture_shape_notes, and texture_force_note's
    at the force limit ``force_limit_n`` (N; None: the one a Feel session would render with,
    force_limit_in_use)."""
    force = texture_force_note(surface, force_limit_n)
    return texture_shape_notes(surface) + ([force] if force else [])


def texture_shape_notes(surface):
    """What a texture is felt as other than its values say, whatever the force limit, as
    sentences: eq. 2 gives levels the renderer clips (it renders 0..1 of the full range) at
    the paper's stroking speeds, harmonics that grow with their order, or, on a Curve
    pattern, a grating finer across its ridges than its period (curve_grating_notes)."""
    texture = _texture_values(surface)
    if texture is None:
        return []
    levels = _texture_levels(texture)
    notes = []
    if (levels >= 1).all():
        notes.append("the texture is at level 1 or more all over at 50-270 mm/s: felt as a flat drag at the full "
                     "range, its ridges clipped")
    elif (levels <= 0).all():
        notes.append("the texture is at level 0 or less all over at 50-270 mm/s: nothing of it is felt")
    elif (levels > 1).mean() > 0.25 or (levels < 0).mean() > 0.25:
        notes.append(f"the texture is outside levels 0..1 for {100 * ((levels > 1) | (levels < 0)).mean():.0f} % "
                     "of a period at 50-270 mm/s: clipped there")
    if texture["TextureAlpha"] < 0:
        notes.append(f"alpha_h {texture['TextureAlpha']:g} makes each harmonic stronger than the one before "
                     "(the paper's decay is 2.5)")
    return notes + curve_grating_notes(surface)


# A texture that leaves less than this share of the force limit for the press is said: at the
# default 3 N, a press of 1.5 N (about 2 mm into ABS) and the paper's strongest preset at its
# fastest stroke already pass it
TEXTURE_PRESS_SHARE = 0.5


def force_limit_in_use(doc):
    """The force limit (N) a Feel session on ``doc`` would render with now: the Preferences'
    under the chosen device's own (stiffness_study.rendered_force_limit_n)."""
    from . import preferences, stiffness_study

    return stiffness_study.rendered_force_limit_n(stiffness_study.device_render_limits(doc),
                                                  preferences.load().force_limit_n)


def _pattern_friction_factor(surface):
    """(largest factor, where) by which a surface's friction pattern scales its friction in
    some stroke direction, as the renderer scales the texture by it (1 and "" without a
    pattern): AcrossFriction across the stripes, BackwardFriction against them."""
    if surface.Pattern == "None" or float(surface.StaticFriction) <= 0:
        return 1.0, ""
    across, backward = float(surface.AcrossFriction), float(surface.BackwardFriction)
    if max(across, backward) <= 1.0:
        return 1.0, ""
    return (across, "across the stripes") if across >= backward else (backward, "against the stripes' direction")


def texture_force_note(surface, force_limit_n=None):
    """A sentence when a surface's texture, at its strongest at the paper's speeds (and
    where a friction pattern gives more friction, which it takes as friction does), leaves
    less than TEXTURE_PRESS_SHARE of the force limit ``force_limit_n`` (N; None:
    force_limit_in_use) for the press, else "". The renderer holds the whole force, press and
    drag, to the limit by scaling both down: the paper's f_DC 0.675 f_vis +0.2 at 270 mm/s
    (level 1 the 3 N limit, its drag up to 2.80 N) pressed 1.6 N had 41 % of its ticks held,
    the press down to 1.49 N, eq. 2's first harmonic 24 % weaker and its third 35 % stronger.
    It says the press that fits and a Full range that lets half the limit be pressed."""
    texture = _texture_values(surface)
    if texture is None:
        return ""
    level = float(np.clip(_texture_levels(texture), 0.0, 1.0).max())
    limit = force_limit_in_use(surface.Document) if force_limit_n is None else float(force_limit_n)
    if level <= 0 or not limit > 0:
        return ""
    factor, where = _pattern_friction_factor(surface)
    where = f" {where}, where the pattern gives {factor:g} × the friction" if where else ""
    press = TEXTURE_PRESS_SHARE * limit
    scaled = ("the press and the drag pass the limit together and the renderer scales the whole force down to "
              "it: the press is felt lighter and the grating's ridges are cut")
    if surface.TextureScale == "Friction level":  # a drag that grows with the press, as friction does
        ratio = level * float(surface.StaticFriction) * factor
        room = limit / math.sqrt(1.0 + ratio ** 2)
        if room >= press:
            return ""
        return (f"the texture drags up to {ratio:.2f} × the press at 50-270 mm/s{where} (level {level:.2f} of μs "
                f"{float(surface.StaticFriction):g} × the press): pressed harder than {room:.2f} N, {scaled}; "
                f"press lighter, or lower its levels")
    full = float(surface.TextureFullRange)
    level_one = f"its {full:g} N Full range" if full > 0 else f"the device's full range, the {limit:g} N force limit"
    drag = level * (full if full > 0 else limit) * factor
    room = math.sqrt(max(limit ** 2 - drag ** 2, 0.0))
    if room >= press:
        return ""
    fits = math.floor(100 * math.sqrt(limit ** 2 - press ** 2) / (level * factor)) / 100
    remedy = f"give Full range {fits:.2f} N or less to press up to {press:g} N"
    said = f"the texture drags up to {drag:.2f} N at 50-270 mm/s{where} (level {level:.2f} of {level_one})"
    if drag >= limit:
        return f"{said}, as much as the {limit:g} N force limit or more: under any press {scaled}; {remedy}"
    deep = ""
    if force_travel_of(surface) is None and float(surface.Stiffness) > 0:
        deep = f" ({room / float(surface.Stiffness):.2g} mm into its {float(surface.Stiffness):g} N/mm)"
    return (f"{said}, which leaves {room:.2f} N of the {limit:g} N force limit for the press: pressed harder{deep}, "
            f"{scaled}; press lighter, or {remedy}")


def curved_face_notes(surface):
    """Faces of ``surface`` on which its roughness grid or grating is laid out flat, as a
    sentence: curved faces that are neither planes nor cylinders (a cylinder's frame is
    unrolled on it, surface_frame.h; a circular or curve pattern lays the grating out
    itself), where the period is felt as given near the face's centre and longer away
    from it (1/cos of the angle the face has turned)."""
    flat_laid = [what for what, on in (("roughness grid", surface.FeelRoughness),
                                       ("grating", surface.Texture != "None" and surface.Pattern not in
                                        ("Circular", "Curve"))) if on]
    if not flat_laid:
        return []
    from .surface_object import reference_pairs

    curved = sorted({f"{o.Label}.{sub}" for o, sub in reference_pairs(surface)
                     if _surface_type(o, sub) not in (None, "Part::GeomPlane", "Part::GeomCylinder")})
    if not curved:
        return []
    return [f"on curved {', '.join(curved)} the {' and the '.join(flat_laid)} {'is' if len(flat_laid) == 1 else 'are'}"
            f" laid out on the face's tangent plane at its centre: felt as given near there and coarser away from it "
            f"(twice as coarse where the face has turned 60°; on cylinders they are laid round the face)"]


def _surface_type(obj, sub):
    """The TypeId of the surface under ``obj``'s face ``sub`` (None when it is gone)."""
    try:
        return obj.Shape.getElement(sub).Surface.TypeId
    except Exception:  # noqa: BLE001 (a face gone: validate() says so)
        return None


def _cylinder_of(face):
    """(radius m, a point on the axis m, the unit axis) of a face on a cylinder, else None."""
    try:
        cylinder = face.Surface
    except Exception:  # noqa: BLE001 (a face with no surface: laid out flat)
        return None
    if cylinder.TypeId != "Part::GeomCylinder":
        return None
    axis = _vec(cylinder.Axis)
    return cylinder.Radius * MM, _vec(cylinder.Center, MM), axis / np.linalg.norm(axis)


def laid_frame(face, frame):
    """(_core.SurfaceFrame, the face's cylinder or None) in which the roughness grid, the
    grating and the linear pattern lie on ``face``: the face_frame ``frame``, rolled round
    the face's cylinder when it has one (surface_frame.h), not on a tangent plane."""
    origin, e1, e2, _ = frame
    laid = _core.SurfaceFrame(origin, e1, e2)
    cylinder = _cylinder_of(face)
    if cylinder is not None:
        laid.radius_m, laid.axis_point_w, laid.axis_w = cylinder
    return laid, cylinder


def compile_surface(surface, face, uv=None):
    """_core.SurfaceProperties of HapticSurface ``surface`` on B-rep ``face`` (global);
    ``uv``: point_on_face(face), when known (face_frame)."""
    props = _core.SurfaceProperties()
    friction = props.friction
    friction.static_coefficient = surface.StaticFriction
    friction.dynamic_coefficient = surface.DynamicFriction
    friction.stick_speed_mps = surface.StickSpeed * MM
    friction.transition_speed_mps = surface.TransitionSpeed * MM
    friction.stribeck_speed_mps = surface.StribeckSpeed * MM
    props.friction = friction
    props.stiffness_n_per_m = surface.Stiffness / MM
    law = force_travel_of(surface)  # a stiffness study's mechanism gives instead
    if law is not None:
        props.force_travel = law
    props.damping_n_s_per_m = surface.Damping
    props.friction_mode = (_core.FrictionMode.CONE if surface.FrictionModel.startswith("Friction cone")
                           else _core.FrictionMode.VELOCITY)

    frame = face_frame(face, float(surface.PatternAngle), uv)
    origin, e1, e2, n = frame
    surface_frame, cylinder = laid_frame(face, frame)
    anisotropy = props.anisotropy
    anisotropy.across_factor = surface.AcrossFriction
    anisotropy.backward_factor = surface.BackwardFriction
    anisotropy.interpolation = (_core.AnisotropyInterpolation.ELLIPSE if surface.Interpolation == "Friction ellipse"
                                else _core.AnisotropyInterpolation.LINEAR)
    props.anisotropy = anisotropy
    if surface.Pattern == "Linear":
        # on a cylinder rolled round it as the grid is: stripes round a handle stay round it
        props.pattern = (_core.LinearPattern(e1) if cylinder is None else
                         _core.LinearPattern(e1, cylinder[0], origin, cylinder[1], cylinder[2]))
    elif surface.Pattern == "Circular":
        centre, axis = circular_centre_axis(surface)
        axis = _vec(axis)
        axis = n if np.linalg.norm(axis) == 0 else axis / np.linalg.norm(axis)
        props.pattern = _core.CircularPattern(_vec(centre, MM), axis,
                                              surface.PatternBlendRadius * MM)
    elif surface.Pattern == "Curve":
        props.pattern = curve_pattern(surface, frame)

    if surface.FeelRoughness:
        props.roughness = _core.make_roughness_grid(surface.RoughnessCategory, surface_frame,
                                                    surface.RoughnessHeight, surface.RoughnessFrictionModulation)
    texture = rendered_texture(surface)  # a similarity study's stimulus while one is held out
    if texture is not None:
        grating = _core.ViscousGrating(viscous_params(texture), surface_frame)
        grating.full_range_n = texture["TextureFullRange"]
        grating.scale = (_core.TextureScale.FRICTION_LEVEL if texture["TextureScale"] == "Friction level"
                         else _core.TextureScale.DEVICE_FORCE)
        props.texture = grating
    try:
        _core.validate_surface_properties(props)
    except ValueError as exc:
        raise ValueError(f"{surface.Label}: {exc}") from None
    return props


def compile_vibration(vibration):
    """The core's Vibration of a HapticVibration, along its axis where its part stands
    now (turned with it, also when a Body or App::Part turned it and nothing recomputed
    the vibration since). Raises ValueError naming it when its values cannot be felt (the
    core would say only "vibration 0")."""
    from .vibration_object import axis_where_felt, validate

    problems = validate(vibration)
    if problems:
        raise ValueError(f"{vibration.Label}: {'; '.join(problems)}")
    axis = _vec(axis_where_felt(vibration))
    return _core.Vibration(vibration.Frequency, vibration.Amplitude, axis / np.linalg.norm(axis),
                           vibration.Powered)
