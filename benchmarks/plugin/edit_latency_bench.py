# SPDX-License-Identifier: GPL-3.0-or-later
"""How long a property edit takes to reach a renderer: the surfaces compiled again from
the document (document_scene.recompile_surfaces) and handed to a ForceRenderer
(set_surfaces), the path a Feel session's edit takes, after which the servo loop reads
the new table at its next tick. A document given (default: the shipped toothbrush), its
first surface's stiffness edited N times. Prints JSON, milliseconds.

    XDG_DATA_HOME=build/test-home/data freecadcmd -c \\
        "import sys; sys.argv=['x', 'resources/examples/toothbrush.FCStd', '50']; \\
exec(open('benchmarks/plugin/edit_latency_bench.py').read())"
"""
import json
import statistics
import sys
import time

import FreeCAD as App

from hapticad import _core
from hapticad.document_scene import build_document_scene, recompile_surfaces
from hapticad.surface_object import surfaces_of


def main(path, edits):
    doc = App.openDocument(path)
    try:
        scene = build_document_scene(doc)
        renderer = _core.ForceRenderer(scene.scene, scene.surfaces, _core.RenderLimits())
        surface = surfaces_of(doc)[0]
        stiffness = float(surface.Stiffness)
        times = []
        for i in range(edits):
            surface.Stiffness = stiffness * (1.0 + 0.01 * (i % 2 + 1))
            start = time.perf_counter()
            scene = recompile_surfaces(doc, scene)
            renderer.set_surfaces(scene.surfaces)
            times.append((time.perf_counter() - start) * 1e3)
        times.sort()
        return {"document": path, "tagged_faces": len(scene.face_surface), "edits": edits,
                "edit_to_renderer_ms": {"p50": round(statistics.median(times), 3),
                                        "p90": round(times[int(0.9 * (len(times) - 1))], 3),
                                        "max": round(times[-1], 3)}}
    finally:
        App.closeDocument(doc.Name)


print(json.dumps(main(sys.argv[1] if len(sys.argv) > 1 else "resources/examples/toothbrush.FCStd",
                      int(sys.argv[2]) if len(sys.argv) > 2 else 50)))
