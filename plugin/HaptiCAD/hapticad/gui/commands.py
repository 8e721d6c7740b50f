# SPDX-License-Identifier: GPL-3.0-or-later
"""Registers every HaptiCAD command; lists what goes in the toolbar and the menu."""
from . import command_surface

TOOLBAR = [command_surface.NAME]
MENU = [command_surface.NAME]
