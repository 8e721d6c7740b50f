# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD's page in FreeCAD's preferences (Edit > Preferences > HaptiCAD).

Shows and stores hapticad.preferences: the device (the simulated probe, or a HID
device found now), servo rate, accuracy (a preset, whose values are shown, or Custom's
own linear and angular deflection, force shading and refinement), force limit,
workspace mapping, and the overlay. preferences.save checks the values again.

A number typed is taken as typed or refused, never changed unsaid (quantity_spin): read as
FreeCAD reads a quantity ("2,5 kHz", "0,05" with a decimal comma, "0,5 rad" in degrees),
and when it is not one, or is outside the preference's range, the field keeps its value
and the page says why at its top; OK then says which typed values were not saved.
"""
import math
from html import escape

from PySide2 import QtWidgets

from .. import accuracy as accuracy_presets
from .. import preferences
from ..quantity_text import read_quantity
from .quantity_spin import QuantitySpin


def hid_devices():
    """[(label, path)] of the haptic devices the core finds now; [] if it cannot look."""
    try:
        from ..feel_session import device_choices
    except ImportError:  # no compiled module (an Addon Manager install)
        return []
    return [(c.label, c.path) for c in device_choices() if not c.simulated]


class RefineSpin(QuantitySpin):
    """The Custom accuracy's refinement: "off" (or 0), or an edge length in mm within
    accuracy.REFINE_RANGE_MM; a length finer than that is refused, not rounded to off."""

    def __init__(self, name, label):
        super().__init__(name, label, "mm")
        self.setRange(0.0, accuracy_presets.REFINE_RANGE_MM[1])
        self.setSpecialValueText("off")

    def read(self, text):
        if text.strip().lower() == "off":
            return 0.0
        value = read_quantity(text, "mm", self.label)
        low, high = accuracy_presets.REFINE_RANGE_MM
        if value != 0.0 and not low <= value <= high:
            raise ValueError(f"{self.label}: {value:g} mm is neither 0 (off) nor in {low:g}..{high:g} mm")
        return value


class PreferencesPage:
    def __init__(self, parent=None):
        self.form = QtWidgets.QWidget(parent)
        self.form.setWindowTitle("HaptiCAD")
        layout = QtWidgets.QVBoxLayout(self.form)
        self.spins = []  # the QuantitySpins: what they refuse is said (_refused)
        self._refusals = {}  # field label -> why what was typed there is not set
        self.message = QtWidgets.QLabel()
        self.message.setObjectName("preferencesMessage")
        self.message.setWordWrap(True)
        self.message.hide()
        layout.addWidget(self.message)

        device_box = QtWidgets.QGroupBox("Haptic device")
        form = QtWidgets.QFormLayout(device_box)
        self.device = QtWidgets.QComboBox()
        self.device.setObjectName("device")
        self.device.setToolTip("The simulated probe follows the mouse; HID devices are listed when connected")
        form.addRow("Device", self.device)
        self.servo_rate = self._spin("servoRate", "Servo rate", "Hz", decimals=0)  # whole Hz, as stored
        self.servo_rate.setRange(*preferences.SERVO_RATE_RANGE_HZ)
        self.servo_rate.setSingleStep(100)
        self.servo_rate.setToolTip("Rate of the C++ servo loop; textures feel cleaner at higher rates. At least "
                                   f"{preferences.SERVO_RATE_RANGE_HZ[0]} Hz: a slower loop would trip its own "
                                   "5 ms watchdog")
        form.addRow("Servo rate", self.servo_rate)
        self.force_limit = self._spin("forceLimit", "Force limit", "N")
        self.force_limit.setRange(*preferences.FORCE_LIMIT_RANGE_N)
        self.force_limit.setSingleStep(0.1)
        self.force_limit.setToolTip("Largest force sent to the device (never more than the device's own limit)")
        form.addRow("Force limit", self.force_limit)
        self.mapping = QtWidgets.QComboBox()
        self.mapping.setObjectName("workspaceMapping")
        self.mapping.addItems(preferences.WORKSPACE_MAPPINGS)
        self.mapping.setToolTip("Fit part: the device's workspace spans the part; Fixed scale: model mm per "
                                "device mm")
        form.addRow("Workspace mapping", self.mapping)
        self.scale = self._spin("workspaceScale", "Scale", "")  # a ratio: its unit is in the row's label
        self.scale.setRange(*preferences.WORKSPACE_SCALE_RANGE)
        self.scale.setSingleStep(0.1)
        form.addRow("Scale (model mm / device mm)", self.scale)
        # why the two above are greyed, when they are: said, not left to guess
        self.mapping_hint = QtWidgets.QLabel()
        self.mapping_hint.setObjectName("workspaceHint")
        self.mapping_hint.setWordWrap(True)
        self.mapping_hint.setStyleSheet("color: #606060")
        form.addRow(self.mapping_hint)
        self.mapping.currentTextChanged.connect(lambda _text: self._enable_mapping())
        self.device.currentIndexChanged.connect(lambda _index: self._enable_mapping())
        layout.addWidget(device_box)

        scene_box = QtWidgets.QGroupBox("Haptic scene")
        form = QtWidgets.QFormLayout(scene_box)
        self.accuracy = QtWidgets.QComboBox()
        self.accuracy.setObjectName("accuracy")
        self.accuracy.addItems(preferences.ACCURACY_PRESETS)
        self.accuracy.setToolTip("How finely parts are tessellated for feeling: Draft is quick to build, Fine "
                                 "follows curved faces closely; Custom takes your own values")
        form.addRow("Accuracy", self.accuracy)
        # what the chosen accuracy means: a preset's values shown greyed, Custom's editable
        # 8 decimals: 4 digits kept at the range's low end, 0.0001 mm
        self.linear_deflection = self._spin("linearDeflection", "Linear deflection", "mm", decimals=8)
        self.linear_deflection.setRange(*accuracy_presets.LINEAR_RANGE_MM)
        self.linear_deflection.setSingleStep(0.01)
        self.linear_deflection.setToolTip("Largest distance between a facet and the face it stands for")
        form.addRow("Linear deflection", self.linear_deflection)
        self.angular_deflection = self._spin("angularDeflection", "Angular deflection", "\u00b0")
        self.angular_deflection.setRange(*preferences.ANGULAR_RANGE_DEG_SHOWN)
        self.angular_deflection.setToolTip("Largest angle between the normals of neighbouring facets")
        form.addRow("Angular deflection", self.angular_deflection)
        self.force_shading = QtWidgets.QCheckBox("Force shading (push along the exact normal of curved faces)")
        self.force_shading.setObjectName("forceShading")
        form.addRow(self.force_shading)
        self.refine_edge = self._spin("refineEdge", "Refine edges over", kind=RefineSpin)
        self.refine_edge.setToolTip("Split edges longer than this after tessellating (off: keep FreeCAD's facets)")
        form.addRow("Refine edges over", self.refine_edge)
        self.accuracy_hint = QtWidgets.QLabel()
        self.accuracy_hint.setObjectName("accuracyHint")
        self.accuracy_hint.setWordWrap(True)
        self.accuracy_hint.setStyleSheet("color: #606060")
        form.addRow(self.accuracy_hint)
        self._custom = None  # Custom's values while a preset is shown
        self._shown = None  # the accuracy the four fields show
        self.accuracy.currentTextChanged.connect(self._show_accuracy)
        layout.addWidget(scene_box)

        overlay_box = QtWidgets.QGroupBox("Overlay")
        form = QtWidgets.QFormLayout(overlay_box)
        self.overlay_visible = QtWidgets.QCheckBox("Show colours and friction stripes on tagged faces")
        self.overlay_visible.setObjectName("overlayVisible")
        form.addRow(self.overlay_visible)
        self.colour_by = QtWidgets.QComboBox()
        self.colour_by.setObjectName("overlayColourBy")
        self.colour_by.addItems(preferences.COLOUR_BY)
        form.addRow("Colour by", self.colour_by)
        layout.addWidget(overlay_box)
        layout.addStretch(1)

    def _spin(self, name, label, unit="", decimals=6, kind=QuantitySpin):
        """A field that takes a number as typed or refuses it, saying why (_refused)."""
        spin = kind(name, label) if kind is not QuantitySpin else kind(name, label, unit, decimals)
        spin.refused.connect(lambda problem, spin=spin: self._refused(spin, problem))
        self.spins.append(spin)
        return spin

    def _refused(self, spin, problem):
        """What was typed in ``spin`` is not set (``problem``, why) or is taken (""): said at
        the page's top until typed again, and at OK."""
        if problem:
            self._refusals[spin.label] = problem
        else:
            self._refusals.pop(spin.label, None)
        self._show_refusals()

    def _show_refusals(self):
        lines = [f"\u26a0 Not set: {escape(text, quote=False)}" for text in self._refusals.values()]
        self.message.setText("<span style='color:#b00000'>" + "<br>".join(lines) + "</span>" if lines else "")
        self.message.setVisible(bool(lines))

    def loadSettings(self):
        self._refusals.clear()
        self._show_refusals()
        prefs = preferences.load()
        self.device.clear()
        self.device.addItem("Simulated probe (mouse)", preferences.SIMULATED_DEVICE)
        for label, path in hid_devices():
            self.device.addItem(label, path)
        index = self.device.findData(prefs.device)
        if index < 0:  # a device stored earlier and not connected now: keep it
            self.device.addItem(f"{prefs.device} (not connected)", prefs.device)
            index = self.device.count() - 1
        self.device.setCurrentIndex(index)
        self.servo_rate.setValue(prefs.servo_rate_hz)
        self.force_limit.setValue(prefs.force_limit_n)
        self.mapping.setCurrentText(prefs.workspace_mapping)
        self.scale.setValue(prefs.workspace_scale)
        self._enable_mapping()
        self._custom = self._stored_custom()
        self._shown = None
        self.accuracy.setCurrentText(prefs.accuracy)
        self._show_accuracy(self.accuracy.currentText())
        self.overlay_visible.setChecked(prefs.overlay_visible)
        self.colour_by.setCurrentText(prefs.overlay_colour_by)

    def _enable_mapping(self):
        """The mapping is a hardware device's: the simulated probe moves in the part's own
        space, so its mapping and scale are greyed (kept for a device chosen later)."""
        hardware = (self.device.currentData() or preferences.SIMULATED_DEVICE) != preferences.SIMULATED_DEVICE
        self.mapping.setEnabled(hardware)
        self.scale.setEnabled(hardware and self.mapping.currentText() == "Fixed scale")
        if not hardware:
            hint = ("The simulated probe moves in the part's own space: the workspace mapping and scale are a "
                    "haptic device's, kept for when you choose one.")
        elif not self.scale.isEnabled():
            hint = "Fit part sets the scale itself, so the part fills the device's workspace."
        else:
            hint = ""
        self.mapping_hint.setText(hint)
        self.mapping_hint.setVisible(bool(hint))

    def _custom_fields(self):
        """Custom's values as the fields hold them; a field left as it was shown gives the
        value it was shown from, not that value rounded to the field's decimals."""
        shown = self._custom or self._stored_custom()
        spins = (self.linear_deflection, self.angular_deflection, None, self.refine_edge)
        values = []
        for spin, before in zip(spins, shown):
            if spin is None:
                values.append(self.force_shading.isChecked())
                continue
            as_shown = min(max(round(before, spin.decimals()), spin.minimum()), spin.maximum())
            values.append(float(before) if spin.value() == as_shown else float(spin.value()))
        return tuple(values)

    @staticmethod
    def _stored_custom():
        prefs = preferences.load()
        return (prefs.custom_linear_deflection_mm, prefs.custom_angular_deflection_deg, prefs.custom_force_shading,
                prefs.custom_refine_edge_mm)

    def _show_accuracy(self, name):
        """Fills the four fields: Custom's own values, editable, or the preset's, greyed
        (Custom's edits are kept while a preset is shown)."""
        if self._custom is None or name == self._shown:
            return
        if self._shown == accuracy_presets.CUSTOM:
            self._custom = self._custom_fields()
        custom = name == accuracy_presets.CUSTOM
        if custom:
            linear, angle, shading, refine = self._custom
        else:
            chosen = accuracy_presets.preset(name)
            linear, angle, shading, refine = (chosen.linear_deflection_mm, math.degrees(chosen.angular_deflection_rad),
                                              chosen.force_shading, chosen.refine_edge_mm)
        self.linear_deflection.setValue(linear)
        self.angular_deflection.setValue(angle)
        self.force_shading.setChecked(shading)
        self.refine_edge.setValue(refine)
        for widget in (self.linear_deflection, self.angular_deflection, self.force_shading, self.refine_edge):
            widget.setEnabled(custom)
        self.accuracy_hint.setText("" if custom else f"{name}'s values; choose Custom to set your own.")
        self.accuracy_hint.setVisible(not custom)
        self._shown = name

    def values(self):
        return preferences.Preferences(
            device=self.device.currentData() or preferences.SIMULATED_DEVICE,
            servo_rate_hz=int(self.servo_rate.value()),
            accuracy=self.accuracy.currentText(),
            **dict(zip(("custom_linear_deflection_mm", "custom_angular_deflection_deg", "custom_force_shading",
                        "custom_refine_edge_mm"),
                       self._custom_fields() if self._shown == accuracy_presets.CUSTOM
                       else self._custom or self._stored_custom())),
            force_limit_n=float(self.force_limit.value()),
            workspace_mapping=self.mapping.currentText(),
            workspace_scale=float(self.scale.value()),
            overlay_visible=self.overlay_visible.isChecked(),
            overlay_colour_by=self.colour_by.currentText(),
        )

    def saveSettings(self):
        """Stores the page's values; a value typed and refused is not among them (its field
        kept the value before), and a message box says which."""
        for spin in self.spins:  # typed, and OK pressed without leaving the field
            spin.commit()
        before = preferences.load()
        prefs = self.values()
        preferences.save(prefs)
        if self._refusals:
            refused = list(self._refusals.values())
            self._refusals.clear()  # said here now: the page's own message goes
            self._show_refusals()
            QtWidgets.QMessageBox.warning(
                self.form, "HaptiCAD preferences",
                "These values typed were refused and not saved (each field kept its value before):\n\n"
                + "\n".join(refused) + "\n\nThe other preferences are saved.")
        if (before.overlay_visible, before.overlay_colour_by) != (prefs.overlay_visible, prefs.overlay_colour_by):
            from .command_overlay import refresh_all

            refresh_all()
