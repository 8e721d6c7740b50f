# SPDX-License-Identifier: GPL-3.0-or-later
"""The controls a participant uses in a similarity study's run (seed 001 §IV), shown in
the Feel panel beside the session: who they are, which texture is on the face now, and
their answer.

The participant presses *Texture 1* or *Texture 2* (as often as they like) to have that
texture on the study's face at the next servo tick, strokes it (a texture counts as felt
once stroked over one period of its grating: Run.stroked, fed from the loop's trace by
``stroked``), and rates how alike the two feel; in the classing part, *Texture*,
*Reference A* and *Reference B*, then *Closer to A* or *Closer to B*. They never see
which stimulus is which. *Back* takes the last answer back. When the last trial is
answered the run is kept in the document as one undo step; a run stopped before is not
kept (a half run would skew the cohort). While a
run holds answers its document cannot be closed (``holds_answers``; the Feel panel sets
it), so no way of closing it loses them unasked.

Every answer of a run in progress is written to disk (run_journal): a run FreeCAD never
kept (it was closed, or crashed) is offered to go on when the study's controls are next
shown, on the study as it was. A kept run the document lost unsaved is offered back (or
to drop), saying under the offer how it was lost (a close without saving, with its time;
a crash; an Undo), and what Put back or Drop did is said there too.

A change to the study during a run (a stimulus, the surface's friction, a reference)
pauses it, its answers held: undoing the change lets it go on, Stop run ends it. An Undo
that takes back a run kept earlier is said at once, and the next run kept asks whether
to keep the one taken back too (keeping clears Redo, which would lose it for good).
"""
import html
import json

import FreeCAD as App
from PySide2 import QtCore, QtWidgets

from .. import run_journal
from .. import similarity_study as ss
from .. import trace_path
from ..proxy_state import is_alive
from .study_observer import StudyObserver

KIND_TITLES = {"warm-up": "Warm-up (not kept)", "pair": "Pair", "class": "Closer to A or to B?"}


class SimilarityControls(QtWidgets.QWidget):
    """One study's run controls. ``presented`` is emitted when the texture on the face
    changes (the Feel panel hands the surfaces to the running loop again).
    ``session_running``: a callable, True while a Feel session renders the face (a
    texture is only felt then, so only then can a press be felt)."""

    presented = QtCore.Signal()
    changed = QtCore.Signal()
    shown = QtCore.Signal()  # after every change of the run's state

    def __init__(self, study, session_running=None, parent=None, session_info=None):
        super().__init__(parent)
        self.study = study
        self.session_running = session_running or (lambda: True)
        # what renders the run ({"device": name, "servo_rate_hz": rate}), kept with it: a
        # practice run on the mouse-driven probe is told from one on a device
        self.session_info = session_info or dict
        self.run = None
        self.slot = None  # what is on the face now: 1, 2, "A", "B" or None
        self.paused = ""  # why the run is paused: the study changed under it ("" when not)
        self.kept_here = []  # the runs these controls kept: an Undo may take them back
        self.taken_said = []  # those of them taken back that the message has said
        layout = QtWidgets.QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        row = QtWidgets.QHBoxLayout()
        self.name = QtWidgets.QLineEdit()
        self.name.setObjectName("similarityParticipant")
        self.name.setPlaceholderText("participant's name or alias")
        row.addWidget(self.name, 1)
        self.start_button = QtWidgets.QPushButton("Start run")
        self.start_button.setObjectName("similarityStart")
        self.start_button.clicked.connect(self.start)
        row.addWidget(self.start_button)
        self.stop_button = QtWidgets.QPushButton("Stop run")
        self.stop_button.setObjectName("similarityStop")
        self.stop_button.setToolTip("End this run without keeping it")
        self.stop_button.clicked.connect(self.stop)
        row.addWidget(self.stop_button)
        layout.addLayout(row)
        # a run written to disk after every answer and never kept (FreeCAD closed, or
        # crashed, mid-run): offered to go on
        self.resume_button = QtWidgets.QPushButton()
        self.resume_button.setObjectName("similarityResume")
        self.resume_button.clicked.connect(self.resume)
        layout.addWidget(self.resume_button)
        # runs kept in the document that was then closed or lost unsaved: offered back,
        # or dropped for good
        lost_row = QtWidgets.QHBoxLayout()
        self.put_back_button = QtWidgets.QPushButton()
        self.put_back_button.setObjectName("similarityPutBack")
        self.put_back_button.clicked.connect(self.put_back)
        lost_row.addWidget(self.put_back_button, 1)
        self.drop_button = QtWidgets.QPushButton("Drop")
        self.drop_button.setObjectName("similarityDropLost")
        self.drop_button.setToolTip("Forget these runs for good (it asks first)")
        self.drop_button.clicked.connect(self.drop_lost)
        lost_row.addWidget(self.drop_button)
        layout.addLayout(lost_row)
        # under the offer: how those runs were lost, and what Put back or Drop did
        self.journal_label = QtWidgets.QLabel()
        self.journal_label.setObjectName("similarityJournal")
        self.journal_label.setWordWrap(True)
        layout.addWidget(self.journal_label)
        # what Put back or Drop did, with the runs it was said of: kept until they change
        # (an Undo of the put back) or the next action
        self.journal_notice = None
        run_journal.watch_saves()

        self.trial_label = QtWidgets.QLabel()
        self.trial_label.setObjectName("similarityTrial")
        self.trial_label.setWordWrap(True)
        layout.addWidget(self.trial_label)
        feel = QtWidgets.QHBoxLayout()
        self.feel_buttons = {}
        for slot, text in ((1, "Texture 1"), (2, "Texture 2"), ("A", "Reference A"), ("B", "Reference B")):
            button = QtWidgets.QPushButton(text)
            button.setObjectName(f"similarityFeel{slot}")
            button.setCheckable(True)
            button.clicked.connect(lambda _checked=False, s=slot: self.show_texture(s))
            feel.addWidget(button)
            self.feel_buttons[slot] = button
        layout.addLayout(feel)

        # the scale's buttons, and under them what its ends mean (side by side, the row
        # would be wider than FreeCAD's Combo View)
        self.rating_buttons = []
        self.scale_box = QtWidgets.QHBoxLayout()
        self.scale_box.setSpacing(2)
        layout.addLayout(self.scale_box)
        self.scale_ends = QtWidgets.QWidget()  # hidden with the scale in a class trial
        self.scale_ends.setObjectName("similarityScaleEnds")
        ends = QtWidgets.QHBoxLayout(self.scale_ends)
        ends.setContentsMargins(0, 0, 0, 0)
        ends.addWidget(QtWidgets.QLabel("1: nothing alike"))
        ends.addStretch(1)
        self.top_label = QtWidgets.QLabel()
        ends.addWidget(self.top_label)
        layout.addWidget(self.scale_ends)
        classes = QtWidgets.QHBoxLayout()
        self.class_buttons = {}
        for key in "AB":
            button = QtWidgets.QPushButton(f"Closer to {key}")
            button.setObjectName(f"similarityClass{key}")
            button.clicked.connect(lambda _checked=False, k=key: self.answer(k))
            classes.addWidget(button)
            self.class_buttons[key] = button
        self.back_button = QtWidgets.QPushButton("Back")
        self.back_button.setObjectName("similarityBack")
        self.back_button.clicked.connect(self.back)
        classes.addWidget(self.back_button)
        layout.addLayout(classes)
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("similarityMessage")
        self.message.setWordWrap(True)
        layout.addWidget(self.message)
        self.observer = StudyObserver(study, self.external_change, watch_references=True)
        self.destroyed.connect(lambda *_: (self.observer.remove(), self.release()))
        self.load()

    def external_change(self):
        """The study, its surface or a reference changed by any way (an undo, the
        property editor): a run whose textures are no longer the study's pauses, its
        answers held, and goes on when they are again; a run kept here and taken back by
        an Undo is said."""
        if self.run is not None and not is_alive(self.study):
            self.run = None
            self.slot = None
            self.show_message("The study was deleted during the run: nothing kept.", error=True)
        elif self.run is not None:
            why = self._changed_since_start()
            if why and not self.paused:
                self.paused = why
                self.slot = None
                self.release()
                self.presented.emit()
                self.show_message(f"The study changed during the run ({why}): the run is paused, its "
                                  f"{len(self.run.answers)} answers held. Undo the change to go on, or Stop run.",
                                  error=True)
            elif not why and self.paused:
                self.paused = ""
                self.show_message("The study is as the run began: the run goes on.")
        taken = self.taken_back()
        if taken and taken != self.taken_said:
            names = html.escape(self._names(taken), quote=False)
            self.show_message(f"Undo took back {names} kept run: Redo brings it back. The next run kept asks "
                              "whether to keep it too.", error=True)
        self.taken_said = taken
        self.load()

    def _changed_since_start(self):
        """What of the study differs from when the run began, or ""."""
        found = ss.validate(self.study)
        if found:
            return "; ".join(found)
        if self.run.stimuli != ss.stimuli(self.study):
            return "its stimuli"
        if not ss.same_context(self.run.context, ss.felt_context(self.study)):
            return "the surface or a reference"
        return ""

    def taken_back(self):
        """The runs kept here that an Undo took back (Redo would bring them back)."""
        redo = self.study.Document.RedoNames if is_alive(self.study) else []
        if "Keep a similarity run" not in redo and "Put back kept similarity runs" not in redo:
            return []
        stored = ss.runs(self.study)
        return [record for record in self.kept_here if record not in stored]

    @staticmethod
    def _names(records):
        """ "Ada's" or "Ada's, Bea's" (plain text)."""
        return ", ".join(f"{r['name']}'s" for r in records)

    def session_stopped(self):
        """The Feel session stopped: nothing is felt, so the trial starts over."""
        self.release()
        self.slot = None
        if self.run is not None:
            self.run.forget_felt()
        self.load()

    def stroked(self, trace, doc_scene):
        """The loop's trace since the last display frame: how far the finger slid over
        the study's faces counts toward feeling the texture held out on them."""
        run = self.run
        if run is None or run.held is None or not len(trace) or not is_alive(self.study):
            return
        surface = self.study.Surface
        faces = [i for i, name in enumerate(doc_scene.face_names)
                 if surface is not None and doc_scene.face_surface.get(name) == surface.Name]
        felt = set(run.felt)
        run.stroked(trace_path.slid_mm(trace, faces))
        if run.felt != felt:
            self.load()  # the answer may be given now

    # --- state ---------------------------------------------------------------------------

    @property
    def holds_answers(self):
        """True while a run in progress has answers that ending it would lose."""
        return self.run is not None and bool(self.run.answers)

    def release(self):
        """Nothing held out on the face any more (the panel closes)."""
        if is_alive(self.study):
            ss.stop_presenting(self.study)

    def _set_scale(self, steps):
        if len(self.rating_buttons) == steps:
            return
        for button in self.rating_buttons:
            self.scale_box.removeWidget(button)
            button.deleteLater()
        self.rating_buttons = []
        self.top_label.setText(f"the same: {steps}")
        for value in range(1, steps + 1):
            button = QtWidgets.QPushButton(str(value))
            button.setObjectName(f"similarityRate{value}")
            button.setMinimumWidth(24)
            button.setMaximumWidth(40)
            button.clicked.connect(lambda _checked=False, v=value: self.answer(v))
            self.scale_box.addWidget(button)
            self.rating_buttons.append(button)

    def load(self):
        """Shows the run as it is: the trial, what can be felt and answered now."""
        if not is_alive(self.study):
            self.setEnabled(False)
            self.show_message("The study was deleted.", error=True)
            self.shown.emit()
            return
        running = self.run is not None
        trial = self.run.current if running and not self.paused else None
        self.name.setEnabled(not running)
        self.start_button.setEnabled(not running)
        waiting = None if running else run_journal.read(self.study)
        lost = [] if running else self.unsaved_kept()
        self.put_back_button.setVisible(bool(lost))
        self.drop_button.setVisible(bool(lost))
        notes = []
        if self.journal_notice is not None and self.journal_notice[1] != self.study.Responses:
            self.journal_notice = None  # said of runs that changed since (an Undo of the put back)
        if self.journal_notice is not None:
            notes.append(self.journal_notice[0])
        if lost:
            many = len(lost) > 1
            them = "them" if many else "it"
            hows = run_journal.how_lost(self.study, lost)
            said = run_journal.said_how_lost([str(r.get("name", "?")) for r in lost], hows)
            closed = any(how not in (run_journal.ENDED, run_journal.UNDONE, "") for how in hows)
            earlier = run_journal.earlier_path(self.study, lost)  # the document moved or renamed since
            said += f" (recorded when the document was at {earlier})" if earlier else ""
            self.put_back_button.setText(f"Put back {self._names(lost)} run{'s' if many else ''} "
                                         "(kept, document not saved)")
            self.put_back_button.setToolTip(f"Kept in the document, and not in it now: {said}. Put back, then save "
                                            "the document.")
            notes.append(f"<span style='color:#b00000'>⚠ {html.escape(self._names(lost), quote=False)} kept "
                         f"run{'s are' if many else ' is'} not in the document: {html.escape(said, quote=False)}. "
                         f"Put {them} back, then save the document"
                         + (f", or Drop {them} if the close was to discard {them}" if closed else "") + ".</span>")
        self.journal_label.setText("<br>".join(notes))
        self.journal_label.setVisible(bool(notes))
        self.resume_button.setVisible(waiting is not None)
        if waiting is not None:
            count = len(waiting["trials"])
            self.resume_button.setText(f"Go on with {waiting['name']}'s run ({len(waiting['answers'])} of {count} "
                                       "answered, not kept)")
        self.stop_button.setEnabled(running)
        self._set_scale(self.run.steps if running else int(self.study.RatingSteps))
        kind = trial.kind if trial else None
        shown = {1, "A", "B"} if kind == "class" else {1, 2}
        for slot, button in self.feel_buttons.items():
            button.setVisible(slot in shown)
            button.setEnabled(trial is not None)
            button.setChecked(self.slot == slot)
        self.feel_buttons[1].setText("Texture" if kind == "class" else "Texture 1")
        # an answer once both textures of a pair (or the texture of a class trial) were felt
        ready = running and not self.paused and self.run.ready
        for button in self.rating_buttons:
            button.setVisible(kind != "class")
            button.setEnabled(ready and kind != "class")
        self.scale_ends.setVisible(kind != "class")
        for button in self.class_buttons.values():
            button.setVisible(kind == "class")
            button.setEnabled(ready and kind == "class")
        self.back_button.setEnabled(running and not self.paused and bool(self.run.answers))
        if not running:
            found = ss.validate(self.study)
            self.trial_label.setText(
                f"<span style='color:#b00000'>Cannot run: {'; '.join(found)}.</span>" if found else
                f"Enter the participant, then Start run: {self._protocol()}.")
            self.start_button.setEnabled(not found)
        else:
            title, number, count = self.run.progress()
            if self.paused:
                self.trial_label.setText(f"<b>Paused at {KIND_TITLES[title]} {number} of {count}</b>: the study "
                                         "changed; undo the change to go on")
                self.shown.emit()
                return
            self.trial_label.setText(
                f"<b>{KIND_TITLES[title]} {number} of {count}</b>" + (
                    " (feel the texture, and references A and B as often as you need, then class it)"
                    if title == "class" else
                    " (feel both textures, then rate how alike they are)") + self._stroke_hint() + (
                    "<br><small>The document stays open until this run ends: finish it, or Stop run "
                    "(its answers are not kept).</small>" if self.holds_answers else ""))
        self.shown.emit()

    def _stroke_hint(self):
        """Says to stroke the texture on the face while it does not count as felt yet."""
        held = self.run.held
        if held is None or held in self.run.felt:
            return ""
        name = {1: "texture" if self.run.current.kind == "class" else "texture 1", 2: "texture 2",
                "A": "reference A", "B": "reference B"}[held]
        return f"<br><small>Stroke the face to feel {name}.</small>"

    def _protocol(self):
        n = len(ss.stimuli(self.study))
        parts = [f"{self.study.WarmUps} warm-ups", f"{n * (n - 1) // 2} pairs"]
        if len(ss.references(self.study)) == 2:
            parts.append(f"{n * self.study.Repeats} classings")
        return ", ".join(parts)

    def show_message(self, text, error=False):
        colour = "#b00000" if error else "#006000"
        self.message.setText(f"<span style='color:{colour}'>{text}</span>" if text else "")

    # --- actions -------------------------------------------------------------------------

    def start(self):
        waiting = run_journal.read(self.study)
        if waiting is not None and QtWidgets.QMessageBox.question(
                self, "Start run",
                f"{waiting['name']}'s run ({len(waiting['answers'])} of {len(waiting['trials'])} answered) was never "
                "kept. Start a new run and drop it?",
                QtWidgets.QMessageBox.Yes | QtWidgets.QMessageBox.No,
                QtWidgets.QMessageBox.No) != QtWidgets.QMessageBox.Yes:
            return False
        self.journal_notice = None
        try:
            self.run = ss.Run(self.study, self.name.text())
        except ValueError as exc:
            self.show_message(f"Not started: {exc}", error=True)
            return False
        self.slot = None
        self.paused = ""
        name = self.run.participant
        # "ada" after "Ada" is most likely the same person: counted (ss.participant_key)
        # and said as the same name
        spelled = [str(r.get("name", "")) for r in ss.runs(self.study)
                   if ss.participant_key(r.get("name", "")) == ss.participant_key(name)]
        before = len(spelled)
        other = next((n for n in spelled if n != name), None)
        # a second sitting, or two people under one name: kept either way, but said
        self.show_message(f"{html.escape(name)} already has {before} kept run{'s' if before != 1 else ''}: this one is "
                          "kept beside it, under the same name" + (
                              f" (kept as {html.escape(other)} before: write it one way)" if other else "")
                          if before else "")
        self.load()
        return True

    def resume(self):
        """Takes back the run written to disk, its answers as they were."""
        state = run_journal.read(self.study)
        if state is None or self.run is not None:
            return False
        self.journal_notice = None
        try:
            self.run = run_journal.resume(self.study, state)
        except ValueError as exc:
            self.show_message(f"{html.escape(str(exc), quote=False)}. Start run drops it (it asks first).", error=True)
            return False
        self.slot = None
        self.paused = ""
        self.show_message(f"{html.escape(self.run.participant)}'s run goes on at answer {len(self.run.answers) + 1}.")
        self.load()
        return True

    def unsaved_kept(self):
        """Runs kept earlier that the document lost unsaved (not those an Undo took back
        while Redo can bring them: the next keep asks about those)."""
        try:
            taken = self.taken_back()
            return [r for r in run_journal.unsaved_kept(self.study) if r not in taken]
        except ValueError:  # the study's stored runs are unreadable: said elsewhere
            return []

    def put_back(self):
        """Keeps again, one undo step, the runs the document lost unsaved."""
        lost = self.unsaved_kept()
        if not lost or self.run is not None:
            return False
        doc = self.study.Document
        doc.openTransaction("Put back kept similarity runs")
        try:
            for record in lost:
                ss.record_run(self.study, record)
        except ValueError as exc:
            doc.abortTransaction()
            self.say_at_offer(f"Not put back: {html.escape(str(exc), quote=False)}", error=True)
            return False
        doc.commitTransaction()
        self.kept_here.extend(lost)
        many = len(lost) > 1
        self.say_at_offer(f"✓ Put back {html.escape(self._names(lost), quote=False)} run{'s' if many else ''} "
                          f"({self.study.Participants} participant{'s' if self.study.Participants != 1 else ''}). "
                          f"Save the document to keep {'them' if many else 'it'} on disk.")
        self.changed.emit()
        return True

    def say_at_offer(self, text, error=False):
        """Shows ``text`` (HTML) under the offer of runs lost unsaved, where Put back and Drop
        are pressed, until the study's runs change or the next action."""
        colour = "#b00000" if error else "#006000"
        self.journal_notice = (f"<span style='color:{colour}'>{text}</span>", self.study.Responses)
        self.load()

    def drop_lost(self):
        """Forgets, when the designer says so, the runs the document lost unsaved."""
        lost = self.unsaved_kept()
        many = len(lost) > 1
        if not lost or QtWidgets.QMessageBox.question(
                self, "Drop kept runs",
                f"Drop {self._names(lost)} kept run{'s' if many else ''} for good? No saved document "
                f"holds {'them' if many else 'it'}.",
                QtWidgets.QMessageBox.Yes | QtWidgets.QMessageBox.No,
                QtWidgets.QMessageBox.No) != QtWidgets.QMessageBox.Yes:
            return False
        try:
            run_journal.drop_kept(self.study, lost)
        except OSError as exc:
            self.say_at_offer(f"Not dropped: {html.escape(str(exc), quote=False)}", error=True)
            return False
        self.say_at_offer(f"✓ Dropped {html.escape(self._names(lost), quote=False)} run"
                          f"{'s' if len(lost) > 1 else ''}.")
        return True

    def _write_journal(self):
        """The run in progress to disk (run_journal), so a crash loses no answer."""
        try:
            if self.run is not None and self.run.answers and not self.run.done:
                run_journal.write(self.study, self.run)
            else:
                run_journal.forget(self.study)
        except OSError as exc:
            self.show_message(f"The answers could not be written to disk as they come ({exc}): they are held "
                              "in memory only until the run is kept.", error=True)

    def stop(self):
        self.run = None
        self.slot = None
        self.paused = ""
        run_journal.forget(self.study)
        ss.stop_presenting(self.study)
        self.presented.emit()
        self.show_message("Run stopped; nothing kept.")
        self.load()

    def show_texture(self, slot):
        """Puts the current trial's texture ``slot`` on the face."""
        if self.run is None or self.run.current is None or not is_alive(self.study):
            return
        if not self.session_running():
            self.feel_buttons[slot].setChecked(False)
            self.show_message("Start the Feel session first: a texture is felt only while it runs.", error=True)
            return
        try:
            self.run.present(slot)
        except ValueError as exc:
            self.show_message(str(exc), error=True)
            return
        self.slot = slot  # felt once stroked (stroked, from the loop's trace)
        self.show_message("")
        self.presented.emit()
        self.load()

    def answer(self, value):
        if self.run is None or not is_alive(self.study):
            return
        try:
            self.run.answer(value)
        except ValueError as exc:
            self.show_message(str(exc), error=True)
            return
        held, self.slot = self.slot, None
        if held is not None:
            self.presented.emit()  # the face is back to the surface's own texture
        if self.run.done:
            self.keep()
        else:
            self._write_journal()
        self.load()

    def back(self):
        if self.run is not None and is_alive(self.study):
            self.run.back()
            self._write_journal()
            self.slot = None
            self.presented.emit()
            self.load()

    def keep(self):
        """Keeps the finished run in the document, one undo step; with it, if asked, the
        runs kept here that an Undo took back (keeping clears Redo: they would be lost)."""
        doc = self.study.Document
        taken = self.taken_back()
        if taken and QtWidgets.QMessageBox.question(
                self, "Keep a similarity run",
                f"Undo took back {self._names(taken)} kept run, which Redo would bring "
                "back. Keeping this run clears Redo.\n\nKeep the run taken back too?",
                QtWidgets.QMessageBox.Yes | QtWidgets.QMessageBox.No,
                QtWidgets.QMessageBox.Yes) != QtWidgets.QMessageBox.Yes:
            taken = []
        self.run.felt_with = dict(self.session_info())
        doc.openTransaction("Keep a similarity run")
        try:
            for earlier in taken:
                ss.record_run(self.study, earlier)
            record = ss.record_run(self.study, self.run)
        except ValueError as exc:
            doc.abortTransaction()
            self.show_message(f"Not kept: {exc}", error=True)
            return None
        doc.commitTransaction()
        unwritten = ""
        try:  # on disk until the document is saved (run_journal.SaveWatcher)
            for kept in [*taken, record]:
                run_journal.write_kept(self.study, json.loads(json.dumps(kept)))
        except OSError as exc:
            unwritten = (f" It could not be written to disk beside the document "
                         f"({html.escape(str(exc), quote=False)}): save now.")
        try:  # the run in progress is over: its journal goes
            run_journal.forget(self.study)
        except OSError as exc:
            App.Console.PrintWarning(f"HaptiCAD: the journal of the kept run could not be removed ({exc})\n")
        self.kept_here.append(json.loads(json.dumps(record)))  # as stored: compared with the stored runs
        self.run = None
        self.name.clear()
        self.show_message(f"Kept {html.escape(record['name'], quote=False)}'s run: {len(record['ratings'])} pairs"
                          + (f", {len(record['choices'])} classings" if record["choices"] else "")
                          + f" ({self.study.Participants} participant{'s' if self.study.Participants != 1 else ''})."
                          # nothing is saved for the designer: the run is written beside the
                          # document until a save holds it (run_journal.write_kept)
                          + " It is in the document: save the document to keep it on disk." + unwritten,
                          error=bool(unwritten))
        App.Console.PrintLog(f"HaptiCAD: {self.study.Label}: kept {record['name']}'s run\n")
        self.changed.emit()
        return record
