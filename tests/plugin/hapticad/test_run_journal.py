# SPDX-License-Identifier: GPL-3.0-or-later
"""A similarity run in progress written to disk after every answer (run_journal): read
back as it was, resumed on the study as it was and only then, gone once kept or stopped.
Run by freecadcmd (see tests/plugin/CMakeLists.txt)."""
import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
import unittest
import uuid
from datetime import datetime

import FreeCAD as App
import moved_documents

import HaptiCAD
from hapticad import run_journal
from hapticad import similarity_study as ss

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from test_similarity_study import finish  # noqa: E402


class RunJournalTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.doc = App.newDocument("RunJournal")
        box = self.doc.addObject("Part::Box", "Plate")
        self.doc.recompute()
        self.plate = HaptiCAD.make_surface(self.doc, [(box, "Face6")], material="ABS", FeelRoughness=False)
        self.study = HaptiCAD.make_similarity_study(self.doc, self.plate, WarmUps=2)

    def tearDown(self):
        run_journal.forget(self.study)
        App.closeDocument(self.doc.Name)
        # the kept runs' files written for this test's documents (they live in the test's FreeCAD home)
        folder = os.path.join(App.getUserAppDataDir(), "HaptiCAD", "runs")
        for name in os.listdir(folder) if os.path.isdir(folder) else []:
            try:
                with open(os.path.join(folder, name), encoding="utf-8") as handle:
                    ours = json.load(handle).get("document", "").startswith(self.tmp.name + os.sep)
            except (OSError, ValueError, AttributeError):
                continue  # another test's, being written
            if ours:
                os.remove(os.path.join(folder, name))
        self.tmp.cleanup()

    def half_run(self, answers=5):
        run = ss.Run(self.study, "Ada", seed=7)
        while len(run.answers) < answers:
            run.present_each()
            run.answer(4)
        return run

    def test_a_kept_run_the_document_lost_unsaved_is_offered_until_a_save(self):
        path = os.path.join(self.tmp.name, "study.FCStd")
        self.doc.saveAs(path)
        run = ss.Run(self.study, "Ada", seed=7)
        finish(run)
        record = json.loads(json.dumps(ss.record_run(self.study, run)))
        run_journal.write_kept(self.study, record)
        self.assertEqual(run_journal.unsaved_kept(self.study), [])  # the study holds it
        # FreeCAD gone before a save: the document opens without the run, which is offered
        name = self.study.Name
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.study = self.doc.getObject(name)
        self.assertEqual(ss.runs(self.study), [])
        self.assertEqual(run_journal.unsaved_kept(self.study), [record])
        ss.record_run(self.study, run_journal.unsaved_kept(self.study)[0])
        self.assertEqual(run_journal.unsaved_kept(self.study), [])  # put back: held again
        # a save (Save As too) is what lets the files go: watched as FreeCAD saves
        run_journal.watch_saves()
        run_journal.write_kept(self.study, record)
        self.assertTrue(os.listdir(os.path.join(App.getUserAppDataDir(), "HaptiCAD", "runs")))
        kept_files = run_journal._kept_files(path, self.study.Name)
        self.assertEqual(len(kept_files), 1)
        self.doc.saveAs(os.path.join(self.tmp.name, "renamed.FCStd"))
        self.assertFalse(any(os.path.exists(f) for f in kept_files))
        # a document never saved writes nothing
        unsaved = App.newDocument("RunJournalUnsaved")
        try:
            box = unsaved.addObject("Part::Box", "Box")
            unsaved.recompute()
            other = HaptiCAD.make_similarity_study(unsaved, HaptiCAD.make_surface(
                unsaved, [(box, "Face6")], material="ABS", FeelRoughness=False))
            run_journal.write_kept(other, record)
            self.assertEqual(run_journal.unsaved_kept(other), [])
        finally:
            App.closeDocument(unsaved.Name)

    def keep_and_lose(self, path, name="Ida"):
        """Saves the document as ``path``, keeps ``name``'s run (written beside it), then
        closes it unsaved and opens it again: the kept record."""
        self.doc.saveAs(path)
        run = ss.Run(self.study, name, seed=7)
        finish(run)
        record = json.loads(json.dumps(ss.record_run(self.study, run)))
        run_journal.write_kept(self.study, record)
        study_name = self.study.Name
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.study = self.doc.getObject(study_name)
        return record

    def test_a_save_that_does_not_hold_a_kept_run_keeps_it_offered(self):
        # a save after the crash, before the run is put back (the next participant's run,
        # then Ctrl+S), deleted its file: the run was lost for good
        run_journal.watch_saves()
        path = os.path.join(self.tmp.name, "study.FCStd")
        record = self.keep_and_lose(path)
        self.doc.save()
        self.assertEqual(run_journal.unsaved_kept(self.study), [record])
        # a copy saved elsewhere leaves the document as unsaved as before, even holding it
        ss.record_run(self.study, record)
        self.doc.saveCopy(os.path.join(self.tmp.name, "copy.FCStd"))
        self.assertEqual(len(run_journal._kept_files(path, self.study.Name)), 1)
        # a save that holds it lets it go
        self.doc.save()
        self.assertEqual(run_journal._kept_files(path, self.study.Name), [])

    def test_another_document_or_study_of_the_same_name_leaves_a_kept_run_alone(self):
        run_journal.watch_saves()
        first = os.path.join(self.tmp.name, "a", "study.FCStd")
        os.makedirs(os.path.dirname(first))
        record = self.keep_and_lose(first, "Jo")
        name = self.study.Name
        App.closeDocument(self.doc.Name)
        # a document of the same name in another folder, saved with a study of that name
        second = os.path.join(self.tmp.name, "b", "study.FCStd")
        os.makedirs(os.path.dirname(second))
        self.doc = App.newDocument("study")
        box = self.doc.addObject("Part::Box", "Plate")
        self.doc.recompute()
        plate = HaptiCAD.make_surface(self.doc, [(box, "Face6")], material="ABS", FeelRoughness=False)
        self.study = HaptiCAD.make_similarity_study(self.doc, plate, WarmUps=2)
        self.doc.saveAs(second)
        self.doc.save()
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(first)
        self.study = self.doc.getObject(name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [record])
        # the study deleted and another made with its name: not offered Jo's run
        self.doc.removeObject(name)
        self.study = HaptiCAD.make_similarity_study(self.doc, self.plate_of(self.doc), WarmUps=2)
        self.assertEqual(self.study.Name, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [])

    def keep(self, name, seed=7):
        """Keeps ``name``'s finished run (one undo step), written beside the document as the
        Feel panel writes it: the record as stored."""
        run = ss.Run(self.study, name, seed=seed)
        finish(run)
        self.doc.openTransaction("Keep a similarity run")
        record = json.loads(json.dumps(ss.record_run(self.study, run)))
        self.doc.commitTransaction()
        run_journal.write_kept(self.study, record)
        return record

    @staticmethod
    def forget_kept(path, name):
        """Takes away the kept runs' files written for the document ``path`` (they live in the
        test's FreeCAD home)."""
        for kept in run_journal._kept_files(path, name):
            os.remove(kept)

    def test_a_kept_run_removed_on_purpose_forgets_its_file_and_an_undo_writes_it_again(self):
        # a kept run removed before the document was saved left its file: offered back next time as lost
        run_journal.watch_saves()
        path = os.path.join(self.tmp.name, "study.FCStd")
        self.doc.saveAs(path)
        self.doc.UndoMode = 1
        name = self.study.Name
        self.addCleanup(self.forget_kept, path, name)
        self.keep("Ida")
        written = run_journal._kept_files(path, name)
        self.assertEqual(len(written), 1)
        self.doc.openTransaction("Remove participants' runs")
        ss.remove_run(self.study, 0)
        self.doc.commitTransaction()
        self.assertEqual(run_journal._kept_files(path, name), [])
        self.doc.undo()  # in the document again, unsaved as it was: written again
        self.assertEqual(run_journal._kept_files(path, name), written)
        self.assertEqual(run_journal.unsaved_kept(self.study), [])
        self.doc.redo()
        self.assertEqual(run_journal._kept_files(path, name), [])
        # a run saved, then removed: nothing written, nor after the removal is undone (it is on disk)
        jo = self.keep("Jo", seed=8)
        self.doc.save()
        self.assertEqual(run_journal._kept_files(path, name), [])
        self.doc.openTransaction("Remove participants' runs")
        ss.remove_run(self.study, 0)
        self.doc.commitTransaction()
        self.doc.undo()
        self.assertEqual(run_journal._kept_files(path, name), [])
        self.assertEqual(ss.runs(self.study), [jo])
        # removed, saved without it, and the removal undone: only the document in memory holds
        # it, so it is written again, and offered if that document is lost unsaved
        self.doc.openTransaction("Remove participants' runs")
        ss.remove_run(self.study, 0)
        self.doc.commitTransaction()
        self.doc.save()
        self.doc.undo()
        self.assertEqual(ss.runs(self.study), [jo])
        self.assertEqual(len(run_journal._kept_files(path, name)), 1,
                         "a run removed, saved without, then put back by Undo is on disk nowhere")
        self.doc.redo()  # removed again: its file goes with it, or it is offered back as lost
        self.assertEqual(run_journal._kept_files(path, name), [])
        self.doc.undo()
        self.assertEqual(len(run_journal._kept_files(path, name)), 1)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.study = self.doc.getObject(name)
        self.assertEqual(ss.runs(self.study), [])
        self.assertEqual(run_journal.unsaved_kept(self.study), [jo])
        # Ida's removal, lost with the document before, is not offered
        ss.record_run(self.study, jo)
        self.doc.save()
        self.assertEqual(run_journal.unsaved_kept(self.study), [])
        self.assertEqual(run_journal._kept_files(path, name), [])

    def test_a_kept_run_lost_to_a_close_without_saving_is_told_from_one_lost_to_a_crash(self):
        # "the document closed (or FreeCAD ended) before it was saved": a discard on purpose
        # could not be told from a crash
        run_journal.watch_saves()
        path = os.path.join(self.tmp.name, "study.FCStd")
        self.doc.saveAs(path)
        name = self.study.Name
        self.addCleanup(self.forget_kept, path, name)
        App.closeDocument(self.doc.Name)
        tests = os.path.dirname(os.path.abspath(__file__))
        code = (f"import os, sys, json, FreeCAD as App, HaptiCAD\n"
                f"sys.path.insert(0, {tests!r})\n"
                "from test_similarity_study import finish\n"
                "from hapticad import run_journal, similarity_study as ss\n"
                f"doc = App.openDocument({path!r})\n"
                f"study = doc.getObject({name!r})\n"
                "run = finish(ss.Run(study, 'Kim', seed=7))\n"
                "run_journal.write_kept(study, json.loads(json.dumps(ss.record_run(study, run))))\n"
                "os._exit(17)\n")
        try:
            done = subprocess.run(["freecadcmd", "-c", code], capture_output=True, text=True, timeout=300)
        finally:
            self.doc = App.openDocument(path)
            self.study = self.doc.getObject(name)
        self.assertEqual(done.returncode, 17, done.stdout[-2000:] + done.stderr[-2000:])
        (kim,) = run_journal.unsaved_kept(self.study)
        self.assertEqual(kim["name"], "Kim")
        self.assertEqual(run_journal.how_lost(self.study, [kim]), [run_journal.ENDED])
        ss.record_run(self.study, kim)  # put back, and lost again: closed without saving
        before = datetime.now().replace(microsecond=0)
        App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.study = self.doc.getObject(name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [kim])  # not forgotten: dropped only when asked
        (closed,) = run_journal.how_lost(self.study, [kim])
        self.assertTrue(before <= datetime.fromisoformat(closed) <= datetime.now(), closed)
        run_journal.drop_kept(self.study, [kim])
        self.assertEqual(run_journal._kept_files(path, name), [])

    def open_at(self, path, name):
        """Opens the document at ``path`` as the test's own (the one before closed first, unsaved)."""
        if self.doc is not None and self.doc.Name in App.listDocuments():
            App.closeDocument(self.doc.Name)
        self.doc = App.openDocument(path)
        self.study = self.doc.getObject(name)

    def test_a_document_saved_from_the_same_template_does_not_take_a_moved_ones_runs(self):
        # Save As keeps the document's Uid: Monday's and Tuesday's documents, saved from one
        # template, share it; Monday's moved away, its kept run went to Tuesday's
        run_journal.watch_saves()
        name = self.study.Name
        monday, tuesday = moved_documents.paths_in(self.tmp.name, ("mon", "tue"))
        self.doc.saveAs(tuesday)
        time.sleep(1.1)  # FreeCAD keeps a save's time to the second
        self.doc.saveAs(monday)
        self.addCleanup(self.forget_kept, monday, name)
        ida = self.keep("Ida")
        uid = self.doc.Uid
        App.closeDocument(self.doc.Name)
        self.doc = None
        (archived,) = moved_documents.move_into(self.tmp.name, "archive", [monday], ["monday.FCStd"])
        self.addCleanup(self.forget_kept, archived, name)
        self.addCleanup(self.forget_kept, tuesday, name)
        self.open_at(tuesday, name)
        self.assertEqual(self.doc.Uid, uid)  # what the journal took for Monday's
        self.assertEqual(run_journal.unsaved_kept(self.study), [], "another document saved from its template took it")
        self.open_at(archived, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [ida])

    def test_runs_that_outlive_a_save_are_found_after_the_document_is_moved(self):
        # a kept run an Undo took out, and a run in progress, are not in the saved file: their
        # files outlive the save, and must be known by the document as saved then
        run_journal.watch_saves()
        name = self.study.Name
        (first,) = moved_documents.paths_in(self.tmp.name, ("a",))
        self.doc.saveAs(first)
        self.addCleanup(self.forget_kept, first, name)
        self.doc.UndoMode = 1
        ida = self.keep("Ida")
        self.doc.undo()  # taken out: offered as undone if the document is lost
        run_journal.write(self.study, self.half_run())
        time.sleep(1.1)  # FreeCAD keeps a save's time to the second
        self.doc.save()
        App.closeDocument(self.doc.Name)
        self.doc = None
        (moved,) = moved_documents.move_into(self.tmp.name, "moved", [first], ["a.FCStd"])
        self.addCleanup(self.forget_kept, moved, name)
        self.open_at(moved, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [ida], "a kept run saved around is not found")
        self.assertIsNotNone(run_journal.read(self.study), "the run in progress saved around is not found")
        run_journal.forget(self.study)

    def test_runs_lost_before_the_document_was_moved_are_offered_where_it_is_now(self):
        # moved (a file manager, a synced folder with another path) after a close without
        # saving, the document was opened under another path: its kept run was not offered,
        # nor its run in progress, and their files stayed under the earlier path's names for good
        run_journal.watch_saves()
        earlier = os.path.join(self.tmp.name, "study.FCStd")
        self.doc.saveAs(earlier)
        name = self.study.Name
        record = self.keep("Ida")
        written = run_journal._kept_files(earlier, name)
        self.assertEqual(len(written), 1)
        App.closeDocument(self.doc.Name)  # lost unsaved
        self.doc = None
        moved = os.path.join(self.tmp.name, "project", "plates.FCStd")  # moved and renamed
        os.makedirs(os.path.dirname(moved))
        os.rename(earlier, moved)
        self.open_at(moved, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [record],
                         "a kept run lost before the document was moved is not offered where it is now")
        self.assertEqual(run_journal.earlier_path(self.study, [record]), os.path.abspath(earlier))
        (closed,) = run_journal.how_lost(self.study, [record])
        self.assertNotIn(closed, (run_journal.ENDED, ""))  # still said: a close
        here = run_journal._kept_files(moved, name)
        self.assertEqual(len(here), 1)
        self.assertFalse(os.path.exists(written[0]), "the file under the earlier path's name stays")
        # put back and saved: no file is left under either name
        ss.record_run(self.study, record)
        self.doc.save()
        self.assertEqual(run_journal._kept_files(moved, name), [])
        self.assertEqual(run_journal._kept_files(earlier, name), [])
        self.open_at(moved, name)
        self.assertEqual(ss.runs(self.study), [record])
        self.assertEqual(run_journal.unsaved_kept(self.study), [])
        # a run in progress lost the same way goes on where the document is now
        run_journal.write(self.study, self.half_run())
        in_progress = run_journal.path_for(self.study)
        again = os.path.join(self.tmp.name, "again.FCStd")
        App.closeDocument(self.doc.Name)
        self.doc = None
        os.rename(moved, again)
        self.open_at(again, name)
        state = run_journal.read(self.study)
        self.assertIsNotNone(state, "a run in progress when the document was moved is not found where it is now")
        self.assertEqual((state["name"], state["answers"], state["moved_from"]), ("Ada", [4] * 5, moved))
        self.assertFalse(os.path.exists(in_progress))
        self.assertTrue(os.path.exists(run_journal.path_for(self.study)))
        self.assertEqual(run_journal.resume(self.study, state).answers, [4] * 5)

    def test_runs_whose_document_is_still_where_it_was_are_not_taken_by_a_copy(self):
        run_journal.watch_saves()
        original = os.path.join(self.tmp.name, "study.FCStd")
        self.doc.saveAs(original)
        name = self.study.Name
        record = self.keep("Ida")
        run_journal.write(self.study, self.half_run())
        App.closeDocument(self.doc.Name)  # lost unsaved
        self.doc = None
        copy = os.path.join(self.tmp.name, "elsewhere", "study.FCStd")
        os.makedirs(os.path.dirname(copy))
        shutil.copy(original, copy)  # the same document (its Uid and all), at another path
        self.open_at(copy, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [])  # the original's, which is still there
        self.assertIsNone(run_journal.read(self.study))
        self.open_at(original, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [record])
        # its file taken away while it is open: the original is still the one its runs are of
        aside = os.path.join(self.tmp.name, "aside.FCStd")
        os.rename(original, aside)
        other = App.openDocument(copy)
        try:
            self.assertEqual(run_journal.unsaved_kept(other.getObject(name)), [])
            self.assertIsNone(run_journal.read(other.getObject(name)))
        finally:
            App.closeDocument(other.Name)
        App.closeDocument(self.doc.Name)
        self.doc = None
        # the original gone for good: the copy is the document its runs were lost from
        os.remove(aside)
        self.open_at(copy, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [record],
                         "the kept runs of a document gone since are not offered to its copy")
        self.assertEqual(run_journal.read(self.study)["name"], "Ada")
        self.assertEqual(run_journal._kept_files(original, name), [])

    def test_the_runs_of_another_document_or_of_one_of_two_copies_moved_away_are_not_taken(self):
        run_journal.watch_saves()
        name = self.study.Name
        # two documents whose studies have the same name and ID (FreeCAD draws a document's first
        # ID from 0-5000: documents made alike can share them), each losing a kept run; the second
        # a copy of the first made another document (another Uid)
        first, second = moved_documents.paths_in(self.tmp.name, ("a", "b"))
        self.doc.saveAs(first)
        shutil.copy(first, second)
        ida = self.keep("Ida")
        uid = self.doc.Uid
        self.open_at(second, name)
        self.doc.Uid = str(uuid.uuid4())
        self.doc.save()
        self.assertNotEqual(self.doc.Uid, uid)
        jo = self.keep("Jo", seed=8)
        App.closeDocument(self.doc.Name)
        self.doc = None
        # both moved away: each is offered its own run, not the other's
        moved_first, moved_second = moved_documents.move_into(self.tmp.name, "moved", (first, second),
                                                              ("a.FCStd", "b.FCStd"))
        self.open_at(moved_second, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [jo],
                         "a moved document is not offered its own kept run (or is offered another's)")
        self.open_at(moved_first, name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [ida])
        ss.record_run(self.study, ida)
        self.doc.save()
        # two copies of one document, each losing a kept run and a run in progress, both moved
        # away: whose they are cannot be told, so none is taken, and all stay
        copies = moved_documents.paths_in(self.tmp.name, ("copy1", "copy2"))
        kept, files = [], []
        for path, who in zip(copies, ("Kim", "Lee")):
            shutil.copy(moved_first, path)
            self.open_at(path, name)
            kept.append(self.keep(who, seed=9))
            run_journal.write(self.study, self.half_run())
            files += [*run_journal._kept_files(path, name), run_journal.path_for(self.study)]
        self.assertEqual(len(files), 4)
        App.closeDocument(self.doc.Name)
        self.doc = None
        moved_copies = moved_documents.move_into(self.tmp.name, "moved", copies, ("copy1.FCStd", "copy2.FCStd"))
        self.open_at(moved_copies[0], name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [])
        self.assertIsNone(run_journal.read(self.study))
        self.assertTrue(all(os.path.exists(f) for f in files))
        App.closeDocument(self.doc.Name)
        self.doc = None
        # one moved back where it was: its files are its own again, and the other's the moved one's
        os.rename(moved_copies[1], copies[1])
        self.open_at(moved_copies[0], name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [kept[0]])
        self.assertIsNotNone(run_journal.read(self.study))
        self.open_at(copies[1], name)
        self.assertEqual(run_journal.unsaved_kept(self.study), [kept[1]])
        self.assertIsNotNone(run_journal.read(self.study))

    @staticmethod
    def plate_of(doc):
        return next(o for o in doc.Objects if o.Name.startswith("HapticSurface"))

    def test_an_unsaved_document_has_no_journal(self):
        self.assertIsNone(run_journal.path_for(self.study))
        run_journal.write(self.study, self.half_run())  # nothing to name it by: nothing written
        self.assertIsNone(run_journal.read(self.study))

    def test_a_run_written_is_read_back_and_goes_on_with_its_answers(self):
        self.doc.saveAs(os.path.join(self.tmp.name, "study.FCStd"))
        run = self.half_run()
        run_journal.write(self.study, run)
        path = run_journal.path_for(self.study)
        self.assertTrue(path.startswith(App.getUserAppDataDir()))
        self.assertFalse(os.path.exists(path + ".part"))  # written whole, then moved in place
        state = run_journal.read(self.study)
        self.assertEqual((state["name"], state["seed"], state["answers"]), ("Ada", 7, [4] * 5))
        again = run_journal.resume(self.study, state)
        self.assertEqual([(t.kind, t.first, t.second) for t in again.trials],
                         [(t.kind, t.first, t.second) for t in run.trials])
        self.assertEqual((again.answers, again.started), (run.answers, run.started))
        finish(again)  # it goes on to the end and is kept as any run
        ss.record_run(self.study, again)
        self.assertEqual(self.study.Participants, 1)
        run_journal.forget(self.study)
        self.assertIsNone(run_journal.read(self.study))
        self.assertFalse(os.path.exists(path))

    def test_a_run_on_a_study_that_changed_since_does_not_go_on(self):
        self.doc.saveAs(os.path.join(self.tmp.name, "study.FCStd"))
        run_journal.write(self.study, self.half_run())
        state = run_journal.read(self.study)
        self.assertEqual(run_journal.resumable(self.study, state), "")
        self.plate.StickSpeed = 3.0
        self.assertEqual(run_journal.resumable(self.study, state), "the surface or a reference changed since")
        with self.assertRaisesRegex(ValueError, "Ada's run cannot go on: the surface or a reference changed since"):
            run_journal.resume(self.study, state)
        self.plate.StickSpeed = 2.0
        self.plate.StaticFriction = 0.9  # not felt with a texture at Device force: it goes on
        self.assertEqual(run_journal.resumable(self.study, state), "")
        state["context"] = {**state["context"], "StaticFriction": 0.6, "TextureFullRange": 0.0}
        del state["context"]["StickSpeed"]  # as journals before the stick speed was kept
        self.assertEqual(run_journal.resumable(self.study, state), "")
        ss.set_stimuli(self.study, ss.stimuli(self.study)[:5])
        self.assertEqual(run_journal.resumable(self.study, state), "the study's stimuli changed since")

    def test_a_run_on_another_scale_or_protocol_does_not_go_on_and_says_what_to_set_back(self):
        # a 5 given on a 7-step scale was stored as a 5 on a 5-step scale ("the same")
        self.doc.saveAs(os.path.join(self.tmp.name, "study.FCStd"))
        self.study.Repeats = 2
        run_journal.write(self.study, self.half_run())
        state = run_journal.read(self.study)
        for name, value, said in (("RatingSteps", 5, "Rating steps 5 (it was 7: set it back to go on)"),
                                  ("WarmUps", 4, "Warm ups 4 (it was 2: set it back to go on)"),
                                  ("Repeats", 3, "Repeats 3 (it was 2: set it back to go on)")):
            before = getattr(self.study, name)
            setattr(self.study, name, value)
            with self.assertRaises(ValueError) as caught:
                run_journal.resume(self.study, state)
            self.assertEqual(str(caught.exception), f"Ada's run cannot go on: the study's {said}", name)
            setattr(self.study, name, before)
        again = run_journal.resume(self.study, state)  # set back, it goes on
        self.assertEqual((again.steps, again.answers), (7, [4] * 5))
        # the scale changed while the run went on (on the scale it began with): the journal
        # still says 7, so a resume on 5 is refused
        self.study.RatingSteps = 5
        run_journal.write(self.study, again)
        self.assertEqual(run_journal.resumable(self.study, run_journal.read(self.study)),
                         "the study's Rating steps 5 (it was 7: set it back to go on)")
        self.study.RatingSteps = 7
        # a journal written before the protocol was: resumed as before, on what the trials show
        del state["protocol"]
        self.assertEqual(run_journal.resumable(self.study, state), "")

    def test_a_damaged_journal_is_no_run(self):
        self.doc.saveAs(os.path.join(self.tmp.name, "study.FCStd"))
        path = run_journal.path_for(self.study)
        os.makedirs(os.path.dirname(path), exist_ok=True)
        with open(path, "w") as handle:
            handle.write('{"name": "Ada", "answers": [4, 4')  # cut off
        self.assertIsNone(run_journal.read(self.study))


if __name__ == "__main__":
    unittest.main()
