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


def space_title(result, study_label=""):
    """"[Study: ]ordinal perceptual space: 6 participants, stress-1 0.02" of ``result``
    (analyse): which scaling, how many people, how well it fits."""
    ordinal = result.get("scaling") == "ordinal"
    n = result["participants"]
    return (f"{study_label + ': ' if study_label else ''}{'ordinal ' if ordinal else ''}perceptual space: "
            f"{n} participant{'s' if n != 1 else ''}, stress{'-1' if ordinal else ''} {result['stress']:.2f}")


def draw_space(ax, result, title=""):
    """Draws ``result`` (similarity_study.analyse) on matplotlib axes of a figure with a
    canvas. The names are placed last, each where it covers the fewest other names,
    points and vectors and stays inside the axes: at the paper's nine stimuli the
    default offsets put a vector's end name on a stimulus' name, and names past the
    axes' edge were cut off or dropped."""
    points = np.asarray(result["points"], float)
    if points.shape[1] == 1:  # one dimension: a line
        points = np.column_stack([points[:, 0], np.zeros(len(points))])
    points = points[:, :2]
    ax.scatter(points[:, 0], points[:, 1], s=36, color="#2b6cb0", zorder=3)
    others = iter(PARAMETER_COLOURS)
    ends = []  # (name, colour, end point) of each vector's two ends
    for label, vector in result["vectors"].items():
        p = np.zeros(2)
        p[:min(2, len(vector["direction"]))] = vector["direction"][:2]
        colour = LIKENESS_COLOUR if label == LIKENESS else next(others)
        ax.plot([-p[0] / 2, p[0] / 2], [-p[1] / 2, p[1] / 2], color=colour,
                lw=2.5 if label == LIKENESS else 1.6, label=f"{label}: |p| {vector['length']:.2f}, "
                f"r {vector['correlation']:.2f}")
        ends += [(vector["high"], colour, p / 2), (vector["low"], colour, -p / 2)]
    ax.axhline(0, color="0.85", lw=0.8, zorder=0)
    ax.axvline(0, color="0.85", lw=0.8, zorder=0)
    # room for the names round the outermost points and ends
    extent = np.vstack([points, *(end for _, _, end in ends), np.zeros((1, 2))])
    low, high = extent.min(axis=0), extent.max(axis=0)
    margin = 0.2 * max(float((high - low).max()), 1e-12)
    corners = np.array([low - margin, high + margin])
    ax.update_datalim(corners)  # the equal aspect widens round the data limits, not the set ones
    ax.set_xlim(*corners[:, 0])
    ax.set_ylim(*corners[:, 1])
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("axis 1")
    ax.set_ylabel("axis 2")
    ax.set_title(title or space_title(result), fontsize=9)
    if result["vectors"]:  # below the axes: inside, "best" still lands on names
        ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=1, frameon=False)
    ax.grid(alpha=0.3)
    _place_names(ax, points, result["stimuli"], ends)


# where a stimulus' name may go: offset from its point (points) and the text's alignment
_AROUND = (((4, 4), "left", "bottom"), ((4, -4), "left", "top"), ((-4, 4), "right", "bottom"),
           ((-4, -4), "right", "top"), ((0, 7), "center", "bottom"), ((0, -7), "center", "top"),
           ((7, 0), "left", "center"), ((-7, 0), "right", "center"))


def _box(anchor, size, ha, va):
    """(x0, y0, x1, y1) in pixels of a text of ``size`` aligned at ``anchor``."""
    w, h = size
    x0 = anchor[0] - {"left": 0.0, "center": w / 2, "right": w}[ha]
    y0 = anchor[1] - {"bottom": 0.0, "center": h / 2, "top": h}[va]
    return x0, y0, x0 + w, y0 + h


def _overlap(a, b):
    return max(0.0, min(a[2], b[2]) - max(a[0], b[0])) * max(0.0, min(a[3], b[3]) - max(a[1], b[1]))


def _place_names(ax, points, stimuli, ends):
    """Names each stimulus and each vector's ends, one at a time, at the candidate place
    that costs least: area outside the axes first, then area over names already placed
    and over points with the length of vector lying under it."""
    fig = ax.figure
    fig.draw_without_rendering()  # settles the layout and the equal-aspect limits
    renderer = fig.canvas.get_renderer()
    px = fig.dpi / 72.0  # pixels a point
    frame = ax.get_window_extent(renderer).extents
    to_px = ax.transData.transform
    marks = [(x - 3 * px, y - 3 * px, x + 3 * px, y + 3 * px) for x, y in to_px(points)]
    lines = [to_px(np.outer(np.linspace(-1.0, 1.0, 41), end)) for _, _, end in ends[::2]]
    placed = []

    def cost(box):
        """(area outside the axes, then the rest): a name is cut off only where every place is."""
        area = (box[2] - box[0]) * (box[3] - box[1])
        covered = sum(_overlap(box, other) for other in placed + marks)
        under = sum(int(np.count_nonzero((line[:, 0] > box[0]) & (line[:, 0] < box[2])
                                         & (line[:, 1] > box[1]) & (line[:, 1] < box[3]))) for line in lines)
        return area - _overlap(box, frame), covered + 4.0 * px * px * under

    def put(name, colour, xy, candidates, **style):
        text = ax.annotate(name, xy, textcoords="offset points", xytext=(0, 0), color=colour, fontsize=7,
                           annotation_clip=False, **style)
        text.set_in_layout(False)  # placed inside the axes: the layout must not move for it
        bbox = text.get_window_extent(renderer)
        size = (bbox.width, bbox.height)
        anchor = to_px(xy)
        boxes = [_box(anchor + np.asarray(offset) * px, size, ha, va) for offset, ha, va in candidates]
        best = min(range(len(boxes)), key=lambda i: (*cost(boxes[i]), i))  # ties: the first listed
        offset, ha, va = candidates[best]
        text.set_position(offset)
        text.set_horizontalalignment(ha)
        text.set_verticalalignment(va)
        x0, y0, x1, y1 = boxes[best]  # kept clear by a space: two names end to end read as one
        placed.append((x0 - 6 * px, y0 - 2 * px, x1 + 6 * px, y1 + 2 * px))

    for name, colour, end in ends:  # beyond the end, along the vector, or to either side
        u = to_px(end) - to_px(np.zeros(2))
        u = u / max(float(np.hypot(*u)), 1e-12)
        across = np.array([-u[1], u[0]])
        candidates = [(tuple(u * along + across * side), "center", "center")
                      for along in (9, 16, 24) for side in (0, 8, -8, 16, -16)]
        put(name, colour, end, candidates, weight="bold")
    for name, xy in zip(stimuli, points):
        candidates = [((dx * k, dy * k), ha, va) for k in (1, 2.5) for (dx, dy), ha, va in _AROUND]
        put(name, "black", xy, candidates)


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
