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


if __name__ == "__main__":
    unittest.main()
