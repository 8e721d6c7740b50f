# SPDX-License-Identifier: GPL-3.0-or-later
"""The perceptual-space plot: every stimulus and every vector's end is named, each name
inside the axes and none on another, at the panel's size and at the CLI's."""
import random
import unittest

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from hapticad.similarity_plot import draw_space
from hapticad.similarity_study import LIKENESS

SIZES = (((5.2, 5.2), 80), ((7, 6.5), 110))  # the Similarity panel's, the CLI's --plot


def vector(direction, low, high):
    return {"direction": list(direction), "length": float(np.linalg.norm(direction)), "correlation": 1.0,
            "low": low, "high": high}


def papers_grid():
    """The paper's nine stimuli as a cohort places them (seed 001 Fig. 7): three DC
    levels along axis 1, three viscosities along axis 2, and the three vectors, whose
    ends fall on the middle row and column of stimuli."""
    names, points = [], []
    for i, dc in enumerate((0.325, 0.5, 0.675)):
        for j, vis in enumerate((-0.2, 0.0, 0.2)):
            names.append(f"f_DC {dc:.3f} f_vis {vis:+.1f}")
            points.append((0.45 * (1 - i), 0.22 * (1 - j)))
    return {"stimuli": names, "points": points, "stress": 0.04, "participants": 10,
            "vectors": {"f_DC": vector((-0.89, 0.0), "low f_DC", "high f_DC"),
                        "f_vis": vector((0.0, -0.45), "low f_vis", "high f_vis"),
                        LIKENESS: vector((0.2, 0.3), "like B", "like A")}}


def names_drawn(result, size_in, dpi):
    fig = Figure(figsize=size_in, dpi=dpi, constrained_layout=True)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    draw_space(ax, result)
    fig.canvas.draw()
    renderer = fig.canvas.get_renderer()
    frame = ax.get_window_extent(renderer)
    return {t.get_text(): t.get_window_extent(renderer) for t in ax.texts}, frame


class SpacePlotTest(unittest.TestCase):
    def assert_named_clearly(self, result, may_touch=0):
        expected = set(result["stimuli"]) | {v[end] for v in result["vectors"].values() for end in ("low", "high")}
        for size_in, dpi in SIZES:
            boxes, frame = names_drawn(result, size_in, dpi)
            self.assertEqual(set(boxes), expected)
            for name, box in boxes.items():  # whole, inside the axes
                self.assertGreaterEqual(box.x0, frame.x0, name)
                self.assertLessEqual(box.x1, frame.x1, name)
                self.assertGreaterEqual(box.y0, frame.y0, name)
                self.assertLessEqual(box.y1, frame.y1, name)
            names = sorted(boxes)
            touching = [(a, b) for i, a in enumerate(names) for b in names[i + 1:] if boxes[a].overlaps(boxes[b])]
            self.assertLessEqual(len(touching), may_touch, (size_in, touching))

    def test_the_papers_nine_stimuli_and_three_vectors_are_all_named_apart(self):
        self.assert_named_clearly(papers_grid())

    def test_a_space_of_one_dimension_is_named_along_its_line(self):
        result = papers_grid()
        result["points"] = [(x,) for x, _ in result["points"]]
        result["vectors"] = {"f_DC": vector((-0.89,), "low f_DC", "high f_DC")}
        self.assert_named_clearly(result, may_touch=len(result["stimuli"]))  # three stimuli share each point

    def test_a_crowded_space_stays_inside_its_axes(self):
        rng = random.Random(7)
        result = papers_grid()
        result["stimuli"] = [f"S{i:02d}" for i in range(25)]
        result["points"] = [(rng.gauss(0, 0.3), rng.gauss(0, 0.2)) for _ in range(25)]
        self.assert_named_clearly(result, may_touch=2)


if __name__ == "__main__":
    unittest.main()
