# SPDX-License-Identifier: GPL-3.0-or-later
"""The material database: the shipped file, and rejection of bad rows by file:line."""
import os
import tempfile
import unittest

from hapticad import materials

HEADER = ",".join(materials.COLUMNS)


class ShippedDatabaseTest(unittest.TestCase):
    def test_has_the_required_materials_and_no_errors(self):
        db = materials.load_database()
        self.assertEqual(db.errors, [])
        for name in ("Steel", "Aluminium", "Glass", "ABS", "PP", "PC", "PMMA", "TPE soft-touch",
                     "Rubber", "Wood"):
            self.assertIn(name, db)
            m = db.get(name)
            self.assertTrue(m.friction_source and m.bulk_source, name)
            self.assertLessEqual(m.friction_min, m.dynamic_friction, name)
            self.assertLessEqual(m.dynamic_friction, m.friction_max, name)

    def test_values_match_the_field_notes(self):
        # dry fingertip defaults of ../shared/notes/field-notes.md
        db = materials.default_database()
        expected = {"Steel": 0.5, "Aluminium": 0.6, "Glass": 0.6, "ABS": 0.5, "PP": 0.4,
                    "PMMA": 0.5, "TPE soft-touch": 1.2, "Rubber": 1.0}
        for name, mu in expected.items():
            self.assertEqual(db.get(name).dynamic_friction, mu, name)
        self.assertEqual(db.get("PP").youngs_modulus_gpa, 1.5)

    def test_unknown_names_raise_a_key_error_listing_the_known_ones(self):
        with self.assertRaises(KeyError) as caught:
            materials.default_database().get("Kryptonite")
        self.assertIn("Steel", str(caught.exception))


class BadFileTest(unittest.TestCase):
    def write(self, text):
        handle = tempfile.NamedTemporaryFile("w", suffix=".csv", delete=False)
        handle.write(text)
        handle.close()
        self.addCleanup(os.unlink, handle.name)
        return handle.name

    def test_each_bad_row_is_reported_by_line_and_the_rest_loads(self):
        path = self.write("\n".join([
            "# comment",
            HEADER,
            "Good,0.6,0.5,0.3,0.8,2,1000,0.5,src,src",
            "NegMu,0.6,-0.5,0.3,0.8,2,1000,0.5,src,src",
            "NaNMu,nan,0.5,0.3,0.8,2,1000,0.5,src,src",
            "ZeroE,0.6,0.5,0.3,0.8,0,1000,0.5,src,src",
            "Short,0.6,0.5",
            "Words,high,0.5,0.3,0.8,2,1000,0.5,src,src",
            "Range,0.6,0.5,0.9,0.8,2,1000,0.5,src,src",
            "Good,0.6,0.5,0.3,0.8,2,1000,0.5,src,src",
            "AlsoGood,1,0.9,0.3,1.2,2,1000,0.5,src,src",
        ]) + "\n")
        db = materials.MaterialDatabase()
        db.load_csv(path)
        self.assertEqual(db.names(), ["Good", "AlsoGood"])
        self.assertEqual(db.get("Good").origin, f"{path}:3")
        expected = [
            (4, "mu_dynamic = -0.5 must be >= 0"),
            (5, "mu_static = nan is not finite"),
            (6, "youngs_modulus_gpa = 0 must be > 0"),
            (7, "3 fields, the header has 10"),
            (8, "mu_static = 'high' is not a number"),
            (9, "mu_min = 0.9 exceeds mu_max = 0.8"),
            (10, "'Good' appears twice"),
        ]
        self.assertEqual(len(db.errors), len(expected), db.errors)
        for error, (line, text) in zip(db.errors, expected):
            self.assertTrue(error.startswith(f"{path}:{line}: "), error)
            self.assertIn(text, error)

    def test_a_missing_column_or_file_is_reported(self):
        path = self.write("name,mu_static\nA,1\n")
        db = materials.MaterialDatabase()
        db.load_csv(path)
        db.load_csv(path + ".missing")
        self.assertEqual(len(db), 0)
        self.assertIn("header lacks column(s) mu_dynamic", db.errors[0])
        self.assertIn("cannot read", db.errors[1])


if __name__ == "__main__":
    unittest.main()
