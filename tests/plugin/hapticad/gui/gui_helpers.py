# SPDX-License-Identifier: GPL-3.0-or-later
"""Helpers for GUI tests: synthetic mouse events in the 3D view, the task panel's
widgets and buttons, screenshots and pixel measures. Used inside FreeCAD's GUI."""
import contextlib
import os
import sys
import time
import traceback

import FreeCAD as App
import FreeCADGui as Gui
from PySide2 import QtCore, QtGui, QtWidgets

SHOTS = os.environ.get("HAPTICAD_SCREENSHOT_DIR", "/tmp")


def process_events(rounds=3):
    for _ in range(rounds):
        QtWidgets.QApplication.processEvents()
        Gui.updateGui()


def wait(seconds):
    """Runs Qt's events for ``seconds`` (a live session's display timer, the loop)."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        process_events(1)
        time.sleep(0.005)


def wait_for(condition, what="", dead_after_s=20.0):
    """Runs Qt's events until ``condition()`` holds, however long a slow host takes; the
    limit only catches a loop or timer that never gets there."""
    end = time.monotonic() + dead_after_s
    while not condition():
        if time.monotonic() > end:
            raise AssertionError(f"not within {dead_after_s} s: {what or condition}")
        process_events(1)
        time.sleep(0.005)


def wait_settled(chart, what, dead_after_s=20.0):
    """Until the Feel panel's simulated hand has landed on the part and the normal force on
    ``chart`` (its strip chart) has settled (the mean of the last 100 samples within 2 % of
    the 100 before), all 300 samples since the call: the hand comes down in a fixed number
    of display ticks, which a slow host stretches in wall time, and a force changed by the
    wheel or an edit takes a moment to settle."""
    import numpy as np

    from hapticad.gui import task_panel_feel

    since = chart.sample_count

    def settled():
        normal = np.asarray(chart.values["normal_force_n"], float)
        panel = task_panel_feel.active_panel()
        if panel is None or panel.steering is None or not panel.steering.hand.landed:
            return False
        if chart.sample_count < since + 300 or len(normal) < 200:
            return False
        last, before = float(normal[-100:].mean()), float(normal[-200:-100].mean())
        return abs(last - before) <= 0.02 * abs(before)

    wait_for(settled, f"{what}: the hand landed and the normal force settled", dead_after_s)


def type_into(spin, text, finish="return"):
    """Types ``text`` into a spin box as a user does (its text selected, key by key), then
    presses Return ("return"), leaves the field with Tab ("leave"; its focus cleared too,
    where Tab found no other widget to move to) or neither (None: still being typed)."""
    from PySide2 import QtCore, QtGui, QtWidgets

    def key(code, char=""):
        for kind in (QtCore.QEvent.KeyPress, QtCore.QEvent.KeyRelease):
            QtWidgets.QApplication.sendEvent(line, QtGui.QKeyEvent(kind, code, QtCore.Qt.NoModifier, char))

    spin.setFocus()
    process_events()
    line = spin.lineEdit()
    line.selectAll()
    for char in text:
        key(0, char)
    if finish == "return":
        key(QtCore.Qt.Key_Return)
    elif finish == "leave":
        key(QtCore.Qt.Key_Tab)
        spin.clearFocus()
    process_events()


def show_workbench():
    """Switches to the HaptiCAD workbench and shows the active document isometric, fitted."""
    Gui.activateWorkbench("HaptiCADWorkbench")
    view = Gui.ActiveDocument.ActiveView
    view.viewIsometric()
    view.fitAll()
    process_events()


def gl_widget():
    """The widget that receives the 3D view's mouse events (its OpenGL viewport)."""
    view = Gui.ActiveDocument.ActiveView
    graphics = view.graphicsView()
    return graphics.viewport() if graphics is not None else None


def screen_pos(point):
    """Widget coordinates (Qt, y down) of a 3D point (mm) in the active view."""
    view = Gui.ActiveDocument.ActiveView
    x, y = view.getPointOnScreen(App.Vector(*point))
    width, height = view.getSize()
    widget = gl_widget()
    sx, sy = widget.width() / width, widget.height() / height
    return QtCore.QPointF(x * sx, (height - y) * sy)


def mouse(kind, pos, button=QtCore.Qt.LeftButton, buttons=None):
    events = {"press": QtCore.QEvent.MouseButtonPress, "release": QtCore.QEvent.MouseButtonRelease,
              "move": QtCore.QEvent.MouseMove}
    if buttons is None:
        buttons = button if kind == "press" else QtCore.Qt.NoButton
    event = QtGui.QMouseEvent(events[kind], pos, QtCore.Qt.NoButton if kind == "move" else button, buttons,
                              QtCore.Qt.NoModifier)
    QtWidgets.QApplication.sendEvent(gl_widget(), event)


def click_at(point):
    """A left click on the 3D point (mm) as a user would do it."""
    pos = screen_pos(point)
    mouse("move", pos)
    mouse("press", pos)
    mouse("release", pos)
    process_events()


def wheel(pos, steps):
    event = QtGui.QWheelEvent(pos, QtCore.QPointF(gl_widget().mapToGlobal(pos.toPoint())), QtCore.QPoint(0, 0),
                              QtCore.QPoint(0, 120 * steps), QtCore.Qt.NoButton, QtCore.Qt.NoModifier,
                              QtCore.Qt.NoScrollPhase, False)
    QtWidgets.QApplication.sendEvent(gl_widget(), event)


class MessageBoxes:
    """Closes every modal message box FreeCAD shows while in use (a timer, since the box
    runs its own event loop), keeping its title and text in ``seen``:

        with h.MessageBoxes() as boxes:
            Gui.runCommand("Std_CloseActiveWindow")
        boxes.seen  # [("Document not closable", "The document is not closable ...")]

    ``press``: the button to click instead, by its text or as a QMessageBox.StandardButton
    (a box without it is rejected)."""

    def __init__(self, press=None):
        self.seen = []
        self.press = press
        self.timer = QtCore.QTimer()
        self.timer.setInterval(50)
        self.timer.timeout.connect(self._close)

    def _close(self):
        for box in QtWidgets.QApplication.topLevelWidgets():
            if isinstance(box, QtWidgets.QMessageBox) and box.isVisible():
                self.seen.append((box.windowTitle(), box.text()))
                if isinstance(self.press, str):
                    chosen = [b for b in box.buttons() if b.text() == self.press]
                else:
                    chosen = [box.button(self.press)] if self.press is not None and box.button(self.press) else []
                if chosen:
                    chosen[0].click()
                else:
                    box.reject()

    def __enter__(self):
        self.timer.start()
        return self

    def __exit__(self, *_):
        process_events()
        self.timer.stop()


def widget(kind, name):
    """The visible widget of a type and objectName in the main window."""
    found = [w for w in Gui.getMainWindow().findChildren(kind, name)]
    visible = [w for w in found if w.isVisibleTo(Gui.getMainWindow())] or found
    if not visible:
        raise LookupError(f"no {kind.__name__} named {name!r}")
    return visible[-1]


def press_task_button(which):
    """Presses OK or Cancel of the task dialog, as a user does."""
    role = {"OK": QtWidgets.QDialogButtonBox.Ok, "Cancel": QtWidgets.QDialogButtonBox.Cancel,
            "Close": QtWidgets.QDialogButtonBox.Close}[which]
    process_events()
    for box in Gui.getMainWindow().findChildren(QtWidgets.QDialogButtonBox):
        button = box.button(role)
        if button is not None and button.isVisible():
            button.click()
            process_events()
            return
    raise LookupError(f"no visible {which} button")


def save_view(name, background="White"):
    """Saves the 3D view (saveImage, at the view's own size so image_pos maps exactly)
    and returns (path, QImage)."""
    path = os.path.join(SHOTS, name)
    view = Gui.ActiveDocument.ActiveView
    width, height = view.getSize()
    view.saveImage(path, width, height, background)
    return path, QtGui.QImage(path)


@contextlib.contextmanager
def uncaught_errors():
    """The tracebacks Qt's callbacks (a timer, a signal) raise while the block runs, as
    texts: they reach sys.excepthook, not the test."""
    errors = []
    hook = sys.excepthook
    sys.excepthook = lambda *info: errors.append("".join(traceback.format_exception(*info)))
    try:
        yield errors
    finally:
        sys.excepthook = hook


def report_text():
    """What FreeCAD's report view holds: where it prints a traceback raised in a callback
    it made (a view provider's onChanged, an observer), which reaches no excepthook."""
    docks = [d for d in Gui.getMainWindow().findChildren(QtWidgets.QDockWidget) if d.objectName() == "Report view"]
    edits = docks[0].findChildren(QtWidgets.QTextEdit) if docks else []
    if not edits:
        raise AssertionError("FreeCAD's report view is not there to read")
    return edits[0].toPlainText()


def scroll_to(widget):
    """Scrolls the task panel that holds ``widget`` until it shows (for a screenshot)."""
    for area in Gui.getMainWindow().findChildren(QtWidgets.QScrollArea):
        if area.isVisible() and area.widget() is not None and area.widget().isAncestorOf(widget):
            area.ensureWidgetVisible(widget, 0, 0)
    process_events()


def widen_panel(width=440):
    """Gives the combo view (tree and task panels) room, as a user would drag it."""
    main = Gui.getMainWindow()
    docks = [d for d in main.findChildren(QtWidgets.QDockWidget) if d.isVisible()]
    combo = [d for d in docks if d.objectName() in ("Combo View", "ComboView")]
    if combo:
        main.resizeDocks(combo, [width], QtCore.Qt.Horizontal)
    for dock in docks:
        if dock.objectName() in ("Report view", "Python console"):
            dock.hide()
    main.statusBar().clearMessage()
    process_events()


def grab_screen(name):
    """The whole screen (main window, task panel and 3D view) as a PNG."""
    process_events()
    path = os.path.join(SHOTS, name)
    QtWidgets.QApplication.primaryScreen().grabWindow(0).save(path)
    return path


def image_pos(point, image):
    """Pixel (x, y) of a 3D point (mm) in an image saved by save_view."""
    view = Gui.ActiveDocument.ActiveView
    x, y = view.getPointOnScreen(App.Vector(*point))
    width, height = view.getSize()
    return int(round(x * image.width() / width)), int(round((height - 1 - y) * image.height() / height))


def pixel(image, x, y):
    c = QtGui.QColor(image.pixel(x, y))
    return c.red(), c.green(), c.blue()


def classify(rgb):
    """"black", "white" or "other" for a pixel of the overlay."""
    r, g, b = rgb
    if max(rgb) < 60:
        return "black"
    if min(rgb) > 200 and max(rgb) - min(rgb) < 40:
        return "white"
    return "other"


def scan(image, p0, p1, samples=200):
    """Classes of the pixels along a segment between two pixel positions."""
    out = []
    for i in range(samples):
        t = i / (samples - 1)
        x = int(round(p0[0] + t * (p1[0] - p0[0])))
        y = int(round(p0[1] + t * (p1[1] - p0[1])))
        out.append(classify(pixel(image, x, y)))
    return out


def runs(classes, kinds=("black", "white")):
    """Number of runs of `kinds` along a scan (a stripe pattern gives many)."""
    count, last = 0, None
    for c in classes:
        if c in kinds and c != last:
            count += 1
        last = c
    return count


def non_white_fraction(image, x0=0.0, y0=0.0, x1=1.0, y1=1.0):
    """Share of pixels in a region (fractions of the image) that are not white."""
    w, h = image.width(), image.height()
    count = total = 0
    for y in range(int(y0 * h), int(y1 * h), 2):
        for x in range(int(x0 * w), int(x1 * w), 2):
            c = QtGui.QColor(image.pixel(x, y))
            total += 1
            count += (c.red() + c.green() + c.blue()) < 720
    return count / max(total, 1)
