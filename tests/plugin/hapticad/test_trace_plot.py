# SPDX-License-Identifier: GPL-3.0-or-later
"""A stroke's plot magnifies a ripple too fine to read at the stroke's scale, and only then; a label in a
script its font lacks is drawn without a warning on the terminal."""
import os
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



class UnicodeLabelTest(unittest.TestCase):
    """A surface labelled in a script the plot's font lacks: matplotlib printed "UserWarning: Glyph 38754
    missing from current font" and its source line to the terminal of `hapticad feel` and `demo`."""

    def test_a_label_the_font_lacks_is_drawn_without_a_warning(self):
        import tempfile
        import warnings

        import FreeCAD as App

        import HaptiCAD
        from hapticad.document_scene import build_document_scene
        from hapticad.feel import Stroke, run_stroke_in_servo_loop, summarize
        from hapticad.trace_plot import plot_trace

        doc = App.newDocument("PlotLabel")
        try:
            box = doc.addObject("Part::Box", "Box")
            doc.recompute()
            HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False).Label = "Grïp 面"
            scene = build_document_scene(doc)
            result = run_stroke_in_servo_loop(scene, Stroke((2, 5, 10), (8, 5, 10), speed_mm_s=60))
            summary = summarize(result, scene)
            with tempfile.TemporaryDirectory() as tmp, warnings.catch_warnings(record=True) as caught:
                warnings.simplefilter("always")
                path = os.path.join(tmp, "trace.png")
                plot_trace(path, result, scene, summary, title="stroke on Grïp 面 ˯")
                self.assertGreater(os.path.getsize(path), 10000)
            self.assertEqual([str(w.message) for w in caught if "missing from current font" in str(w.message)], [])
        finally:
            App.closeDocument(doc.Name)

    def test_an_installed_font_that_has_the_characters_is_found(self):
        from matplotlib import font_manager, ft2font

        from hapticad.trace_plot import fallback_fonts

        # U+02EF: not in DejaVu Sans, in DejaVu Serif (which matplotlib ships)
        (first, *_) = fallback_fonts("˯")
        drawn = font_manager.findfont(font_manager.FontProperties(family=[first]))
        self.assertIn(0x2EF, ft2font.FT2Font(drawn).get_charmap())
        self.assertEqual(fallback_fonts(chr(0x10FFFD)), [])  # a private-use character no font has

if __name__ == "__main__":
    unittest.main()
