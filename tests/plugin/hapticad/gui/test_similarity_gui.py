# SPDX-License-Identifier: GPL-3.0-or-later
"""Similarity studies in FreeCAD's real GUI (Xvfb): the command makes a study of the
selected surface and its panel edits the stimuli (each an undo step, the panel following
undo); during a Feel session a participant's run puts each texture on the face at once,
takes their answers only once they felt both textures, and is kept when done; the panel
then shows the cohort's perceptual space. Run by gui_test_runner.py."""
import os
import random
import re
import sys
import tempfile
import unittest
from unittest import mock

import numpy as np

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtWidgets

import HaptiCAD
from hapticad import preferences, similarity_study as ss
from hapticad.gui import task_panel_feel

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402


class SeededRun(ss.Run):
    def __init__(self, study, participant, seed=20261124):
        super().__init__(study, participant, seed)


def simulated_run(study, name, seed):
    """A participant (answered in code) who tells the textures apart by f_DC and f_vis."""
    rng = random.Random(seed)
    run = ss.Run(study, name, seed=seed)
    while not run.done:
        t = run.current
        run.present_each()  # a trial takes its answer once its textures were felt
        if t.kind == "class":
            v = run.stimuli[t.first]["values"]
            run.answer("A" if v["TextureDC"] + v["TextureViscosity"] < 0.5 else "B")
            continue
        a, b = (run.stimuli[i]["values"] for i in (t.first, t.second))
        d = np.hypot((a["TextureDC"] - b["TextureDC"]) / 0.35,
                     0.5 * (a["TextureViscosity"] - b["TextureViscosity"]) / 0.4)
        run.answer(int(min(7, max(1, round(1 + (1 - d / 1.12 + rng.gauss(0, 0.05)) * 6)))))
    return run


class SimilarityGuiTest(unittest.TestCase):
    def setUp(self):
        preferences.update(device="simulated", servo_rate_hz=1000)
        # a participant's run is shuffled from the system's entropy: here from a seed, so
        # each test strokes the same pairs every time
        seeded = mock.patch.object(ss, "Run", SeededRun)
        seeded.start()
        self.addCleanup(seeded.stop)
        self.doc = App.newDocument("SimilarityGui")
        self.doc.UndoMode = 1
        self.box = self.doc.addObject("Part::Box", "Plate")
        self.box.Length, self.box.Width, self.box.Height = 60, 40, 10
        self.doc.recompute()
        self.plate = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], material="ABS", FeelRoughness=False,
                                           TextureScale="Device force", TextureFullRange=1.5)
        samples = self.doc.addObject("Part::Box", "Samples")
        samples.Placement.Base = App.Vector(0, 80, 0)
        self.doc.recompute()
        self.ref_a = HaptiCAD.make_surface(self.doc, [(samples, "Face6")], material="ABS", FeelRoughness=False,
                                           Texture="Custom", TextureDC=0.2, TextureViscosity=-0.3)
        self.ref_a.Label = "Stiff grating"
        self.ref_b = HaptiCAD.make_surface(self.doc, [(samples, "Face5")], material="ABS", FeelRoughness=False,
                                           Texture="Custom", TextureDC=0.8, TextureViscosity=0.3)
        self.ref_b.Label = "Soft grating"
        self.doc.recompute()
        Gui.Selection.clearSelection()
        h.show_workbench()

    def tearDown(self):
        if Gui.Control.activeDialog():
            h.press_task_button("Close")
        Gui.Selection.clearSelection()
        App.closeDocument(self.doc.Name)

    def test_undoing_the_studys_creation_with_its_panel_open_leaves_no_traceback(self):
        # the panel's load ran a turn later on a closed panel: "for box in self.form:
        # TypeError: 'NoneType' object is not iterable"
        Gui.Selection.addSelection(self.plate)
        Gui.runCommand("HaptiCAD_SimilarityStudy")
        h.process_events()
        self.assertTrue(Gui.Control.activeDialog())
        before = h.report_text()
        with h.uncaught_errors() as errors:
            Gui.runCommand("Std_Undo")
            h.wait(0.5)
        self.assertEqual(HaptiCAD.similarity_studies_of(self.doc), [])
        self.assertFalse(Gui.Control.activeDialog())
        self.assertEqual(errors, [])
        self.assertNotIn("Traceback", h.report_text()[len(before):])

    def test_the_panel_edits_the_stimuli_and_follows_undo(self):
        Gui.Selection.addSelection(self.plate)
        Gui.runCommand("HaptiCAD_SimilarityStudy")
        h.process_events()
        self.assertTrue(Gui.Control.activeDialog())
        (study,) = HaptiCAD.similarity_studies_of(self.doc)
        self.assertIn("Similarity study", self.doc.UndoNames)  # making it is an undo step
        table = h.widget(QtWidgets.QTableWidget, "stimuliTable")
        self.assertEqual(table.rowCount(), 9)
        self.assertIn("no references", h.widget(QtWidgets.QLabel, "similarityStatus").text())
        self.assertIn("no participant has rated these stimuli yet", h.widget(QtWidgets.QLabel, "spaceText").text())
        source = h.widget(QtWidgets.QComboBox, "stimulusSource")
        self.assertEqual([source.itemText(i) for i in range(source.count())], ["Stiff grating", "Soft grating"])
        source.setCurrentText("Soft grating")
        h.widget(QtWidgets.QPushButton, "addStimulus").click()
        self.assertEqual(table.rowCount(), 10)
        self.assertEqual(ss.stimuli(study)[-1]["name"], "Soft grating")
        # only eq. 2's values come along: felt at the plate's level 1, which the panel says
        self.assertIn(f"a stimulus is felt with {self.plate.Label}'s full range 1.5 N, not Soft grating's the "
                      "device's full range", h.widget(QtWidgets.QLabel, "stimuliMessage").text())
        # adding it again is refused, said, and changes nothing
        h.widget(QtWidgets.QPushButton, "addStimulus").click()
        self.assertIn("same texture as", h.widget(QtWidgets.QLabel, "stimuliMessage").text())
        self.assertEqual(len(ss.stimuli(study)), 10)
        table.selectRow(0)
        h.widget(QtWidgets.QPushButton, "removeStimulus").click()
        self.assertEqual(len(ss.stimuli(study)), 9)
        self.assertEqual(ss.stimuli(study)[0]["name"], "f_DC 0.325 f_vis +0.0")
        self.doc.undo()  # the removal undone: the panel shows it
        h.process_events()
        self.assertEqual(table.rowCount(), 10)
        self.assertEqual(table.item(0, 0).text(), "f_DC 0.325 f_vis -0.2")
        h.widget(QtWidgets.QPushButton, "paperStimuli").click()
        self.assertEqual(len(ss.stimuli(study)), 9)
        # references set in the property editor: the panel follows
        study.ReferenceA, study.ReferenceB = self.ref_a, self.ref_b
        h.process_events()
        self.assertIn("classed against Stiff grating (A) and Soft grating (B)",
                      h.widget(QtWidgets.QLabel, "similarityStatus").text())
        h.press_task_button("Close")
        self.assertFalse(Gui.Control.activeDialog())

    def test_closing_the_feel_panel_in_the_middle_of_a_run_asks_first(self):
        from hapticad import run_journal

        self.doc.saveAs(os.path.join(tempfile.mkdtemp(), "study.FCStd"))  # its runs in progress are written
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        panel = task_panel_feel.active_panel()
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Eve")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        controls = panel.similarity_controls[0]
        self.hand_on_plate()
        self.feel_both(controls)
        h.widget(QtWidgets.QPushButton, "similarityRate4").click()
        self.assertEqual(len(controls.run.answers), 1)
        self.assertEqual(run_journal.read(study)["answers"], [4])
        asked = []
        original = QtWidgets.QMessageBox.question
        try:
            QtWidgets.QMessageBox.question = staticmethod(
                lambda *args, **kwargs: asked.append(args[2]) or QtWidgets.QMessageBox.Cancel)
            h.press_task_button("Close")
            h.process_events()
            self.assertTrue(Gui.Control.activeDialog())  # kept open: the run goes on
            self.assertIsNotNone(controls.run)
            self.assertIn("Eve's (1 of 38 answered)", asked[0])
            QtWidgets.QMessageBox.question = staticmethod(lambda *args, **kwargs: QtWidgets.QMessageBox.Close)
            h.press_task_button("Close")
            h.process_events()
        finally:
            QtWidgets.QMessageBox.question = original
        self.assertFalse(Gui.Control.activeDialog())
        self.assertEqual(study.Participants, 0)  # a run is kept only when finished
        self.assertIsNone(run_journal.read(study))  # ended as agreed: not offered to go on later
        self.assertIsNone(ss.presented_texture(self.plate))

    def test_the_document_stays_open_while_a_run_holds_answers(self):
        study, controls = self.start_run("Eve")
        self.assertEqual(controls.run.seed, 20261124)  # the same trials every time
        self.assertTrue(self.doc.isClosable())  # nothing answered yet: nothing to lose
        self.hand_on_plate()
        self.feel_both(controls)
        h.widget(QtWidgets.QPushButton, "similarityRate4").click()
        self.assertIn("The document stays open until this run ends",
                      h.widget(QtWidgets.QLabel, "similarityTrial").text())
        h.widen_panel()
        h.grab_screen("feel_similarity_held.png")
        # every way of closing it: the 3D view's window, Close All, a script
        with h.MessageBoxes() as boxes:
            Gui.runCommand("Std_CloseActiveWindow")
            h.process_events()
            Gui.runCommand("Std_CloseAllWindows")
            h.process_events()
        self.assertEqual([title for title, _ in boxes.seen], ["Document not closable"] * 2)
        with self.assertRaises(Exception):
            App.closeDocument(self.doc.Name)
        self.assertIn(self.doc.Name, App.listDocuments())
        self.assertEqual(len(controls.run.answers), 1)  # the run and its answer are still there
        h.widget(QtWidgets.QPushButton, "similarityBack").click()  # nothing answered again
        self.assertTrue(self.doc.isClosable())
        self.feel_both(controls)
        h.widget(QtWidgets.QPushButton, "similarityRate3").click()
        self.assertFalse(self.doc.isClosable())
        h.widget(QtWidgets.QPushButton, "similarityStop").click()  # ended on purpose: closable
        self.assertTrue(self.doc.isClosable())
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.feel_both(controls)
        h.widget(QtWidgets.QPushButton, "similarityRate5").click()
        self.assertFalse(self.doc.isClosable())
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.Close):
            h.press_task_button("Close")
        self.assertFalse(Gui.Control.activeDialog())
        self.assertTrue(self.doc.isClosable())
        self.assertEqual(study.Participants, 0)

    def start_run(self, name):
        """A study of two warm-ups on the plate, the Feel panel open on it, and ``name``'s
        run started: (the study, its controls)."""
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        controls = task_panel_feel.active_panel().similarity_controls[0]
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText(name)
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        return study, controls

    def run_in_feel(self, name):
        """Opens Feel on the document and answers ``name``'s whole run there: its controls."""
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        controls = task_panel_feel.active_panel().similarity_controls[0]
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText(name)
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.answer_in_code(controls)
        return controls

    def answer_in_code(self, controls, count=None):
        """Answers the run's trials through the controls (4, or A), each texture counted
        as felt without strokes: for the keeping and pausing around the answers."""
        answered = 0
        while controls.run is not None and controls.run.current is not None and answered != count:
            controls.run.present_each()
            controls.answer("A" if controls.run.current.kind == "class" else 4)
            answered += 1

    def test_an_undo_that_takes_back_a_kept_run_is_said_and_the_next_keep_asks(self):
        # one Undo during Bea's run took Ada's kept run back without a word, and keeping
        # Bea's run cleared Redo: Ada's 38 answers were gone for good
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        controls = task_panel_feel.active_panel().similarity_controls[0]
        message = h.widget(QtWidgets.QLabel, "similarityMessage")
        for name in ("Ada", "Bea"):
            h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText(name)
            h.widget(QtWidgets.QPushButton, "similarityStart").click()
            self.answer_in_code(controls, None if name == "Ada" else 5)
        self.assertEqual(study.Participants, 1)
        # what rendered it is kept with it: a practice run on the mouse is told from a device's
        (ada,) = ss.runs(study)
        self.assertEqual((ada["device"], ada["servo_rate_hz"]), ("Simulated hand", 1000.0))
        self.assertLessEqual(ada["started"], ada["recorded"])
        Gui.runCommand("Std_Undo")
        h.process_events()
        self.assertEqual(study.Participants, 0)
        self.assertIn("Undo took back Ada's kept run: Redo brings it back", message.text())
        self.assertEqual(len(controls.run.answers), 5)  # Bea's run goes on
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.Yes) as asked:
            self.answer_in_code(controls)
        self.assertIn("Undo took back Ada's kept run", asked.call_args[0][2])
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Ada", "Bea"])
        # taken back on purpose: answered No, only the new run is kept
        Gui.runCommand("Std_Undo")
        h.process_events()
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Cy")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.No):
            self.answer_in_code(controls)
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Cy"])

    def test_a_run_freecad_never_kept_goes_on_where_it_stopped(self):
        # a crash at trial 74 lost the whole run: the document holds a run only once kept
        from hapticad import run_journal
        from hapticad.gui.similarity_controls import SimilarityControls

        folder = tempfile.mkdtemp()
        self.doc.saveAs(os.path.join(folder, "study.FCStd"))  # a journal is named by the document's path
        study, controls = self.start_run("Fay")
        # Fay's run is kept and never saved: its file lives in the test's FreeCAD home
        path, name = self.doc.FileName, study.Name
        self.addCleanup(lambda: [os.remove(f) for f in run_journal._kept_files(path, name)])
        self.answer_in_code(controls, 4)
        self.assertEqual(run_journal.read(study)["answers"], [4] * 4)
        # FreeCAD gone without a word: the next controls on the study (a new session) offer it
        fresh = SimilarityControls(study)
        self.addCleanup(fresh.deleteLater)
        resume = fresh.findChild(QtWidgets.QPushButton, "similarityResume")
        self.assertFalse(resume.isHidden())
        self.assertEqual(resume.text(), "Go on with Fay's run (4 of 38 answered, not kept)")
        resume.click()
        self.assertEqual((fresh.run.participant, fresh.run.answers), ("Fay", [4] * 4))
        self.assertIn("Fay's run goes on at answer 5", fresh.message.text())
        self.assertTrue(resume.isHidden())
        self.answer_in_code(fresh)
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Fay"])
        self.assertIsNone(run_journal.read(study))  # kept: the journal goes
        controls.stop()
        # one left on a study edited since: not resumed, and dropped only when asked
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Gus")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.answer_in_code(controls, 2)
        controls.run = None  # gone without a word
        self.plate.StickSpeed = 3.0  # felt by the texture (its static friction is not, under Device force)
        fresh.load()
        fresh.findChild(QtWidgets.QPushButton, "similarityResume").click()
        self.assertIsNone(fresh.run)
        self.assertIn("Gus's run cannot go on: the surface or a reference changed since. Start run drops it",
                      fresh.message.text())
        fresh.name.setText("Hal")
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.No):
            fresh.start()
        self.assertIsNone(fresh.run)  # not dropped unasked
        self.assertEqual(run_journal.read(study)["name"], "Gus")
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.Yes):
            fresh.start()
        self.assertEqual(fresh.run.participant, "Hal")
        fresh.stop()
        self.assertIsNone(run_journal.read(study))

    def test_a_kept_run_lost_with_an_unsaved_document_is_put_back(self):
        # the run is in the document once kept, on disk only once it is saved: FreeCAD
        # closed (or crashed) between the two lost it, its journal already gone
        from hapticad import run_journal

        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)
        path = os.path.join(tempfile.mkdtemp(), "study.FCStd")
        self.doc.saveAs(path)
        controls = self.run_in_feel("Ida")
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Ida"])
        self.assertIn("save the document to keep it on disk", controls.message.text())
        self.assertTrue(controls.put_back_button.isHidden())  # the document holds it
        h.press_task_button("Close")
        name = study.Name
        App.closeDocument(self.doc.Name)  # gone unsaved
        self.doc = App.openDocument(path)
        study = self.doc.getObject(name)
        self.assertEqual(ss.runs(study), [])
        Gui.runCommand("HaptiCAD_Feel")  # the panel, as the designer opens it again
        h.process_events()
        fresh = task_panel_feel.active_panel().similarity_controls[0]
        put_back = fresh.findChild(QtWidgets.QPushButton, "similarityPutBack")
        self.assertFalse(put_back.isHidden())
        self.assertEqual(put_back.text(), "Put back Ida's run (kept, document not saved)")
        self.assertFalse(fresh.findChild(QtWidgets.QPushButton, "similarityDropLost").isHidden())
        # how it was lost, under the offer: closed without saving (the close is seen), not a crash
        journal = fresh.findChild(QtWidgets.QLabel, "similarityJournal")
        self.assertFalse(journal.isHidden())
        self.assertRegex(journal.text(), r"Ida's kept run is not in the document: it was closed without saving on "
                         r"\d{4}-\d\d-\d\d at \d\d:\d\d\. Put it back, then save the document, or Drop it if the "
                         r"close was to discard it\.")
        self.assertIn("closed without saving on", put_back.toolTip())
        h.widen_panel()
        h.grab_screen("similarity_put_back.png")
        self.doc.UndoMode = 1
        put_back.click()
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Ida"])
        self.assertEqual(study.Participants, 1)
        self.assertIn("Put back kept similarity runs", self.doc.UndoNames)
        # said where the offer was, not under the trial's buttons
        self.assertIn("Put back Ida's run (1 participant). Save the document", journal.text())
        self.assertFalse(journal.isHidden())
        self.assertNotIn("Put back", fresh.message.text())
        h.grab_screen("similarity_put_back_done.png")
        self.assertTrue(put_back.isHidden())
        # Undo takes it back (Redo brings it, and the next keep asks); once an edit clears
        # Redo, it is offered again rather than lost
        self.doc.undo()
        fresh.load()
        self.assertEqual(ss.runs(study), [])
        self.assertTrue(put_back.isHidden())
        self.assertNotIn("Put back Ida's run (1 participant)", journal.text())  # said of what is undone
        self.doc.openTransaction("Rename")
        study.Label = "Study of gratings"
        self.doc.commitTransaction()
        self.assertEqual(self.doc.RedoNames, [])
        fresh.load()
        self.assertFalse(put_back.isHidden())
        put_back.click()
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Ida"])
        # saved: nothing left to put back, whatever happens next
        h.press_task_button("Close")
        self.doc.save()
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        study = self.doc.getObject(name)
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Ida"])
        self.assertEqual(run_journal.unsaved_kept(study), [])
        self.assertEqual(run_journal._kept_files(path, name), [])  # the save let its file go
        # one kept, undone and saved without it: offered until dropped, and dropped only when asked
        self.doc.UndoMode = 1
        controls = self.run_in_feel("Jan")
        self.doc.undo()
        self.doc.save()
        self.doc.openTransaction("Rename")  # and Redo cleared
        study.Label = "Gratings"
        self.doc.commitTransaction()
        controls.load()
        drop = controls.findChild(QtWidgets.QPushButton, "similarityDropLost")
        journal = controls.findChild(QtWidgets.QLabel, "similarityJournal")
        self.assertEqual(controls.put_back_button.text(), "Put back Jan's run (kept, document not saved)")
        self.assertIn("Jan's kept run is not in the document: an Undo took it out of the document before it was "
                      "saved.", journal.text())
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.No) as asked:
            drop.click()
        self.assertEqual(asked.call_args[0][2], "Drop Jan's kept run for good? No saved document holds it.")
        self.assertFalse(drop.isHidden())
        with mock.patch.object(QtWidgets.QMessageBox, "question", return_value=QtWidgets.QMessageBox.Yes):
            drop.click()
        self.assertTrue(drop.isHidden())
        self.assertTrue(controls.put_back_button.isHidden())
        self.assertIn("Dropped Jan's run.", journal.text())
        self.assertFalse(journal.isHidden())
        self.assertEqual(run_journal._kept_files(path, name), [])
        self.assertEqual([r["name"] for r in ss.runs(study)], ["Ida"])

    def test_a_kept_run_lost_before_the_document_was_moved_is_offered_saying_where_it_was(self):
        # moved after a close without saving, the document opened where it is now offered nothing
        from hapticad import run_journal

        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)
        folder = tempfile.mkdtemp()
        earlier = os.path.join(folder, "study.FCStd")
        self.doc.saveAs(earlier)
        self.run_in_feel("Ida")
        h.press_task_button("Close")
        name = study.Name
        App.closeDocument(self.doc.Name)  # gone unsaved
        moved = os.path.join(folder, "project", "plates.FCStd")
        os.makedirs(os.path.dirname(moved))
        os.rename(earlier, moved)
        for path in (earlier, moved):  # its file taken away after, wherever it is then
            self.addCleanup(lambda p=path: [os.remove(f) for f in run_journal._kept_files(p, name)])
        self.doc = App.openDocument(moved)
        study = self.doc.getObject(name)
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        fresh = task_panel_feel.active_panel().similarity_controls[0]
        self.assertFalse(fresh.findChild(QtWidgets.QPushButton, "similarityPutBack").isHidden())
        journal = fresh.findChild(QtWidgets.QLabel, "similarityJournal")
        self.assertRegex(journal.text(), r"Ida's kept run is not in the document: it was closed without saving on "
                         r"\d{4}-\d\d-\d\d at \d\d:\d\d "
                         rf"\(recorded when the document was at {re.escape(earlier)}\)\. Put it back")

    def test_a_kept_run_removed_in_the_panel_forgets_its_file_and_is_not_offered_back(self):
        # removed before a save, its file stayed beside the document: the next time, the run
        # removed on purpose was offered back as lost
        from hapticad import run_journal

        study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)
        path = os.path.join(tempfile.mkdtemp(), "study.FCStd")
        self.doc.saveAs(path)
        self.doc.UndoMode = 1
        name = study.Name
        self.addCleanup(lambda: [os.remove(f) for f in run_journal._kept_files(path, name)])
        self.run_in_feel("Ida")
        h.press_task_button("Close")
        self.assertEqual(len(run_journal._kept_files(path, name)), 1)
        Gui.ActiveDocument.setEdit(study.Name, 0)
        h.process_events()
        table = h.widget(QtWidgets.QTableWidget, "runsTable")
        table.selectRow(0)
        h.widget(QtWidgets.QPushButton, "removeRun").click()
        self.assertEqual(ss.runs(study), [])
        self.assertEqual(run_journal._kept_files(path, name), [])
        self.doc.undo()  # back in the document, unsaved: written again
        h.process_events()
        self.assertEqual(table.rowCount(), 1)
        self.assertEqual(len(run_journal._kept_files(path, name)), 1)
        table.selectRow(0)
        h.widget(QtWidgets.QPushButton, "removeRun").click()
        h.press_task_button("Close")
        App.closeDocument(self.doc.Name)  # the removal lost unsaved: the run is in no saved document
        self.doc = App.openDocument(path)
        study = self.doc.getObject(name)
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        controls = task_panel_feel.active_panel().similarity_controls[0]
        self.assertTrue(controls.put_back_button.isHidden())
        self.assertEqual(run_journal.unsaved_kept(study), [])

    def test_an_edit_during_a_run_pauses_it_and_undoing_the_edit_goes_on(self):
        # a friction edit at trial 60 threw the run's answers away, and undoing it did not
        # bring them back (the stick speed: the texture uses it)
        study, controls = self.start_run("Dee")
        self.answer_in_code(controls, 3)
        self.doc.openTransaction("friction")
        self.plate.StickSpeed = 2.5
        self.doc.commitTransaction()
        h.process_events()
        self.assertEqual(len(controls.run.answers), 3)  # held, not thrown away
        self.assertIn("the run is paused, its 3 answers held", h.widget(QtWidgets.QLabel, "similarityMessage").text())
        self.assertIn("Paused at Pair", h.widget(QtWidgets.QLabel, "similarityTrial").text())
        controls.run.present_each()
        h.process_events()
        self.assertFalse(h.widget(QtWidgets.QPushButton, "similarityRate4").isEnabled())  # no answer while paused
        self.assertFalse(h.widget(QtWidgets.QPushButton, "similarityFeel1").isEnabled())
        self.doc.undo()
        h.process_events()
        self.assertEqual(controls.paused, "")
        self.assertIn("the run goes on", h.widget(QtWidgets.QLabel, "similarityMessage").text())
        self.answer_in_code(controls)
        self.assertEqual(study.Participants, 1)

    def hand_on_plate(self):
        """The simulated probe's hand rests on the plate, pressed in by two wheel steps."""
        h.mouse("move", h.screen_pos(np.array([20.0, 20.0, 10.0])))
        h.wait(0.3)
        h.wheel(h.screen_pos(np.array([20.0, 20.0, 10.0])), 2)

    def feel_both(self, controls):
        """Texture 1, stroked until felt, then texture 2."""
        for slot in (1, 2):
            h.widget(QtWidgets.QPushButton, f"similarityFeel{slot}").click()
            self.stroke_until_felt(controls, slot)

    def stroke_until_felt(self, controls, slot):
        """The hand strokes the plate back and forth, 1.5 mm a display frame or two,
        until the run counts the texture held out as felt (a loaded host may need more
        than one stroke)."""
        strokes = []

        def felt():
            k = len(strokes)
            strokes.append(k)
            step = k % 12 if k // 12 % 2 == 0 else 11 - k % 12
            h.mouse("move", h.screen_pos(np.array([20.0 + 1.5 * step, 20.0, 10.0])))
            h.wait(0.04)
            return slot in controls.run.felt

        h.wait_for(felt, f"{slot} felt by stroking the plate")

    def test_a_participants_run_in_the_feel_panel(self):
        study = HaptiCAD.make_similarity_study(self.doc, self.plate, ReferenceA=self.ref_a, ReferenceB=self.ref_b,
                                               WarmUps=2)
        for p in range(5):  # earlier participants, for the space
            ss.record_run(study, simulated_run(study, f"P{p}", p))
        Gui.runCommand("HaptiCAD_Feel")
        h.process_events()
        panel = task_panel_feel.active_panel()
        self.assertTrue(h.widget(QtWidgets.QPushButton, "feelStop").isEnabled(),
                        h.widget(QtWidgets.QLabel, "feelMessage").text())
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Ada")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        trial_label = h.widget(QtWidgets.QLabel, "similarityTrial")
        self.assertIn("Warm-up (not kept) 1 of 2", trial_label.text())
        rate4 = h.widget(QtWidgets.QPushButton, "similarityRate4")
        self.assertFalse(rate4.isEnabled())  # not before both textures were felt
        face = panel.doc_scene.face_id("Plate.Face6")
        self.assertIsNone(panel.session.doc_scene.surface_properties(face).texture)  # the plate's own: none

        # the hand strokes the plate while the participant switches textures: each is felt at once
        controls = panel.similarity_controls[0]
        self.hand_on_plate()
        for slot in (1, 2):
            h.widget(QtWidgets.QPushButton, f"similarityFeel{slot}").click()
            trial = controls.run.current
            expected = controls.run.stimuli[trial.first if slot == 1 else trial.second]["values"]["TextureDC"]
            texture = panel.session.doc_scene.surface_properties(face).texture
            self.assertAlmostEqual(texture.params.f_dc, expected)
            if slot == 1:  # held out under the resting hand is not felt: a grating is felt by stroking it
                h.wait(0.3)
                self.assertNotIn(slot, controls.run.felt)
                self.assertFalse(rate4.isEnabled())
            self.assertIn(f"Stroke the face to feel texture {slot}.", trial_label.text())
            chart = panel.chart
            since = chart.times[-1] if len(chart.times) else -np.inf
            self.stroke_until_felt(controls, slot)
            # felt, and kept in the trace (but not drawn: below)
            force = chart.values["texture_force_n"][chart.times > since]
            self.assertGreater(float(np.abs(force).max()), 0.1)
            self.assertNotIn("Stroke the face", trial_label.text())
        # not drawn: the participant cannot read the texture off the chart
        self.assertEqual(panel.chart.hidden, {"texture_force_n", "friction_force_n"})
        self.assertTrue(rate4.isEnabled())
        h.widen_panel(480)
        h.grab_screen("feel_similarity.png")
        rate4.click()
        self.assertIn("Warm-up (not kept) 2 of 2", trial_label.text())
        self.assertIsNone(panel.session.doc_scene.surface_properties(face).texture)  # an answer clears the face
        h.widget(QtWidgets.QPushButton, "similarityBack").click()
        self.assertIn("Warm-up (not kept) 1 of 2", trial_label.text())

        # the rest answered through the buttons: feel, then rate or class
        while controls.run is not None:
            kind = controls.run.current.kind
            if kind == "class":
                for slot in (1, "A", "B"):
                    h.widget(QtWidgets.QPushButton, f"similarityFeel{slot}").click()
                    self.stroke_until_felt(controls, slot)
                self.assertFalse(h.widget(QtWidgets.QPushButton, "similarityFeel2").isVisible())
                # no rating scale, so no legend of its ends
                self.assertFalse(h.widget(QtWidgets.QWidget, "similarityScaleEnds").isVisible())
                h.widget(QtWidgets.QPushButton, "similarityClassA").click()
            else:
                self.assertTrue(h.widget(QtWidgets.QWidget, "similarityScaleEnds").isVisible())
                self.feel_both(controls)
                h.widget(QtWidgets.QPushButton, "similarityRate5").click()
        self.assertEqual(study.Participants, 6)
        h.wait(0.1)
        self.assertEqual(panel.chart.hidden, set())  # the run is over: the chart draws every force again
        self.assertIn("Kept Ada's run: 36 pairs, 27 classings (6 participants). It is in the document: save the "
                      "document to keep it on disk.", h.widget(QtWidgets.QLabel, "similarityMessage").text())
        self.assertIn("Keep a similarity run", self.doc.UndoNames)
        self.assertIsNone(ss.presented_texture(self.plate))
        self.assertTrue(panel.session.running)
        # keeping the run is bookkeeping: the session is not told the surfaces changed
        self.assertNotIn("Surface edited", h.widget(QtWidgets.QLabel, "feelMessage").text())

        # a name already kept: the run starts (a second sitting), and that is said
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Ada")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.assertIn("Ada already has 1 kept run: this one is kept beside it",
                      h.widget(QtWidgets.QLabel, "similarityMessage").text())
        h.widget(QtWidgets.QPushButton, "similarityStop").click()
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("ada ")  # the same, typed otherwise
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.assertIn("ada already has 1 kept run: this one is kept beside it, under the same name (kept as Ada before",
                      h.widget(QtWidgets.QLabel, "similarityMessage").text())
        h.widget(QtWidgets.QPushButton, "similarityStop").click()
        # a run stopped half way keeps nothing
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Bea")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.assertEqual(h.widget(QtWidgets.QLabel, "similarityMessage").text(), "")
        h.widget(QtWidgets.QPushButton, "similarityFeel1").click()
        self.assertIsNotNone(ss.presented_texture(self.plate))
        h.widget(QtWidgets.QPushButton, "similarityStop").click()
        self.assertIsNone(ss.presented_texture(self.plate))
        self.assertEqual(study.Participants, 6)
        # the study edited during a run (the property editor, an undo): the run pauses, its
        # answers held and nothing on the face; undoing the edit lets it go on
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Cy")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        h.widget(QtWidgets.QPushButton, "similarityFeel1").click()
        self.assertIsNotNone(ss.presented_texture(self.plate))
        self.doc.openTransaction("Fewer stimuli")
        ss.set_stimuli(study, ss.stimuli(study)[:5])
        self.doc.commitTransaction()
        h.process_events()
        self.assertIsNotNone(controls.run)
        self.assertIsNone(ss.presented_texture(self.plate))
        self.assertIn("The study changed during the run (its stimuli): the run is paused",
                      h.widget(QtWidgets.QLabel, "similarityMessage").text())
        self.assertFalse(h.widget(QtWidgets.QPushButton, "similarityFeel1").isEnabled())
        self.doc.undo()
        h.process_events()
        self.assertEqual(len(ss.stimuli(study)), 9)
        self.assertEqual(controls.paused, "")
        self.assertTrue(h.widget(QtWidgets.QPushButton, "similarityFeel1").isEnabled())
        h.widget(QtWidgets.QPushButton, "similarityStop").click()
        # the session stopped after both textures were felt: the trial starts over, and the
        # run itself refuses an answer (not only the disabled buttons)
        h.widget(QtWidgets.QLineEdit, "similarityParticipant").setText("Di")
        h.widget(QtWidgets.QPushButton, "similarityStart").click()
        self.feel_both(controls)
        self.assertTrue(h.widget(QtWidgets.QPushButton, "similarityRate4").isEnabled())
        h.widget(QtWidgets.QPushButton, "feelStop").click()
        self.assertFalse(h.widget(QtWidgets.QPushButton, "similarityRate4").isEnabled())
        controls.answer(4)
        self.assertEqual(controls.run.answers, [])
        self.assertIn("feel texture 1 and texture 2 before answering",
                      h.widget(QtWidgets.QLabel, "similarityMessage").text())
        # a run without a running session: a press is not felt, so it does not count
        for slot in (1, 2):
            h.widget(QtWidgets.QPushButton, f"similarityFeel{slot}").click()
        self.assertIn("Start the Feel session first", h.widget(QtWidgets.QLabel, "similarityMessage").text())
        self.assertFalse(h.widget(QtWidgets.QPushButton, "similarityRate4").isEnabled())
        self.assertIsNone(ss.presented_texture(self.plate))
        h.press_task_button("Close")
        self.assertEqual(study.Participants, 6)

        # the study's panel: the runs and the space they make
        Gui.ActiveDocument.setEdit(study.Name, 0)
        h.process_events()
        self.assertEqual(h.widget(QtWidgets.QTableWidget, "runsTable").rowCount(), 6)
        text = h.widget(QtWidgets.QLabel, "spaceText").text()
        self.assertIn("9 stimuli, 6 participants", text)
        self.assertIn("f_DC", text)
        plot = h.widget(QtWidgets.QLabel, "spacePlot")
        self.assertFalse(plot.pixmap().isNull())
        metric = plot.pixmap().toImage()
        # the space made by ordinal scaling instead, one undo step
        steps = self.doc.UndoCount
        h.widget(QtWidgets.QComboBox, "Scaling").setCurrentIndex(1)
        self.assertEqual((study.Scaling, self.doc.UndoCount), ("Ordinal", steps + 1))
        self.assertIn("ordinal scaling, Kruskal's stress-1", h.widget(QtWidgets.QLabel, "spaceText").text())
        # and drawn: a new picture of the same width used to leave the metric one shown
        self.assertEqual(plot.pixmap().width(), metric.width())
        self.assertNotEqual(plot.pixmap().toImage(), metric)
        # every answer out for statistics elsewhere; a folder that cannot be written is said
        answers = os.path.join(tempfile.mkdtemp(), "answers.csv")
        chosen = [answers]
        original = QtWidgets.QFileDialog.getSaveFileName
        QtWidgets.QFileDialog.getSaveFileName = staticmethod(lambda *a, **k: (chosen[0], "CSV (*.csv)"))
        try:
            h.widget(QtWidgets.QPushButton, "exportAnswers").click()
            with open(answers, encoding="utf-8") as handle:
                lines = handle.read().splitlines()
            self.assertIn(f"answers exported to {answers}", h.widget(QtWidgets.QLabel, "runsMessage").text())
            self.assertEqual(h.widget(QtWidgets.QLabel, "runsMessage").text().count(f"{len(lines) - 1} answers"), 1)
            self.assertEqual(sum(line.startswith("Ada,") for line in lines), 2 + 36 + 27)  # her warm-ups too
            chosen[0] = "/nonexistent/folder/answers.csv"
            h.widget(QtWidgets.QPushButton, "exportAnswers").click()
            self.assertIn("Not exported:", h.widget(QtWidgets.QLabel, "runsMessage").text())
        finally:
            QtWidgets.QFileDialog.getSaveFileName = original
        h.widen_panel(520)
        h.grab_screen("similarity_panel.png")
        space = h.widget(QtWidgets.QLabel, "spacePlot").parentWidget()
        space.grab().save(os.path.join(h.SHOTS, "similarity_space.png"))
        self.doc.undo()
        h.process_events()
        self.assertEqual(h.widget(QtWidgets.QComboBox, "Scaling").currentData(), "Metric")
        self.assertNotIn("ordinal", h.widget(QtWidgets.QLabel, "spaceText").text())
        # a run removed: one undo step, said with the way back
        table = h.widget(QtWidgets.QTableWidget, "runsTable")
        table.selectRow(5)
        h.widget(QtWidgets.QPushButton, "removeRun").click()
        self.assertEqual((table.rowCount(), study.Participants), (5, 5))
        self.assertIn("Removed Ada's run: Edit &gt; Undo brings it back",
                      h.widget(QtWidgets.QLabel, "runsMessage").text())
        self.assertNotIn("Ada", [r["name"] for r in ss.runs(study)])
        self.doc.undo()
        h.process_events()
        self.assertEqual((table.rowCount(), study.Participants), (6, 6))


if __name__ == "__main__":
    unittest.main()
