# SPDX-License-Identifier: GPL-3.0-or-later
"""Lets a task panel's boxes shrink to FreeCAD's Combo View as a designer has it (about
250 px wide by default, and no horizontal scroll bar): what a widget would ask for by
its longest entry it does not get.

    for box in panel.form:
        let_narrow(box)

Form rows whose label and field do not fit side by side put the field under the label
(so a spin box keeps the width its value and unit need); combo boxes stop sizing to
their longest item (they elide it). Rows of several spin boxes (x, y, z) set their own
SPIN_WIDTH_PX. Call it once the box is built.
"""
from PySide2 import QtWidgets

COMBO_CHARACTERS = 10  # what a combo box shows at its narrowest, with its arrow
SPIN_WIDTH_PX = 56  # each of an x, y, z row's spin boxes


def let_narrow(root):
    for form in root.findChildren(QtWidgets.QFormLayout):
        form.setRowWrapPolicy(QtWidgets.QFormLayout.WrapLongRows)
    for combo in root.findChildren(QtWidgets.QComboBox):
        combo.setSizeAdjustPolicy(QtWidgets.QComboBox.AdjustToMinimumContentsLengthWithIcon)
        if combo.minimumContentsLength() == 0:  # one that set its own keeps it
            combo.setMinimumContentsLength(COMBO_CHARACTERS)
