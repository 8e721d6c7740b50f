# SPDX-License-Identifier: GPL-3.0-or-later
"""A stroke's plot magnifies a ripple too fine to read at the stroke's scale, and only then."""
import unittest

import numpy as np

from hapticad.trace_plot import DENSE_CYCLES, ZOOM_CYCLES, ripple_cycles, zoom_window


def ripple(cycles, length_mm=22.0, samples_per_cycle=10, lead_mm=2.0):
    """Ft/Fn over a stroke: NaN (not sliding) for ``lead_mm``, then ``cycles`` cycles of a
    sine about 0.41, as a category-1 face at 5 kHz gives (10 samples a 0.1 mm cycle)."""
    x = np.linspace(-lead_mm, length_mm, int((length_mm + lead_mm) / length_mm * cycles * samples_per_cycle))
    values = 0.41 + 0.08 * np.sin(2 * np.pi * cycles * x / length_mm + 0.3)
    values[x < 0] = np.nan
    return x, values


class ZoomWindowTest(unittest.TestCase):
    def test_a_category_1_ripple_is_magnified_round_the_middle_of_the_sliding(self):
        x, values = ripple(220)
        cycles, length = ripple_cycles(x, values)
        self.assertAlmostEqual(cycles, 220, delta=1)
        self.assertAlmostEqual(length, 0.1, delta=0.002)
        start, end = zoom_window(x, values)
        self.assertAlmostEqual(0.5 * (start + end), 11.0, delta=0.05)  # the sliding's middle, not the stroke's
        self.assertAlmostEqual((end - start) / length, ZOOM_CYCLES, delta=0.01)

    def test_a_ripple_readable_at_the_strokes_scale_is_not(self):
        self.assertIsNone(zoom_window(*ripple(30)))
        self.assertIsNone(zoom_window(*ripple(DENSE_CYCLES)))
        self.assertIsNotNone(zoom_window(*ripple(DENSE_CYCLES + 2)))

    def test_no_sliding_or_a_flat_trace_has_no_window(self):
        x = np.linspace(0, 22, 1000)
        self.assertIsNone(zoom_window(x, np.full_like(x, np.nan)))
        self.assertIsNone(zoom_window(x, np.full_like(x, 0.4)))
        rounding = 0.4 + 1e-12 * np.random.default_rng(3).standard_normal(len(x))
        self.assertIsNone(zoom_window(x, rounding))


if __name__ == "__main__":
    unittest.main()
