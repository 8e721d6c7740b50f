# SPDX-License-Identifier: GPL-3.0-or-later
"""The demo's working copy (hapticad/demo.py), headless: the demo opens a copy of the
example in its output folder, so saving never overwrites the shipped example, and a
copy saved before is opened again, not replaced, by the GUI demo and the headless one
alike. Run by freecadcmd."""
import filecmp
import os
import tempfile
import unittest

from hapticad import demo


class WorkingCopyTest(unittest.TestCase):
    def test_the_gui_demo_opens_a_copy_and_keeps_the_designers_changes(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "hapticad-demo")
            path, new = demo.working_copy(out)
            self.assertTrue(new)
            self.assertEqual(path, os.path.join(out, "toothbrush.FCStd"))
            self.assertNotEqual(os.path.realpath(path), os.path.realpath(demo.EXAMPLE))
            self.assertTrue(filecmp.cmp(path, demo.EXAMPLE, shallow=False))
            with open(path, "ab") as saved:  # the designer saved changes into the copy
                saved.write(b"changed")
            again, new = demo.working_copy(out)
            self.assertEqual(again, path)
            self.assertFalse(new)
            with open(path, "rb") as saved:
                self.assertTrue(saved.read().endswith(b"changed"))  # kept, not copied over


    def test_a_damaged_copy_is_named_with_how_to_get_a_fresh_one(self):
        # the copy cut short was opened as a document whose every face reference was
        # broken ("pick the faces again"), a garbage one gave FreeCAD's "Invalid project file"
        from unittest import mock

        with open(demo.EXAMPLE, "rb") as example:
            whole = example.read()
        with tempfile.TemporaryDirectory() as tmp:
            for name, data in (("cut short", whole[:5000]), ("garbage", b"not a zip\n")):
                out = os.path.join(tmp, name)
                os.makedirs(out)
                copy = os.path.join(out, "toothbrush.FCStd")
                with open(copy, "wb") as damaged:
                    damaged.write(data)
                with self.subTest(copy=name):
                    with self.assertRaises(ValueError) as caught:
                        demo.run_headless(out)
                    said = str(caught.exception)
                    self.assertIn(f"{copy}: not a FreeCAD document, or a damaged one", said)
                    self.assertIn("It is the demo's copy of the example: move it away and run hapticad demo again, "
                                  "which copies the example there afresh", said)
                    # the GUI demo says so too, and starts no FreeCAD on it
                    with mock.patch.object(demo.subprocess, "Popen") as popen, \
                            mock.patch.object(demo.shutil, "which", return_value="/usr/bin/freecad"):
                        with self.assertRaises(ValueError) as caught:
                            demo.launch_gui(out)
                    self.assertEqual(str(caught.exception), said)
                    popen.assert_not_called()
                with open(copy, "rb") as kept:
                    self.assertEqual(kept.read(), data)  # left as it is: the designer moves it away


class HeadlessDemoTest(unittest.TestCase):
    def test_the_headless_demo_strokes_the_designers_copy(self):
        import FreeCAD as App

        from hapticad.surface_object import surfaces_of

        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "hapticad-demo")
            path, _ = demo.working_copy(out)
            doc = App.openDocument(path)  # the designer kept one surface and made it rubber
            kept, *others = surfaces_of(doc)
            for surface in others:
                doc.removeObject(surface.Name)
            kept.Material = "Rubber"
            doc.recompute()
            doc.save()
            App.closeDocument(doc.Name)
            result = demo.run_headless(out)
            self.assertEqual(result["document"], path)
            (stroke,) = result["strokes"]
            self.assertEqual(stroke["faces"][stroke["face"]]["material"], "Rubber")

    def test_a_face_a_model_edit_broke_is_said_skipped_and_the_others_stroked(self):
        # the tool moved off the block: the tagged notch wall is gone, its reference broken
        # (stepped aside as Face6~1): the demo stopped at "Invalid subelement name", or
        # stroked whatever face now bore the name, plotted as tagged and felt untagged
        import FreeCAD as App

        import HaptiCAD
        from hapticad import face_references
        from hapticad.surface_object import reference_pairs, reference_status

        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("DemoBroken")
            box, tool = doc.addObject("Part::Box", "Box"), doc.addObject("Part::Box", "Tool")
            box.Length, box.Width, box.Height = 20, 20, 10
            tool.Length = tool.Width = tool.Height = 5
            tool.Placement.Base = App.Vector(-1, -1, -1)
            cut = doc.addObject("Part::Cut", "Cut")
            cut.Base, cut.Tool = box, tool
            doc.recompute()
            top = [f"Face{i + 1}" for i, f in enumerate(cut.Shape.Faces)
                   if abs(f.CenterOfMass.z - 10) < 1e-6 and f.Area > 300][0]
            surface = HaptiCAD.make_surface(doc, [(cut, top), (cut, "Face6")], material="Rubber")
            doc.recompute()
            tool.Placement.Base = App.Vector(-30, -30, -30)
            doc.recompute()
            broken = [f for _, f, s in reference_status(surface) if s == face_references.BROKEN]
            self.assertEqual(len(broken), 1, reference_status(surface))
            self.assertEqual(len(reference_pairs(surface)), 2)
            path = os.path.join(tmp, "broken.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            result = demo.run_headless(os.path.join(tmp, "out"), document=path)
            skipped = [s for s in result["strokes"] if "skipped" in s]
            felt = [s for s in result["strokes"] if "skipped" not in s]
            self.assertEqual([s["face"] for s in skipped], [f"Cut.{face_references.shown_face(broken[0])}"])
            self.assertIn("is broken by a model edit: pick it again", skipped[0]["skipped"])
            (stroke,) = felt
            self.assertEqual(stroke["faces"][stroke["face"]]["material"], "Rubber")

    def test_a_study_and_a_hidden_part_are_said_as_the_feel_panel_says_them(self):
        # the demo printed "pressed 2.77 N" of a neck the study made 4.44 N/mm, with no note,
        # and nothing of a tagged part hidden behind a Cut
        import FreeCAD as App

        import HaptiCAD

        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("DemoNotes")
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 40, 20, 10
            hole = doc.addObject("Part::Cylinder", "Hole")
            hole.Radius, hole.Height = 2, 30
            hole.Placement.Base = App.Vector(35, 15, -5)
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="PP", FeelRoughness=False)
            HaptiCAD.make_study(doc, surface, YoungsModulus=1.5, BeamWidth=5, BeamThickness=8,
                                BeamLength=60).Label = "Neck study"
            cut = doc.addObject("Part::Cut", "Cut")
            cut.Base, cut.Tool = box, hole
            doc.recompute()
            box.Visibility = hole.Visibility = False
            path = os.path.join(tmp, "notes.FCStd")
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            result = demo.run_headless(os.path.join(tmp, "out"), document=path)
            self.assertIn("Box is hidden, used by Cut: you feel Box's shape, not what is shown; tag the faces of Cut "
                          "instead", result["notes"])
            (stroke,) = result["strokes"]
            face = stroke["faces"]["Box.Face6"]
            most = stroke["max_stiffness_n_per_mm"]
            self.assertEqual((face["stiffness_n_per_mm"], face["stiffness_above_device"], face["stiffness_study"]),
                             (most, True, "Neck study"))
            self.assertEqual(len(stroke["notes"]), 1)
            self.assertIn("Neck study's bending beam (4.44 N/mm) replaces the surface's", stroke["notes"][0])

    def test_a_study_whose_law_is_not_felt_is_said(self):
        # a duplicated study: the demo stroked the surface at its own 0.8 N/mm and said
        # nothing of the 0.556 N/mm neck it had before
        import FreeCAD as App

        import HaptiCAD

        with tempfile.TemporaryDirectory() as tmp:
            doc = App.newDocument("DemoStudyNotFelt")
            box = doc.addObject("Part::Box", "Box")
            box.Length, box.Width, box.Height = 40, 20, 10
            doc.recompute()
            surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="PP", stiffness_n_per_mm=0.8,
                                            FeelRoughness=False)
            surface.Label = "Head"
            study = HaptiCAD.make_study(doc, surface)
            study.Label = "Neck"
            copy = doc.copyObject(study, False)
            doc.recompute()
            path = os.path.join(tmp, "studies.FCStd")
            doc.saveAs(path)
            copy_label = copy.Label
            App.closeDocument(doc.Name)
            result = demo.run_headless(os.path.join(tmp, "out"), document=path)
            self.assertIn(f"Neck is not felt (Head is felt at its own stiffness): Head is also studied by "
                          f"{copy_label}: a face gives one way; link another surface", result["notes"])
            (stroke,) = result["strokes"]
            face = stroke["faces"]["Box.Face6"]
            self.assertEqual((face["stiffness_n_per_mm"], face["stiffness_study"]), (0.8, None))


if __name__ == "__main__":
    unittest.main()
