# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad bench-mesh` end to end: the JSON the issue names, for an icosphere and a
mesh file, in mm and in metres, point and sphere proxies; forces as expected from
k * depth; no pop-through; bad input gets a clear error. Timings are printed, never
asserted (they are benchmarks).

Environment: HAPTICAD_CLI (the launcher)."""
import json
import os
import struct
import subprocess
import tempfile
import time
import unittest

CLI = os.environ["HAPTICAD_CLI"]
KEYS = {"triangles", "build_ms", "tick_us", "bytes_per_triangle", "contact_ticks", "pop_through",
        "max_force_n"}


def bench(*args):
    done = subprocess.run([CLI, "bench-mesh", *args, "--json"], capture_output=True, text=True, timeout=120)
    return done


class BenchMeshCommandTest(unittest.TestCase):
    def check(self, result, triangles):
        self.assertTrue(KEYS <= result.keys(), result.keys())
        self.assertEqual(result["triangles"], triangles)
        self.assertTrue({"p50", "p99", "p999"} <= result["tick_us"].keys())
        self.assertGreater(result["contact_ticks"], 0.9 * result["ticks"])
        self.assertEqual(result["pop_through"], 0)
        # pressed 1-3 mm at 0.4 N/mm with mu_d 0.2: at most 1.2 N normal, 1.22 N in all
        low, high = result["expected_force_n"]
        self.assertGreater(result["max_force_n"], low)
        self.assertLessEqual(result["max_force_n"], high * 1.001)
        # ready: the repair, the build and the solids' analysis, all of which come before a touch
        parts = result["repair_ms"] + result["build_ms"] + result["solids_ms"]
        self.assertAlmostEqual(result["ready_ms"], parts, delta=0.002)
        self.assertGreater(result["ready_ms"], result["build_ms"])

    def test_icosphere_point_and_sphere_in_mm_and_m(self):
        for proxy in ("point", "sphere:1"):
            for units in ("mm", "m"):
                done = bench("--icosphere", "9680", "--ticks", "3000", "--proxy", proxy, "--units", units)
                self.assertEqual(done.returncode, 0, done.stderr)
                result = json.loads(done.stdout)
                self.check(result, 9680)
                self.assertEqual(result["units"], units)
                self.assertEqual(result.get("max_penetration_mm", 0.0), 0.0)

    def test_the_same_stroke_feels_the_same_in_mm_and_in_m(self):
        mm = json.loads(bench("--icosphere", "9680", "--ticks", "2000").stdout)
        m = json.loads(bench("--icosphere", "9680", "--ticks", "2000", "--units", "m").stdout)
        self.assertAlmostEqual(mm["max_force_n"], m["max_force_n"], places=9)
        self.assertEqual(mm["contact_ticks"], m["contact_ticks"])

    def test_warming_ahead_times_the_same_stroke(self):
        # the diagnostic's second renderer runs each block first; the timed one must
        # feel exactly what it feels without it
        plain = json.loads(bench("--icosphere", "9680", "--ticks", "2000").stdout)
        warmed = json.loads(bench("--icosphere", "9680", "--ticks", "2000", "--warm-ahead", "4").stdout)
        self.assertEqual((plain["warm_ahead"], warmed["warm_ahead"]), (0, 4))
        self.assertEqual(warmed["max_force_n"], plain["max_force_n"])
        self.assertEqual(warmed["contact_ticks"], plain["contact_ticks"])
        self.assertEqual(warmed["pop_through"], 0)
        done = bench("--icosphere", "9680", "--warm-ahead", "-1")
        self.assertEqual(done.returncode, 2)
        self.assertIn("--warm-ahead", done.stderr)
        # what is wrong, said as it is
        for args, message in ((("--ticks", "2000"), "give a mesh file or --icosphere TRIANGLES"),
                              (("--icosphere", "-5"), "--icosphere needs a positive number of triangles"),
                              (("mesh.off", "--icosphere", "20"), "not both")):
            done = bench(*args)
            self.assertEqual(done.returncode, 2, args)
            self.assertIn(message, done.stderr)
        self.assertNotIn("not both", bench("--ticks", "2000").stderr)

    def test_paced_ticks_feel_the_same_stroke_at_the_servo_rate(self):
        # --rate-hz runs the ticks as the servo loop does, a period apart; what is felt
        # must not change, only when each tick runs
        plain = json.loads(bench("--icosphere", "9680", "--ticks", "300").stdout)
        for pace in ("sleep", "spin"):
            with self.subTest(pace=pace):
                started = time.monotonic()
                done = bench("--icosphere", "9680", "--ticks", "300", "--rate-hz", "1000", "--pace", pace)
                self.assertEqual(done.returncode, 0, done.stderr)
                paced = json.loads(done.stdout)
                # 300 ticks at 1 kHz take at least 0.3 s on any machine
                self.assertGreaterEqual(time.monotonic() - started, 0.3)
                self.assertEqual((paced["rate_hz"], paced["pace"]), (1000, pace))
                self.assertLess(paced["late_ticks"], 30)  # a loaded machine may lose a few, not the run
                self.assertEqual(paced["max_force_n"], plain["max_force_n"])
                self.assertEqual(paced["contact_ticks"], plain["contact_ticks"])
                self.assertEqual(paced["pop_through"], 0)
        self.assertEqual(plain["pace"], "back to back")
        for args, message in ((("--pace", "spin"), "--pace needs --rate-hz"),
                              (("--rate-hz", "1000", "--pace", "nap"), "--pace must be sleep or spin"),
                              (("--rate-hz", "5"), "--rate-hz must be 0 (back to back) or from 100 to 100000"),
                              (("--rate-hz", "1000", "--warm-ahead", "4"), "it means nothing with --rate-hz")):
            done = bench("--icosphere", "80", *args)
            self.assertEqual(done.returncode, 2, args)
            self.assertIn(message, done.stderr)

    def test_ticks_are_grouped_by_how_far_the_contact_moved(self):
        # every tick after the first touches, so each is in one group; a finer mesh of
        # the same sphere, stroked the same way, has its contact move on more often
        moved = {}
        for triangles in ("9680", "100820"):
            result = json.loads(bench("--icosphere", triangles, "--ticks", "2000").stdout)
            self.assertEqual(result["contact_ticks"], result["ticks"])
            groups = result["tick_us_by_move"]
            self.assertEqual(set(groups), {"stayed", "next", "second", "further"})
            self.assertEqual(sum(g["ticks"] for g in groups.values()), result["ticks"] - 1)
            for g in groups.values():
                self.assertLessEqual(g["p50"], g["p99"])
            moved[triangles] = 1 - groups["stayed"]["ticks"] / (result["ticks"] - 1)
        # 0.05-0.1 mm a tick over triangles about 2.7 mm and 0.85 mm across
        self.assertGreater(moved["9680"], 0.01)
        self.assertGreater(moved["100820"], 2 * moved["9680"])

    def test_convex_pieces_settle_the_stroke_and_change_nothing_felt(self):
        # the icosphere is one convex piece: with it every contact tick is settled from
        # the last contact; without it every sweep walks, and the stroke feels the same
        for proxy in ("point", "sphere:1"):
            on = json.loads(bench("--icosphere", "9680", "--ticks", "2000", "--proxy", proxy).stdout)
            off = json.loads(bench("--icosphere", "9680", "--ticks", "2000", "--proxy", proxy,
                                   "--convex-pieces", "off").stdout)
            self.assertEqual((on["convex_pieces"], off["convex_pieces"]), (1, 0))
            self.assertEqual(off["settled_sweeps"], 0)
            self.assertEqual(off["walked_ticks"], off["contact_ticks"])
            self.assertGreater(on["settled_sweeps"], 0.99 * on["sweeps"])
            self.assertLessEqual(on["walked_ticks"], 1)  # the first touch, from no contact
            self.assertAlmostEqual(on["max_force_n"], off["max_force_n"], places=12)
            self.assertEqual(on["contact_ticks"], off["contact_ticks"])
            self.assertEqual(on["pop_through"], 0)
        done = bench("--icosphere", "9680", "--convex-pieces", "maybe")
        self.assertEqual(done.returncode, 2)
        self.assertIn("--convex-pieces", done.stderr)

    def test_a_mesh_file(self):
        with tempfile.TemporaryDirectory() as tmp:
            path = os.path.join(tmp, "tet.off")
            with open(path, "w") as f:
                f.write("OFF\n4 4 0\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
            done = bench(path, "--ticks", "1000", "--proxy", "sphere:0.1")
            self.assertEqual(done.returncode, 0, done.stderr)
            result = json.loads(done.stdout)
            self.assertEqual(result["triangles"], 4)
            self.assertEqual(result["pop_through"], 0)
            # pressed round sharp edges, the god object stays on the face it was pressed into:
            # no force range holds for a mesh file (the tetrahedron gives 20 times the press)
            self.assertIsNone(result["expected_force_n"])
            self.assertIn("closed", result["repair"])

    def test_the_json_gives_back_any_file_name(self):
        # the name was printed as it was: a quote or a backslash broke the string, a tab was a
        # raw control character, and json.loads refused the output
        with tempfile.TemporaryDirectory() as tmp:
            for name in ('quo"te\\back\there.off', "W\u00fcrfel \u2603 \\\".off"):
                with self.subTest(name=name):
                    path = os.path.join(tmp, name)
                    with open(path, "w") as f:
                        f.write("OFF\n4 4 0\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
                    done = bench(path, "--ticks", "100")
                    self.assertEqual(done.returncode, 0, done.stderr)
                    result = json.loads(done.stdout)
                    self.assertEqual(result["mesh"], path)
                    self.assertIn("closed", result["repair"])

    def test_more_than_one_mesh_file_is_refused(self):
        # the program took the last one without a word
        with tempfile.TemporaryDirectory() as tmp:
            first, second = os.path.join(tmp, "first.off"), os.path.join(tmp, "second.off")
            for path in (first, second):
                with open(path, "w") as f:
                    f.write("OFF\n4 4 0\n0 0 0\n10 0 0\n0 10 0\n0 0 10\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n")
            done = bench(first, "--ticks", "100", second)
            self.assertEqual(done.returncode, 2, done.stdout[:200])
            self.assertIn(f"hapticad bench-mesh: one mesh file at a time: give one of {first}, {second}", done.stderr)
            self.assertEqual(done.stdout, "")
            # an option's value is no mesh file, whatever it looks like
            done = bench(first, "--ticks", "100", "--seed", "7", "--units", "mm")
            self.assertEqual(done.returncode, 0, done.stderr)

    def test_bad_input_is_a_clear_error(self):
        done = bench("/nonexistent/part.stl")
        self.assertNotEqual(done.returncode, 0)
        self.assertIn("/nonexistent/part.stl", done.stderr)
        done = bench("--icosphere", "1000", "--proxy", "cube")
        self.assertEqual(done.returncode, 2)
        self.assertIn("--proxy", done.stderr)

    def test_numbers_out_of_range_name_the_option_and_its_bounds(self):
        for args, message in (
                (("--icosphere", "2147483647"), "--icosphere takes at most 10000000 triangles (about 4.7 GB "
                                                "of memory to build); 2147483647 would need about 1.01e+03 GB"),
                (("--icosphere", "99999999999999999999"), "--icosphere takes at most 10000000 triangles"),
                (("--icosphere", "2.5"), "--icosphere must be a whole number of triangles, got '2.5'"),
                (("--icosphere", "0"), "--icosphere needs a positive number of triangles, got 0"),
                (("--icosphere", "80", "--proxy", "sphere:0"),
                 "--proxy sphere:R_MM needs R from 0.001 mm to 1000 mm, got 0 (for a point proxy give --proxy point)"),
                (("--icosphere", "80", "--proxy", "sphere:1e308"), "needs R from 0.001 mm to 1000 mm, got 1e308"),
                (("--icosphere", "80", "--radius", "1e308"), "--radius must be from 0.01 mm to 10000 mm, got 1e+308 mm"),
                (("--icosphere", "80", "--radius", "1e-300"), "--radius must be from 0.01 mm to 10000 mm"),
                (("--icosphere", "80", "--ticks", "1e308"), "--ticks must be from 100 to 10000000"),
                (("--icosphere", "80", "--ticks", "2.5"), "--ticks must be a whole number, got '2.5'"),
                (("--icosphere", "80", "--seed", "99999999999999999999"), "--seed must be from 0 to 4294967295"),
                (("--icosphere", "80", "--warm-ahead", "99999999999"), "--warm-ahead must be from 0 to 10000000"),
                (("--icosphere", "80", "--ticks", "1000", "--warm-ahead", "2000"),
                 "--warm-ahead must be at most --ticks (1000), got 2000")):
            with self.subTest(args=args):
                done = bench(*args)
                self.assertEqual(done.returncode, 2, done.stdout[:200])
                self.assertIn(message, done.stderr)
                self.assertNotIn("bad_alloc", done.stderr)
        # the bounds themselves are taken
        done = bench("--icosphere", "80", "--ticks", "100", "--warm-ahead", "100", "--proxy", "sphere:0.001",
                     "--radius", "0.01")
        self.assertEqual(done.returncode, 0, done.stderr)

    def test_a_mesh_file_that_cannot_be_used_says_why(self):
        tet_faces = "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n"
        with tempfile.TemporaryDirectory() as tmp:
            files = {
                "nan.off": "OFF\n4 4 0\nnan 0 0\n10 0 0\n0 10 0\n0 0 10\n" + tet_faces,
                "inf.off": "OFF\n4 4 0\n0 0 0\n10 0 0\n0 inf 0\n0 0 10\n" + tet_faces,
                "nan.obj": "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n",
                "nan.stl": "solid x\n facet normal 0 0 1\n outer loop\n vertex nan 0 0\n vertex 1 0 0\n"
                           " vertex 0 1 0\n endloop\n endfacet\nendsolid x\n",
            }
            for name, text in files.items():
                with open(os.path.join(tmp, name), "w") as f:
                    f.write(text)
            # a binary STL: 80-byte header, one facet whose first vertex is NaN
            binary = os.path.join(tmp, "nan_binary.stl")
            with open(binary, "wb") as f:
                f.write(b"\0" * 80 + struct.pack("<I", 1)
                        + struct.pack("<12f", 0, 0, 1, float("nan"), 0, 0, 1, 0, 0, 0, 1, 0) + b"\0\0")
            os.mkdir(os.path.join(tmp, "folder.stl"))
            for name, message in (
                    ("missing.off", "missing.off: no such file"),
                    ("folder.stl", "folder.stl: is a folder, not a mesh file (give an OFF, OBJ, STL or PLY file)"),
                    ("nan.off", "nan.off: line 3: 'nan' is not a finite number; every vertex needs three finite "
                                "coordinates"),
                    ("inf.off", "inf.off: line 5: 'inf' is not a finite number"),
                    ("nan.obj", "nan.obj: line 2: 'nan' is not a finite number"),
                    ("nan.stl", "nan.stl: line 4: 'nan' is not a finite number"),
                    ("nan_binary.stl", "nan_binary.stl: face 1 has a vertex that is not finite (nan, 0, 0); "
                                       "every vertex needs three finite coordinates")):
                with self.subTest(name=name):
                    done = bench(os.path.join(tmp, name), "--ticks", "200")
                    self.assertEqual(done.returncode, 1, done.stdout[:200])
                    self.assertIn(message, done.stderr)


if __name__ == "__main__":
    unittest.main()
