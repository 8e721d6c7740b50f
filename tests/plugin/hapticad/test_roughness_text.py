# SPDX-License-Identifier: GPL-3.0-or-later
"""A roughness category's Ra band in words: closed bands, the open ends of Table 2
(seed 000), the ASCII form Coin draws, with and without the ISO N-grades."""
import unittest
from types import SimpleNamespace

from hapticad import _core
from hapticad.roughness_text import ra_band


class RaBandTest(unittest.TestCase):
    def test_the_seven_categories_of_table_2(self):
        self.assertEqual([ra_band(r) for r in _core.roughness_table()], [
            "Ra up to 0.05 µm (N1, N2)",
            "Ra 0.05–0.2 µm (N3, N4)",
            "Ra 0.2–0.8 µm (N5, N6)",
            "Ra 0.8–3.2 µm (N7, N8)",
            "Ra 3.2–12.5 µm (N9, N10)",
            "Ra 12.5–50 µm (N11, N12)",
            "Ra over 50 µm",
        ])

    def test_ascii_for_coin_and_without_grades(self):
        row = _core.roughness_category(3)
        self.assertEqual(ra_band(row, ascii_only=True), "Ra 0.2-0.8 um (N5, N6)")
        self.assertEqual(ra_band(row, grades=False), "Ra 0.2–0.8 µm")
        for r in _core.roughness_table():
            self.assertTrue(ra_band(r, ascii_only=True).isascii())

    def test_a_band_open_at_both_ends_is_unclassified(self):
        row = SimpleNamespace(ra_min_um=None, ra_max_um=None, n_grades=[])
        self.assertEqual(ra_band(row), "Ra unclassified")


if __name__ == "__main__":
    unittest.main()
