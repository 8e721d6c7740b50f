# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad demo` with a display: FreeCAD opens the example and demo_startup.py
switches to the workbench and shows the part. Also: a document written without the
GUI gets HaptiCAD's view providers when opened in it. Run under Xvfb."""
import os
import subprocess
import sys
import tempfile
import unittest

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtGui

import HaptiCAD
from hapticad import demo

SHOTS = os.environ.get("HAPTICAD_SCREENSHOT_DIR", "/tmp")
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from gui_helpers import non_white_fraction, process_events, report_text  # noqa: E402


class DemoStartupTest(unittest.TestCase):
    def test_example_opens_in_the_workbench_with_the_part_in_view(self):
        Gui.activateWorkbench("HaptiCADWorkbench")  # its view providers' callbacks run as the document loads
        before = report_text()
        doc = App.openDocument(demo.EXAMPLE)
        try:
            with open(demo.GUI_STARTUP) as handle:
                exec(compile(handle.read(), demo.GUI_STARTUP, "exec"), {})
            process_events()
            printed = report_text()[len(before):]
            self.assertEqual((printed.count("Traceback"), printed.count("Error")), (0, 0), printed[-600:])
            self.assertEqual(Gui.activeWorkbench().name(), "HaptiCADWorkbench")
            surfaces = HaptiCAD.surfaces_of(doc)
            self.assertEqual(len(surfaces), 4)
            for s in surfaces:
                self.assertEqual(type(s.ViewObject.Proxy).__name__, "ViewProviderHapticSurface")
            self.assertTrue(doc.Toothbrush.ViewObject.Visibility)
            path = os.path.join(SHOTS, "demo_toothbrush.png")
            Gui.getDocument(doc.Name).ActiveView.saveImage(path, 640, 400, "White")
            image = QtGui.QImage(path)
            self.assertGreater(non_white_fraction(image), 0.03)
            # the blue handle: the part is drawn in its own colour, not a default grey
            centre = QtGui.QColor(image.pixel(image.width() // 2, image.height() // 2))
            self.assertGreater(centre.blue(), centre.red() + 30, centre.name())
        finally:
            App.closeDocument(doc.Name)

    def test_a_document_written_headless_gets_view_providers(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "headless.FCStd")
            script = os.path.join(tmp, "make.py")
            with open(script, "w") as handle:
                handle.write(
                    "import FreeCAD as App, HaptiCAD\n"
                    "d = App.newDocument('Headless')\n"
                    "b = d.addObject('Part::Box', 'Box'); d.recompute()\n"
                    "HaptiCAD.make_surface(d, [(b, 'Face6')])\n"
                    f"d.saveAs({path!r})\n"
                )
            subprocess.run(["freecadcmd", script], check=True, capture_output=True, timeout=120)
            doc = App.openDocument(path)
            try:
                surface = HaptiCAD.surfaces_of(doc)[0]
                self.assertEqual(type(surface.ViewObject.Proxy).__name__, "ViewProviderHapticSurface")
                self.assertNotIn("Touched", surface.State)
            finally:
                App.closeDocument(doc.Name)


if __name__ == "__main__":
    unittest.main()
