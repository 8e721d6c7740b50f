# SPDX-License-Identifier: GPL-3.0-or-later
"""Cohort records and statistics, on seed 000's Table 3."""
import os
import tempfile
import unittest

from hapticad import cohort

TABLE_3 = [
    cohort.Record("Steven", "M", "26-40", 70, 1700, 4.5, "N/mm", "Bending beam"),
    cohort.Record("Yang", "M", "41-60", 60, 1680, 3.5, "N/mm", "Bending beam"),
    cohort.Record("Zhang", "F", "26-40", 52, 1650, 3.5, "N/mm", "Bending beam"),
]


class CohortTest(unittest.TestCase):
    def test_statistics_of_table_3_by_gender_and_age(self):
        rows = {r["group"]: r for r in cohort.statistics(TABLE_3)}
        self.assertEqual(rows["all"]["n"], 3)
        self.assertAlmostEqual(rows["all"]["mean"], 11.5 / 3)
        self.assertAlmostEqual(rows["all"]["sd"], 0.57735, places=5)
        self.assertEqual(rows["all"]["median"], 3.5)
        self.assertAlmostEqual(rows["gender M"]["mean"], 4.0)
        self.assertAlmostEqual(rows["gender M"]["sd"], 0.70711, places=5)
        self.assertEqual((rows["gender F"]["n"], rows["gender F"]["sd"]), (1, 0.0))
        self.assertAlmostEqual(rows["age band 26-40"]["mean"], 4.0)
        self.assertEqual(rows["age band 41-60"]["max"], 3.5)
        self.assertEqual(list(rows)[:3], ["all", "gender F", "gender M"])
        self.assertEqual(cohort.statistics([]), [])

    def test_a_design_is_placed_among_the_preferences(self):
        more = TABLE_3 + [cohort.Record(f"P{i}", "F", "18-25", 60, 1600, v, "N/mm", "Bending beam")
                          for i, v in enumerate((2.0, 5.0, 6.0))]
        below, text = cohort.place_design(0.56, more)
        self.assertEqual(below, 0.0)
        self.assertIn("below the middle half", text)
        below, text = cohort.place_design(4.0, more)
        self.assertAlmostEqual(below, 3 / 6)
        self.assertIn("within the middle half", text)
        self.assertEqual(cohort.place_design(1.0, []), (None, "no participant has recorded a preference yet"))
        # few preferences: where the design stands against them, said as it is
        two = more[:2]  # 4.5 and 3.5
        self.assertIn("1.09 is below all 2 preferences (3.5-4.5)", cohort.place_design(1.09, two)[1])
        self.assertIn("5 is above all 2 preferences", cohort.place_design(5.0, two)[1])
        self.assertIn("4 is within the 2 preferences", cohort.place_design(4.0, two)[1])
        self.assertIn("above the one preference so far (4.5)", cohort.place_design(5.0, more[:1])[1])

    def test_a_record_that_cannot_be_kept_says_why(self):
        bad = cohort.Record(" ", "X", "young", 5, 90000, float("nan"), "N/mm", "Bending beam")
        found = " | ".join(cohort.problems(bad))
        for part in ("needs a name", "gender 'X'", "age band 'young'", "weight 5 kg", "height 90000 mm",
                     "must be a number > 0"):
            self.assertIn(part, found)
        self.assertEqual(cohort.problems(TABLE_3[0]), [])

    def test_csv_round_trip_and_a_bad_line_is_named(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cohort.csv")
            first = cohort.Record("Ana", "F", "18-25", 58, 1620, 0.9, "N/mm", "Bending beam",
                                  {"BeamThickness": 4.5, "BendingStiffness": 0.9}, "2026-11-24T10:00:00")
            cohort.write_csv(path, [first, *TABLE_3])
            back = cohort.read_csv(path)
            self.assertEqual(len(back), 4)
            self.assertEqual((back[0].name, back[0].value, back[0].design["BeamThickness"]), ("Ana", 0.9, "4.5"))
            self.assertEqual(back[1].as_dict()["gender"], "M")
            # weight and height not given: empty cells, and back as not given
            quiet = cohort.Record("Quinn", "not given", "not given", None, None, 1.2, "N/mm", "Bending beam")
            self.assertEqual(cohort.problems(quiet), [])
            cohort.write_csv(os.path.join(tmp, "quiet.csv"), [quiet])
            (again,) = cohort.read_csv(os.path.join(tmp, "quiet.csv"))
            self.assertEqual((again.weight_kg, again.height_mm, again.value), (None, None, 1.2))
            # a spreadsheet's "CSV UTF-8" starts with a BOM; its formulas are not run
            with open(path, encoding="utf-8") as handle:
                text = handle.read()
            with open(path, "w", encoding="utf-8-sig") as handle:
                handle.write(text)
            self.assertEqual(len(cohort.read_csv(path)), 4)
            formula = os.path.join(tmp, "formula.csv")
            cohort.write_csv(formula, [cohort.Record("=1+1", "F", "18-25", 58, 1620, 0.9, "N/mm", "Bending beam")])
            self.assertEqual(cohort.read_csv(formula)[0].name, "'=1+1")
            semicolons = os.path.join(tmp, "semicolons.csv")
            with open(semicolons, "w") as handle:
                handle.write(text.replace(",", ";"))
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(semicolons)
            self.assertIn("semicolons.csv: needs the comma-separated columns name, gender", str(caught.exception))
            with open(path, "a") as handle:
                handle.write("Bo,M,26-40,heavy,1800,2.0,N/mm,Bending beam,,\n")
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(path)
            self.assertIn("line 6: weight, height and value must be numbers", str(caught.exception))


if __name__ == "__main__":
    unittest.main()
