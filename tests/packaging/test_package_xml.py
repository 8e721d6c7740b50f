# SPDX-License-Identifier: GPL-3.0-or-later
"""package.xml, as FreeCAD's Addon Manager reads it (FreeCAD.Metadata). freecadcmd."""
import os
import unittest

import FreeCAD as App

TOP = os.path.abspath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))


class PackageXmlTest(unittest.TestCase):
    def test_the_addon_manager_reads_the_workbench(self):
        meta = App.Metadata(os.path.join(TOP, "package.xml"))
        self.assertEqual(meta.Name, "HaptiCAD")
        self.assertTrue(os.path.isfile(os.path.join(TOP, meta.Icon)), meta.Icon)
        self.assertEqual(meta.License[0]["name"], "GPL-3.0-or-later")
        (workbench,) = meta.Content["workbench"]
        folder = os.path.normpath(os.path.join(TOP, workbench.Subdirectory))
        self.assertTrue(os.path.isfile(os.path.join(folder, "InitGui.py")), folder)
        with open(os.path.join(folder, "InitGui.py")) as handle:
            self.assertIn(f"class {workbench.Classname}(", handle.read())
        self.assertTrue(os.path.isfile(os.path.join(TOP, workbench.Icon)))
        self.assertTrue(workbench.supportsCurrentFreeCAD())
        # the version agrees with the code's
        with open(os.path.join(folder, "hapticad", "__init__.py")) as handle:
            self.assertIn(f'__version__ = "{meta.Version}"', handle.read())


if __name__ == "__main__":
    unittest.main()
