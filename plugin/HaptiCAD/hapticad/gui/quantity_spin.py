# SPDX-License-Identifier: GPL-3.0-or-later
"""A spin box that takes a value as typed, read as FreeCAD reads a quantity, or refuses
it saying why: the study panel's values and the preferences page's.

Qt's own spin boxes changed what was typed, unsaid: bounded by their range they dropped
the key that would leave it (the 4th digit of 1500, the 5th of 20000 Hz), their
validator dropped a decimal comma ("0,05" mm became 5 mm), their suffix took "6 cm" as
6 mm, and a value finer than their decimals was rounded (0.005 mm became 0, "off").
"""
import math
import re

import FreeCAD as App
from PySide2 import QtCore, QtGui, QtWidgets

# 1,000 or 12,345,678: thousands, or a decimal comma? (0,005 and 1234,5 are decimal commas)
_THOUSANDS = re.compile(r"(?<![\d.,])(?!0,)\d{1,3}(,\d{3})+(?![\d,])")


def _kind(unit):
    """The name of a FreeCAD unit's kind ("length", "frequency"), or "" for none."""
    return str(unit).rpartition("[")[2].rstrip("]").lower() if "[" in str(unit) else ""


def read_quantity(text, unit, label, value_range=None, whole=False):
    """The value ``text`` means in ``unit`` (a FreeCAD unit: "mm", "N", "Hz", "\u00b0"; ""
    for a plain number), read as FreeCAD reads a quantity: "0.1 cm" is 1 in mm, "2,5 kHz"
    2500 in Hz, "0,5 rad" 28.648 in degrees, "0,05" 0.05 (a decimal comma), a number alone
    in ``unit``. Raises ValueError with a sentence that starts with ``label`` when it is
    not a value of that kind, is outside ``value_range`` (low, high, inclusive; None:
    unchecked) or, ``whole``, not a whole number: nothing is to be set then."""
    typed = " ".join(text.split())
    if not typed:
        raise ValueError(f"{label}: give a value{' in ' + unit if unit else ''}")
    if _THOUSANDS.search(typed):
        plain = typed.replace(",", "")
        raise ValueError(f"{label}: is {typed!r} {plain} or {typed.replace(',', '.')}? give it without the comma "
                         f"({plain}) or with a decimal point")
    try:
        quantity = App.Units.Quantity(typed)
    except (ValueError, OverflowError):
        raise ValueError(f"{label}: {typed!r} is not a value FreeCAD reads"
                         + (f" (a number, or one with a unit, like 5 {unit})" if unit else " (a number)")) from None
    expected = App.Units.Quantity(f"1 {unit}") if unit else App.Units.Quantity(1.0)
    if quantity.Unit == App.Units.Quantity(1.0).Unit:  # a number alone: in the field's unit
        value = quantity.Value
    elif quantity.Unit != expected.Unit:
        raise ValueError(f"{label}: {typed!r} is a {_kind(quantity.Unit) or 'quantity'}, not a "
                         f"{_kind(expected.Unit) if unit else 'plain number'}")
    else:
        value = quantity.Value / expected.Value
    shown_unit = f" {unit}" if unit else ""
    if not math.isfinite(value):
        raise ValueError(f"{label}: {typed!r} is not a finite value")
    if value_range is not None and not value_range[0] <= value <= value_range[1]:
        low, high = value_range
        raise ValueError(f"{label}: {value:g}{shown_unit} is outside {low:g}..{high:g}{shown_unit}")
    if whole and value != round(value):
        raise ValueError(f"{label}: {value:g}{shown_unit} is not a whole number{' of ' + unit if unit else ''}")
    return value


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
