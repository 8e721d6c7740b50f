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

    def test_a_row_that_contradicts_itself_or_a_surfaces_range_is_rejected(self):
        # all accepted before: mu_d above mu_s, mu_d outside the row's own range, a stiffness the
        # surface's property clipped to 1000 N/mm without a word
        path = self.write("\n".join([
            HEADER,
            "Inverted,0.6,0.9,0.3,1.0,2,1000,0.5,src,src",
            "OutOfRange,1.0,0.9,0.3,0.8,2,1000,0.5,src,src",
            "Huge,0.6,0.5,0.3,0.8,2,1000,1e300,src,src",
            "Tiny,0.6,0.5,0.3,0.8,2,1000,1e-5,src,src",
            "Sticky,2000,0.5,0.3,0.8,2,1000,0.5,src,src",
            # the range is mu_d's: mu_s, the peak that starts a slide, may lie above it; equal mu's are fine
            "StaticAbove,0.96,0.8,0.3,0.8,2,1000,0.5,src,src",
            "Equal,0.5,0.5,0.3,0.8,2,1000,1000,src,src",
        ]) + "\n")
        db = materials.MaterialDatabase()
        db.load_csv(path)
        self.assertEqual(db.names(), ["StaticAbove", "Equal"])
        expected = [
            (2, "mu_dynamic = 0.9 is above mu_static = 0.6: sliding would feel stickier than starting to slide"),
            (3, "mu_dynamic = 0.9 is outside its own plausible range mu_min..mu_max 0.3..0.8"),
            (4, "stiffness_n_per_mm = 1e+300 is outside 0.001..1000 N/mm, the range a surface's stiffness takes"),
            (5, "stiffness_n_per_mm = 1e-05 is outside 0.001..1000 N/mm"),
            (6, "mu_static = 2000 is above 1000, the most a surface's friction takes"),
        ]
        self.assertEqual(len(db.errors), len(expected), db.errors)
        for error, (line, text) in zip(db.errors, expected):
            self.assertTrue(error.startswith(f"{path}:{line}: "), error)
            self.assertIn(text, error)

    def test_the_ranges_are_the_surface_properties(self):
        from hapticad import surface_object

        self.assertEqual(materials.FRICTION_MAX, surface_object.FRICTION_MAX)
        self.assertEqual(materials.STIFFNESS_RANGE_N_PER_MM,
                         (surface_object.STIFFNESS_MIN_N_PER_MM, surface_object.STIFFNESS_MAX_N_PER_MM))

    def test_a_missing_column_or_file_is_reported(self):
        path = self.write("name,mu_static\nA,1\n")
        db = materials.MaterialDatabase()
        db.load_csv(path)
        db.load_csv(path + ".missing")
        self.assertEqual(len(db), 0)
        self.assertIn("header lacks column(s) mu_dynamic", db.errors[0])
        self.assertIn("cannot read", db.errors[1])


class FcmatTest(unittest.TestCase):
    """Haptic materials as FreeCAD 0.20 cards in the user's Material folder."""

    def setUp(self):
        self.dir = tempfile.TemporaryDirectory()
        self.addCleanup(self.dir.cleanup)
        self.cards = os.path.join(self.dir.name, "Material")
        os.makedirs(self.cards)

    def test_cards_round_trip_and_freecad_reads_them(self):
        import importFCMat  # FreeCAD's own reader

        for material in materials.load_database(include_user=False):
            path = os.path.join(self.cards, "card.FCMat")
            materials.write_fcmat(material, path)
            back, errors = materials.read_fcmat(path)
            self.assertEqual(errors, [])
            for field in ("name", "static_friction", "dynamic_friction", "friction_min", "friction_max",
                          "stiffness_n_per_mm", "friction_source", "bulk_source"):
                self.assertEqual(getattr(back, field), getattr(material, field), field)
            self.assertAlmostEqual(back.youngs_modulus_gpa, material.youngs_modulus_gpa, places=12)
            self.assertAlmostEqual(back.density_kg_m3, material.density_kg_m3, places=9)
            freecad_view = importFCMat.read(path)
            self.assertEqual(freecad_view["Name"], material.name)
            self.assertEqual(float(freecad_view["HaptiCAD_DynamicFriction"]), material.dynamic_friction)
            self.assertTrue(freecad_view["YoungsModulus"].endswith("MPa"))

    def test_freecads_own_cards_are_left_alone(self):
        import FreeCAD

        standard = os.path.join(FreeCAD.getResourceDir(), "Mod", "Material", "StandardMaterial")
        for path in sorted(os.listdir(standard))[:10]:
            material, errors = materials.read_fcmat(os.path.join(standard, path))
            self.assertIsNone(material, path)
            self.assertEqual(errors, [], path)

    def test_user_cards_add_and_override_without_touching_the_installation(self):
        base = materials.load_database(include_user=False)
        abs_ = base.get("ABS")
        from dataclasses import replace

        materials.write_fcmat(replace(abs_, static_friction=0.9, dynamic_friction=0.8),
                              os.path.join(self.cards, "HaptiCAD-ABS.FCMat"))
        materials.write_fcmat(replace(abs_, name="Walnut veneer", static_friction=0.5),
                              os.path.join(self.cards, "Walnut.FCMat"))
        db = materials.load_database(data_dir=self.dir.name)
        self.assertEqual(db.errors, [])
        self.assertEqual(db.get("ABS").dynamic_friction, 0.8)
        self.assertEqual(db.get("Walnut veneer").static_friction, 0.5)
        self.assertEqual(len(db), len(base) + 1)
        self.assertEqual(materials.load_database(include_user=False).get("ABS").dynamic_friction, 0.5)

    def test_a_bad_card_is_rejected_by_line_and_the_rest_loads(self):
        abs_ = materials.load_database(include_user=False).get("ABS")
        good = os.path.join(self.cards, "Good.FCMat")
        materials.write_fcmat(abs_, good)
        cases = {
            "NegMu.FCMat": ("HaptiCAD_DynamicFriction = 0.5", "HaptiCAD_DynamicFriction = -0.2", "must be >= 0"),
            "NaN.FCMat": ("HaptiCAD_StaticFriction = 0.6", "HaptiCAD_StaticFriction = nan", "not finite"),
            "ZeroE.FCMat": ("YoungsModulus = 2300 MPa", "YoungsModulus = 0 MPa", "must be > 0"),
            "Unit.FCMat": ("YoungsModulus = 2300 MPa", "YoungsModulus = 2300 furlongs", "unknown unit"),
            "Missing.FCMat": ("HaptiCAD_FrictionMax = 0.8\n", "", "lacks HaptiCAD_FrictionMax"),
            # FreeCAD's keys too: it said "YoungsModulus = '' is not a number"
            "NoE.FCMat": ("YoungsModulus = 2300 MPa\n", "", "the card lacks YoungsModulus"),
            "NoDensity.FCMat": ("Density = 1050 kg/m^3\n", "", "the card lacks Density"),
            "Inverted.FCMat": ("HaptiCAD_DynamicFriction = 0.5", "HaptiCAD_DynamicFriction = 0.7",
                               "mu_dynamic = 0.7 is above mu_static = 0.6"),
            "Huge.FCMat": ("HaptiCAD_ContactStiffness = 0.8 N/mm", "HaptiCAD_ContactStiffness = 1e300 N/mm",
                           "is outside 0.001..1000 N/mm"),
            "Garbage.FCMat": ("[Mechanical]", "this line is not a key value pair", "expected 'key = value'"),
        }
        text = open(good).read()
        for name, (old, new, _) in cases.items():
            with open(os.path.join(self.cards, name), "w") as handle:
                handle.write(text.replace(old, new))
        db = materials.load_database(data_dir=self.dir.name)
        self.assertIn("ABS", db)
        self.assertEqual(len(db.errors), len(cases), db.errors)
        for name, (old, new, message) in cases.items():
            error = [e for e in db.errors if name in e]
            self.assertEqual(len(error), 1, name)
            path_line, problem = error[0].split(": ", 1)
            self.assertTrue(path_line.startswith(os.path.join(self.cards, name) + ":"), error[0])
            line = int(path_line.rsplit(":", 1)[1])
            if new:
                with open(os.path.join(self.cards, name)) as handle:
                    self.assertIn(new, handle.read().splitlines()[line - 1], name)
            self.assertIn(message, problem, name)

    def test_a_user_csv_is_read_too(self):
        os.makedirs(os.path.join(self.dir.name, "HaptiCAD"))
        with open(os.path.join(self.dir.name, "HaptiCAD", "materials.csv"), "w") as handle:
            handle.write(HEADER + "\nCork,0.7,0.6,0.4,0.9,0.03,240,0.3,own test,own test\n")
        db = materials.load_database(data_dir=self.dir.name)
        self.assertEqual(db.get("Cork").dynamic_friction, 0.6)
        # as a spreadsheet saves "CSV UTF-8": a byte-order mark first (the whole file was
        # refused, "header lacks column(s) name")
        with open(os.path.join(self.dir.name, "HaptiCAD", "materials.csv"), "w", encoding="utf-8-sig") as handle:
            handle.write(HEADER + "\nCork,0.7,0.5,0.4,0.9,0.03,240,0.3,own test,own test\n")
        db = materials.load_database(data_dir=self.dir.name)
        self.assertEqual((db.errors, db.get("Cork").dynamic_friction), ([], 0.5))

    def test_a_cards_unit_may_follow_its_number_without_a_space(self):
        abs_ = materials.load_database(include_user=False).get("ABS")
        path = os.path.join(self.cards, "Tight.FCMat")
        materials.write_fcmat(abs_, path)
        text = open(path).read()
        line = next(l for l in text.splitlines() if l.startswith("HaptiCAD_ContactStiffness"))
        for written, stiffness in (("0.3N/mm", 0.3), ("300N/m", 0.3), ("1e3 N/m", 1.0), ("0.25", 0.25)):
            with open(path, "w") as handle:
                handle.write(text.replace(line, f"HaptiCAD_ContactStiffness = {written}"))
            material, errors = materials.read_fcmat(path)
            self.assertEqual(errors, [], written)
            self.assertAlmostEqual(material.stiffness_n_per_mm, stiffness, msg=written)
        with open(path, "w") as handle:
            handle.write(text.replace(line, "HaptiCAD_ContactStiffness = N/mm"))
        self.assertIn("is not a number", materials.read_fcmat(path)[1][0])


if __name__ == "__main__":
    unittest.main()
