# SPDX-License-Identifier: GPL-3.0-or-later
"""A value typed as text, read as FreeCAD reads a quantity ("0.1 cm", "2,5 kHz", "0,05"),
or refused with a sentence saying why: what the study panel, the preferences page
(gui/quantity_spin.py) and a script's stiffness_study.typed_value take. App-only.
"""
import math
import re

import FreeCAD as App

# 1,000 or 12,345,678: thousands, or a decimal comma? (0,005 and 1234,5 are decimal commas)
_THOUSANDS = re.compile(r"(?<![\d.,])(?!0,)\d{1,3}(,\d{3})+(?![\d,])")


def _kind(unit):
    """The name of a FreeCAD unit's kind ("length", "frequency"), or "" for none."""
    return str(unit).rpartition("[")[2].rstrip("]").lower() if "[" in str(unit) else ""


def read_quantity(text, unit, label, value_range=None, whole=False, rewrite=None):
    """The value ``text`` means in ``unit`` (a FreeCAD unit: "mm", "N", "Hz", "\u00b0"; ""
    for a plain number), read as FreeCAD reads a quantity: "0.1 cm" is 1 in mm, "2,5 kHz"
    2500 in Hz, "0,5 rad" 28.648 in degrees, "0,05" 0.05 (a decimal comma), a number alone
    in ``unit``. Raises ValueError with a sentence that starts with ``label`` when it is
    not a value of that kind, is outside ``value_range`` (low, high, inclusive; None:
    unchecked) or, ``whole``, not a whole number: nothing is to be set then. ``rewrite``
    turns the text into what FreeCAD reads (units it does not know: "150 gf")."""
    typed = " ".join(text.split())
    if not typed:
        raise ValueError(f"{label}: give a value{' in ' + unit if unit else ''}")
    if _THOUSANDS.search(typed):
        plain = typed.replace(",", "")
        raise ValueError(f"{label}: is {typed!r} {plain} or {typed.replace(',', '.')}? give it without the comma "
                         f"({plain}) or with a decimal point")
    try:
        quantity = App.Units.Quantity(rewrite(typed) if rewrite else typed)
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
