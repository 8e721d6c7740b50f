# SPDX-License-Identifier: GPL-3.0-or-later
"""What following tagged faces through a model edit costs: a plate with N x N bores,
every bore tagged by one HapticSurface, recomputed unchanged and then with every bore
0.1 mm wider (every tag then needs the loose match levels and its rivals). Prints JSON.

    XDG_DATA_HOME=build/test-home/data freecadcmd -c \\
        "import sys; sys.argv=['x', '12']; exec(open('benchmarks/plugin/face_references_bench.py').read())"
"""
import json
import sys
import time

import FreeCAD as App
import Part

import HaptiCAD


def plate(n, radius):
    body = Part.makeBox(10 * n + 10, 10 * n + 10, 5)
    holes = [Part.makeCylinder(radius, 20, App.Vector(10 + 10 * i, 10 + 10 * j, -5))
             for i in range(n) for j in range(n)]
    return body.cut(Part.makeCompound(holes))


def timed(action):
    start = time.perf_counter()
    action()
    return round(time.perf_counter() - start, 3)


def main(n):
    doc = App.newDocument("FaceReferencesBench")
    part = doc.addObject("Part::Feature", "Plate")
    part.Shape = plate(n, 2.0)
    doc.recompute()
    bores = [f"Face{i + 1}" for i, f in enumerate(part.Shape.Faces) if type(f.Surface).__name__ == "Cylinder"]
    made = {}
    result = {"faces": len(part.Shape.Faces), "tagged": len(bores),
              "make_surface_s": timed(lambda: made.update(s=HaptiCAD.make_surface(doc, [(part, b) for b in bores])))}
    surface = made["s"]
    result["state_kb"] = round((len(surface.ReferenceState) + len(getattr(surface, "ReferenceShapes", ""))) / 1e3, 1)
    surface.touch()
    result["recompute_unchanged_s"] = timed(doc.recompute)
    part.Shape = plate(n, 2.1)
    result["recompute_all_wider_s"] = timed(doc.recompute)
    result["statuses"] = sorted({s for _, _, s in HaptiCAD.reference_status(surface)})
    App.closeDocument(doc.Name)
    print(json.dumps(result))


main(int(sys.argv[1]) if len(sys.argv) > 1 else 12)
