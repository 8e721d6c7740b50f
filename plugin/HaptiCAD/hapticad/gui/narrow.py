# SPDX-License-Identifier: GPL-3.0-or-later
"""Lets a task panel's boxes shrink to FreeCAD's Combo View as a designer has it (about
250 px wide by default, and no horizontal scroll bar): what a widget would ask for by
its longest entry it does not get.

    for box in panel.form:
        let_narrow(box)

Form rows whose label and field do not fit side by side put the field under the label;
combo boxes stop sizing to their longest item (they elide it), and spin boxes to their
widest value (a 1e6 range asked 112 px each). Call it once the box is built.
"""
from PySide2 import QtWidgets

COMBO_CHARACTERS = 8  # what a combo box shows at its narrowest, with its arrow
SPIN_WIDTH_PX = 56


def let_narrow(root):
    for form in root.findChildren(QtWidgets.QFormLayout):
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
    for combo in root.findChildren(QtWidgets.QComboBox):
        combo.setSizeAdjustPolicy(QtWidgets.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        combo.setMinimumContentsLength(COMBO_CHARACTERS)
    for spin in root.findChildren(QtWidgets.QAbstractSpinBox):
        spin.setMinimumWidth(SPIN_WIDTH_PX)
