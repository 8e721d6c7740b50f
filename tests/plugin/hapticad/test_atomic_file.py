# SPDX-License-Identifier: GPL-3.0-or-later
"""atomic_file: a file is written whole or not at all, and nothing is left beside it; a
link stays one. (A file the user may not write: tests/cli/test_cli_cohort.py, run as
another user.)"""
import json
import os
import tempfile
import unittest

from hapticad import atomic_file


class ReplacingTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.path = os.path.join(self.tmp.name, "out.csv")

    def read(self):
        with open(self.path, encoding="utf-8") as handle:
            return handle.read()

    def test_the_block_written_becomes_the_file(self):
        with atomic_file.replacing(self.path) as handle:
            handle.write("Zoë\n")
            self.assertFalse(os.path.exists(self.path))  # not before the block ends
        self.assertEqual(self.read(), "Zoë\n")
        self.assertEqual(os.listdir(self.tmp.name), ["out.csv"])

    def test_a_block_that_raises_leaves_the_file_there_and_nothing_beside_it(self):
        with open(self.path, "w", encoding="utf-8") as handle:
            handle.write("before\n")
        for stop in (OSError("No space left on device"), KeyboardInterrupt()):
            with self.subTest(stop=type(stop).__name__), self.assertRaises(type(stop)):
                with atomic_file.replacing(self.path) as handle:
                    handle.write("half")
                    raise stop
            self.assertEqual(self.read(), "before\n")
            self.assertEqual(os.listdir(self.tmp.name), ["out.csv"])

    def test_a_link_stays_a_link_and_a_file_keeps_its_permissions(self):
        # moving the new file onto a link replaced the link; the file it named kept the old text
        real = os.path.join(self.tmp.name, "real.csv")
        with open(real, "w", encoding="utf-8") as handle:
            handle.write("old\n")
        os.chmod(real, 0o600)
        os.symlink("real.csv", self.path)
        with atomic_file.replacing(self.path) as handle:
            handle.write("new\n")
        self.assertTrue(os.path.islink(self.path))
        self.assertEqual(self.read(), "new\n")
        self.assertEqual(os.stat(real).st_mode & 0o777, 0o600)
        self.assertEqual(sorted(os.listdir(self.tmp.name)), ["out.csv", "real.csv"])

    def test_json_in_a_folder_made_for_it(self):
        path = os.path.join(self.tmp.name, "journals", "run.json")
        atomic_file.write_json(path, {"name": "Ada"})
        with open(path, encoding="utf-8") as handle:
            self.assertEqual(json.load(handle), {"name": "Ada"})


if __name__ == "__main__":
    unittest.main()
