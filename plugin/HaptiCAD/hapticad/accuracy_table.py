# SPDX-License-Identifier: GPL-3.0-or-later
"""The speed/accuracy table: what each accuracy preset costs and how true it feels.

On an analytic sphere (radius 25 mm) and cylinder (radius 15 mm, 40 mm high) made as
FreeCAD primitives, each preset's tessellation is felt by a point proxy stroking the
curved surface at 75 mm/s, 1 mm deep, with k = 0.4 N/mm and no friction, so the force
should be exactly k * 1 mm along the exact surface normal. For every preset, with and
without force shading: triangles, tessellation and build time, tick cost, and the
largest and mean error of the force's magnitude (against k * depth) and of its
direction (against the exact normal). Forces are the C++ renderer's, ticked through
``_core.run_stroke``; the analytic normal is the reference.

    hapticad accuracy-table --json --plot accuracy.png

No GUI. Timings are measurements of this machine, not assertions.
"""
import time

import numpy as np

from . import _core
from . import accuracy as presets
from .document_scene import MM, tessellate

K_N_PER_M = 400.0
DEPTH_MM = 1.0
SPEED_MM_S = 75.0
TICKS = 4000
APPROACH_TICKS = 40
DT_S = 1e-3
SPHERE_RADIUS_MM = 25.0
CYLINDER_RADIUS_MM = 15.0
CYLINDER_HEIGHT_MM = 40.0


def _sphere_stroke():
    """Device positions (mm) and exact unit normals: a tilted great circle whose plane
    turns slowly, 1 mm inside."""
    t = np.arange(TICKS) * DT_S
    s = SPEED_MM_S * t / SPHERE_RADIUS_MM
    tilt = 0.4 + 0.3 * np.sin(0.7 * t)
    normal = np.stack([np.cos(s), np.sin(s) * np.cos(tilt), np.sin(s) * np.sin(tilt)], axis=1)
    return normal * SPHERE_RADIUS_MM, normal


def _cylinder_stroke():
    """A wavy helix round the side wall, clear of the caps, 1 mm inside."""
    t = np.arange(TICKS) * DT_S
    s = SPEED_MM_S * t / CYLINDER_RADIUS_MM * 0.95
    z = CYLINDER_HEIGHT_MM / 2 + 12.0 * np.sin(0.5 * s)
    normal = np.stack([np.cos(s), np.sin(s), np.zeros_like(s)], axis=1)
    return normal * CYLINDER_RADIUS_MM + np.stack([0 * s, 0 * s, z], axis=1), normal


def primitives():
    """(name, shape, stroke) of the two analytic test parts."""
    import Part

    return [
        ("sphere", Part.makeSphere(SPHERE_RADIUS_MM), _sphere_stroke),
        ("cylinder", Part.makeCylinder(CYLINDER_RADIUS_MM, CYLINDER_HEIGHT_MM), _cylinder_stroke),
    ]


def _inputs(surface_mm, normal):
    """Positions, velocities (m, m/s) and times: an approach from 2 mm outside, then the
    stroke 1 mm deep."""
    device = (surface_mm - DEPTH_MM * normal) * MM
    start = (surface_mm[0] + 2.0 * normal[0]) * MM
    approach = start + np.outer(np.linspace(0.0, 1.0, APPROACH_TICKS), device[0] - start)
    positions = np.vstack([approach, device])
    velocities = np.gradient(positions, DT_S, axis=0)
    times = np.arange(len(positions)) * DT_S
    return positions, velocities, times


def measure(shape, stroke, accuracy, shading):
    """One row of the table (a dict)."""
    t0 = time.perf_counter()
    vertices, triangles, faces, normals = tessellate(shape, accuracy)
    t1 = time.perf_counter()
    scene = _core.HapticScene.build(vertices, triangles, faces, MM, corner_normals=normals)
    surface = _core.SurfaceProperties()
    surface.stiffness_n_per_m = K_N_PER_M
    surface.friction.static_coefficient = 0.0
    surface.friction.dynamic_coefficient = 0.0
    table = _core.SurfaceTable([surface] * scene.num_cad_faces)
    limits = _core.RenderLimits()
    limits.max_force_n = 1e6
    limits.max_stiffness_n_per_m = 1e6
    options = _core.ContactOptions()
    options.force_shading = shading
    renderer = _core.ForceRenderer(scene, table, limits, options)  # builds the point grid
    t2 = time.perf_counter()
    surface_mm, normal = stroke()
    positions, velocities, times = _inputs(surface_mm, normal)
    run = _core.run_stroke(renderer, positions, velocities, list(times))
    force = run["force_w"][APPROACH_TICKS:]
    contact = (run["flags"][APPROACH_TICKS:] & _core.FLAG_CONTACT) != 0
    expected = K_N_PER_M * DEPTH_MM * MM
    magnitude = np.linalg.norm(force, axis=1)
    ok = contact & (magnitude > 0)
    force_error = np.abs(magnitude[ok] - expected) / expected
    cosine = np.clip(np.einsum("ij,ij->i", force[ok], normal[ok]) / magnitude[ok], -1.0, 1.0)
    angle = np.degrees(np.arccos(cosine))
    tick = run["tick_us"][APPROACH_TICKS:][contact]
    return {
        "preset": accuracy.name,
        "linear_deflection_mm": accuracy.linear_deflection_mm,
        "angular_deflection_rad": accuracy.angular_deflection_rad,
        "force_shading": shading,
        "triangles": int(scene.num_triangles),
        "tessellate_ms": 1e3 * (t1 - t0),
        "build_ms": 1e3 * (t2 - t1),
        "tick_us": {"p50": float(np.percentile(tick, 50)), "p99": float(np.percentile(tick, 99))},
        "contact_ticks": int(contact.sum()),
        "ticks": int(len(contact)),
        "force_error_pct": {"max": 100 * float(force_error.max()), "mean": 100 * float(force_error.mean())},
        "direction_error_deg": {"max": float(angle.max()), "mean": float(angle.mean())},
    }


def run_table(preset_names=None):
    """Every primitive x preset x shading, as a list of rows."""
    names = preset_names or list(presets.PRESETS)
    rows = []
    for name, shape, stroke in primitives():
        for preset in names:
            for shading in (False, True):
                row = measure(shape, stroke, presets.preset(preset), shading)
                row["primitive"] = name
                rows.append(row)
    return rows


def plot(rows, path):
    """Errors and tick cost against triangles, one line per primitive and shading."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 3, figsize=(15, 4.6))
    styles = {("sphere", False): ("tab:blue", "--"), ("sphere", True): ("tab:blue", "-"),
              ("cylinder", False): ("tab:orange", "--"), ("cylinder", True): ("tab:orange", "-")}
    for (primitive, shading), (colour, line) in styles.items():
        sel = [r for r in rows if r["primitive"] == primitive and r["force_shading"] == shading]
        sel.sort(key=lambda r: r["triangles"])
        tri = [r["triangles"] for r in sel]
        label = f"{primitive}, {'shaded' if shading else 'flat'}"
        axes[0].plot(tri, [r["direction_error_deg"]["max"] for r in sel], line, color=colour, marker="o", label=label)
        axes[1].plot(tri, [r["force_error_pct"]["max"] for r in sel], line, color=colour, marker="o", label=label)
        axes[2].plot(tri, [r["tick_us"]["p99"] for r in sel], line, color=colour, marker="o", label=label)
        for r in sel:
            axes[0].annotate(r["preset"], (r["triangles"], r["direction_error_deg"]["max"]), fontsize=7,
                             textcoords="offset points", xytext=(3, 3))
    axes[0].set_ylabel("largest direction error (deg)")
    axes[1].set_ylabel("largest force magnitude error (% of k depth)")
    axes[2].set_ylabel("contact tick p99 (us)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_xlabel("triangles")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_yscale("log")
    axes[0].legend(fontsize=8, loc="center", bbox_to_anchor=(0.55, 0.45))
    fig.suptitle(f"Speed against accuracy: point proxy {DEPTH_MM:g} mm deep at {SPEED_MM_S:g} mm/s, "
                 f"k = {K_N_PER_M / 1000:g} N/mm, per accuracy preset (Draft, Normal, Fine)")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def markdown(rows):
    """The table as Markdown, for BENCHMARKS.md."""
    lines = ["| part | preset | shading | triangles | tessellate + build (ms) | tick p50 / p99 (us) "
             "| force error max / mean (%) | direction error max / mean (deg) |",
             "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(
            f"| {r['primitive']} | {r['preset']} | {'on' if r['force_shading'] else 'off'} | {r['triangles']} "
            f"| {r['tessellate_ms']:.0f} + {r['build_ms']:.1f} | {r['tick_us']['p50']:.2f} / {r['tick_us']['p99']:.2f} "
            f"| {r['force_error_pct']['max']:.2f} / {r['force_error_pct']['mean']:.2f} "
            f"| {r['direction_error_deg']['max']:.3f} / {r['direction_error_deg']['mean']:.3f} |")
    return "\n".join(lines)
