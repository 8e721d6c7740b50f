# SPDX-License-Identifier: GPL-3.0-or-later
"""Task panel of a stiffness study (seed 000 §3, Fig. 10): the mechanism and its values,
the slider a participant moves, the form that records their preference, and the cohort:
its table, its statistics by gender and age, where the design lies among the
preferences, CSV export and import.

Edits go to the study at once, each its own undo step, and the panel has only Close:
participants recorded during a session are never lost to a Cancel. To feel the design,
close the panel and press Feel: the Feel panel shows the same slider and form.

Participants recorded since the document was last saved are written to disk as they come
(study_journal): when the document was closed without saving them, or FreeCAD ended, the
panel offers them back at its top (Put back, one undo step) or to drop them, saying which
of the two lost them (a close is said with its time: the designer who closed it to
discard them drops them), and says there what Put back or Drop did. A document never
saved has nowhere to be written from: the panel says its records are on disk only once
saved.
"""
from html import escape

from PySide2 import QtCore, QtWidgets

from .. import cohort, preferences, stiffness_study, study_journal
from ..proxy_state import is_alive
from .narrow import let_narrow
from .quantity_spin import QuantitySpin
from .study_controls import StudyControls, set_study_property
from .task_panel_base import CloseOnlyPanel

LABELS = {"YoungsModulus": "Young's modulus E", "BeamWidth": "Width b", "BeamThickness": "Thickness h",
          "BeamLength": "Length L", "OperatingForce": "Operating force", "Pretravel": "Pretravel",
          "SnapRatio": "Snap ratio", "SnapTravel": "Snap travel", "TotalTravel": "Total travel",
          "HousingStiffness": "Housing stiffness",
          "BeamMaterial": "Material"}
TABLE_COLUMNS = ("Participant", "Preferred", "Gender", "Age", "Weight (kg)", "Height (mm)")  # what counts, first


class StudyQuantitySpin(QuantitySpin):
    """A spin box of one of the study's values, read as stiffness_study.typed_value reads
    it, in the unit of the property it takes (``quantity_of``; AdjustMin: the slider's):
    "6 cm" in a length is 60 mm, "1500 MPa" in the modulus 1.5 GPa, "4,5" 4.5, "150 gf"
    1.47 N. What is typed, and what is refused, as QuantitySpin."""

    def __init__(self, name, label):
        super().__init__(name, label)
        self.quantity_of = name  # the property whose unit and range it takes (AdjustMin: the slider's)

    def set_quantity(self, name, value_range, step):
        """Takes ``name``'s unit, over ``value_range`` (signals blocked by the caller)."""
        self.quantity_of = name
        self.setRange(*value_range)
        self.setSingleStep(step)

    def unit(self):
        # asked by QuantitySpin's own setup, before quantity_of is set: its name's then
        return stiffness_study.UNITS.get(getattr(self, "quantity_of", self.name), "")

    def read(self, text):
        return stiffness_study.typed_value(self.quantity_of, text, self.label)


class StudyTaskPanel(CloseOnlyPanel):
    ICON = "HaptiCAD_Study"

    def __init__(self, study):
        self.obj = study
        self.doc = study.Document
        self.widgets = {}
        self._loading = False
        # asked once (it probes HID devices): what a Feel session renders, the Feel panel's
        self.device_limits = stiffness_study.device_render_limits(self.doc)
        self.device_k = self.device_limits[0].max_stiffness_n_per_m
        self.controls = None
        self.controls_model = None
        # an import's or export's outcome, with the cohort it was said of: kept over the
        # reloads that follow (the study observer's, a turn later) until the cohort changes
        # or the next edit
        self.notice = None
        # what Put back or Drop did, said where the offer was (at the top), with the cohort it
        # was said of: kept until the cohort changes (an Undo of the put back) or the next edit
        self.journal_notice = None
        self.form = [self._status_box("Stiffness study", "studyStatus"), self._model_box(), self._customise_box(),
                     self._cohort_box()]
        self._journal_row(self.form[0].layout())
        self.watch_closing(self.doc)
        self.load()
        for box in self.form:
            let_narrow(box)

    # --- building -------------------------------------------------------------------

    def _spin(self, name, constraint, label=None):
        box = StudyQuantitySpin(name, label or LABELS.get(name, name))
        if constraint is not None:
            box.set_quantity(name, constraint[:2], constraint[2])
        box.valueChanged.connect(lambda v, n=name: self.set_property(n, float(v)))
        box.refused.connect(self.refused)
        return box

    def refused(self, text):
        """A value typed that is not set: said where the study's problems are, until the
        next edit ("": taken, or nothing typed; the status as the study is)."""
        if self._loading or not self._alive():
            return
        self.load()
        if text:
            self.status.setText(f"<span style='color:#b00000'>⚠ Not set: {escape(text, quote=False)}</span>")

    def _model_box(self):
        box = self._box("Mechanism")
        form = QtWidgets.QFormLayout(box)
        self.surface_label = QtWidgets.QLabel()
        form.addRow("Pressed surface", self.surface_label)
        model = QtWidgets.QComboBox()
        model.setObjectName("Model")
        model.addItems(stiffness_study.MODELS)
        model.currentTextChanged.connect(lambda text: self.set_property("Model", text))
        self.widgets["Model"] = model
        form.addRow("Model", model)
        self.rows = {}
        self.tips = {}  # each field's tooltip: its property's own
        for name, kind, group, tip, _, constraint in stiffness_study.PROPERTIES:
            if group not in ("Beam", "Button") or name == "BendingStiffness":
                continue
            if name == "BeamMaterial":
                field = QtWidgets.QComboBox()
                field.setObjectName(name)
                field.addItems(self.obj.getEnumerationsOfProperty(name))
                field.currentTextChanged.connect(lambda text: self.set_property("BeamMaterial", text))
            else:
                field = self._spin(name, constraint)
            self.tips[name] = tip
            label = QtWidgets.QLabel(LABELS.get(name, name))
            form.addRow(label, field)
            self.widgets[name] = field
            self.rows[name] = (group, label, field)
        self.law_label = QtWidgets.QLabel()
        self.law_label.setObjectName("studyLaw")
        self.law_label.setWordWrap(True)
        form.addRow(self.law_label)
        return box

    def _customise_box(self):
        box = self._box("The participant's slider")
        layout = QtWidgets.QVBoxLayout(box)
        form = QtWidgets.QFormLayout()
        adjust = QtWidgets.QComboBox()
        adjust.setObjectName("Adjust")
        adjust.currentIndexChanged.connect(self.adjust_chosen)
        self.widgets["Adjust"] = adjust
        form.addRow("Slider moves", adjust)
        for name in ("AdjustMin", "AdjustMax"):  # in the unit of what the slider moves (_load)
            label = "From" if name == "AdjustMin" else "To"
            spin = self._spin(name, None, f"The slider's {'low' if name == 'AdjustMin' else 'high'} end")
            self.widgets[name] = spin
            form.addRow(label, spin)
        layout.addLayout(form)
        self.controls_holder = QtWidgets.QVBoxLayout()
        layout.addLayout(self.controls_holder)
        return box

    def _cohort_box(self):
        box = self._box("Cohort")
        layout = QtWidgets.QVBoxLayout(box)
        self.table = QtWidgets.QTableWidget(0, len(TABLE_COLUMNS))
        self.table.setObjectName("cohortTable")
        self.table_rows = []  # what each row shows, (texts, tooltip): _show_rows writes what differs
        self.table.setHorizontalHeaderLabels(TABLE_COLUMNS)
        self.table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        self.table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        # each column as wide as its text, the last stretched: at 100 px each the six overran
        # the Combo View and the height hid behind a scroll bar
        self.table.horizontalHeader().setSectionResizeMode(QtWidgets.QHeaderView.ResizeToContents)
        self.table.horizontalHeader().setStretchLastSection(True)
        self.table.setMinimumHeight(140)
        layout.addWidget(self.table)
        buttons = QtWidgets.QGridLayout()  # two rows: three side by side are wider than the Combo View
        for place, (text, name, slot) in enumerate((("Remove", "removeParticipant", self.remove_selected),
                                                    ("Export CSV…", "exportCohort", self.choose_export),
                                                    ("Import CSV…", "importCohort", self.choose_import))):
            button = QtWidgets.QPushButton(text)
            button.setObjectName(name)
            button.clicked.connect(slot)
            buttons.addWidget(button, *((0, 0, 1, 2) if place == 0 else (1, place - 1)))
        layout.addLayout(buttons)
        self.stats = QtWidgets.QLabel()
        self.stats.setObjectName("cohortStats")
        self.stats.setWordWrap(True)
        self.stats.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        layout.addWidget(self.stats)
        return box

    def _journal_row(self, layout):
        """Under the status, at the top where the panel opens: participants recorded and lost
        unsaved (the document closed, FreeCAD ended), offered back or dropped; a document
        never saved, said to hold its records nowhere on disk yet."""
        self.journal_label = QtWidgets.QLabel()
        self.journal_label.setObjectName("cohortJournal")
        self.journal_label.setWordWrap(True)
        layout.addWidget(self.journal_label)
        lost_row = QtWidgets.QHBoxLayout()
        self.put_back_button = QtWidgets.QPushButton()
        self.put_back_button.setObjectName("putBackParticipants")
        self.put_back_button.setToolTip("Add them to the cohort again (one undo step), then save the document")
        self.put_back_button.clicked.connect(self.put_back)
        lost_row.addWidget(self.put_back_button, 1)
        self.drop_button = QtWidgets.QPushButton("Drop")
        self.drop_button.setObjectName("dropLostParticipants")
        self.drop_button.setToolTip("Forget them for good (it asks first)")
        self.drop_button.clicked.connect(self.drop_lost)
        lost_row.addWidget(self.drop_button)
        layout.addLayout(lost_row)

    # --- object -> widgets -------------------------------------------------------------

    def load(self, controls=True):
        """Shows the study as it is; ``controls``: the slider and form too (not when they
        asked, having just shown it themselves)."""
        self._loading = True
        try:
            self._load(controls)
        finally:
            self._loading = False

    def _controls_changed(self):
        self.load(controls=False)

    def _load(self, controls=True):
        obj = self.obj
        self.surface_label.setText(obj.Surface.Label if obj.Surface is not None else "none")
        for name, widget in self.widgets.items():
            if name == "Adjust":
                continue
            value = getattr(obj, name)
            # a property bound by an expression is the expression's to set, not the panel's
            bound = stiffness_study.expression_of(obj, name)
            widget.setEnabled(bound is None)
            tip = self.tips.get(name, "")
            widget.setToolTip(f"{tip}\nSet by the expression {bound}: edit that to change it".lstrip()
                              if bound else tip)
            widget.blockSignals(True)
            if isinstance(widget, QtWidgets.QComboBox):
                widget.setCurrentText(str(value))
            else:
                if name in ("AdjustMin", "AdjustMax") and obj.Adjust in stiffness_study.UNITS:
                    # the moved parameter's unit and range, widened to show a value set beyond it
                    low, high, step = next(p[5] for p in stiffness_study.PROPERTIES if p[0] == obj.Adjust)
                    widget.set_quantity(obj.Adjust, (min(low, value), max(high, value)), step)
                widget.setValue(float(value))
            widget.blockSignals(False)
        adjust = self.widgets["Adjust"]
        adjust.blockSignals(True)
        adjust.clear()
        for name, (label, unit, _) in stiffness_study.ADJUSTABLE[obj.Model].items():
            adjust.addItem(f"{label} ({unit})" if unit else label, name)
        adjust.setCurrentIndex(max(adjust.findData(obj.Adjust), 0))
        adjust.blockSignals(False)
        for name, (group, label, field) in self.rows.items():
            shown = (group == "Beam") == (obj.Model == stiffness_study.BEAM)
            label.setVisible(shown)
            field.setVisible(shown)
        value, unit = stiffness_study.design_value(obj)
        law = (f"Bending stiffness k = 3EI/L³ = <b>{obj.BendingStiffness:.3g} N/mm</b>" if obj.Model ==
               stiffness_study.BEAM else f"Operating force <b>{obj.OperatingForce:.3g} N</b> at "
               f"{obj.Pretravel:g} mm, returning at {obj.OperatingForce * (1 - obj.SnapRatio):.3g} N; bottoms "
               f"out at {obj.TotalTravel:g} mm on its housing, {obj.HousingStiffness:g} N/mm")
        notes = [n for n in (stiffness_study.device_note(obj, self.device_k),
                             stiffness_study.force_note(obj, self.force_limit()),
                             stiffness_study.ergonomic_note(obj)) if n]
        override = stiffness_study.material_override(obj)  # the combo still names the material
        self.law_label.setText(law + (f"<br>Modulus edited: {override}." if override else "")
                               + "".join(f"<br><span style='color:#a06000'>Note: {n}.</span>" for n in notes))
        if self.controls is None or self.controls_model != obj.Model:  # "softer" or "lighter"
            if self.controls is not None:
                self.controls.observer.remove()  # its call due would load the panel again
                self.controls.setParent(None)
                self.controls.deleteLater()
            # the researcher's panel: the design among the cohort's preferences shown (not in Feel's)
            self.controls = StudyControls(obj, lambda: self.device_k,
                                          force_limit=self.force_limit, show_cohort=True)
            self.controls.changed.connect(self._controls_changed)  # they have shown the change
            self.controls_holder.addWidget(self.controls)
            let_narrow(self.controls)
            self.controls_model = obj.Model
        elif controls:
            self.controls.load()
        self._load_cohort()
        problems = stiffness_study.validate(obj)
        if problems:
            self.status.setText("<span style='color:#b00000'>⚠ " + "<br>⚠ ".join(problems) + "</span>")
        else:
            self.status.setText(f"<span style='color:#006000'>✓ {obj.Model} under "
                                f"{obj.Surface.Label}: {cohort.format_value(value, unit)}. Close, then Feel it.</span>")

    def force_limit(self):
        """The largest force a Feel session renders (N): the Preferences' limit (read each
        time: it may change while the panel is open), under the device's own when known."""
        return stiffness_study.rendered_force_limit_n(self.device_limits, preferences.load().force_limit_n)

    def _load_journal(self):
        """What is not on disk: records lost unsaved (offered back, saying how they were
        lost), a document never saved, a journal that could not be written; and what Put
        back or Drop did (``journal_notice``)."""
        lost = study_journal.lost(self.obj)
        self.put_back_button.setVisible(bool(lost))
        self.drop_button.setVisible(bool(lost))
        notes = []
        if self.journal_notice is not None and self.journal_notice[1] != self.obj.Cohort:
            self.journal_notice = None  # said of a cohort that has changed since (an undo, a record)
        if self.journal_notice is not None:
            notes.append(self.journal_notice[0])
        if lost:
            many = len(lost) != 1
            them = "them" if many else "it"
            hows = study_journal.how_lost(self.obj)
            said = study_journal.said_how_lost([r.name for r in lost], hows)
            # a close without saving is seen (a crash is not): one made to discard them is the designer's to say
            closed = any(how not in (study_journal.ENDED, "") for how in hows)
            earlier = study_journal.earlier_path(self.obj)  # the document moved or renamed since
            where = f" (recorded when the document was at {escape(earlier)})" if earlier else ""
            self.put_back_button.setText(f"Put back {cohort.plural(len(lost), 'record')} ({_names(lost)})")
            notes.append(f"<span style='color:#b00000'>⚠ {cohort.plural(len(lost), 'participant record')} "
                         f"({escape(_names(lost))}) recorded here after the document was last saved "
                         f"{'are' if many else 'is'} not in it: {escape(said)}{where}. Put {them} back, then save the "
                         f"document" + (f", or Drop {them} if the close was to discard {them}" if closed else "")
                         + ".</span>")
        if study_journal.never_saved(self.obj):
            notes.append("<span style='color:#a06000'>This document has never been saved: the participants "
                         "recorded are on disk only once it is saved (from then on, each is written to disk as "
                         "it is recorded).</span>")
        failed = study_journal.failure(self.obj)
        if failed:
            notes.append(f"<span style='color:#b00000'>⚠ The participants recorded since the last save could not "
                         f"be written to disk as they came ({escape(failed)}): save the document now.</span>")
        self.journal_label.setText("<br>".join(notes))
        self.journal_label.setVisible(bool(notes))

    def _load_cohort(self):
        self._load_journal()
        try:  # a stored record that cannot be read (a hand-edited document) is named, the others shown
            held, unread = stiffness_study.readable_records(self.obj)
            records = stiffness_study.comparable_records(self.obj)
        except ValueError as exc:  # the stored cohort as a whole is not readable
            held, unread, records = [], [str(exc)], []
        others = len(held) - len(records)
        shown = []
        for r in records:
            beyond = cohort.mark(r)  # * felt at the device's limit, † its click never felt
            wrong = "; ".join(cohort.problems(r))  # saved before its range was checked
            tip = "; ".join(t for t in (wrong, cohort.force_limit_meaning([r]) + ": not counted in the statistics"
                                        if cohort.beyond_force_limit(r) else "") if t)
            shown.append(((r.name, f"{r.value:.3g} {r.unit}{beyond}{' ⚠' if wrong else ''}", r.gender, r.age_band,
                           *("-" if v is None else f"{v:g}" for v in (r.weight_kg, r.height_mm))), tip))
        self._show_rows(shown)
        rows = cohort.statistics(records)  # not those beyond the force limit (cohort.counted)
        aside = f"<br>{escape(stiffness_study.others_note(self.obj), quote=False)}." if others else ""
        starred = cohort.beyond_device_note(records)  # what the star means for this unit
        if starred:
            aside += f"<br>{escape(starred, quote=False)}"
        wrong = [(r.name, found) for r in records for found in [cohort.problems(r)] if found]
        if wrong:
            aside += (f"<br><span style='color:#b00000'>⚠ {len(wrong)} record{'s' if len(wrong) != 1 else ''} could "
                      f"not be recorded now ({escape(wrong[0][0])}: {escape(wrong[0][1][0])}): select and Remove "
                      f"{'them' if len(wrong) != 1 else 'it'}.</span>")
        if unread:
            aside += "<br><span style='color:#b00000'>" + unread_note(unread) + "</span>"
        if self.notice is not None and self.notice[1] != self.obj.Cohort:
            self.notice = None  # said of a cohort that has changed since (an undo, a record)
        notice = self.notice[0] + "<br>" if self.notice else ""
        if not rows:
            self.stats.setText(notice + ("No preference counted yet." if records else
                                         "No participant yet: each records what feels right with the slider above.")
                               + aside)
            return
        # the spread labelled as the sample SD (a bare ± reads as a range or an error); a group of one has none
        def n(s):  # people, and the records pooled into them when more
            return f"n {s['n']}" + (f" ({s['records']} records)" if s["records"] != s["n"] else "")

        lines = [f"{s['group']}: {n(s)}, {cohort.format_value(s['mean'], records[0].unit)}" if s["n"] == 1 else  # one
                 f"{s['group']}: {n(s)}, mean {s['mean']:.3g} (SD {cohort.format_sd(s['sd'])}), median "
                 f"{s['median']:.3g}, range {s['min']:.3g}-{s['max']:.3g} {records[0].unit}" for s in rows]
        if rows[0]["records"] != rows[0]["n"]:
            lines.append("A participant recorded more than once (one name, case and spacing aside, one gender "
                         "and age band) counts once, at the mean of their records.")
        value, _ = stiffness_study.design_value(self.obj)
        lines.append("This design: " + cohort.place_design(value, records)[1])
        self.stats.setText(notice + "<br>".join(lines) + aside)

    def _show_rows(self, shown):
        """Puts ``shown`` (each row's texts and tooltip) in the table, writing only the rows
        that differ from what it shows: a slider step, which changes no record, writes none.
        The header stops sizing to contents while cells are written: in a shown table each
        cell replaced made it measure every row again, quadratic in the cohort (26 s a
        slider step at 400 participants); it measures once, after."""
        table = self.table
        changed = [row for row, cells in enumerate(shown) if row >= len(self.table_rows)
                   or self.table_rows[row] != cells]
        if not changed and len(shown) == len(self.table_rows):
            return
        header = table.horizontalHeader()
        header.setSectionResizeMode(QtWidgets.QHeaderView.Fixed)
        try:
            table.setRowCount(len(shown))
            for row in changed:
                texts, tip = shown[row]
                for column, text in enumerate(texts):
                    item = QtWidgets.QTableWidgetItem(text)
                    item.setToolTip(tip)
                    table.setItem(row, column, item)
        finally:
            # sized to what it holds now, a removed row's text too (a turn later, once)
            header.setSectionResizeMode(QtWidgets.QHeaderView.ResizeToContents)
        self.table_rows = shown

    def say(self, text):
        """Shows ``text`` above the statistics until the cohort changes or the next edit."""
        self.notice = (text, self.obj.Cohort)
        self.journal_notice = None
        self.load()

    def say_at_offer(self, text):
        """Shows ``text`` where records lost unsaved are offered (at the top: what Put back or
        Drop did, where the designer pressed it) until the cohort changes or the next edit."""
        self.journal_notice = (text, self.obj.Cohort)
        self.load()

    # --- widgets -> object -------------------------------------------------------------

    def _alive(self):
        """False once the panel is closed or its study deleted (a field left as it goes)."""
        return not getattr(self, "_left", False) and is_alive(self.obj)

    def set_property(self, name, value):
        if self._loading or not self._alive():
            return
        self.notice = self.journal_notice = None
        if not set_study_property(self.obj, name, value):
            self.status.setText(f"<span style='color:#b00000'>⚠ {LABELS.get(name, name)}: {value} refused</span>")
            return
        self.load()

    def adjust_chosen(self, index):
        if self._loading or index < 0:
            return
        self.notice = self.journal_notice = None
        # the study sets the slider's range to the parameter's (StiffnessStudy.onChanged)
        set_study_property(self.obj, "Adjust", self.widgets["Adjust"].itemData(index))
        self.load()

    def remove_selected(self):
        # the table lists the comparable records only: its rows are not the records' indices
        shown = stiffness_study.comparable_indices(self.obj)
        indices = sorted({shown[i.row()] for i in self.table.selectedIndexes() if i.row() < len(shown)},
                         reverse=True)
        if not indices:
            return
        self.notice = self.journal_notice = None
        self.doc.openTransaction("Remove participants")
        try:
            for index in indices:
                stiffness_study.remove_record(self.obj, index)
        except ValueError as exc:  # a stored record that cannot be read: writing back would lose it
            self.doc.abortTransaction()
            self.say(f"<span style='color:#b00000'>Not removed: {escape(str(exc))}</span>")
            return
        self.doc.commitTransaction()
        self.load()

    def put_back(self):
        """Adds the records lost unsaved (study_journal.lost) to the cohort, one undo step;
        how many were put back."""
        lost = study_journal.lost(self.obj)
        if not lost or not self._alive():
            return 0
        self.doc.openTransaction("Put back participants recorded unsaved")
        try:
            stiffness_study.add_records(self.obj, lost)
        except ValueError as exc:  # an unreadable stored cohort
            self.doc.abortTransaction()
            self.say_at_offer(f"<span style='color:#b00000'>Not put back: {escape(str(exc))}</span>")
            return 0
        self.doc.commitTransaction()
        many = len(lost) != 1
        self.say_at_offer(f"<span style='color:#006000'>✓ Put back {cohort.plural(len(lost), 'record')} "
                          f"({escape(_names(lost))}). Save the document to keep {'them' if many else 'it'} on "
                          "disk.</span>")
        return len(lost)

    def drop_lost(self):
        """Forgets the records lost unsaved, when the designer says so; True if dropped."""
        lost = study_journal.lost(self.obj)
        many = len(lost) != 1
        if not lost or QtWidgets.QMessageBox.question(
                self.form[-1], "Drop participant records",
                f"Drop {cohort.plural(len(lost), 'record')} ({_names(lost)}) for good? No saved document holds "
                f"{'them' if many else 'it'}.",
                QtWidgets.QMessageBox.Yes | QtWidgets.QMessageBox.No,
                QtWidgets.QMessageBox.No) != QtWidgets.QMessageBox.Yes:
            return False
        try:
            study_journal.drop(self.obj, lost)
        except OSError as exc:
            self.say_at_offer(f"<span style='color:#b00000'>Not dropped: {escape(str(exc))}</span>")
            return False
        self.say_at_offer(f"<span style='color:#006000'>✓ Dropped {cohort.plural(len(lost), 'record')} "
                          f"({escape(_names(lost))}).</span>")
        return True

    def choose_export(self):
        path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Export the cohort", f"{self.obj.Label}.csv",
                                                        "CSV (*.csv)")
        if path:
            self.export_to(path)

    def export_to(self, path):
        try:
            cohort.write_csv(path, stiffness_study.records(self.obj))
        except (OSError, ValueError) as exc:  # (ValueError: an unreadable stored cohort)
            self.say(f"<span style='color:#b00000'>Not exported: {escape(str(exc))}</span>")
            return False
        return True

    def choose_import(self):
        path, _ = QtWidgets.QFileDialog.getOpenFileName(None, "Import participants", "", "CSV (*.csv)")
        if path:
            self.import_from(path)

    def import_from(self, path):
        self.doc.openTransaction("Import participants")
        try:
            result = stiffness_study.import_records(self.obj, path)
        except (ValueError, OSError) as exc:
            self.doc.abortTransaction()
            self.say(f"<span style='color:#b00000'>Nothing imported: {escape(str(exc))}</span>")
            return 0
        added, held, repeated = result
        if added:
            self.doc.commitTransaction()
        else:
            self.doc.abortTransaction()
        # a spreadsheet's re-save: which records were known by a time it rewrote, and how the file was read
        retimed = (f" ({result.retimed} of them known by their time to the precision the file gives it, as a "
                   "spreadsheet rewrites it)" if result.retimed else "")
        self.say(f"Imported {cohort.plural(added, 'record')}"
                 + (f"; {held} already held were left out{retimed}" if held else "")
                 + (f"; {repeated} listed again in the file {'was' if repeated == 1 else 'were'} taken once"
                    if repeated else "") + "."
                 + (f" Read as {escape(result.read_as)}." if result.read_as else ""))
        return added


def unread_note(unread):
    """The sentences of the stored records that cannot be read (stiffness_study.readable_records),
    as HTML, with what follows: they are kept as stored but neither shown nor counted, and
    what writes the cohort back (or out) is refused, since it would lose them."""
    them = "it" if len(unread) == 1 else "them"
    return ("⚠ " + "<br>⚠ ".join(escape(u) for u in unread)
            + f". Kept as stored, but not shown or counted. Recording, removing, importing, putting back and "
            f"exporting are refused while {them} cannot be read, so as not to lose {them}: mend the stored "
            f"record{'' if len(unread) == 1 else 's'}, or undo the edit that broke {them}.")


def _names(records, shown=5):
    """Whose ``records`` are, as plain text: "Bo, Cy", "Bo, Cy, Dan, Eve, Fay and 3 more"."""
    names = [r.name for r in records]
    more = len(names) - shown
    return ", ".join(names[:shown]) + (f" and {more} more" if more > 0 else "")
