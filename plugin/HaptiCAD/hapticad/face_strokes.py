# SPDX-License-Identifier: GPL-3.0-or-later
"""Pick a stroke that stays on one B-rep face (for the demo and for tests).

Candidates run along either parameter direction, across a few levels of the other
parameter, over ``fraction`` of the range; a candidate counts only if every sample of
its chord lies on the face (holes and fused-on features excluded) and close to it.
The longest valid one wins, ties going to the flattest, so strokes on cylinders run
along the axis. No GUI.
"""
import FreeCAD as App
import Part


LEVELS = (0.5, 0.3, 0.7, 0.15, 0.85)


def _candidates(face, fraction):
    u0, u1, v0, v1 = face.ParameterRange
    half = 0.5 * fraction
    for level in LEVELS:
        v = v0 + level * (v1 - v0)
        um = 0.5 * (u0 + u1)
        yield (um - half * (u1 - u0), v), (um + half * (u1 - u0), v)
        u = u0 + level * (u1 - u0)
        vm = 0.5 * (v0 + v1)
        yield (u, vm - half * (v1 - v0)), (u, vm + half * (v1 - v0))


def plan_face_stroke(face, fraction=0.6, samples=13):
    """(p0, p1) as FreeCAD Vectors on ``face``, or None if no straight stroke fits."""
    best = None
    for (ua, va), (ub, vb) in _candidates(face, fraction):
        p0, p1 = face.valueAt(ua, va), face.valueAt(ub, vb)
        length = (p1 - p0).Length
        if length < 1e-6:
            continue
        worst = 0.0
        for i in range(samples):
            point = p0 + (p1 - p0) * (i / (samples - 1))
            # on the face (not in a hole or under a fused feature) and near its surface
            u, v = face.Surface.parameter(point)
            if not face.isInside(face.valueAt(u, v), 1e-6, True):
                break
            worst = max(worst, face.distToShape(Part.Vertex(point))[0])
            if worst > 0.05 * length:
                break
        else:
            key = (round(length, 6), -worst)
            if best is None or key > best[0]:
                best = (key, p0, p1)
    return None if best is None else (best[1], best[2])


def vector_tuple(v):
    return (v.x, v.y, v.z) if isinstance(v, App.Vector) else tuple(v)
