# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad demo --headless` end to end: each tagged face of the example toothbrush
stroked, one readable line a face on stdout (what it is, what was felt, where its plot
is); with --json, every stroke's summary.

Environment: HAPTICAD_CLI (the launcher). Runs under /usr/bin/python3."""
import json
import os
import re
import subprocess
import sys
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

    def test_a_damaged_copy_is_named_with_how_to_get_a_fresh_one(self):
        # a copy cut short was said to have "every tagged face reference broken; pick the
        # faces again", a garbage one FreeCAD's "Invalid project file"
        example = os.path.join(os.environ["HAPTICAD_MOD"], "resources", "examples", "toothbrush.FCStd")
        with open(example, "rb") as handle:
            whole = handle.read()
        with tempfile.TemporaryDirectory() as tmp:
            for name, data in (("cut-short", whole[:5000]), ("garbage", b"not a zip\n")):
                out = os.path.join(tmp, name)
                os.mkdir(out)
                copy = os.path.join(out, "toothbrush.FCStd")
                with open(copy, "wb") as handle:
                    handle.write(data)
                for json_flag in ((), ("--json",)):
                    with self.subTest(copy=name, json=bool(json_flag)):
                        proc = run_cli("demo", "--headless", "--out", out, *json_flag)
                        self.assertEqual(proc.returncode, 2, proc.stderr)
                        self.assertEqual(proc.stdout, "")
                        self.assertIn(f"hapticad demo: {copy}: not a FreeCAD document, or a damaged one", proc.stderr)
                        self.assertIn("It is the demo's copy of the example: move it away and run hapticad demo again",
                                      proc.stderr)
                        self.assertNotIn("pick the faces again", proc.stderr)
                with open(copy, "rb") as handle:
                    self.assertEqual(handle.read(), data)  # left for the designer to move away

    def test_a_face_under_a_stiffness_study_is_said_with_what_was_felt(self):
        # the demo printed "pressed 2.77 N" of a neck the study made 4.44 N/mm (felt at the
        # device's 3), and nothing said a study governed the face
        sys.path.insert(0, os.environ["HAPTICAD_MOD"])
        from hapticad.freecad_env import ensure_freecad

        App = ensure_freecad()
        import HaptiCAD

        with tempfile.TemporaryDirectory() as tmp:
            out = os.path.join(tmp, "study")
            os.mkdir(out)
            copy = os.path.join(out, "toothbrush.FCStd")
            doc = App.openDocument(os.path.join(os.environ["HAPTICAD_MOD"], "resources", "examples",
                                                "toothbrush.FCStd"))
            (neck,) = [s for s in HaptiCAD.surfaces_of(doc) if s.Label == "Neck"]
            HaptiCAD.make_study(doc, neck, YoungsModulus=1.5, BeamWidth=5, BeamThickness=8,
                                BeamLength=60).Label = "NeckStudy"
            doc.recompute()
            doc.saveAs(copy)
            App.closeDocument(doc.Name)
            proc = run_cli("demo", "--headless", "--json", "--out", out)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            (stroke,) = [s for s in json.loads(proc.stdout)["strokes"]
                         if s.get("faces", {}).get(s["face"], {}).get("surface") == "Neck"]
            face = stroke["faces"][stroke["face"]]
            self.assertEqual(face["stiffness_n_per_mm"], 3.0)  # the device's most, not the surface's 0.8
            self.assertEqual((face["stiffness_above_device"], face["stiffness_study"]), (True, "NeckStudy"))
            # 1 mm deep at 3 N/mm (the push and its friction held to the 3 N force limit), not the surface's 0.8
            self.assertGreater(face["mean_normal_force_n"], 2.5)
            said = (f"hapticad demo: {stroke['face']} (Neck): NeckStudy's bending beam (4.44 N/mm) replaces the "
                    "surface's 0.8 N/mm; it is above the 3 N/mm the device renders stably")
            self.assertIn(said, proc.stderr)
            self.assertTrue(stroke["notes"][0].startswith(said[len("hapticad demo: "):]), stroke["notes"])

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
