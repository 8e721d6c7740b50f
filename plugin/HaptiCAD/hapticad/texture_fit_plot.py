# SPDX-License-Identifier: GPL-3.0-or-later
"""PNG of a texture fit: the spectra with their power fits per speed (seed 001 Fig. 4)
and the fitted values against speed with eq. 2's lines (Figs. 5 and 6).

Drawn on a bare matplotlib Figure with the Agg canvas, without pyplot: inside FreeCAD's
GUI (the surface panel's "Plot the fit") pyplot's backend is not ours to switch."""
import numpy as np
from matplotlib import cm
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from . import _core

MM = 1e-3


def plot_fit(path, report, title=""):
    """Writes the fit's PNG to ``path``; returns the Figure drawn (for a caller that looks
    at it; nothing else holds it)."""
    fit = report.fit
    colours = cm.viridis(np.linspace(0, 0.9, max(len(fit.speeds), 1)))
    fig = Figure(figsize=(10, 7.5), constrained_layout=True)
    FigureCanvasAgg(fig)
    axes = fig.subplots(2, 2)
    spectra, dc, beta, alpha = axes.ravel()
    for colour, s in zip(colours, fit.speeds):
        label = f"{s.speed_mps / MM:.0f} mm/s ({s.sections})"
        for k, section in enumerate(x for x in fit.sections if x.target_speed_mps == s.target_speed_mps):
            amplitude = np.asarray(section.amplitude_n)
            f = np.arange(len(amplitude)) / section.periods
            spectra.loglog(f[1:], amplitude[1:], color=colour, lw=0.5, alpha=0.35, label=None if k else label)
        harmonics = np.arange(1, report.options.harmonics + 1)
        spectra.loglog(harmonics, s.harmonic.beta * harmonics ** -s.harmonic.alpha, "o-", color=colour,
                       ms=4, lw=1.5)
        if s.background.points:
            f = np.array([0.2, 16.0])
            spectra.loglog(f, s.background.beta * f ** -s.background.alpha, "--", color=colour, lw=1.2)
    spectra.set_xlabel("spatial frequency (multiples of 1/lambda)")
    spectra.set_ylabel("amplitude (N)")
    spectra.set_title("spectra: harmonic fit (dots), 1/f background fit (dashed)", fontsize=9)
    spectra.set_xlim(0.1, 20)
    spectra.legend(fontsize=7, title="speed (sections)", title_fontsize=7)
    spectra.grid(alpha=0.3, which="both")

    v = np.array([s.speed_mps for s in fit.speeds]) / MM
    line_v = np.linspace(0, max(v.max() * 1.1, 1.0), 50)
    unit = _core.VISCOUS_SPEED_UNIT_MPS / MM
    for ax, values, line, name, ylabel in (
            (dc, [s.dc_n for s in fit.speeds], fit.dc_n, "DC friction: f_DC + v f_vis", "DC force (N)"),
            (beta, [s.harmonic.beta for s in fit.speeds], fit.beta_h_n, "harmonic amplitude: beta_h + v beta_vis",
             "beta_h (N)"),
            (alpha, [s.harmonic.alpha for s in fit.speeds], fit.alpha_h, "harmonic decay: alpha_h + v alpha_vis",
             "alpha_h")):
        ax.plot(v, values, "o", color="black", label="per speed")
        drawn = line.intercept + line.slope * line_v / unit
        ax.plot(line_v, drawn, color="tab:red",
                label=f"{line.intercept:.4g} {'-' if line.slope < 0 else '+'} {abs(line.slope):.3g} v/(400 mm/s)")
        # from 0, so a flat line reads flat, not as noise blown up; a fifth above the
        # highest value, so neither the points nor the legend sit on the edge
        top = max(max(values), float(drawn.max()))
        ax.set_ylim(0, top * 1.25 if top > 0 else 1.0)
        ax.set_title(name, fontsize=9)
        ax.set_xlabel("scanning speed (mm/s)")
        ax.set_ylabel(ylabel)
        ax.legend(fontsize=7)
        ax.grid(alpha=0.3)
    dc.errorbar(v, [s.dc_n for s in fit.speeds], yerr=[s.dc_sd_n for s in fit.speeds], fmt="none",
                ecolor="black", capsize=3)
    fig.suptitle(title or f"texture fit: grating {fit.period_m / MM:g} mm, {len(fit.sections)} sections, "
                 f"{len(report.recordings)} recording(s)", fontsize=10)
    fig.savefig(path, dpi=110)
    return fig
