# SPDX-License-Identifier: GPL-3.0-or-later
"""Strokes that stay on one face: planes, cylinders, faces with something fused on."""
import unittest

import FreeCAD as App
import Part

from hapticad.face_strokes import plan_face_stroke


class FaceStrokeTest(unittest.TestCase):
    def assert_on_face(self, face, p0, p1):
        for i in range(11):
            p = p0 + (p1 - p0) * (i / 10)
            self.assertLess(face.distToShape(Part.Vertex(p))[0], 0.05 * (p1 - p0).Length)

    def test_plane_gets_a_stroke_through_the_middle(self):
        face = Part.makeBox(40, 20, 10).Faces[5]
        p0, p1 = plan_face_stroke(face)
        self.assert_on_face(face, p0, p1)
        self.assertAlmostEqual((p1 - p0).Length, 24.0, delta=1e-9)

    def test_cylinder_stroke_runs_along_the_axis(self):
        face = Part.makeCylinder(10, 50).Faces[0]
        p0, p1 = plan_face_stroke(face)
        self.assertAlmostEqual(abs((p1 - p0).normalize().z), 1.0, places=9)
        self.assert_on_face(face, p0, p1)

    def test_a_fused_feature_in_the_middle_is_avoided(self):
        base = Part.makeBox(100, 20, 10)
        pad = Part.makeBox(20, 20, 2, App.Vector(40, 0, 10))
        shape = base.fuse(pad).removeSplitter()
        top = [f for f in shape.Faces if abs(f.CenterOfMass.z - 10) < 1e-9][0]
        p0, p1 = plan_face_stroke(top)
        for i in range(11):
            p = p0 + (p1 - p0) * (i / 10)
            self.assertTrue(top.isInside(p, 1e-6, True), p)

    def test_a_sphere_has_no_straight_stroke_of_useful_length(self):
        face = Part.makeSphere(5).Faces[0]
        self.assertIsNone(plan_face_stroke(face))


if __name__ == "__main__":
    unittest.main()
