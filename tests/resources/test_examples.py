# SPDX-License-Identifier: GPL-3.0-or-later
"""The example documents open, carry valid tags, and every tagged face can be felt."""
import os
import unittest

import FreeCAD as App

import HaptiCAD
from hapticad import EXAMPLES_DIR
from hapticad.document_scene import build_document_scene
from hapticad.face_strokes import plan_face_stroke


class ToothbrushTest(unittest.TestCase):
    def test_toothbrush_is_tagged_with_distinct_materials_and_roughness(self):
        doc = App.openDocument(os.path.join(EXAMPLES_DIR, "toothbrush.FCStd"))
        try:
            surfaces = HaptiCAD.surfaces_of(doc)
            self.assertEqual(len(surfaces), 4)
            self.assertGreaterEqual(len({s.Material for s in surfaces}), 3)
            self.assertGreaterEqual(len({s.RoughnessCategory for s in surfaces}), 4)
            scene = build_document_scene(doc)
            for s in surfaces:
                for obj, sub in HaptiCAD.reference_pairs(s):
                    face = scene.face_shape(f"{obj.Name}.{sub}")
                    self.assertIsNotNone(plan_face_stroke(face), f"{s.Label} {sub}")
        finally:
            App.closeDocument(doc.Name)


if __name__ == "__main__":
    unittest.main()
