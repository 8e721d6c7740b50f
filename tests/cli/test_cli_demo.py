# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad demo --headless` end to end: each tagged face of the example toothbrush
stroked, one readable line a face on stdout (what it is, what was felt, where its plot
is); with --json, every stroke's summary.

Environment: HAPTICAD_CLI (the launcher). Runs under /usr/bin/python3."""
import json
import os
import re
import subprocess
import tempfile
import unittest

CLI = os.environ["HAPTICAD_CLI"]


def run_cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=240)


class DemoCommandTest(unittest.TestCase):
    def test_an_output_folder_that_is_a_file_is_refused_before_any_work(self):
        with tempfile.TemporaryDirectory() as tmp:
            taken = os.path.join(tmp, "notes.txt")
            with open(taken, "w", encoding="utf-8") as handle:
                handle.write("mine\n")
            for out in (taken, os.path.join(taken, "demo")):
                with self.subTest(out=out):
                    proc = run_cli("demo", "--headless", "--out", out)
                    self.assertEqual(proc.returncode, 2, proc.stdout)
                    self.assertIn(f"{taken} is a file, not a folder", proc.stderr)
                    self.assertNotIn("Traceback", proc.stderr)
            with open(taken, encoding="utf-8") as handle:
                self.assertEqual(handle.read(), "mine\n")  # nothing written over it
            self.assertEqual(os.listdir(tmp), ["notes.txt"])

    def test_headless_demo_says_what_each_face_felt_and_json_holds_it_all(self):
        with tempfile.TemporaryDirectory() as tmp:
            proc = run_cli("demo", "--headless", "--out", os.path.join(tmp, "text"))
            self.assertEqual(proc.returncode, 0, proc.stderr)
            lines = proc.stdout.strip().splitlines()
            # the example's copy in the output folder, which the GUI demo opens too
            copy = os.path.join(tmp, "text", "toothbrush.FCStd")
            self.assertIn(f"each tagged face of {copy} stroked by the simulated probe", lines[0])
            self.assertTrue(os.path.isfile(copy))
            felt = [line for line in lines[1:] if "Ft/Fn" in line]
            self.assertGreaterEqual(len(felt), 4, proc.stdout)
            self.assertLess(len(lines), 12)  # a few lines, not the JSON
            for line in felt:
                match = re.search(r"Ft/Fn (\d+\.\d\d) \(mu_d (\d+\.\d\d)\); (\S+\.png)", line)
                self.assertIsNotNone(match, line)
                self.assertTrue(os.path.exists(os.path.join(tmp, "text", match.group(3).split("/text/")[-1]))
                                or os.path.exists(match.group(3)), line)
            proc = run_cli("demo", "--headless", "--json", "--out", os.path.join(tmp, "json"))
            self.assertEqual(proc.returncode, 0, proc.stderr)
            result = json.loads(proc.stdout)
            felt = [s for s in result["strokes"] if s.get("contact_ticks", 0) > 0]
            self.assertGreaterEqual(len(felt), 4)
            # each stroke runs between rows of roughness balls, where the friction is the
            # material's: the mean Ft/Fn reads against mu_d (along a row it read m/3 = 5 %
            # above; what is left is the balls' slopes tilting the force, 1-3.4 %)
            for stroke in felt:
                face = stroke["faces"][stroke["face"]]
                self.assertLess(abs(face["mean_ft_over_fn"] / face["mu_dynamic"] - 1), 0.04, stroke["face"])


if __name__ == "__main__":
    unittest.main()
