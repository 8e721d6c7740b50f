# SPDX-License-Identifier: GPL-3.0-or-later
"""Face references that survive model edits, or say plainly that they broke.

FreeCAD 0.20 names faces by index ("Face3"), and a model edit can renumber them: in
Box minus Cylinder, moving the cylinder onto a corner turns the top face from Face6
into Face3 while "Face6" then names a side face. So each referenced face keeps a
geometric *signature*, and after every recompute the reference is re-matched:

- **ok**: the name still names the face the signature describes;
- **rematched**: the face now has another name, found unambiguously; the reference
  follows it (the status says so, nothing is silent);
- **broken**: no face, or more than one, fits; the reference keeps its old name and
  signature (so it comes back if the edit is undone) and is left out of the scene.

A signature is taken in the shape's own frame (its Placement removed), so moving a
part, or the App::Part holding it, changes nothing. Lengths in mm. Matching goes from
strict to loose and accepts only a *unique* candidate at the first level that has any:

1. the same face: same underlying surface, area and centre of mass;
2. the same underlying surface (plane, cylinder, ... with the same parameters): the
   face was trimmed or extended, e.g. a corner cut off the top face;
3. the same kind of surface facing the same way (plane normal, cylinder axis and
   sense): the face moved, e.g. the box got taller.

At the two loose levels the tagged face's *rivals* decide too: the other faces of the
part, at the last match, that level 3 could confuse with it (a second hole bored the
same way, the other faces of a B-spline part). Those still there unchanged are no
candidates. Rivals that changed too must have moved with the tagged face, one face
now for each, told apart by area (a longer Pad lifts its top face and the floor of a
Pocket sketched on it): else nothing tells the tagged face from one of them, and it
is broken. Without them, removing the tagged hole moved its tag onto the other hole
and called that "ok". So each surface keeps the signatures of its parts' faces at the
last match (tables(); one list per part, not per reference). A document written
before has them taken when it opens. When no face is left at a level at all (a
pattern's keys made taller: every top left their plane together), the next level
decides, with its own, wider, rivals.

Moved rivals that area does not tell apart are told apart by place, but only when the
tagged face clearly stayed put (Previous.stayed_near): a Fillet on four edges made
larger changes four equal faces, and the tagged one moved 1 mm while the others are at
the other corners, 28 mm and more away. Its centre must have moved less than NEAR of the
way to its nearest moved rival (one still there unchanged is that face now, no other's),
every other candidate must be CLEAR of that way off, and its
area must be no nearer a moved rival's than its own. Anything less is left broken: a
step whose two tops both rose 1 mm with their centres 5.4 mm apart, two holes of
different sizes that moved past each other (the one now nearest is the other hole), a
face that split or came or went.

No GUI; used by the HapticSurface object on every recompute.
"""
import math

import FreeCAD as App

OK, REMATCHED, BROKEN = "ok", "rematched", "broken"
STATUSES = (OK, REMATCHED, BROKEN)
ANGLE_TOLERANCE = 1e-7  # 1 - cos of the angle two directions may differ by (about 0.03 degrees)
RELATIVE_TOLERANCE = 1e-6  # of the shape's size, for lengths; of the area, for areas
# a face whose rivals moved too is followed by place (Previous.stayed_near) when its centre moved
# less than NEAR of the distance to its nearest moved rival, and every other candidate is at least CLEAR
# of that distance off: the face taken is then wrong only if a rival moved 9 times as far as the
# tagged face seems to have, and the tagged face itself moved half the distance. A step whose two
# tops both rose 1 mm, 5.4 mm apart (a fifth), stays broken
NEAR = 0.1
CLEAR = 0.5


def _vec(v):
    return [float(v.x), float(v.y), float(v.z)]


def local_shape(shape):
    """A copy of ``shape`` in its own frame (Placement removed)."""
    local = shape.copy()
    local.Placement = App.Placement()
    return local


def _uv_on_face(face):
    u, v = face.Surface.parameter(face.CenterOfMass)
    if face.isInside(face.valueAt(u, v), 1e-6, True):
        return u, v
    u0, u1, v0, v1 = face.ParameterRange
    return 0.5 * (u0 + u1), 0.5 * (v0 + v1)


def _axis_line(position, direction):
    """A line as (unit direction with a canonical sign, its point closest to the origin)."""
    d = App.Vector(direction)
    d.normalize()
    # canonical sign: the first clearly non-zero component positive
    for c in (d.x, d.y, d.z):
        if abs(c) > 1e-9:
            if c < 0:
                d = -d
            break
    p = App.Vector(position)
    foot = p - d * p.dot(d)
    return _vec(d), _vec(foot)


def _surface_parameters(face, normal, point):
    """(kind, parameters, orientation) of the face's underlying surface; parameters are
    what identifies the surface, orientation what a moved copy would keep."""
    surface = face.Surface
    kind = type(surface).__name__
    if kind == "Plane":
        n = App.Vector(normal)
        return kind, {"normal": _vec(n), "offset": float(n.dot(point))}, {"normal": _vec(n)}
    if kind in ("Cylinder", "Cone", "Sphere", "Toroid"):
        centre = surface.Center
        axis, foot = _axis_line(centre, surface.Axis)
        # sense: +1 when the face points away from the axis (a boss), -1 toward it (a hole)
        radial = point - App.Vector(*foot)
        along = App.Vector(*axis)
        radial = radial - along * radial.dot(along)
        sense = 1 if radial.Length == 0 or App.Vector(normal).dot(radial) >= 0 else -1
        params = {"axis": axis, "foot": foot}
        if kind == "Cylinder":
            params["radius"] = float(surface.Radius)
        elif kind == "Cone":
            params.update(apex=_vec(surface.Apex), semi_angle=float(surface.SemiAngle))
        elif kind == "Sphere":
            params.update(centre=_vec(centre), radius=float(surface.Radius))
        else:
            params.update(centre=_vec(centre), major=float(surface.MajorRadius),
                          minor=float(surface.MinorRadius))
        orientation = {"sense": sense}
        if kind in ("Cylinder", "Cone", "Toroid"):
            orientation["axis"] = axis
        return kind, params, orientation
    return kind, {}, {}


def face_signature(face):
    """The signature of a B-rep face (in the frame it is given in), JSON-ready."""
    u, v = _uv_on_face(face)
    point = face.valueAt(u, v)
    normal = face.normalAt(u, v)
    kind, params, orientation = _surface_parameters(face, normal, point)
    return {
        "type": kind,
        "surface": params,
        "orientation": orientation,
        "area": float(face.Area),
        "centre": _vec(face.CenterOfMass),
    }


def shape_signatures(shape):
    """Signatures of every face of ``shape`` in its own frame, and its size (mm)."""
    local = local_shape(shape)
    size = local.BoundBox.DiagonalLength if local.BoundBox.isValid() else 1.0
    return [face_signature(f) for f in local.Faces], max(size, 1.0)


def _close(a, b, tolerance):
    if isinstance(a, (list, tuple)):
        return len(a) == len(b) and all(abs(x - y) <= tolerance for x, y in zip(a, b))
    return abs(a - b) <= tolerance


def _same_direction(a, b):
    return sum(x * y for x, y in zip(a, b)) >= 1.0 - ANGLE_TOLERANCE


def _same_dict(a, b, length_tol):
    if a.keys() != b.keys():
        return False
    for key in a:
        if key in ("normal", "axis"):
            if not _same_direction(a[key], b[key]):
                return False
        elif key == "semi_angle":
            if not _close(a[key], b[key], math.sqrt(2 * ANGLE_TOLERANCE)):
                return False
        elif key == "sense":
            if a[key] != b[key]:
                return False
        elif not _close(a[key], b[key], length_tol):
            return False
    return True


def same_orientation(a, b, size):
    return a["type"] == b["type"] and _same_dict(a["orientation"], b["orientation"], RELATIVE_TOLERANCE * size)


def same_surface(a, b, size):
    return same_orientation(a, b, size) and _same_dict(a["surface"], b["surface"], RELATIVE_TOLERANCE * size)


def same_face(a, b, size):
    return (same_surface(a, b, size)
            and abs(a["area"] - b["area"]) <= RELATIVE_TOLERANCE * max(abs(a["area"]), 1e-12)
            and _close(a["centre"], b["centre"], RELATIVE_TOLERANCE * size))


LEVELS = (same_face, same_surface, same_orientation)


class Previous:
    """An object's faces at the last match (``old``, signatures as shape_signatures gave
    them) against its faces now: which old faces are still there exactly, and which
    faces now are one of them. Worked out once per object, and only when a loose match
    needs it."""

    def __init__(self, old, signatures, size):
        self.old, self.signatures, self.size = old, signatures, size
        self._now_of_old = None

    def now_of_old(self):
        """For each old face, the faces now that are exactly it."""
        if self._now_of_old is None:
            self._now_of_old = [[i for i, s in enumerate(self.signatures) if same_face(o, s, self.size)]
                                for o in self.old]
        return self._now_of_old

    def rivals(self, index, signature, level):
        """Old faces other than ``index`` that ``signature`` matches at ``level``."""
        return [j for j, o in enumerate(self.old) if j != index and level(signature, o, self.size)]

    def moved_together(self, index, signature, moved, level, excluded):
        """The face now (its index) the tagged old face ``index`` became when it moved
        with rivals (``moved``: old faces that ``signature`` matches at ``level`` and
        that are not there unchanged): found only when the faces now that match at
        ``level`` (less ``excluded``, the unchanged rivals) are as many as the moved old
        faces, and the tagged face's area is met once among them and by none of the
        moved rivals. A Pad made longer lifts its top face and the floor of a Pocket
        sketched on it alike; their areas tell them apart. Anything less clear (a face
        come or gone, a rival of the same area, the area changed): None."""
        now = self.candidates(signature, level, excluded)
        if len(now) != 1 + len(moved):
            return None  # a face came or went: not a move

        def same_area(area):
            return lambda a: abs(a - area) <= RELATIVE_TOLERANCE * max(area, 1e-12)

        tagged = same_area(signature["area"])
        if any(tagged(self.old[j]["area"]) for j in moved):
            return None  # a moved rival of the same area: either could be it
        found = [i for i in now if tagged(self.signatures[i]["area"])]
        return found[0] if len(found) == 1 else None

    def stayed_near(self, signature, moved, level, excluded):
        """The face now (its index) the tagged face (``signature``) became when it moved
        with rivals that its area does not tell it from (four equal fillets made larger):
        the one candidate (the faces now that match at ``level``, less ``excluded``; as
        many as the moved old faces, as in moved_together) whose centre is within NEAR of
        ``spacing`` of the tagged face's, every other candidate at least CLEAR of it away,
        and whose area is no nearer a moved rival's than the tagged face's. ``spacing``
        is the distance (mm) from the tagged face's centre to the nearest of the
        ``moved`` rivals' (old faces): a rival still there unchanged is no candidate, so
        it cannot be taken for the tagged face however near (a plate's top 9.8 mm from a
        key's). Anything less clear: None."""
        now = self.candidates(signature, level, excluded)
        if len(now) != 1 + len(moved):
            return None  # a face came or went: not a move
        centre = signature["centre"]
        spacing = min(math.dist(centre, self.old[j]["centre"]) for j in moved)
        if spacing <= RELATIVE_TOLERANCE * self.size:
            return None  # a rival where the tagged face was: place tells nothing
        distances = sorted((math.dist(centre, self.signatures[i]["centre"]), i) for i in now)
        (nearest, found), others = distances[0], distances[1:]
        if nearest > NEAR * spacing or any(d < CLEAR * spacing for d, _ in others):
            return None
        area = self.signatures[found]["area"]
        own = abs(area - signature["area"]) - RELATIVE_TOLERANCE * max(area, 1e-12)  # equal areas tie
        if any(abs(area - self.old[j]["area"]) < own for j in moved):
            return None  # it looks more like a rival that moved here (two holes that passed)
        return found

    def candidates(self, signature, level, excluded):
        """Faces now (indices) that ``signature`` matches at ``level``, less ``excluded``."""
        return [i for i, s in enumerate(self.signatures) if i not in excluded and level(signature, s, self.size)]


def match_face(signature, name, signatures, size, previous=None, loose=True):
    """(face name or None, status) of the face of a shape that ``signature`` describes;
    ``name`` is the stored name, ``signatures`` those of the shape's faces (Face1 first),
    ``previous`` the object's faces at the last match (a Previous, or None when unknown).

    At each level, from strict to loose: if the stored name fits it is kept ("ok");
    otherwise exactly one fitting face is a re-match; two or more are ambiguous
    ("broken"); none passes to the next, looser, level. At a loose level the tagged
    face's rivals at that level still there unchanged are no candidates, and rivals
    that changed must have moved with it, told apart by area (Previous.moved_together)
    or, failing that, by having clearly stayed near (Previous.stayed_near), else nothing
    tells it from one of them: broken; when no face fits the level at all, they all left
    it together and the next level decides. Without ``loose`` only the first level is tried (a
    broken reference comes back only as the very face it was)."""
    index = _face_index(name)
    excluded = set()
    for level in LEVELS if loose else LEVELS[:1]:
        if level is not same_face and previous is not None and previous.old:
            now_of_old = previous.now_of_old()
            rivals = previous.rivals(index, signature, level)
            excluded = {i for j in rivals for i in now_of_old[j]}
            moved = [j for j in rivals if not now_of_old[j]]
            if moved:
                if not 0 <= index < len(previous.old):
                    return None, BROKEN
                if not previous.candidates(signature, level, excluded):
                    continue  # it left this surface with its rivals (a pattern's keys made taller)
                found = previous.moved_together(index, signature, moved, level, excluded)
                if found is None:
                    found = previous.stayed_near(signature, moved, level, excluded)
                if found is None:
                    return None, BROKEN
                return f"Face{found + 1}", OK if found == index else REMATCHED
        fits = [i for i, s in enumerate(signatures) if i not in excluded and level(signature, s, size)]
        if not fits:
            continue
        if len(fits) == 1:
            found = fits[0]
            return f"Face{found + 1}", OK if found == index else REMATCHED
        if level is same_face and index in fits:
            return name, OK
        return None, BROKEN
    return None, BROKEN


# a broken reference keeps its face's name, and FreeCAD may give that name to another
# face the surface tags (a renumbering edit): the broken one then steps aside as
# "Face6~1", which names no face; shown_face gives the name it had
ASIDE = "~"


def shown_face(name):
    """The face name a reference is shown by: "Face6" of a broken "Face6~1"."""
    return name.split(ASIDE, 1)[0]


def _face_index(name):
    try:
        return int(name[4:]) - 1 if name.startswith("Face") else -1
    except ValueError:
        return -1


def rematch(entries, shapes, previous=None, signed=None):
    """Re-matches reference entries against the current shapes.

    ``entries``: [{"object": name, "face": "FaceN", "signature": {...}, "status": ...}];
    ``shapes``: {object name: shape or None}; ``previous``: {object name: signatures of
    its faces at the last match} (see tables()); ``signed``, if given, receives the
    signatures taken now ({object name: [...]}, the next rematch's ``previous``).
    Returns new entries (same order): the face and signature follow the matched face; a
    broken entry keeps its old face and signature so that undoing the edit restores it."""
    previous = previous or {}
    cache = {}
    result = []
    for entry in entries:
        shape = shapes.get(entry["object"])
        if entry.get("signature") is None or shape is None or shape.isNull() or not shape.Faces:
            result.append(dict(entry, status=BROKEN))
            continue
        if entry["object"] not in cache:
            signatures, size = shape_signatures(shape)
            old = previous.get(entry["object"])
            cache[entry["object"]] = (signatures, size, Previous(old, signatures, size) if old else None)
            if signed is not None:
                signed[entry["object"]] = signatures
        signatures, size, before = cache[entry["object"]]
        # a broken reference's name may name another face by now, and the table no
        # longer holds its face: it comes back only exactly (an undo), never loosely
        name, status = match_face(entry["signature"], entry["face"], signatures, size, before,
                                  loose=entry.get("status") != BROKEN)
        if status == BROKEN:
            result.append(dict(entry, status=BROKEN))
        else:
            result.append(dict(entry, face=name, status=status, signature=signatures[_face_index(name)]))
    return result


def tables(shapes, signed=None):
    """{object name: signatures of its faces} of the given {object name: shape}: what
    the next rematch takes as ``previous``; ``signed`` holds those already taken."""
    signed = signed or {}
    return {name: signed[name] if name in signed else shape_signatures(shape)[0]
            for name, shape in shapes.items() if shape is not None and not shape.isNull()}


def new_entry(obj, face_name, cache=None):
    """A reference entry for a face as it is now. ``cache`` ({object name: what
    shape_signatures gave}) saves signing a part's faces again for each of its faces."""
    index = _face_index(face_name)
    cache = {} if cache is None else cache
    if obj.Name not in cache:
        shape = getattr(obj, "Shape", None)
        cache[obj.Name] = shape_signatures(shape) if shape is not None and not shape.isNull() else ([], 1.0)
    signatures, _ = cache[obj.Name]
    if not 0 <= index < len(signatures):  # no such face (yet): recorded as broken
        return {"object": obj.Name, "face": face_name, "signature": None, "status": BROKEN}
    return {"object": obj.Name, "face": face_name, "signature": signatures[index], "status": OK}


# --- PartDesign: a designer picks the visible solid, which belongs to the Body -----------

def _body_of(obj):
    if obj.TypeId.startswith("PartDesign::") and obj.TypeId != "PartDesign::Body":
        for parent in obj.InList:
            if parent.TypeId == "PartDesign::Body":
                return parent
    return None


def owner_face(obj, face_name):
    """(object, face name) a reference should hold for a face picked on ``obj``.

    A PartDesign feature's faces belong to its Body: a later feature would otherwise
    leave the tag on a hidden intermediate solid. The Body's face is the one with the
    same geometry (global frame); anything else is kept as given."""
    body = _body_of(obj)
    if body is None or body.Shape.isNull():
        return obj, face_name
    picked = obj.Shape.copy()
    picked.Placement = obj.getGlobalPlacement()
    whole = body.Shape.copy()
    whole.Placement = body.getGlobalPlacement()
    size = max(whole.BoundBox.DiagonalLength, 1.0)
    signature = face_signature(picked.getElement(face_name))
    fits = [i for i, f in enumerate(whole.Faces) if same_face(signature, face_signature(f), size)]
    if len(fits) == 1:
        return body, f"Face{fits[0] + 1}"
    return obj, face_name
