# SPDX-License-Identifier: GPL-3.0-or-later
"""A live strip chart of force components against time (the last few seconds).

Fed with whole arrays of samples drained from the servo loop's trace; keeps a bounded
history; paints at most as often as the Feel panel's display timer updates it.
"""
import numpy as np
from PySide2 import QtCore, QtGui, QtWidgets

from ..trace_lateral import felt_lateral_parts

SERIES = (  # trace field, label, colour
    ("normal_force_n", "normal", QtGui.QColor(31, 119, 180)),
    ("friction_force_n", "friction", QtGui.QColor(214, 39, 40)),
    ("texture_force_n", "texture", QtGui.QColor(44, 160, 44)),
    ("vibration_force_n", "vibration", QtGui.QColor(148, 103, 189)),
)
# drawn (and named in the legend) only while they hold a force: most parts never vibrate
OPTIONAL = frozenset({"vibration_force_n"})


class StripChart(QtWidgets.QWidget):
    def __init__(self, seconds=5.0, parent=None):
        super().__init__(parent)
        self.setObjectName("stripChart")
        self.setMinimumHeight(150)
        self.seconds = seconds
        self.times = np.zeros(0)
        self.values = {field: np.zeros(0) for field, _, _ in SERIES}
        self.sample_count = 0  # every sample ever received
        self.hidden = frozenset()  # fields recorded but not drawn (a blind study's run)

    def set_hidden(self, fields):
        """Draws the series of ``fields`` no more (their values are still kept), or
        all of them again with an empty set. A participant in a similarity study's run
        must not read the texture off the screen."""
        fields = frozenset(fields)
        if fields != self.hidden:
            self.hidden = fields
            self.update()

    def append(self, trace):
        """Adds drained trace samples (a structured array with time_s, flags,
        tangential_force_n and SERIES fields). Friction and texture are drawn as felt:
        where the force was clamped to the device's limit, scaled down with it (the trace
        holds them as rendered before the clamp)."""
        if trace is None or len(trace) == 0:
            return
        self.sample_count += len(trace)
        self.times = np.concatenate([self.times, np.asarray(trace["time_s"], float)])
        keep = self.times >= self.times[-1] - self.seconds
        self.times = self.times[keep]
        felt = felt_lateral_parts(trace)
        # a vibration along any axis, as its size: the chart draws forces from 0 up
        felt["vibration_force_n"] = (np.abs(np.asarray(trace["vibration_force_n"], float))
                                     if "vibration_force_n" in trace.dtype.names else np.zeros(len(trace)))
        for field in self.values:
            new = felt[field] if field in felt else np.asarray(trace[field], float)
            self.values[field] = np.concatenate([self.values[field], new])[keep]
        self.update()

    def drawn(self):
        """The SERIES fields drawn now: not hidden, and an optional one only while it
        holds a force in the window."""
        return [field for field, _, _ in SERIES if field not in self.hidden
                and (field not in OPTIONAL or (len(self.values[field]) and np.any(self.values[field] != 0)))]

    def clear(self):
        self.times = np.zeros(0)
        self.values = {field: np.zeros(0) for field in self.values}
        self.update()

    def paintEvent(self, event):
        painter = QtGui.QPainter(self)
        painter.setRenderHint(QtGui.QPainter.Antialiasing)
        rect = self.rect().adjusted(36, 6, -6, -20)
        painter.fillRect(self.rect(), QtGui.QColor(255, 255, 255))
        painter.setPen(QtGui.QColor(200, 200, 200))
        painter.drawRect(rect)
        top = 1.0
        drawn = self.drawn()
        for field in drawn:
            if len(self.values[field]):
                top = max(top, float(np.nanmax(np.abs(self.values[field]))) * 1.1)
        painter.setPen(QtGui.QColor(90, 90, 90))
        painter.drawText(QtCore.QRectF(0, rect.top() - 4, 34, 14), QtCore.Qt.AlignRight, f"{top:.1f}")
        painter.drawText(QtCore.QRectF(0, rect.bottom() - 10, 34, 14), QtCore.Qt.AlignRight, "0 N")
        x = rect.left() + 4
        for field, label, colour in SERIES:
            if field in OPTIONAL and field not in drawn:
                continue
            if field in self.hidden:
                label, colour = f"{label}: hidden", QtGui.QColor(150, 150, 150)
            painter.setPen(colour)
            painter.drawText(QtCore.QPointF(x, self.height() - 5), label)
            x += painter.fontMetrics().horizontalAdvance(label) + 14
        painter.setPen(QtGui.QColor(90, 90, 90))
        span = f"last {self.seconds:g} s"
        if x + painter.fontMetrics().horizontalAdvance(span) <= rect.right():  # a narrow panel: the legend first
            painter.drawText(QtCore.QRectF(rect.right() - 80, self.height() - 17, 80, 14), QtCore.Qt.AlignRight,
                             span)
        if len(self.times) < 2:
            return
        t1 = self.times[-1]
        t0 = t1 - self.seconds
        # at most two points per pixel: decimate by taking the extremes of each column
        columns = max(int(rect.width()), 2)
        index = np.clip(((self.times - t0) / self.seconds * (columns - 1)).astype(int), 0, columns - 1)
        # a vibration fills a band from 0 to its size: drawn first, the others stay seen on it
        for field, _, colour in sorted(SERIES, key=lambda series: series[0] not in OPTIONAL):
            if field not in drawn:
                continue
            values = self.values[field]
            path = QtGui.QPainterPath()
            first = True
            for column in np.unique(index):
                chunk = values[index == column]
                for value in (chunk.min(), chunk.max()) if len(chunk) > 1 else (chunk[0],):
                    px = rect.left() + column * rect.width() / (columns - 1)
                    py = rect.bottom() - max(min(value, top), 0.0) / top * rect.height()
                    if first:
                        path.moveTo(px, py)
                        first = False
                    else:
                        path.lineTo(px, py)
            painter.setPen(QtGui.QPen(colour, 1.5))
            painter.drawPath(path)
