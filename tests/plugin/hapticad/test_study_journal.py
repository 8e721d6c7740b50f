# SPDX-License-Identifier: GPL-3.0-or-later
"""A stiffness study's participants recorded since the last save, written to disk as they
come (study_journal): offered back, exactly those, when the document was closed unsaved
(as after a crash), kept until put back or dropped, and forgotten once a save holds
them. Run by freecadcmd (see tests/plugin/CMakeLists.txt)."""
import json
import os
import shutil
import subprocess
import tempfile
import time
import unittest
import uuid
from datetime import datetime

import FreeCAD as App
import moved_documents

import HaptiCAD
from hapticad import cohort, stiffness_study, study_journal


class StudyJournalTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.path = os.path.join(self.tmp.name, "toothbrush.FCStd")
        self.doc = App.newDocument("StudyJournal")
        self.doc.UndoMode = 1
        box = self.doc.addObject("Part::Box", "Head")
        self.doc.recompute()
        surface = HaptiCAD.make_surface(self.doc, [(box, "Face6")], material="PP", FeelRoughness=False)
        self.study = HaptiCAD.make_study(self.doc, surface)
        self.written = set()  # journal files to take away after (they live in the test's FreeCAD home)

    def tearDown(self):
        # taken away once the document is closed: a close writes what it holds unsaved
        if self.doc is None:  # closed by the test
            self.tmp.cleanup()
            return
        paths = (self.written | {study_journal.path_for(s) for s in HaptiCAD.studies_of(self.doc)}) - {None}
        App.closeDocument(self.doc.Name)
        for path in paths:
            if os.path.exists(path):
                os.remove(path)
        self.tmp.cleanup()

    def record(self, name, thickness):
        self.doc.openTransaction(f"Record {name}")
        self.study.BeamThickness = thickness
        record = HaptiCAD.record_preference(self.study, name, "F", "26-40", 60, 1650)
        self.doc.commitTransaction()
        self.written.add(study_journal.path_for(self.study))
        return record

    def close_unsaved_and_reopen(self):
        """Closes the document without saving (its records lost as a crash loses them; the
        journal notes the close) and opens its file again."""
        name = self.study.Name
        App.closeDocument(self.doc.Name)
        self.reopen(name)

    def reopen(self, name):
        self.doc = App.openDocument(self.path)
        self.doc.UndoMode = 1
        self.study = self.doc.getObject(name)

    def crash_elsewhere(self, study_name, name, thickness):
        """Another FreeCAD opens the saved document, records ``name`` in ``study_name`` and
        ends without a word (os._exit: no save and no close, as a crash leaves it)."""
        code = (f"import os, FreeCAD as App, HaptiCAD\n"
                f"doc = App.openDocument({self.path!r})\n"
                f"study = doc.getObject({study_name!r})\n"
                f"study.BeamThickness = {thickness!r}\n"
                f"HaptiCAD.record_preference(study, {name!r}, 'F', '26-40', 60, 1650)\n"
                "os._exit(17)\n")
        done = subprocess.run(["freecadcmd", "-c", code], capture_output=True, text=True, timeout=300)
        self.assertEqual(done.returncode, 17, done.stdout[-2000:] + done.stderr[-2000:])

    def remove(self, name):
        """Removes ``name``'s record on purpose, as the panel's Remove does (one undo step)."""
        index = self.names(stiffness_study.records(self.study)).index(name)
        self.doc.openTransaction("Remove participants")
        stiffness_study.remove_record(self.study, index)
        self.doc.commitTransaction()

    def put_back(self):
        self.doc.openTransaction("Put back participants recorded unsaved")
        stiffness_study.add_records(self.study, study_journal.lost(self.study))
        self.doc.commitTransaction()

    def names(self, records):
        return [r.name for r in records]

    def test_records_lost_with_a_close_unsaved_are_offered_exactly_and_put_back(self):
        self.doc.saveAs(self.path)
        ann = self.record("Ann", 4.0)
        self.doc.save()
        self.assertFalse(os.path.exists(study_journal.path_for(self.study)))  # Ann is saved
        bo, cy = self.record("Bo", 5.0), self.record("Cy", 6.0)
        journal = study_journal.path_for(self.study)
        self.assertTrue(journal.startswith(App.getUserAppDataDir()))
        with open(journal, encoding="utf-8") as handle:
            written = json.load(handle)
        self.assertEqual([r["name"] for r in written["cohort"]], ["Ann", "Bo", "Cy"])
        self.assertEqual(study_journal.lost(self.study), [])  # the document holds them
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann"])
        lost = study_journal.lost(self.study)
        self.assertEqual([r.as_dict() for r in lost], [bo.as_dict(), cy.as_dict()])  # exactly, values and all
        # put back as one undo step: undone, they are offered again; redone, held
        self.doc.openTransaction("Put back")
        stiffness_study.add_records(self.study, lost)
        self.doc.commitTransaction()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Bo", "Cy"])
        self.assertEqual(self.study.Participants, 3)
        self.assertEqual(study_journal.lost(self.study), [])
        self.doc.undo()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo", "Cy"])
        self.doc.redo()
        self.assertEqual(study_journal.lost(self.study), [])
        # put back and lost again before a save: still offered
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo", "Cy"])
        stiffness_study.add_records(self.study, study_journal.lost(self.study))
        # a save holding them lets the file go; opened again, nothing is offered
        self.doc.save()
        self.assertFalse(os.path.exists(journal))
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Bo", "Cy"])
        self.assertEqual(study_journal.lost(self.study), [])
        self.assertEqual(ann.as_dict(), stiffness_study.records(self.study)[0].as_dict())

    def test_lost_records_wait_through_new_records_and_saves_until_put_back_or_dropped(self):
        self.doc.saveAs(self.path)
        self.record("Bo", 5.0)
        self.close_unsaved_and_reopen()
        # the next participant is recorded before Bo is put back, and the document saved: Bo still waits
        self.record("Dan", 3.0)
        self.doc.save()
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Dan"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"])
        self.record("Eve", 7.0)
        self.close_unsaved_and_reopen()  # Eve lost too
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo", "Eve"])
        study_journal.drop(self.study, [r for r in study_journal.lost(self.study) if r.name == "Bo"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Eve"])
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Eve"])  # dropped for good
        study_journal.drop(self.study, study_journal.lost(self.study))
        self.assertFalse(os.path.exists(study_journal.path_for(self.study)))

    def test_an_undone_or_removed_record_and_an_import_are_journaled_as_the_cohort_is(self):
        self.doc.saveAs(self.path)
        self.record("Ann", 4.0)
        self.doc.save()
        self.record("Bo", 5.0)
        self.record("Cy", 6.0)
        self.doc.undo()  # Cy undone: not lost, taken back
        self.doc.openTransaction("Remove")
        stiffness_study.remove_record(self.study, 1)  # Bo removed on purpose
        self.doc.commitTransaction()
        csv_path = os.path.join(self.tmp.name, "more.csv")
        cohort.write_csv(csv_path, [cohort.Record("Fay", "F", "18-25", None, None, 0.9, "N/mm",
                                                  stiffness_study.BEAM, {}, "2026-11-24T10:00:00")])
        self.doc.openTransaction("Import")
        self.assertEqual(stiffness_study.import_records(self.study, csv_path), (1, 0, 0))
        self.doc.commitTransaction()
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Fay"])
        # an Undo of a removal of a saved record brings back what the file holds: nothing is lost
        self.doc.openTransaction("Remove")
        stiffness_study.remove_record(self.study, 0)
        self.doc.commitTransaction()
        self.doc.undo()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Fay"])

    def test_a_record_removed_on_purpose_is_not_offered_back_and_an_undo_brings_it_back_as_before(self):
        # Cy, lost unsaved and put back, then removed on purpose: offered back at once as lost,
        # and again each time the document was opened
        self.doc.saveAs(self.path)
        self.record("Ann", 4.0)
        self.record("Bo", 5.0)
        self.doc.save()
        # a saved record removed, the removal not saved: the saved document holds him, nothing is offered
        self.remove("Bo")
        self.assertEqual(study_journal.lost(self.study), [])
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Bo"])
        self.assertEqual(study_journal.lost(self.study), [])
        self.remove("Bo")
        self.doc.save()
        # recorded, lost unsaved, put back, then removed on purpose
        self.record("Cy", 6.0)
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Cy"])
        self.put_back()
        self.record("Dan", 3.0)
        self.remove("Cy")
        self.assertEqual(self.names(study_journal.lost(self.study)), [])
        self.doc.undo()  # the removal undone: Cy held again
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Cy", "Dan"])
        self.assertEqual(study_journal.lost(self.study), [])
        self.doc.undo()
        self.doc.undo()  # Dan's record and the put back undone: Cy offered again, as before
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Cy"])
        for _ in range(3):  # the put back, Dan, the removal redone: Cy is not offered
            self.doc.redo()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Dan"])
        self.assertEqual(study_journal.lost(self.study), [])
        # lost with the document: Dan, recorded and never saved, is offered; Cy, removed on purpose, is not
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Dan"])
        # removed on purpose and saved, then the removal undone: Dan is held unsaved, and lost with the document
        self.put_back()
        self.remove("Dan")
        self.doc.save()
        self.assertEqual(study_journal.lost(self.study), [])
        self.doc.undo()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Dan"])
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Dan"])

    def test_a_close_without_saving_is_told_from_a_crash_and_neither_forgets_the_records(self):
        # "it was closed without saving, or FreeCAD ended": the designer who discarded the
        # document on purpose could not tell that from a crash
        self.doc.saveAs(self.path)
        self.record("Ann", 4.0)
        self.doc.save()
        name = self.study.Name
        App.closeDocument(self.doc.Name)  # nothing unsaved: nothing noted
        try:
            self.crash_elsewhere(name, "Bo", 5.0)
        finally:
            self.reopen(name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"])
        self.assertEqual(study_journal.how_lost(self.study), [study_journal.ENDED])
        with open(study_journal.path_for(self.study), "rb") as handle:
            written = handle.read()
        self.close_unsaved_and_reopen()  # closed with nothing new: Bo was lost to the crash all the same
        self.assertEqual(study_journal.how_lost(self.study), [study_journal.ENDED])
        with open(study_journal.path_for(self.study), "rb") as handle:
            self.assertEqual(handle.read(), written)  # a session that wrote nothing leaves the file as it was
        self.record("Cy", 6.0)
        before = datetime.now().replace(microsecond=0)
        self.close_unsaved_and_reopen()  # on purpose: not forgotten (a discard meant for an edit loses nobody)
        lost = study_journal.lost(self.study)
        self.assertEqual(self.names(lost), ["Bo", "Cy"])
        ended, closed = study_journal.how_lost(self.study)
        self.assertEqual(ended, study_journal.ENDED)
        self.assertTrue(before <= datetime.fromisoformat(closed) <= datetime.now(), closed)
        when = datetime.fromisoformat(closed).strftime("%Y-%m-%d at %H:%M")
        self.assertEqual(study_journal.said_how_lost(["Bo", "Cy"], [ended, closed]),
                         f"Bo: FreeCAD ended before it was saved; Cy: it was closed without saving on {when}")
        self.assertEqual(study_journal.said_how_lost(["Cy"], [closed]), f"it was closed without saving on {when}")
        self.assertEqual(study_journal.said_how_lost(["Bo", "Cy"], [ended, ended]),
                         "FreeCAD ended before it was saved")
        # a journal written before closes were noted: either
        self.assertEqual(study_journal.said_how_lost(["Bo"], [""]), "it was closed without saving, or FreeCAD ended")
        # dropped only when the designer says so; what is left keeps how it was lost
        study_journal.drop(self.study, lost[1:])
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"])
        self.assertEqual(study_journal.how_lost(self.study), [study_journal.ENDED])

    def test_a_record_given_twice_is_offered_as_many_times_as_it_was_lost(self):
        self.doc.saveAs(self.path)
        twice = cohort.Record("Gus", "M", "over 60", None, None, 1.0, "N/mm", stiffness_study.BEAM, {},
                              "2026-11-24T10:00:00")
        stiffness_study.add_records(self.study, [twice])
        self.doc.save()
        stiffness_study.add_records(self.study, [twice])  # the same again, as stored: one held, one not
        self.written.add(study_journal.path_for(self.study))
        self.close_unsaved_and_reopen()
        self.assertEqual(len(stiffness_study.records(self.study)), 1)
        self.assertEqual([r.as_dict() for r in study_journal.lost(self.study)], [twice.as_dict()])

    def test_a_document_never_saved_writes_nothing_and_says_so(self):
        self.assertTrue(study_journal.never_saved(self.study))
        self.assertIsNone(study_journal.path_for(self.study))
        self.record("Ann", 4.0)
        self.assertEqual(study_journal.lost(self.study), [])
        self.doc.saveAs(self.path)  # saved now: Ann is on disk, nothing to journal
        self.assertFalse(study_journal.never_saved(self.study))
        self.assertFalse(os.path.exists(study_journal.path_for(self.study)))

    def test_save_as_moves_the_journal_and_a_copy_saved_elsewhere_leaves_it(self):
        self.doc.saveAs(self.path)
        self.record("Bo", 5.0)
        first = study_journal.path_for(self.study)
        self.assertTrue(os.path.exists(first))
        self.doc.saveCopy(os.path.join(self.tmp.name, "copy.FCStd"))  # the document is as unsaved as before
        self.assertTrue(os.path.exists(first))
        self.path = os.path.join(self.tmp.name, "renamed.FCStd")
        self.doc.saveAs(self.path)
        self.assertFalse(os.path.exists(first))
        self.record("Cy", 6.0)
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Bo"])
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Cy"])

    def test_a_deleted_study_is_not_offered_another_of_its_name_records(self):
        self.doc.saveAs(self.path)
        self.record("Bo", 5.0)
        self.close_unsaved_and_reopen()
        surface, name = self.study.Surface, self.study.Name
        journal = study_journal.path_for(self.study)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"])
        self.assertTrue(os.path.exists(journal))
        self.doc.removeObject(name)
        self.study = HaptiCAD.make_study(self.doc, surface)
        self.assertEqual(self.study.Name, name)
        self.assertEqual(study_journal.lost(self.study), [])  # another study (another ID)
        self.doc.save()  # the deleted study's records are in no document now: its file goes
        self.assertFalse(os.path.exists(journal))

    def forget_journals_here(self):
        """Takes away the journals written for the documents of this test's folder (they live
        in the test's FreeCAD home), wherever they were moved."""
        folder = os.path.join(App.getUserAppDataDir(), "HaptiCAD", "cohorts")
        for name in os.listdir(folder) if os.path.isdir(folder) else []:
            try:
                with open(os.path.join(folder, name), encoding="utf-8") as handle:
                    ours = json.load(handle).get("document", "").startswith(self.tmp.name + os.sep)
            except (OSError, ValueError, AttributeError):
                continue
            if ours:
                os.remove(os.path.join(folder, name))

    def open_at(self, path, name):
        """Opens the document at ``path`` as the test's own (the one before closed first)."""
        if self.doc is not None and self.doc.Name in App.listDocuments():
            App.closeDocument(self.doc.Name)
        self.path = path
        self.reopen(name)

    def test_a_document_saved_from_the_same_template_does_not_take_a_moved_ones_records(self):
        # Save As keeps the document's Uid: Monday's and Tuesday's documents, saved from one
        # template, share it; Monday's moved away, its records went to Tuesday's
        self.addCleanup(self.forget_journals_here)
        name = self.study.Name
        monday, tuesday = moved_documents.paths_in(self.tmp.name, ("mon", "tue"))
        self.doc.saveAs(tuesday)
        time.sleep(1.1)  # FreeCAD keeps a save's time to the second
        self.doc.saveAs(monday)
        self.record("Ann", 5.0)
        uid = self.doc.Uid
        App.closeDocument(self.doc.Name)
        self.doc = None
        (archived,) = moved_documents.move_into(self.tmp.name, "archive", [monday], ["monday.FCStd"])
        self.open_at(tuesday, name)
        self.assertEqual(self.doc.Uid, uid)  # what the journal took for Monday's
        self.assertEqual(study_journal.lost(self.study), [], "another document saved from its template took them")
        self.open_at(archived, name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Ann"])

    def test_records_lost_before_the_document_was_moved_are_offered_where_it_is_now(self):
        # moved (a file manager, a synced folder with another path) after a close without
        # saving, the document was opened under another path: nothing was offered, and the
        # records stayed in a file under the earlier path's name for good
        self.addCleanup(self.forget_journals_here)
        self.doc.saveAs(self.path)
        earlier = self.path
        self.record("Ann", 4.0)
        self.doc.save()
        bo, cy = self.record("Bo", 5.0), self.record("Cy", 6.0)
        journal = study_journal.path_for(self.study)
        name = self.study.Name
        App.closeDocument(self.doc.Name)  # lost unsaved
        self.doc = None
        moved = os.path.join(self.tmp.name, "project", "brush head.FCStd")  # moved and renamed
        os.makedirs(os.path.dirname(moved))
        os.rename(earlier, moved)
        self.open_at(moved, name)
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann"])
        self.assertEqual([r.as_dict() for r in study_journal.lost(self.study)], [bo.as_dict(), cy.as_dict()],
                         "the records lost before the document was moved are not offered where it is now")
        self.assertEqual(len(study_journal.how_lost(self.study)), 2)
        self.assertNotIn(study_journal.ENDED, study_journal.how_lost(self.study))  # still said: a close
        self.assertEqual(study_journal.earlier_path(self.study), os.path.abspath(earlier))
        # from now on the file is the one of the document where it is
        here = study_journal.path_for(self.study)
        self.assertNotEqual(here, journal)
        self.assertFalse(os.path.exists(journal), "the file under the earlier path's name stays")
        self.assertTrue(os.path.exists(here))
        # lost here again before they are put back: still offered, still from where it was
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo", "Cy"])
        self.assertEqual(study_journal.earlier_path(self.study), os.path.abspath(earlier))
        self.put_back()
        self.assertEqual(study_journal.earlier_path(self.study), "")  # nothing offered
        self.doc.save()
        self.assertFalse(os.path.exists(journal))
        self.assertFalse(os.path.exists(here))
        self.close_unsaved_and_reopen()
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Ann", "Bo", "Cy"])
        self.assertEqual(study_journal.lost(self.study), [])

    def test_a_journal_whose_document_is_still_where_it_was_is_not_taken_by_a_copy(self):
        self.addCleanup(self.forget_journals_here)
        self.doc.saveAs(self.path)
        original = self.path
        self.record("Bo", 5.0)
        journal = study_journal.path_for(self.study)
        name = self.study.Name
        App.closeDocument(self.doc.Name)  # lost unsaved
        self.doc = None
        copy = os.path.join(self.tmp.name, "elsewhere", "toothbrush.FCStd")
        os.makedirs(os.path.dirname(copy))
        shutil.copy(original, copy)  # the same document (its Uid and all), at another path
        self.open_at(copy, name)
        self.assertEqual(study_journal.lost(self.study), [])  # the original's, which is still there
        self.assertFalse(os.path.exists(study_journal.path_for(self.study)))
        self.assertTrue(os.path.exists(journal))
        self.open_at(original, name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"])
        # its file taken away while it is open: the original is still the one its records are of
        aside = os.path.join(self.tmp.name, "aside.FCStd")
        os.rename(original, aside)
        other = App.openDocument(copy)
        try:
            self.assertEqual(study_journal.lost(other.getObject(name)), [])
        finally:
            App.closeDocument(other.Name)
        self.assertTrue(os.path.exists(journal))
        App.closeDocument(self.doc.Name)
        self.doc = None
        # the original gone for good: the copy is the document its records were lost from
        os.remove(aside)
        self.open_at(copy, name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"],
                         "the records of a document gone since are not offered to its copy")
        self.assertFalse(os.path.exists(journal))

    def test_the_journal_of_another_document_or_of_one_of_two_copies_moved_away_is_not_taken(self):
        self.addCleanup(self.forget_journals_here)
        name = self.study.Name
        # two documents whose studies have the same name and ID (FreeCAD draws a document's first
        # ID from 0-5000: documents made alike can share them), each losing records; the second a
        # copy of the first made another document (another Uid)
        first, second = moved_documents.paths_in(self.tmp.name, ("a", "b"))
        self.doc.saveAs(first)
        shutil.copy(first, second)
        self.record("Bo", 5.0)
        doc = App.openDocument(second)
        doc.Uid = str(uuid.uuid4())
        doc.save()
        study = doc.getObject(name)
        self.assertEqual((study.Name, study.ID), (self.study.Name, self.study.ID))
        self.assertNotEqual(doc.Uid, self.doc.Uid)
        doc.openTransaction("Record Cy")
        study.BeamThickness = 6.0
        HaptiCAD.record_preference(study, "Cy", "F", "26-40", 60, 1650)
        doc.commitTransaction()
        App.closeDocument(doc.Name)
        App.closeDocument(self.doc.Name)
        self.doc = None
        # both moved away: each is offered its own records, not the other's
        moved_first, moved_second = moved_documents.move_into(self.tmp.name, "moved", (first, second),
                                                              ("a.FCStd", "b.FCStd"))
        self.open_at(moved_second, name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Cy"],
                         "a moved document is not offered its own lost records (or is offered another's)")
        self.open_at(moved_first, name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Bo"])
        self.put_back()
        self.doc.save()
        # two copies of one document, each losing records, both moved away: whose they are
        # cannot be told, so neither is taken, and both stay
        copies = moved_documents.paths_in(self.tmp.name, ("copy1", "copy2"))
        journals = []
        for path, (who, thickness) in zip(copies, (("Dan", 3.0), ("Eve", 7.0))):
            shutil.copy(moved_first, path)
            self.open_at(path, name)
            self.record(who, thickness)
            journals.append(study_journal.path_for(self.study))
        App.closeDocument(self.doc.Name)
        self.doc = None
        moved_copies = moved_documents.move_into(self.tmp.name, "moved", copies, ("copy1.FCStd", "copy2.FCStd"))
        self.open_at(moved_copies[0], name)
        self.assertEqual(study_journal.lost(self.study), [])
        self.assertTrue(all(os.path.exists(j) for j in journals))
        App.closeDocument(self.doc.Name)
        self.doc = None
        # one moved back where it was: its file is its own again, and the other's is the moved one's
        os.rename(moved_copies[1], copies[1])
        self.open_at(moved_copies[0], name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Dan"])
        self.open_at(copies[1], name)
        self.assertEqual(self.names(study_journal.lost(self.study)), ["Eve"])

    def test_a_journal_that_cannot_be_written_is_said_and_the_record_still_made(self):
        self.doc.saveAs(self.path)
        journal = study_journal.path_for(self.study)
        os.makedirs(journal + ".part")  # where it is written first: a folder, so the write fails
        self.addCleanup(shutil.rmtree, journal + ".part", True)
        self.record("Bo", 5.0)
        self.assertEqual(self.names(stiffness_study.records(self.study)), ["Bo"])
        self.assertIn("Is a directory", study_journal.failure(self.study))
        shutil.rmtree(journal + ".part")
        self.record("Cy", 6.0)
        self.assertEqual(study_journal.failure(self.study), "")


if __name__ == "__main__":
    unittest.main()
