# SPDX-License-Identifier: GPL-3.0-or-later
"""Task panel of a Feel session: pick the device, start, watch, stop.

The servo loop runs in C++ (hapticad.feel_session); this panel only displays, from a
Qt timer at most 60 times a second: the probe, proxy and force arrow in the 3D view, a
strip chart of normal, friction and texture force (not the last two during a similarity
study's run, which is blind), the face under the probe with its
properties, and the loop rate. With the simulated probe the mouse steers it over the
part and the wheel or the slider sets how hard it presses. A HID device is opened on a
worker thread (hapticad.device_opening), polled from a Qt timer: a device that does not
answer takes seconds to fail, and FreeCAD stays responsive meanwhile. A session keeps the
preferences it started with: the display timer looks every PREFS_CHECK_S whether the saved
ones differ in what it uses, and a note then says they apply at the next Start.
"""
import html
import time

import numpy as np

import FreeCADGui as Gui
from PySide2 import QtCore, QtGui, QtWidgets

from .. import _core, device_opening, feel_notes, feel_session, icon, preferences, stiffness_study
from ..proxy_state import is_alive
from ..similarity_study import similarity_studies_of
from ..stiffness_study import studies_of
from .busy_cursor import busy_cursor
from .document_closing import DocumentClosingObserver
from .feel_view import FeelView, MouseSteering
from .narrow import let_narrow
from .strip_chart import StripChart
from .session_edit_observer import SessionEditObserver
from .similarity_controls import SimilarityControls
from .study_controls import StudyControls

DISPLAY_HZ = 60
OPEN_POLL_MS = 30  # how often the panel asks whether the device has opened (the Qt event loop runs between)
PREFS_CHECK_S = 0.25  # how often the display timer reads the preferences (a dozen parameters) during a session
# what the strip chart does not draw during a similarity run (the texture held out on the face)
BLIND_SERIES = ("texture_force_n", "friction_force_n")
_ACTIVE = []  # the open panel, for tests and for the Stop of a closing document


def _note(text):
    return f" Note: {text}." if text else ""


def active_panel():
    return _ACTIVE[-1] if _ACTIVE else None


def session_settings(prefs, simulated):
    """What a session uses of ``prefs``, by name: the servo rate, the force limit, the
    scene's accuracy and, with a device, its workspace mapping (the simulated hand's is
    the world). The device preference is not: the panel's choice is."""
    used = {"servo rate": prefs.servo_rate_hz, "force limit": prefs.force_limit_n,
            "accuracy": preferences.scene_accuracy(prefs)}
    if not simulated:
        used["workspace mapping"] = (prefs.workspace_mapping, prefs.workspace_scale
                                     if prefs.workspace_mapping == "Fixed scale" else None)
    return used
DEPTH_RANGE_MM = (0.0, 15.0)  # a 0.4 N/mm hand aimed 15 mm in pushes 6 N: past a 4.9 N switch
DEPTH_STEP_MM = 0.25


def _view_3d(doc):
    """The 3D view Feel draws in: the document's active view, or its 3D view brought to
    the front when another (a spreadsheet) is active; None when it has none open."""
    gui_doc = Gui.getDocument(doc.Name)
    if hasattr(gui_doc.ActiveView, "getSceneGraph"):
        return gui_doc.ActiveView
    if not gui_doc.mdiViewsOfType("Gui::View3DInventor"):
        return None
    if Gui.ActiveDocument is gui_doc:
        Gui.activateView("Gui::View3DInventor", False)
        if hasattr(gui_doc.ActiveView, "getSceneGraph"):
            return gui_doc.ActiveView
    return gui_doc.mdiViewsOfType("Gui::View3DInventor")[0]

class FeelTaskPanel:
    def __init__(self, doc):
        self.doc = doc
        self.session = None
        self.view_nodes = None
        self.steering = None
        self.edits = None  # the SessionEditObserver of a running session
        self.doc_scene = None
        self.frames = 0  # display updates with new samples
        self.last_sample = None
        self._limits_for = self._limits = None  # device_limits' answer, and what it was for
        self.opening = None  # the device_opening.DeviceOpening of a HID device Start is opening
        self.session_prefs = None  # the preferences the running session started with
        self._prefs_checked_at = 0.0  # time.monotonic() the display timer last read the preferences
        self.opening_label = ""  # that device's label, as the device choice shows it
        self.main = self._build()
        # a stiffness study's slider and participant form, next to the session (seed 000 Fig. 10)
        self.study_controls = [StudyControls(study, self.device_stiffness, force_limit=self.force_limit)
                               for study in studies_of(doc)]
        # a similarity study's runs: the participant picks the texture on the face and answers (seed 001 §IV)
        self.similarity_controls = [SimilarityControls(study, self.session_running, session_info=self.session_info)
                                    for study in similarity_studies_of(doc)]
        for controls in self.similarity_controls:
            controls.presented.connect(self.presented)
            controls.shown.connect(self.hold_document)
        self.form = [self.main, *(self._study_box(c) for c in self.study_controls),
                     *(self._study_box(c, "Similarity study", "HaptiCAD_SimilarityStudy")
                       for c in self.similarity_controls)]
        self.timer = QtCore.QTimer()
        self.timer.setInterval(int(1000 / DISPLAY_HZ))
        self.timer.timeout.connect(self.update_display)
        self.open_timer = QtCore.QTimer()
        self.open_timer.setInterval(OPEN_POLL_MS)
        self.open_timer.timeout.connect(self._poll_opening)
        self.refresh_devices()
        self.set_running(False)
        self.closing = DocumentClosingObserver(doc, self.document_closing)
        # closed without Close (Gui.Control.closeDialog()): the session must not outlive it
        self.main.destroyed.connect(self._form_destroyed)
        _ACTIVE.append(self)
        for box in self.form:
            let_narrow(box)

    # --- widgets -----------------------------------------------------------------------

    def _build(self):
        box = QtWidgets.QWidget()
        box.setWindowTitle("Feel")
        box.setWindowIcon(QtGui.QIcon(icon("HaptiCAD_Feel")))
        layout = QtWidgets.QVBoxLayout(box)
        form = QtWidgets.QFormLayout()
        self.device = QtWidgets.QComboBox()
        self.device.setObjectName("feelDevice")
        self.device.currentIndexChanged.connect(self._device_chosen)
        form.addRow("Device", self.device)
        self.depth = QtWidgets.QSlider(QtCore.Qt.Horizontal)
        self.depth.setObjectName("feelDepth")
        self.depth.setRange(0, int(DEPTH_RANGE_MM[1] / DEPTH_STEP_MM))
        self.depth.setValue(int(1.0 / DEPTH_STEP_MM))
        self.depth.setToolTip("How far below the face the simulated hand aims (the mouse wheel sets it too); the "
                              "face pushes back, so the probe goes in less: the line under the chart says how far")
        self.depth_label = QtWidgets.QLabel()
        row = QtWidgets.QHBoxLayout()
        row.addWidget(self.depth, 1)
        row.addWidget(self.depth_label)
        form.addRow("Aim", row)
        self.depth.valueChanged.connect(self.depth_set)
        layout.addLayout(form)
        buttons = QtWidgets.QHBoxLayout()
        self.start_button = QtWidgets.QPushButton(QtGui.QIcon(icon("HaptiCAD_Feel")), "Start")
        self.start_button.setObjectName("feelStart")
        self.start_button.clicked.connect(self.start)
        self.stop_button = QtWidgets.QPushButton("Stop")
        self.stop_button.setObjectName("feelStop")
        self.stop_button.clicked.connect(self.stop)
        buttons.addWidget(self.start_button)
        buttons.addWidget(self.stop_button)
        layout.addLayout(buttons)
        self.chart = StripChart()
        layout.addWidget(self.chart)
        self.face_label = QtWidgets.QLabel("Face: -")
        self.face_label.setObjectName("feelFace")
        self.face_label.setWordWrap(True)
        self.rate_label = QtWidgets.QLabel("Loop: stopped")
        self.rate_label.setObjectName("feelRate")
        self.rate_label.setWordWrap(True)
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("feelMessage")
        self.message.setWordWrap(True)
        # the preferences saved since Start that the session does not use yet (PREFS_CHECK_S)
        self.prefs_note = QtWidgets.QLabel()
        self.prefs_note.setObjectName("feelPreferencesNote")
        self.prefs_note.setWordWrap(True)
        self.prefs_note.setStyleSheet("color: #a06000")
        self.prefs_note.hide()
        for widget in (self.face_label, self.rate_label, self.message, self.prefs_note):
            layout.addWidget(widget)
        self.depth_set(self.depth.value())
        return box

    def device_stiffness(self):
        """The stable stiffness (N per m of the handle's travel, as felt) of the running
        session, or with none running, the one a session would have (a record made then
        keeps its device mark)."""
        if self.session is not None:
            return self.session.render_limits.max_stiffness_n_per_m
        return self.device_limits()[0].max_stiffness_n_per_m

    def force_limit(self):
        """The largest force rendered (N): the running session's, or with none running, the
        one a session started now would have: the preferences' limit under the chosen
        device's (a 20 N preference on the 8.9 N simulated hand renders 8.9 N)."""
        if self.session is not None:
            return self.session.render_limits.max_force_n
        return stiffness_study.rendered_force_limit_n(self.device_limits(), preferences.load().force_limit_n)

    def device_limits(self):
        """stiffness_study.device_render_limits for the device chosen above and the
        preferences as they are now; asked again only when either changes (it probes the
        HID devices, and the study controls ask at every slider step)."""
        prefs = preferences.load().replace(device=self.device.currentData() or feel_session.SIMULATED)
        if self._limits_for != prefs:
            self._limits = stiffness_study.device_render_limits(self.doc, prefs)
            self._limits_for = prefs
        return self._limits

    def _study_box(self, controls, kind="Stiffness study", icon_name="HaptiCAD_Study"):
        box = QtWidgets.QWidget()
        box.setWindowTitle(controls.study.Label)  # the icon tells the kind; both would not fit
        box.setToolTip(f"{kind}: {controls.study.Label}")
        box.setWindowIcon(QtGui.QIcon(icon(icon_name)))
        layout = QtWidgets.QVBoxLayout(box)
        layout.addWidget(controls)
        return box

    def refresh_devices(self):
        self.device.clear()
        for choice in feel_session.device_choices():
            self.device.addItem(choice.label, choice.path)
            if choice.problem:  # listed, so it is not missed, but not chosen: it says why
                item = self.device.model().item(self.device.count() - 1)
                item.setEnabled(False)
                item.setToolTip(choice.problem)
        index = self.device.findData(preferences.load().device)
        self.device.setCurrentIndex(max(index, 0))

    def _device_chosen(self, _index):
        """Another device: the study notes judge its limits (a session runs on the one it started with)."""
        if self.session is None:
            for controls in getattr(self, "study_controls", ()):
                controls.load()

    def depth_mm(self):
        return self.depth.value() * DEPTH_STEP_MM

    def depth_set(self, _value):
        self.depth_label.setText(f"{self.depth_mm():.2f} mm in")
        if self.steering is not None:
            self.steering.depth_mm = self.depth_mm()
            self.steering.aim_again()

    def wheel(self, step):
        self.depth.setValue(self.depth.value() + step)

    def set_running(self, running):
        """The buttons and the device choice for a session running or not; while a device
        opens (self.opening) Start and the device choice are off, and Stop gives up the opening."""
        busy = running or self.opening is not None
        self.start_button.setEnabled(not busy)
        self.stop_button.setEnabled(busy)
        self.device.setEnabled(not busy)
        self.depth.setEnabled(self.device.currentData() == feel_session.SIMULATED)

    def show_message(self, text, error=False):
        colour = "#b00000" if error else "#303030"
        # plain text with labels in it ("Lid <rev B>"): escaped, not read as markup
        self.message.setText(f"<span style='color:{colour}'>{html.escape(text, quote=False)}</span>" if text else "")

    # --- session -----------------------------------------------------------------------

    def start(self):
        """Start: with the simulated probe the session starts now (True), or the message
        says why not (False). A HID device is opened on a worker thread while the message
        says "Opening <device>..." and the Qt event loop runs (None is returned); the session
        starts once it has opened, or the device layer's error shows (_poll_opening)."""
        if self.opening is not None:  # Start is off while a device opens: a script's second call
            return None
        self.show_message("")
        path = self.device.currentData() or feel_session.SIMULATED
        if path == feel_session.SIMULATED:
            return self._start_session(path)
        if self._view_or_say() is None:  # before the device is opened: the probe is drawn there
            return False
        if device_opening.still_giving_up(path):  # its late session end would cut the new one's
            self.show_message(f"{self.device.currentText() or path} is still answering the open that was stopped: "
                              "press Start again in a moment.", error=True)
            return False
        self.opening_label = self.device.currentText() or path
        self.opening = device_opening.DeviceOpening(path)
        self.set_running(False)  # Start and the device choice off, Stop gives up
        self.show_message(f"Opening {self.opening_label}...")
        self.open_timer.start()
        return None

    def _view_or_say(self):
        """The 3D view Feel draws in, or None when the document has none open (the message says so)."""
        view = _view_3d(self.doc)
        if view is None:
            self.show_message(f"Feel draws the probe in a 3D view of {self.doc.Label}, and it has none open: open "
                              "one (View > Create new view) and press Start.", error=True)
        return view

    def _poll_opening(self):
        """The open timer: while the device opens, nothing; then the session starts on it,
        or the device layer's error shows and Start is on again."""
        if self.opening is None:
            self.open_timer.stop()
            return
        if self.opening.still_opening:
            return
        opening, self.opening = self.opening, None
        self.open_timer.stop()
        try:
            device = opening.poll()
        except (ValueError, RuntimeError) as exc:
            self.show_message(str(exc), error=True)
            self.set_running(False)
            return
        except Exception:
            self.set_running(False)
            raise
        if not self._start_session(device):
            self.set_running(False)

    def _start_session(self, device):
        """Builds the scene and starts a session on ``device`` (SIMULATED, or a device
        opened already); True, or False with the reason in the message."""
        from .. import preferences
        from ..document_scene import build_document_scene

        view = self._view_or_say()  # before anything is built (a device opens for seconds: it may have closed)
        if view is None:
            return False
        prefs = preferences.load()
        try:
            with busy_cursor():  # tessellating and building a large part's scene takes seconds
                self.doc_scene = build_document_scene(self.doc, preferences.scene_accuracy(prefs))
                self.session = feel_session.LiveSession(self.doc_scene, device, prefs)
        except (ValueError, RuntimeError) as exc:
            self.session = None
            self.show_message(str(exc), error=True)
            return False
        except MemoryError:  # a scene too fine for this computer (a custom accuracy)
            self.session = None
            self.doc_scene = None
            self.show_message("Not enough memory to build the part's scene at this accuracy: choose a coarser one "
                              "in Preferences (HaptiCAD > Accuracy).", error=True)
            return False
        low, high = feel_session.scene_box_m(self.doc_scene)
        radius = max(float(np.linalg.norm(high - low)) / feel_session.MM / 45.0, 0.3)
        self.view_nodes = FeelView(view, radius)
        start_w = None
        if self.session.simulated:
            self.steering = MouseSteering(view, self.doc_scene, self.session.set_target, self.wheel,
                                          tool_w=self.session.tool_w, proxy_w=self.session.proxy_w,
                                          top_mm=high[2] / feel_session.MM, clutch=self.session)
            self.steering.depth_mm = self.depth_mm()
            # the hand starts above the middle of the parts, clear of them
            start_w = np.array([0.5 * (low[0] + high[0]), 0.5 * (low[1] + high[1]), high[2] + 0.01])
        try:
            self.session.start(start_w)
        except (ValueError, RuntimeError) as exc:
            self.show_message(str(exc), error=True)
            self._tear_down()
            return False
        self.session_prefs = prefs
        self._prefs_checked_at = time.monotonic()
        self.chart.clear()
        self.timer.start()
        for controls in self.study_controls:  # now a device's limit can be told
            controls.load()
        self.edits = SessionEditObserver(self.doc, self.edited, lambda: self.doc_scene.shapes)
        self.set_running(True)
        self.show_message(("Move the mouse over the part; the wheel or the slider sets how hard you press."
                           if self.session.simulated else
                           "The device drives the probe." + _note(self.session.reach_note)) + self.session_notes())
        return True

    def session_notes(self):
        """As notes: vibrations felt nowhere (their part deleted), what the servo rate and the force limit
        keep a vibration from being felt as set, the roughness grids and gratings the servo rate cannot
        follow, and tagged parts hidden behind what is shown (a fillet made after tagging):
        feel_notes.session_notes, which `hapticad feel` and the headless demo say too."""
        return "".join(_note(n) for n in feel_notes.session_notes(self.doc, self.session.rate_hz,
                                                                  self.session.render_limits.max_force_n))

    def edited(self, geometry):
        """The designer edited the document while the session runs: a surface (felt from
        the next tick on) or the shape of a part, or a part newly tagged (tessellated
        again and swapped in)."""
        if self.session is None:
            return
        if geometry:
            # tessellating again takes a while on a big part: say so now (repaint draws
            # at once, without running other events in the middle of the edit)
            self.show_message("The part changed: building it again...")
            self.message.repaint()
        held = set(self.doc_scene.shapes)  # the parts felt until now, by name
        try:
            with busy_cursor():
                applied = self.session.apply_edit(self.doc, geometry)
        except Exception as exc:  # noqa: BLE001 (OCC and core errors too: named, and the loop keeps what it had)
            kept = "the part as it was" if geometry else "the surfaces as they were"
            self.show_message(f"{exc} (still feeling {kept})", error=True)
            return
        self.doc_scene = self.session.doc_scene
        if self.steering is not None:
            if applied == "scene":  # the hand re-lands if the swap left its proxy behind the part
                self.steering.scene_changed(self.doc_scene)
            else:
                self.steering.doc_scene = self.doc_scene
        if applied == "surfaces":
            self.show_message("Surface edited: you feel the change now." + self.session_notes())
        elif geometry:
            gone = sorted(held - set(self.doc_scene.shapes))  # deleted, or their last tag removed
            lead = (f"{', '.join(gone)} left the scene (deleted, or no longer tagged): you feel the rest now."
                    if gone else "Geometry edited: you feel the new shape now.")
            self.show_message(lead + _note(self.session.reach_note) + self.session_notes())
        else:
            self.show_message("Surface edited on a part the session did not hold: the scene was "
                              "built again and you feel it now." + _note(self.session.reach_note)
                              + self.session_notes())

    def hold_document(self):
        """A half-answered similarity run keeps the document open: FreeCAD then refuses
        every way of closing it (the window, Close All, quitting, a script), and the
        run's controls say why. Closing the document under the run took its answers
        without the question the panel's Close asks."""
        if is_alive(self.doc):
            self.doc.setClosable(not any(c.holds_answers for c in self.similarity_controls))

    def presented(self):
        """A similarity study put another texture on its face: the loop gets the surfaces
        again (no document edit, so the edit observer does not see it)."""
        if self.session is None:
            return
        try:
            self.session.apply_edit(self.doc, False)
        except Exception as exc:  # noqa: BLE001 (named, and the loop keeps what it had)
            self.show_message(f"{exc} (still feeling the surfaces as they were)", error=True)
            return
        self.doc_scene = self.session.doc_scene
        if self.steering is not None:
            self.steering.doc_scene = self.doc_scene

    def document_closing(self):
        """The document is being closed: the session stops, and the panel closes with it.
        Its 3D view is already being destroyed (asking it for its scene graph now
        crashes FreeCAD): the probe's nodes and the mouse callbacks go with it untouched."""
        self.closing = None
        self.view_nodes = None
        if self.steering is not None:
            self.steering.halt()  # its timer only: the view it listens to is going
        self.steering = None
        self.stop()
        self._leave()
        if Gui.Control.activeDialog():
            Gui.Control.closeDialog()

    def _form_destroyed(self, *_):
        if self.session is not None:
            self.session.stop()
        self._tear_down()
        self._leave()

    def update_display(self):
        """Drains the trace and shows it (the display timer, at most DISPLAY_HZ)."""
        if self.session is None:
            return
        # a similarity run is blind: the texture on the face must not be read off the chart
        self.chart.set_hidden(BLIND_SERIES if any(c.run is not None for c in self.similarity_controls) else ())
        trace = self.session.drain()
        for controls in self.similarity_controls:  # a texture held out is felt by stroking it
            controls.stroked(trace, self.doc_scene)
        if len(trace):
            self.frames += 1
            self.chart.append(trace)
            last = trace[-1]
            self.last_sample = last
            self.view_nodes.show(last["device_m"], last["proxy_m"], last["force_n"])
            contact = bool(last["flags"] & _core.FLAG_CONTACT)
            face = self.session.describe_face(int(last["cad_face"])) if contact else ""
            pressed_mm = float(np.linalg.norm(np.asarray(last["proxy_m"]) - np.asarray(last["device_m"]))) * 1e3
            self.face_label.setText(f"Face: {face}; the probe {pressed_mm:.2f} mm in" if face
                                    else "Face: - (not touching)")
        self.rate_label.setText(f"Loop: {self.session.achieved_rate_hz():.0f} Hz of "
                                f"{self.session.rate_hz:.0f} Hz, display {DISPLAY_HZ} Hz")
        if time.monotonic() - self._prefs_checked_at >= PREFS_CHECK_S:
            self._prefs_checked_at = time.monotonic()
            self.note_preferences()
        if not self.session.running:
            self.show_message(self.session.end_message or "The session ended.", error=True)
            self.stop()

    def note_preferences(self):
        """Says, once, which saved preferences the running session does not use (it keeps
        those it started with), and that they apply at the next Start; the note goes when
        they are as the session's again."""
        if self.session is None or self.session_prefs is None:
            return
        simulated = self.session.simulated
        now, kept = session_settings(preferences.load(), simulated), session_settings(self.session_prefs, simulated)
        changed = [name for name in kept if now[name] != kept[name]]
        text = (f"Preferences changed ({', '.join(changed)}): they apply when you press Stop and Start again; "
                "this session keeps those it started with." if changed else "")
        if text != self.prefs_note.text():  # set on a change only, not at every check
            self.prefs_note.setText(text)
            self.prefs_note.setVisible(bool(text))

    def session_running(self):
        return self.session is not None and self.session.running

    def session_info(self):
        """What renders now: the device's name and the servo rate (empty without a session)."""
        if self.session is None:
            return {}
        return {"device": str(self.session.device.info.name), "servo_rate_hz": float(self.session.rate_hz)}

    def stop(self):
        """Stops the session, or gives up a device still opening (no session starts on it)."""
        if self.opening is not None:
            self.show_message(f"Stopped: {self.opening_label} was still opening, and no session started.")
        if self.session is not None:
            self.session.stop()
            self.update_display_final()
            self.face_label.setText("Face: -")  # nothing is touched now
        self._tear_down()
        self.set_running(False)
        self.prefs_note.setText("")  # the next Start takes the preferences as they are
        self.prefs_note.hide()
        for controls in self.similarity_controls:  # nothing is felt now: no trial counts as felt
            controls.session_stopped()
        for controls in self.study_controls:  # their notes now judge what a session started now would render
            controls.load()

    def update_display_final(self):
        trace = self.session.drain()
        if len(trace):
            self.chart.append(trace)
        self.rate_label.setText(f"Loop: stopped after {self.session.ticks} ticks "
                                f"({self.session.achieved_rate_hz():.0f} Hz)")

    def _tear_down(self):
        self.timer.stop()
        self.open_timer.stop()
        if self.opening is not None:  # a device that opens later is dropped (closed), not started
            self.opening.abandon()
            self.opening = None
        if self.edits is not None:
            self.edits.remove()
            self.edits = None
        if self.steering is not None:
            self.steering.remove()
            self.steering = None
        if self.view_nodes is not None:
            self.view_nodes.remove()
            self.view_nodes = None
        self.session = None
        self.session_prefs = None

    # --- FreeCAD's task dialog -----------------------------------------------------------

    def getStandardButtons(self):
        return int(QtWidgets.QDialogButtonBox.Close)

    def _leave(self):
        """The panel is done: its document observer goes, no study holds a texture out,
        and it is no longer active."""
        for controls in self.similarity_controls:
            controls.release()
        if is_alive(self.doc):
            self.doc.setClosable(True)
        if self.closing is not None:
            self.closing.remove()
            self.closing = None
        if self in _ACTIVE:
            _ACTIVE.remove(self)

    def reject(self):
        if self not in _ACTIVE:
            return True  # left already (the document closed under it)
        if not self.confirm_ending_runs():
            return False  # the panel stays, the run goes on
        for controls in self.similarity_controls:  # ended as agreed: not offered again later
            if controls.run is not None:
                controls.stop()
        self.stop()
        self._leave()
        return True

    def confirm_ending_runs(self):
        """True to close: no similarity run is half answered, or the designer agrees to
        end it (a run is kept only when finished, so its answers go)."""
        going = [c.run for c in self.similarity_controls if c.run is not None and c.run.answers]
        if not going:
            return True
        runs = "; ".join(f"{r.participant}'s ({len(r.answers)} of {len(r.trials)} answered)" for r in going)
        answer = QtWidgets.QMessageBox.question(
            Gui.getMainWindow(), "Similarity run in progress",
            f"Closing ends the run in progress, {runs}, and keeps none of its answers: a run is kept "
            "only when finished. Close anyway?",
            QtWidgets.QMessageBox.Close | QtWidgets.QMessageBox.Cancel, QtWidgets.QMessageBox.Cancel)
        return answer == QtWidgets.QMessageBox.Close

    def accept(self):
        return self.reject()
