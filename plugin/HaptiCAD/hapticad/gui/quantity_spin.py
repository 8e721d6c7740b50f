# SPDX-License-Identifier: GPL-3.0-or-later
"""A spin box that takes a value as typed, read as FreeCAD reads a quantity, or refuses
it saying why: the study panel's values and the preferences page's.

Qt's own spin boxes changed what was typed, unsaid: bounded by their range they dropped
the key that would leave it (the 4th digit of 1500, the 5th of 20000 Hz), their
validator dropped a decimal comma ("0,05" mm became 5 mm), their suffix took "6 cm" as
6 mm, and a value finer than their decimals was rounded (0.005 mm became 0, "off").
"""
from PySide2 import QtCore, QtGui, QtWidgets

from ..quantity_text import read_quantity

class QuantitySpin(QtWidgets.QDoubleSpinBox):
    """A spin box of a value in ``unit``, shown with it ("80 mm") and read by ``read``:
    read_quantity over the field's range here, a subclass's own way there ("6 cm" in a
    length is 60 mm, "4,5" 4.5, a number alone in the unit). Every key typed stays; on
    Return or leaving the field, a value that is not one, or is outside the range, is not
    set (the field shows the value it keeps) and ``refused`` says why ("" when what was
    typed is taken). ``decimals``: the digits kept; 0 takes whole numbers only (a
    fraction is refused, not rounded)."""

    refused = QtCore.Signal(str)

    def __init__(self, name, label, unit="", decimals=6):
        super().__init__()
        self.setObjectName(name)
        self.name, self.label, self.problem = name, label, None
        self._unit = unit
        self.setDecimals(decimals)
        self.setKeyboardTracking(False)
        self.editingFinished.connect(self._finished)

    def unit(self):
        """The unit the value is in and shown with ("" for a plain number)."""
        return self._unit

    def read(self, text):
        """The value ``text`` means; raises ValueError with a sentence when it is none to set."""
        return read_quantity(text, self.unit(), self.label, (self.minimum(), self.maximum()),
                             whole=self.decimals() == 0)

    def validate(self, text, pos):
        return QtGui.QValidator.Acceptable  # whatever is typed stays; valueFromText judges it

    def fixup(self, text):
        return text

    def valueFromText(self, text):
        try:
            value = self.read(text)
        except ValueError as exc:
            self.problem = str(exc)
            return self.value()  # nothing set
        self.problem = None
        return value

    def textFromValue(self, value):
        shown = f"{value:.{self.decimals()}f}"
        if "." in shown:
            shown = shown.rstrip("0").rstrip(".")
        return f"{shown} {self.unit()}".rstrip()

    def commit(self):
        """Reads what is typed and not read yet, and says it as leaving the field does: for
        OK pressed without leaving the field (a shortcut, a click that takes no focus)."""
        if self.lineEdit().isModified():
            self.interpretText()
            self._finished()

    def _finished(self):
        problem, self.problem = self.problem, None
        self.refused.emit(problem or "")
