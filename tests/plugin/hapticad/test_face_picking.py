# SPDX-License-Identifier: GPL-3.0-or-later
"""Which part's face a click picked (face_picking): paths as the 3D view gives them, from
a top-level object down to the face. A path through a link is refused, naming the link
and what to tag instead; it used to tag the link's original, felt somewhere else (or a
part of the same name in the clicked document). Run by freecadcmd."""
import os
import tempfile
import unittest

import FreeCAD as App
import Part
import Sketcher

import HaptiCAD
from hapticad import face_picking, surface_object
from hapticad.face_picking import picked_face


def body_box(doc, name, length, width, height):
    """A PartDesign Body padded from a rectangle at the origin."""
    body = doc.addObject("PartDesign::Body", name)
    sketch = body.newObject("Sketcher::SketchObject", "Sketch")
    sketch.Support = (body.Origin.OriginFeatures[3], [""])
    sketch.MapMode = "FlatFace"
    corners = [App.Vector(0, 0, 0), App.Vector(length, 0, 0), App.Vector(length, width, 0), App.Vector(0, width, 0)]
    for i in range(4):
        sketch.addGeometry(Part.LineSegment(corners[i], corners[(i + 1) % 4]))
    for i in range(4):
        sketch.addConstraint(Sketcher.Constraint("Coincident", i, 2, (i + 1) % 4, 1))
    pad = body.newObject("PartDesign::Pad", "Pad")
    pad.Profile = sketch
    pad.Length = height
    doc.recompute()
    return body, pad


def top_face(shape, z):
    return [f"Face{i + 1}" for i, f in enumerate(shape.Faces)
            if abs(f.CenterOfMass.z - z) < 1e-6 and type(f.Surface).__name__ == "Plane"][0]


class PickedFaceTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("Picking")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_a_parts_own_face_is_picked_as_the_reference_holds_it(self):
        self.assertEqual(picked_face(self.box, "Face6"), (self.box, "Face6", ""))
        # inside an App::Part, and a PartDesign feature's face as its Body's
        container = self.doc.addObject("App::Part", "Assembly")
        inner = self.doc.addObject("Part::Box", "Inner")
        container.addObject(inner)
        container.Placement.Base = App.Vector(0, 50, 0)
        body, pad = body_box(self.doc, "Body", 20, 10, 5)
        container.addObject(body)
        self.doc.recompute()
        self.assertEqual(picked_face(container, "Inner.Face6"), (inner, "Face6", ""))
        obj, face, why = picked_face(container, f"Body.Pad.{top_face(pad.Shape, 5)}")
        self.assertEqual((obj, why), (body, ""))
        self.assertAlmostEqual(body.Shape.getElement(face).CenterOfMass.z, 5.0)
        self.assertEqual(picked_face(self.box, "Edge1")[0], None)

    def test_a_plain_link_is_refused_as_make_surface_refuses_it(self):
        link = self.doc.addObject("App::Link", "Link")
        link.setLink(self.box)
        link.Label = "BoxLink"
        link.Placement.Base = App.Vector(40, 0, 0)
        self.doc.recompute()
        obj, face, why = picked_face(link, "Face6")
        self.assertIsNone(obj)
        self.assertEqual(why, "BoxLink is a link to Box: a link's faces cannot be tagged yet; tag Box's faces")
        with self.assertRaisesRegex(ValueError, "BoxLink is a link to Box: a link's faces"):
            HaptiCAD.make_surface(self.doc, [(link, "Face6")])
        # a link inside an App::Part is a link all the same
        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(link)
        self.doc.recompute()
        self.assertIn("BoxLink is a link to Box", picked_face(container, "Link.Face6")[2])

    def test_a_link_to_an_app_part_is_refused_naming_the_part_inside(self):
        # the click resolved to Knob itself, which the scene feels 40 mm from where it was clicked
        container = self.doc.addObject("App::Part", "Assembly")
        knob = self.doc.addObject("Part::Cylinder", "Knob")
        container.addObject(knob)
        link = self.doc.addObject("App::Link", "AsmLink")
        link.LinkedObject = container
        link.Placement.Base = App.Vector(40, 40, 0)
        self.doc.recompute()
        self.assertEqual(picked_face(link, "Knob.Face3"),
                         (None, "", "AsmLink is a link to Assembly: a link's faces cannot be tagged yet; tag "
                                    "Knob's faces in Assembly"))

    def test_a_link_arrays_element_is_refused_naming_the_array(self):
        array = self.doc.addObject("App::Link", "LinkArr")
        array.LinkedObject = self.box
        array.ElementCount = 3
        self.doc.recompute()
        expected = "LinkArr is a link array of Box: a link's faces cannot be tagged yet; tag Box's faces"
        for path in ("1.Face6", f"{array.ElementList[1].Name}.Face6"):
            self.assertEqual(picked_face(array, path), (None, "", expected), path)
        # an element given alone (the resolved selection), and the array, as a script gives them
        self.assertIn("LinkArr_i1 is a link to Box", surface_object.untaggable(array.ElementList[1]))
        self.assertEqual(surface_object.untaggable(array), expected)  # was "not a placed part"

    def test_a_draft_array_made_with_links_is_refused_one_made_without_is_picked(self):
        import Draft

        self.box.Placement.Base = App.Vector(0, 80, 0)
        self.box.Label = "ArrBase"
        self.doc.recompute()
        linked = Draft.make_ortho_array(self.box, App.Vector(20, 0, 0), App.Vector(0, 20, 0),
                                        App.Vector(0, 0, 20), 3, 1, 1, use_link=True)
        self.doc.recompute()
        obj, _, why = picked_face(linked, "2.Face6")  # the third element's top: ArrBase's, 40 mm off
        self.assertIsNone(obj)
        self.assertEqual(why, f"{linked.Label} is an array made with links to ArrBase: its faces are ArrBase's, "
                              "shown where the array places them, and cannot be tagged there; make the array "
                              "without links (Draft's Link array option off) and tag its faces")
        plain = Draft.make_ortho_array(self.box, App.Vector(20, 0, 0), App.Vector(0, 20, 0),
                                       App.Vector(0, 0, 20), 3, 1, 1, use_link=False)
        self.doc.recompute()
        self.assertEqual(picked_face(plain, "Face6"), (plain, "Face6", ""))

    def test_a_link_group_is_refused(self):
        group = self.doc.addObject("App::LinkGroup", "Group")
        group.setLink(self.box)
        group.Placement.Base = App.Vector(0, 0, 30)
        self.doc.recompute()
        obj, _, why = picked_face(group, "Box.Face6")
        self.assertIsNone(obj)
        self.assertIn("Group is a link group showing Box: a link's faces cannot be tagged yet", why)

    def test_a_part_of_another_document_is_never_taken_for_this_ones(self):
        # a stand-in for a container that shows another document's part without a link
        other = App.newDocument("Elsewhere")
        try:
            foreign = other.addObject("Part::Box", "Box")
            other.recompute()
            root = self.doc.addObject("App::Part", "Shows")

            class Shows:
                Label, Document = "Shows", self.doc

                def getSubObjectList(self, path):
                    return [root, foreign]

            self.assertEqual(picked_face(Shows(), "Box.Face6"),
                             (None, "", f"Box.Face6 is in {other.Label}, shown by Shows: tag it in its own "
                                        "document"))
        finally:
            App.closeDocument(other.Name)


class PickedCurveTest(unittest.TestCase):
    """A curve pattern's edges, as the unresolved selection names them: through a link they
    were the original sketch's, shown elsewhere, and the pattern followed those."""

    def setUp(self):
        self.doc = App.newDocument("Curves")
        self.sketch = self.doc.addObject("Sketcher::SketchObject", "Guide")
        self.sketch.addGeometry(Part.LineSegment(App.Vector(0, 5, 0), App.Vector(40, 25, 0)))
        self.sketch.addGeometry(Part.LineSegment(App.Vector(40, 25, 0), App.Vector(60, 25, 0)))
        self.box = self.doc.addObject("Part::Box", "Box")
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)

    def test_a_sketchs_own_edges_or_the_whole_sketch_are_picked(self):
        self.assertEqual(face_picking.picked_curve([(self.sketch, ["Edge2", "Edge1", "Edge2"])]),
                         ((self.sketch, ["Edge2", "Edge1"]), ""))
        self.assertEqual(face_picking.picked_curve([(self.sketch, [])]), ((self.sketch, []), ""))
        # in an App::Part, as the view names it; a box's faces and a box whole are no curve
        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(self.sketch)
        self.doc.recompute()
        self.assertEqual(face_picking.picked_curve([(self.box, ["Face6"]), (container, ["Guide.Edge1"])]),
                         ((self.sketch, ["Edge1"]), ""))
        self.assertEqual(face_picking.picked_curve([(container, ["Guide."])]), ((self.sketch, []), ""))
        self.assertEqual(face_picking.picked_curve([(self.box, [])]), (None, ""))
        # the edges of one object: a second one's are left out
        self.assertEqual(face_picking.picked_curve([(self.box, ["Edge1"]), (container, ["Guide.Edge1"])]),
                         ((self.box, ["Edge1"]), ""))

    def test_edges_through_any_link_are_refused_in_the_words_faces_are(self):
        link = self.doc.addObject("App::Link", "GuideLink")
        link.LinkedObject = self.sketch
        link.Placement.Base = App.Vector(0, 40, 0)
        holder = self.doc.addObject("App::Part", "Holder")
        holder.addObject(self.sketch)
        part_link = self.doc.addObject("App::Link", "PartLink")
        part_link.LinkedObject = holder
        array = self.doc.addObject("App::Link", "LinkArr")
        array.LinkedObject = self.sketch
        array.ElementCount = 2
        self.doc.recompute()
        said = "a link's edges cannot be followed by a curve pattern yet"
        for selection, expected in [
                ([(link, ["Edge1"])], f"GuideLink is a link to Guide: {said}; pick Guide's edges"),
                ([(link, [])], f"GuideLink is a link to Guide: {said}; pick Guide's edges"),  # whole, in the tree
                ([(part_link, ["Guide.Edge2"])], f"PartLink is a link to Holder: {said}; pick Guide's edges in Holder"),
                ([(array, ["1.Edge1"])], f"LinkArr is a link array of Guide: {said}; pick Guide's edges"),
                # one of the edges through a link: refused, not followed in part
                ([(holder, ["Guide.Edge1"]), (link, ["Edge2"])], f"GuideLink is a link to Guide: {said}")]:
            with self.subTest(selection=[(o.Name, p) for o, p in selection]):
                curve, why = face_picking.picked_curve(selection)
                self.assertIsNone(curve)
                self.assertTrue(why.startswith(expected), why)
        # a link to a box, whole, is no curve to refuse
        box_link = self.doc.addObject("App::Link", "BoxLink")
        box_link.LinkedObject = self.box
        self.doc.recompute()
        self.assertEqual(face_picking.picked_curve([(box_link, [])]), (None, ""))
        # the face's words stay as they were
        self.assertEqual(face_picking.link_refusal(link),
                         "GuideLink is a link to Guide: a link's faces cannot be tagged yet; tag Guide's faces")

    def test_a_draft_array_made_with_links_is_refused_for_its_edges(self):
        import Draft

        array = Draft.make_ortho_array(self.box, App.Vector(20, 0, 0), App.Vector(0, 20, 0),
                                       App.Vector(0, 0, 20), 2, 1, 1, use_link=True)
        self.doc.recompute()
        curve, why = face_picking.picked_curve([(array, ["1.Edge1"])])
        self.assertIsNone(curve)
        self.assertEqual(why, f"{array.Label} is an array made with links to Box: its edges are Box's, shown where "
                              "the array places them, and cannot be followed by a curve pattern there; make the "
                              "array without links (Draft's Link array option off) and pick its edges")

    def test_a_centre_clicked_on_a_link_is_refused_naming_the_link_and_the_parts(self):
        link = self.doc.addObject("App::Link", "BoxLink")
        link.LinkedObject = self.box
        container = self.doc.addObject("App::Part", "Assembly")
        container.addObject(link)
        self.doc.recompute()
        self.assertIsNone(face_picking.link_on_path(self.box, "Face6"))
        self.assertEqual(face_picking.link_on_path(container, "BoxLink.Face6"), link)
        self.assertEqual(face_picking.centre_refusal(link, ["Box"]),
                         "BoxLink is a link to Box: the point clicked lies where it shows Box, away from the faces "
                         "the circles are felt on; click the centre on Box itself")
        self.assertTrue(face_picking.centre_refusal(link, ["Box", "Lid", "Cap"]).endswith(
            "click the centre on Box, Lid or Cap itself"))


class CrossDocumentLinkTest(unittest.TestCase):
    """An assembly with its own Body "Body" and an App::Link to a knob's Body "Body" in
    another file: a click on the knob's top tagged the assembly's plate top."""

    def setUp(self):
        self.folder = tempfile.TemporaryDirectory()
        self.knob_doc = App.newDocument("Knob")
        self.knob, self.knob_pad = body_box(self.knob_doc, "Body", 10, 10, 6)
        self.knob_doc.saveAs(os.path.join(self.folder.name, "knob.FCStd"))
        self.doc = App.newDocument("Assembly")
        self.doc.saveAs(os.path.join(self.folder.name, "assembly.FCStd"))
        self.plate, _ = body_box(self.doc, "Body", 80, 40, 4)
        self.link = self.doc.addObject("App::Link", "KnobLink")
        self.link.LinkedObject = self.knob
        self.link.Placement.Base = App.Vector(50, 15, 4)
        self.doc.recompute()

    def tearDown(self):
        App.closeDocument(self.doc.Name)
        App.closeDocument(self.knob_doc.Name)
        self.folder.cleanup()

    def test_the_knobs_face_is_refused_naming_its_file_and_the_plate_is_not_tagged(self):
        top = top_face(self.knob_pad.Shape, 6)
        self.assertEqual(picked_face(self.link, f"Pad.{top}"),
                         (None, "", "KnobLink is a link to Body in knob.FCStd: a link's faces cannot be tagged yet; "
                                    "tag Body's faces in knob.FCStd itself, and feel them there"))
        # a script is told the same
        self.assertEqual(surface_object.untaggable(self.link), picked_face(self.link, f"Pad.{top}")[2])
        # the plate's own top is still picked, as the assembly's
        obj, face, why = picked_face(self.plate, f"{self.plate.Tip.Name}.{top_face(self.plate.Shape, 4)}")
        self.assertEqual((obj, why), (self.plate, ""))
        self.assertEqual(face_picking.document_file(self.knob_doc), "knob.FCStd")

    def test_the_knobs_edges_are_refused_naming_its_file(self):
        # a curve pattern in the assembly followed the knob's sketch where knob.FCStd has it
        curve, why = face_picking.picked_curve([(self.link, ["Sketch.Edge1"])])
        self.assertIsNone(curve)
        self.assertEqual(why, "KnobLink is a link to Body in knob.FCStd: a link's edges cannot be followed by a "
                              "curve pattern yet; pick Sketch's edges in Body in knob.FCStd itself, and feel them "
                              "there")


if __name__ == "__main__":
    unittest.main()
