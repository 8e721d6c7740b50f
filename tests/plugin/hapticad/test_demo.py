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


if __name__ == "__main__":
    unittest.main()
