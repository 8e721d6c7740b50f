# SPDX-License-Identifier: GPL-3.0-or-later
"""Scenes built from documents: every face of every referenced solid, face ids that
match FreeCAD's face names, per-face properties, global placement."""
import math
import unittest

import FreeCAD as App
import Part

import HaptiCAD
import numpy as np

from hapticad import _core
from hapticad import accuracy
from hapticad import document_scene
from hapticad.document_scene import MM, build_document_scene
from hapticad.tessellation_size import TooManyTriangles


def point_on(face):
    """(u, v) of a point on the face (not in a hole), as central as a 9x9 grid allows."""
    u0, u1, v0, v1 = face.ParameterRange
    grid = sorted(((i, j) for i in range(1, 10) for j in range(1, 10)),
                  key=lambda ij: abs(ij[0] - 5) + abs(ij[1] - 5))
    for i, j in grid:
        u, v = u0 + (u1 - u0) * i / 10, v0 + (v1 - v0) * j / 10
        if face.isInside(face.valueAt(u, v), 1e-6, True):
            return u, v
    raise AssertionError("no point found on the face")


def probe_face(doc_scene, face, offset_mm=0.01):
    """The scene's face name at a point just off a B-rep face."""
    u, v = point_on(face)
    p = face.valueAt(u, v) + face.normalAt(u, v) * offset_mm
    sample = doc_scene.scene.calc_closest_point([p.x * MM, p.y * MM, p.z * MM])
    return doc_scene.face_names[sample.cad_face], sample


def hold_device_at(doc_scene, device, ticks=20):
    """(proxy, force) after the device has rested at ``device`` (mm) from a fresh start:
    the proxy in mm, the force in N, both App.Vector."""
    renderer = _core.ForceRenderer(doc_scene.scene, doc_scene.surfaces, _core.RenderLimits())
    out = _core.run_stroke(renderer, np.tile([v * MM for v in device], (ticks, 1)),
                           np.zeros((ticks, 3)), [k * 1e-3 for k in range(ticks)])
    return App.Vector(*(out["proxy_w"][-1] / MM)), App.Vector(*out["force_w"][-1])


class DocumentSceneTest(unittest.TestCase):
    def assertPushedOutTowardTheProxy(self, proxy, device, force):
        # within a ray's reach of the nearest way out, the spring pulling the device to it
        self.assertLess(proxy.distanceToPoint(device), 12.0)
        self.assertGreater(force.Length, 0.0)
        self.assertGreater(force.dot(proxy - device), 0.99 * force.Length * (proxy - device).Length)

    def setUp(self):
        self.doc = App.newDocument("SceneTest")
        box = Part.makeBox(40, 30, 20)
        hole = Part.makeCylinder(5, 40, App.Vector(20, 15, -10))
        self.part = self.doc.addObject("Part::Feature", "Part")
        self.part.Shape = box.cut(hole)
        self.other = self.doc.addObject("Part::Sphere", "Ball")
        self.other.Radius = 8
        self.other.Placement.Base = App.Vector(100, 0, 0)
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def top_face(self):
        for i, f in enumerate(self.part.Shape.Faces):
            if abs(f.CenterOfMass.z - 20) < 1e-9 and f.Surface.__class__.__name__ == "Plane":
                return f"Face{i + 1}"
        raise AssertionError("no top face")

    def test_all_faces_of_referenced_solids_with_matching_ids(self):
        top = self.top_face()
        HaptiCAD.make_surface(self.doc, [(self.part, top)], material="Rubber")
        ds = build_document_scene(self.doc)
        shape = self.part.Shape
        self.assertEqual(ds.scene.num_cad_faces, len(shape.Faces))
        self.assertEqual(ds.face_names, [f"Part.Face{i + 1}" for i in range(len(shape.Faces))])
        # the untagged sphere is not part of the scene
        self.assertNotIn("Ball.Face1", ds.face_names)
        for i, face in enumerate(shape.Faces):
            name, sample = probe_face(ds, face)
            self.assertEqual(name, f"Part.Face{i + 1}")
            self.assertLess(sample.distance_m, 0.2 * MM)

    def test_tagged_faces_get_their_properties_and_others_the_default(self):
        top = self.top_face()
        HaptiCAD.make_surface(self.doc, [(self.part, top)], material="Rubber", stiffness_n_per_mm=0.25)
        ds = build_document_scene(self.doc)
        tagged = ds.surface_properties(ds.face_id(f"Part.{top}"))
        self.assertEqual(tagged.friction.dynamic_coefficient, 1.0)
        self.assertAlmostEqual(tagged.stiffness_n_per_m, 250.0)
        untagged = ds.surface_properties(ds.face_id("Part.Face1" if top != "Face1" else "Part.Face2"))
        self.assertEqual(untagged.friction.dynamic_coefficient, _core.UNTAGGED_SURFACE.friction.dynamic_coefficient)
        self.assertEqual(ds.face_material, {f"Part.{top}": "Rubber"})

    def test_a_property_edit_compiles_the_faces_again_without_finding_them_again(self):
        # finding each face's frame point cost most of an edit's way to the loop (3 ms on
        # the toothbrush): it is the same on the same shapes, so it is kept with the scene
        from unittest import mock

        from hapticad import document_scene

        top = self.top_face()
        surface = HaptiCAD.make_surface(self.doc, [(self.part, top)], material="Rubber", pattern="Linear",
                                         roughness_category=5)
        ds = build_document_scene(self.doc)
        self.assertEqual(set(ds.face_points), {f"Part.{top}"})
        surface.Stiffness, surface.PatternAngle = 0.3, 30.0
        with mock.patch.object(document_scene, "point_on_face", side_effect=AssertionError("found again")):
            edited = document_scene.recompile_surfaces(self.doc, ds)
        fresh = build_document_scene(self.doc)  # built from nothing: the same properties
        a, b = (s.surface_properties(s.face_id(f"Part.{top}")) for s in (edited, fresh))
        self.assertAlmostEqual(a.stiffness_n_per_m, 300.0)
        self.assertEqual(a.stiffness_n_per_m, b.stiffness_n_per_m)
        for frame in ("origin_w", "e1_w", "e2_w"):
            np.testing.assert_array_equal(getattr(a.roughness.frame, frame), getattr(b.roughness.frame, frame))
        np.testing.assert_array_equal(a.pattern.direction_w, b.pattern.direction_w)

    def test_objects_inside_a_placed_container_use_their_global_placement(self):
        container = self.doc.addObject("App::Part", "Assembly")
        container.Placement.Base = App.Vector(0, 0, 500)
        container.addObject(self.other)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.other, "Face1")])
        ds = build_document_scene(self.doc)
        sample = ds.scene.calc_closest_point([0.1, 0.0, 0.6])
        self.assertAlmostEqual(sample.point_w[2], 0.5 + 0.008, delta=1e-4)
        self.assertEqual(ds.face_names[sample.cad_face], "Ball.Face1")

    def test_two_objects_share_one_scene(self):
        HaptiCAD.make_surface(self.doc, [(self.part, "Face1")])
        HaptiCAD.make_surface(self.doc, [(self.other, "Face1")], material="Steel")
        ds = build_document_scene(self.doc)
        self.assertEqual(len(ds.face_names), len(self.part.Shape.Faces) + 1)
        name, _ = probe_face(ds, self.other.Shape.Faces[0])
        self.assertEqual(name, "Ball.Face1")

    def test_errors_name_the_problem(self):
        with self.assertRaises(ValueError) as caught:
            build_document_scene(self.doc)
        self.assertIn("no HapticSurface", str(caught.exception))
        a = HaptiCAD.make_surface(self.doc, [(self.part, "Face1")])
        with self.assertRaisesRegex(ValueError, "already tagged"):
            HaptiCAD.make_surface(self.doc, [(self.part, "Face1")], name="Again")
        # a script that sets References itself gets past make_surface, not past the scene
        again = HaptiCAD.make_surface(self.doc, [(self.part, "Face2")], name="Again")
        again.References = [(self.part, ("Face1", "Face2"))]
        with self.assertRaises(ValueError) as caught:
            build_document_scene(self.doc)
        self.assertIn("Part.Face1 is tagged by both", str(caught.exception))
        self.assertTrue(a.isValid())
        # the tagged part deleted: said, not "every tagged face reference is broken"
        label = self.part.Label
        self.doc.removeObject(self.part.Name)
        with self.assertRaises(ValueError) as caught:
            build_document_scene(self.doc)
        self.assertIn(f"the tagged part {label} was deleted; undo the deletion", str(caught.exception))

    def test_the_faces_tessellations_are_stitched_into_a_closed_surface(self):
        # a box with a hole and a sphere: the repair welds every face to its neighbours
        HaptiCAD.make_surface(self.doc, [(self.part, "Face1")])
        HaptiCAD.make_surface(self.doc, [(self.other, "Face1")])
        for name in accuracy.PRESETS:
            ds = build_document_scene(self.doc, accuracy.preset(name))
            self.assertTrue(ds.watertight, f"{name}: {ds.repair}")
            self.assertIn("closed", ds.repair)
            self.assertIs(ds.accuracy, accuracy.PRESETS[name])

    def test_a_part_far_from_the_origin_is_felt_as_at_the_origin(self):
        # FreeCAD's meshes are single precision: 1 km off (1e6 mm) the cylinder came out on
        # a 1/16 mm grid, with 24 open edges, its forces 3.75 % off, and a 1 mm ball lost
        # three quarters of its triangles. Meshed about its centre, the same to 1e-9
        forces, counts = {}, {}
        for offset in (0.0, 1e3, 1e6):
            doc = App.newDocument("Far")
            try:
                can = doc.addObject("Part::Cylinder", "Can")
                can.Radius, can.Height = 15, 40
                ball = doc.addObject("Part::Sphere", "Bead")
                ball.Radius = 0.5
                can.Placement.Base = App.Vector(offset, offset, offset)
                ball.Placement.Base = App.Vector(offset + 40, offset, offset)
                doc.recompute()
                HaptiCAD.make_surface(doc, [(can, "Face1"), (ball, "Face1")], material="ABS")
                ds = build_document_scene(doc, accuracy.preset("Fine"))
                self.assertTrue(ds.watertight, f"{offset}: {ds.repair}")
                counts[offset] = ds.scene.num_triangles
                # round the can, 1 mm deep, rising and falling; then pressed into the bead off its pole
                # (a press straight over a vertex is a tie that any rounding decides)
                t = np.arange(2000) * 1e-3
                turn = 75 * t / 15
                out = np.stack([np.cos(turn), np.sin(turn), 0 * turn], 1)
                path = out * 14 + np.stack([0 * t, 0 * t, 20 + 12 * np.sin(0.5 * turn)], 1)
                bead = np.tile([40.13, 0.07, 0.7], (300, 1)) - np.linspace(0, 0.4, 300)[:, None] * [0, 0, 1]
                path = np.vstack([out[0] * 17 + [0, 0, 20], path, [40, 0, 2], bead]) + offset
                renderer = _core.ForceRenderer(ds.scene, ds.surfaces, _core.RenderLimits(), ds.contact_options())
                trace = _core.run_stroke(renderer, path * MM, np.zeros_like(path), list(np.arange(len(path)) * 1e-3))
                self.assertTrue((np.asarray(trace["flags"])[-100:] & _core.FLAG_CONTACT).all())  # on the bead
                forces[offset] = np.asarray(trace["force_w"])
            finally:
                App.closeDocument(doc.Name)
        largest = np.abs(forces[0.0]).max()
        self.assertGreater(largest, 0.3)
        for offset in (1e3, 1e6):
            self.assertEqual(counts[offset], counts[0.0])
            np.testing.assert_allclose(forces[offset], forces[0.0], rtol=0, atol=1e-9 * largest,
                                       err_msg=f"{offset:g} mm off")

    def test_corner_normals_are_the_exact_normals_of_each_face(self):
        # on the cylinder's wall the normal at a vertex is radial, whatever the facets do
        HaptiCAD.make_surface(self.doc, [(self.part, "Face1")])
        ds = build_document_scene(self.doc, accuracy.preset("Draft"))
        hole = next(i for i, f in enumerate(self.part.Shape.Faces) if f.Surface.TypeId == "Part::GeomCylinder")
        checked = 0
        for z in (2.0, 10.0, 18.0):
            for angle in np.linspace(0.1, 6.0, 7):
                # a point a hair inside the hole's wall (the wall faces the axis)
                p = np.array([20 + 4.99 * np.cos(angle), 15 + 4.99 * np.sin(angle), z])
                sample = ds.scene.calc_closest_point(p * MM)
                if sample.cad_face != hole:
                    continue
                q = np.asarray(sample.point_w) / MM
                radial = np.array([20 - q[0], 15 - q[1], 0.0])  # toward the axis: out of the material
                radial /= np.linalg.norm(radial)
                self.assertGreater(float(np.dot(sample.normal_w, radial)), np.cos(np.radians(1.0)))
                checked += 1
        self.assertGreater(checked, 15)

    def test_presets_trade_triangles_for_accuracy(self):
        HaptiCAD.make_surface(self.doc, [(self.other, "Face1")])
        counts = [build_document_scene(self.doc, accuracy.preset(n)).scene.num_triangles
                  for n in ("Draft", "Normal", "Fine")]
        self.assertLess(counts[0], counts[1])
        self.assertLess(counts[1], counts[2])
        with self.assertRaises(KeyError):
            accuracy.preset("Ultra")
        with self.assertRaises(ValueError) as caught:
            accuracy.custom(0.0, 0.3)
        self.assertIn("linear deflection", str(caught.exception))
        custom = accuracy.custom(0.05, 0.2, force_shading=False)
        self.assertFalse(custom.force_shading)
        with self.assertRaises(ValueError) as caught:
            accuracy.custom(0.1, 0.3, refine_edge_mm=-1.0)
        self.assertIn("refinement edge", str(caught.exception))
        # refinement: more triangles, still closed
        coarse = build_document_scene(self.doc, accuracy.preset("Draft"))
        refined = build_document_scene(self.doc, accuracy.custom(0.5, 0.5, refine_edge_mm=2.0))
        self.assertGreater(refined.scene.num_triangles, 2 * coarse.scene.num_triangles)
        self.assertTrue(refined.watertight, refined.repair)

    def test_parts_that_would_make_too_many_triangles_are_refused_before_anything_is_meshed(self):
        # a 1 m ball at Fine (251,048 triangles in one face: 19 s and 1.15 GB on the GUI
        # thread), a 1 mm bead at the smallest angle the Preferences page shows (805,416:
        # 508 s), next to the part of the other tests, which alone is built as before
        HaptiCAD.make_surface(self.doc, [(self.part, self.top_face())])
        ball = self.doc.addObject("Part::Sphere", "Globe")
        ball.Radius = 500
        bead = self.doc.addObject("Part::Sphere", "Bead")
        bead.Radius = 0.5
        self.doc.recompute()
        meshed = []
        mesher = document_scene.MeshPart.meshFromShape

        def counted(**kwargs):
            meshed.append(kwargs["Shape"])
            if kwargs["Shape"].BoundBox.DiagonalLength > 1000 or kwargs["Shape"].BoundBox.DiagonalLength < 2:
                raise AssertionError("the globe or the bead was meshed")  # for seconds to minutes
            return mesher(**kwargs)

        document_scene.MeshPart.meshFromShape = counted
        try:
            for part, acc, said in ((ball, accuracy.preset("Fine"), "Globe: about 252,000 triangles in its Face1"),
                                    (bead, accuracy.custom(0.02, math.radians(0.573)),
                                     "Bead: about 807,000 triangles in its Face1")):
                with self.subTest(part=part.Label):
                    surface = HaptiCAD.make_surface(self.doc, [(part, "Face1")])
                    with self.assertRaises(TooManyTriangles) as caught:
                        build_document_scene(self.doc, acc)
                    self.assertIn(said, str(caught.exception))
                    self.assertEqual(meshed, [])
                    self.doc.removeObject(surface.Name)
            self.assertEqual(build_document_scene(self.doc, accuracy.preset("Fine")).face_names[0], "Part.Face1")
            self.assertEqual(len(meshed), 1)
        finally:
            document_scene.MeshPart.meshFromShape = mesher

    def test_a_device_starting_inside_parts_that_touch_is_pushed_out_of_both(self):
        # an assembly: a button against its housing's side, then sunk 3 mm into it. The
        # device starts in the housing 0.5 mm from the button: the proxy must not be
        # left in the button, whose face lies nearest along the +x rays
        housing = self.doc.addObject("Part::Box", "Housing")
        housing.Length = housing.Width = housing.Height = 20
        housing.Placement.Base = App.Vector(0, 100, 0)
        button = self.doc.addObject("Part::Box", "Button")
        button.Length, button.Width, button.Height = 10, 12, 12
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(housing, "Face1"), (button, "Face1")])
        for sunk in (0.0, 3.0):
            button.Placement.Base = App.Vector(20 - sunk, 104, 4)
            self.doc.recompute()
            ds = build_document_scene(self.doc)
            self.assertTrue(ds.watertight, ds.repair)
            device = App.Vector(19.5, 110, 10)
            proxy, force = hold_device_at(ds, device)
            # (it rests 1e-9 of the scene's size off the faces: 4e-8 mm here)
            for part in (housing, button):
                self.assertFalse(part.Shape.isInside(proxy, 1e-9, False),
                                 f"sunk {sunk}: proxy {proxy} in {part.Name}")
            # the housing's sides are 0.5 mm and 10 mm away, the button's far end 10 mm
            self.assertPushedOutTowardTheProxy(proxy, device, force)

    def test_a_device_starting_inside_a_part_beside_a_sheet_is_pushed_out(self):
        # a solid and an open sheet in one scene (a surface model's panel beside a
        # part): the sheet bounds nothing, and the part's inside is still known. The
        # device starts 2 mm under the part's top, away from its bore
        sheet = self.doc.addObject("Part::Plane", "Panel")
        sheet.Length, sheet.Width = 60, 50
        sheet.Placement.Base = App.Vector(-10, -10, 30)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(self.part, self.top_face()), (sheet, "Face1")])
        ds = build_document_scene(self.doc)
        self.assertFalse(ds.watertight)  # the sheet's edges are open
        device = App.Vector(8, 7, 18)
        proxy, force = hold_device_at(ds, device)
        self.assertFalse(self.part.Shape.isInside(proxy, 1e-9, False), f"proxy {proxy} in the part")
        self.assertPushedOutTowardTheProxy(proxy, device, force)
        # a device starting on the sheet itself, beside the part, is left where it is
        on_sheet = App.Vector(45, 0, 30)
        proxy, force = hold_device_at(ds, on_sheet, ticks=1)
        self.assertAlmostEqual(proxy.distanceToPoint(on_sheet), 0.0, delta=1e-9)  # < the offset

    def test_a_hollow_parts_void_stays_a_void(self):
        # a block round a sealed spherical void (two shells, the inner one wound inward by
        # the tessellator), and a sheet beside it, so inside is known piece by piece, by
        # how each winds: the repair turns nothing round, a device in the void is left
        # there, and one in the wall is pushed out
        hollow = self.doc.addObject("Part::Feature", "Hollow")
        hollow.Shape = Part.makeBox(40, 40, 40).cut(Part.makeSphere(12, App.Vector(20, 20, 20)))
        hollow.Placement.Base = App.Vector(0, 0, 100)
        self.doc.recompute()
        self.assertEqual(len(hollow.Shape.Shells), 2)
        HaptiCAD.make_surface(self.doc, [(hollow, "Face1")])
        sheet = self.doc.addObject("Part::Plane", "Panel")
        sheet.Length, sheet.Width = 30, 30
        sheet.Placement.Base = App.Vector(60, 0, 120)
        self.doc.recompute()
        HaptiCAD.make_surface(self.doc, [(sheet, "Face1")])
        ds = build_document_scene(self.doc)
        self.assertNotIn("inside out", ds.repair)
        in_void = App.Vector(20, 20, 122)
        proxy, force = hold_device_at(ds, in_void, ticks=1)
        self.assertAlmostEqual(proxy.distanceToPoint(in_void), 0.0, delta=1e-9)
        self.assertAlmostEqual(force.Length, 0.0, delta=1e-9)
        in_wall = App.Vector(20, 20, 137)
        proxy, force = hold_device_at(ds, in_wall)
        self.assertFalse(hollow.Shape.isInside(proxy, 1e-9, False), f"proxy {proxy} in the part")
        self.assertPushedOutTowardTheProxy(proxy, in_wall, force)


if __name__ == "__main__":
    unittest.main()
