# SPDX-License-Identifier: GPL-3.0-or-later
"""`hapticad fit-texture` end to end: a rig's recording is fitted (JSON, text and a plot),
the fit is set on a document's surface and saved; bad input gets a clear error (exit 2)
and leaves the document as it was.

Environment: HAPTICAD_CLI (the launcher), HAPTICAD_MOD (the staged Mod folder).
Runs under /usr/bin/python3 (FreeCAD's interpreter)."""
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

App = ensure_freecad()
import HaptiCAD  # noqa: E402
from hapticad import _core  # noqa: E402
from other_user import run_as_nobody, shared_folder  # noqa: E402
from partdesign_parts import make_padded_body  # noqa: E402
from texture_recordings import write_rig_csv  # noqa: E402

assert HaptiCAD.__file__.startswith(os.environ["HAPTICAD_MOD"]), HaptiCAD.__file__


def run_cli(*args, cwd=None):
    return subprocess.run([CLI, *args], capture_output=True, text=True, timeout=120, cwd=cwd)


class FitTextureCommandTest(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tmp = tempfile.TemporaryDirectory()
        cls.rig = os.path.join(cls.tmp.name, "rig.csv")
        write_rig_csv(_core, cls.rig, speeds_mm_s=(50.0, 120.0), f_dc=0.4, f_vis=0.2, full_range_n=2.0)

    @classmethod
    def tearDownClass(cls):
        cls.tmp.cleanup()

    def make_document(self, name):
        path = os.path.join(self.tmp.name, name)
        doc = App.newDocument("CliFit")
        box = doc.addObject("Part::Box", "Box")
        doc.recompute()
        surface = HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS", FeelRoughness=False,
                                        TextureFullRange=2.0)
        surface.Label = "Grip"
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        return path

    def test_a_partdesign_body_comes_through_the_apply_whole(self):
        path = os.path.join(self.tmp.name, "body.FCStd")
        doc = App.newDocument("CliFitBody")
        _, surface = make_padded_body(App, HaptiCAD, doc)
        surface.Label = "Top"
        doc.saveAs(path)
        App.closeDocument(doc.Name)
        with open(path, "rb") as f:
            saved = f.read()
        # a FreeCAD without the PartDesign workbench leaves the Body out: refused, the file as it was
        proc = subprocess.run([CLI, "fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120",
                               "--apply", path, "--surface", "Top"], capture_output=True, text=True, timeout=120,
                              env={**os.environ, "HAPTICAD_FREECAD_MOD": os.path.join(self.tmp.name, "no-mods")})
        self.assertEqual(proc.returncode, 2, proc.stdout)
        self.assertIn("this FreeCAD could not load 2 of its objects: Body (PartDesign::Body), BodyPad (PartDesign::Pad)",
                      proc.stderr)
        self.assertIn("nothing was read or changed", proc.stderr)
        with open(path, "rb") as f:
            self.assertEqual(f.read(), saved)
        # with it (as installed): the fit is set, and the Body and its tag are still there
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120",
                       "--apply", path, "--surface", "Top")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        doc = App.openDocument(path)
        try:
            self.assertEqual(sorted(o.TypeId for o in doc.Objects if o.TypeId.startswith("PartDesign")),
                             ["PartDesign::Body", "PartDesign::Pad"])
            surface = doc.getObjectsByLabel("Top")[0]
            self.assertEqual([o.Name for o, _ in surface.References], ["Body"])
            self.assertEqual(surface.Texture, "Custom")
        finally:
            App.closeDocument(doc.Name)

    def test_fits_a_recording_and_plots_it(self):
        plot = os.path.join(self.tmp.name, "fit.png")
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--json", "--plot", plot)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        result = json.loads(proc.stdout)
        self.assertEqual([s["sections"] for s in result["speeds"]], [2, 2])
        self.assertAlmostEqual(result["eq2_newtons"]["f_dc_n"], 0.8, delta=0.01)
        self.assertAlmostEqual(result["eq2_newtons"]["f_vis_n_per_400mm_s"], 0.4, delta=0.02)
        self.assertGreater(os.path.getsize(plot), 10000)
        text = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120")
        self.assertEqual(text.returncode, 0, text.stderr)
        self.assertIn("eq. 2 in newtons", text.stdout)

    def test_sets_the_fit_on_a_surface_and_saves_the_document(self):
        path = self.make_document("apply.FCStd")
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--json",
                       "--apply", path, "--surface", "Grip")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(json.loads(proc.stdout)["applied"]["surface"], "Grip")
        doc = App.openDocument(path)
        try:
            surface = doc.getObjectsByLabel("Grip")[0]
            self.assertEqual(surface.Texture, "Custom")
            self.assertAlmostEqual(surface.TextureDC, 0.4, delta=0.005)
            self.assertAlmostEqual(surface.TextureViscosity, 0.2, delta=0.01)
            self.assertAlmostEqual(surface.TexturePeriod, 2.5)
        finally:
            App.closeDocument(doc.Name)

    def test_the_saved_document_keeps_what_freecads_gui_shows(self):
        # saved without the GUI, the toothbrush opened in FreeCAD with every part hidden
        # and grey: GuiDocument.xml and the colour arrays it names were dropped
        import shutil
        import zipfile

        example = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "resources", "examples",
                               "toothbrush.FCStd")
        path = os.path.join(self.tmp.name, "toothbrush.FCStd")
        shutil.copyfile(example, path)
        with zipfile.ZipFile(path) as archive:
            gui = {n: archive.read(n) for n in archive.namelist() if n != "Document.xml" and not n.endswith(".brp")}
        self.assertIn("GuiDocument.xml", gui)
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--apply", path,
                       "--surface", "ThumbGrip")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        with zipfile.ZipFile(path) as archive:
            self.assertIsNone(archive.testzip())
            for name, data in gui.items():
                self.assertEqual(archive.read(name), data, name)
            self.assertIn('value="Custom"', archive.read("Document.xml").decode())  # and the fit is in it

    def test_bad_input_is_refused_and_the_document_is_left_alone(self):
        path = self.make_document("untouched.FCStd")
        before = os.path.getmtime(path)
        cases = [
            (("fit-texture", os.path.join(self.tmp.name, "missing.csv"), "--period", "2.5"),
             f"{os.path.join(self.tmp.name, 'missing.csv')}: there is no such file"),
            (("fit-texture", self.tmp.name, "--period", "2.5"),
             f"{self.tmp.name} is a folder, not a recording: give the CSV files in it"),
            (("fit-texture", self.rig, "--period", "2.5", "--apply", path), "go together"),
            (("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--apply", path, "--surface",
              "Handle"), "no haptic surface named 'Handle' (it has: Grip)"),
            (("fit-texture", self.rig, "--period", "2.5", "--speeds", "300"), "no section of constant speed"),
            (("fit-texture", self.rig, "--period", "0", "--speeds", "50"), "period must be > 0"),
            (("fit-texture", self.rig, "--period", "2.5", "--speeds", "fast"), "not a list of speeds"),
        ]
        for args, message in cases:
            with self.subTest(message=message):
                proc = run_cli(*args)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)
        self.assertEqual(os.path.getmtime(path), before)


    def test_a_document_the_user_cannot_write_is_refused_before_the_fit_and_left_alone(self):
        # run as another user (root may write anything): FreeCAD replaced a read-only file
        # in a writable folder, and in a folder it could not write in the error was a dict
        # of FreeCAD's exception fields ('sclassname': 'N4Base13FileExceptionE', ...)
        import shutil
        import stat

        place = shared_folder(self)
        rig = shutil.copy(self.rig, place)
        open_folder = os.path.join(place, "open")  # anyone may write in it, the file is read-only
        locked_folder = os.path.join(place, "locked")  # nobody may write in it, the file is writable
        for folder, folder_mode, file_mode in ((open_folder, 0o777, 0o444), (locked_folder, 0o755, 0o666)):
            os.mkdir(folder)
            path = shutil.copy(self.make_document("doc.FCStd"), folder)
            os.chmod(path, file_mode)
            os.chmod(folder, folder_mode)
        cases = ((os.path.join(open_folder, "doc.FCStd"), "the file is read-only for you; nothing was saved"),
                 (os.path.join(locked_folder, "doc.FCStd"), f"its folder {locked_folder} cannot be written in"))
        for path, message in cases:
            with self.subTest(message=message):
                before = (os.stat(path).st_mtime_ns, os.stat(path).st_ino)
                proc = run_as_nobody(place, [CLI, "fit-texture", rig, "--period", "2.5", "--speeds", "50,120",
                                             "--apply", path, "--surface", "Grip"])
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(f"{path}: ", proc.stderr)
                self.assertIn(message, proc.stderr)
                self.assertNotIn("sclassname", proc.stderr)
                self.assertEqual((os.stat(path).st_mtime_ns, os.stat(path).st_ino), before)
                self.assertEqual(sorted(os.listdir(os.path.dirname(path))), ["doc.FCStd"])
                self.assertEqual(stat.S_IMODE(os.stat(path).st_mode), 0o444 if "read-only" in message else 0o666)

    def test_forces_in_mn_are_refused_on_a_surface_with_a_full_range_too(self):
        # after a fit set Full range, a rig's mN were set as levels of hundreds (TextureDC
        # 571), exit 0, only "above level 1 it is clipped"; at the device's full range refused
        millinewtons = os.path.join(self.tmp.name, "millinewtons.csv")
        write_rig_csv(_core, millinewtons, speeds_mm_s=(50.0, 120.0), full_range_n=2000.0)
        path = self.make_document("full_range.FCStd")  # Full range 2 N
        with open(path, "rb") as f:
            saved = f.read()
        proc = run_cli("fit-texture", millinewtons, "--period", "2.5", "--speeds", "50,120", "--apply", path,
                       "--surface", "Grip")
        self.assertEqual(proc.returncode, 2, proc.stdout)
        self.assertIn("are the forces recorded in mN? Give lateral_force_n in newtons; nothing was changed",
                      proc.stderr)
        with open(path, "rb") as f:
            self.assertEqual(f.read(), saved)

    def test_recordings_are_named_as_given(self):
        # `hapticad feel` writes every trace as trace.csv: "note: trace.csv gave no section"
        # did not say which of several
        for folder, speed in (("slow", 50.0), ("fast", 120.0), ("other", 200.0)):
            os.makedirs(os.path.join(self.tmp.name, "named", folder), exist_ok=True)
            write_rig_csv(_core, os.path.join(self.tmp.name, "named", folder, "trace.csv"), speeds_mm_s=(speed,))
        proc = run_cli("fit-texture", "slow/trace.csv", "fast/trace.csv", "other/trace.csv", "--period", "2.5",
                       "--speeds", "50,120", cwd=os.path.join(self.tmp.name, "named"))
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertIn("note: other/trace.csv gave no section", proc.stdout)
        proc = run_cli("fit-texture", "slow/trace.csv", "gone/trace.csv", "--period", "2.5",
                       cwd=os.path.join(self.tmp.name, "named"))
        self.assertEqual(proc.returncode, 2, proc.stdout)
        self.assertEqual(proc.stderr, "hapticad fit-texture: gone/trace.csv: there is no folder gone\n")

    def test_a_slow_low_pass_settles_before_the_sections_start_or_is_said(self):
        # the core cut the sections from the filtered force as the strokes began: --lowpass 3
        # gave f_vis 0.11 for 0.2 and --lowpass 1 -0.52, and said nothing
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--lowpass", "3", "--json")
        self.assertEqual(proc.returncode, 0, proc.stderr)
        eq2 = json.loads(proc.stdout)["eq2_newtons"]  # f_vis 0.2 levels of 2 N
        self.assertAlmostEqual(eq2["f_vis_n_per_400mm_s"], 0.4, delta=0.01)
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--lowpass", "1")
        self.assertEqual(proc.returncode, 2, proc.stdout)
        self.assertIn("the low-pass at 1 Hz needs 1.1 s to settle, left out at the start of each stroke: give a "
                      "higher cut-off (the paper's 1000 Hz)", proc.stderr)

    def test_counts_beyond_their_range_name_the_option_and_the_range(self):
        for args, message in ((("--harmonics", "99999999999999999999"),
                               "argument --harmonics: 99999999999999999999 is out of range: give a whole number "
                               "from 2 to 8"),
                              (("--harmonics", "9"), "--harmonics: 9 is out of range: give a whole number from 2 to 8"),
                              (("--harmonics", "2.5"), "--harmonics: '2.5' is not a whole number"),
                              (("--min-periods", "2147483648"),
                               "argument --min-periods: 2147483648 is out of range: give a whole number from 6 to "
                               "100000"),
                              (("--min-periods", "5"), "--min-periods: 5 is out of range")):
            with self.subTest(args=args):
                proc = run_cli("fit-texture", self.rig, "--period", "2.5", *args)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)
                self.assertNotIn("Traceback", proc.stderr)

    def test_the_plot_reported_is_the_file_written(self):
        # no extension: .png is added, and that file is what the JSON and the text name
        base = os.path.join(self.tmp.name, "noext")
        proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--json", "--plot", base)
        self.assertEqual(proc.returncode, 0, proc.stderr)
        self.assertEqual(json.loads(proc.stdout)["plot"], base + ".png")
        with open(base + ".png", "rb") as f:
            self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
        text = run_cli("fit-texture", self.rig, "--period", "2.5", "--speeds", "50,120", "--plot", base)
        self.assertIn(f"plot: {base}.png", text.stdout)
        # a folder, another extension or no name at all: refused before anything is fitted or written
        folder = os.path.join(self.tmp.name, "plots")
        os.mkdir(folder)
        for plot, message in ((folder, f"argument --plot: {folder} is a folder: give the PNG file to write in it, "
                                       f"like {os.path.join(folder, 'plot.png')}"),
                              (os.path.join(self.tmp.name, "fit.txt"),
                               "the plot is a PNG image, so the name must end in .png"),
                              ("", "argument --plot: an empty name: give the PNG file to write")):
            with self.subTest(plot=plot):
                proc = run_cli("fit-texture", self.rig, "--period", "2.5", "--plot", plot)
                self.assertEqual(proc.returncode, 2, proc.stderr)
                self.assertIn(message, proc.stderr)
        self.assertFalse(os.path.exists(folder + ".png"))
        self.assertFalse(os.path.exists(os.path.join(self.tmp.name, "fit.txt")))

if __name__ == "__main__":
    unittest.main()
