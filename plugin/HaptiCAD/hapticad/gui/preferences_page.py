# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD's page in FreeCAD's preferences (Edit > Preferences > HaptiCAD).

Shows and stores hapticad.preferences: the device (the simulated probe, or a HID
device found now), servo rate, accuracy preset, force limit, workspace mapping, and
the overlay. The widgets only allow valid values; preferences.save checks them again.
"""
from PySide2 import QtWidgets

from .. import preferences


def hid_devices():
    """[(label, path)] of the haptic devices the core finds now; [] if it cannot look."""
    try:
        from ..feel_session import device_choices
    except ImportError:  # no compiled module (an Addon Manager install)
        return []
    return [(c.label, c.path) for c in device_choices() if not c.simulated]


class PreferencesPage:
    def __init__(self, parent=None):
        self.form = QtWidgets.QWidget(parent)
        self.form.setWindowTitle("HaptiCAD")
        layout = QtWidgets.QVBoxLayout(self.form)

        device_box = QtWidgets.QGroupBox("Haptic device")
        form = QtWidgets.QFormLayout(device_box)
        self.device = QtWidgets.QComboBox()
        self.device.setObjectName("device")
        self.device.setToolTip("The simulated probe follows the mouse; HID devices are listed when connected")
        form.addRow("Device", self.device)
        self.servo_rate = QtWidgets.QSpinBox()
        self.servo_rate.setObjectName("servoRate")
        self.servo_rate.setRange(*preferences.SERVO_RATE_RANGE_HZ)
        self.servo_rate.setSingleStep(100)
        self.servo_rate.setSuffix(" Hz")
        self.servo_rate.setToolTip("Rate of the C++ servo loop; textures feel cleaner at higher rates. At least "
                                   f"{preferences.SERVO_RATE_RANGE_HZ[0]} Hz: a slower loop would trip its own "
                                   "5 ms watchdog")
        form.addRow("Servo rate", self.servo_rate)
        self.force_limit = QtWidgets.QDoubleSpinBox()
        self.force_limit.setObjectName("forceLimit")
        self.force_limit.setRange(*preferences.FORCE_LIMIT_RANGE_N)
        self.force_limit.setDecimals(2)
        self.force_limit.setSingleStep(0.1)
        self.force_limit.setSuffix(" N")
        self.force_limit.setToolTip("Largest force sent to the device (never more than the device's own limit)")
        form.addRow("Force limit", self.force_limit)
        self.mapping = QtWidgets.QComboBox()
        self.mapping.setObjectName("workspaceMapping")
        self.mapping.addItems(preferences.WORKSPACE_MAPPINGS)
        self.mapping.setToolTip("Fit part: the device's workspace spans the part; Fixed scale: model mm per "
                                "device mm")
        form.addRow("Workspace mapping", self.mapping)
        self.scale = QtWidgets.QDoubleSpinBox()
        self.scale.setObjectName("workspaceScale")
        self.scale.setRange(*preferences.WORKSPACE_SCALE_RANGE)
        self.scale.setDecimals(3)
        self.scale.setSuffix(" model mm / device mm")
        form.addRow("Scale", self.scale)
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
                                 "follows curved faces closely")
        form.addRow("Accuracy", self.accuracy)
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

    def loadSettings(self):
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
        self.accuracy.setCurrentText(prefs.accuracy)
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

    def values(self):
        return preferences.Preferences(
            device=self.device.currentData() or preferences.SIMULATED_DEVICE,
            servo_rate_hz=int(self.servo_rate.value()),
            accuracy=self.accuracy.currentText(),
            force_limit_n=float(self.force_limit.value()),
            workspace_mapping=self.mapping.currentText(),
            workspace_scale=float(self.scale.value()),
            overlay_visible=self.overlay_visible.isChecked(),
            overlay_colour_by=self.colour_by.currentText(),
        )

    def saveSettings(self):
        before = preferences.load()
        prefs = self.values()
        preferences.save(prefs)
        if (before.overlay_visible, before.overlay_colour_by) != (prefs.overlay_visible, prefs.overlay_colour_by):
            from .command_overlay import refresh_all

            refresh_all()
