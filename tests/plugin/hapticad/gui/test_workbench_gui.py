# SPDX-License-Identifier: GPL-3.0-or-later
"""The workbench in FreeCAD's real GUI: it loads from the user's Mod folder, the
"Haptic surface" command tags a face picked with Gui.Selection as one undoable step,
and the 3D view shows the part. Run through gui_test_runner.py under Xvfb."""
import os
import sys
import unittest

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtGui, QtWidgets

import HaptiCAD
from hapticad import vibration_object

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import gui_helpers as h  # noqa: E402

SHOTS = os.environ.get("HAPTICAD_SCREENSHOT_DIR", "/tmp")


class WorkbenchGuiTest(unittest.TestCase):
    def setUp(self):
        self.doc = App.newDocument("GuiTest")
        self.box = self.doc.addObject("Part::Box", "Box")
        self.box.Length, self.box.Width, self.box.Height = 40, 30, 20
        self.doc.recompute()
        Gui.activateWorkbench("HaptiCADWorkbench")
        Gui.Selection.clearSelection()

    def tearDown(self):
        Gui.Selection.clearSelection()
        App.closeDocument(self.doc.Name)

    def test_workbench_loads_from_the_user_mod_folder(self):
        self.assertIn("HaptiCADWorkbench", Gui.listWorkbenches())
        self.assertEqual(Gui.activeWorkbench().name(), "HaptiCADWorkbench")
        self.assertTrue(HaptiCAD.__file__.startswith(os.path.join(App.getUserAppDataDir(), "Mod")),
                        HaptiCAD.__file__)
        toolbars = [t.windowTitle() for t in Gui.getMainWindow().findChildren(QtWidgets.QToolBar)]
        self.assertIn("HaptiCAD", toolbars)

    def test_command_is_enabled_only_with_faces_selected(self):
        from hapticad.gui.command_surface import CommandHapticSurface

        command = CommandHapticSurface()
        self.assertFalse(command.IsActive())
        Gui.Selection.addSelection(self.box, "Edge1")
        self.assertFalse(command.IsActive())
        Gui.Selection.addSelection(self.box, "Face6")
        self.assertTrue(command.IsActive())

    def test_commands_are_in_toolbar_and_menu_with_icons_tooltips_and_sensible_enabling(self):
        from hapticad.gui import commands

        names = [c for c in commands.MENU if c != "Separator"]
        for name in ("HaptiCAD_Surface", "HaptiCAD_EditSurface", "HaptiCAD_ToggleOverlay",
                     "HaptiCAD_OverlayByRoughness", "HaptiCAD_Feel", "HaptiCAD_Preferences"):
            self.assertIn(name, names)
        for name in names:
            command = Gui.Command.get(name)
            info = command.getInfo()
            self.assertTrue(info["toolTip"], name)
            self.assertTrue(os.path.isfile(info["pixmap"]), (name, info["pixmap"]))
        toolbar = [t for t in Gui.getMainWindow().findChildren(QtWidgets.QToolBar) if t.windowTitle() == "HaptiCAD"][0]
        self.assertEqual(len([a for a in toolbar.actions() if not a.isSeparator()]),
                         len([c for c in commands.TOOLBAR if c != "Separator"]))
        # without a surface: no edit, no feel; with one selected: both
        self.assertFalse(Gui.Command.get("HaptiCAD_EditSurface").isActive())
        self.assertFalse(Gui.Command.get("HaptiCAD_Feel").isActive())
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        Gui.Selection.addSelection(surface)
        h.process_events()
        self.assertTrue(Gui.Command.get("HaptiCAD_EditSurface").isActive())
        self.assertTrue(Gui.Command.get("HaptiCAD_Feel").isActive())
        # the overlay commands are check boxes that show the stored state
        self.assertTrue(Gui.Command.get("HaptiCAD_ToggleOverlay").getAction()[0].isCheckable())

    def test_command_tags_the_selected_face_in_one_undoable_step(self):
        Gui.Selection.addSelection(self.box, "Face6")
        Gui.runCommand("HaptiCAD_Surface")
        self.assertTrue(Gui.Control.activeDialog())  # the task panel opened on the new surface
        h.press_task_button("OK")
        surfaces = HaptiCAD.surfaces_of(self.doc)
        self.assertEqual(len(surfaces), 1)
        self.assertEqual(HaptiCAD.reference_pairs(surfaces[0]), [(self.box, "Face6")])
        self.assertEqual(type(surfaces[0].ViewObject.Proxy).__name__, "ViewProviderHapticSurface")
        self.doc.undo()
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [])

    def test_a_links_face_is_refused_with_a_sentence_and_nothing_is_made(self):
        # the toolbar button is enabled on an App::Link's face: it made a surface that
        # failed every recompute (a traceback, 44 drawing errors) and left its transaction open
        from unittest import mock

        link = self.doc.addObject("App::Link", "Link")
        link.setLink(self.box)
        link.Label = "BoxLink"
        self.doc.recompute()
        Gui.Selection.addSelection(link, "Face6")
        before = h.report_text()
        with mock.patch.object(QtWidgets.QMessageBox, "warning") as warned:
            Gui.runCommand("HaptiCAD_Surface")
        self.assertEqual(warned.call_count, 1)
        self.assertIn("BoxLink is a link to Box", warned.call_args[0][2])
        self.assertIn("tag Box's faces", warned.call_args[0][2])
        self.assertFalse(Gui.Control.activeDialog())
        self.assertEqual(HaptiCAD.surfaces_of(self.doc), [])
        self.assertFalse(self.doc.HasPendingTransaction)
        self.assertNotIn("Traceback", h.report_text()[len(before):])
        # a script is told the same
        with self.assertRaisesRegex(ValueError, "BoxLink is a link to Box"):
            HaptiCAD.make_surface(self.doc, [(link, "Face6")])

    def test_a_face_clicked_through_any_link_is_refused_and_no_other_part_is_tagged(self):
        # the command read the resolved selection: a click on a knob shown by a link to
        # another file tagged this file's own "Body" (the plate's top, no warning); through
        # a link to an App::Part or on a Draft link array it tagged the original, felt 38
        # and 35 mm from the click
        from unittest import mock

        from link_scenes import LinkedAssembly

        scene = LinkedAssembly()
        told = {}
        try:
            for what, point, refusal in scene.clicks:
                with self.subTest(what):
                    Gui.Selection.clearSelection()
                    h.click_at(point)
                    self.assertTrue(Gui.Selection.getSelectionEx("", 0), f"the click missed {what}")
                    self.assertTrue(Gui.Command.get("HaptiCAD_Surface").isActive())  # pressed, it says why
                    with mock.patch.object(QtWidgets.QMessageBox, "warning") as warned:
                        Gui.runCommand("HaptiCAD_Surface")
                        h.process_events()
                    made = scene.surfaces()
                    if Gui.Control.activeDialog():  # a surface made: taken back, for the next click
                        h.press_task_button("Cancel")
                    self.assertEqual(warned.call_count, 1)
                    said = told[what] = warned.call_args[0][2]
                    self.assertIn(refusal, said)
                    self.assertIn("cannot be tagged", said)
                    self.assertEqual(made, [])
                    self.assertFalse(scene.doc.HasPendingTransaction)
            # the knob's says where to tag it instead: in its own file
            self.assertIn("tag Body's faces in knob.FCStd itself", told.get(scene.clicks[0][0], ""))
            h.save_view("gui_link_refused.png")
            # the plate's own top, next to the knob, is tagged as the assembly's plate
            Gui.Selection.clearSelection()
            h.click_at((20, 20, 4))
            Gui.runCommand("HaptiCAD_Surface")
            h.press_task_button("OK")
            (surface,) = scene.surfaces()
            ((part, face),) = HaptiCAD.reference_pairs(surface)
            self.assertEqual((part.Document.Name, part.Name), ("Assembly", "Body"))
            self.assertAlmostEqual(part.Shape.getElement(face).CenterOfMass.z, 4.0)
        finally:
            Gui.Selection.clearSelection()
            scene.close()

    def test_deleting_a_vibrating_part_names_it_in_its_vibration_and_undo_mends_it(self):
        # the vibration said only "no part to vibrate", for good, after Std_Delete of its part
        HaptiCAD.make_surface(self.doc, [(self.box, "Face6")])
        vibration = HaptiCAD.make_vibration(self.doc, self.box)
        self.box.Label = "Razor head"
        self.doc.UndoMode = 1
        self.doc.recompute()
        before = h.report_text()
        Gui.Selection.addSelection(self.box)
        with h.MessageBoxes(press=QtWidgets.QMessageBox.Yes) as boxes:
            Gui.runCommand("Std_Delete")
            h.process_events()
        self.assertIn(vibration.Name, boxes.seen[0][1])  # FreeCAD's "might break" lists it
        self.doc.recompute()
        h.process_events()
        said = h.report_text()[len(before):]
        self.assertIn(f"{vibration.Label}: no part to vibrate: Razor head, which it vibrated, was deleted; undo the "
                      f"deletion, link a part in its Part property (Data tab) or delete {vibration.Label}", said)
        self.assertIsNone(vibration.Part)
        Gui.runCommand("Std_Undo")
        self.doc.recompute()
        h.process_events()
        self.assertEqual(vibration.Part.Name, "Box")
        self.assertEqual(vibration_object.validate(vibration), [])

    def test_every_panel_fits_freecads_combo_view_as_it_opens(self):
        # FreeCAD's Combo View opens about 250 px wide and its task panels do not scroll
        # sideways: a wider panel hides its right side (OK, Stop, messages). Every panel,
        # with its widest rows showing (a circular pattern, a texture, a vibration, both
        # kinds of study in the Feel panel, a study's space), fits 250 px
        from hapticad import preferences, similarity_study

        preferences.update(device="simulated")
        surface = HaptiCAD.make_surface(self.doc, [(self.box, "Face6")], pattern="Circular",
                                        Texture="Paper f_DC 0.500 f_vis +0.0")
        HaptiCAD.make_vibration(self.doc, self.box)
        study = HaptiCAD.make_study(self.doc, surface)
        HaptiCAD.record_preference(study, "Ada", "F", "26-40", 60, 1650)
        similarity = HaptiCAD.make_similarity_study(self.doc, surface, WarmUps=0)
        run = similarity_study.Run(similarity, "Ada", seed=1)
        while not run.done:
            run.present_each()
            run.answer(1 + (run.current.first + run.current.second) % 7)
        similarity_study.record_run(similarity, run)  # its space is drawn in the panel
        self.doc.recompute()
        h.widen_panel(260)  # as FreeCAD opens it

        def panel():
            for area in Gui.getMainWindow().findChildren(QtWidgets.QScrollArea):
                content = area.widget()
                if area.isVisible() and content is not None and content.findChildren(QtWidgets.QDialogButtonBox):
                    return content
            self.fail("no task panel showing")

        def widest():
            content = panel()
            # and no spin box squeezed below what its value and unit need (x, y, z rows set their own)
            for spin in content.findChildren(QtWidgets.QAbstractSpinBox):
                if spin.isVisible() and spin.minimumWidth() == 0:  # (a form layout may round a pixel off)
                    self.assertGreaterEqual(spin.width(), spin.minimumSizeHint().width() - 2, spin.objectName())
            return content.minimumSizeHint().width()

        for name, open_panel, button in (
                ("surface", lambda: Gui.ActiveDocument.setEdit(surface.Name, 0), "Cancel"),
                ("stiffness study", lambda: Gui.ActiveDocument.setEdit(study.Name, 0), "Close"),
                ("similarity study", lambda: Gui.ActiveDocument.setEdit(similarity.Name, 0), "Close"),
                ("feel", lambda: Gui.runCommand("HaptiCAD_Feel"), "Close")):
            open_panel()
            h.process_events()
            self.assertLessEqual(widest(), 250, name)
            h.press_task_button(button)
            h.process_events()

    def test_the_3d_view_shows_the_part(self):
        Gui.Selection.addSelection(self.box, "Face6")
        Gui.runCommand("HaptiCAD_Surface")
        h.press_task_button("OK")
        Gui.Selection.clearSelection()
        view = Gui.ActiveDocument.ActiveView
        view.viewIsometric()
        view.fitAll()
        path = os.path.join(SHOTS, "gui_workbench_box.png")
        view.saveImage(path, 480, 360, "White")
        image = QtGui.QImage(path)
        self.assertFalse(image.isNull())
        # not blank, and the part sits in the middle of the view (the overlay's legend
        # takes the top-left corner: look at the bottom-left one)
        self.assertGreater(h.non_white_fraction(image), 0.10)
        self.assertGreater(h.non_white_fraction(image, 0.4, 0.4, 0.6, 0.6), 0.9)
        self.assertLess(h.non_white_fraction(image, 0.0, 0.9, 0.1, 1.0), 0.05)


if __name__ == "__main__":
    unittest.main()
