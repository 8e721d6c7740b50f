# SPDX-License-Identifier: GPL-3.0-or-later
"""What fitting a texture costs and how true it is, against the recording's sample rate
and the spatial resampling (samples a period). A finger strokes a grating (eq. 2: f_DC
0.4, f_vis 0.2, beta_h 0.1, alpha_h 2, level 1 = 2 N) back and forth over 70 mm at the
paper's five speeds, position quantised like its encoder (3.8 um), 0.01 N of seeded
sensor noise; the fit runs with the paper's defaults (1000 Hz low-pass, 2.5 %, three
harmonics). Prints JSON: per configuration the fit's time (median of 5) and the errors
of the four levels; last, one long session (every stroke 160 times at 10 kHz).

    /usr/bin/python3 benchmarks/core/analysis/texture_fit_bench.py --mod build/Mod/HaptiCAD
"""
import argparse
import json
import os
import sys
import time

import numpy as np

TRUTH = {"f_dc": 0.4, "f_vis": 0.2, "beta_h": 0.1, "alpha_h": 2.0}
FULL_RANGE_N = 2.0
SPEEDS_MPS = (0.05, 0.08, 0.12, 0.18, 0.27)


def recording(core, rate_hz, seed=1, repeats=1):
    params = core.ViscousTextureParams()
    params.f_dc, params.f_vis, params.beta_h, params.alpha_h = (TRUTH[k] for k in ("f_dc", "f_vis", "beta_h",
                                                                                 "alpha_h"))
    dt, t, x = 1.0 / rate_hz, [], []
    now, pos, speeds = 0.0, 0.0, []
    for speed in [s for s in SPEEDS_MPS for _ in range(repeats)]:
        for direction in (1, -1):
            start, v = pos, 0.0
            while abs(pos - start) < 0.07:
                to_go = 0.07 - abs(pos - start)
                v = min(v + 2.0 * dt, speed, max((4.0 * to_go) ** 0.5, 1e-3))
                pos += direction * v * dt
                now += dt
                t.append(now)
                x.append(pos)
                speeds.append(direction * v)
    level = np.array([core.viscous_texture_level(params, xi, abs(vi)) for xi, vi in zip(x, speeds)])
    rng = np.random.default_rng(seed)
    force = -np.sign(speeds) * FULL_RANGE_N * level + rng.normal(0.0, 0.01, len(level))
    quantised = np.round(np.asarray(x) / 3.8e-6) * 3.8e-6
    return core.TextureRecording(np.asarray(t), quantised, force)


def run(core, data, samples_per_period, repetitions=5):
    options = core.TextureFitOptions()
    options.samples_per_period = samples_per_period
    times = []
    for _ in range(repetitions):
        start = time.perf_counter()
        fit = core.fit_texture([data], options)
        times.append(time.perf_counter() - start)
    fitted = {"f_dc": fit.dc_n.intercept / FULL_RANGE_N, "f_vis": fit.dc_n.slope / FULL_RANGE_N,
              "beta_h": fit.beta_h_n.intercept / FULL_RANGE_N, "alpha_h": fit.alpha_h.intercept}
    return {
        "samples": data.samples,
        "samples_per_period": samples_per_period,
        "sections": len(fit.sections),
        "fit_ms": round(1e3 * float(np.median(times)), 2),
        "error": {k: float(f"{fitted[k] - TRUTH[k]:.2g}") for k in TRUTH},
    }


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--mod", required=True, help="the HaptiCAD Mod folder (build/Mod/HaptiCAD)")
    args = parser.parse_args()
    sys.path.insert(0, os.path.abspath(args.mod))
    from hapticad import _core

    rows = []
    for rate in (1000, 5000, 20000, 125000):
        data = recording(_core, rate)
        for spp in ((16, 32, 64, 128, 256) if rate == 20000 else (64,)):
            rows.append({"rate_hz": rate, **run(_core, data, spp)})
    # a long session: every stroke 160 times at 10 kHz (4.9 M samples, 1600 sections)
    rows.append({"rate_hz": 10000, "repeats": 160, **run(_core, recording(_core, 10000, repeats=160), 64, 1)})
    json.dump(rows, sys.stdout, indent=1)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()
