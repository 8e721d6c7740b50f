# SPDX-License-Identifier: GPL-3.0-or-later
"""HaptiCAD's user preferences: read and written here only.

They live in FreeCAD's parameter tree under ``User parameter:BaseApp/Preferences/Mod/
HaptiCAD`` (saved in user.cfg), so the preferences page, the Feel session, the scene
builder and scripts all see the same values:

    from hapticad import preferences
    prefs = preferences.load()          # a frozen Preferences
    preferences.save(prefs.replace(servo_rate_hz=2000))

Units: Hz, N, and model mm per device mm for the workspace scale. ``save`` refuses
bad values with a clear message and writes nothing. No GUI.
"""
import dataclasses
import math

import FreeCAD as App

from . import accuracy as accuracy_presets

GROUP = "User parameter:BaseApp/Preferences/Mod/HaptiCAD"
SIMULATED_DEVICE = "simulated"
ACCURACY_PRESETS = tuple(accuracy_presets.PRESETS) + (accuracy_presets.CUSTOM,)
# the custom accuracy's angle is set in degrees, as in FreeCAD's own tessellation settings
ANGULAR_RANGE_DEG = tuple(math.degrees(r) for r in accuracy_presets.ANGULAR_RANGE_RAD)
ANGULAR_RANGE_DEG_SHOWN = accuracy_presets.ANGULAR_RANGE_DEG_SHOWN
_START = accuracy_presets.PRESETS[accuracy_presets.DEFAULT]  # a custom accuracy starts as the default
WORKSPACE_MAPPINGS = ("Fit part", "Fixed scale")
COLOUR_BY = ("Material", "Roughness")
# The servo loop refuses a period over half its 5 ms watchdog (and stale-data limit):
# below 400 Hz every late tick would cut the force (_core.min_servo_rate_hz()).
SERVO_RATE_RANGE_HZ = (400, 10000)
FORCE_LIMIT_RANGE_N = (0.1, 50.0)
WORKSPACE_SCALE_RANGE = (0.01, 100.0)


@dataclasses.dataclass(frozen=True)
class Preferences:
    device: str = SIMULATED_DEVICE  # "simulated" or a HID device path
    servo_rate_hz: int = 1000
    accuracy: str = accuracy_presets.DEFAULT  # tessellation preset of the haptic scene (accuracy.py), or Custom
    # the Custom accuracy's values (kept while a preset is chosen)
    custom_linear_deflection_mm: float = _START.linear_deflection_mm
    custom_angular_deflection_deg: float = round(math.degrees(_START.angular_deflection_rad), 4)
    custom_force_shading: bool = _START.force_shading
    custom_refine_edge_mm: float = _START.refine_edge_mm  # 0: off
    force_limit_n: float = 3.0  # never more than the device's own limit
    workspace_mapping: str = "Fit part"  # device workspace -> model
    workspace_scale: float = 1.0  # model mm per device mm, with "Fixed scale"
    overlay_visible: bool = True
    overlay_colour_by: str = "Material"

    def replace(self, **changes):
        return dataclasses.replace(self, **changes)


# field -> (parameter name, kind)
_PARAMETERS = {
    "device": ("Device", "String"),
    "servo_rate_hz": ("ServoRateHz", "Int"),
    "accuracy": ("AccuracyPreset", "String"),
    "custom_linear_deflection_mm": ("CustomLinearDeflectionMm", "Float"),
    "custom_angular_deflection_deg": ("CustomAngularDeflectionDeg", "Float"),
    "custom_force_shading": ("CustomForceShading", "Bool"),
    "custom_refine_edge_mm": ("CustomRefineEdgeMm", "Float"),
    "force_limit_n": ("ForceLimitN", "Float"),
    "workspace_mapping": ("WorkspaceMapping", "String"),
    "workspace_scale": ("WorkspaceScale", "Float"),
    "overlay_visible": ("ShowOverlay", "Bool"),
    "overlay_colour_by": ("OverlayColourBy", "String"),
}
DEFAULTS = Preferences()


def problems(prefs):
    """What is wrong with ``prefs``, as sentences (empty when fine)."""
    found = []
    if not isinstance(prefs.device, str) or not prefs.device.strip():
        found.append("device: choose the simulated probe or a HID device")
    low, high = SERVO_RATE_RANGE_HZ
    if not (isinstance(prefs.servo_rate_hz, int) and low <= prefs.servo_rate_hz <= high):
        found.append(f"servo rate {prefs.servo_rate_hz!r} Hz is outside {low}..{high} Hz")
    if prefs.accuracy not in ACCURACY_PRESETS:
        found.append(f"accuracy {prefs.accuracy!r} is not one of {', '.join(ACCURACY_PRESETS)}")
    angle = prefs.custom_angular_deflection_deg
    if not (isinstance(angle, (int, float)) and not isinstance(angle, bool) and math.isfinite(angle)
            and ANGULAR_RANGE_DEG[0] <= angle <= ANGULAR_RANGE_DEG[1]):
        found.append(f"custom angular deflection {angle!r} degrees is outside "
                     f"{ANGULAR_RANGE_DEG_SHOWN[0]:g}..{ANGULAR_RANGE_DEG_SHOWN[1]:g} degrees")
    # the other custom values, checked as accuracy.py checks them (the angle above, in degrees)
    others = accuracy_presets.Accuracy(accuracy_presets.CUSTOM, prefs.custom_linear_deflection_mm,
                                       _START.angular_deflection_rad, prefs.custom_force_shading,
                                       prefs.custom_refine_edge_mm)
    found += ["custom " + p for p in others.problems()]
    for label, value, (low, high), unit in (
            ("force limit", prefs.force_limit_n, FORCE_LIMIT_RANGE_N, " N"),
            ("workspace scale", prefs.workspace_scale, WORKSPACE_SCALE_RANGE, "")):
        if not (isinstance(value, (int, float)) and math.isfinite(value) and low <= value <= high):
            found.append(f"{label} {value!r}{unit} is outside {low}..{high}{unit}")
    if prefs.workspace_mapping not in WORKSPACE_MAPPINGS:
        found.append(f"workspace mapping {prefs.workspace_mapping!r} is not one of {', '.join(WORKSPACE_MAPPINGS)}")
    if prefs.overlay_colour_by not in COLOUR_BY:
        found.append(f"overlay colour {prefs.overlay_colour_by!r} is not one of {', '.join(COLOUR_BY)}")
    return found


def scene_accuracy(prefs):
    """The accuracy.Accuracy the haptic scene is built with: the preset chosen, or the
    custom values when Custom is."""
    if prefs.accuracy == accuracy_presets.CUSTOM:
        return accuracy_presets.custom(prefs.custom_linear_deflection_mm,
                                       math.radians(prefs.custom_angular_deflection_deg),
                                       prefs.custom_force_shading, prefs.custom_refine_edge_mm)
    return accuracy_presets.preset(prefs.accuracy)


def _group():
    return App.ParamGet(GROUP)


def load():
    """The stored preferences; a missing or bad value falls back to its default."""
    group = _group()
    values = {}
    for field, (name, kind) in _PARAMETERS.items():
        default = getattr(DEFAULTS, field)
        values[field] = getattr(group, f"Get{kind}")(name, default)
    prefs = Preferences(**values)
    # a hand-edited user.cfg must not break the workbench: reset only what is wrong
    if problems(prefs):
        for field in _PARAMETERS:
            if problems(Preferences(**{field: values[field]})):
                values[field] = getattr(DEFAULTS, field)
        prefs = Preferences(**values)
    return prefs


def save(prefs):
    """Writes every value; raises ValueError (writing nothing) if one is bad."""
    found = problems(prefs)
    if found:
        raise ValueError("preferences: " + "; ".join(found))
    group = _group()
    for field, (name, kind) in _PARAMETERS.items():
        getattr(group, f"Set{kind}")(name, getattr(prefs, field))


def update(**changes):
    """Changes some values (checked like ``save``) and returns the new preferences."""
    prefs = load().replace(**changes)
    save(prefs)
    return prefs
