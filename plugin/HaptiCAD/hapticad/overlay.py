# SPDX-License-Identifier: GPL-3.0-or-later
"""What the overlay draws on tagged faces: colours, stripes and the legend.

The overlay is drawn by the HapticSurface's view provider in its own scene graph, over
the user's part, which keeps its own colours. This module computes what to draw and
needs no GUI (tested headless):

- each tagged face as triangles in global mm, with vertex normals;
- its colour, by material or by roughness category;
- for a friction pattern, a stripe coordinate per vertex: black and white stripes run
  along the direction of lowest friction, as seed 000 draws them (linear: straight
  stripes; circular: rings, or spokes when friction is lower across the rings; curve:
  the parallel copies of the curve);
- the legend's entries.

Labels are ASCII: Coin's text nodes do not take every Unicode character.
"""
import colorsys
import math
import zlib
from dataclasses import dataclass

import numpy as np

from . import _core, materials
from .roughness_text import ra_band
from .surface_compile import curve_pattern, face_frame, global_shape, laid_frame
from .surface_object import circular_centre_axis

MM = 1e-3
STRIPES_PER_FACE = 10  # stripe pairs across a face: readable at any zoom that shows the face
SPOKES = 24  # stripe pairs around a circular pattern with friction lowest across the rings
MIN_STRIPE_PERIOD_MM = 0.2

# 7 categories, smooth (pale) to rough (dark), a sequential palette readable on grey parts
ROUGHNESS_COLOURS = [
    (0.99, 0.91, 0.65), (0.99, 0.78, 0.40), (0.98, 0.60, 0.25), (0.93, 0.40, 0.18),
    (0.80, 0.22, 0.15), (0.60, 0.10, 0.16), (0.40, 0.05, 0.20),
]
# distinct hues for materials, in database order (stable between sessions)
MATERIAL_COLOURS = [
    (0.12, 0.47, 0.71), (0.17, 0.63, 0.17), (0.89, 0.47, 0.76), (0.58, 0.40, 0.74),
    (0.09, 0.75, 0.81), (0.74, 0.74, 0.13), (0.55, 0.34, 0.29), (1.00, 0.50, 0.05),
    (0.84, 0.15, 0.16), (0.50, 0.50, 0.50),
]


def material_colour(name):
    """RGB (0..1) of a material: its database position picks a hue."""
    names = materials.default_database().names()
    if name in names:
        i = names.index(name)
        if i < len(MATERIAL_COLOURS):
            return MATERIAL_COLOURS[i]
        hue = (i * 0.618034) % 1.0  # golden-ratio hues beyond the table
        return colorsys.hsv_to_rgb(hue, 0.65, 0.85)
    # a material not in the database (a document from elsewhere): a hue of its own, not a
    # grey next to the table's
    hue = (zlib.crc32(str(name).encode()) % 1000) / 1000.0
    return colorsys.hsv_to_rgb(hue, 0.45, 0.75)


# friction edited off the material's listed values shades its colour: darker for more,
# lighter for less, by up to this share at twice (or half) the listed mu, and at least a
# quarter of it, so an edit is seen next to the material as listed
EDITED_SHADE = 0.45


def friction_shade(surface):
    """-1..1: how far a surface's friction is edited from its material's listed values
    (log2 of the ratio, the dynamic mu's, else the static's, clipped, and at least 0.25
    when edited at all); 0 when as listed or the material is not in the database."""
    database = materials.default_database()
    if surface.Material not in database:
        return 0.0
    listed = database.get(surface.Material)
    for value, base in ((surface.DynamicFriction, listed.dynamic_friction),
                        (surface.StaticFriction, listed.static_friction)):
        if base > 0 and abs(value - base) > 1e-9 * base:
            # no friction at all is as far below as it goes (log2 of 0 is -inf: clipped)
            step = min(1.0, abs(math.log2(value / base))) if value > 0 else 1.0
            return math.copysign(max(0.25, step), value - base)
    return 0.0


def roughness_colour(category):
    return ROUGHNESS_COLOURS[max(1, min(7, int(category))) - 1]


def surface_colour(surface, colour_by):
    if colour_by == "Roughness":
        return roughness_colour(surface.RoughnessCategory)
    rgb = material_colour(surface.Material)
    shade = friction_shade(surface) * EDITED_SHADE
    if shade > 0:
        return tuple(c * (1 - shade) for c in rgb)
    return tuple(c + (1 - c) * -shade for c in rgb)


def roughness_label(category):
    return f"Roughness {category}: {ra_band(_core.roughness_category(int(category)), ascii_only=True)}"


def material_label(surface):
    shade = friction_shade(surface)
    edited = "" if shade == 0 else f" (edited: {'more' if shade > 0 else 'less'} friction than listed)"
    return f"{surface.Material}: mu_s {surface.StaticFriction:.2f}, mu_d {surface.DynamicFriction:.2f}{edited}"


def draws_stripes(surface):
    """True when the surface's overlay has stripes: a pattern, and for a Curve pattern a
    curve that is there (its sketch deleted, the stripes go and the legend must not
    explain them)."""
    if surface.Pattern == "Curve":
        from .surface_compile import _curve_edges

        link = surface.PatternCurve
        try:
            return bool(link and link[0] is not None and _curve_edges(link))
        except ValueError:
            return False
    return surface.Pattern != "None"


def legend_entries(surfaces, colour_by):
    """[(rgb, label), ...] for the legend: one per colour in use on a shown part, then the
    stripes key."""
    entries, seen = [], set()
    patterned = False
    for s in surfaces:
        if not shown_reference_pairs(s):
            continue
        key = s.RoughnessCategory if colour_by == "Roughness" else (s.Material, s.StaticFriction, s.DynamicFriction)
        patterned = patterned or draws_stripes(s)
        if key in seen:
            continue
        seen.add(key)
        label = roughness_label(s.RoughnessCategory) if colour_by == "Roughness" else material_label(s)
        entries.append((surface_colour(s, colour_by), label))
    if colour_by == "Roughness":
        entries.sort(key=lambda e: e[1])
    if patterned:
        entries.append((None, "Stripes: direction of lowest friction"))
    return entries


@dataclass
class OverlayFace:
    name: str  # "Object.FaceN"
    points: np.ndarray  # #V x 3, global mm
    normals: np.ndarray  # #V x 3, unit, outward
    triangles: np.ndarray  # #T x 3 indices
    stripes: object  # #V stripe coordinates (1 per stripe pair), or None without a pattern
    colour: tuple


def _global_face(obj, sub):
    return global_shape(obj).getElement(sub)


_MESHES = {}  # (face key) -> (points, normals, triangles): geometry edits are rarer than value edits
_MESH_CACHE_SIZE = 64
FINE_EDGES_PER_FACE = 25  # rings and curves need interior vertices: edge <= face size / this


def _face_key(face, fine):
    c, box = face.CenterOfMass, face.BoundBox
    return (fine, round(face.Area, 9), round(c.x, 9), round(c.y, 9), round(c.z, 9),
            round(box.XMin, 9), round(box.YMin, 9), round(box.ZMin, 9),
            round(box.XMax, 9), round(box.YMax, 9), round(box.ZMax, 9), len(face.Edges))


def _tessellate(face, fine):
    """(points, normals, triangles) of a face; ``fine`` adds interior vertices (Mefisto)
    so that stripe coordinates that are not linear in position (rings) interpolate well."""
    key = _face_key(face, fine)
    if key not in _MESHES:
        if len(_MESHES) >= _MESH_CACHE_SIZE:
            _MESHES.pop(next(iter(_MESHES)))
        _MESHES[key] = _calc_tessellation(face, fine)
    return _MESHES[key]


def _calc_tessellation(face, fine):
    box = face.BoundBox
    if fine:
        import MeshPart

        mesh = MeshPart.meshFromShape(Shape=face, MaxLength=max(box.DiagonalLength / FINE_EDGES_PER_FACE, 1e-3))
        points, triangles = mesh.Topology
    else:
        points, triangles = face.tessellate(max(box.DiagonalLength / 150.0, 1e-3))
    pts = np.array([(p.x, p.y, p.z) for p in points], dtype=float).reshape(-1, 3)
    tris = np.array(triangles, dtype=np.int32).reshape(-1, 3)
    normals = []
    surface = face.Surface
    for p in points:
        u, v = surface.parameter(p)
        n = face.normalAt(u, v)
        normals.append((n.x, n.y, n.z))
    return pts, np.array(normals, dtype=float).reshape(-1, 3), tris


def _stripe_direction_is_e1(surface):
    """True when friction is lowest along the pattern's first direction (mu_a <= mu_n)."""
    return surface.AcrossFriction >= 1.0


def stripe_coordinates(surface, face, points_mm):
    """Stripe coordinate per point (mm, or None without a pattern): constant along the
    direction of lowest friction, so iso-lines of it are the stripes."""
    pattern = surface.Pattern
    if pattern == "None":
        return None, None
    origin_m, e1, e2, n = face_frame(face, float(surface.PatternAngle))
    origin = np.asarray(origin_m) / MM
    along_first = _stripe_direction_is_e1(surface)
    if pattern == "Linear":  # laid as it is felt: round a cylinder, not on its tangent plane
        laid, _ = laid_frame(face, (origin_m, e1, e2, n))
        xy = np.asarray(_core.frame_coordinates(laid, np.asarray(points_mm, float) * MM)) / MM
        return xy[:, 1] if along_first else xy[:, 0], "length"
    if pattern == "Circular":
        centre, axis = circular_centre_axis(surface)
        centre, axis = np.array([centre.x, centre.y, centre.z]), np.array([axis.x, axis.y, axis.z])
        axis = np.asarray(n) if np.linalg.norm(axis) == 0 else axis / np.linalg.norm(axis)
        d = points_mm - centre
        radial = d - np.outer(d @ axis, axis)
        if along_first:  # friction lowest along the circles: rings
            return np.linalg.norm(radial, axis=1), "length"
        # lowest across the circles: spokes, by angle about the axis
        ref = radial[np.argmax(np.linalg.norm(radial, axis=1))]
        ref = ref / max(np.linalg.norm(ref), 1e-12)
        other = np.cross(axis, ref)
        return np.arctan2(radial @ other, radial @ ref), "angle"
    if pattern == "Curve":
        frame = (origin_m, e1, e2, n)
        family = curve_pattern(surface, frame)
        offsets = np.array([family.member_offset(p * MM) for p in points_mm]) / MM
        if along_first:
            return offsets, "length"
        # lowest across the curves: stripes across them, approximated by lines across the
        # curve's chord (exact for straight curves)
        return (points_mm - origin) @ _chord_direction(surface, np.asarray(n)), "length"
    return None, None


def _chord_direction(surface, n):
    from .surface_compile import _as_bspline, _curve_edges

    curve = _as_bspline(_curve_edges(surface.PatternCurve))
    a, b = curve.value(curve.FirstParameter), curve.value(curve.LastParameter)
    chord = np.array([b.x - a.x, b.y - a.y, b.z - a.z])
    chord -= chord.dot(n) * n
    return chord / max(np.linalg.norm(chord), 1e-12)


def overlay_face(surface, obj, sub, colour_by):
    """The OverlayFace of face ``sub`` of ``obj`` as ``surface`` tags it."""
    face = _global_face(obj, sub)
    fine = surface.Pattern in ("Circular", "Curve")
    points, normals, triangles = _tessellate(face, fine)
    stripes = None
    try:
        values, kind = stripe_coordinates(surface, face, points)
    except ValueError:  # e.g. a Curve pattern without its curve: no stripes, the panel says why
        values, kind = None, None
    if values is not None and len(values):
        if kind == "angle":
            stripes = values * SPOKES / (2 * math.pi)
        else:
            extent = float(values.max() - values.min())
            period = max(extent / STRIPES_PER_FACE, MIN_STRIPE_PERIOD_MM)
            stripes = (values - values.min()) / period
    return OverlayFace(f"{obj.Name}.{sub}", points, normals, triangles, stripes,
                       surface_colour(surface, colour_by))


def face_outline(obj, sub):
    """Polylines (global mm) along the edges of a face, to outline it."""
    try:
        face = _global_face(obj, sub)
    except Exception:
        return []
    lines = []
    for edge in face.Edges:
        points = edge.discretize(Deflection=max(edge.Length / 200.0, 1e-3)) if edge.Length > 0 else []
        if len(points) >= 2:
            lines.append([(p.x, p.y, p.z) for p in points])
    return lines


def is_shown(obj):
    """True when ``obj`` is drawn: it, and every App::Part or Body holding it, is visible.
    (Hiding an App::Part hides its content but leaves each child's Visibility on.)"""
    while obj is not None:
        if not obj.Visibility:
            return False
        obj = obj.getParentGeoFeatureGroup()
    return True


def shown_reference_pairs(surface):
    """The (object, "FaceN") a surface tags on parts that are drawn (broken references
    left out): an overlay on a hidden part would float in the air, and its legend entry
    would explain nothing in view."""
    from .surface_object import active_reference_pairs

    return [(obj, sub) for obj, sub in active_reference_pairs(surface) if is_shown(obj)]


def overlay_faces(surface, colour_by="Material"):
    """OverlayFaces of every face a surface tags on a shown part (shown_reference_pairs).
    A face its part no longer has is left out quietly: the part was just recomputed and
    the surface's own recompute, still to come, follows the face or says once that its
    reference broke (surface_object.validate)."""
    faces = []
    for obj, sub in shown_reference_pairs(surface):
        if not _has_face(obj, sub):
            continue
        try:
            faces.append(overlay_face(surface, obj, sub, colour_by))
        except Exception as exc:  # a face that cannot be drawn must not hide the others
            import FreeCAD as App

            App.Console.PrintWarning(f"{surface.Label}: the overlay leaves out {obj.Label}.{sub}, whose shape "
                                     f"cannot be drawn ({exc}); it is still felt\n")
    return faces


def _has_face(obj, sub):
    try:
        return not obj.Shape.getElement(sub).isNull()
    except Exception:  # noqa: BLE001 (Part raises its own error for a missing element)
        return False
