# SPDX-License-Identifier: GPL-3.0-or-later
"""The controls a participant uses while feeling a stiffness study (seed 000, Fig. 10):
a slider over one design parameter, the design's value on a relative scale, and a form
that records their preference with their personal data (Table 3).

Shown in the study's task panel and, while a Feel session runs on a document with a
study, in the Feel panel, so the participant presses, moves the slider, presses again,
and records without stopping. Every change is its own undo step; nothing here waits for
an OK, so a recorded participant is never lost to a Cancel, and each is written to disk
as it is recorded until the document is saved (study_journal; a document never saved is
said to have nowhere to write it).
"""
from html import escape

import FreeCAD as App
import shiboken2
from PySide2 import QtCore, QtWidgets

from .. import cohort, stiffness_study, study_journal
from ..proxy_state import is_alive
from .study_observer import StudyObserver

SLIDER_STEPS = 200


def _optional_spin(name, value_range, suffix, decimals):
    """A spin box whose lowest position, 0, reads "not given" (_given then gives None).
    It takes any number up to ten times ``value_range``'s top, not only the plausible
    range: a value outside that (170 typed as a height in cm) is kept as typed, and the
    record refused with cohort.problems' message (in centimetres? give 1700), where a spin
    box bounded by the range dropped it to "not given" on leaving the field, unsaid."""
    spin = _OptionalSpin(value_range[0])
    spin.setObjectName(name)
    spin.setDecimals(decimals)
    spin.setRange(0.0, 10.0 * value_range[1])
    spin.setSpecialValueText(cohort.NOT_GIVEN)
    spin.setSuffix(suffix)
    spin.setValue(spin.minimum())
    return spin


def _namesake_note(record, before):
    """What recording ``record`` after ``before`` did to the count, when its name was there
    already (as HTML, or ""): averaged with the same person's records (one name, gender and
    age band), or counted apart as another person of that name."""
    same = sum(1 for r in before if cohort.person_key(r) == cohort.person_key(record))
    namesakes = cohort.namesakes(record.name, before) - same
    if same:
        said = (f"{escape(record.name)} was recorded before ({cohort.plural(same, 'time')}): one person's records "
                "(one name, gender and age band) are averaged, as one participant, in the statistics; if this is "
                "someone else, remove this record and give another name.")
    elif namesakes:
        said = (f"{cohort.plural(namesakes, 'record')} of another {escape(record.name)} (another gender or age "
                f"band) {'is' if namesakes == 1 else 'are'} held: counted as another participant; if this is the "
                "same person, remove this record and record it again with the gender and age band given before.")
    else:
        return ""
    return f"<br><span style='color:#a06000'>Note: {said}</span>"


class _OptionalSpin(QtWidgets.QDoubleSpinBox):
    """A step up from "not given" goes to the plausible range's ``low`` end, a step down
    from there back to "not given" (not through 1, 2, 3 kg)."""

    def __init__(self, low):
        super().__init__()
        self.low = low

    def stepBy(self, steps):
        if steps > 0 and self.value() == self.minimum():
            self.setValue(self.low)
        elif steps < 0 and self.minimum() < self.value() <= self.low:
            self.setValue(self.minimum())
        else:
            super().stepBy(steps)


def _given(spin):
    return None if spin.value() == spin.minimum() else spin.value()


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
    """Slider, value and participant form of one study. ``changed`` is emitted after the
    study changed through these controls or any other way. ``device_stiffness``: a
    callable giving the device's stable stiffness (N/m), to say when a design is beyond
    it and to keep that with each record; ``force_limit``: one giving the largest force
    rendered (N), to say when a button's click lies above it and to keep that with each
    record. ``show_cohort``: say where the design lies among the other participants'
    preferences; off by default, for the participant's view (the Feel panel), where it
    would anchor their choice; the study's own panel, the researcher's, turns it on."""

    changed = QtCore.Signal()

    def __init__(self, study, device_stiffness=None, parent=None, force_limit=None, show_cohort=False):
        super().__init__(parent)
        self.study = study
        self.device_stiffness = device_stiffness or (lambda: None)
        self.force_limit = force_limit or (lambda: None)
        self.show_cohort = show_cohort
        self._loading = False
        self._dragging = False
        layout = QtWidgets.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        self.slider_label = QtWidgets.QLabel()
        self.slider_label.setObjectName("studySliderLabel")
        self.slider_label.setWordWrap(True)
        layout.addWidget(self.slider_label)
        row = QtWidgets.QHBoxLayout()
        self.lower_end = QtWidgets.QLabel()  # what the slider's ends do to the design (slider_ends)
        self.lower_end.setObjectName("studySliderLow")
        row.addWidget(self.lower_end)
        self.slider = QtWidgets.QSlider(QtCore.Qt.Horizontal)
        self.slider.setObjectName("studySlider")
        self.slider.setRange(0, SLIDER_STEPS)
        self.slider.valueChanged.connect(self.slid)
        # a drag is one undo step, not one per position it passed
        self.slider.sliderPressed.connect(self.drag_started)
        self.slider.sliderReleased.connect(self.drag_ended)
        row.addWidget(self.slider, 1)
        self.harder = QtWidgets.QLabel()
        self.harder.setObjectName("studySliderHigh")
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
        # one step below the range reads "not given": a participant need not say
        self.weight = _optional_spin("participantWeight", cohort.WEIGHT_RANGE_KG, " kg", 1)
        self.height = _optional_spin("participantHeight", cohort.HEIGHT_RANGE_MM, " mm", 0)
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
        self.clear_participant()
        self.observer = StudyObserver(study, self.external_change)
        self.destroyed.connect(lambda *_: self.observer.remove())
        self.load()

    def external_change(self):
        if not shiboken2.isValid(self):  # deleted with its panel (the study's creation undone)
            self.observer.remove()
            return
        if not is_alive(self.study):
            self.setEnabled(False)
            self.show_message("The study was deleted.", error=True)
            return
        self.load()
        self.changed.emit()

    def _range(self):
        return float(self.study.AdjustMin), float(self.study.AdjustMax)

    def load(self):
        """Shows the study as it is (signals blocked: no echo back)."""
        self._loading = True
        try:
            label, unit = stiffness_study.adjust_info(self.study)
            low, high = self._range()
            current = float(getattr(self.study, self.study.Adjust))
            bound = stiffness_study.adjust_expression(self.study)
            self.slider.setEnabled(high > low and bound is None)
            if high > low:
                self.slider.setValue(round((current - low) / (high - low) * SLIDER_STEPS))
            force_limit = self.force_limit()
            past = stiffness_study.range_note(self.study, force_limit)  # where the click stops being felt
            self.slider_label.setText(f"Slide to change the {label}: {low:g}-{high:g} {unit}".rstrip()
                                      + (f"<br><span style='color:#a06000'>{past[0].upper() + past[1:]}.</span>"
                                         if past else ""))
            low_end, high_end = stiffness_study.slider_ends(self.study)
            self.lower_end.setText(low_end)
            self.harder.setText(high_end)
            value, value_unit = stiffness_study.design_value(self.study)
            placed = ""
            unread = _unread(self.study)  # recording is refused: said before a participant tries
            if self.show_cohort and not unread:  # the others' preferences: the researcher's, not the participant's
                placed = cohort.place_design(value, stiffness_study.comparable_records(self.study))[1]
                placed = f" {placed[0].upper() + placed[1:]}."
            problems = stiffness_study.law_problems(self.study)
            limit = self.device_stiffness()
            note = stiffness_study.device_note(self.study, limit) if limit else ""
            note = "; ".join(n for n in (note, stiffness_study.force_note(self.study, force_limit)
                                         if force_limit else "", stiffness_study.outside_slider(self.study)) if n)
            recorded = f"<b>{cohort.format_value(value, value_unit)}</b>"
            # a neck's thickness gives its stiffness; a button's slider moves the value recorded itself
            moved = (f"{label} {current:.3g} {unit}".rstrip() + f" → {recorded}" if self.study.Model ==
                     stiffness_study.BEAM else recorded)
            self.value_label.setText(
                f"{moved}.{placed}"
                + (f"<br><span style='color:#a06000'>Note: {note}.</span>" if note else "")
                + (f"<br><span style='color:#a06000'>The {label} is set by the expression {bound}: clear "
                   "it to move the slider.</span>" if bound else "")
                + (f"<br><span style='color:#b00000'>Not felt: {'; '.join(problems)}.</span>" if problems else "")
                + (f"<br><span style='color:#b00000'>Not recordable: {escape(unread)}.</span>" if unread else ""))
        finally:
            self._loading = False
        # shown as it is now: the observer's call for the changes so far (a slider step's
        # own, a turn later) would load it, and the panel holding it, again
        self.observer.mark_shown()

    def drag_started(self):
        self._dragging = True
        self.study.Document.openTransaction("Stiffness study: slider")

    def drag_ended(self):
        self._dragging = False
        self.study.Document.commitTransaction()

    def slid(self, position):
        if self._loading:
            return
        low, high = self._range()
        value = low + (high - low) * position / SLIDER_STEPS
        if self._dragging:  # inside the drag's own transaction
            setattr(self.study, self.study.Adjust, value)
        else:
            set_study_property(self.study, self.study.Adjust, value)
        self.load()
        self.changed.emit()

    def show_message(self, text, error=False):
        colour = "#b00000" if error else "#006000"
        self.message.setText(f"<span style='color:{colour}'>{text}</span>" if text else "")

    def clear_participant(self):
        """The form as for a new participant: no name, and nothing else given."""
        self.name.clear()
        self.gender.setCurrentText(cohort.NOT_GIVEN)
        self.age.setCurrentText(cohort.NOT_GIVEN)
        self.weight.setValue(self.weight.minimum())  # not given
        self.height.setValue(self.height.minimum())

    def record(self):
        """Records the participant's preference for the design as it is now."""
        doc = self.study.Document
        # the same name again is noted, not refused: a second session of one person (averaged
        # with the first), or two people of one name, is the coordinator's call
        doc.openTransaction("Record a participant's preference")
        try:
            before = stiffness_study.comparable_records(self.study)  # (ValueError: an unreadable stored cohort)
            record = stiffness_study.record_preference(self.study, self.name.text(), self.gender.currentText(),
                                                       self.age.currentText(), _given(self.weight),
                                                       _given(self.height), self.device_stiffness(),
                                                       self.force_limit())
        except ValueError as exc:
            doc.abortTransaction()
            self.show_message(f"Not recorded: {escape(str(exc))}", error=True)  # may quote a hand-edited record
            return None
        doc.commitTransaction()
        if cohort.beyond_force_limit(record):  # its forces were not felt as designed: the star's note would not hold
            beyond = f" Marked †: {cohort.force_limit_meaning([record])}; left out of the statistics."
        elif cohort.beyond_device(record):
            beyond = f" Marked *: {cohort.BEYOND_DEVICE.get(record.unit, 'beyond what the device renders')}."
        else:
            beyond = ""
        again = _namesake_note(record, before)
        # the people the statistics count; those with records only of another unit said apart
        compared = cohort.count_participants(stiffness_study.comparable_records(self.study))
        held = self.study.Participants
        count = cohort.plural(compared, "participant") + (f" compared, {held} in all" if held != compared else "")
        # a document never saved has nowhere to write its records to as they come (study_journal)
        unsaved = ("<br><span style='color:#a06000'>The document has never been saved: save it to keep this "
                   "record on disk.</span>" if study_journal.never_saved(self.study) else "")
        self.show_message(f"Recorded {escape(record.name)}: {cohort.format_value(record.value, record.unit)} "
                          f"({count}).{beyond}" + again + unsaved)
        self.clear_participant()  # the next participant starts blank, inheriting nothing
        self.load()
        self.changed.emit()
        App.Console.PrintLog(f"HaptiCAD: {self.study.Label}: recorded {record.name}\n")
        return record


def _unread(study):
    """Why no preference can be recorded in ``study`` now, as a sentence, or "": a stored
    record (or the whole stored cohort) cannot be read, and writing the cohort back would
    lose it (stiffness_study.records)."""
    try:
        _, unread = stiffness_study.readable_records(study)
    except ValueError as exc:
        return str(exc)
    return unread[0] + (f" (and {len(unread) - 1} more)" if len(unread) > 1 else "") if unread else ""
