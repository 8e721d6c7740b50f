# SPDX-License-Identifier: GPL-3.0-or-later
"""PNG plot of a stroke: normal and tangential force against distance along it."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from . import _core  # noqa: E402
from .feel import distance_along_stroke_mm, sliding_mask  # noqa: E402


def plot_trace(path, result, doc_scene, summary, title=""):
    trace = result.trace
    contact = (trace["flags"] & _core.FLAG_CONTACT) != 0
    sliding = sliding_mask(result, doc_scene)
    x = distance_along_stroke_mm(result)
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True, constrained_layout=True)
    fn = np.where(contact, trace["normal_force_n"], np.nan)
    ft = np.where(contact, trace["tangential_force_n"], np.nan)
    top.plot(x, fn, color="tab:blue", lw=1.2, label="normal force $F_n$")
    top.plot(x, ft, color="tab:red", lw=1.2, label="tangential force $F_t$")
    top.axhline(summary["expected_normal_force_n"], color="tab:blue", ls=":", lw=1,
                label=f"$k\\cdot$depth = {summary['expected_normal_force_n']:.3f} N")
    top.set_ylabel("force (N)")
    top.legend(loc="upper right", fontsize=8)
    top.grid(alpha=0.3)
    ratio = np.where(sliding, trace["tangential_force_n"] / np.maximum(trace["normal_force_n"], 1e-12), np.nan)
    bottom.plot(x, ratio, color="black", lw=1.2, label="$F_t/F_n$ while sliding")
    for name, face in summary["faces"].items():
        bottom.axhline(face["mu_dynamic"], ls="--", lw=1, label=f"$\\mu_d$ {name} ({face['material'] or 'untagged'})")
    bottom.set_xlabel("distance along the stroke (mm)")
    bottom.set_ylabel("$F_t/F_n$")
    bottom.legend(loc="upper right", fontsize=8)
    bottom.grid(alpha=0.3)
    stroke = summary["stroke"]
    fig.suptitle(title or f"stroke on {stroke['start_face']}: {stroke['depth_mm']} mm deep, "
                 f"{stroke['speed_mm_s']} mm/s, {summary['rate_hz']:.0f} Hz", fontsize=10)
    fig.savefig(path, dpi=110)
    plt.close(fig)
