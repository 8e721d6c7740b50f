# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad cohort` end to end: a document's stiffness study and its participants'
preferences, as statistics (JSON and text) and CSV; bad input gets a clear error (exit 2).

Environment: HAPTICAD_CLI (the launcher), HAPTICAD_MOD (the staged Mod folder).
Runs under /usr/bin/python3 (FreeCAD's interpreter)."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import unittest

CLI = os.environ["HAPTICAD_CLI"]
sys.path.insert(0, os.environ["HAPTICAD_MOD"])
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))

from hapticad.freecad_env import ensure_freecad  # noqa: E402
from other_user import run_as_nobody, shared_folder  # noqa: E402

App = ensure_freecad()
import HaptiCAD  # noqa: E402

assert HaptiCAD.__file__.startswith(os.environ["HAPTICAD_MOD"]), HaptiCAD.__file__


def run_cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=120)


class CohortCommandTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.path = os.path.join(cls.tmp.name, "toothbrush.FCStd")
        doc = App.newDocument("CliCohort")
        box = doc.addObject("Part::Box", "Head")
        doc.recompute()
        surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="PP", FeelRoughness=False)
        study = HaptiCAD.make_study(doc, surface, YoungsModulus=1.5, BeamWidth=5, BeamLength=60)
        study.Label = "Neck"
        # seed 000's Table 3: 4.5, 3.5 and 3.5 N/mm, made by the neck's thickness
        for name, gender, age, weight, height, k in (("Steven", "M", "26-40", 70, 1700, 4.5),
                                                     ("Yang", "M", "41-60", 60, 1680, 3.5),
                                                     ("Zhang", "F", "26-40", 52, 1650, 3.5)):
            study.BeamThickness = 4.0 * (k / study.BendingStiffness * study.BeamThickness ** 3 / 64) ** (1 / 3)
            HaptiCAD.record_preference(study, name, gender, age, weight, height)
        study.BeamThickness = 4.0
        doc.saveAs(cls.path)
        App.closeDocument(doc.Name)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_statistics_of_the_cohort(self):
        out_csv = os.path.join(self.tmp.name, "neck.csv")
        proc = run_cli("cohort", self.path, "--json", "--csv", out_csv)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        (study,) = json.loads(proc.stdout)
        self.assertEqual((study["study"], study["participants"], study["unit"]), ("Neck", 3, "N/mm"))
        rows = {r["group"]: r for r in study["statistics"]}
        self.assertAlmostEqual(rows["all"]["mean"], 11.5 / 3, places=6)
        self.assertAlmostEqual(rows["gender M"]["mean"], 4.0, places=6)
        self.assertIn("0% of the 3 participants preferred less", study["design_among_preferences"])
        with open(out_csv) as handle:
            self.assertEqual([r["name"] for r in csv.DictReader(handle)], ["Steven", "Yang", "Zhang"])
        text = run_cli("cohort", self.path)
        self.assertEqual(text.returncode, 0, text.stderr)
        self.assertIn("Neck (Bending beam): design 0.556 N/mm, 3 participants", text.stdout)

    def test_a_study_switched_to_the_other_model_keeps_and_exports_every_record(self):
        doc = App.openDocument(self.path)
        try:
            (study,) = HaptiCAD.studies_of(doc)
            study.Model = "Push button"
            switched = os.path.join(self.tmp.name, "switched.FCStd")
            doc.saveAs(switched)
        finally:
            App.closeDocument(doc.Name)
        out_csv = os.path.join(self.tmp.name, "all.csv")
        proc = run_cli("cohort", switched, "--json", "--csv", out_csv)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        (study,) = json.loads(proc.stdout)
        self.assertEqual((study["participants"], study["other_unit"], study["unit"]), (0, 3, "N"))
        with open(out_csv) as handle:  # all three, each with its unit: nothing lost
            self.assertEqual([(r["name"], r["unit"]) for r in csv.DictReader(handle)],
                             [("Steven", "N/mm"), ("Yang", "N/mm"), ("Zhang", "N/mm")])
        self.assertEqual(study["other_note"], "3 made with the bending beam model (N/mm) are kept but not compared "
                                              "with the operating force; the study's Participants (3) counts everyone "
                                              "with a record, of any unit")
        text = run_cli("cohort", switched).stdout
        self.assertIn("0 participants (3 made with the bending beam model (N/mm) are kept but not compared", text)

    def test_starred_preferences_are_counted_and_said_as_the_panel_does(self):
        doc = App.newDocument("CliCohortButton")
        try:
            box = doc.addObject("Part::Box", "Cap")
            doc.recompute()
            study = HaptiCAD.make_study(doc, HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS"),
                                        model="Push button")
            study.Label = "Button"
            # Omron B3F's 1.47 N: 5.9 N/mm to its operating point, beyond the 3 N/mm device; 0.5 N is not
            for name, force in (("Ann", 1.47), ("Bo", 0.5)):
                study.OperatingForce = force
                HaptiCAD.record_preference(study, name, "F", "26-40", None, None, 3000.0)
            path = os.path.join(self.tmp.name, "button.FCStd")
            doc.saveAs(path)
        finally:
            App.closeDocument(doc.Name)
        proc = run_cli("cohort", path, "--json")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        (study,) = json.loads(proc.stdout)
        note = ("* 1 preference steeper than the device renders stably, its forces felt as designed over a longer "
                "travel; counted as recorded.")
        self.assertEqual((study["beyond_device"], study["beyond_device_note"]), (1, note))
        text = run_cli("cohort", path).stdout
        self.assertIn("Button (Push button): design 0.5 N, 2 participants\n", text)
        self.assertIn(f"  {note}", text)
        self.assertNotIn("at its limit", text)
        # one participant is one
        single = run_cli("cohort", self.path).stdout
        self.assertNotIn("*", single)
        doc = App.openDocument(self.path)
        try:
            (neck,) = HaptiCAD.studies_of(doc)
            stiffness_study_records = json.loads(neck.Cohort)[:1]
            neck.Cohort = json.dumps(stiffness_study_records)
            neck.Participants = 1
            one = os.path.join(self.tmp.name, "one.FCStd")
            doc.saveAs(one)
        finally:
            App.closeDocument(doc.Name)
        self.assertIn("Neck (Bending beam): design 0.556 N/mm, 1 participant\n", run_cli("cohort", one).stdout)
        # a group of one has no SD: "-" in text, null in JSON (it read 0, as if everyone agreed)
        self.assertRegex(run_cli("cohort", one).stdout, r"\n  all +n 1 +mean 4.5 sd - median 4.5 ")
        (alone,) = json.loads(run_cli("cohort", one, "--json").stdout)
        self.assertEqual([row["sd"] for row in alone["statistics"]], [None, None, None])
        # the same person's second session: still one participant, at the mean of the two
        doc = App.openDocument(one)
        try:
            (neck,) = HaptiCAD.studies_of(doc)
            (steven,) = json.loads(neck.Cohort)
            neck.Cohort = json.dumps([steven, dict(steven, value=steven["value"] + 1.0, recorded="")])
            twice = os.path.join(self.tmp.name, "twice.FCStd")
            doc.saveAs(twice)
        finally:
            App.closeDocument(doc.Name)
        self.assertIn("Neck (Bending beam): design 0.556 N/mm, 1 participant in 2 records\n",
                      run_cli("cohort", twice).stdout)
        (again,) = json.loads(run_cli("cohort", twice, "--json").stdout)
        self.assertEqual((again["participants"], again["records"]), (1, 2))
        self.assertEqual((again["statistics"][0]["n"], again["statistics"][0]["records"]), (1, 2))
        self.assertAlmostEqual(again["statistics"][0]["mean"], 5.0)

    def test_a_preference_above_the_force_limit_is_counted_apart_and_said(self):
        doc = App.newDocument("CliCohortForce")
        try:
            box = doc.addObject("Part::Box", "Cap")
            doc.recompute()
            study = HaptiCAD.make_study(doc, HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS"),
                                        model="Push button")
            # the force limit 3 N: 4.5 N stops at 3 N and its click never comes
            for name, force in (("Ann", 1.47), ("Bo", 2.0), ("Cy", 4.5)):
                study.OperatingForce = force
                HaptiCAD.record_preference(study, name, "F", "26-40", None, None, 3000.0, 3.0)
            path = os.path.join(self.tmp.name, "force.FCStd")
            doc.saveAs(path)
        finally:
            App.closeDocument(doc.Name)
        (study,) = json.loads(run_cli("cohort", path, "--json").stdout)
        self.assertEqual((study["participants"], study["beyond_device"], study["beyond_force_limit"]), (3, 2, 1))
        self.assertEqual((study["statistics"][0]["n"], study["statistics"][0]["max"]), (2, 2.0))
        self.assertIn("† 1 preference above the force limit (3 N): the force stopped there and the click was never "
                      "felt; left out of the statistics", study["beyond_device_note"])
        self.assertIn("† 1 preference above the force limit (3 N)", run_cli("cohort", path).stdout)

    def test_a_hand_edited_cohort_is_named_and_the_rest_still_told(self):
        # a record lacking a key stopped the whole command ("Record.__init__() missing 1 required
        # positional argument: 'gender'"), and one unreadable study stopped the others' summary
        doc = App.openDocument(self.path)
        try:
            (neck,) = HaptiCAD.studies_of(doc)
            stored = json.loads(neck.Cohort)
            del stored[1]["gender"]
            neck.Cohort = json.dumps(stored)
            handle = doc.addObject("Part::Box", "Handle")
            doc.recompute()
            grip = HaptiCAD.make_surface(doc, [(handle, "Face6")], material="PP", FeelRoughness=False)
            broken = HaptiCAD.make_study(doc, grip, YoungsModulus=1.5)
            broken.Label = "Grip study"
            broken.Cohort = "[{not json"
            edited = os.path.join(self.tmp.name, "edited.FCStd")
            doc.saveAs(edited)
        finally:
            App.closeDocument(doc.Name)
        proc = run_cli("cohort", edited)
        self.assertEqual(proc.returncode, 1, proc.stderr)
        self.assertIn("Neck (Bending beam): design 0.556 N/mm, 2 participants", proc.stdout)
        self.assertIn("Neck: stored record 2 of 3 (Yang) cannot be read: it lacks gender; left out of the statistics",
                      proc.stdout)
        self.assertIn("hapticad cohort: Grip study: the stored cohort is not readable JSON", proc.stderr)
        proc = run_cli("cohort", edited, "--json")
        self.assertEqual(proc.returncode, 1, proc.stderr)
        neck, grip = sorted(json.loads(proc.stdout), key=lambda s: s["study"] != "Neck")
        self.assertEqual(neck["participants"], 2)
        self.assertEqual(len(neck["unread"]), 1)
        self.assertEqual(grip, {"study": "Grip study", "error": "Grip study: the stored cohort is not readable JSON"})
        # the one study asked for, unreadable: refused (exit 2); its CSV would lose a record: refused
        self.assertEqual(run_cli("cohort", edited, "--study", "Grip study").returncode, 2)
        out_csv = os.path.join(self.tmp.name, "edited.csv")
        proc = run_cli("cohort", edited, "--study", "Neck", "--csv", out_csv)
        self.assertEqual(proc.returncode, 2, proc.stdout)
        self.assertIn("it lacks gender", proc.stderr)
        self.assertFalse(os.path.exists(out_csv))

    def test_bad_input_is_refused(self):
        for args, message in ((("cohort", os.path.join(self.tmp.name, "none.FCStd")), "no such file"),
                              (("cohort", self.path, "--study", "Handle"), "no stiffness study named 'Handle' "
                                                                          "(it has: Neck)")):
            with self.subTest(message=message):
                proc = run_cli(*args)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)


    def test_an_empty_or_folder_csv_name_is_refused(self):
        for name, message in (("", "argument --csv: an empty name: give the CSV file to write, like cohort.csv"),
                              (self.tmp.name, f"argument --csv: {self.tmp.name} is a folder: give the CSV file to "
                                              f"write in it, like {os.path.join(self.tmp.name, 'cohort.csv')}")):
            with self.subTest(name=name):
                proc = run_cli("cohort", self.path, "--csv", name)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)
                self.assertEqual(proc.stdout, "")

    def test_the_csv_is_never_written_over_the_document_read(self):
        # `--csv c2.FCStd` wrote the table over the document: the study and every record were gone
        with tempfile.TemporaryDirectory() as tmp:
            doc = os.path.join(tmp, "c2.FCStd")
            with open(self.path, "rb") as source:
                held = source.read()
            with open(doc, "wb") as copy:
                copy.write(held)
            os.symlink(doc, os.path.join(tmp, "linked.csv"))
            os.link(doc, os.path.join(tmp, "hard.csv"))
            other = os.path.join(tmp, "other.csv")  # another FreeCAD document, whatever its name
            with open(other, "wb") as copy:
                copy.write(held)
            for target, message in (
                    (doc, f"argument --csv: {doc}: the table is a CSV file, so the name must end in .csv (like "
                          f"{os.path.join(tmp, 'c2.csv')}), not .FCStd"),
                    (os.path.join(tmp, "linked.csv"), f"argument --csv: {os.path.join(tmp, 'linked.csv')} is a "
                                                      "FreeCAD document: writing the CSV over it would lose it"),
                    (os.path.join(tmp, "hard.csv"), f"{os.path.join(tmp, 'hard.csv')} is a FreeCAD document"),
                    (other, f"{other} is a FreeCAD document")):
                with self.subTest(target=target):
                    proc = run_cli("cohort", doc, "--study", "Neck", "--csv", target)
                    self.assertEqual(proc.returncode, 2, proc.stderr)
                    self.assertIn(message, proc.stderr)
                    self.assertEqual(proc.stdout, "")
            for path in (doc, other):
                with open(path, "rb") as kept:
                    self.assertEqual(kept.read(), held, path)
            self.assertIn("Neck (Bending beam)", run_cli("cohort", doc).stdout)

    def test_a_csv_name_ends_in_csv(self):
        with tempfile.TemporaryDirectory() as tmp:
            bare = os.path.join(tmp, "neck")  # gets .csv, as a plot's name gets .png
            proc = run_cli("cohort", self.path, "--csv", bare)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertFalse(os.path.exists(bare))
            with open(bare + ".csv", encoding="utf-8") as handle:
                self.assertEqual([r["name"] for r in csv.DictReader(handle)], ["Steven", "Yang", "Zhang"])
            self.assertEqual(run_cli("cohort", self.path, "--csv", os.path.join(tmp, "NECK.CSV")).returncode, 0)
            text = os.path.join(tmp, "neck.txt")
            proc = run_cli("cohort", self.path, "--csv", text)
            self.assertEqual(proc.returncode, 2, proc.stderr)
            self.assertIn(f"argument --csv: {text}: the table is a CSV file, so the name must end in .csv (like "
                          f"{bare}.csv), not .txt", proc.stderr)
            self.assertFalse(os.path.exists(text))

    def test_a_csv_in_a_missing_folder_is_said_by_the_name_given(self):
        # it said "[Errno 2] No such file or directory: 'nodir/x.csv.part'"
        missing = os.path.join(self.tmp.name, "nodir", "x.csv")
        proc = run_cli("cohort", self.path, "--csv", missing)
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn(f"argument --csv: {missing}: there is no folder {os.path.dirname(missing)}", proc.stderr)
        self.assertNotIn(".part", proc.stderr)

    def test_a_csv_read_only_for_the_user_or_behind_a_link_is_not_replaced(self):
        # a folder the user may write in let the CSV replace a read-only file, and a link
        # became a plain file (the file it pointed to kept the old table)
        import shutil

        place = shared_folder(self)
        shutil.copy(self.path, place)
        document = os.path.join(place, "toothbrush.FCStd")
        folder = os.path.join(place, "out")
        os.mkdir(folder)
        os.chmod(folder, 0o777)
        read_only = os.path.join(folder, "kept.csv")
        for path in (read_only, os.path.join(folder, "real.csv")):
            with open(path, "w", encoding="utf-8") as handle:
                handle.write("old\n")
        os.chmod(read_only, 0o444)
        os.chmod(os.path.join(folder, "real.csv"), 0o666)
        os.symlink("real.csv", os.path.join(folder, "link.csv"))
        proc = run_as_nobody(place, [CLI, "cohort", document, "--csv", read_only])
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn(f"{read_only}: the file is read-only for you, so it was not written over", proc.stderr)
        with open(read_only, encoding="utf-8") as handle:
            self.assertEqual(handle.read(), "old\n")
        proc = run_as_nobody(place, [CLI, "cohort", document, "--csv", os.path.join(folder, "link.csv")])
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertTrue(os.path.islink(os.path.join(folder, "link.csv")))
        with open(os.path.join(folder, "real.csv"), encoding="utf-8") as handle:
            self.assertEqual([r["name"] for r in csv.DictReader(handle)], ["Steven", "Yang", "Zhang"])
        self.assertEqual(os.stat(os.path.join(folder, "real.csv")).st_mode & 0o777, 0o666)  # its permissions kept
        self.assertEqual(sorted(os.listdir(folder)), ["kept.csv", "link.csv", "real.csv"])

    @unittest.skipUnless(os.path.isdir("/proc/self"), "needs Linux's /proc, where no file can be made")
    def test_a_file_that_cannot_be_written_is_said_without_errno_or_temporary_name(self):
        proc = run_cli("cohort", self.path, "--csv", "/proc/hapticad-cohort.csv")
        self.assertEqual(proc.returncode, 2, proc.stderr)
        self.assertIn("hapticad cohort: /proc/hapticad-cohort.csv: No such file or directory", proc.stderr)
        self.assertNotIn(".part", proc.stderr)
        self.assertNotIn("Errno", proc.stderr)


if __name__ == "__main__":
    unittest.main()
