# SPDX-License-Identifier: GPL-3.0-or-later
"""The controls a participant uses while feeling a stiffness study (seed 000, Fig. 10):
a slider over one design parameter, the design's value on a relative scale, and a form
that records their preference with their personal data (Table 3).

Shown in the study's task panel and, while a Feel session runs on a document with a
study, in the Feel panel, so the participant presses, moves the slider, presses again,
and records without stopping. Every change is its own undo step; nothing here waits for
an OK, so a recorded participant is never lost to a Cancel.
"""
import FreeCAD as App
from PySide2 import QtCore, QtWidgets

from .. import cohort, stiffness_study

SLIDER_STEPS = 200


def set_study_property(study, name, value):
    """Sets a study's property as one undo step; False (and nothing set) if refused."""
    doc = study.Document
    doc.openTransaction(f"Stiffness study: {name}")
    try:
        setattr(study, name, value)
    except Exception:  # noqa: BLE001 (a value the property refuses)
        doc.abortTransaction()
        return False
    doc.commitTransaction()
    return True


class StudyControls(QtWidgets.QWidget):
    """Slider, value and participant form of one study. ``changed`` is emitted after
    the study changed through these controls."""

    changed = QtCore.Signal()

    def __init__(self, study, parent=None):
        super().__init__(parent)
        self.study = study
        self._loading = False
        layout = QtWidgets.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.slider_label = QtWidgets.QLabel()
        self.slider_label.setObjectName("studySliderLabel")
        layout.addWidget(self.slider_label)
        row = QtWidgets.QHBoxLayout()
        row.addWidget(QtWidgets.QLabel("softer" if study.Model == stiffness_study.BEAM else "lighter"))
        self.slider = QtWidgets.QSlider(QtCore.Qt.Horizontal)
        self.slider.setObjectName("studySlider")
        self.slider.setRange(0, SLIDER_STEPS)
        self.slider.valueChanged.connect(self.slid)
        row.addWidget(self.slider, 1)
        self.harder = QtWidgets.QLabel()
        row.addWidget(self.harder)
        layout.addLayout(row)
        self.value_label = QtWidgets.QLabel()
        self.value_label.setObjectName("studyValue")
        self.value_label.setWordWrap(True)
        layout.addWidget(self.value_label)

        form = QtWidgets.QFormLayout()
        self.name = QtWidgets.QLineEdit()
        self.name.setObjectName("participantName")
        self.name.setPlaceholderText("name or alias")
        self.gender = QtWidgets.QComboBox()
        self.gender.setObjectName("participantGender")
        self.gender.addItems(cohort.GENDERS)
        self.age = QtWidgets.QComboBox()
        self.age.setObjectName("participantAge")
        self.age.addItems(cohort.AGE_BANDS)
        self.weight = QtWidgets.QDoubleSpinBox()
        self.weight.setObjectName("participantWeight")
        self.weight.setRange(*cohort.WEIGHT_RANGE_KG)
        self.weight.setValue(70.0)
        self.weight.setSuffix(" kg")
        self.height = QtWidgets.QDoubleSpinBox()
        self.height.setObjectName("participantHeight")
        self.height.setRange(*cohort.HEIGHT_RANGE_MM)
        self.height.setDecimals(0)
        self.height.setValue(1700.0)
        self.height.setSuffix(" mm")
        for label, widget in (("Participant", self.name), ("Gender", self.gender), ("Age", self.age),
                              ("Weight", self.weight), ("Height", self.height)):
            form.addRow(label, widget)
        layout.addLayout(form)
        self.record_button = QtWidgets.QPushButton("Record: this feels right")
        self.record_button.setObjectName("recordPreference")
        self.record_button.setToolTip("Keep this participant's data and the design as it is now (Table 3 of seed 000)")
        self.record_button.clicked.connect(self.record)
        layout.addWidget(self.record_button)
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("studyMessage")
        self.message.setWordWrap(True)
        layout.addWidget(self.message)
        self.load()

    def _range(self):
        return float(self.study.AdjustMin), float(self.study.AdjustMax)

    def load(self):
        """Shows the study as it is (signals blocked: no echo back)."""
        self._loading = True
        try:
            label, unit = stiffness_study.adjust_info(self.study)
            low, high = self._range()
            current = float(getattr(self.study, self.study.Adjust))
            self.slider.setEnabled(high > low)
            if high > low:
                self.slider.setValue(round((current - low) / (high - low) * SLIDER_STEPS))
            self.slider_label.setText(f"Slide to change the {label}: {low:g}-{high:g} {unit}".rstrip())
            self.harder.setText("stiffer" if self.study.Model == stiffness_study.BEAM else "heavier")
            value, value_unit = stiffness_study.design_value(self.study)
            placed = cohort.place_design(value, stiffness_study.records(self.study))[1]
            self.value_label.setText(f"{label} {current:.3g} {unit} → <b>{value:.3g} {value_unit}</b>. "
                                     f"{placed[0].upper() + placed[1:]}.")
        finally:
            self._loading = False

    def slid(self, position):
        if self._loading:
            return
        low, high = self._range()
        set_study_property(self.study, self.study.Adjust, low + (high - low) * position / SLIDER_STEPS)
        self.load()
        self.changed.emit()

    def show_message(self, text, error=False):
        colour = "#b00000" if error else "#006000"
        self.message.setText(f"<span style='color:{colour}'>{text}</span>" if text else "")

    def record(self):
        """Records the participant's preference for the design as it is now."""
        doc = self.study.Document
        doc.openTransaction("Record a participant's preference")
        try:
            record = stiffness_study.record_preference(self.study, self.name.text(), self.gender.currentText(),
                                                       self.age.currentText(), self.weight.value(),
                                                       self.height.value())
        except ValueError as exc:
            doc.abortTransaction()
            self.show_message(f"Not recorded: {exc}", error=True)
            return None
        doc.commitTransaction()
        self.show_message(f"Recorded {record.name}: {record.value:.3g} {record.unit} "
                          f"({self.study.Participants} participant{'s' if self.study.Participants != 1 else ''}).")
        self.name.clear()
        self.load()
        self.changed.emit()
        App.Console.PrintLog(f"HaptiCAD: {self.study.Label}: recorded {record.name}\n")
        return record
