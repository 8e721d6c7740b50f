# SPDX-License-Identifier: GPL-3.0-or-later
"""PNG of a similarity study's perceptual space (seed 001 Fig. 7): the stimuli as points
in the first two axes, and each parameter's eq. 3 vector drawn through the origin from
its low end (q = -0.5) to its high end (q = +0.5); the references' vector is the long one.

Drawn on a bare matplotlib Figure with the Agg canvas, without pyplot: inside FreeCAD's
GUI it must not switch the backend other workbenches (Plot) use."""
import io

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .similarity_study import LIKENESS

# the points are blue; the parameters' vectors green, purple, ochre, teal, grey, olive;
# the references' a thick red
PARAMETER_COLOURS = ("#2f855a", "#6b46c1", "#b7791f", "#2c7a7b", "#4a5568", "#718096")
LIKENESS_COLOUR = "#c53030"


def draw_space(ax, result, title=""):
    """Draws ``result`` (similarity_study.analyse) on matplotlib axes."""
    points = np.asarray(result["points"], float)
    if points.shape[1] == 1:  # one dimension: a line
        points = np.column_stack([points[:, 0], np.zeros(len(points))])
    ax.scatter(points[:, 0], points[:, 1], s=36, color="#2b6cb0", zorder=3)
    for name, (x, y) in zip(result["stimuli"], points[:, :2]):
        ax.annotate(name, (x, y), textcoords="offset points", xytext=(4, 4), fontsize=7)
    others = iter(PARAMETER_COLOURS)
    for label, vector in result["vectors"].items():
        p = np.zeros(2)
        p[:min(2, len(vector["direction"]))] = vector["direction"][:2]
        colour = LIKENESS_COLOUR if label == LIKENESS else next(others)
        ax.plot([-p[0] / 2, p[0] / 2], [-p[1] / 2, p[1] / 2], color=colour,
                lw=2.5 if label == LIKENESS else 1.6, label=f"{label}: |p| {vector['length']:.2f}, "
                f"r {vector['correlation']:.2f}")
        # the ends' names just beyond the ends, clear of the line
        ax.annotate(vector["high"], p / 2 * 1.12, color=colour, fontsize=7, ha="center", va="center",
                    weight="bold")
        ax.annotate(vector["low"], -p / 2 * 1.12, color=colour, fontsize=7, ha="center", va="center",
                    weight="bold")
    ax.axhline(0, color="0.85", lw=0.8, zorder=0)
    ax.axvline(0, color="0.85", lw=0.8, zorder=0)
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("axis 1")
    ax.set_ylabel("axis 2")
    ordinal = result.get("scaling") == "ordinal"
    ax.set_title(title or f"{'ordinal ' if ordinal else ''}perceptual space: {result['participants']} participants, "
                 f"stress{'-1' if ordinal else ''} {result['stress']:.2f}", fontsize=9)
    if result["vectors"]:
        ax.legend(fontsize=7, loc="best")
    ax.grid(alpha=0.3)


def space_png(result, title="", size_in=(7, 6.5), dpi=110):
    """The space drawn as PNG bytes."""
    fig = Figure(figsize=size_in, dpi=dpi, constrained_layout=True)
    FigureCanvasAgg(fig)
    draw_space(fig.add_subplot(), result, title)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png")
    return buffer.getvalue()


def plot_space(path, result, title=""):
    with open(path, "wb") as handle:
        handle.write(space_png(result, title))
    return path
