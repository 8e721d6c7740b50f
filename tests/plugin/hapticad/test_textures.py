# SPDX-License-Identifier: GPL-3.0-or-later
"""The paper's nine viscous-texture presets, as offered in the document."""
import unittest

from hapticad import textures


class PresetTest(unittest.TestCase):
    def test_nine_presets_cross_dc_and_viscosity_with_the_fixed_values(self):
        self.assertEqual(len(textures.PRESETS), 9)
        dcs = sorted({p[0] for p in textures.PRESETS.values()})
        viscosities = sorted({p[1] for p in textures.PRESETS.values()})
        self.assertEqual(dcs, [0.325, 0.5, 0.675])
        self.assertEqual(viscosities, [-0.2, 0.0, 0.2])
        for values in textures.PRESETS.values():
            self.assertEqual(values[2:], (0.125, 2.5, 0.0, 0.0))
        self.assertEqual(textures.CHOICES[:2], ["None", "Custom"])
        self.assertIn("Paper f_DC 0.500 f_vis +0.2", textures.PRESETS)


if __name__ == "__main__":
    unittest.main()
