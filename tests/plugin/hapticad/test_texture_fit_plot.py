# SPDX-License-Identifier: GPL-3.0-or-later
"""The texture fit's plot draws what the fit found: each section's spectrum and each
speed's power fits (Fig. 4), the per-speed values with their spread and eq. 2's lines
through them (Figs. 5 and 6), a title that says what was fitted, as a PNG."""
import os
import struct
import sys
import tempfile
import unittest

import numpy as np
from matplotlib import colors

from hapticad import _core, texture_fit
from hapticad.texture_fit_plot import plot_fit

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "support"))
from texture_recordings import write_rig_csv  # noqa: E402

SPEEDS_MM_S = (50.0, 120.0, 180.0)
UNIT_MM_S = _core.VISCOUS_SPEED_UNIT_MPS * 1e3  # eq. 2's speed unit, 400 mm/s


def png_size(path):
    """(width, height) in pixels from a PNG's header."""
    with open(path, "rb") as f:
        head = f.read(24)
    assert head[:8] == b"\x89PNG\r\n\x1a\n", "not a PNG"
    return struct.unpack(">II", head[16:24])


class TextureFitPlotTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        # a rig stroking a grating (the default f_DC 0.4, f_vis 0.2 of a 2 N range) back and
        # forth at three speeds: deterministic, no randomness
        cls.tmp = tempfile.TemporaryDirectory()
        rig = os.path.join(cls.tmp.name, "rig.csv")
        write_rig_csv(_core, rig, speeds_mm_s=SPEEDS_MM_S)
        cls.report = texture_fit.fit_files([rig], 2.5, SPEEDS_MM_S)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def draw(self, title=""):
        """Plots the report; returns (the figure drawn, the PNG path)."""
        path = os.path.join(self.tmp.name, f"fit{len(os.listdir(self.tmp.name))}.png")
        return plot_fit(path, self.report, title), path

    def test_a_png_of_four_panels_is_written(self):
        fig, path = self.draw()
        self.assertEqual(png_size(path), (1100, 825))  # 10 x 7.5 in at 110 dpi
        self.assertEqual(len(fig.axes), 4)
        titles = [ax.get_title() for ax in fig.axes]
        self.assertIn("spectra", titles[0])
        self.assertEqual(titles[1:], ["DC friction: f_DC + v f_vis", "harmonic amplitude: beta_h + v beta_vis",
                                      "harmonic decay: alpha_h + v alpha_vis"])

    def test_the_title_says_what_was_fitted_unless_one_is_given(self):
        fit = self.report.fit
        fig, _ = self.draw()
        self.assertEqual(fig._suptitle.get_text(),
                         f"texture fit: grating 2.5 mm, {len(fit.sections)} sections, 1 recording(s)")
        fig, _ = self.draw("Grip, rig of 3 May")
        self.assertEqual(fig._suptitle.get_text(), "Grip, rig of 3 May")

    def test_the_spectra_panel_draws_every_section_and_each_speeds_fits(self):
        fit = self.report.fit
        self.assertEqual(len(fit.speeds), 3)
        spectra = self.draw()[0].axes[0]
        harmonics = np.arange(1, self.report.options.harmonics + 1)
        fits = [line for line in spectra.lines if line.get_marker() == "o"]
        backgrounds = [line for line in spectra.lines if line.get_linestyle() == "--"]
        sections = [line for line in spectra.lines if line.get_linewidth() == 0.5]
        self.assertEqual(len(sections), len(fit.sections))
        self.assertEqual(len(fits), len(fit.speeds))
        self.assertEqual(len(backgrounds), sum(1 for s in fit.speeds if s.background.points))
        for s, line in zip(fit.speeds, fits):
            x, y = line.get_data()
            np.testing.assert_allclose(x, harmonics)
            np.testing.assert_allclose(y, s.harmonic.beta * harmonics ** -s.harmonic.alpha)
            # the speed's sections are drawn in its colour, one legend entry for them
            mine = [line2 for line2 in sections if colors.same_color(line2.get_color(), line.get_color())]
            self.assertEqual(len(mine), s.sections)
            self.assertEqual([m.get_label() for m in mine if not m.get_label().startswith("_")],
                             [f"{s.speed_mps * 1e3:.0f} mm/s ({s.sections})"])
        # a section's spectrum: its amplitudes against multiples of 1/lambda, DC left out
        section = fit.sections[0]
        amplitude = np.asarray(section.amplitude_n)
        x, y = sections[0].get_data()
        np.testing.assert_allclose(x, np.arange(1, len(amplitude)) / section.periods)
        np.testing.assert_allclose(y, amplitude[1:])
        self.assertEqual((spectra.get_xscale(), spectra.get_yscale()), ("log", "log"))

    def test_each_value_is_drawn_per_speed_with_eq2s_line_through_it(self):
        fit = self.report.fit
        fig, _ = self.draw()
        speeds = np.array([s.speed_mps * 1e3 for s in fit.speeds])
        for ax, values, line in ((fig.axes[1], [s.dc_n for s in fit.speeds], fit.dc_n),
                                 (fig.axes[2], [s.harmonic.beta for s in fit.speeds], fit.beta_h_n),
                                 (fig.axes[3], [s.harmonic.alpha for s in fit.speeds], fit.alpha_h)):
            title = ax.get_title()
            (dots,) = [x for x in ax.lines if x.get_label() == "per speed"]
            np.testing.assert_allclose(dots.get_xdata(), speeds, err_msg=title)
            np.testing.assert_allclose(dots.get_ydata(), values, err_msg=title)
            sign = "-" if line.slope < 0 else "+"  # "0.25 - 4.4e-05 v", not "0.25 + -4.366e-05 v"
            (drawn,) = [x for x in ax.lines
                        if x.get_label() == f"{line.intercept:.4g} {sign} {abs(line.slope):.3g} v/(400 mm/s)"]
            x, y = drawn.get_data()
            self.assertEqual(x[0], 0.0)
            self.assertGreater(x[-1], speeds.max())  # past the fastest speed
            np.testing.assert_allclose(y, line.intercept + line.slope * x / UNIT_MM_S, err_msg=title)
            self.assertEqual(ax.get_ylim()[0], 0.0, title)
            self.assertGreater(ax.get_ylim()[1], 1.2 * max(values), title)  # points and legend off the edge
        # the rig's grating: f_DC 0.4 + f_vis 0.2 of 2 N, so the DC line reads 0.8 N + 0.4 N per 400 mm/s
        self.assertAlmostEqual(fit.dc_n.intercept, 0.8, delta=0.02)
        self.assertAlmostEqual(fit.dc_n.slope, 0.4, delta=0.02)

    def test_the_dc_forces_spread_is_drawn_as_error_bars(self):
        fit = self.report.fit
        dc = self.draw()[0].axes[1]
        (bars,) = dc.containers
        segments = bars.lines[2][0].get_segments()
        self.assertEqual(len(segments), len(fit.speeds))
        for s, segment in zip(fit.speeds, segments):
            (x0, low), (x1, high) = segment
            self.assertAlmostEqual(x0, s.speed_mps * 1e3)
            self.assertAlmostEqual(x1, s.speed_mps * 1e3)
            self.assertAlmostEqual(low, s.dc_n - s.dc_sd_n)
            self.assertAlmostEqual(high, s.dc_n + s.dc_sd_n)
        self.assertTrue(any(s.dc_sd_n > 0 for s in fit.speeds))  # two sections a speed: a spread to draw


if __name__ == "__main__":
    unittest.main()
