# SPDX-License-Identifier: GPL-3.0-or-later
"""A similarity study's answers as CSV: every answer of every kept run in the order given
(warm-ups and classings included), runs kept before the order was recorded, the pooled
flag, each row's stimulus values, spreadsheet-safe names."""
import csv
import errno
import json
import os
import tempfile
import unittest
from unittest import mock

import FreeCAD as App

import HaptiCAD
from hapticad import similarity_export, similarity_study as ss


def answered(run, rating=4):
    """A scripted participant: feels each trial's textures, rates every pair ``rating``,
    classes every texture A."""
    while not run.done:
        run.present_each()
        run.answer("A" if run.current.kind == "class" else rating)
    return run


class ExportTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("ExportTest")
        plate = self.doc.addObject("Part::Box", "Plate")
        samples = self.doc.addObject("Part::Box", "Samples")
        self.doc.recompute()
        surface = HaptiCAD.make_surface(self.doc, [(plate, "Face6")], material="ABS", FeelRoughness=False)
        a = HaptiCAD.make_surface(self.doc, [(samples, "Face1")], material="ABS", Texture="Custom", TextureDC=0.2)
        b = HaptiCAD.make_surface(self.doc, [(samples, "Face2")], material="ABS", Texture="Custom", TextureDC=0.8)
        self.study = HaptiCAD.make_similarity_study(self.doc, surface, items=ss.paper_stimuli()[:3],
                                                    ReferenceA=a, ReferenceB=b,
                                                    WarmUps=2, Repeats=1)
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "answers.csv")

    def tearDown(self):
        for study in ss.similarity_studies_of(self.doc):
            ss.stop_presenting(study)
        App.closeDocument(self.doc.Name)
        self.tmp.cleanup()

    def read(self):
        with open(self.path, newline="", encoding="utf-8") as handle:
            return list(csv.DictReader(handle))

    def test_every_answer_in_the_order_given_with_its_stimuli(self):
        run = answered(ss.Run(self.study, "Ada", seed=3), rating=5)
        ss.record_run(self.study, run)
        self.assertEqual(similarity_export.write_csv(self.path, self.study), 2 + 3 + 3)
        rows = self.read()
        self.assertEqual([r["kind"] for r in rows], ["warm-up"] * 2 + ["pair"] * 3 + ["class"] * 3)
        self.assertEqual([r["position"] for r in rows], [str(k) for k in range(1, 9)])
        names = [s["name"] for s in ss.stimuli(self.study)]
        for row, trial in zip(rows, run.trials):  # as presented: the first texture felt first
            self.assertEqual(row["first"], names[trial.first])
            self.assertEqual(row["second"], names[trial.second] if trial.kind != "class" else "")
        self.assertEqual({(r["rating"], r["class"]) for r in rows if r["kind"] != "class"}, {("5", "")})
        self.assertEqual({(r["rating"], r["class"]) for r in rows if r["kind"] == "class"}, {("", "A")})
        values = {s["name"]: s["values"] for s in ss.stimuli(self.study)}
        for row in rows:
            self.assertEqual(float(row["first_f_vis"]), values[row["first"]]["TextureViscosity"])
            self.assertEqual(row["second_f_DC"] == "", row["kind"] == "class")
        self.assertEqual((rows[0]["participant"], rows[0]["steps"], rows[0]["seed"]), ("Ada", "7", "3"))
        self.assertTrue(rows[0]["started"] and rows[0]["started"] <= rows[0]["recorded"])  # when it began
        # a warm-up is never analysed: "yes" had a statistician filtering on it mix them in
        self.assertEqual({(r["kind"], r["pooled"]) for r in rows},
                         {("warm-up", "no"), ("pair", "yes"), ("class", "yes")})
        # the references swapped: the ratings still pool, the classings no longer do
        self.study.ReferenceA, self.study.ReferenceB = self.study.ReferenceB, self.study.ReferenceA
        similarity_export.write_csv(self.path, self.study)
        self.assertEqual({(r["kind"], r["pooled"]) for r in self.read()},
                         {("warm-up", "no"), ("pair", "yes"), ("class", "no")})

    def test_older_runs_unpooled_runs_and_formula_like_names(self):
        ss.record_run(self.study, answered(ss.Run(self.study, "=HYPERLINK()", seed=1)))
        # a run kept before the order was recorded: its pairs and classes, no positions
        old = answered(ss.Run(self.study, "Bob", seed=2)).as_record()
        del old["trials"]
        ss.record_run(self.study, old)
        # the stimuli change: both runs are kept, written, and no longer pooled
        items = ss.stimuli(self.study)
        items[0]["values"]["TextureDC"] += 0.05
        ss.set_stimuli(self.study, items)
        similarity_export.write_csv(self.path, self.study)
        rows = self.read()
        first = [r for r in rows if r["participant"] == "'=HYPERLINK()"]
        bob = [r for r in rows if r["participant"] == "Bob"]
        self.assertEqual((len(first), len(bob)), (8, 6))  # Bob's warm-ups were never kept
        self.assertEqual({r["position"] for r in bob}, {""})
        self.assertEqual([r["kind"] for r in bob], ["pair"] * 3 + ["class"] * 3)
        self.assertEqual({r["pooled"] for r in rows}, {"no"})
        # the values each run felt, not the study's new ones
        self.assertIn(float(bob[0]["first_f_DC"]), [s["values"]["TextureDC"] for s in old["stimuli"]])

    def test_a_study_without_runs_and_a_damaged_order_are_refused(self):
        with self.assertRaises(ValueError) as caught:
            similarity_export.write_csv(self.path, self.study)
        self.assertIn("no participant's run is kept yet: nothing to export", str(caught.exception))
        self.assertFalse(os.path.exists(self.path))
        record = answered(ss.Run(self.study, "Cy", seed=4)).as_record()
        record["trials"][3][2] = 17  # a stimulus the run did not have
        self.assertIn("Cy: the trial order names a stimulus it does not have", ss.record_problems(record))
        with self.assertRaises(ValueError):
            ss.record_run(self.study, record)
        self.assertEqual(json.loads(self.study.Responses or "[]"), [])

    def test_a_write_that_fails_half_way_leaves_the_file_there_as_it_was(self):
        # the disk fills after the header: the earlier export stays whole, nothing is left beside it
        with open(self.path, "w", encoding="utf-8") as handle:
            handle.write("an earlier export\n")
        ss.record_run(self.study, answered(ss.Run(self.study, "Ada", seed=3)))

        def disk_full(writer, rows):
            writer.writerow(rows[0])
            raise OSError(errno.ENOSPC, "No space left on device")

        with mock.patch.object(csv.DictWriter, "writerows", disk_full), \
                self.assertRaisesRegex(OSError, "No space left"):
            similarity_export.write_csv(self.path, self.study)
        with open(self.path, encoding="utf-8") as handle:
            self.assertEqual(handle.read(), "an earlier export\n")
        self.assertEqual(os.listdir(self.tmp.name), ["answers.csv"])
        self.assertEqual(similarity_export.write_csv(self.path, self.study), 8)  # and it writes when it can
        self.assertEqual(len(self.read()), 8)


if __name__ == "__main__":
    unittest.main()
