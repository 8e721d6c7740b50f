# SPDX-License-Identifier: GPL-3.0-or-later
"""trace_path: how far the proxy slid over given faces in a trace, counted only between
samples that both touch one of them."""
import unittest

import numpy as np

from hapticad import _core
from hapticad.trace_path import slid_mm


def trace(points_mm, faces, contact):
    """A trace of the three fields slid_mm reads: proxy positions (mm), faces, contact."""
    out = np.zeros(len(points_mm), dtype=[("proxy_m", float, 3), ("cad_face", np.int32), ("flags", np.uint32)])
    out["proxy_m"] = np.asarray(points_mm, float) * 1e-3
    out["cad_face"] = faces
    out["flags"] = [_core.FLAG_CONTACT if c else 0 for c in contact]
    return out


class SlidTest(unittest.TestCase):
    def test_a_stroke_over_the_faces_is_its_path_length(self):
        points = [[x, 0.0, 0.0] for x in (0.0, 0.5, 1.0, 2.0)] + [[2.0, 1.5, 0.0]]
        self.assertAlmostEqual(slid_mm(trace(points, [3] * 5, [True] * 5), [3]), 3.5)
        self.assertAlmostEqual(slid_mm(trace(points, [3] * 5, [True] * 5), np.array([1, 3])), 3.5)

    def test_only_steps_between_two_samples_touching_the_faces_count(self):
        points = [[x, 0.0, 0.0] for x in range(6)]
        # 0-1 on face 3; 1-2 onto face 4 (not counted); 2-3 on 4; 3-4 off contact; 4-5 on 3
        faces = [3, 3, 4, 4, 3, 3]
        contact = [True, True, True, True, False, True]
        self.assertAlmostEqual(slid_mm(trace(points, faces, contact), [3]), 1.0)
        self.assertAlmostEqual(slid_mm(trace(points, faces, contact), [3, 4]), 3.0)
        # the same face id without the contact flag (the trace's last face when free) is not touching
        self.assertEqual(slid_mm(trace(points, [3] * 6, [False] * 6), [3]), 0.0)

    def test_resting_pressing_and_short_traces_slide_nothing(self):
        resting = trace([[1.0, 2.0, 0.0]] * 4, [3] * 4, [True] * 4)
        self.assertEqual(slid_mm(resting, [3]), 0.0)
        self.assertEqual(slid_mm(trace([[0.0, 0.0, 0.0]], [3], [True]), [3]), 0.0)
        self.assertEqual(slid_mm(trace([[0, 0, 0], [5, 0, 0]], [3, 3], [True, True]), []), 0.0)


if __name__ == "__main__":
    unittest.main()
