# SPDX-License-Identifier: GPL-3.0-or-later
"""Pattern-curve edges that survive sketch edits, or say plainly that they broke.

A Curve pattern may name edges of a sketch or a part ("Edge2"). Editing the sketch
renumbers them: delete the first of two splines and "Edge1" names the second. So each
named edge keeps a *signature* (kind of curve, length, end points, middle point, in the
object's own frame, mm), and the state keeps the signatures of the object's other edges
too. After every recompute each named edge is looked for again:

- **ok**: the name still names the signed edge, or, while every other edge is still
  there unchanged, another curve (the designer reshaped this one: still the one
  picked);
- **rematched**: the signed edge now has another name, found uniquely; the pattern
  follows it;
- **broken**: no such edge any more, or the name now names one of the other edges, and
  no edge is the one signed. The state keeps the old name and signature (undoing the
  edit brings it back) and the pattern is not felt until the curve is picked again.

A link to a whole sketch (no edge named) needs none of this. No GUI.
"""
import json

import FreeCAD as App

OK, REMATCHED, BROKEN = "ok", "rematched", "broken"
RELATIVE_TOLERANCE = 1e-6  # of the object's size


# a Curve pattern without its curve: never picked, or the sketch deleted since
NO_CURVE = ("the Curve pattern needs a sketch or edge to follow and has none (none was picked, or it was deleted): "
            "select one and press Use selection, or choose another pattern")


def _vec(v):
    return [float(v.x), float(v.y), float(v.z)]


def edge_signature(edge):
    """The signature of an edge (in the frame it is given in), JSON-ready."""
    ends = sorted([_vec(edge.valueAt(edge.FirstParameter)), _vec(edge.valueAt(edge.LastParameter))])
    middle = edge.valueAt(0.5 * (edge.FirstParameter + edge.LastParameter))
    return {"type": type(edge.Curve).__name__, "length": float(edge.Length), "ends": ends,
            "middle": _vec(middle)}


def _close(a, b, tolerance):
    return all(abs(x - y) <= tolerance for x, y in zip(a, b))


def same_edge(a, b, size):
    tolerance = RELATIVE_TOLERANCE * size
    return (a["type"] == b["type"] and abs(a["length"] - b["length"]) <= tolerance
            and all(_close(p, q, tolerance) for p, q in zip(a["ends"], b["ends"]))
            and _close(a["middle"], b["middle"], tolerance))


def _edge_signatures(obj):
    """Signatures of every edge of ``obj``'s shape in its own frame, and its size (mm)."""
    shape = getattr(obj, "Shape", None)
    if shape is None or shape.isNull():
        return [], 1.0
    local = shape.copy()
    local.Placement = App.Placement()
    size = local.BoundBox.DiagonalLength if local.BoundBox.isValid() else 1.0
    return [edge_signature(e) for e in local.Edges], max(size, 1.0)


def _edge_index(name):
    try:
        return int(name[4:]) - 1 if name.startswith("Edge") else -1
    except ValueError:
        return -1


def named_edges(link):
    """The edge names a PatternCurve link holds (empty: the whole object)."""
    if link is None:
        return []
    _, subs = link
    subs = [subs] if isinstance(subs, str) else list(subs or [])
    return [s for s in subs if s]


def sign(link):
    """A fresh state for a PatternCurve link, as its edges are now."""
    if link is None or not named_edges(link):
        return {}
    obj = link[0]
    signatures, _ = _edge_signatures(obj)
    names = named_edges(link)
    indices = {_edge_index(n) for n in names}
    edges = []
    for name in names:
        i = _edge_index(name)
        known = 0 <= i < len(signatures)
        edges.append({"name": name, "signature": signatures[i] if known else None,
                      "status": OK if known else BROKEN})
    others = [s for i, s in enumerate(signatures) if i not in indices]
    return {"object": obj.Name, "edges": edges, "others": others}


def rematch(state, link):
    """(new state, edge names for the link) after a recompute; see the module's rules."""
    if not state or link is None or link[0].Name != state.get("object"):
        return sign(link), named_edges(link)
    obj = link[0]
    signatures, size = _edge_signatures(obj)
    others = state.get("others", [])
    # an edge may be "the same curve, reshaped" only while every other edge is still
    # there unchanged: else the name may now name one of them, changed too
    others_kept = all(any(same_edge(o, s, size) for s in signatures) for o in others)
    edges = []
    for entry in state.get("edges", []):
        signature, i = entry.get("signature"), _edge_index(entry["name"])
        if signature is None:
            edges.append(dict(entry, status=BROKEN))
            continue
        exact = [j for j, s in enumerate(signatures) if same_edge(signature, s, size)]
        if i in exact:
            edges.append(dict(entry, signature=signatures[i], status=OK))
        elif len(exact) == 1:
            edges.append({"name": f"Edge{exact[0] + 1}", "signature": signatures[exact[0]], "status": REMATCHED})
        elif (not exact and entry.get("status") != BROKEN  # a broken one comes back only exactly
              and 0 <= i < len(signatures) and others_kept
              and not any(same_edge(o, signatures[i], size) for o in others)):
            edges.append(dict(entry, signature=signatures[i], status=OK))  # reshaped in place
        else:
            edges.append(dict(entry, status=BROKEN))
    kept = {_edge_index(e["name"]) for e in edges if e["status"] != BROKEN}
    if any(e["status"] != BROKEN for e in edges):
        others = [s for j, s in enumerate(signatures) if j not in kept]
    return {"object": obj.Name, "edges": edges, "others": others}, [e["name"] for e in edges]


def loads(text):
    try:
        state = json.loads(text) if text else {}
    except ValueError:
        state = {}
    return state if isinstance(state, dict) else {}


def dumps(state):
    return json.dumps(state, sort_keys=True)


def broken_edges(state):
    """Names of the state's edges that are broken."""
    return [e["name"] for e in state.get("edges", []) if e.get("status") == BROKEN]


def problem(state, object_label):
    """A sentence naming the state's broken edges (None when there are none)."""
    broken = broken_edges(state)
    if not broken:
        return None
    names = ", ".join(f"{object_label}.{e}" for e in broken)
    verb = "are gone or are now other edges" if len(broken) > 1 else "is gone or is now another edge"
    return f"the pattern curve's {names} {verb} (the sketch changed): pick the curve again"


def status(state):
    """[(edge name, status), ...] of a state."""
    return [(e["name"], e.get("status", OK)) for e in state.get("edges", [])]
