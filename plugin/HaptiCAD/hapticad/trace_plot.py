# SPDX-License-Identifier: GPL-3.0-or-later
"""PNG plot of a stroke: normal and tangential force against distance along it, and the
friction ratio while sliding. Where roughness or a texture ripples too finely to read at
the stroke's scale (a category-1 face: some 220 cycles in 22 mm), a third panel shows a
few cycles from the middle of the sliding, magnified."""
import functools
import warnings

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from matplotlib import font_manager, ft2font  # noqa: E402
from matplotlib.text import Text  # noqa: E402

from . import _core  # noqa: E402
from .feel import distance_along_stroke_mm, sliding_mask  # noqa: E402

DENSE_CYCLES = 40  # more ripple cycles than this along the stroke get the magnified panel
ZOOM_CYCLES = 6


def ripple_cycles(x_mm, values):
    """(cycles, mean cycle length in mm) of ``values`` about their mean along ``x_mm``: half
    the crossings of the mean. Samples that are NaN (not sliding) are left out; a swing
    under 0.1 % of the mean counts as none."""
    keep = np.isfinite(values)
    x, v = np.asarray(x_mm)[keep], np.asarray(values)[keep]
    if len(v) < 3 or np.ptp(v) <= 1e-3 * abs(v.mean()):  # rounding about a flat line is no ripple
        return 0, 0.0
    above = v > v.mean()
    cycles = int(np.count_nonzero(above[1:] != above[:-1])) // 2
    return cycles, (abs(x[-1] - x[0]) / cycles if cycles else 0.0)


def zoom_window(x_mm, values):
    """The magnified panel's (start, end) in mm, ZOOM_CYCLES cycles round the middle of the
    sliding, or None when the ripple is readable at the stroke's scale."""
    cycles, length = ripple_cycles(x_mm, values)
    if cycles <= DENSE_CYCLES:
        return None
    x = np.asarray(x_mm)[np.isfinite(values)]
    middle = 0.5 * (x.min() + x.max())
    return middle - ZOOM_CYCLES * length / 2, middle + ZOOM_CYCLES * length / 2


def plot_trace(path, result, doc_scene, summary, title=""):
    trace = result.trace
    contact = (trace["flags"] & _core.FLAG_CONTACT) != 0
    sliding = sliding_mask(result, doc_scene)
    x = distance_along_stroke_mm(result)
    fn = np.where(contact, trace["normal_force_n"], np.nan)
    ft = np.where(contact, trace["tangential_force_n"], np.nan)
    # where a vibration takes the push away (a face only pushes) there is no ratio to plot
    pushed = sliding & (trace["normal_force_n"] > 0)
    ratio = np.where(pushed, trace["tangential_force_n"] / np.where(pushed, trace["normal_force_n"], 1.0), np.nan)
    window = zoom_window(x, ratio)
    rows = 3 if window else 2
    fig = plt.figure(figsize=(8, 8.4 if window else 6), constrained_layout=True)
    top = fig.add_subplot(rows, 1, 1)
    bottom = fig.add_subplot(rows, 1, 2, sharex=top)
    top.plot(x, fn, color="tab:blue", lw=1.2, label="normal force $F_n$")
    top.plot(x, ft, color="tab:red", lw=1.2, label="tangential force $F_t$")
    top.axhline(summary["expected_normal_force_n"], color="tab:blue", ls=":", lw=1,
                label=f"$k\\cdot$depth = {summary['expected_normal_force_n']:.3f} N")
    limit = summary.get("force_limit_n")
    if limit is not None and limit < summary["expected_normal_force_n"]:  # the push is cut there
        top.axhline(limit, color="black", ls="--", lw=1, label=f"force limit {limit:g} N")
    top.set_ylabel("force (N)")
    _legend_above_data(top)
    top.grid(alpha=0.3)
    plt.setp(top.get_xticklabels(), visible=False)
    bottom.plot(x, ratio, color="black", lw=0.8 if window else 1.2, label="$F_t/F_n$ while sliding")
    _mean_and_mu(bottom, ratio, summary)
    bottom.set_xlabel("distance along the stroke (mm)")
    bottom.set_ylabel("$F_t/F_n$")
    _legend_above_data(bottom)
    bottom.grid(alpha=0.3)
    if window:
        bottom.axvspan(*window, color="tab:orange", alpha=0.25, lw=0)
        zoom = fig.add_subplot(rows, 1, 3)
        inside = (x >= window[0]) & (x <= window[1])
        zoom.plot(x[inside], ratio[inside], color="black", lw=1.2, marker=".", ms=2,
                  label=f"$F_t/F_n$, {window[1] - window[0]:.2f} mm magnified")
        _mean_and_mu(zoom, ratio, summary)
        zoom.set_xlim(*window)
        zoom.set_xlabel("distance along the stroke (mm), the shaded band above")
        zoom.set_ylabel("$F_t/F_n$")
        _legend_above_data(zoom)
        zoom.grid(alpha=0.3)
    stroke = summary["stroke"]
    fig.suptitle(title or f"stroke on {stroke['start_face']}: {stroke['depth_mm']} mm deep, "
                 f"{stroke['speed_mm_s']} mm/s, {summary['rate_hz']:.0f} Hz", fontsize=10)
    save_figure(fig, path)
    plt.close(fig)


# matplotlib's warning for a character no font of the text has (it drew a box there)
_MISSING_GLYPH = r"Glyph \d+ .*missing from current font"


def save_figure(fig, path, dpi=110):
    """Saves ``fig``, each text a label or name wrote in a script its font lacks (a surface
    labelled "Grïp 面") drawn with an installed font that has the characters
    (fallback_fonts), else with boxes for them, silently: matplotlib's warning, with its
    source line, went to the terminal of `hapticad feel` and `demo`."""
    for text in fig.findobj(Text):
        content = text.get_text()
        if not content or content.isascii():
            continue
        families = text.get_fontfamily()
        own = _charmap(font_manager.findfont(text.get_fontproperties()))
        more = fallback_fonts({c for c in content if not c.isspace() and ord(c) not in own})
        if more:
            text.set_fontfamily([*families, *more])
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message=_MISSING_GLYPH, category=UserWarning)
        fig.savefig(path, dpi=dpi)


@functools.lru_cache(maxsize=None)
def _charmap(path):
    """The characters (code points) a font file has; none when it cannot be read."""
    if not path:
        return frozenset()
    try:
        return frozenset(ft2font.FT2Font(path).get_charmap())
    except (OSError, RuntimeError, ValueError):
        return frozenset()


def fallback_fonts(characters):
    """Family names of installed fonts that together have as many of ``characters`` as
    they can, the one having the most first; [] when none has any. Each family is judged
    by the file matplotlib draws it with. Reads each font's character map once a session
    (some 0.1 s for 70 fonts)."""
    wanted = {ord(c) for c in characters}
    chosen = []
    while wanted:
        best, found = None, set()
        for family in _families():
            has = wanted & _charmap(_drawn_with(family))
            if len(has) > len(found) and family not in chosen:
                best, found = family, has
        if best is None:
            break
        chosen.append(best)
        wanted -= found
    return chosen


def _families():
    """The installed font families, by name, once each, in a stable order."""
    return sorted({font.name for font in font_manager.fontManager.ttflist})


@functools.lru_cache(maxsize=None)
def _drawn_with(family):
    """The font file matplotlib draws ``family`` with (its regular style), "" if none."""
    try:
        return font_manager.findfont(font_manager.FontProperties(family=[family]), fallback_to_default=False)
    except ValueError:
        return ""


def _mean_and_mu(ax, ratio, summary):
    """The sliding's mean friction ratio beside each face's mu_d: what the plot is read for."""
    if np.isfinite(ratio).any():
        mean = float(np.nanmean(ratio))
        ax.axhline(mean, color="tab:orange", lw=1.4, label=f"mean $F_t/F_n$ {mean:.3f}")
    for name, face in summary["faces"].items():
        ax.axhline(face["mu_dynamic"], ls="--", lw=1.2,
                   label=f"$\\mu_d$ {face['mu_dynamic']:g} {name} ({face['material'] or 'untagged'})")


def _legend_above_data(ax):
    """The legend in room made above the data: in the data's corner it hid the curves."""
    low, high = ax.get_ylim()
    entries = len(ax.get_legend_handles_labels()[0])
    ax.set_ylim(low, high + (high - low) * (0.12 + 0.1 * entries))
    ax.legend(loc="upper right", fontsize=8, ncol=2 if entries > 2 else 1)
