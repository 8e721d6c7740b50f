# SPDX-License-Identifier: GPL-3.0-or-later
"""Face references survive model edits (or say they broke): Box minus Cylinder, a box
made taller, a PartDesign Body, an App::Part; never a silent re-bind. Run by freecadcmd."""
import json
import math
import os
import tempfile
import unittest

import FreeCAD as App

import HaptiCAD
from hapticad import face_references
from hapticad.document_scene import build_document_scene


def faces_where(shape, kind, predicate):
    """Names of the faces of `shape` of surface type `kind` whose centre passes `predicate`."""
    return [f"Face{i + 1}" for i, f in enumerate(shape.Faces)
            if type(f.Surface).__name__ == kind and predicate(f.CenterOfMass)]


class BoxMinusCylinderTest(unittest.TestCase):
    """The issue's example: the cylinder starts clear of the box, then cuts a corner."""

    def setUp(self):
        self.doc = App.newDocument("BoxMinusCylinder")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.cyl = self.doc.addObject("Part::Cylinder", "Cylinder")
        self.cyl.Radius, self.cyl.Height = 5, 30
        self.cyl.Placement.Base = App.Vector(-20, -20, -5)
        self.cut = self.doc.addObject("Part::Cut", "Cut")
        self.cut.Base, self.cut.Tool = self.box, self.cyl
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def top(self):
        (name,) = faces_where(self.cut.Shape, "Plane", lambda c: abs(c.z - 20) < 1e-6)
        return name

    def test_the_tag_stays_on_the_top_face_when_freecad_renumbers_it(self):
        old_top = self.top()
        surface = HaptiCAD.make_surface(self.doc, [(self.cut, old_top)], material="Steel")
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface), [("Cut", old_top, "ok")])

        self.cyl.Placement.Base = App.Vector(40, 30, -5)  # now it cuts the corner
        self.doc.recompute()
        new_top = self.top()
        # the trap is real: FreeCAD renumbered the top face and the old name is a side face
        self.assertNotEqual(new_top, old_top)
        old_face = self.cut.Shape.getElement(old_top)
        self.assertLess(abs(old_face.normalAt(*old_face.Surface.parameter(old_face.CenterOfMass)).z), 1e-9)

        self.assertEqual(HaptiCAD.reference_status(surface), [("Cut", new_top, "rematched")])
        self.assertEqual(HaptiCAD.reference_pairs(surface), [(self.cut, new_top)])
        self.assertNotIn("Touched", surface.State)
        self.assertEqual(surface_object_problems(surface), [])
        # the scene carries Steel on the top face, and nothing on the side face
        scene = build_document_scene(self.doc)
        self.assertEqual(scene.face_material, {f"Cut.{new_top}": "Steel"})

    def test_two_surfaces_renumbered_in_one_edit_report_no_clash(self):
        front = faces_where(self.cut.Shape, "Plane", lambda c: abs(c.y) < 1e-6)[0]
        top = HaptiCAD.make_surface(self.doc, [(self.cut, self.top())], material="Steel")
        side = HaptiCAD.make_surface(self.doc, [(self.cut, front)], material="ABS")
        self.doc.recompute()
        errors = []
        original = App.Console.PrintError
        App.Console.PrintError = errors.append
        try:
            self.cyl.Placement.Base = App.Vector(40, 30, -5)  # both faces renumbered
            self.doc.recompute()
            # the first surface checked itself against the second before the second had
            # followed its face: "also tagged by", a clash that was not there
            self.assertEqual(errors, [])
            self.assertEqual([s for _, _, s in HaptiCAD.reference_status(top) + HaptiCAD.reference_status(side)],
                             ["rematched", "rematched"])
            # a real clash, made by a script, is still reported by the recompute
            side.References = [(self.cut, (HaptiCAD.reference_pairs(side)[0][1], self.top()))]
            self.doc.recompute()
            self.assertTrue(any("also tagged by" in e for e in errors), errors)
        finally:
            App.Console.PrintError = original

    def test_moving_the_cylinder_back_reports_ok_at_the_old_name(self):
        old_top = self.top()
        surface = HaptiCAD.make_surface(self.doc, [(self.cut, old_top)])
        self.doc.recompute()
        self.cyl.Placement.Base = App.Vector(40, 30, -5)
        self.doc.recompute()
        self.cyl.Placement.Base = App.Vector(-20, -20, -5)
        self.doc.recompute()
        self.assertEqual(self.top(), old_top)
        self.assertEqual(HaptiCAD.reference_status(surface), [("Cut", old_top, "rematched")])
        self.doc.recompute()  # nothing changed: the surface is not even recomputed
        surface.touch()
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface), [("Cut", old_top, "ok")])

    def test_a_face_split_in_two_is_broken_not_rebound(self):
        # a slot right through the top face splits it into two coplanar faces
        top = self.top()
        surface = HaptiCAD.make_surface(self.doc, [(self.cut, top), (self.cut, "Face1")])
        self.doc.recompute()
        slot = self.doc.addObject("Part::Box", "Slot")
        slot.Length, slot.Width, slot.Height = 4, 50, 10
        slot.Placement.Base = App.Vector(18, -10, 15)
        self.cyl.Placement.Base = App.Vector(-20, -20, -5)
        tool = self.doc.addObject("Part::MultiFuse", "Tools")
        tool.Shapes = [self.cyl, slot]
        self.cut.Tool = tool
        self.doc.recompute()
        self.assertEqual(len(faces_where(self.cut.Shape, "Plane", lambda c: abs(c.z - 20) < 1e-6)), 2)
        status = dict(((o, f), s) for o, f, s in HaptiCAD.reference_status(surface))
        self.assertIn(("Cut", top), status)
        self.assertEqual(status[("Cut", top)], "broken")
        # the untouched end face is still fine, and the broken one stays out of the scene
        self.assertEqual(list(status.values()).count("broken"), 1)
        problems = surface_object_problems(surface)
        self.assertTrue(any("broken face reference" in p and f"Cut.{top}" in p for p in problems), problems)
        scene = build_document_scene(self.doc)
        self.assertEqual(len(scene.face_surface), 1)
        self.assertNotIn(f"Cut.{top}", scene.face_surface)
        # undoing the edit (removing the slot) brings it back
        self.cut.Tool = self.cyl
        self.doc.recompute()
        self.assertEqual([s for _, _, s in HaptiCAD.reference_status(surface)].count("broken"), 0)

    def test_a_copy_made_with_its_part_follows_the_copys_top_face(self):
        # Duplicate selection, and a paste into a document that has a "Cut" already: the
        # copy tags Cut001 while its signatures named Cut. It moved to a side face, "ok".
        surface = HaptiCAD.make_surface(self.doc, [(self.cut, self.top())], material="Steel")
        self.doc.recompute()
        other = App.newDocument("PasteTarget")
        try:
            other.addObject("Part::Box", "Cut")  # the name the copy would have had
            other.recompute()
            for doc in (self.doc, other):
                with self.subTest(doc=doc.Name):
                    copy = doc.copyObject(surface, True)
                    doc.recompute()
                    (part, face), = HaptiCAD.reference_pairs(copy)
                    self.assertNotEqual(part.Name, "Cut")
                    self.assertEqual(HaptiCAD.reference_status(copy), [(part.Name, face, "ok")])
                    tool = part.Tool
                    tool.Placement.Base = App.Vector(40, 30, -5)  # the copy's cylinder cuts its corner
                    doc.recompute()
                    (part, face), = HaptiCAD.reference_pairs(copy)
                    tagged = part.Shape.getElement(face)
                    normal = tagged.normalAt(*tagged.Surface.parameter(tagged.CenterOfMass))
                    self.assertAlmostEqual(normal.z, 1.0, places=9)  # the top, not a side face
                    self.assertEqual(HaptiCAD.reference_status(copy), [(part.Name, face, "rematched")])
        finally:
            App.closeDocument(other.Name)

    def test_status_survives_save_and_reopen(self):
        top = self.top()
        surface = HaptiCAD.make_surface(self.doc, [(self.cut, top)])
        self.doc.recompute()
        self.cyl.Placement.Base = App.Vector(40, 30, -5)
        self.doc.recompute()
        before = HaptiCAD.reference_status(surface)
        name = surface.Name
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cut.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
            surface = self.doc.getObject(name)
            self.assertEqual(HaptiCAD.reference_status(surface), before)
            self.assertNotIn("Touched", surface.State)


def surface_object_problems(surface):
    from hapticad.surface_object import validate

    return validate(surface)


class SimpleEditsTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("SimpleEdits")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_a_face_renumbered_onto_a_broken_references_name_keeps_its_tag(self):
        # the notch goes and FreeCAD calls the top face by the notch face's name: the two
        # references were merged into one, read as broken, and the top's tag was lost
        box, tool = self.box, self.doc.addObject("Part::Box", "Tool")
        box.Length, box.Width, box.Height = 20, 20, 10
        tool.Length = tool.Width = tool.Height = 5
        tool.Placement.Base = App.Vector(-1, -1, -1)
        cut = self.doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = box, tool
        self.doc.recompute()
        (top,) = faces_where(cut.Shape, "Plane", lambda c: abs(c.z - 10) < 1e-6)
        notch = "Face6"  # a face of the notch, by the name a plain box gives its top
        self.assertNotEqual(top, notch)
        self.assertLessEqual(max(cut.Shape.getElement(notch).CenterOfMass[:2]), 4.0)  # in the notch
        surface = HaptiCAD.make_surface(self.doc, [(cut, top), (cut, notch)], material="Rubber")
        self.doc.recompute()
        tool.Placement.Base = App.Vector(-30, -30, -30)  # the notch is gone
        self.doc.recompute()
        (new_top,) = faces_where(cut.Shape, "Plane", lambda c: abs(c.z - 10) < 1e-6)
        self.assertEqual(new_top, notch)  # the trap: the top now has the notch face's name
        self.assertEqual(HaptiCAD.reference_status(surface),
                         [("Cut", new_top, "rematched"), ("Cut", f"{notch}~1", "broken")])
        self.assertEqual(build_document_scene(self.doc).face_material, {f"Cut.{new_top}": "Rubber"})
        self.assertEqual(surface_object_problems(surface),
                         [f"broken face reference(s) Cut.{notch}: the model changed and the face cannot be found "
                          "unambiguously; pick it again"])
        # through a save and later edits; and the notch back: both tags where they were
        tmp = tempfile.TemporaryDirectory()
        self.addCleanup(tmp.cleanup)
        path = os.path.join(tmp.name, "notch.FCStd")
        self.doc.saveAs(path)
        name = surface.Name
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        cut, tool, surface = (self.doc.getObject(n) for n in ("Cut", "Tool", name))
        self.doc.getObject("Box").Height = 11
        self.doc.recompute()
        self.doc.getObject("Box").Height = 10
        tool.Placement.Base = App.Vector(-1, -1, -1)
        self.doc.recompute()
        self.assertEqual([(f, s) for _, f, s in HaptiCAD.reference_status(surface)],
                         [(top, "rematched"), (notch, "rematched")])
        self.assertEqual(len(build_document_scene(self.doc).face_material), 2)

    def test_a_taller_box_keeps_its_top_face(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        self.box.Height = 25
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface), [("Box", "Face6", "ok")])
        # the signature follows the face: its centre is now at the new height
        (entry,) = HaptiCAD_state(surface)
        self.assertAlmostEqual(entry["signature"]["centre"][2], 25.0)

    def test_moving_the_part_changes_nothing(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        state = surface.ReferenceState
        self.box.Placement = App.Placement(App.Vector(100, 5, 3), App.Rotation(App.Vector(1, 0, 0), 90))
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface), [("Box", "Face6", "ok")])
        self.assertEqual(surface.ReferenceState, state)

    def test_a_moved_face_beside_one_facing_the_same_way_is_followed_unless_both_moved(self):
        # a step: two faces facing +z at different heights, the tagged one moves
        step = self.doc.addObject("Part::Box", "Step")
        step.Length, step.Width, step.Height = 5, 10, 15
        fuse = self.doc.addObject("Part::MultiFuse", "Fuse")
        fuse.Shapes = [self.box, step]
        fuse.Refine = True
        self.doc.recompute()
        (top,) = faces_where(fuse.Shape, "Plane", lambda c: abs(c.z - 15) < 1e-6)
        surface = HaptiCAD.make_surface(self.doc, [(fuse, top)])
        step.Height = 12  # +z faces at 10 and 12: the one at 10 is the box's, unchanged
        self.doc.recompute()
        (step_top,) = faces_where(fuse.Shape, "Plane", lambda c: abs(c.z - 12) < 1e-6)
        ((_, face, status),) = HaptiCAD.reference_status(surface)
        self.assertEqual(face, step_top)
        self.assertNotEqual(status, "broken")
        # both move in one edit: +z faces at 11 and 13, and nothing tells which is which
        self.box.Height, step.Height = 11, 13
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface), [("Fuse", step_top, "broken")])
        # the designer picks the face again (the panel's Add on it): signed afresh
        from hapticad.surface_object import resign_reference

        (step_top,) = faces_where(fuse.Shape, "Plane", lambda c: abs(c.z - 13) < 1e-6)
        resign_reference(surface, fuse, step_top)
        self.assertEqual(HaptiCAD.reference_status(surface), [("Fuse", step_top, "ok")])
        step.Height = 14
        self.doc.recompute()
        (step_top,) = faces_where(fuse.Shape, "Plane", lambda c: abs(c.z - 14) < 1e-6)
        self.assertEqual(HaptiCAD.reference_status(surface)[0][1:], (step_top, "ok"))

    def test_a_face_that_is_gone_is_broken(self):
        hole = self.doc.addObject("Part::Cylinder", "Hole")
        hole.Radius, hole.Height = 2, 20
        hole.Placement.Base = App.Vector(5, 5, -5)
        cut = self.doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = self.box, hole
        self.doc.recompute()
        (bore,) = faces_where(cut.Shape, "Cylinder", lambda c: True)
        surface = HaptiCAD.make_surface(self.doc, [(cut, bore), (cut, "Face1")])
        self.doc.recompute()
        hole.Radius = 3  # a wider hole is still the same hole
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface)[0][2], "ok")
        # a square hole instead: no cylinder any more
        square = self.doc.addObject("Part::Box", "Square")
        square.Length, square.Width, square.Height = 2, 2, 20
        square.Placement.Base = App.Vector(4, 4, -5)
        cut.Tool = square
        self.doc.recompute()
        self.assertEqual([s for _, _, s in HaptiCAD.reference_status(surface)], ["broken", "ok"])
        self.assertEqual(len(build_document_scene(self.doc).face_surface), 1)


class TwoHolesTest(unittest.TestCase):
    """A plate with two holes bored the same way: the tag on one never lands on the other."""

    def setUp(self):
        self.doc = App.newDocument("TwoHoles")
        plate = self.doc.addObject("Part::Box", "Plate")
        plate.Length, plate.Width, plate.Height = 60, 30, 5
        self.hole_a = self.doc.addObject("Part::Cylinder", "HoleA")
        self.hole_a.Radius, self.hole_a.Height = 2, 20
        self.hole_a.Placement.Base = App.Vector(15, 15, -5)
        self.hole_b = hole_b = self.doc.addObject("Part::Cylinder", "HoleB")
        hole_b.Radius, hole_b.Height = 4, 20
        hole_b.Placement.Base = App.Vector(45, 15, -5)
        cut_a = self.doc.addObject("Part::Cut", "CutA")
        cut_a.Base, cut_a.Tool = plate, self.hole_a
        self.cut = self.doc.addObject("Part::Cut", "CutB")
        self.cut.Base, self.cut.Tool = cut_a, hole_b
        self.doc.recompute()
        self.surface = HaptiCAD.make_surface(self.doc, [(self.cut, self.bore(2))], material="Rubber")
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def bore(self, radius):
        names = [f"Face{i + 1}" for i, f in enumerate(self.cut.Shape.Faces)
                 if type(f.Surface).__name__ == "Cylinder" and abs(f.Surface.Radius - radius) < 1e-9]
        return names[0] if names else None

    def test_removing_the_tagged_hole_breaks_the_tag_instead_of_moving_it_to_the_other(self):
        self.hole_a.Placement.Base = App.Vector(200, 15, -5)  # off the plate: hole A is gone
        self.doc.recompute()
        self.assertIsNone(self.bore(2))
        ((_, face, status),) = HaptiCAD.reference_status(self.surface)
        self.assertEqual(status, "broken", f"the tag went to {face} (hole B is {self.bore(4)})")
        with self.assertRaisesRegex(ValueError, "every tagged face reference is broken"):
            build_document_scene(self.doc)

    def test_a_broken_tag_stays_broken_through_later_edits_and_comes_back_on_undo(self):
        self.hole_a.Placement.Base = App.Vector(200, 15, -5)
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(self.surface)[0][2], "broken")
        # any later edit: the old name now names hole B, which it took as "ok"
        self.doc.getObject("Plate").Length = 70
        self.doc.recompute()
        self.cut.touch()
        self.doc.recompute()
        ((_, face, status),) = HaptiCAD.reference_status(self.surface)
        self.assertEqual(status, "broken", f"the tag went to {face} (hole B is {self.bore(4)})")
        # hole A back where it was: the very face the tag was on
        self.doc.getObject("Plate").Length = 60
        self.hole_a.Placement.Base = App.Vector(15, 15, -5)
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(self.surface), [("CutB", self.bore(2), "ok")])

    def test_a_face_round_a_widened_blind_pocket_keeps_its_tag(self):
        # the top face loses area to a wider pocket, whose floor faces the same way and
        # changed too: only faces in the top's own plane can be confused with it
        pocket = self.doc.addObject("Part::Box", "Pocket")
        pocket.Length, pocket.Width, pocket.Height = 10, 10, 10
        pocket.Placement.Base = App.Vector(25, 10, 3)
        cut = self.doc.addObject("Part::Cut", "Pocketed")
        cut.Base, cut.Tool = self.cut, pocket
        self.doc.recompute()
        (top,) = faces_where(cut.Shape, "Plane", lambda c: abs(c.z - 5) < 1e-6)
        surface = HaptiCAD.make_surface(self.doc, [(cut, top)])
        self.doc.recompute()
        pocket.Length = 14
        self.doc.recompute()
        (top,) = faces_where(cut.Shape, "Plane", lambda c: abs(c.z - 5) < 1e-6)
        ((_, face, status),) = HaptiCAD.reference_status(surface)
        self.assertNotEqual(status, "broken")
        self.assertEqual(face, top)

    def test_the_tagged_hole_removed_as_the_other_changes_breaks_the_tag(self):
        # one edit: hole A gone, hole B widened. The tag landed on B as "ok" while the
        # rivals had to be unchanged only to be no candidates
        self.hole_a.Placement.Base = App.Vector(200, 15, -5)
        self.hole_b.Radius = 5
        self.doc.recompute()
        ((_, face, status),) = HaptiCAD.reference_status(self.surface)
        self.assertEqual(status, "broken", f"the tag went to {face} (hole B is {self.bore(5)})")

    def test_holes_that_moved_past_each_other_break_the_tag(self):
        # one edit: hole A (r 2, x 15) made r 3 and moved to x 43, hole B (r 4, x 45) moved
        # to x 17. Nearest the tagged hole's place is now hole B, 2 mm off against 30 mm
        # between them: by place alone the tag would go to B; its size, B's, says it is B
        self.hole_a.Radius = 3
        self.hole_a.Placement.Base = App.Vector(43, 15, -5)
        self.hole_b.Placement.Base = App.Vector(17, 15, -5)
        self.doc.recompute()
        ((_, face, status),) = HaptiCAD.reference_status(self.surface)
        self.assertEqual(status, "broken", f"the tag went to {face} (hole B is {self.bore(4)})")

    def test_the_tagged_hole_made_wider_keeps_its_tag_beside_the_other(self):
        # without the rivals both bores faced the same way and the tag broke as ambiguous
        self.hole_a.Radius = 3
        self.doc.recompute()
        ((_, face, status),) = HaptiCAD.reference_status(self.surface)
        self.assertNotEqual(status, "broken")
        self.assertEqual(face, self.bore(3))

    def test_a_document_written_without_the_parts_faces_gets_them_when_it_opens(self):
        faces = json.loads(self.surface.ReferenceShapes)["CutB"]
        self.assertEqual(len(faces), len(self.cut.Shape.Faces))
        self.assertEqual(sorted(f["surface"]["radius"] for f in faces if f["type"] == "Cylinder"), [2.0, 4.0])
        self.surface.ReferenceShapes = ""  # as schema 3 wrote it
        name = self.surface.Name
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "holes.FCStd")
            self.doc.saveAs(path)
            App.closeDocument(self.doc.Name)
            self.doc = App.openDocument(path)
        self.surface = self.doc.getObject(name)
        self.cut = self.doc.getObject("CutB")
        self.hole_a = self.doc.getObject("HoleA")
        self.assertEqual(json.loads(self.surface.ReferenceShapes)["CutB"], faces)
        self.assertNotIn("Touched", self.surface.State)
        self.hole_a.Placement.Base = App.Vector(200, 15, -5)
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(self.surface)[0][2], "broken")


def HaptiCAD_state(surface):
    from hapticad.surface_object import read_reference_state

    return read_reference_state(surface)


class PartDesignBodyTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("BodyTest")
        self.body = self.doc.addObject("PartDesign::Body", "Body")
        sketch = self.rectangle("Sketch", (self.doc.getObject("XY_Plane"), [""]), 0, 0, 40, 30)
        self.pad = self.body.newObject("PartDesign::Pad", "Pad")
        self.pad.Profile = sketch
        self.pad.Length = 20
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def rectangle(self, name, support, x0, y0, x1, y1):
        """A closed rectangle sketch in the Body, mapped flat on ``support``."""
        import Part
        import Sketcher

        sketch = self.body.newObject("Sketcher::SketchObject", name)
        sketch.Support = support
        sketch.MapMode = "FlatFace"
        corners = [App.Vector(x0, y0, 0), App.Vector(x1, y0, 0), App.Vector(x1, y1, 0), App.Vector(x0, y1, 0)]
        for i in range(4):
            sketch.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
        for i in range(4):
            sketch.addConstraint(Sketcher.Constraint("Coincident", i, 2, (i + 1) % 4, 1))
        return sketch

    def top(self, obj):
        (name,) = faces_where(obj.Shape, "Plane", lambda c: abs(c.z - 20) < 1e-6)
        return name

    def test_a_script_tagging_the_pads_face_tags_the_bodys_once(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.pad, self.top(self.pad))])
        self.assertEqual(HaptiCAD.reference_pairs(surface), [(self.body, self.top(self.body))])
        with self.assertRaisesRegex(ValueError, "already tagged"):  # it was accepted as the Pad's
            HaptiCAD.make_surface(self.doc, [(self.pad, self.top(self.pad))])

    def test_a_face_picked_on_the_pad_belongs_to_the_body_and_survives_a_pocket(self):
        owner, face = face_references.owner_face(self.pad, self.top(self.pad))
        self.assertEqual((owner.Name, face), ("Body", self.top(self.body)))
        surface = HaptiCAD.make_surface(self.doc, [(owner, face)], material="ABS")
        top_before = self.top(self.body)

        # a hole through the top, added as a Pocket from a sketch on the XY plane
        import Part as P

        sketch = self.body.newObject("Sketcher::SketchObject", "HoleSketch")
        sketch.Support = (self.doc.getObject("XY_Plane"), [""])
        sketch.MapMode = "FlatFace"
        sketch.addGeometry(P.Circle(App.Vector(8, 8, 0), App.Vector(0, 0, 1), 3))
        pocket = self.body.newObject("PartDesign::Pocket", "Pocket")
        pocket.Profile = sketch
        pocket.Type = "ThroughAll"
        pocket.Reversed = True
        self.doc.recompute()
        self.assertTrue(pocket.isValid(), pocket.State)
        self.assertEqual(self.body.Tip, pocket)
        top_after = self.top(self.body)
        status = HaptiCAD.reference_status(surface)
        self.assertEqual(status, [("Body", top_after, "ok" if top_after == top_before else "rematched")])
        scene = build_document_scene(self.doc)
        self.assertEqual(scene.face_material, {f"Body.{top_after}": "ABS"})
        # the tagged face has the hole: area 40 x 30 minus the circle
        import math

        area = self.body.Shape.getElement(top_after).Area
        self.assertAlmostEqual(area, 1200 - math.pi * 9, places=3)

    def test_a_longer_pad_keeps_the_tag_on_the_body_top(self):
        surface = HaptiCAD.make_surface(self.doc, [(self.body, self.top(self.body))])
        self.pad.Length = 35
        self.doc.recompute()
        (name, face, status), = HaptiCAD.reference_status(surface)
        self.assertEqual(status, "ok")
        self.assertAlmostEqual(self.body.Shape.getElement(face).CenterOfMass.z, 35.0)


    def test_a_longer_pad_keeps_the_tag_beside_a_pocket_sketched_on_its_top(self):
        # the most common PartDesign edit: the Pocket's sketch sits on the Pad's top face,
        # so the Pocket's floor (facing +z too) rises with the top; the tag broke
        sketch = self.rectangle("PocketSketch", (self.pad, [self.top(self.pad)]), 5, 5, 15, 15)
        pocket = self.body.newObject("PartDesign::Pocket", "Pocket")
        pocket.Profile = sketch
        pocket.Length = 3
        self.doc.recompute()
        self.assertTrue(pocket.isValid(), pocket.State)
        surface = HaptiCAD.make_surface(self.doc, [(self.body, self.top(self.body))])
        for length in (24, 20, 31):
            self.pad.Length = length
            self.doc.recompute()
            (_, face, status), = HaptiCAD.reference_status(surface)
            self.assertNotEqual(status, "broken", length)
            top = self.body.Shape.getElement(face)
            self.assertAlmostEqual(top.CenterOfMass.z, length)
            self.assertAlmostEqual(top.Area, 40 * 30 - 10 * 10)  # the top, not the pocket's floor
        # a deeper pocket: its floor moves, the top does not (found at the first level)
        pocket.Length = 5
        self.doc.recompute()
        self.assertEqual(HaptiCAD.reference_status(surface)[0][2], "ok")


class FilletedBodyTest(unittest.TestCase):
    """A Body: a 40 x 30 mm Pad 10 mm high, a Fillet on its four vertical edges, a Pocket
    in the top; faces tagged on each. The four fillet faces are alike but for place."""

    def setUp(self):
        import Part

        self.doc = App.newDocument("FilletedBody")
        self.body = self.doc.addObject("PartDesign::Body", "Body")
        sketch = self.rectangle("Sketch", (self.doc.getObject("XY_Plane"), [""]), 0, 0, 40, 30)
        pad = self.body.newObject("PartDesign::Pad", "Pad")
        pad.Profile = sketch
        pad.Length = 10
        self.doc.recompute()
        vertical = [f"Edge{i + 1}" for i, e in enumerate(pad.Shape.Edges)
                    if isinstance(e.Curve, Part.Line) and abs(e.Vertexes[0].Point.z - e.Vertexes[1].Point.z) > 1]
        self.assertEqual(len(vertical), 4)
        self.fillet = self.body.newObject("PartDesign::Fillet", "Fillet")
        self.fillet.Base = (pad, vertical)
        self.fillet.Radius = 3
        pocket_sketch = self.rectangle("PocketSketch", (self.doc.getObject("XY_Plane"), [""]), 15, 10, 25, 18)
        pocket_sketch.AttachmentOffset = App.Placement(App.Vector(0, 0, 10), App.Rotation())
        self.pocket = self.body.newObject("PartDesign::Pocket", "Pocket")
        self.pocket.Profile = pocket_sketch
        self.pocket.Length = 4
        self.doc.recompute()
        self.assertTrue(all(o.isValid() for o in self.doc.Objects), [o.Name for o in self.doc.Objects])
        self.assertEqual(len(faces_where(self.body.Shape, "Cylinder", lambda c: True)), 4)

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    rectangle = PartDesignBodyTest.rectangle

    def corner_fillet(self):
        """The fillet face at the (40, 30) corner."""
        (name,) = faces_where(self.body.Shape, "Cylinder", lambda c: c.x > 30 and c.y > 20)
        return name

    def tagged(self):
        """Names of the top, the (40, 30) fillet, the pocket floor and the y = 0 side."""
        shape = self.body.Shape
        (top,) = faces_where(shape, "Plane", lambda c: abs(c.z - 10) < 1e-6)
        (floor,) = faces_where(shape, "Plane", lambda c: abs(c.z - 10 + self.pocket.Length.Value) < 1e-6)
        (side,) = faces_where(shape, "Plane", lambda c: abs(c.y) < 1e-6)
        return [top, self.corner_fillet(), floor, side]

    def test_a_fillet_made_larger_keeps_its_tag_at_its_corner(self):
        # the four fillets all changed alike, so area told the tagged one from none of
        # the others and the tag broke; it moved 1 mm, the others are 28 mm and more away
        surface = HaptiCAD.make_surface(self.doc, [(self.body, f) for f in self.tagged()], material="ABS")
        self.doc.recompute()
        for radius in (5, 2, 3):
            self.fillet.Radius = radius
            self.doc.recompute()
            status = HaptiCAD.reference_status(surface)
            self.assertEqual([f for _, f, _ in status], self.tagged(), radius)
            self.assertNotIn("broken", [s for _, _, s in status], radius)
            fillet = self.body.Shape.getElement(status[1][1])
            self.assertAlmostEqual(fillet.Surface.Radius, radius)
            self.assertAlmostEqual(fillet.Surface.Center.x, 40 - radius)
            self.assertAlmostEqual(fillet.Surface.Center.y, 30 - radius)
        self.assertEqual(surface_object_problems(surface), [])
        self.assertEqual(len(build_document_scene(self.doc).face_material), 4)


class PatternedFeaturesTest(unittest.TestCase):
    """Faces of a pattern, alike but for place: a remote's keys (a PartDesign Body: a
    100 x 30 x 5 mm plate, a 10 x 10 mm key Pad 2 mm high on it, a LinearPattern of 4
    keys 25 mm apart) and a Draft ortho array of three boxes 20 mm apart."""

    def setUp(self):
        self.doc = App.newDocument("Patterned")

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def keys(self):
        self.body = self.doc.addObject("PartDesign::Body", "Body")
        plate = self.body.newObject("PartDesign::Pad", "Plate")
        plate.Profile = self.rectangle("PlateSketch", (self.doc.getObject("XY_Plane"), [""]), 0, 0, 100, 30)
        plate.Length = 5
        self.key = self.body.newObject("PartDesign::Pad", "Key")
        sketch = self.rectangle("KeySketch", (self.doc.getObject("XY_Plane"), [""]), 5, 10, 15, 20)
        sketch.AttachmentOffset = App.Placement(App.Vector(0, 0, 5), App.Rotation())
        self.key.Profile = sketch
        self.key.Length = 2
        self.doc.recompute()
        self.pattern = self.body.newObject("PartDesign::LinearPattern", "Keys")
        self.pattern.Originals = [self.key]
        self.pattern.Direction = (self.doc.getObject("X_Axis"), [""])
        self.pattern.Length, self.pattern.Occurrences = 75, 4
        self.body.Tip = self.pattern
        self.doc.recompute()
        self.assertTrue(all(o.isValid() for o in self.doc.Objects), [o.Name for o in self.doc.Objects])

    rectangle = PartDesignBodyTest.rectangle

    def tops(self, shape, z):
        """{x of the centre: name} of the faces facing +z at height z."""
        return {round(shape.getElement(n).CenterOfMass.x, 6): n
                for n in faces_where(shape, "Plane", lambda c: abs(c.z - z) < 1e-6)
                if shape.getElement(n).normalAt(0, 0).z > 0.5}

    def test_the_keys_of_a_pattern_made_taller_keep_each_its_tag(self):
        # the four tops left their plane together, so the level that looks for the tagged
        # face in its own plane found nothing, and said broken instead of looking further;
        # the fourth key then broke too, its nearest rival being the plate's top (9.8 mm
        # off), which stayed as it was and so can be no other key's top
        self.keys()
        tops = self.tops(self.body.Shape, 7)
        self.assertEqual(sorted(tops), [10, 35, 60, 85])
        surface = HaptiCAD.make_surface(self.doc, [(self.body, tops[x]) for x in sorted(tops)], material="Rubber")
        self.doc.recompute()
        for length in (3, 2, 3.5):
            self.key.Length = length
            self.doc.recompute()
            now = self.tops(self.body.Shape, 5 + length)
            status = HaptiCAD.reference_status(surface)
            # each key's tag on its own key's top: never two on one, nor one on the plate
            self.assertEqual([(f, s != "broken") for _, f, s in status], [(now[x], True) for x in sorted(now)], length)
            self.assertEqual(surface_object_problems(surface), [])
            self.assertEqual(sorted(build_document_scene(self.doc).face_material),
                             sorted(f"Body.{now[x]}" for x in now))

    def test_a_key_added_to_the_pattern_breaks_the_tags_of_the_keys_that_moved(self):
        # five keys over the same 75 mm: the end keys stay where they were, the two
        # between move and a key comes, so nothing says which key a moved tag is on
        self.keys()
        tops = self.tops(self.body.Shape, 7)
        surface = HaptiCAD.make_surface(self.doc, [(self.body, tops[x]) for x in sorted(tops)])
        self.doc.recompute()
        self.pattern.Occurrences = 5
        self.doc.recompute()
        now = self.tops(self.body.Shape, 7)
        self.assertEqual(sorted(now), [10, 28.75, 47.5, 66.25, 85])
        status = HaptiCAD.reference_status(surface)
        self.assertEqual([s == "broken" for _, _, s in status], [False, True, True, False])
        self.assertEqual([status[0][1], status[3][1]], [now[10], now[85]])

    def test_the_boxes_of_a_draft_array_made_taller_keep_their_tags(self):
        import Draft

        base = self.doc.addObject("Part::Box", "Base")
        self.doc.recompute()
        array = Draft.make_ortho_array(base, App.Vector(20, 0, 0), App.Vector(0, 20, 0), App.Vector(0, 0, 20),
                                       3, 1, 1, use_link=False)
        self.doc.recompute()
        tops = self.tops(array.Shape, 10)
        self.assertEqual(sorted(tops), [5, 25, 45])
        middle = HaptiCAD.make_surface(self.doc, [(array, tops[25])], material="Steel")
        ends = HaptiCAD.make_surface(self.doc, [(array, tops[5]), (array, tops[45])], material="ABS")
        self.doc.recompute()
        base.Height = 11
        self.doc.recompute()
        now = self.tops(array.Shape, 11)
        self.assertEqual([(f, s != "broken") for _, f, s in HaptiCAD.reference_status(middle)], [(now[25], True)])
        self.assertEqual([(f, s != "broken") for _, f, s in HaptiCAD.reference_status(ends)],
                         [(now[5], True), (now[45], True)])


class AppPartTest(unittest.TestCase):
    def test_a_box_in_a_moved_app_part_keeps_its_tag_and_scene_position(self):
        doc = App.newDocument("AppPart")
        try:
            part = doc.addObject("App::Part", "Part")
            box = doc.addObject("Part::Box", "Box")
            part.addObject(box)
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")])
            part.Placement.Base = App.Vector(0, 0, 100)
            box.Length = 25
            doc.recompute()
            self.assertEqual(HaptiCAD.reference_status(surface), [("Box", "Face6", "ok")])
            scene = build_document_scene(doc)
            top = scene.face_shape("Box.Face6")
            self.assertAlmostEqual(top.CenterOfMass.z, 110.0)  # global: Part placement applied
            self.assertAlmostEqual(top.CenterOfMass.x, 12.5)
        finally:
            App.closeDocument(doc.Name)


class MatchFaceUnitTest(unittest.TestCase):
    """match_face on hand-made signature lists: the decision table."""

    def sig(self, z, area=100.0, normal=(0, 0, 1), centre=None):
        return {"type": "Plane", "surface": {"normal": list(normal), "offset": float(z)},
                "orientation": {"normal": list(normal)}, "area": area, "centre": list(centre or (5.0, 5.0, z))}

    def test_decision_table(self):
        m = face_references.match_face
        a, b = self.sig(10), self.sig(0, normal=(0, 0, -1))
        self.assertEqual(m(a, "Face1", [a, b], 10), ("Face1", "ok"))
        self.assertEqual(m(a, "Face2", [b, a], 10), ("Face2", "ok"))
        self.assertEqual(m(a, "Face1", [b, a], 10), ("Face2", "rematched"))
        trimmed = self.sig(10, area=80.0, centre=(4.0, 4.0, 10))
        self.assertEqual(m(a, "Face1", [b, trimmed], 10), ("Face2", "rematched"))
        moved = self.sig(12)
        self.assertEqual(m(a, "Face2", [b, moved], 10), ("Face2", "ok"))
        split = [self.sig(10, 50, centre=(2, 5, 10)), self.sig(10, 50, centre=(8, 5, 10)), b]
        self.assertEqual(m(a, "Face1", split, 10), (None, "broken"))
        self.assertEqual(m(a, "Face1", [b], 10), (None, "broken"))
        two_moved = [self.sig(12), self.sig(14, centre=(1, 1, 14)), b]
        self.assertEqual(m(a, "Face1", two_moved, 10), (None, "broken"))
        # with the faces as they were (a, b and a rival facing the same way as a):
        rival = self.sig(14, centre=(1, 1, 14))

        def before(now, old=(a, b, rival)):  # the tagged face's name is its index in old
            return face_references.Previous(list(old), now, 10)

        self.assertEqual(before([]).rivals(0, a, face_references.same_orientation), [2])
        self.assertEqual(before([]).rivals(0, a, face_references.same_surface), [])
        # a rival that is still there is no candidate: a's face gone, the other remains
        self.assertEqual(m(a, "Face1", [rival, b], 10), ("Face1", "ok"))  # without: wrong
        now = [rival, b]
        self.assertEqual(m(a, "Face1", now, 10, before(now)), (None, "broken"))
        # the face that moved is found beside the unchanged rival
        now = [rival, moved, b]
        self.assertEqual(m(a, "Face2", now, 10, before(now, (rival, a, b))), ("Face2", "ok"))
        self.assertEqual(m(a, "Face1", [moved, rival, b], 10, before([moved, rival, b])), ("Face1", "ok"))
        now = [b, rival, moved]
        self.assertEqual(m(a, "Face1", now, 10, before(now)), ("Face3", "rematched"))
        # a rival that changed too: nothing tells them apart any more
        now = [self.sig(15, centre=(1, 1, 15)), b]
        self.assertEqual(m(a, "Face1", now, 10, before(now)), (None, "broken"))
        now = [moved, self.sig(15, centre=(1, 1, 15)), b]
        self.assertEqual(m(a, "Face1", now, 10, before(now)), (None, "broken"))
        # ... unless their areas tell them apart: both lifted, as a longer Pad lifts its
        # top and the floor of a Pocket sketched on it
        floor = self.sig(7, area=30.0, centre=(1, 1, 7))
        lifted = [self.sig(12), b, self.sig(9, area=30.0, centre=(1, 1, 9))]
        self.assertEqual(m(a, "Face1", lifted, 10, before(lifted, (a, b, floor))), ("Face1", "ok"))
        lifted = [self.sig(9, area=30.0, centre=(1, 1, 9)), b, self.sig(12)]
        self.assertEqual(m(a, "Face1", lifted, 10, before(lifted, (a, b, floor))), ("Face3", "rematched"))
        # not when the tagged face's area changed too, nor when a face came or went
        grown = [self.sig(12, area=120.0), b, self.sig(9, area=30.0, centre=(1, 1, 9))]
        self.assertEqual(m(a, "Face1", grown, 10, before(grown, (a, b, floor))), (None, "broken"))
        extra = [*lifted, self.sig(20, area=5.0, centre=(3, 3, 20))]
        self.assertEqual(m(a, "Face1", extra, 10, before(extra, (a, b, floor))), (None, "broken"))
        gone = [self.sig(12), b]
        self.assertEqual(m(a, "Face1", gone, 10, before(gone, (a, b, floor))), (None, "broken"))
        # a unchanged is found at the first level, whatever its rivals did
        now = [a, b]
        self.assertEqual(m(a, "Face1", now, 10, before(now)), ("Face1", "ok"))

    def fillet(self, x, y, radius, sx, sy):
        """The signature of a round on the vertical edge at (x, y) of a 10 mm high block;
        (sx, sy) points out of the block at that corner."""
        k = 1 - 2 / math.pi  # the quarter round's centre of mass is k r (1, 1) in from the corner
        return {"type": "Cylinder",
                "surface": {"axis": [0.0, 0.0, 1.0], "foot": [x - sx * radius, y - sy * radius, 0.0],
                            "radius": float(radius)},
                "orientation": {"sense": 1, "axis": [0.0, 0.0, 1.0]},
                "area": math.pi / 2 * radius * 10, "centre": [x - sx * k * radius, y - sy * k * radius, 5.0]}

    def rounds(self, radius, length=40.0, width=30.0):
        return [self.fillet(x, y, radius, sx, sy)
                for x, sx in ((0.0, -1), (length, 1)) for y, sy in ((0.0, -1), (width, 1))]

    def test_a_face_that_clearly_stayed_near_is_followed_among_rivals_alike(self):
        m = face_references.match_face
        old = self.rounds(3)
        tagged = old[3]  # the round at (40, 30)

        def match(now, old=old, name="Face4"):
            return m(tagged, name, now, 50, face_references.Previous(list(old), now, 50))

        # all four rounds made 5 mm: the tagged one moved 1 mm, its rivals are 28 mm off
        now = self.rounds(5)
        self.assertEqual(match(now), ("Face4", "ok"))
        self.assertEqual(match(now[::-1]), ("Face1", "rematched"))
        # ... not without the faces as they were (all four could be it), nor when a face
        # came or went, nor on a block so small that 1 mm is a fifth of the way to a rival
        self.assertEqual(m(tagged, "Face4", now, 50), (None, "broken"))
        self.assertEqual(match([*now, self.fillet(20, 30, 5, 0, 1)]), (None, "broken"))
        self.assertEqual(match(now[:3]), (None, "broken"))
        small = self.rounds(1, 6, 6)
        self.assertEqual(match(self.rounds(3, 6, 6), small), (None, "broken"))
        # a rival now nearer the tagged face's place than half the way between them (the
        # round at (40, 0) moved up to y 20): either might be the tagged one
        near = [*now[:2], self.fillet(40, 20, 5, 1, -1), now[3]]
        self.assertEqual(match(near), (None, "broken"))
        # the one face near has a rival's size: a 4 mm round that moved to the tagged 3 mm
        # round's corner as that one became a 5 mm round at (40, 0), two holes that passed
        old = [*self.rounds(3)[:2], self.fillet(40, 0, 4, 1, -1), tagged]
        passed = [*old[:2], self.fillet(40, 30, 4, 1, 1), self.fillet(40, 0, 5, 1, -1)]
        self.assertEqual(match(passed, old), (None, "broken"))

    def test_faces_of_a_pattern_that_left_their_plane_together_are_followed_each_to_its_own(self):
        m = face_references.match_face
        # a plate's top (z 5, the keys' footprints left out) and four key tops, 25 mm apart
        plate = self.sig(5, area=2600.0, centre=(50.38, 15.0, 5.0))
        keys = [self.sig(7, centre=(x, 15.0, 7)) for x in (10.0, 35.0, 60.0, 85.0)]
        old = [plate, *keys]

        def match(now, key, old=old):
            return m(old[key], f"Face{key + 1}", now, 100, face_references.Previous(list(old), now, 100))

        # the keys 1 mm taller, renumbered: no face is left in their old plane, and each
        # key's tag goes to its own key (the key at x 60 too, though the plate top is
        # 9.8 mm off: it stayed as it was, so it is no other face now)
        raised = [self.sig(8, centre=(x, 15.0, 8)) for x in (10.0, 35.0, 60.0, 85.0)]
        now = [raised[2], plate, raised[0], raised[3], raised[1]]
        self.assertEqual([match(now, k)[0] for k in range(1, 5)], ["Face3", "Face5", "Face1", "Face4"])
        # still broken: a key more or fewer, keys so close (8 mm) that 1 mm is an eighth
        # of the way to the next one
        extra = [*now, self.sig(8, centre=(110.0, 15.0, 8))]
        self.assertEqual([match(extra, k) for k in range(1, 5)], [(None, "broken")] * 4)
        self.assertEqual(match(now[:4], 1), (None, "broken"))
        close = [self.sig(7, centre=(x, 15.0, 7)) for x in (10.0, 18.0, 26.0, 34.0)]
        close_now = [self.sig(8, centre=(x, 15.0, 8)) for x in (10.0, 18.0, 26.0, 34.0)]
        self.assertEqual(match([plate, *close_now], 2, [plate, *close]), (None, "broken"))
        # keys 2 mm taller: the key at x 60 is followed beside the plate as it was, not
        # beside a plate that changed too (a moved face 9.8 mm off: it might be the key's)
        raised = [self.sig(9, centre=(x, 15.0, 9)) for x in (10.0, 35.0, 60.0, 85.0)]
        self.assertEqual(match([plate, *raised], 3), ("Face4", "ok"))
        wider = self.sig(5, area=2700.0, centre=(50.5, 15.0, 5.0))
        self.assertEqual(match([wider, *raised], 3), (None, "broken"))
        self.assertEqual(match([wider, *raised], 1), ("Face2", "ok"))  # 40 mm from the plate's top


if __name__ == "__main__":
    unittest.main()
