# SPDX-License-Identifier: GPL-3.0-or-later
"""packaging/check-install-folder.sh, which setup.sh runs before it installs anything:
a checkout cloned into FreeCAD's Mod folder (or put there by the Addon Manager) would be
deleted when setup.sh replaces that folder with the built workbench. Plain /usr/bin/python3."""
import os
import subprocess
import tempfile
import unittest

TOP = os.path.normpath(os.path.join(os.path.dirname(__file__), "..", ".."))
CHECK = os.path.join(TOP, "packaging", "check-install-folder.sh")
SETUP = os.path.join(TOP, "packaging", "setup.sh")


def check(checkout, mod_dir):
    return subprocess.run([CHECK, checkout, mod_dir], capture_output=True, text=True)


class InstallFolderTest(unittest.TestCase):
    def test_a_checkout_in_the_mod_folder_is_refused_and_kept(self):
        with tempfile.TemporaryDirectory() as home:
            mod_dir = os.path.join(home, ".local", "share", "FreeCAD", "Mod", "HaptiCAD")
            os.makedirs(os.path.join(mod_dir, "packaging"))
            work = os.path.join(mod_dir, "my_change.cc")
            open(work, "w").close()
            for checkout in (mod_dir, mod_dir + "/", os.path.join(mod_dir, "packaging", "..")):
                done = check(checkout, mod_dir)
                self.assertEqual(done.returncode, 2, checkout)
                self.assertIn("the folder setup.sh replaces with the built workbench: installing would delete it",
                              done.stderr)
                self.assertIn("nothing was changed", done.stderr)
            # under it (the Addon Manager's copy with a subfolder, a clone inside the workbench)
            self.assertEqual(check(os.path.join(mod_dir, "src", "HaptiCAD"), mod_dir).returncode, 2)
            # the same folder named through a link
            link = os.path.join(home, "link")
            os.symlink(mod_dir, link)
            self.assertEqual(check(link, mod_dir).returncode, 2)
            self.assertTrue(os.path.exists(work))

    def test_a_checkout_elsewhere_installs(self):
        with tempfile.TemporaryDirectory() as home:
            mod_dir = os.path.join(home, ".local", "share", "FreeCAD", "Mod", "HaptiCAD")
            for checkout in (os.path.join(home, "src", "HaptiCAD"), mod_dir + "-src",
                             os.path.join(home, ".local", "share", "FreeCAD", "Mod")):
                done = check(checkout, mod_dir)
                self.assertEqual((done.returncode, done.stderr), (0, ""), checkout)

    def test_setup_checks_before_it_installs_or_removes_anything(self):
        with open(SETUP) as handle:
            script = handle.read()
        checked = script.index("check-install-folder.sh")
        for step in ('"$top/packaging/install-deps.sh"', "rm -rf", "cmake --install"):
            self.assertLess(checked, script.index(step), step)


if __name__ == "__main__":
    unittest.main()
