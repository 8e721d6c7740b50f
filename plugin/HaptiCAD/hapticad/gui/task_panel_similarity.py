# SPDX-License-Identifier: GPL-3.0-or-later
"""Task panel of a similarity study (seed 001 §IV, Fig. 7): what it can run, its stimuli,
its participants' runs, and the perceptual space they make with each parameter's vector.

The surface and the references are links, set in the property editor (or with the
study's Python API). Edits go to the study at once, each its own undo step, and the
panel has only Close: runs kept during a session are never lost to a Cancel. The runs
themselves are made in the Feel panel, where the participant feels the textures.
"""
import html

from PySide2 import QtCore, QtGui, QtWidgets

from .. import similarity_study as ss
from ..similarity_export import write_csv as write_answers_csv
from ..similarity_plot import space_png
from ..surface_object import is_haptic_surface
from .study_observer import StudyObserver
from .narrow import let_narrow
from .task_panel_base import CloseOnlyPanel

STIMULUS_COLUMNS = ("Stimulus", *(ss.SYMBOLS[k] for k in ss.TEXTURE_VALUES))
RUN_COLUMNS = ("Participant", "Recorded", "Pairs", "Classings", "Stimuli")


class FittedPicture(QtWidgets.QLabel):
    """A picture shrunk to the width the panel gives it (never drawn larger): a plain
    pixmap would hold the panel at the picture's width."""

    def __init__(self):
        super().__init__()
        self.picture = None
        self.setSizePolicy(QtWidgets.QSizePolicy.Ignored, QtWidgets.QSizePolicy.Preferred)
        self.setAlignment(QtCore.Qt.AlignCenter)

    def set_picture(self, pixmap):
        self.picture = pixmap
        self._fit(new_picture=True)

    def clear(self):
        self.picture = None
        super().clear()

    def resizeEvent(self, event):
        super().resizeEvent(event)
        self._fit()

    def _fit(self, new_picture=False):
        if self.picture is None:
            return
        width = max(min(self.width(), self.picture.width()), 1)
        # a new picture of the same width is shown too: an analysis redrawn (another
        # scaling, a run removed) kept showing the old one
        if new_picture or self.pixmap() is None or self.pixmap().width() != width:
            self.setPixmap(self.picture.scaledToWidth(width, QtCore.Qt.SmoothTransformation))


class SimilarityTaskPanel(CloseOnlyPanel):
    ICON = "HaptiCAD_SimilarityStudy"

    def __init__(self, study):
        self.obj = study
        self.doc = study.Document
        self.form = [self._status_box("Similarity study", "similarityStatus"), self._stimuli_box(), self._runs_box()]
        self.watch_closing(self.doc, StudyObserver(study, self.load, watch_references=True))
        self.load()
        for box in self.form:
            let_narrow(box)

    # --- building -------------------------------------------------------------------

    def _table(self, name, columns):
        table = QtWidgets.QTableWidget(0, len(columns))
        table.setObjectName(name)
        table.setHorizontalHeaderLabels(columns)
        table.setEditTriggers(QtWidgets.QAbstractItemView.NoEditTriggers)
        table.setSelectionBehavior(QtWidgets.QAbstractItemView.SelectRows)
        table.horizontalHeader().setStretchLastSection(True)
        table.verticalHeader().setVisible(False)
        table.setMinimumHeight(120)
        return table

    def _button(self, text, name, slot, tip=""):
        button = QtWidgets.QPushButton(text)
        button.setObjectName(name)
        button.setToolTip(tip)
        button.clicked.connect(slot)
        return button

    def _stimuli_box(self):
        box = self._box("Stimuli")
        layout = QtWidgets.QVBoxLayout(box)
        self.stimuli_table = self._table("stimuliTable", STIMULUS_COLUMNS)
        layout.addWidget(self.stimuli_table)
        row = QtWidgets.QHBoxLayout()
        self.source = QtWidgets.QComboBox()
        self.source.setObjectName("stimulusSource")
        self.source.setMinimumContentsLength(6)  # beside Add, in the Combo View's width
        self.source.setToolTip("A haptic surface whose texture to add as a stimulus (one fitted to a recording, say)")
        row.addWidget(self.source, 1)
        row.addWidget(self._button("Add", "addStimulus", self.add_from_source))
        layout.addLayout(row)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self._button("Remove", "removeStimulus", self.remove_stimuli))
        row.addWidget(self._button("The paper's nine", "paperStimuli", self.paper_stimuli,
                                   "Three DC friction levels by three viscosities (seed 001 §IV)"))
        layout.addLayout(row)
        self.stimuli_message = QtWidgets.QLabel()
        self.stimuli_message.setObjectName("stimuliMessage")
        self.stimuli_message.setWordWrap(True)
        layout.addWidget(self.stimuli_message)
        return box

    def _runs_box(self):
        box = self._box("Perceptual space")
        layout = QtWidgets.QVBoxLayout(box)
        self.runs_table = self._table("runsTable", RUN_COLUMNS)
        layout.addWidget(self.runs_table)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self._button("Remove", "removeRun", self.remove_runs))
        row.addWidget(self._button("Export answers…", "exportAnswers", self.choose_export,
                                   "Every answer of every run, one row each with its stimuli's values, as CSV "
                                   "(for statistics elsewhere)"))
        layout.addLayout(row)
        self.runs_message = QtWidgets.QLabel()
        self.runs_message.setObjectName("runsMessage")
        self.runs_message.setWordWrap(True)
        layout.addWidget(self.runs_message)
        # how the space is made: classical MDS or Kruskal's ordinal MDS, in how many dimensions
        analysis = QtWidgets.QFormLayout()
        self.scaling = QtWidgets.QComboBox()
        self.scaling.setObjectName("Scaling")
        for value, text in (("Metric", "Metric (classical MDS)"), ("Ordinal", "Ordinal (Kruskal)")):
            self.scaling.addItem(text, value)
        self.scaling.setToolTip("Metric takes the dissimilarities as distances; Ordinal keeps only their order, "
                                "for participants who used the rating scale unevenly")
        self.scaling.currentIndexChanged.connect(
            lambda _i: self.set_analysis("Scaling", self.scaling.currentData()))
        analysis.addRow("Scaling", self.scaling)
        self.dimensions = QtWidgets.QSpinBox()
        self.dimensions.setObjectName("Dimensions")
        self.dimensions.setRange(1, 3)
        self.dimensions.valueChanged.connect(lambda v: self.set_analysis("Dimensions", int(v)))
        analysis.addRow("Dimensions", self.dimensions)
        layout.addLayout(analysis)
        self.space_text = QtWidgets.QLabel()
        self.space_text.setObjectName("spaceText")
        self.space_text.setWordWrap(True)
        self.space_text.setTextInteractionFlags(QtCore.Qt.TextSelectableByMouse)
        layout.addWidget(self.space_text)
        self.space_plot = FittedPicture()
        self.space_plot.setObjectName("spacePlot")
        layout.addWidget(self.space_plot)
        return box

    # --- object -> widgets -------------------------------------------------------------

    def load(self):
        from ..proxy_state import is_alive

        if getattr(self, "_left", False) or not self.form:
            return  # closed (an undone study closes its panel; a load was still due)
        if not is_alive(self.obj):
            for box in self.form:
                box.setEnabled(False)
            self.status.setText("<span style='color:#b00000'>The study was deleted.</span>")
            return
        found = ss.validate(self.obj)
        refs = ss.references(self.obj)
        surface = self.obj.Surface.Label if self.obj.Surface is not None else "no surface"
        if found:
            self.status.setText(f"<span style='color:#b00000'>Cannot run: {'; '.join(found)}.</span>")
        else:
            classing = (f"classed against {refs['A'].Label} (A) and {refs['B'].Label} (B)" if len(refs) == 2 else
                        "no references: link ReferenceA and ReferenceB to class the stimuli against them")
            self.status.setText(f"Felt on {surface}; {classing}. Runs are made in the Feel panel: "
                                "start a session there, enter the participant and Start run.")
        for widget, value in ((self.scaling, self.obj.Scaling), (self.dimensions, self.obj.Dimensions)):
            widget.blockSignals(True)
            if widget is self.scaling:
                widget.setCurrentIndex(max(widget.findData(value), 0))
            else:
                widget.setValue(int(value))
            widget.blockSignals(False)
        self._load_stimuli()
        self._load_runs()

    def _load_stimuli(self):
        try:
            items = ss.stimuli(self.obj)
        except ValueError as exc:
            items = []
            self.stimuli_message.setText(f"<span style='color:#b00000'>{exc}</span>")
        self.stimuli_table.setRowCount(len(items))
        for row, item in enumerate(items):
            cells = [item.get("name", "")] + [f"{item['values'].get(k, float('nan')):.3g}" for k in ss.TEXTURE_VALUES]
            for col, text in enumerate(cells):
                self.stimuli_table.setItem(row, col, QtWidgets.QTableWidgetItem(text))
        self.stimuli_table.resizeColumnsToContents()
        current = self.source.currentText()
        self.source.clear()
        for obj in self.doc.Objects:
            if is_haptic_surface(obj) and obj.Texture != "None":
                self.source.addItem(obj.Label, obj.Name)
        self.source.setCurrentIndex(max(self.source.findText(current), 0))

    def _load_runs(self):
        try:
            kept = ss.runs(self.obj)
        except ValueError as exc:
            self.space_text.setText(f"<span style='color:#b00000'>{exc}</span>")
            return
        self.runs_table.setRowCount(len(kept))
        for row, record in enumerate(kept):
            same = ss.comparable(record, self.obj)
            pooled = ("other: not pooled" if not same else
                      "these; classings against other references" if record.get("choices")
                      and not ss.classings_pooled(record, self.obj) else "these")
            cells = (record.get("name", "?"), record.get("recorded", ""), str(len(record.get("ratings", []))),
                     str(len(record.get("choices", []))), pooled)
            for col, text in enumerate(cells):
                self.runs_table.setItem(row, col, QtWidgets.QTableWidgetItem(text))
        self.runs_table.resizeColumnsToContents()
        try:
            result = ss.analyse(self.obj)
        except ValueError as exc:
            self.space_text.setText(str(exc) + ".")
            self.space_plot.clear()
            return
        # aligned like the console's, but wrapped to the panel (a <pre> line would widen it)
        self.space_text.setText("<div style='white-space:pre-wrap; font-family:monospace'>"
                                + html.escape(ss.describe(self.obj, result), quote=False) + "</div>")
        pixmap = QtGui.QPixmap()
        pixmap.loadFromData(space_png(result, size_in=(5.2, 5.2), dpi=80))
        self.space_plot.set_picture(pixmap)

    # --- widgets -> object -------------------------------------------------------------

    def _edit(self, title, change):
        """Runs ``change`` as one undo step; a refusal is said and nothing changes."""
        self.doc.openTransaction(title)
        try:
            change()
        except ValueError as exc:
            self.doc.abortTransaction()
            self.load()
            self.stimuli_message.setText(f"<span style='color:#b00000'>{exc}</span>")
            return False
        self.doc.commitTransaction()
        self.stimuli_message.setText("")
        self.load()
        return True

    def set_analysis(self, name, value):
        """How the space is made (Scaling, Dimensions): one undo step; the space follows."""
        if getattr(self.obj, name) != value:
            self.doc.openTransaction(f"Similarity study: {name}")
            setattr(self.obj, name, value)
            self.doc.commitTransaction()
        self.load()

    def add_from_source(self):
        name = self.source.currentData()
        surface = self.doc.getObject(name) if name else None
        if surface is None:
            self.stimuli_message.setText("<span style='color:#b00000'>No textured haptic surface to add.</span>")
            return False
        notes = []
        if not self._edit("Add a stimulus", lambda: notes.extend(ss.add_stimulus_from(self.obj, surface))):
            return False
        if notes:
            self.stimuli_message.setText("".join(
                f"<span style='color:#a06000'>Note: {html.escape(n, quote=False)}.</span>" for n in notes))
        return True

    def remove_stimuli(self):
        rows = {i.row() for i in self.stimuli_table.selectedIndexes()}
        if not rows:
            return False
        items = [s for i, s in enumerate(ss.stimuli(self.obj)) if i not in rows]
        return self._edit("Remove stimuli", lambda: ss.set_stimuli(self.obj, items))

    def paper_stimuli(self):
        return self._edit("The paper's nine stimuli", lambda: ss.set_stimuli(self.obj, ss.paper_stimuli()))

    def choose_export(self):
        path, _ = QtWidgets.QFileDialog.getSaveFileName(None, "Export the answers", f"{self.obj.Label}.csv",
                                                        "CSV (*.csv)")
        if path:
            self.export_to(path)

    def export_to(self, path):
        try:
            count = write_answers_csv(path, self.obj)
        except (OSError, ValueError) as exc:
            self.runs_message.setText(f"<span style='color:#b00000'>Not exported: {html.escape(str(exc))}</span>")
            return False
        self.runs_message.setText(f"<span style='color:#006000'>{count} answer{'s' if count != 1 else ''} "
                                  f"exported to {html.escape(path)}</span>")
        return True

    def remove_runs(self):
        rows = sorted({i.row() for i in self.runs_table.selectedIndexes()}, reverse=True)
        if not rows:
            return False

        names = [ss.runs(self.obj)[row].get("name", "?") for row in reversed(rows)]

        def remove():
            for row in rows:
                ss.remove_run(self.obj, row)
        if not self._edit("Remove participants' runs", remove):
            return False
        # one undo step and no question, as FreeCAD deletes: said, with the way back
        self.runs_message.setText(f"<span style='color:#006000'>Removed {html.escape(', '.join(names))}'s "
                                  f"run{'s' if len(names) != 1 else ''}: Edit &gt; Undo brings "
                                  f"{'them' if len(names) != 1 else 'it'} back.</span>")
        return True

