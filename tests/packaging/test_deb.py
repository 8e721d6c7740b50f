#!/usr/bin/python3
# SPDX-License-Identifier: GPL-3.0-or-later
"""The .deb that CPack builds: depends on Debian's FreeCAD, installs the workbench with
its compiled module into FreeCAD's system Mod folder, the command, and the udev rules
the tree has. Builds the package in its own folder inside the build tree, then reads it
with dpkg-deb. Usage: test_deb.py BUILD_DIR SOURCE_DIR"""
import glob
import os
import subprocess
import sys
import tempfile
import unittest

BUILD, SOURCE = sys.argv[1], sys.argv[2]
MOD = "./usr/share/freecad/Mod/HaptiCAD/"


class DebTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.out = tempfile.mkdtemp(prefix="deb-", dir=BUILD)
        subprocess.run(["cpack", "-G", "DEB", "--config", os.path.join(BUILD, "CPackConfig.cmake"),
                        "-B", cls.out], check=True, capture_output=True, timeout=600)
        (cls.deb,) = glob.glob(os.path.join(cls.out, "hapticad_*.deb"))
        cls.info = subprocess.run(["dpkg-deb", "-I", cls.deb], check=True, capture_output=True, text=True).stdout
        listing = subprocess.run(["dpkg-deb", "-c", cls.deb], check=True, capture_output=True, text=True).stdout
        cls.files = [line.split()[-1] for line in listing.splitlines()]

    @classmethod
    def tearDownClass(cls):
        subprocess.run(["rm", "-rf", cls.out], check=False)

    def field(self, name):
        for line in self.info.splitlines():
            if line.strip().startswith(name + ":"):
                return line.split(":", 1)[1].strip()
        self.fail(f"no {name} in the control file")

    def test_control_fields(self):
        self.assertEqual(self.field("Package"), "hapticad")
        depends = [d.strip().split(" ")[0] for d in self.field("Depends").split(",")]
        for package in ("freecad", "python3-numpy", "python3-matplotlib", "python3-pivy"):
            self.assertIn(package, depends)
        self.assertIn("freecad (>= 0.20)", self.field("Depends"))
        self.assertEqual(self.field("Architecture"), "amd64")

    def test_installs_the_workbench_and_its_compiled_module(self):
        for name in ("Init.py", "InitGui.py", "HaptiCAD.py", "hapticad/__init__.py", "hapticad/surface_object.py",
                     "hapticad/gui/task_panel_surface.py", "resources/icons/HaptiCAD.svg",
                     "resources/materials/materials.csv"):
            self.assertIn(MOD + name, self.files)
        self.assertEqual(len([f for f in self.files if f.startswith(MOD + "hapticad/_core") and f.endswith(".so")]),
                         1)
        self.assertFalse([f for f in self.files if "__pycache__" in f or f.endswith(".FCStd1")])
        # nothing outside /usr (nothing in a user's home)
        self.assertTrue(all(f.startswith("./usr/") for f in self.files), self.files)

    def test_the_command_points_at_the_system_mod_folder(self):
        self.assertIn("./usr/bin/hapticad", self.files)
        text = subprocess.run(["dpkg-deb", "--fsys-tarfile", self.deb], check=True, capture_output=True).stdout
        import io
        import tarfile

        with tarfile.open(fileobj=io.BytesIO(text)) as tar:
            script = tar.extractfile("./usr/bin/hapticad").read().decode()
            mode = tar.getmember("./usr/bin/hapticad").mode
        self.assertIn('"/usr/share/freecad/Mod/HaptiCAD"', script)
        self.assertTrue(mode & 0o111)

    def test_the_benchmark_program_stays_executable(self):
        # `hapticad bench-mesh` runs it: packaged 0644 it said the program "is missing"
        import io
        import tarfile

        text = subprocess.run(["dpkg-deb", "--fsys-tarfile", self.deb], check=True, capture_output=True).stdout
        with tarfile.open(fileobj=io.BytesIO(text)) as tar:
            mode = tar.getmember(MOD + "hapticad/hapticad-bench-mesh").mode
        self.assertEqual(mode & 0o111, 0o111, oct(mode))

    def test_udev_rules_of_the_tree_are_installed(self):
        rules = sorted(os.path.basename(p) for d in ("packaging", "packaging/udev", "devices/udev", "resources/udev")
                       for p in glob.glob(os.path.join(SOURCE, d, "*.rules")))
        installed = sorted(os.path.basename(f) for f in self.files if f.startswith("./usr/lib/udev/rules.d/")
                           and f.endswith(".rules"))
        self.assertEqual(installed, rules)
        # with rules, the package makes their group on installation
        control = subprocess.run(["dpkg-deb", "-I", self.deb], check=True, capture_output=True, text=True).stdout
        self.assertEqual("postinst" in control, bool(rules))


if __name__ == "__main__":
    unittest.main(argv=sys.argv[:1], verbosity=2)
