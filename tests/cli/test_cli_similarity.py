# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad similarity` end to end: a document's similarity study, its participants'
runs, the perceptual space as JSON, text and a plot; bad input gets a clear error (exit 2).

Environment: HAPTICAD_CLI (the launcher), HAPTICAD_MOD (the staged Mod folder).
Runs under /usr/bin/python3 (FreeCAD's interpreter)."""
import csv
import json
import os
import random
import subprocess
import sys
import tempfile
import unittest

import numpy as np

CLI = os.environ["HAPTICAD_CLI"]
sys.path.insert(0, os.environ["HAPTICAD_MOD"])

from hapticad.freecad_env import ensure_freecad  # noqa: E402

App = ensure_freecad()
import HaptiCAD  # noqa: E402
from hapticad import similarity_study as ss  # noqa: E402


def run_cli(*args):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=120)


def rate(run, seed):
    """A participant who tells textures apart by their DC friction alone."""
    rng = random.Random(seed)
    while not run.done:
        t = run.current
        run.present_each()
        a, b = (run.stimuli[i]["values"]["TextureDC"] for i in (t.first, t.second))
        alike = 1 - abs(a - b) / 0.35 + rng.gauss(0, 0.05)
        run.answer(int(min(run.steps, max(1, round(1 + alike * (run.steps - 1))))))
    return run


class SimilarityCommandTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.path = os.path.join(cls.tmp.name, "gratings.FCStd")
        doc = App.newDocument("CliSimilarity")
        box = doc.addObject("Part::Box", "Plate")
        doc.recompute()
        surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False)
        study = HaptiCAD.make_similarity_study(doc, surface, WarmUps=0)
        study.Label = "Gratings"
        for p in range(4):
            ss.record_run(study, rate(ss.Run(study, f"P{p}", seed=p), 10 + p))
        HaptiCAD.make_similarity_study(doc, HaptiCAD.make_surface(doc, [(box, "Face1")]), name="Empty")
        doc.saveAs(cls.path)
        App.closeDocument(doc.Name)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_the_space_of_one_study_as_json_and_a_plot(self):
        png = os.path.join(self.tmp.name, "space.png")
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--json", "--plot", png)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        (study,) = json.loads(proc.stdout)
        self.assertEqual((study["study"], study["participants"], len(study["points"])), ("Gratings", 4, 9))
        # friction alone made the ratings: its vector is long and the points line up on it
        self.assertGreater(study["vectors"]["f_DC"]["correlation"], 0.95)
        self.assertGreater(study["vectors"]["f_DC"]["length"], 3 * study["vectors"]["f_vis"]["length"])
        with open(png, "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertGreater(os.path.getsize(png), 20000)

    def test_every_answer_as_csv_and_the_matrix_in_the_json(self):
        answers = os.path.join(self.tmp.name, "answers.csv")
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--json", "--csv", answers)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        (study,) = json.loads(proc.stdout)
        with open(answers, newline="", encoding="utf-8") as handle:
            rows = list(csv.DictReader(handle))
        per_run = 36  # 9 stimuli: 36 pairs; no warm-ups, no references to class by
        self.assertEqual((study["csv"], study["answers"], len(rows)), (answers, 4 * per_run, 4 * per_run))
        self.assertEqual([r["participant"] for r in rows[::per_run]], ["P0", "P1", "P2", "P3"])
        self.assertEqual([int(r["position"]) for r in rows[:per_run]], list(range(1, per_run + 1)))
        self.assertEqual({r["pooled"] for r in rows}, {"yes"})
        pairs = [r for r in rows if r["kind"] == "pair"]
        self.assertEqual(len(pairs), len(rows))
        self.assertTrue(all(1 <= int(r["rating"]) <= 7 and r["class"] == "" for r in pairs))
        # the matrix the space is drawn from, back from the rows: 1 - the mean rating scaled to 0..1
        names = study["stimuli"]
        d = np.array(study["dissimilarity"])
        self.assertEqual(d.shape, (9, 9))
        np.testing.assert_allclose(d, d.T)
        for i, j in ((0, 1), (2, 7)):
            ratings = [int(r["rating"]) for r in pairs if {r["first"], r["second"]} == {names[i], names[j]}]
            self.assertEqual(len(ratings), 4)
            self.assertAlmostEqual(d[i, j], 1 - np.mean([(x - 1) / 6 for x in ratings]), places=12)
        # each row carries its stimuli's values, as the JSON lists them
        row = pairs[0]
        first = study["stimulus_values"][names.index(row["first"])]
        self.assertEqual(float(row["first_f_DC"]), first["TextureDC"])
        # text mode says where they went
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--csv", answers)
        self.assertIn(f"answers: {answers} (144 rows)", proc.stdout)

    def test_text_summary(self):
        proc = run_cli("similarity", self.path, "--study", "Gratings")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("Gratings: 9 stimuli, 4 participants", proc.stdout)
        self.assertRegex(proc.stdout, r"f_DC +\|p\| \d\.\d{3}  r (0\.9[5-9]|1\.00)")

    def test_ordinal_scaling_asked_for_on_the_command_line(self):
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--scaling", "ordinal", "--json")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        (study,) = json.loads(proc.stdout)
        self.assertEqual(study["scaling"], "ordinal")
        self.assertGreater(study["iterations"], 0)
        self.assertGreater(study["vectors"]["f_DC"]["correlation"], 0.95)
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--scaling", "ordinal")
        self.assertIn("ordinal scaling, Kruskal's stress-1", proc.stdout)
        # the document keeps its own choice
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--json")
        self.assertEqual(json.loads(proc.stdout)[0]["scaling"], "metric")
        proc = run_cli("similarity", self.path, "--scaling", "kruskal")
        self.assertEqual(proc.returncode, 2)
        self.assertIn("invalid choice: 'kruskal'", proc.stderr)

    def test_every_study_of_a_document_one_without_runs_told_not_fatal(self):
        proc = run_cli("similarity", self.path, "--json")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        gratings, empty = json.loads(proc.stdout)
        self.assertEqual(gratings["participants"], 4)
        self.assertIn("no participant has rated these stimuli yet", empty["error"])
        proc = run_cli("similarity", self.path)
        self.assertIn("Gratings: 9 stimuli, 4 participants", proc.stdout)
        self.assertIn("\nEmpty: no participant has rated these stimuli yet", proc.stdout)

    def test_bad_input_gets_a_clear_error(self):
        for args, message in ((["--study", "Nope"], "no similarity study named 'Nope' (it has: Gratings, Empty)"),
                              (["--study", "Empty"], "Empty: no participant has rated these stimuli yet"),
                              (["--plot", os.path.join(self.tmp.name, "x.png")], "--plot draws one study's space"),
                              # an empty name (a script's unset variable) used to mean every study
                              (["--study", ""], "--study needs a study's name or label (it has: Gratings, Empty)"),
                              (["--csv", os.path.join(self.tmp.name, "a.csv")], "--csv writes one study's answers"),
                              (["--study", "Empty", "--csv", os.path.join(self.tmp.name, "a.csv")],
                               "Empty: no participant's run is kept yet: nothing to export")):
            proc = run_cli("similarity", self.path, *args)
            self.assertEqual(proc.returncode, 2, proc.stdout)
            self.assertIn(message, proc.stderr)
            self.assertNotIn("Traceback", proc.stderr)
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "x.png")))


    def test_the_plot_reported_is_the_file_written_and_a_png(self):
        base = os.path.join(self.tmp.name, "space_noext")
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--json", "--plot", base)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(json.loads(proc.stdout)[0]["plot"], base + ".png")
        with open(base + ".png", "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        self.assertFalse(os.path.exists(base))
        proc = run_cli("similarity", self.path, "--study", "Gratings", "--plot", base)
        self.assertIn(f"plot: {base}.png", proc.stdout)
        txt = os.path.join(self.tmp.name, "space.txt")
        for plot, message in ((txt, f"argument --plot: {txt}: the plot is a PNG image, so the name must end in "
                                    f".png (like {os.path.join(self.tmp.name, 'space.png')}), not .txt"),
                              (self.tmp.name, f"argument --plot: {self.tmp.name} is a folder"),
                              ("", "argument --plot: an empty name: give the PNG file to write, like plot.png")):
            with self.subTest(plot=plot):
                proc = run_cli("similarity", self.path, "--study", "Gratings", "--plot", plot)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)
                self.assertNotIn("Traceback", proc.stderr)
        self.assertFalse(os.path.exists(txt))

    def test_the_answers_and_the_plot_are_never_written_over_the_document_read(self):
        # `--csv s2.FCStd` wrote the answers over the document: the study and every run were gone
        with tempfile.TemporaryDirectory() as tmp:
            doc = os.path.join(tmp, "s2.FCStd")
            with open(self.path, "rb") as source:
                held = source.read()
            with open(doc, "wb") as copy:
                copy.write(held)
            os.link(doc, os.path.join(tmp, "hard.csv"))
            os.symlink(doc, os.path.join(tmp, "linked.png"))
            for option, target, message in (
                    ("--csv", doc, f"argument --csv: {doc}: the table is a CSV file, so the name must end in .csv"),
                    ("--csv", os.path.join(tmp, "hard.csv"), f"argument --csv: {os.path.join(tmp, 'hard.csv')} is a "
                                                             "FreeCAD document: writing the CSV over it would lose it"),
                    ("--plot", os.path.join(tmp, "linked.png"),
                     f"argument --plot: {os.path.join(tmp, 'linked.png')} is a FreeCAD document")):
                with self.subTest(option=option, target=target):
                    proc = run_cli("similarity", doc, "--study", "Gratings", option, target)
                    self.assertEqual(proc.returncode, 2, proc.stderr)
                    self.assertIn(message, proc.stderr)
                    self.assertEqual(proc.stdout, "")
            with open(doc, "rb") as kept:
                self.assertEqual(kept.read(), held)
            self.assertEqual(run_cli("similarity", doc, "--study", "Gratings").returncode, 0)
            # a bare name gets .csv
            proc = run_cli("similarity", doc, "--study", "Gratings", "--json", "--csv", os.path.join(tmp, "answers"))
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertEqual(json.loads(proc.stdout)[0]["csv"], os.path.join(tmp, "answers.csv"))
            self.assertTrue(os.path.isfile(os.path.join(tmp, "answers.csv")))


if __name__ == "__main__":
    unittest.main()
