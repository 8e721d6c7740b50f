# SPDX-License-Identifier: GPL-3.0-or-later
"""View provider of HapticVibration objects: icon; double-click edits the surface panel's
vibration through the properties (a vibration draws nothing of its own)."""
from .view_provider_base import DrawsNothing


class ViewProviderHapticVibration(DrawsNothing):
    ICON = "HaptiCAD_Vibration"
