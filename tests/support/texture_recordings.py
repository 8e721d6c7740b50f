# SPDX-License-Identifier: GPL-3.0-or-later
"""A rig's recording of a finger stroked over a viscous grating, for the texture-fit tests."""
import csv
import random


def write_rig_csv(core, path, speeds_mm_s=(50.0, 120.0), normal_force_n=None, f_dc=0.4, f_vis=0.2,
                  full_range_n=2.0, noise_n=0.0):
    """Back and forth over 70 mm at each speed (2 m/s^2 ramps), 10 kHz; the lateral force on
    the finger as eq. 2 gives it (``core``: hapticad._core), resisting the motion, plus a
    force sensor's white noise of ``noise_n`` N (seeded)."""
    rng = random.Random(5)
    params = core.ViscousTextureParams()
    params.f_dc, params.f_vis = f_dc, f_vis
    rows, t, x, dt = [], 0.0, 0.0, 1e-4
    for speed in speeds_mm_s:
        for direction in (1, -1):
            start, v = x, 0.0
            while abs(x - start) < 70.0:
                to_go = 70.0 - abs(x - start)
                v = min(v + 2000.0 * dt, speed, max((2 * 2000.0 * to_go) ** 0.5, 1.0))
                x += direction * v * dt
                t += dt
                f = full_range_n * core.viscous_texture_level(params, x * 1e-3, v * 1e-3)
                f += rng.gauss(0.0, noise_n) if noise_n else 0.0
                rows.append([f"{t:.6f}", f"{x:.6f}", f"{-direction * f:.6f}"]
                            + ([f"{normal_force_n:.3f}"] if normal_force_n else []))
    with open(path, "w", newline="") as handle:
        out = csv.writer(handle)
        out.writerow(["time_s", "position_mm", "lateral_force_n"] + (["normal_force_n"] if normal_force_n else []))
        out.writerows(rows)
