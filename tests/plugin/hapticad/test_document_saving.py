# SPDX-License-Identifier: GPL-3.0-or-later
"""document_saving: a document read by a command line is saved back only if nobody saved
it meanwhile, and keeps what only the GUI writes. (A file or folder the user cannot write:
tests/cli/test_cli_fit_texture.py, run as another user.)"""
import os
import shutil
import tempfile
import threading
import time
import unittest
import zipfile

import FreeCAD as App

import HaptiCAD
from hapticad import document_saving


class SaveInPlaceTest(unittest.TestCase):
    def setUp(self):
        self.tmp = tempfile.TemporaryDirectory()
        self.addCleanup(self.tmp.cleanup)
        self.path = os.path.join(self.tmp.name, "part.FCStd")
        doc = App.newDocument("Saving")
        box = doc.addObject("Part::Box", "Box")
        doc.recompute()
        HaptiCAD.make_surface(doc, [(box, "Face6")], material="ABS").Label = "Grip"
        doc.saveAs(self.path)
        App.closeDocument(doc.Name)
        with zipfile.ZipFile(self.path, "a") as archive:  # what FreeCAD's GUI adds on its saves
            archive.writestr("GuiDocument.xml", "<Document/>")

    def open(self):
        doc = App.openDocument(self.path)
        name = doc.Name
        self.addCleanup(lambda: App.closeDocument(name) if name in App.listDocuments() else None)
        return doc

    def grip(self, doc):
        return doc.getObjectsByLabel("Grip")[0]

    def test_a_save_keeps_the_guis_part_of_the_file(self):
        read = document_saving.fingerprint(self.path)
        doc = self.open()
        self.grip(doc).TextureDC = 0.3
        document_saving.save_in_place(doc, read)
        with zipfile.ZipFile(self.path) as archive:
            self.assertEqual(archive.read("GuiDocument.xml"), b"<Document/>")
        App.closeDocument(doc.Name)
        self.assertAlmostEqual(self.grip(self.open()).TextureDC, 0.3)

    def test_another_programs_save_in_between_is_kept_and_this_one_refused(self):
        # two `fit-texture --apply` at once each said "set"; one change was lost
        read = document_saving.fingerprint(self.path)
        doc = self.open()
        other_path = os.path.join(self.tmp.name, "other.FCStd")  # FreeCAD opens a file once: a copy, moved in
        shutil.copyfile(self.path, other_path)
        other = App.openDocument(other_path)
        self.grip(other).TextureViscosity = 0.2
        other.save()
        App.closeDocument(other.Name)
        os.replace(other_path, self.path)
        kept = document_saving.fingerprint(self.path)
        self.grip(doc).TextureDC = 0.3
        with self.assertRaisesRegex(ValueError, "another program saved the document after it was read here; "
                                                "nothing was saved"):
            document_saving.save_in_place(doc, read)
        self.assertEqual(document_saving.fingerprint(self.path), kept)

    def test_the_check_and_the_save_wait_for_another_hapticad_saving_there(self):
        read = document_saving.fingerprint(self.path)
        doc = self.open()
        self.grip(doc).TextureDC = 0.3
        saved = threading.Event()
        with document_saving._folder_locked(self.tmp.name):
            worker = threading.Thread(target=lambda: (document_saving.save_in_place(doc, read), saved.set()))
            worker.start()
            time.sleep(0.3)
            self.assertFalse(saved.is_set())  # held while the other one saves
        worker.join(30)
        self.assertTrue(saved.is_set())


if __name__ == "__main__":
    unittest.main()
