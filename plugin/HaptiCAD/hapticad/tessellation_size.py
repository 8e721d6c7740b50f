# SPDX-License-Identifier: GPL-3.0-or-later
"""How many triangles a shape's tessellation will make, told before it is made.

``MeshPart.meshFromShape`` (OCC's BRepMesh) takes absolute deflections: a face's
triangles grow with its size over the deflection, and one face is meshed in one piece
in a time that grows faster than its triangles (a 1 m ball at Fine, one face: 251,000
triangles, 19 s and 1.15 GB; BENCHMARKS.md). ``measure(shape)`` reads what sets the
count, once: each face's kind, radii and parameter ranges (on a B-spline or any other
surface, the area and the normal curvatures along u and v of a grid of cells) and each
edge's curvature. ``ShapeSize.triangles(linear, angular)`` is then arithmetic,
so the accuracy that would fit is found by trying many.

A chord of deflection d on a radius R spans an angle 2 acos(1 - d/R) (sqrt(8 R d) long)
and the angular deflection bounds the angle of a segment; BRepMesh takes the smaller
(``GCPnts_TangentialDeflection::ArcAngularStep``). Measured against meshFromShape on
FreeCAD 0.20.2 / OCC 7.6: edges are divided at half the deflections; a sphere's face
gets a grid of 0.7 steps in u and v, a torus's the parameters of its boundary's nodes,
a cone's a grid of its largest circle's step, a plane or a cylinder only its edges' nodes;
a B-spline face is refined until its triangles keep within the linear deflection, which
leaves them smaller than the chord step (``REFINED``). A face of V interior and B
boundary nodes has 2 V + B - 2 triangles. Not foreseen: BRepMesh sometimes refines a
face curved one way only, not a cylinder's, as finely across as round (a 3 m tall
extrusion of an interpolated B-spline curve: 458,630 triangles at Fine; an ellipse made
a B-spline and extruded 300 mm: 66 at Draft, 74,648 at Fine, an arc's 84); such faces
are estimated by their edges, as a cylinder is. No GUI; FreeCAD's Part shapes in,
numbers out.
"""
import math
from dataclasses import dataclass

import numpy as np

# The most a scene is built with: a build past either waits on the GUI thread for more
# than about 15 s on the 2-core machine of BENCHMARKS.md ("Large parts").
# One face, meshed in one piece (its time grows as its triangles^1.8): 200,000 took
# 14 s and 0.83 GB, 250,000 19 s and 1.15 GB, 500,000 57 s and 3.1 GB.
MAX_FACE_TRIANGLES = 200_000
# The scene: 609,000 triangles in 48 faces took 11 s and 0.63 GB; the core's own
# benchmarks go to 1,000,000 (BENCHMARKS.md, contact engine).
MAX_SCENE_TRIANGLES = 1_000_000

EDGE_SHARE = 0.5  # an edge is divided at half the linear and angular deflection
SPHERE_STEP = 0.7  # BRepMesh_SphereRangeSplitter's grid: 0.7 of the arc step
GRID = 7  # points a side sampled on a face of no closed form
EDGE_SAMPLES = 8  # intervals sampled along an edge of no closed form


def arc_step(radius, linear, angular):
    """The angle of one segment of an arc of ``radius`` (BRepMesh's ArcAngularStep,
    without its minimum size): the chord's deflection at most ``linear``, the angle at
    most ``angular``."""
    return float(_step(1.0 / radius, linear, angular)) if radius > 0 else math.inf


def _step(curvature, linear, angular):
    """arc_step of the radius 1 / curvature (numpy too): 2 acos(1 - d k), written
    4 asin(sqrt(d k / 2)) so that a nearly flat piece is not rounded to a step of 0."""
    bend = np.minimum(linear * np.asarray(curvature, dtype=float), 2.0)
    return np.minimum(4.0 * np.arcsin(np.sqrt(0.5 * bend)), angular)


def _per_length(curvatures, linear, angular):
    """Segments per mm of pieces of these |normal curvatures| (0 where flat)."""
    curvatures = np.abs(np.asarray(curvatures, dtype=float))
    safe = np.where(curvatures > 0.0, curvatures, 1.0)
    return np.where(curvatures > 0.0, safe / _step(safe, linear, angular), 0.0)


@dataclass
class _Edge:
    kind: str  # "line", "circle", "curve" or "degenerate"
    radius: float = 0.0  # a circle's
    span: float = 0.0  # a circle's angle (rad)
    lengths: object = None  # a curve's pieces (mm) ...
    curvatures: object = None  # ... and their curvature (1/mm)

    def segments(self, linear, angular):
        linear, angular = EDGE_SHARE * linear, EDGE_SHARE * angular
        if self.kind == "degenerate":
            return 0
        if self.kind == "line":
            return 1
        if self.kind == "circle":
            return max(1, math.ceil(self.span / arc_step(self.radius, linear, angular) - 1e-9))
        return max(1, math.ceil(float(np.sum(self.lengths * _per_length(self.curvatures, linear, angular)))))


def _edge(edge):
    if edge.Degenerated:
        return _Edge("degenerate")
    curve = edge.Curve
    kind = type(curve).__name__
    if kind in ("Line", "LineSegment"):
        return _Edge("line")
    if kind == "Circle":
        return _Edge("circle", radius=curve.Radius, span=abs(edge.LastParameter - edge.FirstParameter))
    first, last = edge.FirstParameter, edge.LastParameter
    params = np.linspace(first, last, EDGE_SAMPLES + 1)
    points = np.array([tuple(edge.valueAt(p)) for p in params])
    lengths = np.linalg.norm(np.diff(points, axis=0), axis=1)  # chords: short of the arc by < 1 % here
    curvatures = []
    for p in 0.5 * (params[1:] + params[:-1]):
        try:
            curvatures.append(edge.curvatureAt(p))
        except Exception:  # noqa: BLE001 (OCC raises at an inflection: straight there)
            curvatures.append(0.0)
    if not np.any(curvatures):
        return _Edge("line")
    return _Edge("curve", lengths=lengths, curvatures=np.array(curvatures))


@dataclass
class _Face:
    kind: str  # "flat" (plane, cylinder, extrusion: its edges' nodes only), "sphere", "torus", "cone", "grid"
    boundary: list  # (edge index, times in the face's boundary: 2 for a seam)
    holes: int = 0
    fraction: float = 1.0  # of its parameter range's patch the face covers
    radius: float = 0.0  # sphere; torus: minor; cone: largest
    rounds: tuple = ()  # torus: the radii of its boundary's arcs round its axis
    span_u: float = 0.0
    span_v: float = 0.0  # a cone's: the slant length (mm)
    refined: float = 0.0  # "grid": interior nodes over a grid of chord steps (REFINED)
    # "grid": per cell of the sampled patch, its area inside the face (mm^2) and its
    # normal curvatures along u and v (1/mm)
    areas: object = None
    k_u: object = None
    k_v: object = None

    def interior(self, linear, angular):
        """Nodes BRepMesh puts inside the face."""
        if self.kind == "flat":
            return 0.0
        if self.kind == "grid":
            chord = _per_length(self.k_u, linear, math.pi) * _per_length(self.k_v, linear, math.pi)
            grid = _per_length(self.k_u, linear, angular) * _per_length(self.k_v, linear, angular)
            return float(np.sum(self.areas * np.maximum(self.refined * chord, grid)))
        if self.kind == "sphere":
            step = SPHERE_STEP * arc_step(self.radius, linear, angular)
            nodes = (self.span_u / step) * (self.span_v / step)
        elif self.kind == "torus":
            # a grid of the parameters of its boundary's nodes, edges divided as edges are:
            # round it those of its arcs round the axis (two of other steps interleave,
            # the closest left out), along it those of its tube's circles
            linear, angular = EDGE_SHARE * linear, EDGE_SHARE * angular
            steps = sorted({round(arc_step(r, linear, angular), 12) for r in self.rounds})
            counts = [self.span_u / step for step in steps]
            nu = counts[0] + sum(n * n / (n + counts[0]) for n in counts[1:])
            nv = self.span_v / arc_step(self.radius, linear, angular)
            nodes = max(nu - 1.0, 0.0) * max(nv - 1.0, 0.0)
        else:  # cone: a grid of its largest circle's step round it and that length along
            step = arc_step(self.radius, linear, angular)
            nodes = math.floor(self.span_u / step) * math.floor(self.span_v / (step * self.radius))
        return self.fraction * nodes


# A face of no closed form is refined until its triangles keep within the linear
# deflection: interior nodes over those of a grid of chord steps both ways, measured
# (tessellation_size_test): 4.4-11.5 on B-spline faces (lofts, interpolated, spheres,
# ellipsoids, tori), 3.6-6 on surfaces of revolution.
REFINED = {"Part::GeomSurfaceOfRevolution": 4.5}
REFINED_OTHER = 7.5
FLAT_KINDS = ("Part::GeomPlane", "Part::GeomCylinder", "Part::GeomSurfaceOfExtrusion")


def _grid(face, surface, u0, u1, v0, v1):
    """A face of no closed form sampled on (GRID + 1)^2 points of its parameter range:
    per cell, its area inside the face and its normal curvatures along u and v."""
    us, vs = np.linspace(u0, u1, GRID + 1), np.linspace(v0, v1, GRID + 1)
    points = np.array([[tuple(surface.value(float(u), float(v))) for v in vs] for u in us])  # [u][v]
    du, dv = np.gradient(points, axis=0), np.gradient(points, axis=1)
    normal = np.cross(du, dv)
    size = np.linalg.norm(normal, axis=2, keepdims=True)
    normal = np.divide(normal, size, out=np.zeros_like(normal), where=size > 0)

    def curvature(first, axis):
        bend = np.einsum("ijk,ijk->ij", np.gradient(first, axis=axis), normal)
        speed = np.sum(first * first, axis=2)
        k = np.abs(np.divide(bend, speed, out=np.zeros_like(bend), where=speed > 1e-24))
        return 0.25 * (k[1:, 1:] + k[:-1, 1:] + k[1:, :-1] + k[:-1, :-1])  # per cell

    areas = 0.5 * np.linalg.norm(np.cross(points[1:, 1:] - points[:-1, :-1], points[:-1, 1:] - points[1:, :-1]),
                                 axis=2)
    bounds = surface.bounds()
    trimmed = (len(face.Wires) > 1 or max(abs(x - y) for x, y in zip(bounds, (u0, u1, v0, v1))) > 1e-9)
    if trimmed:  # a cell counts as far as its centre is in the face
        centres_u, centres_v = 0.5 * (us[1:] + us[:-1]), 0.5 * (vs[1:] + vs[:-1])
        inside = np.array([[face.isPartOfDomain(float(u), float(v)) for v in centres_v] for u in centres_u])
        areas = areas * inside
    return areas, curvature(du, 0), curvature(dv, 1)


def _face(face, edge_index):
    boundary = {}
    for edge in face.Edges:
        key = edge_index.setdefault(edge.hashCode(), (len(edge_index), edge))[0]
        boundary[key] = boundary.get(key, 0) + (2 if edge.isSeam(face) else 1)
    described = _Face("flat", sorted(boundary.items()), holes=max(len(face.Wires) - 1, 0))
    surface = face.Surface
    kind = surface.TypeId
    if kind in FLAT_KINDS:
        return described
    u0, u1, v0, v1 = face.ParameterRange
    described.span_u, described.span_v = u1 - u0, v1 - v0
    if kind == "Part::GeomSphere":
        r = surface.Radius
        described.kind, described.radius = "sphere", r
        patch = r * r * (u1 - u0) * (math.sin(v1) - math.sin(v0))
    elif kind == "Part::GeomToroid":
        big, r = surface.MajorRadius, surface.MinorRadius
        described.kind, described.radius = "torus", r
        described.rounds = tuple(edge.Curve.Radius for edge in face.Edges
                                 if type(edge.Curve).__name__ == "Circle"
                                 and edge.Curve.Axis.cross(surface.Axis).Length < 1e-9)
        if not described.rounds:  # no arc round it: its outermost circle
            described.rounds = (big + r * (1.0 if _holds_zero(v0, v1) else max(math.cos(v0), math.cos(v1))),)
        patch = r * (u1 - u0) * (big * (v1 - v0) + r * (math.sin(v1) - math.sin(v0)))
    elif kind == "Part::GeomCone":
        base, semi = surface.Radius, surface.SemiAngle
        ends = (abs(base + v0 * math.sin(semi)), abs(base + v1 * math.sin(semi)))
        if max(ends) <= 0.0:
            return described
        described.kind, described.radius = "cone", max(ends)
        patch = (u1 - u0) * (v1 - v0) * 0.5 * sum(ends)
    else:
        described.kind, described.refined = "grid", REFINED.get(kind, REFINED_OTHER)
        described.areas, described.k_u, described.k_v = _grid(face, surface, u0, u1, v0, v1)
        return described
    described.fraction = min(1.0, face.Area / patch) if patch > 0 else 1.0
    return described


def _holds_zero(v0, v1):
    """Whether [v0, v1] holds an angle 2 pi k (a torus's outermost circle)."""
    return math.floor(v1 / (2 * math.pi)) >= math.ceil(v0 / (2 * math.pi))


class ShapeSize:
    """What sets a shape's triangle count at any deflection (``measure``)."""

    def __init__(self, faces, edges):
        self.faces = faces
        self.edges = edges

    def face_triangles(self, linear_mm, angular_rad):
        """Triangles each face (Face1, Face2, ...) makes at these deflections: 2 V + B - 2
        (+ 2 a hole) for its V interior and B boundary nodes."""
        segments = [edge.segments(linear_mm, angular_rad) for edge in self.edges]
        counts = []
        for face in self.faces:
            boundary = sum(segments[index] * times for index, times in face.boundary)
            counts.append(max(2.0 * face.interior(linear_mm, angular_rad) + boundary - 2 + 2 * face.holes, 1.0))
        return np.array(counts)

    def triangles(self, linear_mm, angular_rad):
        return float(self.face_triangles(linear_mm, angular_rad).sum())


def measure(shape):
    """The ShapeSize of a FreeCAD shape (its faces and edges as they are placed)."""
    edge_index = {}
    faces = [_face(face, edge_index) for face in shape.Faces]
    edges = [_edge(edge) for _, edge in sorted(edge_index.values(), key=lambda pair: pair[0])]
    return ShapeSize(faces, edges)


class TooManyTriangles(ValueError):
    """A scene refused before anything is meshed: it would make more triangles than
    MAX_FACE_TRIANGLES in a face or MAX_SCENE_TRIANGLES in all. The message names the
    part, about how many, and the deflections that would fit."""


def refuse_too_many(parts, accuracy):
    """Raises TooManyTriangles when the shapes of ``parts`` ([(label, shape)]) would make
    too many triangles at ``accuracy`` (an accuracy.Accuracy); returns the estimate of
    all their triangles otherwise. Milliseconds: nothing is meshed."""
    sizes = [(label, measure(shape)) for label, shape in parts]

    def counts(linear, angular):
        return [(label, size.face_triangles(linear, angular)) for label, size in sizes]

    found = counts(accuracy.linear_deflection_mm, accuracy.angular_deflection_rad)
    total = sum(float(faces.sum()) for _, faces in found)
    if not _too_many(found):
        return total
    worst_label, worst = max(found, key=lambda part: part[1].max() if len(part[1]) else 0.0)
    if worst.max() > MAX_FACE_TRIANGLES:
        what = (f"{worst_label}: about {_about(worst.max())} triangles in its Face{int(worst.argmax()) + 1} at "
                f"{accuracy.deflections()}, more than the {MAX_FACE_TRIANGLES:,} a face is meshed to (a face is "
                "meshed in one piece, the slower the more it has: 200,000 take about 15 s and 0.8 GB, FreeCAD "
                "waiting)")
    else:
        named = sorted(found, key=lambda part: -float(part[1].sum()))
        listed = ", ".join(f"{label} about {_about(faces.sum())}" for label, faces in named[:3])
        more = f" and {len(named) - 3} more" if len(named) > 3 else ""
        what = (f"the tagged parts would make about {_about(total)} triangles ({listed}{more}) at "
                f"{accuracy.deflections()}, more than the {MAX_SCENE_TRIANGLES:,} a scene is built with (about "
                "15 s and 1 GB, FreeCAD waiting)")
    raise TooManyTriangles(f"{what}: {_what_fits(counts, accuracy)}. Nothing was built.")


def _too_many(found):
    return (any(len(faces) and faces.max() > MAX_FACE_TRIANGLES for _, faces in found)
            or sum(float(faces.sum()) for _, faces in found) > MAX_SCENE_TRIANGLES)


def _about(count):
    """A count to three figures, with thousands separators: 252,000."""
    count = float(count)
    if count < 1000:
        return f"{count:.0f}"
    return f"{round(count, 2 - int(math.floor(math.log10(count)))):,.0f}"


def _what_fits(counts, accuracy):
    """What the designer may give instead, in the Preferences' and `hapticad feel`'s units:
    the least linear deflection that fits (the angle kept), the least angular one (the
    linear kept), both together if neither alone does, and the finest preset that fits."""
    from . import accuracy as accuracies

    linear, angular = accuracy.linear_deflection_mm, accuracy.angular_deflection_rad
    top_linear, top_angular = accuracies.LINEAR_RANGE_MM[1], accuracies.ANGULAR_RANGE_RAD[1]

    def fits(lin, ang):
        return not _too_many(counts(lin, ang))

    said, flags = [], []
    coarser_linear = _least(lambda x: fits(x, angular), linear, top_linear, _up)
    if coarser_linear is not None:
        said.append(f"a linear deflection of {coarser_linear:g} mm or more")
        flags.append(f"--linear-deflection {coarser_linear:g}")
    coarser_angle = _least(lambda deg: fits(linear, math.radians(deg)), math.degrees(angular),
                           accuracies.ANGULAR_RANGE_DEG_SHOWN[1], _up_shown)
    if coarser_angle is not None:
        said.append(f"an angular deflection of {coarser_angle:g} degrees or more")
        flags.append(f"--angular-deflection {coarser_angle:g}")
    if not said:  # neither alone: both, by one factor
        factor = _least(lambda t: fits(min(linear * t, top_linear), min(angular * t, top_angular)), 1.0,
                        max(top_linear / linear, top_angular / angular), lambda t: t)
        if factor is None:
            return ("no accuracy HaptiCAD takes makes it few enough (at most a linear deflection of "
                    f"{top_linear:g} mm and an angular one of {accuracies.ANGULAR_RANGE_DEG_SHOWN[1]:g} degrees): "
                    "tag a smaller part, or feel this one in pieces")
        both_angle = min(_up_shown(math.degrees(min(angular * factor, top_angular))),
                         accuracies.ANGULAR_RANGE_DEG_SHOWN[1])
        # at that angle, the least linear deflection
        both_linear = _least(lambda x: fits(x, math.radians(both_angle)), linear, top_linear, _up)
        said.append(f"a linear deflection of {both_linear:g} mm with an angular one of {both_angle:g} degrees")
        flags.append(f"--linear-deflection {both_linear:g} --angular-deflection {both_angle:g}")
    presets = [p for p in accuracies.PRESETS.values()
               if p.name != accuracy.name and fits(p.linear_deflection_mm, p.angular_deflection_rad)]
    preset = ""
    if presets:
        finest = min(presets, key=lambda p: (p.linear_deflection_mm, p.angular_deflection_rad))
        made = sum(float(f.sum()) for _, f in counts(finest.linear_deflection_mm, finest.angular_deflection_rad))
        preset = f", or the {finest.name} preset (about {_about(made)} triangles)"
    return (f"{' or '.join(said)} fits{preset}; set it in Preferences (HaptiCAD > Accuracy: Custom), or give "
            f"hapticad feel {' or '.join(flags)}")


def _least(fits, low, high, shown):
    """The least value in [low, high], as ``shown`` rounds it up, for which ``fits`` holds
    (None if not even at high); ``fits`` is taken to hold from some value on."""
    if not fits(high):
        return None
    below, above = low, high
    for _ in range(40):
        middle = math.sqrt(below * above)
        below, above = (below, middle) if fits(middle) else (middle, above)
    value = shown(above)
    while value < high and not fits(value):  # rounded onto a count a shade above the limit
        value = shown(value * 1.01)
    return min(value, high)


def _up(value):
    """Rounded up to two significant figures: 0.0252 -> 0.026."""
    scale = 10.0 ** (math.floor(math.log10(value)) - 1)
    return round(math.ceil(value / scale - 1e-9) * scale, 12)


def _up_shown(degrees):
    """An angle in degrees rounded up to two significant figures, as the Preferences page
    shows it (four decimals at most)."""
    return round(_up(degrees), 4)
