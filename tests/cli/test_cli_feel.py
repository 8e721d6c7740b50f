# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad feel` end to end: a stroke across a tagged box face feels k * depth
normal force and Ft/Fn = mu_d (within 5%); bad input gets a clear error (exit 2).

Environment: HAPTICAD_CLI (the launcher), HAPTICAD_MOD (the staged Mod folder).
Runs under /usr/bin/python3 (FreeCAD's interpreter)."""
import csv
import json
import os
import subprocess
import sys
import tempfile
import time
import unittest
import zipfile

CLI = os.environ["HAPTICAD_CLI"]
sys.path.insert(0, os.environ["HAPTICAD_MOD"])
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "support"))

from hapticad.freecad_env import ensure_freecad  # noqa: E402

App = ensure_freecad()
import HaptiCAD  # noqa: E402
from partdesign_parts import make_padded_body  # noqa: E402

# the module under test is the build's, not an installed copy
assert HaptiCAD.__file__.startswith(os.environ["HAPTICAD_MOD"]), HaptiCAD.__file__

K_N_PER_MM = 0.5
MU_D = 0.45


def run_cli(*args, timeout=120):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=timeout)


class FeelCommandTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.doc_path = os.path.join(cls.tmp.name, "box.FCStd")
        doc = App.newDocument("CliBox")
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 80, 40, 20
        doc.recompute()
        HaptiCAD.make_surface(doc, [(box, "Face6")], material="PMMA", static_friction=0.6,
                              dynamic_friction=MU_D, stiffness_n_per_mm=K_N_PER_MM,
                              FeelRoughness=False)
        doc.saveAs(cls.doc_path)
        App.closeDocument(doc.Name)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def test_a_partdesign_bodys_face_is_felt(self):
        # read outside FreeCAD, PartDesign's objects used to be left out without a word:
        # the stroke then said its start was "75 mm from the nearest surface"
        path = os.path.join(self.tmp.name, "body.FCStd")
        doc = App.newDocument("CliBody")
        _, surface = make_padded_body(App, HaptiCAD, doc)
        top = f"Body.{surface.References[0][1][0]}"
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        proc = run_cli("feel", path, "--stroke", "5,10,10:25,10,10", "--out", os.path.join(self.tmp.name, "body"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertGreater(json.loads(proc.stdout)["faces"][top]["contact_ticks"], 100)

    def test_stroke_across_a_tagged_face_feels_k_depth_and_mu_d(self):
        out = os.path.join(self.tmp.name, "stroke")
        depth = 1.2
        proc = run_cli("feel", self.doc_path, "--stroke", "10,20,20:70,20,20", "--speed", "60",
                       "--depth", str(depth), "--out", out)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        summary = json.loads(proc.stdout)
        for key in ("ticks", "contact_ticks", "max_normal_force_n", "faces", "tick_us"):
            self.assertIn(key, summary)
        self.assertIn("p50", summary["tick_us"])
        self.assertIn("p99", summary["tick_us"])
        self.assertGreater(summary["contact_ticks"], 1000)
        self.assertLessEqual(summary["contact_ticks"], summary["ticks"])
        face = summary["faces"]["Box.Face6"]
        expected_fn = K_N_PER_MM * depth
        self.assertAlmostEqual(face["mean_normal_force_n"], expected_fn, delta=0.05 * expected_fn)
        self.assertAlmostEqual(summary["max_normal_force_n"], expected_fn, delta=0.05 * expected_fn)
        self.assertAlmostEqual(face["mean_ft_over_fn"], MU_D, delta=0.05 * MU_D)
        self.assertEqual(face["material"], "PMMA")

        with open(os.path.join(out, "trace.csv")) as handle:
            rows = list(csv.DictReader(handle))
        self.assertEqual(len(rows), summary["ticks"])
        for column in ("time_s", "device_x_mm", "proxy_z_mm", "force_z_n", "face"):
            self.assertIn(column, rows[0])
        in_contact = [r for r in rows if r["contact"] == "1"]
        self.assertTrue(all(r["face"] == "Box.Face6" for r in in_contact))
        # the proxy stays on the surface while the device is below it
        self.assertTrue(all(abs(float(r["proxy_z_mm"]) - 20.0) < 1e-6 for r in in_contact))
        with open(os.path.join(out, "trace.png"), "rb") as handle:
            self.assertEqual(handle.read(8), b"\x89PNG\r\n\x1a\n")

    def test_a_vibration_the_rate_cannot_render_is_said(self):
        path = os.path.join(self.tmp.name, "razor.FCStd")
        doc = App.openDocument(self.doc_path)
        HaptiCAD.make_vibration(doc, doc.getObject("Box"), frequency_hz=700.0, amplitude_n=0.3)
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        proc = run_cli("feel", path, "--stroke", "10,20,20:30,20,20", "--rate", "1000",
                       "--out", os.path.join(self.tmp.name, "razor"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("700 Hz is felt at 300 Hz instead at the 1000 Hz servo rate", proc.stderr)
        self.assertIn("raise the servo rate with --rate", proc.stderr)  # the CLI's rate, not Preferences'
        self.assertNotIn("Preferences", proc.stderr)

    def test_a_face_stiffer_than_the_device_and_a_surface_left_out_are_said(self):
        # a 5 N/mm surface was felt at the simulated hand's 3 N/mm without a word; a surface
        # whose part was deleted was left out without one
        path = os.path.join(self.tmp.name, "stiff.FCStd")
        doc = App.openDocument(self.doc_path)
        doc.getObject("HapticSurface").Stiffness = 5.0
        gone = doc.addObject("Part::Box", "Lid")
        doc.recompute()
        HaptiCAD.make_surface(doc, [(gone, "Face6")], material="PP", FeelRoughness=False).Label = "Lid grip"
        doc.removeObject("Lid")
        doc.recompute()
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        proc = run_cli("feel", path, "--stroke", "10,20,20:30,20,20", "--depth", "0.5",
                       "--out", os.path.join(self.tmp.name, "stiff"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("is 5 N/mm stiff, above the 3 N/mm the device renders stably: it was felt at 3 N/mm (0.5 mm "
                      "deep it pushes back with 1.5 N, not 2.5 N)", proc.stderr)
        self.assertIn("Lid grip is not felt on Lid, which was deleted", proc.stderr)

    def test_a_stiffness_studys_law_is_reported_as_felt(self):
        # the summary said 0.8 N/mm (the surface's), notes [], while the probe felt the study's
        # neck: 2.77 N of a 4.44 N/mm neck held to the device's 3, 1.08 N of a 1.09 N/mm one
        for thickness, label in ((8.0, "Stiff neck"), (4.0, "Soft neck")):
            path = os.path.join(self.tmp.name, f"study-{thickness:g}.FCStd")
            doc = App.openDocument(self.doc_path)
            HaptiCAD.make_study(doc, doc.getObject("HapticSurface"), YoungsModulus=1.5, BeamWidth=5,
                                BeamThickness=thickness, BeamLength=60).Label = label
            doc.recompute()
            doc.saveAs(path)
            App.closeDocument(doc.Name)
            proc = run_cli("feel", path, "--stroke", "10,20,20:30,20,20", "--depth", "0.5", "--out",
                           os.path.join(self.tmp.name, f"study-{thickness:g}"))
            self.assertEqual(proc.returncode, 0, proc.stderr)
            summary = json.loads(proc.stdout)
            face = summary["faces"]["Box.Face6"]
            law = 0.5556 * (thickness / 4) ** 3  # k = 3 E I / L^3: 4.44 and 0.556 N/mm
            felt = min(law, summary["max_stiffness_n_per_mm"])
            with self.subTest(study=label):
                self.assertAlmostEqual(face["stiffness_n_per_mm"], felt, places=3)
                # 0.5 mm deep: under the 3 N force limit, which holds the push with its friction
                self.assertAlmostEqual(face["mean_normal_force_n"], 0.5 * felt, delta=0.05 * felt)
                self.assertEqual((face["surface_stiffness_n_per_mm"], face["stiffness_above_device"],
                                  face["stiffness_study"]), (K_N_PER_MM, law > felt, label))
                said = (f"Box.Face6 (HapticSurface): {label}'s bending beam ({law:.3g} N/mm) replaces the surface's "
                        "0.5 N/mm")
                self.assertIn(said, proc.stderr)
                (note,) = [n for n in summary["notes"] if "bending beam" in n]
                self.assertTrue(note.startswith(said), note)
                self.assertEqual("it is above the 3 N/mm the device renders stably" in note, law > felt, note)

    def test_a_study_whose_law_is_not_felt_is_said(self):
        # the study duplicated: exit 0, notes [], felt at the surface's 0.5 N/mm, while before
        # the duplicate it said the neck's law replaced it
        path = os.path.join(self.tmp.name, "two-studies.FCStd")
        doc = App.openDocument(self.doc_path)
        study = HaptiCAD.make_study(doc, doc.getObject("HapticSurface"))
        study.Label = "Neck"
        copy = doc.copyObject(study, False)
        doc.recompute()
        copy_label = copy.Label
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        proc = run_cli("feel", path, "--stroke", "10,20,20:30,20,20", "--out", os.path.join(self.tmp.name, "two"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        summary = json.loads(proc.stdout)
        self.assertEqual(summary["faces"]["Box.Face6"]["stiffness_study"], None)
        for label, other in (("Neck", copy_label), (copy_label, "Neck")):
            said = (f"{label} is not felt (HapticSurface is felt at its own stiffness): HapticSurface is also "
                    f"studied by {other}: a face gives one way; link another surface")
            with self.subTest(study=label):
                self.assertIn(f"hapticad feel: {said}\n", proc.stderr)
                self.assertIn(said, summary["notes"])

    def test_what_the_feel_panel_says_is_said_a_hidden_part_and_a_clipped_texture(self):
        # the stroke crossed a hole the Cut shows and the tagged Box, hidden, does not have;
        # and a texture at level 1e6 was felt clipped at the full range: notes [] both times
        path = os.path.join(self.tmp.name, "cut.FCStd")
        doc = App.openDocument(self.doc_path)
        box = doc.getObject("Box")
        hole = doc.addObject("Part::Cylinder", "Hole")
        hole.Radius, hole.Height = 5, 30
        hole.Placement.Base = App.Vector(40, 20, -5)
        cut = doc.addObject("Part::Cut", "Cut")
        cut.Base, cut.Tool = box, hole
        surface = doc.getObject("HapticSurface")
        surface.Texture, surface.TextureDC = "Custom", 1e6
        doc.recompute()
        box.Visibility = hole.Visibility = False
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        proc = run_cli("feel", path, "--stroke", "10,20,20:70,20,20", "--out", os.path.join(self.tmp.name, "cut"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        notes = json.loads(proc.stdout)["notes"]
        for said in ("Box is hidden, used by Cut: you feel Box's shape, not what is shown; tag the faces of Cut "
                     "instead",
                     "HapticSurface: the texture is at level 1 or more all over at 50-270 mm/s: felt as a flat drag "
                     "at the full range, its ridges clipped"):
            with self.subTest(note=said[:20]):
                self.assertIn(f"hapticad feel: {said}\n", proc.stderr)
                self.assertIn(said, notes)

    def test_a_texture_whose_drag_with_the_press_passes_the_force_limit_is_said(self):
        # reviewer (make_texture_doc.py + hapticad feel + analyze_cli_grating.py): the paper's f_DC 0.675 f_vis +0.2
        # on ABS, pressed 2 mm at 270 mm/s under the 3 N limit: 41 % of the ticks held to 3 N, the press 1.49 N
        # for 1.6, eq. 2's DC 2.376 N for 2.430 and its harmonics off by -24 to +35 %, with "notes": []
        path = os.path.join(self.tmp.name, "grating.FCStd")
        doc = App.newDocument("CliGrating")
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 300, 300, 10
        doc.recompute()
        HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False,
                              Texture="Paper f_DC 0.675 f_vis +0.2").Label = "Grating"
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        proc = run_cli("feel", path, "--stroke", "150,20,10:150,150,10", "--speed", "270", "--depth", "2",
                       "--out", os.path.join(self.tmp.name, "grating"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        notes = json.loads(proc.stdout)["notes"]
        before = ("Grating: the texture drags up to 2.80 N at 50-270 mm/s (level 0.93 of the device's full range, the "
                  "3 N force limit), which leaves 1.07 N of the 3 N force limit for the press")
        felt = "Box.Face6 (Grating): "
        for said in (before, felt):
            with self.subTest(said=said[:20]):
                (note,) = [n for n in notes if n.startswith(said)]
                self.assertIn(f"hapticad feel: {note}\n", proc.stderr)
        (note,) = [n for n in notes if n.startswith(felt)]
        self.assertRegex(note, r"^Box\.Face6 \(Grating\): [34]\d % of the slide was held to the 3 N force limit: the "
                               r"texture's drag \(up to 2\.80 N\) and the 1\.60 N press passed it together")
        self.assertIn("pressed at most 1.07 N it fits", note)
        self.assertLess(proc.stderr.index(before), proc.stderr.index(felt))  # said before the stroke, then as felt

    def test_the_preferences_force_limit_holds_the_stroke_as_in_the_feel_panel(self):
        # Steel (10 N/mm, felt at the probe's 1 N/mm) pressed 2 mm deep: 2 N, held to the
        # force limit set in HaptiCAD's Preferences (the panel's simulated hand is held so)
        path = os.path.join(self.tmp.name, "steel.FCStd")
        doc = App.newDocument("CliSteel")
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 80, 40, 20
        doc.recompute()
        HaptiCAD.make_surface(doc, [(box, "Face6")], material="Steel", FeelRoughness=False)
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        config = os.path.join(self.tmp.name, "config")
        env = dict(os.environ, XDG_CONFIG_HOME=config)
        code = ("import FreeCAD as App\n"
                "App.ParamGet('User parameter:BaseApp/Preferences/Mod/HaptiCAD').SetFloat('ForceLimitN', 1.5)\n"
                "App.saveParameter()\n")
        subprocess.run(["freecadcmd", "-c", code], env=env, check=True, capture_output=True, timeout=120)
        felt = {}
        for name, environment in (("set", env), ("default", dict(env, XDG_CONFIG_HOME=config + "-fresh"))):
            proc = subprocess.run([CLI, "feel", path, "--stroke", "10,20,20:70,20,20", "--depth", "2",
                                   "--out", os.path.join(self.tmp.name, f"steel-{name}")],
                                  capture_output=True, text=True, timeout=120, env=environment)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            felt[name] = (json.loads(proc.stdout), proc.stderr)
        summary, said = felt["set"]
        self.assertEqual(summary["force_limit_n"], 1.5)
        self.assertAlmostEqual(summary["expected_normal_force_n"], 2.0, delta=1e-6)
        self.assertLessEqual(summary["max_normal_force_n"], 1.5 + 1e-9)
        self.assertIn("2 mm deep the face pushes back with 2.00 N, more than the 1.5 N force limit", said)
        summary, said = felt["default"]
        self.assertEqual(summary["force_limit_n"], 3.0)  # Preferences' default, under the probe's 8.9 N
        self.assertAlmostEqual(summary["max_normal_force_n"], 2.0, delta=0.1)
        self.assertNotIn("force limit", said)

    def test_a_custom_accuracy_is_built_and_said(self):
        # a cylinder: its side's tessellation is where deflection shows (coarser values,
        # fewer triangles); the stroke crosses its flat top
        path = os.path.join(self.tmp.name, "can.FCStd")
        doc = App.newDocument("CliCan")
        can = doc.addObject("Part::Cylinder", "Can")
        can.Radius, can.Height = 20, 30
        doc.recompute()
        HaptiCAD.make_surface(doc, [(can, "Face2")], material="PMMA", FeelRoughness=False)
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        felt = {}
        for name, args in (("Fine", ("--accuracy", "Fine")),
                           ("coarse", ("--linear-deflection", "0.5", "--angular-deflection", "30",
                                       "--no-force-shading")),
                           ("refined", ("--accuracy", "Custom", "--linear-deflection", "0.5",
                                        "--angular-deflection", "30", "--refine-edge", "2", "--force-shading"))):
            proc = run_cli("feel", path, "--stroke", "-10,0,30:10,0,30", "--out", os.path.join(self.tmp.name, name),
                           *args)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            felt[name] = json.loads(proc.stdout)["accuracy"]
        self.assertEqual(felt["Fine"]["name"], "Fine")
        self.assertEqual({k: felt["coarse"][k] for k in ("name", "linear_deflection_mm", "angular_deflection_deg",
                                                         "force_shading", "refine_edge_mm")},
                         {"name": "Custom", "linear_deflection_mm": 0.5, "angular_deflection_deg": 30.0,
                          "force_shading": False, "refine_edge_mm": 0.0})
        self.assertLess(felt["coarse"]["triangles"], felt["Fine"]["triangles"] / 4)
        # refinement splits the long facets of the coarse side; shading stays on unless turned off
        self.assertGreater(felt["refined"]["triangles"], felt["coarse"]["triangles"])
        self.assertTrue(felt["refined"]["force_shading"])
        # what cannot be built is said, and nothing runs
        for args, message in ((("--accuracy", "Draft", "--linear-deflection", "0.5"),
                               "cannot go with --accuracy Draft"),
                              (("--linear-deflection", "0"), "--linear-deflection 0.0 mm is outside 0.0001..10 mm"),
                              (("--angular-deflection", "0.57"),
                               "--angular-deflection 0.57 degrees is outside 0.573..85.9436 degrees"),
                              (("--refine-edge", "0.001"), "--refine-edge 0.001 mm is neither 0 (off) nor in"),
                              # a flag takes no value, negative or not; after -- a name is a name
                              (("--force-shading", "-1"), "unrecognized arguments: -1")):
            with self.subTest(args=args):
                out = os.path.join(self.tmp.name, "refused")
                proc = run_cli("feel", path, "--stroke", "-10,0,30:10,0,30", "--out", out, *args)
                self.assertEqual(proc.returncode, 2, proc.stdout[:200])
                self.assertIn(message, proc.stderr)
                self.assertFalse(os.path.exists(out))
        proc = run_cli("feel", "--stroke", "-10,0,30:10,0,30", "--out", os.path.join(self.tmp.name, "x"), "--", "-5")
        self.assertEqual(proc.returncode, 2)
        self.assertIn("-5: no such file", proc.stderr)

    def test_a_part_that_would_make_too_many_triangles_is_refused_before_it_is_meshed(self):
        # a 1 m ball: at Fine 251,048 triangles in one face (19 s and 1.15 GB), at the
        # smallest angle 805,416; said with what to give instead, in 2 s, nothing written
        # (the demo: the designer's copy of the example, a ball added to it and saved)
        path = os.path.join(self.tmp.name, "globe.FCStd")
        demo_out = os.path.join(self.tmp.name, "demo-globe")
        os.makedirs(demo_out)
        from hapticad.demo import EXAMPLE
        for target, source in ((path, None), (os.path.join(demo_out, os.path.basename(EXAMPLE)), EXAMPLE)):
            doc = App.openDocument(source) if source else App.newDocument("CliGlobe")
            globe = doc.addObject("Part::Sphere", "Globe")
            globe.Radius = 500
            doc.recompute()
            HaptiCAD.make_surface(doc, [(globe, "Face1")], material="PMMA", FeelRoughness=False)
            doc.saveAs(target)
            App.closeDocument(doc.Name)
        out = os.path.join(self.tmp.name, "globe")
        stroke = ("--stroke", "-10,0,510:10,0,510", "--out", out)
        for args, said in (
                (("feel", path, *stroke), ("hapticad feel: Globe: about 252,000 triangles in its Face1 at a linear "
                                           "deflection of 0.02 mm and an angular deflection of 5.7296 degrees (Fine)",
                                           "hapticad feel --linear-deflection 0.026")),
                (("feel", path, *stroke, "--angular-deflection", "0.573"),
                 ("at a linear deflection of 0.02 mm and an angular deflection of 0.573 degrees (Custom)",
                  "a linear deflection of 0.026 mm with an angular one of 1.2 degrees fits",
                  "hapticad feel --linear-deflection 0.026 --angular-deflection 1.2")),
                (("demo", "--headless", "--out", demo_out), ("hapticad demo: Globe: about 252,000 triangles",))):
            with self.subTest(args=args):
                start = time.monotonic()
                proc = run_cli(*args, timeout=40)  # meshed, they take 19 s and 8 minutes
                self.assertLess(time.monotonic() - start, 20.0)  # FreeCAD starting, not meshing
                self.assertEqual(proc.returncode, 2, proc.stderr)
                for text in said:
                    self.assertIn(text, proc.stderr)
                self.assertIn("Nothing was built.", proc.stderr)
                self.assertEqual(proc.stdout, "")
        self.assertFalse(os.path.exists(out))

    def test_bad_input_gets_a_clear_error(self):
        out = os.path.join(self.tmp.name, "bad")
        cut_short = os.path.join(self.tmp.name, "cut_short.FCStd")
        with open(self.doc_path, "rb") as whole, open(cut_short, "wb") as part:
            part.write(whole.read()[:3000])  # FreeCAD opened it and said every face was gone
        # a whole archive whose Document.xml is cut short: FreeCAD opened it as surfaces
        # without their properties, and feel raised AttributeError
        bad_xml = os.path.join(self.tmp.name, "bad_xml.FCStd")
        with zipfile.ZipFile(self.doc_path) as source, zipfile.ZipFile(bad_xml, "w") as copy:
            for item in source.infolist():
                data = source.read(item.filename)
                copy.writestr(item, data[:len(data) // 2] if item.filename == "Document.xml" else data)
        cases = [
            (("feel", cut_short, "--stroke", "1,1,20:2,2,20", "--out", out), "a damaged one"),
            (("feel", bad_xml, "--stroke", "1,1,20:2,2,20", "--out", out),
             f"{bad_xml}: a damaged FreeCAD document: its Document.xml cannot be read ("),
            (("feel", self.doc_path + "x", "--stroke", "1,1,20:2,2,20", "--out", out), "no such file"),
            (("feel", self.doc_path, "--stroke", "10,20,50:70,20,50", "--out", out), "from the nearest surface"),
            (("feel", self.doc_path, "--stroke", "10,20:70,20,20", "--out", out), "is not X,Y,Z"),
            (("feel", self.doc_path, "--stroke", "10,20,20:70,20,20", "--speed", "-3", "--out", out), "speed"),
            # real time: 60 mm at 1 um/s would run for 17 hours (and its trace fill the memory)
            (("feel", self.doc_path, "--stroke", "10,20,20:70,20,20", "--speed", "0.001", "--out", out),
             "takes 6e+04 s; strokes run in real time: give one under 600 s"),
        ]
        for args, message in cases:
            with self.subTest(message=message):
                proc = run_cli(*args)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)
                self.assertEqual(proc.stdout, "")

    def test_an_out_folder_that_is_a_file_is_refused_before_the_stroke(self):
        # it ran the stroke, then said "[Errno 17] File exists"
        with open(self.doc_path, "rb") as source:
            held = source.read()
        with tempfile.TemporaryDirectory() as tmp:
            aside = os.path.join(tmp, "aside")
            os.mkdir(aside)
            as_trace = os.path.join(aside, "trace.png")  # the document read, where the plot would go
            with open(as_trace, "wb") as copy:
                copy.write(held)
            for doc, out, message in (
                    (self.doc_path, self.doc_path,
                     f"argument --out: {self.doc_path} is a file, not a folder: give a folder to write in"),
                    (self.doc_path, os.path.join(self.doc_path, "sub"),
                     f"argument --out: {os.path.join(self.doc_path, 'sub')}: {self.doc_path} is a file, not a folder"),
                    (self.doc_path, "", "argument --out: an empty name"),
                    (as_trace, aside, f"argument --out: {as_trace} is a FreeCAD document: writing the trace.png "
                                      "over it would lose it")):
                with self.subTest(out=out):
                    proc = run_cli("feel", doc, "--stroke", "10,20,20:70,20,20", "--out", out)
                    self.assertEqual(proc.returncode, 2, proc.stderr)
                    self.assertIn(message, proc.stderr)
                    self.assertEqual(proc.stdout, "")
            for path in (self.doc_path, as_trace):
                with open(path, "rb") as kept:
                    self.assertEqual(kept.read(), held)
            self.assertEqual(os.listdir(aside), ["trace.png"])


class TablesCommandTest(unittest.TestCase):
    def test_roughness_table_json_is_table_2(self):
        proc = run_cli("roughness-table", "--json")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        rows = json.loads(proc.stdout)
        self.assertEqual([r["category"] for r in rows], list(range(1, 8)))
        self.assertEqual(set(rows[0]), {"category", "ra_min_um", "ra_max_um", "n_grades", "grid_size_mm"})
        self.assertEqual(rows[0], {"category": 1, "ra_min_um": None, "ra_max_um": 0.05,
                                   "n_grades": ["N1", "N2"], "grid_size_mm": 0.1})
        self.assertEqual(rows[3], {"category": 4, "ra_min_um": 0.8, "ra_max_um": 3.2,
                                   "n_grades": ["N7", "N8"], "grid_size_mm": 0.9})
        self.assertEqual(rows[6], {"category": 7, "ra_min_um": 50.0, "ra_max_um": None,
                                   "n_grades": [], "grid_size_mm": 3.0})

    def test_materials_json_lists_every_material_with_sources(self):
        proc = run_cli("materials", "--json", "--shipped-only")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        rows = json.loads(proc.stdout)
        names = [r["name"] for r in rows]
        for name in ("Steel", "Aluminium", "Glass", "ABS", "PP", "PC", "PMMA", "TPE soft-touch", "Rubber", "Wood"):
            self.assertIn(name, names)
        for row in rows:
            self.assertTrue(row["mu_source"] and row["bulk_source"], row)
            self.assertGreater(row["youngs_modulus_gpa"], 0)

    def test_materials_can_be_exported_as_freecad_cards(self):
        with tempfile.TemporaryDirectory() as tmp:
            proc = run_cli("materials", "--json", "--shipped-only", "--export-fcmat", tmp)
            self.assertEqual(proc.returncode, 0, proc.stderr)
            cards = sorted(os.listdir(tmp))
            self.assertEqual(len(cards), len(json.loads(proc.stdout)))
            self.assertIn("HaptiCAD-TPE-soft-touch.FCMat", cards)
        self.assertEqual(run_cli("materials", "--export-fcmat", "/nonexistent/dir").returncode, 2)

    def test_exported_cards_already_there_are_kept_unless_overwrite(self):
        # the export replaced, without a word, a card the designer had edited
        with tempfile.TemporaryDirectory() as tmp:
            edited = os.path.join(tmp, "HaptiCAD-ABS.FCMat")
            mine = "; my edited card\n[General]\nName = ABS\n"
            with open(edited, "w", encoding="utf-8") as handle:
                handle.write(mine)
            proc = run_cli("materials", "--json", "--shipped-only", "--export-fcmat", tmp)
            self.assertEqual(proc.returncode, 0, proc.stderr)  # nothing the designer made is lost
            self.assertEqual(len(os.listdir(tmp)), len(json.loads(proc.stdout)))
            with open(edited, encoding="utf-8") as handle:
                self.assertEqual(handle.read(), mine)
            self.assertIn(f"kept 1 card already in {tmp} that differs from HaptiCAD's (edited?), not replaced: "
                          "HaptiCAD-ABS.FCMat; give --overwrite to replace it", proc.stderr)
            # again: HaptiCAD's own cards, unchanged, are not news
            again = run_cli("materials", "--shipped-only", "--export-fcmat", tmp)
            self.assertEqual(again.returncode, 0, again.stderr)
            self.assertIn("kept 1 card", again.stderr)
            proc = run_cli("materials", "--shipped-only", "--export-fcmat", tmp, "--overwrite")
            self.assertEqual(proc.returncode, 0, proc.stderr)
            self.assertNotIn("kept", proc.stderr)
            with open(edited, encoding="utf-8") as handle:
                self.assertIn("HaptiCAD_StaticFriction = ", handle.read())
            proc = run_cli("materials", "--overwrite")
            self.assertEqual(proc.returncode, 2)
            self.assertIn("--overwrite replaces cards --export-fcmat DIR writes", proc.stderr)

    def test_an_export_folder_that_is_a_file_is_said_so(self):
        with tempfile.NamedTemporaryFile() as afile:
            proc = run_cli("materials", "--export-fcmat", afile.name)
            self.assertEqual(proc.returncode, 2)
            self.assertIn(f"{afile.name} is a file, not a folder: give --export-fcmat the folder", proc.stderr)
            self.assertEqual(os.path.getsize(afile.name), 0)

    def test_a_rejected_card_is_said_and_fails_the_command_but_the_rest_is_listed(self):
        with tempfile.TemporaryDirectory() as data:
            os.makedirs(os.path.join(data, "FreeCAD", "Material"))
            card = os.path.join(data, "FreeCAD", "Material", "Broken.FCMat")
            with open(card, "w", encoding="utf-8") as handle:
                handle.write("[General]\nName = Broken\n[HaptiCAD]\nHaptiCAD_StaticFriction = 0.5\n")
            env = dict(os.environ, XDG_DATA_HOME=data)
            proc = subprocess.run([CLI, "materials", "--json"], capture_output=True, text=True, timeout=120, env=env)
            self.assertEqual(proc.returncode, 1, proc.stderr)
            self.assertIn(f"rejected {card}:4: the card lacks HaptiCAD_DynamicFriction", proc.stderr)
            self.assertIn("1 entry rejected", proc.stderr)
            names = [r["name"] for r in json.loads(proc.stdout)]
            self.assertIn("Steel", names)
            self.assertNotIn("Broken", names)
            # --shipped-only does not read the user's cards: nothing to refuse
            self.assertEqual(subprocess.run([CLI, "materials", "--shipped-only"], capture_output=True,
                                            timeout=120, env=env).returncode, 0)


class PatternStrokeTest(unittest.TestCase):
    """A linear pattern felt through the CLI: mu_a along the stripes, mu_n across."""

    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.doc_path = os.path.join(cls.tmp.name, "striped.FCStd")
        doc = App.newDocument("Striped")
        box = doc.addObject("Part::Box", "Box")
        box.Length, box.Width, box.Height = 80, 80, 20
        doc.recompute()
        HaptiCAD.make_surface(doc, [(box, "Face6")], material="PMMA", static_friction=0.4,
                              dynamic_friction=0.3, pattern="Linear", pattern_angle_deg=0.0,
                              AcrossFriction=2.0, FeelRoughness=False)
        doc.saveAs(cls.doc_path)
        App.closeDocument(doc.Name)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def ratio(self, stroke):
        proc = run_cli("feel", self.doc_path, "--stroke", stroke, "--out", os.path.join(self.tmp.name, "s"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        return json.loads(proc.stdout)["faces"]["Box.Face6"]["mean_ft_over_fn"]

    def test_along_across_and_diagonal(self):
        self.assertAlmostEqual(self.ratio("10,40,20:70,40,20"), 0.3, delta=0.015)   # along x: mu_a
        self.assertAlmostEqual(self.ratio("40,10,20:40,70,20"), 0.6, delta=0.03)    # across: mu_n
        self.assertAlmostEqual(self.ratio("15,15,20:65,65,20"), 0.45, delta=0.0225)  # eq. 3 at 45 degrees


if __name__ == "__main__":
    unittest.main()
