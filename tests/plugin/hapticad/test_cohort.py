# SPDX-License-Identifier: GPL-3.0-or-later
"""Cohort records and statistics, on seed 000's Table 3."""
import csv
import os
import re
import tempfile
import unittest
from dataclasses import replace as dataclass_replace

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
        # a group of one has no sample SD: undefined (None), not 0 (which reads as "all agree")
        self.assertEqual((rows["gender F"]["n"], rows["gender F"]["sd"]), (1, None))
        self.assertAlmostEqual(rows["age band 26-40"]["mean"], 4.0)
        self.assertEqual(rows["age band 41-60"]["max"], 3.5)
        self.assertEqual(list(rows)[:3], ["all", "gender F", "gender M"])
        self.assertEqual(cohort.statistics([]), [])

    def test_one_persons_records_count_once_at_their_mean(self):
        # Steven pressed twice (his second session, his name typed otherwise): one person of
        # Table 3's three, at the mean of his 4.5 and 6.5; he used to count as two (n 4, mean 4.5)
        again = cohort.Record("  steven ", "M", "26-40", 70, 1700, 6.5, "N/mm", "Bending beam")
        rows = {r["group"]: r for r in cohort.statistics(TABLE_3 + [again])}
        self.assertEqual((rows["all"]["n"], rows["all"]["records"]), (3, 4))
        self.assertAlmostEqual(rows["all"]["mean"], (5.5 + 3.5 + 3.5) / 3)
        self.assertEqual(rows["all"]["max"], 5.5)
        self.assertEqual((rows["gender M"]["n"], rows["gender M"]["records"]), (2, 3))
        self.assertAlmostEqual(rows["gender M"]["mean"], (5.5 + 3.5) / 2)
        self.assertIn("of the 3 participants", cohort.place_design(5.0, TABLE_3 + [again])[1])
        self.assertEqual(cohort.place_design(5.0, TABLE_3 + [again])[0], 2 / 3)
        self.assertEqual(cohort.count_participants(TABLE_3 + [again]), 3)
        self.assertEqual(cohort.namesakes("STEVEN", TABLE_3 + [again]), 2)
        # one name but another gender or age band: two people of one name, counted apart
        other = dataclass_replace(again, gender="F")
        rows = {r["group"]: r for r in cohort.statistics(TABLE_3 + [other])}
        self.assertEqual((rows["all"]["n"], rows["gender F"]["n"], rows["gender M"]["mean"]), (4, 2, 4.0))
        self.assertEqual(cohort.count_participants(TABLE_3 + [other, dataclass_replace(again, age_band="41-60")]),
                         5)
        # a record left out (above the force limit) is not pooled into its person's mean
        unfelt = dataclass_replace(again, design={"BeyondForceLimit": 1.0, "ForceLimit": 3.0})
        rows = {r["group"]: r for r in cohort.statistics(TABLE_3 + [unfelt])}
        self.assertEqual((rows["all"]["n"], rows["all"]["records"], rows["all"]["max"]), (3, 3, 4.5))

    def test_the_export_is_utf_8_whatever_the_systems_encoding(self):
        # a system whose encoding has no Chinese characters (cp1252 on a Windows FreeCAD; an
        # ASCII locale here) stopped at Zhang's name, leaving the file cut short
        import json
        import subprocess

        names = ["Zhang Wei 张伟", "Zoë Müller"]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cohort.csv")
            code = ("import json, sys; from hapticad import cohort; "  # the names as ASCII escapes (json)
                    "cohort.write_csv(sys.argv[1], [cohort.Record(n, 'F', '26-40', None, None, 3.5, 'N/mm', 'Beam') "
                    f"for n in json.loads({json.dumps(json.dumps(names))})])")
            env = dict(os.environ, LC_ALL="C", LANG="C", PYTHONUTF8="0", PYTHONIOENCODING="ascii",
                       PYTHONPATH=os.path.dirname(os.path.dirname(cohort.__file__)))
            done = subprocess.run(["/usr/bin/python3", "-c", code, path], env=env, capture_output=True, text=True)
            self.assertEqual(done.returncode, 0, done.stderr)
            self.assertEqual([r.name for r in cohort.read_csv(path)], names)
            self.assertEqual(os.listdir(tmp), ["cohort.csv"])  # nothing left beside it

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
            self.assertEqual((back[0].name, back[0].value, back[0].design["BeamThickness"]), ("Ana", 0.9, 4.5))
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
            # the guard is the export's, not the name's: it comes back off (a re-import matches the name held)
            self.assertEqual(cohort.read_csv(formula)[0].name, "=1+1")
            # a separator that is none of comma, semicolon and tab: said, with the columns wanted
            pipes = os.path.join(tmp, "pipes.csv")
            with open(pipes, "w") as handle:
                handle.write(text.replace(",", "|"))
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(pipes)
            self.assertIn("pipes.csv: needs the columns name, gender, age_band, weight_kg, height_mm, value, unit, "
                          "separated by commas, semicolons or tabs", str(caught.exception))
            with open(path, "a") as handle:
                handle.write("Bo,M,26-40,heavy,1800,2.0,N/mm,Bending beam,,\n")
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(path)
            self.assertIn("cohort.csv, line 6, column weight_kg (D): 'heavy' is not a number (or empty: not given)",
                          str(caught.exception))

    def test_every_bad_cell_is_named_by_its_line_and_column_as_a_spreadsheet_shows_them(self):
        # a cell that was no number said "weight, height and value must be numbers", and a value out of range
        # named no column: a spreadsheet user hunted through the row. Each cell's column is named, with its
        # letter in this file (the columns here in another order than the export's)
        columns = ("unit", "value", "name", "gender", "age_band", "weight_kg", "height_mm", "model", "design",
                   "recorded")
        good = {"unit": "N/mm", "value": "0.5", "name": "Ann", "gender": "F", "age_band": "18-25", "weight_kg": "58",
                "height_mm": "1620", "model": "Bending beam", "design": "", "recorded": "2026-11-24T10:00:00"}
        cases = [({"weight_kg": "heavy"}, "column weight_kg (F): 'heavy' is not a number (or empty: not given)"),
                 ({"height_mm": "tall"}, "column height_mm (G): 'tall' is not a number (or empty: not given)"),
                 ({"value": "soft"}, "column value (B): 'soft' is not a number"),
                 ({"value": ""}, "column value (B): empty"),
                 ({"name": "", "unit": ""}, "columns unit (A), name (C): empty"),
                 ({"gender": "X"}, "column gender (D): gender 'X' is not one of F, M, other, not given"),
                 ({"age_band": "young"}, "column age_band (E): age band 'young' is not one of"),
                 ({"weight_kg": "5"}, "column weight_kg (F): weight 5.0 kg is outside 10..300 kg"),
                 ({"height_mm": "90000"}, "column height_mm (G): height 90000.0 mm is outside 500..2500 mm"),
                 ({"value": "0"}, "column value (B): the preferred value 0.0 must be a number > 0"),
                 ({"value": "nan"}, "column value (B): the preferred value nan must be a number > 0"),
                 ({"value": "2000"}, "column value (B): the preferred value 2000 N/mm is outside the plausible "
                                     "0.0001..1000 N/mm: in N/m? that is 2 N/mm"),
                 ({"unit": "kN"}, "column unit (A): unit 'kN' is not one of N/mm, N, snap ratio"),
                 ({"name": " "}, "column name (C): a participant needs a name"),
                 ({"name": "Ze\x00d"}, "column name (C): the name 'Ze\\x00d' holds a control character"),
                 ({"model": "Beam\x07"}, "column model (H): the model 'Beam\\x07' holds a control character"),
                 ({"recorded": "2026\x00"}, "column recorded (J): the time recorded '2026\\x00' holds a control "
                                            "character"),
                 ({"gender": "X", "weight_kg": "5"}, "column gender (D): gender 'X' is not one of F, M, other, "
                                                     "not given; column weight_kg (F): weight 5.0 kg is outside"),
                 # a design item was dropped, or kept without a name
                 ({"design": "YoungsModulus=1.5;=1"}, "column design (I): '=1' is not name=value"),
                 ({"design": "YoungsModulus=1.5;x"}, "column design (I): 'x' is not name=value")]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "cells.csv")
            for bad, said in cases:
                with self.subTest(bad=bad):
                    with open(path, "w", newline="", encoding="utf-8") as handle:
                        out = csv.writer(handle)
                        out.writerow(columns)
                        out.writerow([good[c] for c in columns])
                        out.writerow([{**good, "design": "x=1\ny=2"}[c] for c in columns])  # a cell over two lines
                        out.writerow([{**good, **bad}[c] for c in columns])
                    with self.assertRaises(ValueError) as caught:
                        cohort.read_csv(path)
                    self.assertIn(f"cells.csv, line 5 (row 4 in a spreadsheet), {said}", str(caught.exception))
        self.assertEqual([cohort._column_letter(i) for i in (0, 25, 26, 27, 51, 52, 701, 702)],
                         ["A", "Z", "AA", "AB", "AZ", "BA", "ZZ", "AAA"])

    def test_a_file_misread_as_it_is_says_what_is_wrong_with_it(self):
        # a column twice kept the second (a name lost), a decimal comma split the value
        # into the unit, an open quote swallowed the file and was said as empty columns, a
        # folder raised IsADirectoryError
        header = "name,gender,age_band,weight_kg,height_mm,value,unit,model,design,recorded\n"
        cases = [("name,name,gender,age_band,weight_kg,height_mm,value,unit\nLi,Lo,F,18-25,,,0.5,N/mm\n",
                  "twice.csv: the header has the column name more than once (A, B): which one holds it cannot be "
                  "told; keep one"),
                 (header + "Dan,M,18-25,,,1,5,N/mm,,,\n",
                  "comma.csv, line 2, column unit (G): unit '5' is not one of N/mm, N, snap ratio (a decimal comma "
                  "in a comma-separated file splits a number in two: give it with a point, or in quotes)"),
                 (header + "Ann,F,18-25,,,0.5,N/mm,,,\n\"Bo,F,18-25,,,0.5,N/mm,,,\nCy,M,18-25,,,0.6,N/mm,,,\n",
                  "quote.csv, line 3: a quote (\") opens a cell there that never closes")]
        with tempfile.TemporaryDirectory() as tmp:
            for (text, said), file in zip(cases, ("twice.csv", "comma.csv", "quote.csv")):
                with self.subTest(file=file):
                    path = os.path.join(tmp, file)
                    with open(path, "w", encoding="utf-8") as handle:
                        handle.write(text)
                    with self.assertRaises(ValueError) as caught:
                        cohort.read_csv(path)
                    self.assertIn(said, str(caught.exception))
            with self.assertRaisesRegex(ValueError, f"{tmp}: Is a directory"):
                cohort.read_csv(tmp)
            with open(os.path.join(tmp, "inch.csv"), "w", encoding="utf-8") as handle:  # a quote inside a cell
                handle.write(header + 'Ann 5",F,18-25,,,0.5,N/mm,,,\n')
            self.assertEqual(cohort.read_csv(os.path.join(tmp, "inch.csv"))[0].name, 'Ann 5"')  # read as before

    def test_a_preference_beyond_what_a_hand_can_mean_is_refused_by_its_unit(self):
        def found(value, unit):
            return " | ".join(cohort.problems(cohort.Record("Zed", "M", "18-25", 70, 1700, value, unit, "")))

        self.assertIn("the preferred value 1e+308 N/mm is outside the plausible 0.0001..1000 N/mm",
                      found(1e308, "N/mm"))
        self.assertIn("outside the plausible 0.05..50 N", found(60.0, "N"))
        self.assertIn("outside the plausible 0.01..0.99 snap ratio", found(1.0, "snap ratio"))
        self.assertIn("unit 'kN' is not one of", found(1.0, "kN"))
        for value, unit in ((0.0694, "N/mm"), (4.5, "N/mm"), (1.47, "N"), (0.5, "snap ratio")):
            self.assertEqual(found(value, unit), "")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "huge.csv")
            cohort.write_csv(path, TABLE_3)
            with open(path, "a") as handle:
                handle.write("Zed,M,18-25,70,1700,1.5e308,N/mm,Bending beam,,\n")
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(path)
            self.assertIn("huge.csv, line 5, column value (F): the preferred value 1.5e+308 N/mm is outside",
                          str(caught.exception))

    def test_statistics_never_raise_on_stored_values(self):
        # a document saved before the range was checked may hold these: its cohort is still summarised
        huge = [cohort.Record(n, "M", "18-25", 70, 1700, v, "N/mm", "") for n, v in (("Zed", 1e308), ("Yan", 1.5e308))]
        rows = {r["group"]: r for r in cohort.statistics(TABLE_3 + huge)}
        self.assertEqual(rows["all"]["n"], 5)
        self.assertAlmostEqual(rows["all"]["mean"] / 5e307, 1.0)  # (1e308 + 1.5e308 + 11.5) / 5
        self.assertGreater(rows["all"]["sd"], 1e307)
        self.assertIn("0% of the 5 participants", cohort.place_design(0.5, TABLE_3 + huge)[1])
        endless = cohort.Record("Inf", "M", "18-25", 70, 1700, float("inf"), "N/mm", "")
        # no number to summarise: left out with a note (it made every figure NaN; test below)
        (everyone,) = cohort.statistics(TABLE_3 + [endless], by=())
        self.assertEqual(everyone["n"], 3)
        self.assertAlmostEqual(everyone["mean"], 11.5 / 3)

    def test_a_stored_value_that_is_no_finite_number_is_left_out_of_the_statistics_and_said(self):
        # a hand-edited document's NaN made every figure "nan" and `cohort --json` write bare NaN (invalid JSON)
        import json

        nan = cohort.Record("Zoë", "F", "26-40", 52, 1650, float("nan"), "N/mm", "Bending beam")
        kept = TABLE_3 + [nan]
        rows = {r["group"]: r for r in cohort.statistics(kept)}
        self.assertEqual((rows["all"]["n"], rows["gender F"]["n"]), (3, 1))
        self.assertAlmostEqual(rows["all"]["mean"], 11.5 / 3)
        json.dumps(cohort.statistics(kept), allow_nan=False)  # raises on a NaN
        self.assertIn("of the 3 participants", cohort.place_design(4.0, kept)[1])
        self.assertEqual(cohort.beyond_device_note(kept),
                         "1 record whose value is not a finite number (Zoë: nan; a hand-edited document?) left out "
                         "of the statistics: remove or correct it.")
        self.assertEqual(cohort.beyond_device_note(TABLE_3), "")

    def test_a_stored_record_that_is_not_one_says_what_it_lacks_or_holds_wrongly(self):
        good = TABLE_3[0].as_dict()
        self.assertEqual(cohort.from_dict(good), TABLE_3[0])
        cases = [
            ({k: v for k, v in good.items() if k != "gender"}, "not a participant record: it lacks gender"),
            ({"a": 1}, "it lacks name, gender, age_band, weight_kg, height_mm, value, unit, model"),
            (dict(good, value="4.5"), "value '4.5' is not a number"),
            (dict(good, value=None), "value None is not a number"),
            (dict(good, weight_kg=True), "weight_kg True is not a number"),
            (dict(good, name=7), "name 7 is not text"),
            (dict(good, design=[1]), "design '[1]' is not a set of design values"),
            ([1, 2], "not a participant record but list '[1, 2]'"),
        ]
        for data, message in cases:
            with self.subTest(message=message):
                with self.assertRaises(ValueError) as caught:
                    cohort.from_dict(data)
                self.assertIn(message, str(caught.exception))
        self.assertIsNone(cohort.from_dict(dict(good, weight_kg=None)).weight_kg)  # not given
        self.assertTrue(cohort.unfit_value(cohort.from_dict(dict(good, value=float("nan")))))

    def test_table_3s_heights_in_cm_say_what_to_give(self):
        # Table 3 prints 170/168/165 under "Height(mm)": they are cm; heights stay in mm, and the error says so
        printed = cohort.Record("Steven", "M", "26-40", 70, 170, 4.5, "N/mm", "Bending beam")
        self.assertIn("height 170 mm is outside 500..2500 mm: in centimetres? give 1700", cohort.problems(printed))
        self.assertNotIn("centimetres", " ".join(cohort.problems(cohort.Record(
            "Tall", "M", "26-40", 70, 9000, 4.5, "N/mm", "Bending beam"))))

    def test_formula_guard_is_the_exports_and_names_come_back_as_they_were(self):
        names = ["=1+1", "-Neg", "+plus", "@at", "'=quoted", "'Tis", "O'Brien", "Ann"]
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "names.csv")
            cohort.write_csv(path, [cohort.Record(n, "F", "18-25", None, None, 1.0, "N/mm", "") for n in names])
            with open(path) as handle:
                self.assertIn("'=1+1,", handle.read())  # still guarded for a spreadsheet
            back = [r.name for r in cohort.read_csv(path)]
            self.assertEqual(back, names)
            cohort.write_csv(path, cohort.read_csv(path))  # and again: no apostrophe piles up
            self.assertEqual([r.name for r in cohort.read_csv(path)], names)

    def test_design_values_come_back_as_numbers_at_full_precision(self):
        design = {"BeamThickness": 2.3, "BendingStiffness": 0.5555555555555556, "DeviceStiffness": 3.0,
                  "BeyondDevice": 0.0}
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "design.csv")
            cohort.write_csv(path, [cohort.Record("Ann", "F", "18-25", None, None, 0.5555555555555556, "N/mm",
                                                  "Bending beam", design, "2026-01-01T10:00:00")])
            (back,) = cohort.read_csv(path)
            self.assertEqual(back.design, design)
            self.assertEqual({type(v) for v in back.design.values()}, {float})
            self.assertFalse(cohort.beyond_device(back))  # "0" was truthy: every import was starred
        # a record imported before this held the text: still not beyond
        for text, beyond in (("0", False), ("0.0", False), ("1", True), ("1.0", True)):
            self.assertEqual(cohort.beyond_device(cohort.Record("Ann", "F", "18-25", None, None, 1.0, "N/mm", "",
                                                                {"BeyondDevice": text})), beyond)

    def test_a_name_with_a_control_character_is_refused_naming_its_line(self):
        for name in ("Ze\x00d", "Line1\nLine2", "tab\tname"):
            self.assertIn("holds a control character", " ".join(cohort.problems(
                cohort.Record(name, "M", "18-25", 70, 1700, 0.5, "N/mm", ""))))
        self.assertEqual(cohort.problems(cohort.Record("Zoë 李", "M", "18-25", 70, 1700, 0.5, "N/mm", "")), [])
        header = ",".join(cohort.CSV_COLUMNS) + "\n"
        good = "Zed,M,18-25,70,1700,0.5,N/mm,Bending beam,,2024\n"
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "names.csv")
            for rows, line in (('"Ze\nd",M,18-25,70,1700,0.5,N/mm,Bending beam,,2024\n', "line 2"),
                               (good + '"Ze\nd",M,18-25,70,1700,0.5,N/mm,Bending beam,,2024\n', "line 3"),
                               # a design cell over two lines: the next record starts on line 4, a
                               # spreadsheet's row 3
                               ('Ann,F,18-25,,,0.5,N/mm,Bending beam,"x=1\ny=2",2024\n' + "Ze\x00d" + good[3:],
                                "line 4 (row 3 in a spreadsheet)")):
                with open(path, "w", newline="") as handle:
                    handle.write(header + rows)
                with self.assertRaises(ValueError) as caught:
                    cohort.read_csv(path)
                self.assertIn(f"names.csv, {line}, column name (A): the name", str(caught.exception))
                self.assertIn("holds a control character", str(caught.exception))
        self.assertEqual(cohort.namesakes(" ann ", [TABLE_3[0], cohort.Record("Ann", "F", "18-25", None, None, 1.0,
                                                                               "N/mm", "")]), 1)

    def test_age_bands_and_genders_are_listed_in_their_order_not_given_last(self):
        people = [cohort.Record(f"P{i}", gender, age, None, None, 1.0 + i, "N/mm", "") for i, (gender, age) in
                  enumerate((("not given", "over 60"), ("other", "not given"), ("M", "under 18"), ("F", "41-60"),
                             ("M", "18-25"), ("F", "26-40")))]
        groups = [r["group"] for r in cohort.statistics(people)]
        self.assertEqual(groups, ["all", "gender F", "gender M", "gender other", "gender not given",
                                  "age band under 18", "age band 18-25", "age band 26-40", "age band 41-60",
                                  "age band over 60", "age band not given"])

    def test_one_participant_is_told_from_another_by_every_field_they_gave(self):
        wang = cohort.Record("Wang", "M", "26-40", 70, 1750, 3.5, "N/mm", "Bending beam", {}, "2026-01-01T10:00:00")
        self.assertTrue(cohort.same_record(wang, cohort.Record(**wang.as_dict())))
        for field, other in (("gender", "F"), ("age_band", "41-60"), ("weight_kg", 55.0), ("height_mm", 1600.0),
                             ("weight_kg", None), ("value", 3.6), ("unit", "N"), ("recorded", "2026-01-02T10:00:00"),
                             ("name", "Li")):
            with self.subTest(field=field):
                self.assertFalse(cohort.same_record(wang, cohort.Record(**dict(wang.as_dict(), **{field: other}))))
        # a spreadsheet saves 15 significant digits: the same record still
        k = 0.4396961805555557
        exact = cohort.Record("Ann", "F", "18-25", 58.3, None, k, "N/mm", "", {}, "2026-01-01T10:00:00")
        for rounded in (float(f"{k:.15g}"), float(f"{k:.13g}")):
            self.assertTrue(cohort.same_record(exact, cohort.Record(**dict(exact.as_dict(), value=rounded))))
        self.assertFalse(cohort.same_record(exact, cohort.Record(**dict(exact.as_dict(), value=k * (1 + 1e-9)))))

    def test_the_star_says_what_the_device_did_to_each_kind_of_preference(self):
        def starred(unit, value):
            return cohort.Record("Ann", "F", "18-25", None, None, value, unit, "", {"BeyondDevice": 1.0})

        self.assertEqual(cohort.beyond_device_note(TABLE_3), "")
        # a neck stiffer than the device is felt at its limit
        self.assertEqual(cohort.beyond_device_note([starred("N/mm", 4.4), *TABLE_3]),
                         "* 1 preference beyond what the device renders stably, felt at its limit (softer); counted "
                         "as recorded.")
        # a button's travel is stretched: its forces, and so its operating force and snap, are as designed
        for unit, value in (("N", 1.47), ("snap ratio", 0.5)):
            note = cohort.beyond_device_note([starred(unit, value), starred(unit, value)])
            self.assertEqual(note, "* 2 preferences steeper than the device renders stably, its forces felt as "
                                   "designed over a longer travel; counted as recorded.")
            self.assertNotIn("at its limit", note)
        self.assertEqual((cohort.plural(1, "participant"), cohort.plural(2, "participant")),
                         ("1 participant", "2 participants"))
        self.assertEqual((cohort.format_value(0.5, "snap ratio"), cohort.format_value(0.5556, "N/mm")),
                         ("snap ratio 0.5", "0.556 N/mm"))

    def test_preferences_above_the_force_limit_are_marked_and_left_out_of_the_statistics(self):
        def button(name, force, above, limit=3.0):
            return cohort.Record(name, "F", "18-25", None, None, force, "N", "Push button",
                                 {"BeyondDevice": 1.0, "ForceLimit": limit, "BeyondForceLimit": float(above)})

        kept = [button("Ann", 1.5, False), button("Bo", 2.5, False), button("Cy", 3.48, True),
                button("Di", 4.5, True, 2.5)]
        self.assertEqual([cohort.mark(r) for r in kept], [" *", " *", " †", " †"])  # † outweighs the star
        rows = {r["group"]: r for r in cohort.statistics(kept)}
        self.assertEqual((rows["all"]["n"], rows["all"]["max"]), (2, 2.5))  # the clicks never felt are not counted
        self.assertAlmostEqual(rows["all"]["mean"], 2.0)
        self.assertIn("of the 2 participants", cohort.place_design(3.0, kept)[1])
        self.assertEqual(cohort.beyond_device_note(kept),
                         "* 2 preferences steeper than the device renders stably, its forces felt as designed over a "
                         "longer travel; counted as recorded. † 2 preferences above the force limit (2.5 N, 3 N): "
                         "the force stopped there and the click was never felt; left out of the statistics (kept, "
                         "and exported).")
        # none counted: no statistics, and the note still says why
        self.assertEqual(cohort.statistics(kept[2:]), [])
        self.assertTrue(cohort.beyond_device_note(kept[2:]).startswith("† 2 preferences above the force limit"))
        # the flag read back from a CSV (a number) and from a record imported as text
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "button.csv")
            cohort.write_csv(path, kept)
            self.assertEqual([cohort.beyond_force_limit(r) for r in cohort.read_csv(path)], [False, False, True, True])
        self.assertFalse(cohort.beyond_force_limit(button("Ed", 1.0, False)))
        self.assertTrue(cohort.beyond_force_limit(cohort.Record("Ed", "F", "18-25", None, None, 4.0, "N", "",
                                                                {"BeyondForceLimit": "1.0"})))

    def test_a_group_of_one_has_no_sd_said_as_a_dash(self):
        rows = cohort.statistics(TABLE_3[:1])
        self.assertEqual([r["sd"] for r in rows], [None, None, None])
        self.assertEqual((cohort.format_sd(None), cohort.format_sd(0.57735)), ("-", "0.58"))
        # the overflow path too: a stored 1e308 alone
        (alone,) = cohort.statistics([cohort.Record("Zed", "M", "18-25", 70, 1700, 1e308, "N/mm", "")], by=())
        self.assertIsNone(alone["sd"])
        self.assertAlmostEqual(cohort.statistics(TABLE_3, by=())[0]["sd"], 0.57735, places=5)

    def test_a_time_rewritten_by_a_spreadsheet_is_the_same_time_to_the_precision_it_gives(self):
        kept = cohort.Record("Wang", "M", "26-40", 70, 1750, 3.5, "N/mm", "Bending beam", {}, "2026-11-24T15:17:03")
        for shown in ("2026-11-24 15:17", "2026-11-24T15:17:03", "2026-11-24 15:17:03", "24/11/2026 15:17",
                      "11/24/2026 15:17", "11/24/26 3:17 PM", "24.11.2026 15:17", "2026/11/24 15:17", "24/11/2026",
                      " 2026-11-24 15:17 "):
            with self.subTest(shown=shown):
                self.assertTrue(cohort.same_record(kept, dataclass_replace(kept, recorded=shown)))
        # shown rounded to the minute: 15:17:43 as 15:18
        late = dataclass_replace(kept, recorded="2026-11-24T15:17:43")
        self.assertTrue(cohort.same_record(late, dataclass_replace(kept, recorded="2026-11-24 15:18")))
        for other in ("2026-11-24 15:19", "2026-11-24 15:16", "2026-11-24T15:17:04", "25/11/2026", "2026-11-24 3:17 AM",
                      "24.11.2026 15:18", "", "yesterday"):
            with self.subTest(other=other):
                self.assertFalse(cohort.same_record(kept, dataclass_replace(kept, recorded=other)))
        # the time agreeing is not enough: every other field still tells two records apart
        self.assertFalse(cohort.same_record(kept, dataclass_replace(kept, recorded="2026-11-24 15:17", value=3.6)))
        # text that is no time is compared as text
        self.assertTrue(cohort.same_record(dataclass_replace(kept, recorded="session 2"),
                                           dataclass_replace(kept, recorded="session 2")))
        # 05/06: May or June, both read; 24.11: day first only
        self.assertEqual({t.month for t, _ in cohort.recorded_times("05/06/2026 10:00")}, {5, 6})
        self.assertEqual([t.month for t, _ in cohort.recorded_times("05.06.2026")], [6])
        self.assertEqual(cohort.recorded_times("31/02/2026"), [])

    def test_rows_of_empty_cells_are_skipped_as_blank_lines_are(self):
        header = ",".join(cohort.CSV_COLUMNS) + "\r\n"
        ann = "Ann,F,18-25,58,1620,0.9,N/mm,Bending beam,,2026-11-24 15:17\r\n"
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "blank.csv")
            with open(path, "w", newline="", encoding="utf-8-sig") as handle:
                handle.write(header + ann + ",,,,,,,,,\r\n" + "\r\n" + "  \r\n" + ann.replace("Ann", "Bo"))
            self.assertEqual([r.name for r in cohort.read_csv(path)], ["Ann", "Bo"])
            # a bad line after them is still named by its own line
            with open(path, "a", newline="") as handle:
                handle.write("Cy,F,18-25,58,1620,0.9,N/mm,Bending beam,,\r\n,,,,,,,,,\r\nDi,X,18-25,,,0.9,N/mm,,,\r\n")
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(path)
            self.assertIn("blank.csv, line 9, column gender (B): gender 'X'", str(caught.exception))
            # a row with some cells given is not blank: what it lacks is said
            with open(path, "w", newline="") as handle:
                handle.write(header + ann + ",,,,,0.9,,,,\r\n")
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(path)
            self.assertIn("blank.csv, line 3, columns name (A), gender (B), age_band (C), unit (G): empty",
                          str(caught.exception))

    def test_semicolon_and_tab_files_are_read_and_said_with_their_decimal_commas(self):
        people = [cohort.Record("Smith, John", "M", "26-40", 70.5, 1700, 0.5555555555555556, "N/mm", "Bending beam",
                                {"BeamThickness": 4.5, "BendingStiffness": 0.5555555555555556}, "2026-11-24T15:17:03"),
                  cohort.Record("Zhang", "F", "26-40", None, 1650, 3.5, "N/mm", "Bending beam", {}, "")]
        with tempfile.TemporaryDirectory() as tmp:
            comma = os.path.join(tmp, "comma.csv")
            cohort.write_csv(comma, people)
            with open(comma, newline="") as handle:
                rows = list(csv.reader(handle))
            self.assertEqual(cohort.read_csv_as_read(comma), (people, ""))
            for separator, said, decimal in ((";", "semicolon-separated", "."),
                                             (";", "semicolon-separated, with decimal commas", ","),
                                             ("\t", "tab-separated", ".")):
                with self.subTest(separator=separator, decimal=decimal):
                    path = os.path.join(tmp, "other.csv")
                    with open(path, "w", newline="", encoding="utf-8-sig") as handle:  # as Excel saves it
                        out = csv.writer(handle, delimiter=separator, lineterminator="\r\n")
                        out.writerow(rows[0])
                        for row in rows[1:]:  # a European spreadsheet's numbers, the design's too
                            out.writerow([re.sub(r"(?<=\d)\.(?=\d)", decimal, cell) for cell in row])
                    self.assertEqual(cohort.read_csv_as_read(path), (people, said))
            # a decimal comma in a comma file may be thousands: refused, naming the line
            with open(comma, "a", newline="") as handle:
                handle.write('Bo,M,26-40,"70,5",1700,"1,5",N/mm,Bending beam,,\r\n')
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(comma)
            self.assertIn("comma.csv, line 4, column weight_kg (D): '70,5' is not a number: give it with a decimal "
                          "point (a comma-separated file takes no decimal commas)", str(caught.exception))
            # a ';' inside an unquoted cell shifts the cells after it: refused, not read into the wrong columns
            path = os.path.join(tmp, "shifted.csv")
            with open(path, "w", newline="") as handle:
                handle.write(";".join(cohort.CSV_COLUMNS) + "\nAnn;F;18-25;;;0,9;N/mm;Bending beam;"
                                                            "BeamThickness=4,5;BendingStiffness=0,9;2026-01-01\n")
            with self.assertRaises(ValueError) as caught:
                cohort.read_csv(path)
            self.assertIn("shifted.csv, line 2: more cells than the header has columns, from column K on (a cell "
                          "holding a semicolon without quotes around it?)", str(caught.exception))

    def test_heights_in_inches_and_weights_in_pounds_say_what_to_give(self):
        def found(weight, height):
            return " | ".join(cohort.problems(cohort.Record("Ann", "F", "under 18", weight, height, 1.0, "N/mm", "")))

        # 69: a 69 cm child or a 69 in (1753 mm) adult: both said
        self.assertIn("height 69 mm is outside 500..2500 mm: in centimetres? give 690, or in inches? give 1753",
                      found(None, 69))
        self.assertIn("height 40 mm is outside 500..2500 mm: in inches? give 1016", found(None, 40))  # 40 cm is not
        self.assertNotIn("inches", found(None, 170))  # 170 in is 4318 mm
        self.assertIn("weight 350 kg is outside 10..300 kg: in pounds? give 159", found(350, None))
        self.assertNotIn("pounds", found(5, None))  # 5 lb is 2.3 kg
        self.assertNotIn("pounds", found(900, None))  # 408 kg
        # a child of the "under 18" band: 15 kg and 1100 mm are kept
        self.assertEqual(found(15, 1100), "")
        self.assertEqual(found(10, 500), "")
        self.assertIn("weight 9.5 kg is outside 10..300 kg", found(9.5, None))

    def test_every_text_cell_is_guarded_on_export_and_comes_back_as_given(self):
        odd = cohort.Record("=1+1", "F", "18-25", None, None, 1.0, "N/mm", '=HYPERLINK("http://x","y")',
                            {"-cmd": "=2+3", "BeamThickness": 4.0}, "@SUM(A1)")
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "odd.csv")
            cohort.write_csv(path, [odd])
            with open(path, newline="") as handle:
                header, row = list(csv.reader(handle))
            for column in cohort.TEXT_COLUMNS:  # no cell a spreadsheet would run
                with self.subTest(column=column):
                    self.assertNotIn(row[header.index(column)][:1], cohort.FORMULA_STARTS)
            self.assertEqual(row[header.index("model")], "\'=HYPERLINK(\"http://x\",\"y\")")
            (back,) = cohort.read_csv(path)  # stored as given: data, shown as plain text
            self.assertEqual(back, odd)
            cohort.write_csv(path, [back])  # and again: no apostrophe piles up
            self.assertEqual(cohort.read_csv(path), [odd])
        # a control character in the model or the time is refused, as in the name
        for field, text in (("model", "Bending\nbeam"), ("recorded", "2026-01-01\x00")):
            with self.subTest(field=field):
                self.assertIn("holds a control character", " ".join(cohort.problems(dataclass_replace(odd, **{
                    field: text}))))


if __name__ == "__main__":
    unittest.main()
