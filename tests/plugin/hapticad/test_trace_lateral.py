# SPDX-License-Identifier: GPL-3.0-or-later
"""A trace's friction and texture as felt: scaled down together where the force was
clamped to the device's limit, so that they add up to the lateral force sent, and left
as rendered everywhere else."""
import unittest

import numpy as np

from hapticad import _core
from hapticad.trace_lateral import felt_lateral_parts

FIELDS = [("time_s", float), ("flags", np.uint32), ("tangential_force_n", float), ("friction_force_n", float),
          ("texture_force_n", float)]


def trace(friction, texture, sent, flags):
    samples = np.zeros(len(friction), dtype=FIELDS)
    samples["time_s"] = np.arange(len(friction)) * 1e-3
    samples["friction_force_n"], samples["texture_force_n"] = friction, texture
    samples["tangential_force_n"], samples["flags"] = sent, flags
    return samples


CLAMPED = _core.FLAG_FORCE_CLAMPED
CONTACT = _core.FLAG_CONTACT


class FeltLateralPartsTest(unittest.TestCase):
    def test_a_clamped_force_scales_friction_and_texture_to_what_was_sent(self):
        # 1.5 N of friction and 3 N of texture rendered, 2.25 N sent: each felt at half
        felt = felt_lateral_parts(trace([1.5], [3.0], [2.25], [CLAMPED | CONTACT]))
        np.testing.assert_allclose(felt["friction_force_n"], [0.75])
        np.testing.assert_allclose(felt["texture_force_n"], [1.5])

    def test_samples_not_clamped_are_felt_as_rendered(self):
        # unflagged (even if sent less: that is not the clamp's doing), or flagged but sent
        # at least what was rendered
        felt = felt_lateral_parts(trace([0.6, 0.5, 0.4], [0.2, 1.0, 0.1], [0.8, 0.9, 0.7],
                                        [CONTACT, CONTACT, CLAMPED | CONTACT]))
        np.testing.assert_allclose(felt["friction_force_n"], [0.6, 0.5, 0.4])
        np.testing.assert_allclose(felt["texture_force_n"], [0.2, 1.0, 0.1])

    def test_each_sample_is_scaled_on_its_own(self):
        rng = np.random.default_rng(11)
        friction = rng.uniform(0.1, 2.0, 200)
        texture = rng.uniform(-0.05, 3.0, 200)
        clamped = rng.random(200) < 0.5
        sent = np.where(clamped, 0.4 * (friction + texture), friction + texture)
        felt = felt_lateral_parts(trace(friction, texture, sent, np.where(clamped, CLAMPED, 0)))
        total = felt["friction_force_n"] + felt["texture_force_n"]
        np.testing.assert_allclose(total[clamped], sent[clamped])  # they add up to what was sent
        np.testing.assert_allclose(felt["friction_force_n"][clamped], 0.4 * friction[clamped])
        np.testing.assert_allclose(felt["friction_force_n"][~clamped], friction[~clamped])
        np.testing.assert_allclose(felt["texture_force_n"][~clamped], texture[~clamped])

    def test_nothing_rendered_stays_nothing_and_an_empty_trace_is_empty(self):
        felt = felt_lateral_parts(trace([0.0], [0.0], [0.0], [CLAMPED]))
        self.assertEqual((felt["friction_force_n"][0], felt["texture_force_n"][0]), (0.0, 0.0))
        self.assertTrue(np.isfinite(felt["friction_force_n"]).all())
        empty = felt_lateral_parts(trace([], [], [], []))
        self.assertEqual({k: len(v) for k, v in empty.items()}, {"friction_force_n": 0, "texture_force_n": 0})


if __name__ == "__main__":
    unittest.main()
